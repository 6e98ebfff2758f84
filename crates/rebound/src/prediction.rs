//! What the broad and the narrow phase share: how far apart two colliders may be and still get a contact this
//! step (the *prediction distance*), the quantities it is built from — a collider's rotation reach and a
//! ball's world centre — and the ball-pair test both phases apply to the same values.
//!
//! The prediction distance of a pair is the speculative margin plus what the pair can close in the step:
//!
//! ```text
//! prediction = speculative_margin + (|v₁ − v₂| + |ω₁|·r₁ + |ω₂|·r₂)·dt
//! ```
//!
//! with `r` bounding each collider's distance from its body's centre of mass ([`rotation_reach`]). The broad
//! phase fattens each box by its own body's share of this (`speculative_margin + (|v| + |ω|·r)·dt`), which is
//! never less than a pair's prediction distance; it then drops two balls whose centres are farther apart than
//! the prediction distance allows ([`centres_clearly_apart`]), and the narrow phase asks the generators for
//! points up to that distance.

use crate::{Collider, ColliderShape};
use parry3d::bounding_volume::Aabb;
use rebound_dynamics::RigidBody;
use rebound_math::{Pose, Vec3};

/// The largest prediction distance (m); see the broad phase's margin cap.
const MAX_PREDICTION: f32 = 1.0e7;

/// How much farther apart (m) than the prediction distance two balls' surfaces must be, measured in world
/// space, for [`centres_clearly_apart`] to skip the pair: far more than the rounding that separates the
/// world-space distance from the one the ball–ball generator measures in ball 1's frame, so the skip never
/// drops a contact the generator would report.
const BALL_SKIP_MARGIN: f32 = 1.0e-3;

/// How far rotation can move the surface of a collider whose world box is `aabb` per second this step,
/// `|ω|·r` (m/s), with `r` = the box centre's distance from `body`'s centre of mass plus the box's half
/// diagonal, a bound on the distance of every point of the box from the centre of mass.
#[inline]
pub(crate) fn rotation_reach(body: &RigidBody, aabb: &Aabb) -> f32 {
    let r = (aabb.center() - body.center_of_mass()).length() + aabb.half_extents().length();
    body.angular_velocity().length() * r
}

/// How far apart (m) two colliders on bodies of linear velocities `v1` and `v2` (m/s) may be and still get a
/// (speculative) contact this step: the speculative margin plus how far they can close within `dt` — their
/// relative speed and each one's rotation reach `|ω|·r` (m/s, [`rotation_reach`]).
#[inline]
pub(crate) fn prediction_distance(
    (v1, v2): (Vec3, Vec3),
    (reach1, reach2): (f32, f32),
    speculative_margin: f32,
    dt: f32,
) -> f32 {
    let closing = (v1 - v2).length() + reach1 + reach2;
    (speculative_margin + closing * dt).min(MAX_PREDICTION)
}

/// Whether two balls of world centres `center1`, `center2` and radii `r1`, `r2` (m) are farther apart than
/// `prediction` plus [`BALL_SKIP_MARGIN`]: their centres' world distance, without composing the poses that
/// the ball–ball generator needs. Most overlapping boxes of a pile of balls hold balls this far apart; the
/// broad phase drops them before they become candidates.
#[inline]
pub(crate) fn centres_clearly_apart(
    (center1, r1): (Vec3, f32),
    (center2, r2): (Vec3, f32),
    prediction: f32,
) -> bool {
    let reach = r1 + r2 + prediction + BALL_SKIP_MARGIN;
    center1.distance_squared(center2) > reach * reach
}

/// The world position of the centre of ball collider `c` on body `b`: the body's origin for a ball at it (the
/// common case: no rotation to apply), else the collider's offset carried by the body's pose.
#[inline]
pub(crate) fn ball_center(c: &Collider, b: &RigidBody) -> Vec3 {
    ball_center_at(c, b.pose())
}

/// [`ball_center`] for a body at `body_pose`.
#[inline]
pub(crate) fn ball_center_at(c: &Collider, body_pose: Pose) -> Vec3 {
    let offset = c.desc.local_pose.position;
    if offset == Vec3::ZERO {
        body_pose.position
    } else {
        body_pose.transform_point(offset)
    }
}

/// A body that turns by more than this (rad) in a step is swept: 30°, beyond which the start-of-step
/// linearisation of a contact is off by more than 1 − cos 30° ≈ 13 % of the lever arm.
pub(crate) const SWEPT_TURN: f32 = 0.52;

/// Whether `body` (awake, dynamic) turns by more than [`SWEPT_TURN`] in `dt` at its angular velocity, and
/// turning it moves `collider` — which a ball centred on the body's centre of mass it does not. The broad
/// phase lists such bodies, with their start poses, as it fattens their boxes.
#[inline]
pub(crate) fn is_swept(collider: &Collider, body: &RigidBody, dt: f32) -> bool {
    let turn = body.angular_velocity().length_squared() * dt * dt;
    turn > SWEPT_TURN * SWEPT_TURN
        && body.is_dynamic()
        && !(matches!(collider.desc.shape, ColliderShape::Ball { .. })
            && collider.desc.local_pose.position == body.mass_properties().local_center_of_mass())
}
