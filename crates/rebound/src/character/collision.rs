//! What a move reports: the corrected translation, the ground, and every surface the shape ran into on the
//! way ([`CharacterCollision`]), in the order it met them.

use super::Ground;
use crate::ColliderHandle;
use rebound_math::Vec3;
use rebound_world::BodyHandle;

/// One surface the shape ran into during a move.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CharacterCollision {
    /// The collider hit.
    pub collider: ColliderHandle,
    /// Its body.
    pub body: BodyHandle,
    /// The contact point on the collider (m, world space).
    pub point: Vec3,
    /// The collider's outward unit normal there (world space; it points at the character).
    pub normal: Vec3,
    /// How far the shape had moved in this move when it touched (m, world space).
    pub translation_before: Vec3,
    /// The motion still wanted at that moment, before it was turned along the surface (m, world space).
    pub translation_remaining: Vec3,
}

/// The result of [`super::CharacterController::move_shape`]: add `translation` to the shape's (or its
/// body's) position.
#[derive(Debug, Clone, PartialEq)]
pub struct CharacterMove {
    /// The corrected translation (m, world space): the desired one slid along walls and slopes, stepped,
    /// snapped, plus the ground's motion when carried.
    pub translation: Vec3,
    /// The translation asked for (m).
    pub desired_translation: Vec3,
    /// The time the move stands for (s): a moving ground's velocity is carried over it, and pushes aim at the
    /// desired velocity `desired_translation / dt`.
    pub dt: f32,
    /// The walkable ground under the shape at the end of the move, if any.
    pub ground: Option<Ground>,
    /// Whether the move climbed a step.
    pub stepped: bool,
    /// Whether the move was pulled down onto the ground ([`super::CharacterSettings::snap_to_ground`]).
    pub snapped: bool,
    /// The part of `translation` that is the ground's motion (m): zero unless carried by a moving body.
    pub carried: Vec3,
    /// The surfaces hit, in order.
    pub collisions: Vec<CharacterCollision>,
}

impl CharacterMove {
    /// Whether the shape ends the move on walkable ground.
    #[must_use]
    pub fn is_grounded(&self) -> bool {
        self.ground.is_some()
    }

    /// The velocity the move asked for (m/s): `desired_translation / dt`.
    #[must_use]
    pub fn desired_velocity(&self) -> Vec3 {
        self.desired_translation / self.dt
    }
}
