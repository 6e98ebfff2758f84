//! The example scenes built into the command: `rebound run newtons_cradle` runs `scenes/newtons_cradle.ron`
//! from any directory, so a `rebound` installed with `cargo install` works away from the source tree. A path
//! that names an existing file always wins over a built-in name. The five benchmark scenes
//! (`scenes/benchmarks/`, up to 0.7 MB each) are not built in; run them by path.

use std::path::Path;

/// The built-in scenes: each name and the RON text of `scenes/<name>.ron`.
pub const SCENES: [(&str, &str); 7] = [
    (
        "newtons_cradle",
        include_str!("../../../scenes/newtons_cradle.ron"),
    ),
    (
        "rope_bridge",
        include_str!("../../../scenes/rope_bridge.ron"),
    ),
    ("pyramid", include_str!("../../../scenes/pyramid.ron")),
    ("car", include_str!("../../../scenes/car.ron")),
    ("chain", include_str!("../../../scenes/chain.ron")),
    (
        "drag_and_drop",
        include_str!("../../../scenes/drag_and_drop.ron"),
    ),
    (
        "spring_camera",
        include_str!("../../../scenes/spring_camera.ron"),
    ),
];

/// The text of the built-in scene `path` names — `NAME`, `NAME.ron` or `scenes/NAME.ron` — if `path` is
/// not an existing file.
#[must_use]
pub fn scene(path: &Path) -> Option<&'static str> {
    if path.exists() {
        return None;
    }
    let text = path.to_str()?;
    let name = text.strip_prefix("scenes/").unwrap_or(text);
    let name = name.strip_suffix(".ron").unwrap_or(name);
    SCENES
        .iter()
        .find(|(known, _)| *known == name)
        .map(|&(_, source)| source)
}

/// The built-in names, comma-separated (for messages).
#[must_use]
pub fn names() -> String {
    SCENES.map(|(name, _)| name).join(", ")
}

#[cfg(test)]
mod tests {
    use super::{SCENES, scene};
    use std::path::Path;

    #[test]
    fn every_built_in_scene_loads_and_is_its_file() {
        let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../..");
        for (name, source) in SCENES {
            let file = std::fs::read_to_string(root.join(format!("scenes/{name}.ron"))).unwrap();
            assert_eq!(source, file, "{name}");
            assert!(rebound_scene::load_str(source).is_ok(), "{name}");
        }
        for spelling in ["pyramid", "pyramid.ron", "scenes/pyramid.ron"] {
            let found = scene(Path::new(spelling));
            // From the package directory `scenes/pyramid.ron` is not a file: all three are the name.
            assert_eq!(found, Some(SCENES[2].1), "{spelling}");
        }
        assert_eq!(scene(Path::new("no_such_scene")), None);
    }
}
