//! `StepLimits`: the physical bounds beyond which a body is quarantined (taken out of the step, see
//! `quarantine.rs`), `QuarantineReason` (which bound a body passed) and the caps on the work one step does.
//! Part of [`crate::WorldSettings`].

use crate::WorldError;
use rebound_math::validity::check_positive;

/// The largest physical bound accepted (in its unit): its square stays finite in `f32`.
pub const MAX_BOUND: f32 = 1.0e15;

/// The bounds a step holds to. Public fields with [`Default`]; checked with the rest of the settings.
///
/// **Physical bounds.** A moving (dynamic or kinematic) body whose speed, angular speed or distance from the
/// origin along any axis exceeds these — at the start of a step, or in the solver's result — or whose state
/// is not finite, is *quarantined*: taken out of the step, its velocities zeroed, its contacts and joint
/// impulses cleared, reported by [`crate::Event::BodyQuarantined`] and
/// [`crate::StepReport::quarantined_body_count`]; the other bodies step as if it were not there. The
/// defaults are far beyond anything a game scene does and well inside where `f32` arithmetic stays finite:
/// at 10⁶ m a position is still resolved to 6 cm, and the products the solver forms of speeds, masses and
/// inverse step lengths stay below 10³⁸.
///
/// **Work caps.** The collision backend keeps at most `max_candidate_pairs` candidate pairs (the lowest by
/// collider handle, so the choice does not depend on the broad phase's history) and the world at most
/// `max_contact_points` contact points (whole manifolds in pair order); what is left out is counted in the
/// step report. They bound a step's memory whatever the scene: 10,000 balls created at one point make 50
/// million overlapping pairs.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[cfg_attr(feature = "serde", serde(default))]
pub struct StepLimits {
    /// The fastest a body may move (m/s). Default: 10⁴ m/s.
    pub max_speed: f32,
    /// The fastest a body may spin (rad/s). Default: 10⁴ rad/s.
    pub max_angular_speed: f32,
    /// The farthest a body's position may be from the origin along any axis (m). Default: 10⁶ m.
    pub max_position: f32,
    /// The most candidate pairs the broad phase hands the narrow phase in one step. Default: 131,072
    /// (2¹⁷; the 4,096-ball peer scene has about 20,000, a pile of 16,384 balls about 100,000).
    pub max_candidate_pairs: u32,
    /// The most contact points the solver receives in one step. Default: 524,288 (2¹⁹: four points for
    /// each of the most candidate pairs).
    pub max_contact_points: u32,
}

impl Default for StepLimits {
    fn default() -> Self {
        Self {
            max_speed: 1.0e4,
            max_angular_speed: 1.0e4,
            max_position: 1.0e6,
            max_candidate_pairs: 1 << 17,
            max_contact_points: 1 << 19,
        }
    }
}

impl StepLimits {
    /// Checks every field.
    ///
    /// # Errors
    /// A [`WorldError`] naming the first field that is not a positive finite number at most [`MAX_BOUND`],
    /// or a zero cap.
    pub fn validate(&self) -> Result<(), WorldError> {
        for (field, bound) in [
            ("limits.max_speed", self.max_speed),
            ("limits.max_angular_speed", self.max_angular_speed),
            ("limits.max_position", self.max_position),
        ] {
            check_positive(field, bound)?;
            if bound > MAX_BOUND {
                return Err(WorldError::InvalidSetting {
                    field,
                    value: bound,
                });
            }
        }
        for (field, cap) in [
            ("limits.max_candidate_pairs", self.max_candidate_pairs),
            ("limits.max_contact_points", self.max_contact_points),
        ] {
            if cap == 0 {
                return Err(WorldError::InvalidSetting { field, value: 0.0 });
            }
        }
        Ok(())
    }
}

/// Why a body was quarantined.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub enum QuarantineReason {
    /// Its speed exceeded [`StepLimits::max_speed`].
    Speed,
    /// Its angular speed exceeded [`StepLimits::max_angular_speed`].
    AngularSpeed,
    /// Its position exceeded [`StepLimits::max_position`] along an axis.
    Position,
    /// The solver's result for it was not finite.
    NotFinite,
}
