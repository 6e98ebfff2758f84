//! The scene description: what a scene file holds, as plain serde types. Bodies, colliders, joints and the
//! world settings are the engine's own descriptions ([`BodyDesc`], [`ColliderDesc`], [`Joint`],
//! [`WorldSettings`]); this module adds only what a file needs around them: names, the body each joint
//! connects (by its index in [`Scene::bodies`]), and how long a run is.

use rebound::prelude::*;
use serde::{Deserialize, Serialize};

/// A scene: the world's settings, its bodies with their colliders, its joints, and how to run it.
///
/// Every field has a default, so a file names only what it needs. In RON:
///
/// ```
/// let scene = rebound_scene::Scene::from_ron(r#"
/// Scene(
///     bodies: [
///         (body: (body_type: Fixed), colliders: [(shape: Cuboid(half_extents: (5.0, 0.5, 5.0)))]),
///         (body: (position: (0.0, 3.0, 0.0)), colliders: [(shape: Ball(radius: 0.5))]),
///     ],
///     joints: [(body_b: 1, joint: (kind: Rope((max_length: 4.0, restitution: 0.0)),
///         local_anchor_a: (0.0, 6.0, 0.0)))],
/// )"#)?;
/// let built = scene.build()?;
/// assert_eq!(built.world.bodies().len(), 2);
/// # Ok::<(), rebound_scene::SceneError>(())
/// ```
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, Default)]
#[serde(default)]
pub struct Scene {
    /// A short name (`"newtons_cradle"`). Default: empty.
    pub name: String,
    /// What the scene shows, in a sentence or two. Default: empty.
    pub description: String,
    /// The world's settings. Default: [`WorldSettings::default`].
    pub settings: WorldSettings,
    /// How a run of the scene steps and how long it lasts. Default: [`RunSettings::default`].
    pub run: RunSettings,
    /// Where a picture of the scene looks from, if the scene suggests a view. Default: none (the renderer
    /// frames the bodies itself).
    pub camera: Option<SceneCamera>,
    /// The bodies, in insertion order. Joints name them by their index here. Default: none.
    pub bodies: Vec<SceneBody>,
    /// The joints, in insertion order. Default: none.
    pub joints: Vec<SceneJoint>,
}

/// How a run of the scene steps.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(default)]
pub struct RunSettings {
    /// The step length (s, > 0 and finite). Default: 1/60 s.
    pub dt: f32,
    /// How many steps a run takes unless told otherwise (≥ 1). Default: 600 (10 s at 60 Hz).
    pub steps: u32,
}

impl Default for RunSettings {
    fn default() -> Self {
        Self {
            dt: 1.0 / 60.0,
            steps: 600,
        }
    }
}

/// A view suggested for pictures of the scene: a pinhole camera at `position` looking at `target`.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(default)]
pub struct SceneCamera {
    /// The eye (m, world frame). Default: (6, 4, 10).
    pub position: Vec3,
    /// The point looked at (m). Default: origin.
    pub target: Vec3,
    /// Vertical field of view (degrees, in (0, 180)). Default: 45°.
    pub fov_degrees: f32,
}

impl Default for SceneCamera {
    fn default() -> Self {
        Self {
            position: Vec3::new(6.0, 4.0, 10.0),
            target: Vec3::ZERO,
            fov_degrees: 45.0,
        }
    }
}

/// A body and the colliders on it.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, Default)]
#[serde(default)]
pub struct SceneBody {
    /// A name for people and tools (`"ball 3"`); joints do not use it. Default: empty.
    pub name: String,
    /// The body: type, pose, velocities, damping, mass when no collider gives one. Default:
    /// [`BodyDesc::default`] (a dynamic body at the origin).
    pub body: BodyDesc,
    /// The colliders on the body, in insertion order. Default: none.
    pub colliders: Vec<ColliderDesc>,
}

/// A joint and the bodies it connects.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct SceneJoint {
    /// Index in [`Scene::bodies`] of body A, or `None` for the world (then the joint's anchor A is a world
    /// point). Default: `None`.
    #[serde(default)]
    pub body_a: Option<usize>,
    /// Index in [`Scene::bodies`] of body B.
    pub body_b: usize,
    /// The joint: kind with its options, anchors, frames, break limits.
    pub joint: Joint,
    /// Whether the two bodies still collide with each other. Default: true.
    #[serde(default = "yes")]
    pub contacts_enabled: bool,
}

fn yes() -> bool {
    true
}
