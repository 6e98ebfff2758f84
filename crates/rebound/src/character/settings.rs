//! `CharacterSettings`: how the character controller moves a shape (skin, slope limit, autostep, snapping,
//! pushing, iterations), checked once when a [`super::CharacterController`] is made. Not a step stage.

use rebound_math::Vec3;
use rebound_math::validity::is_unit_vec3;

/// The largest number of slide iterations a move may take: each one is a shape cast against the scene.
pub const MAX_SLIDE_ITERATIONS: u32 = 64;

/// Climbing steps: when the character, standing on walkable ground, runs into something it cannot walk up,
/// it tries to go over it by rising at most `max_height`, moving on, and landing on walkable ground at least
/// `min_width` deep.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Autostep {
    /// The highest step climbed (m, > 0), measured from the ground under the character to the step's top.
    /// Default: 0.25.
    pub max_height: f32,
    /// How deep the top of a step must be, walkable, beyond the edge the character lands on (m, > 0): a
    /// thinner ledge (a low wall, a fence top) is not a step. Default: 0.1.
    pub min_width: f32,
    /// Whether the character steps onto dynamic bodies (crates) too. Default: false (it pushes them instead).
    pub include_dynamic_bodies: bool,
}

impl Default for Autostep {
    fn default() -> Self {
        Self {
            max_height: 0.25,
            min_width: 0.1,
            include_dynamic_bodies: false,
        }
    }
}

/// How hard the character pushes the dynamic bodies it runs into ([`super::CharacterController::push_bodies`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Push {
    /// Bodies heavier than this are not pushed (kg, ≥ 0; +∞ pushes every dynamic body): the character stops
    /// against them as against a wall. Default: 100.
    pub max_mass: f32,
    /// The largest impulse given to one body in one move (N·s, ≥ 0; +∞ for no limit). Default: +∞.
    pub max_impulse: f32,
}

impl Default for Push {
    fn default() -> Self {
        Self {
            max_mass: 100.0,
            max_impulse: f32::INFINITY,
        }
    }
}

/// What a character controller does. Every field states its unit and default; [`CharacterSettings::validate`]
/// lists what is refused.
///
/// ```
/// use rebound::prelude::*;
///
/// let settings = CharacterSettings {
///     max_slope_angle: 40f32.to_radians(),
///     autostep: Some(Autostep { max_height: 0.35, ..Autostep::default() }),
///     ..CharacterSettings::default()
/// };
/// let controller = CharacterController::new(settings)?;
/// assert!((controller.settings().skin - 0.01).abs() < 1e-6);
/// # Ok::<(), rebound::Error>(())
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CharacterSettings {
    /// The world's up direction (unit vector): slopes are measured from it, steps rise along it and snapping
    /// goes against it. Default: +Y.
    pub up: Vec3,
    /// The gap kept between the shape and every surface (m, > 0): casts stop this far from what they hit, so
    /// the next cast does not start in contact. Default: 0.01.
    pub skin: f32,
    /// The steepest slope walked up, between the ground normal and `up` (rad, in (0, π/2)). A steeper
    /// surface is a wall: horizontal motion into it stops and downward motion slides down it. Default: 45°
    /// (π/4).
    pub max_slope_angle: f32,
    /// Climbing steps; `None` turns it off. Default: `Some(Autostep::default())` (0.25 m high, 0.1 m deep).
    pub autostep: Option<Autostep>,
    /// Keeps a grounded character on the ground when the ground drops away by at most this much in one move
    /// (m, > 0), e.g. walking down a slope or a step; `None` turns it off. Not done while the desired motion
    /// rises (a jump). Default: `Some(0.2)`.
    pub snap_to_ground: Option<f32>,
    /// Pushing dynamic bodies; `None` turns it off (they are walls). Default: `Some(Push::default())`.
    pub push: Option<Push>,
    /// Whether the character moves with the body it stands on (a moving platform): the ground's velocity at
    /// the contact point times the move's `dt` is added to the move. Default: true.
    pub carry_with_ground: bool,
    /// The most shape casts of the slide (1 to [`MAX_SLIDE_ITERATIONS`]): each hit uses one, and motion left
    /// after the last is dropped. Default: 8.
    pub max_iterations: u32,
}

impl Default for CharacterSettings {
    fn default() -> Self {
        Self {
            up: Vec3::Y,
            skin: 0.01,
            max_slope_angle: core::f32::consts::FRAC_PI_4,
            autostep: Some(Autostep::default()),
            snap_to_ground: Some(0.2),
            push: Some(Push::default()),
            carry_with_ground: true,
            max_iterations: 8,
        }
    }
}

