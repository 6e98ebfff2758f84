//! The peer scenes of docs/scenes.md built in Rebound, one module each, exactly as the rapier side
//! (`benches/peers/src/scenes/`) builds them: the same counts, positions, seeds and f32 arithmetic, and the
//! same quality metrics under the same names, so that the two engines compare one to one.
//!
//! Every scene owns its [`PhysicsWorld`]. A runner calls [`Scene::step`] (the one timed call: a single
//! `PhysicsWorld::step` of 1/60 s) and then [`Scene::observe`] outside the timed region, which keeps the
//! run-long metrics up to date; [`Scene::quality`] reads the metrics at the end.
//!
//! Rebound runs these scenes on its own defaults ([`WorldSettings::default`]) with two changes docs/scenes.md asks
//! for: sleeping off (in the settings and on every dynamic body, unless [`SceneOptions::sleep`]), and zero
//! gravity in `springs`. One thread (Rebound has no other mode yet), dt = 1/60 s.

use rebound::prelude::*;

pub mod balls;
pub mod bridge;
pub mod chain;
pub mod metrics;
pub mod pyramid;
pub mod ragdolls;
pub mod springs;

pub use balls::Balls;
pub use bridge::Bridge;
pub use chain::{Chain, Link};
pub use metrics::Value;
pub use pyramid::Pyramid;
pub use ragdolls::Ragdolls;
pub use springs::Springs;

/// The step every scene runs with (s).
pub const DT: f32 = 1.0 / 60.0;

/// The five default peer scenes, in the order of docs/scenes.md.
pub const DEFAULT_SCENES: [&str; 5] = ["balls", "pyramid", "chain", "springs", "bridge"];

/// Every scene name [`build`] accepts: the five default ones and the supplementary `chain_spherical` and
/// `ragdolls`.
pub const ALL_SCENES: [&str; 7] = [
    "balls",
    "pyramid",
    "chain",
    "springs",
    "bridge",
    "chain_spherical",
    "ragdolls",
];

/// Options shared by every scene.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct SceneOptions {
    /// Let bodies fall asleep (Rebound's default). Off by default: docs/scenes.md disables sleeping on every
    /// dynamic body, so that both engines do the same work every step.
    pub sleep: bool,
}

impl SceneOptions {
    /// Rebound's default settings with sleeping as asked and the given gravity (m/s²).
    #[must_use]
    pub fn settings(self, gravity: Vec3) -> WorldSettings {
        WorldSettings {
            gravity,
            sleep_enabled: self.sleep,
            ..WorldSettings::default()
        }
    }

    /// A dynamic body at `position`, allowed to sleep only if [`SceneOptions::sleep`] is set.
    #[must_use]
    pub fn dynamic(self, position: Vec3) -> BodyDesc {
        BodyDesc::dynamic()
            .with_position(position)
            .with_can_sleep(self.sleep)
    }
}

/// A built scene, ready to step (`Send`: it can be stepped inside a thread pool, as `compare --threads` does).
pub trait Scene: Send {
    /// The world.
    fn world(&self) -> &PhysicsWorld;

    /// The world, for settings that change no result (its thread pool and when a step uses it).
    fn world_mut(&mut self) -> &mut PhysicsWorld;

    /// One step of [`DT`]: the only call a benchmark times.
    fn step(&mut self) -> StepReport;

    /// Called after step `step` (1-based), outside the timed region: updates the run-long metrics.
    fn observe(&mut self, step: usize);

    /// The quality metrics now (and over the run where the name ends in `_run`), in the order of docs/scenes.md, with
    /// the rapier side's names.
    fn quality(&self) -> Vec<(&'static str, Value)>;

    /// Dynamic bodies (the "bodies" column of docs/scenes.md: the fixed ground and anchors are not counted).
    fn body_count(&self) -> usize {
        self.world()
            .bodies()
            .iter()
            .filter(|(_, body)| body.is_dynamic())
            .count()
    }

    /// Joints.
    fn joint_count(&self) -> usize {
        self.world().world().joints().count()
    }
}

/// Builds the scene called `name` (one of [`ALL_SCENES`]), or `Ok(None)` for an unknown name.
///
/// # Errors
/// Whatever Rebound refuses while the scene is built (a bug: the scenes' parameters are constants).
pub fn build(name: &str, options: SceneOptions) -> Result<Option<Box<dyn Scene>>, Error> {
    let scene: Box<dyn Scene> = match name {
        "balls" => Box::new(Balls::new(options, balls::SIDE)?),
        "pyramid" => Box::new(Pyramid::new(options, pyramid::BASE)?),
        "chain" => Box::new(Chain::new(options, Link::Rope)?),
        "chain_spherical" => Box::new(Chain::new(options, Link::Spherical)?),
        "springs" => Box::new(Springs::new(options)?),
        "bridge" => Box::new(Bridge::new(options)?),
        "ragdolls" => Box::new(Ragdolls::new(options)?),
        _ => return Ok(None),
    };
    Ok(Some(scene))
}

/// Adds the ground of docs/scenes.md: a fixed cuboid of half-extents 100 × 0.5 × 100 centred at (0, −0.5, 0), so its
/// top face is y = 0 (collider defaults: friction 0.5, restitution 0, as rapier's).
///
/// # Errors
/// As [`PhysicsWorld::insert_body`] and [`PhysicsWorld::insert_collider`].
pub fn add_ground(world: &mut PhysicsWorld) -> Result<BodyHandle, Error> {
    let ground = world.insert_body(BodyDesc::fixed().with_position(Vec3::new(0.0, -0.5, 0.0)))?;
    world.insert_collider(ColliderDesc::cuboid(Vec3::new(100.0, 0.5, 100.0)), ground)?;
    Ok(ground)
}

/// A joint description error as the facade's error type (it reaches the facade through the world's).
#[must_use]
pub fn joint_error(error: ConstraintError) -> Error {
    Error::World(error.into())
}
