//! The free coordinate of a hinge (angle), prismatic joint (slide) or wheel (suspension travel, drive): its
//! optional spring, motor and limit rows, solved on one [`Row`] — an [`crate::part::AnglePart`] or an
//! [`crate::part::AxisPart`]. The spring in stage *apply forces* (its whole substep, the distance spring's
//! [`crate::OscillatorStep`]: no numerical damping); motor and limits in *solve* and *relax*.
//!
//! ```text
//! spring:  C = x − x_target, λ = m_eff·((α − 1)·Ċ + β·C) once per substep       → JointState::axial_impulse
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
use rebound_dynamics::SolverBody;

/// A joint whose free coordinate carries [`CoordinateRows`] — a hinge's angle, a prismatic joint's slide, a
/// wheel's suspension travel: its rows, and the row and value of the coordinate at a pose. Stage *apply
/// forces* of the coordinate's spring is written once, here ([`Coordinate::apply_spring`]).
pub(crate) trait Coordinate {
    /// The row the coordinate moves along (an [`crate::part::AnglePart`] or an [`crate::part::AxisPart`]).
    type Part: Row;

    /// The joint's coordinate rows.
    fn rows(&self) -> &CoordinateRows;

    /// The coordinate's row and its value (m or rad) at the pose of `a`, `b`.
    fn coordinate(&self, pair: &BodyPair, a: &SolverBody, b: &SolverBody) -> (Self::Part, f32);

    /// Whether the coordinate has a spring ([`Coordinate::apply_spring`] acts).
    #[inline]
    fn has_spring(&self) -> bool {
        self.rows().spring.is_some()
    }

    /// Stage *apply forces*: the coordinate's spring over the substep `h` (s), if any
    /// ([`CoordinateRows::apply_spring`] at the current pose).
    #[inline]
    fn apply_spring(
        &self,
        pair: &BodyPair,
        state: &mut JointState,
        (a, b): (&mut SolverBody, &mut SolverBody),
        h: f32,
    ) {
        let (row, position) = self.coordinate(pair, a, b);
        self.rows()
            .apply_spring(&row, pair, position, state, (a, b), h);
    }
}

/// The optional rows of a joint coordinate.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct CoordinateRows {
    pub spring: Option<JointSpring>,
    pub motor: Option<Motor>,
    pub limits: Option<Limits>,
}

impl CoordinateRows {
    /// The impulse of all these rows in the last substep (they share one direction), for the reaction.
    #[inline]
    pub(crate) fn accumulated(state: &JointState) -> f32 {
        state.axial_impulse + state.motor_impulse + state.lower_impulse + state.upper_impulse
    }

    /// The accumulated impulse of the rows the passes solve (motor and limits), for warm starting: the
    /// spring's impulse is its whole substep, applied afresh in *apply forces*.
    #[inline]
    pub(crate) fn warm_start_impulse(state: &JointState) -> f32 {
        state.motor_impulse + state.lower_impulse + state.upper_impulse
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

    /// Whether the passes have nothing to solve: no limits and no motor (the spring acts in *apply forces*).
    /// Then the caller need not measure the coordinate at all.
    #[inline]
    pub(crate) fn is_idle(&self) -> bool {
        self.limits.is_none() && self.motor.is_none()
    }

    /// Stage *apply forces*: the spring's impulse over the substep `h` (s) at the coordinate value
    /// `position` (m or rad) — the [`crate::OscillatorStep`] of the row's effective mass — applied along
    /// `row` and kept in `state.axial_impulse`; nothing without a spring.
    #[inline]
    pub(crate) fn apply_spring<R: Row>(
        &self,
        row: &R,
        pair: &BodyPair,
        position: f32,
        state: &mut JointState,
        (a, b): (&mut SolverBody, &mut SolverBody),
        h: f32,
    ) {
        let Some(spring) = self.spring else {
            return;
        };
        let effective_mass = row.effective_mass();
        let step = spring.spring().oscillator_step(effective_mass, h);
        let impulse = step.impulse(
            effective_mass,
            row.velocity(a, b),
            position - spring.target(),
        );
        row.apply_impulse(pair, a, b, impulse);
        state.axial_impulse = impulse;
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
