//! Scene files for Rebound: a world's settings, its bodies with their colliders, its joints and how to run
//! it, as RON text read through serde.
//!
//! The bodies, colliders, joints and settings in a file are the engine's own serde descriptions
//! ([`rebound::BodyDesc`], [`rebound::ColliderDesc`] with every [`rebound::ColliderShape`],
//! [`rebound::Joint`] with every [`rebound::JointKind`], [`rebound::WorldSettings`]); every field has its
//! default, so a file names only what differs. A file is checked whole before anything runs: text that is not
//! a scene and values the engine refuses both give a [`SceneError`] naming the item, the field and the value,
//! with the line and column.
//!
//! ```
//! use rebound_scene::{Scene, SceneError};
//! let text = "Scene(bodies: [(colliders: [(shape: Ball(radius: -0.5))])])";
//! let error = Scene::from_ron(text).unwrap_err();
//! assert_eq!(error.location().map(|l| (l.line, l.column)), Some((1, 42)));
//! assert_eq!(
//!     error.to_string(),
//!     "line 1, column 42: bodies[0].colliders[0]: `radius` must be > 0, got -0.5"
//! );
//! ```
//!
//! Files and code meet in both directions: [`Scene::build`] makes the world, [`Scene::from_world`] reads a
//! world back into a scene, and [`Scene::to_ron`] writes it.

mod build;
mod error;
mod export;
mod load;
mod scene;
mod write;

pub use build::BuiltScene;
pub use error::{Location, Place, SceneError};
pub use load::{load_file, load_str, ron_options};
pub use scene::{RunSettings, Scene, SceneBody, SceneCamera, SceneJoint};
