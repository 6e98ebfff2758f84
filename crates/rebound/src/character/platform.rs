//! Platform carry: a character standing on a moving body moves with it. The ground's velocity at the contact
//! point, `v + ω × (p − c)` (m/s), times the move's `dt`, is added to the move, cast like any motion but
//! through the platform itself (which moves the same way during the next step).
//!
//! The velocity is the one the platform had over the last step; a platform that keeps it (or whose kinematic
//! target moves it the same way again) keeps the character's offset exactly. A change of velocity reaches
//! the character one move late, and the platform's rotation turns the carried offset but not the shape.

use super::ground::Ground;
use super::sweep::Probe;
use rebound_dynamics::BodyType;
use rebound_math::Vec3;

/// The translation (m) that keeps a character at `position` on `ground` over `dt` (s).
pub(crate) fn carry(probe: &Probe<'_>, position: Vec3, ground: &Ground, dt: f32) -> Vec3 {
    let Some(body) = probe.scene.bodies.get(ground.body) else {
        return Vec3::ZERO;
    };
    if body.body_type() == BodyType::Fixed {
        return Vec3::ZERO;
    }
    let motion = body.velocity_at_point(ground.point) * dt;
    let length = motion.length();
    let Some(direction) = motion.try_normalize().filter(|_| length.is_finite()) else {
        return Vec3::ZERO;
    };
    match probe.sweep(position, direction, length, Some(ground.body)) {
        Some(hit) => direction * hit.distance,
        None => motion,
    }
}
