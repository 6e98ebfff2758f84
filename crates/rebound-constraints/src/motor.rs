//! A velocity motor on a joint coordinate: drives the relative speed to a target with a bounded force or
//! torque (Box2D's joint motors). Solved as a rigid row with the accumulated impulse clamped to
//! `±max_force·h` per substep, in both the bias and the relax pass.

use crate::error::ConstraintError;
use crate::error::check_non_negative_or_infinite as check_max_force;
use rebound_math::validity::check_finite;

rebound_math::checked_serde! { "Motor", Motor::validated;
/// A velocity motor.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize))]
pub struct Motor {
    target_speed: f32,
    /// +∞ (unbounded, the usual choice) is written as `null` in JSON.
    #[cfg_attr(
        feature = "serde",
        serde(
            with = "crate::bounds::unbounded",
            default = "crate::bounds::unbounded::infinity"
        )
    )]
    max_force: f32,
}
}

impl Motor {
    /// A motor driving the joint speed to `target_speed` (rad/s for a hinge or wheel, m/s for a prismatic
    /// joint) with at most `max_force` (N·m for a hinge or wheel, N for a prismatic joint; +∞ = unbounded).
    ///
    /// # Errors
    /// A non-finite `target_speed`; a negative or NaN `max_force`.
    pub fn new(target_speed: f32, max_force: f32) -> Result<Self, ConstraintError> {
        check_finite("target_speed", target_speed)?;
        check_max_force("max_force", max_force)?;
        Ok(Self {
            target_speed,
            max_force,
        })
    }

    /// Returns `self` if it passes the checks of [`Motor::new`] (for values that bypassed it: deserialised).
    ///
    /// # Errors
    /// As [`Motor::new`].
    pub fn validated(self) -> Result<Self, ConstraintError> {
        Self::new(self.target_speed, self.max_force)
    }

    /// The target speed (rad/s or m/s).
    #[must_use]
    pub fn target_speed(&self) -> f32 {
        self.target_speed
    }

    /// The largest force or torque the motor applies (N or N·m).
    #[must_use]
    pub fn max_force(&self) -> f32 {
        self.max_force
    }

    /// Changes the target speed; nothing changes on error.
    ///
    /// # Errors
    /// A non-finite `target_speed`.
    pub fn set_target_speed(&mut self, target_speed: f32) -> Result<(), ConstraintError> {
        self.target_speed = check_finite("target_speed", target_speed)?;
        Ok(())
    }

    /// Changes the force or torque cap; nothing changes on error.
    ///
    /// # Errors
    /// A negative or NaN `max_force`.
    pub fn set_max_force(&mut self, max_force: f32) -> Result<(), ConstraintError> {
        self.max_force = check_max_force("max_force", max_force)?;
        Ok(())
    }
}