/// A character setting or move argument that cannot be used; the message names the field and the value.
#[derive(Debug, Clone, Copy, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum CharacterError {
    /// A length or mass was NaN, infinite where it must be finite, zero or negative.
    #[error("`{field}` must be a finite number > 0, got {value}")]
    NotPositive {
        /// The field, e.g. `"skin"` or `"autostep.max_height"`.
        field: &'static str,
        /// The value given.
        value: f32,
    },
    /// A limit was NaN or negative.
    #[error("`{field}` must be >= 0 (+∞ allowed), got {value}")]
    Negative {
        /// The field.
        field: &'static str,
        /// The value given.
        value: f32,
    },
    /// The slope angle was outside the open interval (0, π/2).
    #[error("`max_slope_angle` must lie strictly between 0 and π/2 rad (90°), got {value} rad")]
    SlopeAngle {
        /// The value given (rad).
        value: f32,
    },
    /// `up` was not a unit vector.
    #[error("`up` must be a unit vector, got {value}")]
    Up {
        /// The value given.
        value: Vec3,
    },
    /// The shape to move is not convex (a mesh, a height field or a compound): casts need a convex shape.
    #[error("the character's shape must be convex, got a {kind}")]
    NonConvexShape {
        /// The shape's kind.
        kind: &'static str,
    },
    /// The desired translation of a move is longer than [`crate::MAX_SHAPE_COORDINATE`] (m).
    #[error("`desired_translation` must be at most {max} m long, got {value}")]
    TooLong {
        /// The translation given (m).
        value: Vec3,
        /// The longest accepted (m).
        max: f32,
    },
    /// `max_iterations` was 0 or above [`MAX_SLIDE_ITERATIONS`].
    #[error("`max_iterations` must lie in 1..={max}, got {value}")]
    Iterations {
        /// The value given.
        value: u32,
        /// The largest accepted value.
        max: u32,
    },
}

fn positive(field: &'static str, value: f32) -> Result<(), CharacterError> {
    if value.is_finite() && value > 0.0 {
        Ok(())
    } else {
        Err(CharacterError::NotPositive { field, value })
    }
}

impl CharacterSettings {
    /// Checks every field.
    ///
    /// # Errors
    /// The first bad field, in declaration order: `up` not unit; `skin` not finite and > 0; `max_slope_angle`
    /// outside (0, π/2); `autostep.max_height` or `autostep.min_width` not finite and > 0; `snap_to_ground`
    /// not finite and > 0; `push.max_mass` or `push.max_impulse` NaN or negative;
    /// `max_iterations` outside 1..=[`MAX_SLIDE_ITERATIONS`].
    pub fn validate(&self) -> Result<(), CharacterError> {
        if !is_unit_vec3(self.up) {
            return Err(CharacterError::Up { value: self.up });
        }
        positive("skin", self.skin)?;
        let angle = self.max_slope_angle;
        if !(angle > 0.0 && angle < core::f32::consts::FRAC_PI_2) {
            return Err(CharacterError::SlopeAngle { value: angle });
        }
        if let Some(step) = self.autostep {
            positive("autostep.max_height", step.max_height)?;
            positive("autostep.min_width", step.min_width)?;
        }
        if let Some(distance) = self.snap_to_ground {
            positive("snap_to_ground", distance)?;
        }
        if let Some(push) = self.push {
            if push.max_mass.is_nan() || push.max_mass < 0.0 {
                return Err(CharacterError::Negative {
                    field: "push.max_mass",
                    value: push.max_mass,
                });
            }
            if push.max_impulse.is_nan() || push.max_impulse < 0.0 {
                return Err(CharacterError::Negative {
                    field: "push.max_impulse",
                    value: push.max_impulse,
                });
            }
        }
        if self.max_iterations == 0 || self.max_iterations > MAX_SLIDE_ITERATIONS {
            return Err(CharacterError::Iterations {
                value: self.max_iterations,
                max: MAX_SLIDE_ITERATIONS,
            });
        }
        Ok(())
    }

    /// `cos(max_slope_angle)`: a surface whose normal `n` has `n·up` at least this is walkable.
    pub(crate) fn min_walkable_cos(&self) -> f32 {
        rebound_math::real::cos(self.max_slope_angle)
    }
}
