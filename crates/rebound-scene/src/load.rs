//! Reading a scene file: RON text to a checked [`Scene`], with every error placed at a line and column.
//!
//! Two passes over the text, both by the `ron` parser. The first reads the [`Scene`]; the parser places
//! syntax and type errors itself. The second reads only the scene's outline with every item kept as its raw
//! text ([`ron::value::RawValue`] borrows it from the source), which tells where each body, collider and
//! joint starts. A value the parser accepts but the engine refuses (a negative radius, a `NaN`, a joint to a
//! body that does not exist) is then found by building the scene, and placed at its item's field: the field
//! the error names, looked up inside that item's text, or the item's start when it cannot be told.
//! A value that its own type's check refuses while it is read (`Rope` with a negative length, settings above
//! their bounds: the engine's descriptions check themselves when deserialised) stops the first pass; it is
//! placed the same way, its item being the one whose text holds the place where the parser stopped.

use crate::error::{Location, Place};
use crate::{BuiltScene, Scene, SceneError};
use ron::extensions::Extensions;
use ron::value::RawValue;
use serde::Deserialize;
use serde::de::DeserializeSeed;
use std::path::Path;

/// The RON options scene files are read with: the `implicit_some` extension is on without being declared, so
/// `Some` may be left out (`body_a: 0` for `body_a: Some(0)`).
#[must_use]
pub fn ron_options() -> ron::Options {
    ron::Options::default().with_default_extension(Extensions::IMPLICIT_SOME)
}

impl Scene {
    /// Reads a scene from RON text and checks it by building it once.
    ///
    /// # Errors
    /// A [`SceneError`] with the line and column: [`SceneError::Syntax`] for text that is not a scene,
    /// the others for values the engine refuses.
    pub fn from_ron(source: &str) -> Result<Self, SceneError> {
        Ok(load_str(source)?.0)
    }

    /// Reads and checks a scene file, as [`Scene::from_ron`].
    ///
    /// # Errors
    /// [`SceneError::Read`] if the file cannot be read, otherwise as [`Scene::from_ron`].
    pub fn from_file(path: impl AsRef<Path>) -> Result<Self, SceneError> {
        Ok(load_file(path)?.0)
    }
}

/// Reads a scene file and builds its world: [`Scene::from_file`] and [`Scene::build`] in one, building once.
///
/// # Errors
/// As [`Scene::from_file`].
pub fn load_file(path: impl AsRef<Path>) -> Result<(Scene, BuiltScene), SceneError> {
    let path = path.as_ref();
    let source = std::fs::read_to_string(path).map_err(|source| SceneError::Read {
        path: path.to_owned(),
        source,
    })?;
    load_str(&source)
}

/// Reads a scene from RON text and builds its world, as [`load_file`].
///
/// # Errors
/// As [`Scene::from_ron`].
pub fn load_str(source: &str) -> Result<(Scene, BuiltScene), SceneError> {
    let mut ignored = Vec::new();
    let scene = ron_options()
        .from_str_seed(source, Tracking(&mut ignored))
        .map_err(|e| {
            let location = Location {
                line: e.span.start.line,
                column: e.span.start.col,
            };
            match e.code {
                // A description's own check refused a value it read (serde's custom error).
                ron::Error::Message(message) => refused(source, location, message),
                code => SceneError::Syntax {
                    location,
                    message: code.to_string(),
                },
            }
        })?;
    if let Some(path) = ignored.into_iter().next() {
        let mut error = unknown_field(&path);
        locate(source, &mut error);
        return Err(error);
    }
    match scene.build() {
        Ok(built) => Ok((scene, built)),
        Err(mut error) => {
            locate(source, &mut error);
            Err(error)
        }
    }
}

/// The error for a value refused while it was read, the parser having stopped at `stopped`: placed at the
/// field it names inside the deepest item whose text holds `stopped`, else where the parser stopped.
fn refused(source: &str, stopped: Location, message: String) -> SceneError {
    let offset = offset_of(source, stopped);
    let item = ron_options()
        .from_str::<Outline<'_>>(source)
        .ok()
        .and_then(|outline| item_at(source, &outline, offset))
        .unwrap_or_else(|| "scene".to_owned());
    let mut error = SceneError::Refused {
        place: Place {
            item,
            location: None,
        },
        message,
    };
    locate(source, &mut error);
    if let Some(place) = error.place_mut()
        && place.location.is_none()
    {
        place.location = Some(stopped);
    }
    error
}

