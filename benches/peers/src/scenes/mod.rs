//! The peer scenes of docs/scenes.md, one module each, built in rapier3d exactly as specified there.
//!
//! Every scene owns its [`World`] and whatever it needs to measure its quality. The runner steps the world
//! (the timed part) and calls [`Scene::observe`] after each step, outside the timed region, so that metrics
//! maximised over the run cost nothing in the timings.

use rapier3d::prelude::*;

use crate::metrics::Quality;
use crate::world::World;

pub mod balls;
pub mod bridge;
pub mod chain;
pub mod pyramid;
pub mod ragdolls;
pub mod springs;

/// The five default peer scenes, in the order of docs/scenes.md (what `--scene all` runs).
pub const DEFAULT_SCENES: [&str; 5] = ["balls", "pyramid", "chain", "springs", "bridge"];

/// Every scene name accepted by `--scene`: the five default ones and the supplementary `chain_spherical` and
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
#[derive(Debug, Clone, Copy, Default)]
pub struct SceneOptions {
    /// Let dynamic bodies fall asleep (rapier's default). Off by default: docs/scenes.md disables sleeping on every
    /// dynamic body so that the engines do the same work each step.
    pub sleep: bool,
}

impl SceneOptions {
    /// A dynamic-body builder at `translation`, with sleeping allowed only if `--sleep` was given.
    pub fn dynamic(self, translation: Vector) -> RigidBodyBuilder {
        RigidBodyBuilder::dynamic()
            .translation(translation)
            .can_sleep(self.sleep)
    }
}

/// A built scene, ready to step.
pub trait Scene {
    /// The world to step.
    fn world(&self) -> &World;

    /// Mutable access to the world (for stepping).
    fn world_mut(&mut self) -> &mut World;

    /// Called after step `step` (1-based) of `total`, outside the timed region: updates run-long metrics.
    fn observe(&mut self, step: usize, total: usize);

    /// The quality metrics at the end of the run.
    fn quality(&self) -> Quality;
}

/// Builds the scene called `name`, or returns `None` for an unknown name.
pub fn build(name: &str, options: SceneOptions) -> Option<Box<dyn Scene>> {
    let scene: Box<dyn Scene> = match name {
        "balls" => Box::new(balls::Balls::new(options)),
        "pyramid" => Box::new(pyramid::Pyramid::new(options)),
        "chain" => Box::new(chain::Chain::new(options, chain::Link::Rope)),
        "chain_spherical" => Box::new(chain::Chain::new(options, chain::Link::Spherical)),
        "springs" => Box::new(springs::Springs::new(options)),
        "bridge" => Box::new(bridge::Bridge::new(options)),
        "ragdolls" => Box::new(ragdolls::Ragdolls::new(options)),
        _ => return None,
    };
    Some(scene)
}

/// Adds the ground of docs/scenes.md: a fixed cuboid of half-extents 100 × 0.5 × 100 centred at (0, −0.5, 0), so its
/// top face is y = 0 (collider defaults: friction 0.5, restitution 0).
pub fn add_ground(world: &mut World) -> RigidBodyHandle {
    world.add_body(
        RigidBodyBuilder::fixed().translation(Vector::new(0.0, -0.5, 0.0)),
        Some(ColliderBuilder::cuboid(100.0, 0.5, 100.0).build()),
    )
}
