//! The ball (spherical) joint: two anchor points held together, rotation free — or limited by a swing cone
//! and a twist range ([`SwingTwistLimits`]) and driven to a target orientation ([`OrientationMotor`]).
//! Stages: *prepare*, *warm start*, *solve* and *relax*, *restitution*.

use crate::error::ConstraintError;
use crate::orientation_motor::{OrientationMotor, PreparedMotor};
use crate::pair::BodyPair;
use crate::part::{PointPart, block_target};
use crate::path::{JointRows, MAX_ROWS, TargetRule, equality_violation};
use crate::stage::Stage;
use crate::state::JointState;
use crate::swing_twist::{LimitRows, PreparedLimits, SwingTwistLimits};
use rebound_dynamics::{SolverBody, StepContext};
use rebound_math::Vec3;
use rebound_math::glam::Vec3A;

/// A ball joint: the anchors of the [`crate::Joint`] are the pivot. Free by default; optional swing–twist
/// limits about the joint axis (the joint frames' X) and an orientation motor.
///
/// ```text
/// C = d = p_b − p_a = 0                                 (m, 3 rows)
/// Ċ = v_b + ω_b × r_b − v_a − ω_a × r_a,   J = [ −1   [r_a]×   1   −[r_b]× ]
/// K = (1/m_a + 1/m_b)·1 − [r_a]×·I_a⁻¹·[r_a]× − [r_b]×·I_b⁻¹·[r_b]×,    M_eff = K⁻¹
/// limits: see crate::swing_twist;  motor: see crate::orientation_motor
/// ```
///
/// Softness: the joint softness of [`crate::JointSettings`] in the bias pass, none in the relax pass. Row
/// order in an iteration: motor, twist, swing, point — the point last so that holding the bodies together
/// wins.
///
/// # Examples
///
/// ```
/// use rebound_constraints::{BallJoint, SwingTwistLimits};
/// let hip = BallJoint::new().with_limits(SwingTwistLimits::new().with_cone(0.9, 0.5)?.with_twist(-0.3, 0.6)?);
/// assert!(!hip.is_free());
/// assert!(BallJoint::new().is_free());
/// # Ok::<(), rebound_constraints::ConstraintError>(())
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Default)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[cfg_attr(feature = "serde", serde(default))]
pub struct BallJoint {
    limits: Option<SwingTwistLimits>,
    motor: Option<OrientationMotor>,
}

impl BallJoint {
    /// A free ball joint.
    #[must_use]
    pub const fn new() -> Self {
        Self {
            limits: None,
            motor: None,
        }
    }

    /// Adds swing–twist limits.
    #[must_use]
    pub const fn with_limits(mut self, limits: SwingTwistLimits) -> Self {
        self.limits = Some(limits);
        self
    }

    /// Adds an orientation motor.
    #[must_use]
    pub const fn with_motor(mut self, motor: OrientationMotor) -> Self {
        self.motor = Some(motor);
        self
    }

    /// The swing–twist limits, if any.
    #[must_use]
    pub fn limits(&self) -> Option<SwingTwistLimits> {
        self.limits
    }

    /// The orientation motor, if any.
    #[must_use]
    pub fn motor(&self) -> Option<OrientationMotor> {
        self.motor
    }

    /// Sets or removes the limits.
    pub fn set_limits(&mut self, limits: Option<SwingTwistLimits>) {
        self.limits = limits;
    }

    /// Sets or removes the motor (to move its target, [`OrientationMotor::set_target`] on a copy and set it).
    pub fn set_motor(&mut self, motor: Option<OrientationMotor>) {
        self.motor = motor;
    }

    /// Whether the rotation is free: no limit and no motor (the three point rows alone).
    #[must_use]
    pub fn is_free(&self) -> bool {
        self.limits.is_none_or(|l| l.is_empty()) && self.motor.is_none()
    }

    /// Returns `self` if its limits and motor are valid (for deserialized values).
    ///
    /// # Errors
    /// The first invalid field.
    pub fn validated(self) -> Result<Self, ConstraintError> {
        self.limits.map(SwingTwistLimits::validated).transpose()?;
        self.motor.map(OrientationMotor::validated).transpose()?;
        Ok(self)
    }

