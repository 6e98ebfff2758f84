//! The wheel joint (course item 6): a wheel (body B) on a chassis (body A) — a suspension spring along one
//! axis of the chassis, a free axle, and an optional drive motor and suspension travel limits (Box2D's wheel
//! joint in 3D). Stages: *prepare*, *warm start*, *solve* and *relax*.

use crate::coordinate::{Coordinate, CoordinateRows};
use crate::error::ConstraintError;
use crate::limits::Limits;
use crate::motor::Motor;
use crate::pair::BodyPair;
use crate::part::{AlignPart, AnglePart, AxisPart, Row, RowTarget};
use crate::prismatic::SlideGeometry;
use crate::soft_spring::{JointSpring, SoftSpring};
use crate::stage::Stage;
use crate::state::JointState;
use rebound_dynamics::SolverBody;

rebound_math::checked_serde! { "WheelJoint", WheelJoint::validated;
/// A wheel joint.
///
/// A's joint frame: X = the axle, Y = the suspension direction (from the wheel towards the chassis, usually
/// up), Z = X × Y. B's joint frame: X = the wheel's spin axis. The suspension is relaxed where the anchors
/// coincide (`x = 0`); under a load `m·g` it settles at `x = −m·g/k` (tested). With `d = p_b − p_a`:
///
/// ```text
/// across:     C = t·d = 0, t = F_a·x̂, F_a·ẑ (2 rows), lever r_a + d     see crate::prismatic
/// axle:       C = (a·b₁, a·b₂) = 0, a = F_a·x̂, bᵢ = F_b·ŷ, F_b·ẑ         see crate::part::AlignPart
/// suspension: x = s·d, s = F_a·ŷ: soft spring to x = 0 (its own SoftSpring), limits x_min ≤ x ≤ x_max
/// drive:      Ċ = a·(ω_b − ω_a) → ω_target, |λ| ≤ τ_max·h                  see crate::part::AnglePart
/// ```
///
/// The suspension spring acts in *apply forces*, before the passes; row order in them: suspension limits,
/// drive, axle, across.
///
/// # Examples
///
/// ```
/// use rebound_constraints::{Limits, Motor, SoftSpring, WheelJoint};
/// let wheel = WheelJoint::new(SoftSpring::stiffness(2.0e4, 1.0e3)?)?
///     .with_suspension_limits(Limits::new(-0.2, 0.1)?)
///     .with_motor(Motor::new(10.0, 400.0)?);
/// assert!(wheel.motor().is_some());
/// # Ok::<(), rebound_constraints::ConstraintError>(())
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize))]
pub struct WheelJoint {
    suspension: SoftSpring,
    suspension_limits: Option<Limits>,
    motor: Option<Motor>,
}
}

impl Default for WheelJoint {
    /// A 5 Hz, ζ = 0.7 suspension, no limits, no motor.
    fn default() -> Self {
        Self {
            suspension: SoftSpring::default(),
            suspension_limits: None,
            motor: None,
        }
    }
}

impl WheelJoint {
    /// A wheel with the suspension stiffness `suspension` (Hz/ζ, or N/m and N·s/m).
    ///
    /// # Errors
    /// An invalid `suspension` (see [`SoftSpring::validated`]).
    pub fn new(suspension: SoftSpring) -> Result<Self, ConstraintError> {
        Ok(Self {
            suspension: suspension.validated()?,
            suspension_limits: None,
            motor: None,
        })
    }

    /// Limits the suspension travel `x` to `[lower, upper]` (m along the suspension direction: positive = the
    /// wheel pushed towards the chassis, negative = hanging out).
    #[must_use]
    pub const fn with_suspension_limits(mut self, limits: Limits) -> Self {
        self.suspension_limits = Some(limits);
        self
    }

    /// Adds a drive motor about the axle (target rad/s, max torque N·m).
    #[must_use]
    pub const fn with_motor(mut self, motor: Motor) -> Self {
        self.motor = Some(motor);
        self
    }

    /// Returns `self` if its suspension, limits and motor pass the checks of their constructors (for values
    /// that bypassed them: deserialised).
    ///
    /// # Errors
    /// The first invalid field.
    pub fn validated(self) -> Result<Self, ConstraintError> {
        self.suspension.validated()?;
        self.suspension_limits.map(Limits::validated).transpose()?;
        self.motor.map(Motor::validated).transpose()?;
        Ok(self)
    }

