//! Pushing: after a move, each dynamic body the character ran into (at most once per body, at its first
//! contact) gets the impulse along the push direction `d = −n` that brings its velocity at the contact point
//! up to the character's desired velocity along `d`:
//!
//! ```text
//! J = (v_char·d − v_body(p)·d) / (1/m + (r × d)·I⁻¹(r × d)),   r = p − c,   J ≤ max_impulse
//! ```
//!
//! Bodies heavier than `max_mass`, and bodies already moving away at least as fast, get nothing. The
//! character itself is kinematic and is not pushed back.

use super::{CharacterMove, Push};
use crate::{Error, PhysicsWorld};
use rebound_math::Vec3;
use rebound_world::BodyHandle;

/// An impulse a move gave a body.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CharacterPush {
    /// The body pushed.
    pub body: BodyHandle,
    /// Where (m, world space).
    pub point: Vec3,
    /// The impulse (N·s, world space).
    pub impulse: Vec3,
}

/// Applies the pushes of `moved` to `world` and returns them, in the order of the collisions.
pub(crate) fn push_bodies(
    world: &mut PhysicsWorld,
    push: &Push,
    moved: &CharacterMove,
) -> Result<Vec<CharacterPush>, Error> {
    let velocity = moved.desired_velocity();
    let mut pushes: Vec<CharacterPush> = Vec::new();
    for collision in &moved.collisions {
        if pushes.iter().any(|p| p.body == collision.body) {
            continue;
        }
        let Some(body) = world.body(collision.body) else {
            continue;
        };
        let inv_mass = body.inv_mass();
        if !body.is_dynamic() || inv_mass <= 0.0 || inv_mass * push.max_mass < 1.0 {
            continue;
        }
        let direction = -collision.normal;
        let closing =
            velocity.dot(direction) - body.velocity_at_point(collision.point).dot(direction);
        let arm = (collision.point - body.center_of_mass()).cross(direction);
        let effective_inv_mass = inv_mass + arm.dot(body.inv_inertia_world() * arm);
        let impulse = (closing / effective_inv_mass).min(push.max_impulse);
        if !(impulse > 0.0 && impulse.is_finite()) {
            continue;
        }
        world.wake_body(collision.body)?;
        if let Some(body) = world.body_mut(collision.body) {
            body.apply_impulse_at_point(direction * impulse, collision.point)?;
        }
        pushes.push(CharacterPush {
            body: collision.body,
            point: collision.point,
            impulse: direction * impulse,
        });
    }
    Ok(pushes)
}
