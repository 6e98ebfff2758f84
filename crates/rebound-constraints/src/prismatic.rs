//! The prismatic (slider) joint: body B slides along an axis fixed in body A without turning relative to it,
//! with optional limits, a motor and a spring on the slide. Stages: *prepare*, *warm start*, *solve* and
//! *relax*.

use crate::coordinate::{Coordinate, CoordinateRows};
use crate::error::ConstraintError;
use crate::limits::Limits;
use crate::motor::Motor;
use crate::pair::BodyPair;
use crate::part::{AxisPart, RotationPart, Row, RowTarget};
use crate::soft_spring::JointSpring;
use crate::stage::Stage;
use crate::state::JointState;
use rebound_dynamics::SolverBody;
use rebound_math::{Quat, Vec3};

rebound_math::checked_serde! { "PrismaticJoint", PrismaticJoint::validated;
/// A prismatic joint. Free along its axis by default.
///
/// The slide axis is the X axis of A's joint frame; Y and Z of that frame span the locked directions. With
/// `d = p_b − p_a` the anchor separation and `r_a + d = p_b − c_a` the lever arm of A (both bodies pushed at
/// B's anchor, the exact Jacobian of `C = n·d` with `n` turning with A — Box2D's `cross(d + rA, axis)`):
///
/// ```text
/// across:   C = t·d = 0 for t = F_a·ŷ, F_a·ẑ (2 rows)   J = [ −tᵀ  −((r_a + d) × t)ᵀ  tᵀ  (r_b × t)ᵀ ]
/// rotation: C = 2·sign(w)·xyz of F_b·F_a⁻¹ = 0 (3 rows)  see crate::part::RotationPart
/// slide:    x = n·d, n = F_a·x̂                          J = [ −nᵀ  −((r_a + d) × n)ᵀ  nᵀ  (r_b × n)ᵀ ]
///           limits x_min ≤ x ≤ x_max, motor (m/s, max force N), spring to x_target — see crate::coordinate
/// m_eff = 1/(1/m_a + 1/m_b + ((r_a + d) × t)·I_a⁻¹·((r_a + d) × t) + (r_b × t)·I_b⁻¹·(r_b × t))   per row
/// ```
///
/// Softness: the joint softness in the bias pass for the locks and limits; the spring takes its oscillator step.
/// The spring acts in *apply forces*, before the passes; row order in them: motor, limits, rotation, across.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
#[cfg_attr(feature = "serde", derive(serde::Serialize))]
pub struct PrismaticJoint {
    limits: Option<Limits>,
    motor: Option<Motor>,
    spring: Option<JointSpring>,
}
}

impl PrismaticJoint {
    /// A prismatic joint free along its axis.
    #[must_use]
    pub const fn new() -> Self {
        Self {
            limits: None,
            motor: None,
            spring: None,
        }
    }

    /// Limits the slide to `[lower, upper]` (m).
    #[must_use]
    pub const fn with_limits(mut self, limits: Limits) -> Self {
        self.limits = Some(limits);
        self
    }

    /// Adds a motor (target speed m/s, max force N).
    #[must_use]
    pub const fn with_motor(mut self, motor: Motor) -> Self {
        self.motor = Some(motor);
        self
    }

    /// Adds a spring on the slide (target m, stiffness in Hz/ζ or N/m and N·s/m).
    #[must_use]
    pub const fn with_spring(mut self, spring: JointSpring) -> Self {
        self.spring = Some(spring);
        self
    }

    /// Returns `self` if its limits, motor and spring pass the checks of their constructors (for values
    /// that bypassed them: deserialised).
    ///
    /// # Errors
    /// The first invalid field.
    pub fn validated(self) -> Result<Self, ConstraintError> {
        self.limits.map(Limits::validated).transpose()?;
        self.motor.map(Motor::validated).transpose()?;
        self.spring.map(JointSpring::validated).transpose()?;
        Ok(self)
    }

    /// The slide limits (m), if any.
    #[must_use]
    pub fn limits(&self) -> Option<Limits> {
        self.limits
    }

    /// The motor, if any.
    #[must_use]
    pub fn motor(&self) -> Option<Motor> {
        self.motor
    }

    /// The spring, if any.
    #[must_use]
    pub fn spring(&self) -> Option<JointSpring> {
        self.spring
    }

    /// Sets or removes the limits.
    pub fn set_limits(&mut self, limits: Option<Limits>) {
        self.limits = limits;
    }

    /// Sets or removes the motor.
    pub fn set_motor(&mut self, motor: Option<Motor>) {
        self.motor = motor;
    }

    /// Sets or removes the spring.
    pub fn set_spring(&mut self, spring: Option<JointSpring>) {
        self.spring = spring;
    }

