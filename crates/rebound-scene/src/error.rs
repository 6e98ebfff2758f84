//! Why a scene file cannot be loaded: typed errors that name the item, the field and the value, and where in
//! the file they are (line and column, both from 1).

use std::fmt;
use std::path::PathBuf;

/// A place in a scene file: line and column, both counted from 1 (columns in characters).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct Location {
    /// Line, from 1.
    pub line: usize,
    /// Column, from 1, in characters.
    pub column: usize,
}

impl Location {
    /// The location of byte `offset` in `source` (clamped to its end and to a character boundary).
    #[must_use]
    pub fn of_offset(source: &str, offset: usize) -> Self {
        let mut offset = offset.min(source.len());
        while !source.is_char_boundary(offset) {
            offset -= 1;
        }
        let before = &source[..offset];
        let line_start = before.rfind('\n').map_or(0, |i| i + 1);
        Self {
            line: before.matches('\n').count() + 1,
            column: before[line_start..].chars().count() + 1,
        }
    }
}

impl fmt::Display for Location {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "line {}, column {}", self.line, self.column)
    }
}

/// Where an error is: the item (`bodies[3].colliders[0]`, `joints[2]`, `settings`) and, for a scene read
/// from text, the line and column of the offending field (or of the item when the field cannot be told).
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Place {
    /// The item's path in the scene, as `bodies[3].colliders[0]`.
    pub item: String,
    /// Its line and column in the file, when the scene was read from text.
    pub location: Option<Location>,
}

impl fmt::Display for Place {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self.location {
            Some(location) => write!(f, "{location}: {}", self.item),
            None => f.write_str(&self.item),
        }
    }
}

/// Why a scene cannot be read or built. Nothing is built when one is returned.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum SceneError {
    /// The file could not be read.
    #[error("cannot read scene file {path}: {source}")]
    Read {
        /// The file.
        path: PathBuf,
        /// What the system said.
        #[source]
        source: std::io::Error,
    },
    /// The text is not a scene: bad RON, an unknown field or kind, a value of the wrong type. The message is
    /// the parser's and names what it expected and found.
    #[error("{location}: {message}")]
    Syntax {
        /// Where the parser stopped.
        location: Location,
        /// What it expected and found.
        message: String,
    },
    /// A field the item does not have (misspelt, or from another kind): without this check it would be
    /// skipped and its default used.
    #[error("{place}: unknown field `{field}` (at `{path}`)")]
    UnknownField {
        /// The item and where the field is.
        place: Place,
        /// The field as written.
        field: String,
        /// Its full path in the scene, as `bodies.3.colliders.0.densty`.
        path: String,
    },
    /// A value the engine refuses (a negative radius, a NaN, a zero axis): the engine's own error, which
    /// names the field and the value.
    #[error("{place}: {source}")]
    Invalid {
        /// The item and where it is.
        place: Place,
        /// The engine's error (boxed: it is large, and errors are rare).
        #[source]
        source: Box<rebound::Error>,
    },
    /// A value its description's own check refused while the file was read (the message is that check's,
    /// naming the field and the value): a rope of negative length, settings above their bounds, a zero mass.
    #[error("{place}: {message}")]
    Refused {
        /// The item and where the field is.
        place: Place,
        /// What the check said.
        message: String,
    },
    /// A body's mass properties are not a positive mass with a finite centre and inertia.
    #[error("{place}: `{field}` must be finite{positive}, got {value}", positive = if *field == "mass" { " and > 0" } else { "" })]
    InvalidMass {
        /// The body and where it is.
        place: Place,
        /// `mass`, `local_center_of_mass` or `local_inertia`.
        field: &'static str,
        /// The value given.
        value: String,
    },
    /// A joint names a body that the scene does not have.
    #[error("{place}: `{field}` names body {index}, but the scene has {body_count} bodies (0 to {last})", last = body_count.saturating_sub(1) as i64)]
    UnknownBody {
        /// The joint and where it is.
        place: Place,
        /// `body_a` or `body_b`.
        field: &'static str,
        /// The index given.
        index: usize,
        /// How many bodies the scene has.
        body_count: usize,
    },
    /// The run settings are unusable.
    #[error("{place}: `{field}` must be {expected}, got {value}")]
    InvalidRun {
        /// `run` and where it is.
        place: Place,
        /// `dt` or `steps`.
        field: &'static str,
        /// What is accepted.
        expected: &'static str,
        /// The value given.
        value: String,
    },
}

impl SceneError {
    /// The error's place in the scene (none for read and syntax errors, whose location is their own).
    #[must_use]
    pub fn place(&self) -> Option<&Place> {
        match self {
            Self::Read { .. } | Self::Syntax { .. } => None,
            Self::Invalid { place, .. }
            | Self::Refused { place, .. }
            | Self::UnknownField { place, .. }
            | Self::InvalidMass { place, .. }
            | Self::UnknownBody { place, .. }
            | Self::InvalidRun { place, .. } => Some(place),
        }
    }

    /// Where in the file the error is, if the scene was read from text.
    #[must_use]
    pub fn location(&self) -> Option<Location> {
        match self {
            Self::Syntax { location, .. } => Some(*location),
            _ => self.place().and_then(|p| p.location),
        }
    }

    pub(crate) fn place_mut(&mut self) -> Option<&mut Place> {
        match self {
            Self::Read { .. } | Self::Syntax { .. } => None,
            Self::Invalid { place, .. }
            | Self::Refused { place, .. }
            | Self::UnknownField { place, .. }
            | Self::InvalidMass { place, .. }
            | Self::UnknownBody { place, .. }
            | Self::InvalidRun { place, .. } => Some(place),
        }
    }

    /// The field the error is about, when it names one: the engine's errors quote it between backticks.
    pub(crate) fn field(&self) -> Option<String> {
        match self {
            Self::InvalidMass { field, .. }
            | Self::UnknownBody { field, .. }
            | Self::InvalidRun { field, .. } => Some((*field).to_owned()),
            Self::UnknownField { field, .. } => Some(field.clone()),
            Self::Invalid { source, .. } => quoted_field(&source.to_string()),
            Self::Refused { message, .. } => quoted_field(message),
            Self::Read { .. } | Self::Syntax { .. } => None,
        }
    }
}

/// The first field an engine error quotes between backticks: its leading identifier (`points[3]`,
/// `heights × scale.y` give `points`, `heights`).
fn quoted_field(text: &str) -> Option<String> {
    let start = text.find('`')? + 1;
    let len = text[start..].find('`')?;
    let field: String = text[start..start + len]
        .chars()
        .take_while(|c| c.is_alphanumeric() || *c == '_')
        .collect();
    (!field.is_empty()).then_some(field)
}