    /// Stage *prepare* of a ball joint that is not free, with the impulses it does not use in `state` zeroed.
    pub(crate) fn prepare(
        &self,
        pair: &BodyPair,
        bodies: (&SolverBody, &SolverBody),
        ctx: &StepContext,
        state: &mut JointState,
    ) -> PreparedBall {
        let kept = *state;
        *state = JointState {
            linear_impulse: kept.linear_impulse,
            angular_impulse: kept.angular_impulse,
            axial_impulse: kept.axial_impulse,
            lower_impulse: kept.lower_impulse,
            upper_impulse: kept.upper_impulse,
            ..kept.tether_only()
        };
        let limits = self.limits.filter(|l| !l.is_empty());
        if limits.is_none() {
            state.axial_impulse = 0.0;
            state.lower_impulse = 0.0;
            state.upper_impulse = 0.0;
        }
        if self.motor.is_none() {
            state.angular_impulse = Vec3::ZERO;
        }
        PreparedBall {
            limits: limits.map(|l| l.prepare(pair, bodies, ctx, state)),
            motor: self.motor.map(|m| m.prepare(pair, ctx)),
        }
    }
}

/// A ball joint with limits or a motor, ready for the substeps (a free one needs nothing prepared).
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct PreparedBall {
    limits: Option<PreparedLimits>,
    motor: Option<PreparedMotor>,
}

impl PreparedBall {
    /// Stage *warm start*: the point, limit and motor impulses, each body's torques turned once.
    pub(crate) fn warm_start(
        &self,
        pair: &BodyPair,
        state: &JointState,
        a: &mut SolverBody,
        b: &mut SolverBody,
    ) {
        let frames = pair.frames(a, b);
        let anchors = pair.anchors(a, b);
        let (limits, carried) = self.limits.as_ref().map_or((Vec3::ZERO, Vec3::ZERO), |l| {
            let point = PointPart::new(pair, anchors.r_a, anchors.r_b);
            LimitRows::new(l.limits(), frames).warm_impulses(pair, &point, state)
        });
        let twist = Vec3A::from(limits + state.angular_impulse);
        let p = Vec3A::from(state.linear_impulse + carried);
        let levers = (Vec3A::from(anchors.r_a), Vec3A::from(anchors.r_b));
        PointPart::apply_with_twist(pair, levers, p, twist, a, b);
    }

    /// Stages *solve* and *relax*: the motor and the limits, then (unless the point rows are solved on a
    /// path, `on_path`) the point.
    pub(crate) fn solve(
        &mut self,
        pair: &BodyPair,
        state: &mut JointState,
        a: &mut SolverBody,
        b: &mut SolverBody,
        stage: &Stage,
        on_path: bool,
    ) {
        if let Some(motor) = &self.motor {
            let frames = pair.frames(a, b);
            motor.solve(pair, frames, &mut state.angular_impulse, a, b, stage);
        }
        if let Some(limits) = &mut self.limits
            && !(on_path && limits.is_direct())
        {
            // Each limit row acts about the pivot (`crate::part::PivotAnglePart`), so the point rows after
            // it, here or on a path, leave it be.
            let anchors = pair.anchors(a, b);
            let point = PointPart::new(pair, anchors.r_a, anchors.r_b);
            limits.solve(pair, &point, pair.frames(a, b), state, a, b, stage);
        }
        if !on_path {
            solve(pair, state, a, b, stage);
        }
    }

    /// Whether a Gauss–Seidel pass visits the joint when it is on a directly solved path or graph: for its
    /// motor or soft limits (rigid limits are solved with its point rows there).
    pub(crate) fn is_iterated_on_path(&self) -> bool {
        self.motor.is_some() || self.limits.is_some_and(|l| !l.is_direct())
    }

    /// The rows for the direct solve of a path or graph ([`crate::path`]) at the current pose: the point
    /// rows ([`direct_rows`]) and, for rigid limits, the swing and twist rows
    /// ([`PreparedLimits::push_direct_rows`]).
    pub(crate) fn direct_rows(
        &mut self,
        pair: &BodyPair,
        a: &SolverBody,
        b: &SolverBody,
        stage: &Stage,
        out: &mut JointRows,
    ) {
        let anchors = pair.anchors(a, b);
        PointPart::push_rows(anchors.r_a, anchors.r_b, anchors.d, stage, out);
        if let Some(limits) = self.limits.as_mut().filter(|l| l.is_direct()) {
            let point = PointPart::new(pair, anchors.r_a, anchors.r_b);
            limits.push_direct_rows(pair, &point, anchors.d, pair.frames(a, b), stage, out);
        }
    }