    pub(crate) fn prepare(&self, pair: &BodyPair, state: &mut JointState) -> PreparedPrismatic {
        let rows = CoordinateRows {
            spring: self.spring,
            motor: self.motor,
            limits: self.limits,
        };
        rows.clear_unused(state);
        state.linear_impulse.z = 0.0;
        PreparedPrismatic {
            rows,
            rotation: RotationPart::new(pair),
        }
    }
}

/// The current geometry of a slider: A's frame, B's frame, the anchors' separation, the levers and the three
/// directions of A's frame.
pub(crate) struct SlideGeometry {
    pub frame_a: Quat,
    pub frame_b: Quat,
    pub d: Vec3,
    pub lever_a: Vec3,
    pub r_b: Vec3,
    pub axes: [Vec3; 3],
}

impl SlideGeometry {
    #[inline]
    pub(crate) fn new(pair: &BodyPair, a: &SolverBody, b: &SolverBody) -> Self {
        let anchors = pair.anchors(a, b);
        let (frame_a, frame_b) = pair.frames(a, b);
        Self {
            frame_a,
            frame_b,
            d: anchors.d,
            lever_a: anchors.r_a + anchors.d,
            r_b: anchors.r_b,
            axes: [frame_a * Vec3::X, frame_a * Vec3::Y, frame_a * Vec3::Z],
        }
    }

    /// The linear row along A's frame axis `i` (0 = X, 1 = Y, 2 = Z), pushing both bodies at B's anchor.
    #[inline]
    pub(crate) fn row(&self, pair: &BodyPair, i: usize) -> AxisPart {
        AxisPart::new(pair, self.axes[i], self.lever_a, self.r_b)
    }

    /// The row along A's frame axis `i` and the anchors' offset along it (m): a slide's coordinate.
    #[inline]
    pub(crate) fn coordinate(&self, pair: &BodyPair, i: usize) -> (AxisPart, f32) {
        (self.row(pair, i), self.axes[i].dot(self.d))
    }

    /// Solves the two equality rows along A's frame axes `across` (indices), accumulating into
    /// `linear_impulse.x` and `.y`.
    #[inline]
    pub(crate) fn solve_across(
        &self,
        pair: &BodyPair,
        across: [usize; 2],
        state: &mut JointState,
        a: &mut SolverBody,
        b: &mut SolverBody,
        stage: &Stage,
    ) {
        let mut impulses = [state.linear_impulse.x, state.linear_impulse.y];
        for (&i, accumulated) in across.iter().zip(&mut impulses) {
            let c = self.axes[i].dot(self.d);
            let target = RowTarget::equality(c, stage.bias, stage.joint_softness);
            self.row(pair, i).solve_clamped(
                pair,
                a,
                b,
                target,
                accumulated,
                f32::NEG_INFINITY,
                f32::INFINITY,
            );
        }
        state.linear_impulse.x = impulses[0];
        state.linear_impulse.y = impulses[1];
    }

    /// Warm-starts the two rows along A's frame axes `across`.
    #[inline]
    pub(crate) fn warm_start_across(
        &self,
        pair: &BodyPair,
        across: [usize; 2],
        state: &JointState,
        a: &mut SolverBody,
        b: &mut SolverBody,
    ) {
        self.row(pair, across[0])
            .apply(pair, a, b, state.linear_impulse.x);
        self.row(pair, across[1])
            .apply(pair, a, b, state.linear_impulse.y);
    }
}

/// A prismatic joint ready for the substeps.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct PreparedPrismatic {
    rows: CoordinateRows,
    rotation: RotationPart,
}

impl Coordinate for PreparedPrismatic {
    type Part = AxisPart;

    fn rows(&self) -> &CoordinateRows {
        &self.rows
    }

    /// The row along A's frame X axis and the slide along it.
    #[inline]
    fn coordinate(&self, pair: &BodyPair, a: &SolverBody, b: &SolverBody) -> (AxisPart, f32) {
        SlideGeometry::new(pair, a, b).coordinate(pair, 0)
    }
}

impl PreparedPrismatic {
    pub(crate) fn warm_start(
        pair: &BodyPair,
        state: &JointState,
        a: &mut SolverBody,
        b: &mut SolverBody,
    ) {
        let g = SlideGeometry::new(pair, a, b);
        g.row(pair, 0)
            .apply(pair, a, b, CoordinateRows::warm_start_impulse(state));
        RotationPart::apply(pair, a, b, state.angular_impulse);
        g.warm_start_across(pair, [1, 2], state, a, b);
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
        let (slide, x) = g.coordinate(pair, 0);
        self.rows.solve(&slide, pair, x, state, a, b, stage);
        let frames = (g.frame_a, g.frame_b);
        self.rotation
            .solve_frames(pair, frames, a, b, stage, &mut state.angular_impulse);
        g.solve_across(pair, [1, 2], state, a, b, stage);
    }
}