    /// The suspension stiffness.
    #[must_use]
    pub fn suspension(&self) -> SoftSpring {
        self.suspension
    }

    /// The suspension travel limits (m), if any.
    #[must_use]
    pub fn suspension_limits(&self) -> Option<Limits> {
        self.suspension_limits
    }

    /// The drive motor, if any.
    #[must_use]
    pub fn motor(&self) -> Option<Motor> {
        self.motor
    }

    /// Changes the suspension stiffness; nothing changes on error.
    ///
    /// # Errors
    /// An invalid `suspension`.
    pub fn set_suspension(&mut self, suspension: SoftSpring) -> Result<(), ConstraintError> {
        self.suspension = suspension.validated()?;
        Ok(())
    }

    /// Sets or removes the suspension travel limits.
    pub fn set_suspension_limits(&mut self, limits: Option<Limits>) {
        self.suspension_limits = limits;
    }

    /// Sets or removes the drive motor.
    pub fn set_motor(&mut self, motor: Option<Motor>) {
        self.motor = motor;
    }

    pub(crate) fn prepare(&self, state: &mut JointState) -> PreparedWheel {
        let suspension = CoordinateRows {
            spring: Some(JointSpring::relaxed_at_zero(self.suspension)),
            motor: None,
            limits: self.suspension_limits,
        };
        suspension.clear_unused(state);
        if self.motor.is_none() {
            state.motor_impulse = 0.0;
        }
        state.linear_impulse.z = 0.0;
        state.angular_impulse.z = 0.0;
        PreparedWheel {
            suspension,
            motor: self.motor,
        }
    }
}

/// The rows of A's frame across the suspension: the axle (X) and Z.
const ACROSS: [usize; 2] = [0, 2];

/// A wheel ready for the substeps.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct PreparedWheel {
    /// Suspension spring and limits (its motor slot unused: the drive is angular).
    suspension: CoordinateRows,
    motor: Option<Motor>,
}

impl Coordinate for PreparedWheel {
    type Part = AxisPart;

    fn rows(&self) -> &CoordinateRows {
        &self.suspension
    }

    /// The row along A's frame Y axis (the suspension) and the travel along it.
    #[inline]
    fn coordinate(&self, pair: &BodyPair, a: &SolverBody, b: &SolverBody) -> (AxisPart, f32) {
        SlideGeometry::new(pair, a, b).coordinate(pair, 1)
    }
}

impl PreparedWheel {
    pub(crate) fn warm_start(
        pair: &BodyPair,
        state: &JointState,
        a: &mut SolverBody,
        b: &mut SolverBody,
    ) {
        let g = SlideGeometry::new(pair, a, b);
        // The suspension spring's impulse is its whole substep, applied afresh in *apply forces*.
        let suspension = state.lower_impulse + state.upper_impulse;
        g.row(pair, 1).apply(pair, a, b, suspension);
        let axle = g.axes[0];
        AnglePart::new(pair, axle).apply(a, b, state.motor_impulse);
        AlignPart::apply_about(
            pair,
            axle,
            AlignPart::perpendiculars(g.frame_b),
            a,
            b,
            state.angular_impulse.truncate(),
        );
        g.warm_start_across(pair, ACROSS, state, a, b);
    }

    pub(crate) fn solve(
        &self,
        pair: &BodyPair,
        state: &mut JointState,
        a: &mut SolverBody,
        b: &mut SolverBody,
        stage: &Stage,
    ) {
        let g = SlideGeometry::new(pair, a, b);
        let (travel, x) = g.coordinate(pair, 1);
        self.suspension.solve(&travel, pair, x, state, a, b, stage);
        let axle = g.axes[0];
        if let Some(motor) = self.motor {
            let max = motor.max_force() * stage.h;
            AnglePart::new(pair, axle).solve_clamped(
                pair,
                a,
                b,
                RowTarget::speed(motor.target_speed()),
                &mut state.motor_impulse,
                -max,
                max,
            );
        }
        let align = AlignPart::new(pair, axle, AlignPart::perpendiculars(g.frame_b));
        let mut lambda = state.angular_impulse.truncate();
        align.solve(a, b, stage.bias, stage.joint_softness, &mut lambda);
        state.angular_impulse = lambda.extend(0.0);
        g.solve_across(pair, ACROSS, state, a, b, stage);
    }
}
