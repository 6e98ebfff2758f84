//! A motor driving a joint's relative rotation to a target orientation ([`OrientationMotor`]), for
//! animation-driven ragdolls: a soft 3-DOF angular spring toward the target with a bounded torque. Stage
//! *solve* (bias pass only: it is a spring, and the relax pass leaves springs alone).
//!
//! ```text
//! C = 2·sign(w)·xyz of F_b·(F_a·q_target)⁻¹            (rad, world; see crate::part::rotation_error)
//! Ċ ≈ ω_b − ω_a,   K = I_a⁻¹ + I_b⁻¹
//! ΔL = −mass_scale·K⁻¹·(Ċ + bias_rate·C) − impulse_scale·L,   |L| ≤ τ_max·h
//! ```

use crate::error::{ConstraintError, check_non_negative_or_infinite};
use crate::pair::BodyPair;
use crate::part::{RotationPart, inverse3_or_zero, rotation_error};
use crate::soft_spring::SoftSpring;
use crate::stage::Stage;
use rebound_dynamics::{Bias, Softness, SolverBody, StepContext};
use rebound_math::validity::check_rotation;
use rebound_math::{Mat3, Quat, Vec3};

/// Drives the rotation of B's joint frame relative to A's (`F_a⁻¹·F_b`) to `target` with a soft spring and
/// at most `max_torque`.
///
/// # Examples
///
/// ```
/// use rebound_constraints::{OrientationMotor, SoftSpring};
/// use rebound_math::Quat;
/// let pose = OrientationMotor::new(Quat::from_rotation_z(0.5), SoftSpring::frequency(4.0, 1.0)?, 200.0)?;
/// assert_eq!(pose.max_torque(), 200.0);
/// assert!(OrientationMotor::new(Quat::from_xyzw(0.0, 0.0, 0.0, 2.0), SoftSpring::default(), 1.0).is_err());
/// # Ok::<(), rebound_constraints::ConstraintError>(())
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct OrientationMotor {
    target: Quat,
    spring: SoftSpring,
    #[cfg_attr(
        feature = "serde",
        serde(
            with = "crate::bounds::unbounded",
            default = "crate::bounds::unbounded::infinity"
        )
    )]
    max_torque: f32,
}

impl OrientationMotor {
    /// A motor toward the relative rotation `target` (unit quaternion, A's joint frame to B's), with the
    /// spring `spring` (Hz/ζ, or N·m/rad and N·m·s/rad) and at most `max_torque` (N·m, ≥ 0; +∞ = unbounded).
    ///
    /// # Errors
    /// A non-unit or non-finite `target`; an invalid `spring`; a negative or NaN `max_torque`.
    pub fn new(target: Quat, spring: SoftSpring, max_torque: f32) -> Result<Self, ConstraintError> {
        let target = check_rotation("target", target)?.normalize();
        Ok(Self {
            target,
            spring: spring.validated()?,
            max_torque: check_non_negative_or_infinite("max_torque", max_torque)?,
        })
    }

    /// The target relative rotation.
    #[must_use]
    pub fn target(&self) -> Quat {
        self.target
    }

    /// The spring.
    #[must_use]
    pub fn spring(&self) -> SoftSpring {
        self.spring
    }

    /// The largest torque the motor applies (N·m).
    #[must_use]
    pub fn max_torque(&self) -> f32 {
        self.max_torque
    }

    /// Changes the target (an animation's pose for this frame); nothing changes on error.
    ///
    /// # Errors
    /// A non-unit or non-finite `target`.
    pub fn set_target(&mut self, target: Quat) -> Result<(), ConstraintError> {
        self.target = check_rotation("target", target)?.normalize();
        Ok(())
    }

    /// Returns `self` if every field is valid (for deserialized values).
    ///
    /// # Errors
    /// As [`OrientationMotor::new`].
    pub fn validated(self) -> Result<Self, ConstraintError> {
        Self::new(self.target, self.spring, self.max_torque)
    }

    pub(crate) fn prepare(&self, pair: &BodyPair, ctx: &StepContext) -> PreparedMotor {
        PreparedMotor {
            motor: *self,
            softness: self.spring.softness(0.0, ctx.h),
            effective_mass: inverse3_or_zero(&(pair.inv_inertia_a + pair.inv_inertia_b)),
        }
    }
}

/// An orientation motor ready for the substeps.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct PreparedMotor {
    motor: OrientationMotor,
    /// The spring's coefficients in frequency form.
    softness: Softness,
    /// `K⁻¹` (kg·m²).
    effective_mass: Mat3,
}

impl PreparedMotor {
    /// One pass of the motor's block at the frames `(fa, fb)` (world), accumulating into `accumulated`
    /// (N·m·s, world).
    pub(crate) fn solve(
        &self,
        pair: &BodyPair,
        (fa, fb): (Quat, Quat),
        accumulated: &mut Vec3,
        a: &mut SolverBody,
        b: &mut SolverBody,
        stage: &Stage,
    ) {
        if stage.bias == Bias::Off {
            return;
        }
        let c = rotation_error(fa * self.motor.target, fb);
        let s = if self.motor.spring.depends_on_mass() {
            // The stiffness form needs a scalar mass: the block's along the error.
            let along = c.normalize_or(Vec3::X);
            let k = along.dot((pair.inv_inertia_a + pair.inv_inertia_b) * along);
            let mass = if k > f32::MIN_POSITIVE {
                k.recip()
            } else {
                0.0
            };
            self.motor.spring.softness(mass, stage.h)
        } else {
            self.softness
        };
        let velocity = RotationPart::velocity(a, b);
        let delta = -s.mass_scale * (self.effective_mass * (velocity + s.bias_rate * c))
            - s.impulse_scale * *accumulated;
        let new = (*accumulated + delta).clamp_length_max(self.motor.max_torque * stage.h);
        let applied = new - *accumulated;
        *accumulated = new;
        RotationPart::apply(pair, a, b, applied);
    }
}