/// The byte offset of a line and column (both from 1, columns in characters), clamped to the text.
fn offset_of(source: &str, location: Location) -> usize {
    let line_start: usize = source
        .split_inclusive('\n')
        .take(location.line.saturating_sub(1))
        .map(str::len)
        .sum();
    let line = &source[line_start.min(source.len())..];
    let within = line
        .char_indices()
        .nth(location.column.saturating_sub(1))
        .map_or(line.len(), |(i, _)| i);
    line_start + within
}

/// The path of the deepest item (`bodies[3].colliders[0]`, `bodies[3].body`, `joints[2]`, `settings`) whose
/// text holds byte `offset` of `source`.
fn item_at(source: &str, outline: &Outline<'_>, offset: usize) -> Option<String> {
    let holds = |raw: &RawValue| {
        let text = raw.get_ron();
        (text.as_ptr() as usize)
            .checked_sub(source.as_ptr() as usize)
            .is_some_and(|start| (start..=start + text.len()).contains(&offset))
    };
    for (i, body) in outline.bodies.iter().enumerate() {
        if !holds(body) {
            continue;
        }
        let Ok(parts) = ron_options().from_str::<BodyOutline<'_>>(body.get_ron()) else {
            return Some(format!("bodies[{i}]"));
        };
        if parts.body.is_some_and(holds) {
            return Some(format!("bodies[{i}].body"));
        }
        let collider = parts.colliders.iter().position(|c| holds(c));
        return Some(collider.map_or_else(
            || format!("bodies[{i}]"),
            |j| format!("bodies[{i}].colliders[{j}]"),
        ));
    }
    if let Some(k) = outline.joints.iter().position(|j| holds(j)) {
        return Some(format!("joints[{k}]"));
    }
    [
        ("settings", outline.settings),
        ("run", outline.run),
        ("camera", outline.camera),
    ]
    .into_iter()
    .find(|(_, raw)| raw.is_some_and(holds))
    .map(|(name, _)| name.to_owned())
}

/// Reads a [`Scene`] and collects the path of every field serde skipped.
struct Tracking<'v>(&'v mut Vec<Vec<String>>);

impl<'de> DeserializeSeed<'de> for Tracking<'_> {
    type Value = Scene;

    fn deserialize<D: serde::Deserializer<'de>>(self, deserializer: D) -> Result<Scene, D::Error> {
        serde_ignored::deserialize(deserializer, |path| self.0.push(segments(&path)))
    }
}

/// A skipped field's path as keys and indices from the root (`["bodies", "3", "colliders", "0", "densty"]`).
fn segments(path: &serde_ignored::Path<'_>) -> Vec<String> {
    use serde_ignored::Path;
    match path {
        Path::Root => Vec::new(),
        Path::Seq { parent, index } => {
            let mut s = segments(parent);
            s.push(index.to_string());
            s
        }
        Path::Map { parent, key } => {
            let mut s = segments(parent);
            s.push(key.clone());
            s
        }
        Path::Some { parent }
        | Path::NewtypeStruct { parent }
        | Path::NewtypeVariant { parent } => segments(parent),
    }
}

/// The error for a skipped field: its item is the deepest body, collider or joint (or top-level part) the
/// path passes through.
fn unknown_field(path: &[String]) -> SceneError {
    let field = path.last().cloned().unwrap_or_default();
    let at = |i: usize| path.get(i).map(String::as_str);
    let item = match (at(0), at(1), at(2), at(3)) {
        (Some("bodies"), Some(i), Some("colliders"), Some(j)) if path.len() > 4 => {
            format!("bodies[{i}].colliders[{j}]")
        }
        (Some("bodies"), Some(i), Some("body"), _) if path.len() > 3 => format!("bodies[{i}].body"),
        (Some("bodies"), Some(i), _, _) if path.len() > 2 => format!("bodies[{i}]"),
        (Some("joints"), Some(k), _, _) if path.len() > 2 => format!("joints[{k}]"),
        (Some(part @ ("settings" | "run" | "camera")), _, _, _) if path.len() > 1 => {
            part.to_owned()
        }
        _ => "scene".to_owned(),
    };
    SceneError::UnknownField {
        place: Place {
            item,
            location: None,
        },
        field,
        path: path.join("."),
    }
}

