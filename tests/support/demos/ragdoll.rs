//! A ragdoll ([`rebound::ragdoll`]) pushed off the top landing of a flight of stairs: it tumbles down them.

use super::About;
use rebound::prelude::*;
use rebound::ragdoll::{Ragdoll, RagdollDesc};

/// Steps in the flight, landing included.
pub const STEPS: usize = 6;
/// Height of one step (m).
pub const RISE: f32 = 0.25;
/// Depth of one step (m).
pub const RUN: f32 = 0.45;
/// Half the stairs' width (m).
const HALF_WIDTH: f32 = 2.0;
/// Depth of the top landing (m), behind `z = 0`.
const LANDING: f32 = 1.5;

/// The scene file's name, run and view.
pub const ABOUT: About = About {
    name: "ragdoll",
    description: "A 15-part ragdoll with human joint ranges pushed off the top landing of six stairs: it \
                  tumbles down them.",
    steps: 300,
    camera: (Vec3::new(5.5, 3.0, 4.5), Vec3::new(0.0, 0.8, 1.3), 50.0),
};

/// The stairs and the ragdoll.
#[derive(Debug)]
pub struct RagdollStairs {
    /// The world.
    pub world: PhysicsWorld,
    /// The ragdoll's parts and joints.
    pub ragdoll: Ragdoll,
}

/// The height of the stairs' surface (m) at depth `z` (m): the landing's top behind `z = 0`, then each step's,
/// then the ground at 0.
#[must_use]
pub fn surface_height(z: f32) -> f32 {
    let top = |k: usize| (STEPS - 1 - k) as f32 * RISE;
    if z < 0.0 {
        return top(0) + RISE;
    }
    let k = (z / RUN) as usize;
    if k >= STEPS - 1 { 0.0 } else { top(k) }
}

/// Builds the stairs descending along +z and the ragdoll standing on the landing, walking off at 1.5 m/s.
///
/// # Errors
/// Whatever Rebound refuses (a bug).
pub fn build() -> Result<RagdollStairs, Error> {
    let mut world = PhysicsWorld::new(WorldSettings::default())?;
    let ground = world.insert_body(BodyDesc::fixed().with_position(Vec3::new(0.0, -0.5, 4.0)))?;
    world.insert_collider(ColliderDesc::cuboid(Vec3::new(10.0, 0.5, 10.0)), ground)?;
    // The landing, then one block per step, each from the ground up to its top.
    let landing_top = surface_height(-1.0);
    let block = |world: &mut PhysicsWorld, top: f32, z0: f32, z1: f32| -> Result<(), Error> {
        let body = world.insert_body(BodyDesc::fixed().with_position(Vec3::new(
            0.0,
            0.5 * top,
            0.5 * (z0 + z1),
        )))?;
        let half = Vec3::new(HALF_WIDTH, 0.5 * top, 0.5 * (z1 - z0));
        world.insert_collider(ColliderDesc::cuboid(half).with_friction(0.8), body)?;
        Ok(())
    };
    block(&mut world, landing_top, -LANDING, 0.0)?;
    for k in 0..STEPS - 1 {
        let top = surface_height((k as f32 + 0.5) * RUN);
        block(&mut world, top, k as f32 * RUN, (k + 1) as f32 * RUN)?;
    }
    let ragdoll = Ragdoll::build(
        &mut world,
        &RagdollDesc {
            position: Vec3::new(0.0, landing_top, -0.35),
            // Leaning forward over the edge.
            rotation: Quat::from_rotation_x(0.25),
            linear_velocity: Vec3::new(0.0, 0.0, 1.5),
            ..RagdollDesc::default()
        },
    )?;
    Ok(RagdollStairs { world, ragdoll })
}