    /// The accumulated impulses of [`PreparedBall::direct_rows`]' rows, in row order: the point block's,
    /// then the limit rows'.
    #[inline]
    pub(crate) fn direct_impulses(&self, state: &JointState) -> [f32; MAX_ROWS] {
        let mut out = direct_impulses(state);
        if let Some(limits) = self.limits.as_ref().filter(|l| l.is_direct()) {
            let (lambda, count) = limits.direct_impulses(state);
            out[3..3 + count].copy_from_slice(&lambda[..count]);
        }
        out
    }

    /// Writes the impulses a direct solve gave [`PreparedBall::direct_rows`]' rows back into `state`.
    #[inline]
    pub(crate) fn store_direct_impulses(
        &mut self,
        state: &mut JointState,
        lambda: [f32; MAX_ROWS],
    ) {
        store_direct_impulses(state, lambda);
        if let Some(limits) = self.limits.as_mut().filter(|l| l.is_direct()) {
            limits.store_direct_impulses(state, &lambda[3..]);
        }
    }

    /// The worst position error of [`PreparedBall::direct_rows`]' rows at the pose `a`, `b` (m or rad), from
    /// the errors alone: the point rows' (as [`equality_violation`] measures them for `stage`) and the angle
    /// past the limits.
    pub(crate) fn direct_violation(
        &self,
        pair: &BodyPair,
        a: &SolverBody,
        b: &SolverBody,
        stage: &Stage,
    ) -> f32 {
        let point = equality_violation(&direct_errors(pair, a, b), stage);
        self.limits
            .as_ref()
            .filter(|l| l.is_direct())
            .map_or(point, |l| point.max(l.excess(pair.frames(a, b))))
    }

    /// Stage *restitution* of the limits.
    pub(crate) fn apply_restitution(
        &self,
        pair: &BodyPair,
        state: &mut JointState,
        a: &mut SolverBody,
        b: &mut SolverBody,
        ctx: &StepContext,
    ) {
        if let Some(limits) = &self.limits {
            let anchors = pair.anchors(a, b);
            let point = PointPart::new(pair, anchors.r_a, anchors.r_b);
            limits.apply_restitution(pair, &point, pair.frames(a, b), state, a, b, ctx);
        }
    }
}

pub(crate) fn warm_start(
    pair: &BodyPair,
    state: &JointState,
    a: &mut SolverBody,
    b: &mut SolverBody,
) {
    let anchors = pair.anchors(a, b);
    PointPart::apply_at(pair, anchors.r_a, anchors.r_b, a, b, state.linear_impulse);
}

pub(crate) fn solve(
    pair: &BodyPair,
    state: &mut JointState,
    a: &mut SolverBody,
    b: &mut SolverBody,
    stage: &Stage,
) {
    let anchors = pair.anchors(a, b);
    let part = PointPart::new(pair, anchors.r_a, anchors.r_b);
    let target = block_target(anchors.d, stage.bias, stage.joint_softness);
    part.solve(pair, a, b, target, &mut state.linear_impulse);
}

/// The accumulated impulses of [`direct_rows`]' rows, in row order (the point block's, along x, y, z).
#[inline]
pub(crate) fn direct_impulses(state: &JointState) -> [f32; MAX_ROWS] {
    let l = state.linear_impulse;
    let mut out = [0.0; MAX_ROWS];
    out[..3].copy_from_slice(&[l.x, l.y, l.z]);
    out
}

/// Writes the impulses a direct solve gave [`direct_rows`]' rows back into `state`.
#[inline]
pub(crate) fn store_direct_impulses(state: &mut JointState, lambda: [f32; MAX_ROWS]) {
    state.linear_impulse = Vec3::new(lambda[0], lambda[1], lambda[2]);
}

/// The position errors `C` of [`direct_rows`]' rows and their target rules, in row order, without building
/// the rows: what the position projection measures a path's worst error from after every step it tries.
pub(crate) fn direct_errors(
    pair: &BodyPair,
    a: &SolverBody,
    b: &SolverBody,
) -> [(f32, TargetRule); 3] {
    PointPart::errors(pair.anchors(a, b).d)
}

/// The three point rows (world axes) for the direct solve of a chain ([`crate::path`]) at the current pose:
/// [`PointPart::push_rows`] at the anchors [`solve`] builds its block at.
pub(crate) fn direct_rows(
    pair: &BodyPair,
    a: &SolverBody,
    b: &SolverBody,
    stage: &Stage,
    out: &mut JointRows,
) {
    let anchors = pair.anchors(a, b);
    PointPart::push_rows(anchors.r_a, anchors.r_b, anchors.d, stage, out);
}