/// The scene's outline: each item's raw text.
#[derive(Deserialize)]
#[serde(rename = "Scene")]
struct Outline<'a> {
    #[serde(borrow, default)]
    settings: Option<&'a RawValue>,
    #[serde(borrow, default)]
    run: Option<&'a RawValue>,
    #[serde(borrow, default)]
    camera: Option<&'a RawValue>,
    #[serde(borrow, default)]
    bodies: Vec<&'a RawValue>,
    #[serde(borrow, default)]
    joints: Vec<&'a RawValue>,
}

#[derive(Deserialize)]
struct BodyOutline<'a> {
    #[serde(borrow, default)]
    body: Option<&'a RawValue>,
    #[serde(borrow, default)]
    colliders: Vec<&'a RawValue>,
}

/// Gives `error` the line and column of its item in `source` (and of its field there, if it names one).
fn locate(source: &str, error: &mut SceneError) {
    let field = error.field();
    let Some(place) = error.place_mut() else {
        return;
    };
    let Ok(outline) = ron_options().from_str::<Outline<'_>>(source) else {
        return;
    };
    let raw = if place.item == "scene" {
        source
    } else {
        let Some(raw) = item_text(&outline, &place.item) else {
            return;
        };
        raw.trim().get_ron()
    };
    let Some(start) = (raw.as_ptr() as usize).checked_sub(source.as_ptr() as usize) else {
        return;
    };
    if start + raw.len() > source.len() {
        return;
    }
    let at = field
        .and_then(|f| find_field(raw, &f))
        .map_or(start, |offset| start + offset);
    place.location = Some(Location::of_offset(source, at));
}

/// The raw text of the item at `path` (`bodies[3].colliders[0]`, `joints[2]`, `settings`, `run`).
fn item_text<'a>(outline: &Outline<'a>, path: &str) -> Option<&'a RawValue> {
    let index = |s: &str| -> Option<usize> { s.strip_suffix(']')?.parse().ok() };
    let mut parts = path.split('.');
    let head = parts.next()?;
    if let Some(k) = head.strip_prefix("joints[") {
        return outline.joints.get(index(k)?).copied();
    }
    if let Some(i) = head.strip_prefix("bodies[") {
        let raw = *outline.bodies.get(index(i)?)?;
        let part = parts.next();
        if part.is_none() {
            return Some(raw);
        }
        let body: BodyOutline<'a> = ron_options().from_str(raw.get_ron()).ok()?;
        return match part {
            None | Some("body") => body.body,
            Some(c) => body
                .colliders
                .get(index(c.strip_prefix("colliders[")?)?)
                .copied(),
        };
    }
    match head {
        "settings" => outline.settings,
        "run" => outline.run,
        "camera" => outline.camera,
        _ => None,
    }
}

/// The byte offset in `text` of the first `field:` (the name as a whole word, then a colon).
fn find_field(text: &str, field: &str) -> Option<usize> {
    let is_word = |c: char| c.is_alphanumeric() || c == '_';
    let mut from = 0;
    while let Some(found) = text[from..].find(field) {
        let at = from + found;
        let before = text[..at].chars().next_back();
        let after = text[at + field.len()..].trim_start();
        if !before.is_some_and(is_word) && after.starts_with(':') {
            return Some(at);
        }
        from = at + field.len();
    }
    None
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn offsets_become_lines_and_columns() {
        let text = "ab\ncdé\nf";
        assert_eq!(
            Location::of_offset(text, 0),
            Location { line: 1, column: 1 }
        );
        assert_eq!(
            Location::of_offset(text, 4),
            Location { line: 2, column: 2 }
        );
        // After the two-byte 'é': column counts characters.
        assert_eq!(
            Location::of_offset(text, 7),
            Location { line: 2, column: 4 }
        );
        assert_eq!(
            Location::of_offset(text, 8),
            Location { line: 3, column: 1 }
        );
    }

    #[test]
    fn fields_are_found_as_whole_words_before_a_colon() {
        let text = "(half_height: 1.0, radius: 2.0)";
        assert_eq!(find_field(text, "radius"), Some(19));
        assert_eq!(find_field(text, "height"), None);
        assert_eq!(find_field("(radius_b: 1)", "radius"), None);
    }
}
