//! Platform carry: a character standing on a moving body moves with it. The contact point `p` is carried as a
//! point of the body over the move's `dt`: `p' = c + v·dt + R(ω·dt)·(p − c)`, with the body's centre of mass
//! `c`, velocity `v`, angular velocity `ω` and `R(ω·dt)` the rotation by `|ω|·dt` about `ω` — the motion
//! the step gives the body, exact for constant velocities (to first order it is `(v + ω × (p − c))·dt`).
//! `p' − p` is added to the move, cast like any motion but through the platform itself (which moves the same
//! way during the next step).
//!
//! The velocities are the ones the platform had over the last step; a platform that keeps them (or whose
//! kinematic target moves it the same way again) keeps the character's offset. A change of velocity reaches
//! the character one move late, and the shape is carried round a turning platform without turning itself.

use super::ground::Ground;
use super::sweep::Probe;
use rebound_dynamics::BodyType;
use rebound_math::{Quat, Vec3};

/// The translation (m) that keeps a character at `position` on `ground` over `dt` (s).
pub(crate) fn carry(probe: &Probe<'_>, position: Vec3, ground: &Ground, dt: f32) -> Vec3 {
    let Some(body) = probe.scene.bodies.get(ground.body) else {
        return Vec3::ZERO;
    };
    if body.body_type() == BodyType::Fixed {
        return Vec3::ZERO;
    }
    let centre = body.center_of_mass();
    let turn = Quat::from_scaled_axis(body.angular_velocity() * dt);
    let carried_point = centre + body.linear_velocity() * dt + turn * (ground.point - centre);
    let motion = carried_point - ground.point;
    let length = motion.length();
    let Some(direction) = motion.try_normalize().filter(|_| length.is_finite()) else {
        return Vec3::ZERO;
    };
    match probe.sweep(position, direction, length, Some(ground.body)) {
        Some(hit) => direction * hit.distance,
        None => motion,
    }
}
