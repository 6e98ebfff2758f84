//! The free coordinate of a hinge (angle), prismatic joint (slide) or wheel (suspension travel, drive): its
//! optional spring, motor and limit rows, solved on one [`Row`] — an [`crate::part::AnglePart`] or an
//! [`crate::part::AxisPart`]. Stage *solve* (the spring in the bias pass only) and *relax*.
//!
//! ```text
//! spring:  C = x − x_target, soft (its own SoftSpring), λ unclamped            → JointState::axial_impulse
//! motor:   Ċ → v_target, rigid, |λ| ≤ F_max·h                                  → JointState::motor_impulse
//! lower:   C = x − x_min ≥ 0, speculative inside, joint softness outside, λ ≥ 0 → JointState::lower_impulse
//! upper:   C = x − x_max ≤ 0, likewise, λ ≤ 0                                   → JointState::upper_impulse
//! ```

use crate::limits::Limits;
use crate::motor::Motor;
use crate::pair::BodyPair;
use crate::part::{Row, RowTarget};
use crate::soft_spring::JointSpring;
use crate::stage::Stage;
use crate::state::JointState;
use rebound_dynamics::{Bias, Softness, SolverBody};

/// The optional rows of a joint coordinate.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct CoordinateRows {
    pub spring: Option<JointSpring>,
    /// The spring's coefficients in frequency form (the stiffness form is computed per iteration).
    pub spring_softness: Softness,
    pub motor: Option<Motor>,
    pub limits: Option<Limits>,
}

impl CoordinateRows {
    /// The accumulated impulse of all these rows (they share one direction), for warm starting.
    #[inline]
    pub(crate) fn accumulated(state: &JointState) -> f32 {
        state.axial_impulse + state.motor_impulse + state.lower_impulse + state.upper_impulse
    }

    /// Zeroes the impulses of rows that are absent (so a removed motor is not warm-started).
    pub(crate) fn clear_unused(&self, state: &mut JointState) {
        if self.spring.is_none() {
            state.axial_impulse = 0.0;
        }
        if self.motor.is_none() {
            state.motor_impulse = 0.0;
        }
        if self.limits.is_none() {
            state.lower_impulse = 0.0;
            state.upper_impulse = 0.0;
        }
    }

    /// Whether a pass of stage `bias` has nothing to solve: no limits, no motor, and no spring (or the relax
    /// pass, where springs rest). Then the caller need not measure the coordinate at all.
    #[inline]
    pub(crate) fn is_idle(&self, bias: Bias) -> bool {
        self.limits.is_none()
            && self.motor.is_none()
            && (self.spring.is_none() || bias == Bias::Off)
    }

    /// One pass over the rows, at the coordinate value `position` (m or rad).
    pub(crate) fn solve<R: Row>(
        &self,
        row: &R,
        pair: &BodyPair,
        position: f32,
        state: &mut JointState,
        a: &mut SolverBody,
        b: &mut SolverBody,
        stage: &Stage,
    ) {
        if let (Some(spring), Bias::On) = (self.spring, stage.bias) {
            let softness = spring.spring().softness_in_iteration(
                self.spring_softness,
                row.effective_mass(),
                stage.h,
            );
            let target = RowTarget::spring(position - spring.target(), softness);
            row.solve_clamped(
                pair,
                a,
                b,
                target,
                &mut state.axial_impulse,
                f32::NEG_INFINITY,
                f32::INFINITY,
            );
        }
        if let Some(motor) = self.motor {
            let max = motor.max_force() * stage.h;
            let target = RowTarget::speed(motor.target_speed());
            row.solve_clamped(pair, a, b, target, &mut state.motor_impulse, -max, max);
        }
        if let Some(limits) = self.limits {
            let lower = RowTarget::lower_limit(
                position - limits.lower(),
                stage.bias,
                stage.joint_softness,
                stage.inv_h,
            );
            row.solve_clamped(
                pair,
                a,
                b,
                lower,
                &mut state.lower_impulse,
                0.0,
                f32::INFINITY,
            );
            let upper = RowTarget::upper_limit(
                position - limits.upper(),
                stage.bias,
                stage.joint_softness,
                stage.inv_h,
            );
            row.solve_clamped(
                pair,
                a,
                b,
                upper,
                &mut state.upper_impulse,
                f32::NEG_INFINITY,
                0.0,
            );
        }
    }
}
