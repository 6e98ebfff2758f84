//! The example scenes (`examples/`), built in code: each module builds its world and returns the handles its
//! example watches, and describes the scene file it is written to under `scenes/` ([`scene_of`]).
//!
//! The examples run these worlds and print what they measure; `tests/scene_files.rs` checks that every file
//! in `scenes/` builds the same world, bit for bit, as the code here and in [`crate::scenes`].

use rebound::prelude::*;
use rebound_scene::{RunSettings, Scene, SceneCamera};

pub mod car;
pub mod chain;
pub mod drag_and_drop;
pub mod newtons_cradle;
pub mod pyramid;
pub mod ragdoll;
pub mod rope_bridge;
pub mod spring_camera;

/// The step every example runs with (s).
pub const DT: f32 = 1.0 / 60.0;

/// The example scenes' names, as their files under `scenes/` and their examples are called.
pub const DEMOS: [&str; 8] = [
    "newtons_cradle",
    "rope_bridge",
    "drag_and_drop",
    "spring_camera",
    "pyramid",
    "chain",
    "car",
    "ragdoll",
];

/// What a scene file says besides the world: its name, a sentence, how long a run lasts, where to look from.
#[derive(Debug, Clone, Copy)]
pub struct About {
    /// The file's name without `.ron`.
    pub name: &'static str,
    /// What the scene shows.
    pub description: &'static str,
    /// Steps of [`DT`] a run takes.
    pub steps: u32,
    /// Camera position, target (m) and vertical field of view (degrees).
    pub camera: (Vec3, Vec3, f32),
}

/// The scene file for `world` with `about`'s name, description, run length and camera.
#[must_use]
pub fn scene_of(world: &PhysicsWorld, about: &About) -> Scene {
    let (position, target, fov_degrees) = about.camera;
    Scene {
        name: about.name.to_owned(),
        description: about.description.to_owned(),
        run: RunSettings {
            dt: DT,
            steps: about.steps,
        },
        camera: Some(SceneCamera {
            position,
            target,
            fov_degrees,
        }),
        ..Scene::from_world(world)
    }
}

/// The world of the example scene called `name` (one of [`DEMOS`]) and its [`About`], or `Ok(None)` for an
/// unknown name.
///
/// # Errors
/// Whatever Rebound refuses while building (a bug: the scenes' parameters are constants).
pub fn build(name: &str) -> Result<Option<(PhysicsWorld, About)>, Error> {
    Ok(Some(match name {
        "newtons_cradle" => (newtons_cradle::build()?.world, newtons_cradle::ABOUT),
        "rope_bridge" => (rope_bridge::build()?.world, rope_bridge::ABOUT),
        "drag_and_drop" => (drag_and_drop::build()?.world, drag_and_drop::ABOUT),
        "spring_camera" => (spring_camera::build(0.3)?.world, spring_camera::ABOUT),
        "pyramid" => (pyramid::build()?.world, pyramid::ABOUT),
        "chain" => (chain::build()?.world, chain::ABOUT),
        "car" => (car::build()?.world, car::ABOUT),
        "ragdoll" => (ragdoll::build()?.world, ragdoll::ABOUT),
        _ => return Ok(None),
    }))
}

/// The five benchmark scenes' files (`scenes/benchmarks/NAME.ron`), in [`crate::scenes::DEFAULT_SCENES`]'
/// order: their name, sentence, run and view; the worlds are [`crate::scenes::build`]'s with the default
/// options.
pub const BENCHMARKS: [About; 5] = [
    About {
        name: "balls",
        description: "Benchmark: 4,096 balls falling into a pile on the ground (SCENES.md scene 1).",
        steps: 600,
        camera: (Vec3::new(30.0, 22.0, 40.0), Vec3::new(0.0, 6.0, 0.0), 45.0),
    },
    About {
        name: "pyramid",
        description: "Benchmark: a one-box-deep pyramid of 820 unit cubes, base 40 (SCENES.md scene 2).",
        steps: 600,
        camera: (Vec3::new(30.0, 25.0, 60.0), Vec3::new(0.0, 17.0, 0.0), 45.0),
    },
    About {
        name: "chain",
        description: "Benchmark: 500 balls on ropes, released horizontally from a fixed point (SCENES.md \
                      scene 3).",
        steps: 600,
        camera: (
            Vec3::new(0.0, -50.0, 200.0),
            Vec3::new(0.0, -50.0, 0.0),
            50.0,
        ),
    },
    About {
        name: "springs",
        description: "Benchmark: 1,000 damped spring pairs in zero gravity (SCENES.md scene 4).",
        steps: 600,
        camera: (
            Vec3::new(70.0, 50.0, 90.0),
            Vec3::new(18.0, 18.0, 18.0),
            45.0,
        ),
    },
    About {
        name: "bridge",
        description: "Benchmark: a slack rope bridge of 100 planks between two anchors, with 50 balls dropped \
                      on it (SCENES.md scene 5).",
        steps: 600,
        camera: (Vec3::new(10.0, 12.0, 60.0), Vec3::new(0.0, 3.0, 0.0), 50.0),
    },
];
