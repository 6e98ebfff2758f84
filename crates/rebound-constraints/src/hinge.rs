//! The hinge (revolute) joint (course item 6): the anchors held together and the joint axes of the two bodies
//! kept parallel, leaving one rotation free — with optional angle limits, a motor and a spring on the angle.
//! Stages: *prepare*, *warm start*, *solve* and *relax*.

use crate::ball;
use crate::coordinate::{Coordinate, CoordinateRows};
use crate::error::ConstraintError;
use crate::error::check_in_range;
use crate::limits::Limits;
use crate::motor::Motor;
use crate::pair::BodyPair;
use crate::part::{AlignPart, AnglePart, PointPart};
use crate::path::{JointRows, MAX_ROWS, Row, TargetRule, equality_violation};
use crate::soft_spring::JointSpring;
use crate::stage::Stage;
use crate::state::JointState;
use core::f32::consts::{PI, TAU};
use rebound_dynamics::SolverBody;
use rebound_math::glam::Vec3A;
use rebound_math::{Quat, Vec3};

rebound_math::checked_serde! { "HingeJoint", HingeJoint::validated;
/// A hinge joint. Free by default: no limits, no motor, no spring.
///
/// The hinge axis is the X axis of each body's joint frame ([`crate::Joint::local_basis_a`]); the angle θ is
/// the twist of frame B relative to frame A about it, zero when the frames' Y axes coincide.
///
/// ```text
/// point:   C = d = 0 (3 rows)                                    see crate::part::PointPart
/// axis:    C = (a·b₁, a·b₂) = 0 (2 rows), a = F_a·x̂, bᵢ = F_b·ŷ, F_b·ẑ    see crate::part::AlignPart
/// angle:   θ = 2·atan2(q_x, q_w) of q = F_a⁻¹·F_b,  wrapped to (−π, π]
///          Ċ = a·(ω_b − ω_a),   J = [ 0  −aᵀ  0  aᵀ ],   m_eff = 1/(a·I_a⁻¹·a + a·I_b⁻¹·a)
/// limits:  θ − θ_min ≥ 0 (λ ≥ 0),  θ − θ_max ≤ 0 (λ ≤ 0), speculative inside, joint softness outside
/// motor:   Ċ → ω_target, |λ| ≤ τ_max·h
/// spring:  C = θ − θ_target, its own SoftSpring, the oscillator step in apply forces (see crate::coordinate)
/// ```
///
/// The spring acts before the passes; row order in an iteration: motor, limits, axis, point — the point last so that holding the bodies
/// together wins (Box2D's and Jolt's order).
///
/// Limitation: the angle wraps at ±π, so limits should lie inside (−π, π) with some margin; a hinge spun past
/// ±π while at a limit near ±π sees the angle jump.
///
/// # Examples
///
/// ```
/// use rebound_constraints::{HingeJoint, Motor};
/// let door = HingeJoint::new()
///     .with_limits(-1.5, 1.5)?
///     .with_motor(Motor::new(0.5, 20.0)?);
/// assert_eq!(door.limits().map(|l| l.upper()), Some(1.5));
/// assert!(HingeJoint::new().with_limits(1.0, -1.0).is_err());
/// # Ok::<(), rebound_constraints::ConstraintError>(())
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Default)]
#[cfg_attr(feature = "serde", derive(serde::Serialize))]
pub struct HingeJoint {
    limits: Option<Limits>,
    motor: Option<Motor>,
    spring: Option<JointSpring>,
}
}

impl HingeJoint {
    /// A free hinge.
    #[must_use]
    pub const fn new() -> Self {
        Self {
            limits: None,
            motor: None,
            spring: None,
        }
    }

    /// Limits the angle to `[lower, upper]` (rad, each in `[−π, π]`).
    ///
    /// # Errors
    /// Non-finite bounds, bounds outside `[−π, π]`, `lower > upper`.
    pub fn with_limits(mut self, lower: f32, upper: f32) -> Result<Self, ConstraintError> {
        self.set_limits(Some(Limits::new(lower, upper)?))?;
        Ok(self)
    }

    /// Adds a motor (target speed rad/s, max torque N·m).
    #[must_use]
    pub const fn with_motor(mut self, motor: Motor) -> Self {
        self.motor = Some(motor);
        self
    }

    /// Adds a spring on the angle (target rad, stiffness in Hz/ζ or N·m/rad and N·m·s/rad).
    #[must_use]
    pub const fn with_spring(mut self, spring: JointSpring) -> Self {
        self.spring = Some(spring);
        self
    }

    /// Returns `self` if its limits, motor and spring pass the checks of their constructors and of
    /// [`HingeJoint::set_limits`] (for values that bypassed them: deserialised).
    ///
    /// # Errors
    /// The first invalid field.
    pub fn validated(self) -> Result<Self, ConstraintError> {
        let mut checked = Self::new();
        checked.set_limits(self.limits.map(Limits::validated).transpose()?)?;
        self.motor.map(Motor::validated).transpose()?;
        self.spring.map(JointSpring::validated).transpose()?;
        Ok(self)
    }

    /// The angle limits (rad), if any.
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

    /// Sets or removes the angle limits; nothing changes on error.
    ///
    /// # Errors
    /// Bounds outside `[−π, π]` ([`ConstraintError::OutOfRange`]).
    pub fn set_limits(&mut self, limits: Option<Limits>) -> Result<(), ConstraintError> {
        if let Some(l) = limits {
            check_in_range("lower", l.lower(), -PI, PI)?;
            check_in_range("upper", l.upper(), -PI, PI)?;
        }
        self.limits = limits;
        Ok(())
    }

    /// Sets or removes the motor.
    pub fn set_motor(&mut self, motor: Option<Motor>) {
        self.motor = motor;
    }

    /// Sets or removes the spring.
    pub fn set_spring(&mut self, spring: Option<JointSpring>) {
        self.spring = spring;
    }

    pub(crate) fn prepare(&self, pair: &BodyPair, state: &mut JointState) -> PreparedHinge {
        let rows = CoordinateRows {
            spring: self.spring,
            motor: self.motor,
            limits: self.limits,
        };
        rows.clear_unused(state);
        state.angular_impulse.z = 0.0;
        PreparedHinge {
            rows,
            axis_a: pair.basis_a * Vec3A::X,
            perpendiculars_b: [pair.basis_b * Vec3A::Y, pair.basis_b * Vec3A::Z],
        }
    }
}

/// The twist angle θ (rad, in (−π, π]) of `frame_b` relative to `frame_a` about `frame_a`'s X axis.
#[inline]
#[must_use]
pub fn twist_angle(frame_a: Quat, frame_b: Quat) -> f32 {
    let q = frame_a.conjugate() * frame_b;
    wrap_angle(2.0 * rebound_math::real::atan2(q.x, q.w))
}

/// `angle` wrapped to (−π, π] (for inputs in (−3π, 3π]).
#[inline]
#[must_use]
pub(crate) fn wrap_angle(angle: f32) -> f32 {
    if angle > PI {
        angle - TAU
    } else if angle <= -PI {
        angle + TAU
    } else {
        angle
    }
}

/// A hinge ready for the substeps.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct PreparedHinge {
    rows: CoordinateRows,
    /// A's hinge axis and B's two perpendiculars (the joint frames' X, and Y and Z) at the start of the step,
    /// world: each body's rotation since then turns them to the current ones.
    axis_a: Vec3A,
    perpendiculars_b: [Vec3A; 2],
}

impl PreparedHinge {
    pub(crate) fn warm_start(
        &self,
        pair: &BodyPair,
        state: &JointState,
        a: &mut SolverBody,
        b: &mut SolverBody,
    ) {
        // Each part's angular impulse `Jᵀλ` — the angle rows' about the axis, the alignment rows' — summed
        // into one twist, which the point part applies with its impulse `P` at the anchors: each body's
        // torques turned by its inverse inertia once. B's perpendiculars are weighted by their impulses
        // before they are turned to the current pose (one rotation instead of two).
        let axis = a.delta_rotation * self.axis_a;
        let align = state.angular_impulse;
        let [b1, b2] = self.perpendiculars_b;
        let perpendicular = b.delta_rotation * (b1 * align.x + b2 * align.y);
        let twist = AnglePart::twist(axis, CoordinateRows::warm_start_impulse(state))
            + AlignPart::twist(axis, perpendicular);
        let r_a = a.delta_rotation * Vec3A::from(pair.anchor_a);
        let r_b = b.delta_rotation * Vec3A::from(pair.anchor_b);
        let p = Vec3A::from(state.linear_impulse);
        PointPart::apply_with_twist(pair, (r_a, r_b), p, twist, a, b);
    }

    /// The point rows and the two alignment rows for the direct solve of a path or graph ([`crate::path`])
    /// at the current pose, then, for limits in the direct solve ([`PreparedHinge::has_direct_limit`]), the
    /// limit row of the bound nearer the angle ([`limit_row`]); the motor and the other limits stay with
    /// [`PreparedHinge::solve_coordinate`] (the spring acts in *apply forces*).
    pub(crate) fn direct_rows(
        &self,
        pair: &BodyPair,
        a: &SolverBody,
        b: &SolverBody,
        stage: &Stage,
        out: &mut JointRows,
    ) {
        ball::direct_rows(pair, a, b, stage, out);
        let frames = pair.frames(a, b);
        let (axis, perpendiculars) = alignment_axes(frames);
        AlignPart::push_rows(axis, perpendiculars, stage, out);
        if let Some(limits) = self.direct_limits() {
            let (row, c, rule) = limit_row(limits, axis, twist_angle(frames.0, frames.1), stage);
            out.push(row, c, rule);
        }
    }

    /// The accumulated impulses of [`PreparedHinge::direct_rows`]' rows, in row order: the point block's,
    /// the two alignment rows', then the limit row's (the lower bound's impulse, `λ ≥ 0`, plus the upper
    /// bound's, `λ ≤ 0`: the one along the axis that the row pushed carries on).
    #[inline]
    pub(crate) fn direct_impulses(&self, state: &JointState) -> [f32; MAX_ROWS] {
        let (l, w) = (state.linear_impulse, state.angular_impulse);
        let limit = if self.direct_limits().is_some() {
            state.lower_impulse + state.upper_impulse
        } else {
            0.0
        };
        [l.x, l.y, l.z, w.x, w.y, limit]
    }

    /// Writes the impulses a direct solve gave [`PreparedHinge::direct_rows`]' rows back into `state`: the
    /// limit row's by its sign to the lower bound (`λ > 0`) or the upper one (`λ < 0`), as the limit rows of
    /// [`PreparedHinge::solve_coordinate`] hold them.
    #[inline]
    pub(crate) fn store_direct_impulses(&self, state: &mut JointState, lambda: [f32; MAX_ROWS]) {
        ball::store_direct_impulses(state, lambda);
        state.angular_impulse.x = lambda[3];
        state.angular_impulse.y = lambda[4];
        if self.direct_limits().is_some() {
            let limit = lambda[5];
            state.lower_impulse = limit.max(0.0);
            state.upper_impulse = limit.min(0.0);
        }
    }

    /// The limits solved in the direct solve when the hinge is on a path or graph: limits whose range is
    /// at least [`MIN_DIRECT_RANGE`]. The row of the nearer bound alone is in the system, so a range too
    /// narrow to tell the bounds apart within a substep (a hinge locked by equal bounds) keeps both rows in
    /// [`PreparedHinge::solve_coordinate`].
    #[inline]
    pub(crate) fn direct_limits(&self) -> Option<Limits> {
        self.rows
            .limits
            .filter(|l| l.upper() - l.lower() >= MIN_DIRECT_RANGE)
    }

    /// How many rows [`PreparedHinge::direct_rows`] pushes: 5, or 6 with a limit row.
    pub(crate) fn direct_row_count(&self) -> usize {
        if self.direct_limits().is_some() { 6 } else { 5 }
    }

    /// The worst position error of [`PreparedHinge::direct_rows`]' rows at the pose `a`, `b` (m or rad), from
    /// the errors alone: the point and alignment rows' (as [`equality_violation`] measures them for `stage`)
    /// and the angle past the limits in the direct solve.
    #[inline]
    pub(crate) fn direct_violation(
        &self,
        pair: &BodyPair,
        a: &SolverBody,
        b: &SolverBody,
        stage: &Stage,
    ) -> f32 {
        let rows = equality_violation(&Self::direct_errors(pair, a, b), stage);
        self.direct_limits().map_or(rows, |limits| {
            let (fa, fb) = pair.frames(a, b);
            let angle = twist_angle(fa, fb);
            rows.max(limits.lower() - angle).max(angle - limits.upper())
        })
    }

    /// The position errors `C` of [`PreparedHinge::direct_rows`]' point and alignment rows and their target
    /// rules, in row order,
    /// computed as it computes them but without building the rows: what the position projection measures a
    /// path's worst error from after every step it tries.
    pub(crate) fn direct_errors(
        pair: &BodyPair,
        a: &SolverBody,
        b: &SolverBody,
    ) -> [(f32, TargetRule); 5] {
        let [x, y, z] = ball::direct_errors(pair, a, b);
        let (axis, perpendiculars) = alignment_axes(pair.frames(a, b));
        let [p, q] = AlignPart::errors(axis, perpendiculars);
        [x, y, z, p, q]
    }

    /// Whether all the rows the hinge's passes solve are those of [`PreparedHinge::direct_rows`]: no motor,
    /// and no limits or limits in the direct solve (a spring acts in *apply forces*, before them).
    pub(crate) fn is_solved_directly_whole(&self) -> bool {
        self.coordinate_rows_on_path().is_idle()
    }

    /// The rows [`PreparedHinge::solve_coordinate`] solves when the hinge is on a path or graph: the motor,
    /// and the limits not in the direct solve.
    #[inline]
    fn coordinate_rows_on_path(&self) -> CoordinateRows {
        CoordinateRows {
            limits: self.rows.limits.filter(|_| self.direct_limits().is_none()),
            ..self.rows
        }
    }

    /// The motor and the limit rows not in the direct solve alone (when the point, alignment and, for a
    /// range of at least [`MIN_DIRECT_RANGE`], limit rows are solved directly).
    pub(crate) fn solve_coordinate(
        &self,
        pair: &BodyPair,
        state: &mut JointState,
        a: &mut SolverBody,
        b: &mut SolverBody,
        stage: &Stage,
    ) {
        let rows = self.coordinate_rows_on_path();
        // A plain hinge (no limit or motor; every hinge of a bridge) skips the angle and its row.
        if rows.is_idle() {
            return;
        }
        let frames = pair.frames(a, b);
        let (part, angle) = angle_at(pair, frames, hinge_axis(frames.0));
        rows.solve(&part, pair, angle, state, a, b, stage);
    }

    /// The limit and motor rows on the angle between the joint frames `frames` (world), about A's
    /// hinge axis `axis` (world).
    #[inline]
    fn solve_angle(
        &self,
        pair: &BodyPair,
        frames: (Quat, Quat),
        axis: Vec3,
        state: &mut JointState,
        a: &mut SolverBody,
        b: &mut SolverBody,
        stage: &Stage,
    ) {
        let (part, angle) = angle_at(pair, frames, axis);
        self.rows.solve(&part, pair, angle, state, a, b, stage);
    }

    pub(crate) fn solve(
        &self,
        pair: &BodyPair,
        state: &mut JointState,
        a: &mut SolverBody,
        b: &mut SolverBody,
        stage: &Stage,
    ) {
        let (fa, fb) = pair.frames(a, b);
        let (axis, perpendiculars) = alignment_axes((fa, fb));
        if !self.rows.is_idle() {
            self.solve_angle(pair, (fa, fb), axis, state, a, b, stage);
        }
        let align = AlignPart::new(pair, axis, perpendiculars);
        let mut lambda = state.angular_impulse.truncate();
        align.solve(a, b, stage.bias, stage.joint_softness, &mut lambda);
        state.angular_impulse = lambda.extend(0.0);
        ball::solve(pair, state, a, b, stage);
    }
}

impl Coordinate for PreparedHinge {
    type Part = AnglePart;

    fn rows(&self) -> &CoordinateRows {
        &self.rows
    }

    /// The row about A's hinge axis and the hinge angle ([`twist_angle`]).
    #[inline]
    fn coordinate(&self, pair: &BodyPair, a: &SolverBody, b: &SolverBody) -> (AnglePart, f32) {
        let frames = pair.frames(a, b);
        angle_at(pair, frames, hinge_axis(frames.0))
    }
}

/// The angle row about A's hinge `axis` (world) and the hinge angle between the joint frames `fa`, `fb`.
#[inline]
fn angle_at(pair: &BodyPair, (fa, fb): (Quat, Quat), axis: Vec3) -> (AnglePart, f32) {
    (AnglePart::new(pair, axis), twist_angle(fa, fb))
}

/// The narrowest range of limits (rad) that the direct solve holds ([`PreparedHinge::direct_limits`]).
pub(crate) const MIN_DIRECT_RANGE: f32 = 0.1;

/// The limit row of the bound of `limits` nearer the hinge angle `angle` (rad), about A's hinge `axis`
/// (world), for a pass of `stage`, with its position error and target rule: the angle row ([`AnglePart::row`])
/// with `C = θ − θ_min`, `λ ≥ 0`, or `C = θ − θ_max`, `λ ≤ 0` — as [`CoordinateRows::solve`]'s limit rows,
/// speculative inside the range, one-sided, and left to the path solver's active set.
fn limit_row(limits: Limits, axis: Vec3, angle: f32, stage: &Stage) -> (Row, f32, TargetRule) {
    let (c_lower, c_upper) = (angle - limits.lower(), angle - limits.upper());
    let (c, rule, bounds) = if c_lower < -c_upper {
        (c_lower, TargetRule::LowerLimit, (0.0, f32::INFINITY))
    } else {
        (c_upper, TargetRule::UpperLimit, (f32::NEG_INFINITY, 0.0))
    };
    let row = AnglePart::row(axis, rule.target(c, stage)).clamped(bounds.0, bounds.1);
    (row, c, rule)
}

/// A's hinge axis and B's two axes across it, from the joint frames `fa`, `fb` (world), at the current pose:
/// what [`AlignPart`] is built from for the Gauss–Seidel solve ([`PreparedHinge::solve`]) and for the
/// direct rows and their errors ([`PreparedHinge::direct_rows`], [`PreparedHinge::direct_errors`]).
#[inline]
fn alignment_axes((fa, fb): (Quat, Quat)) -> (Vec3, [Vec3; 2]) {
    (hinge_axis(fa), AlignPart::perpendiculars(fb))
}

/// A's hinge axis (world), the X axis of its joint frame `fa`: the axis of the alignment and of the angle.
#[inline]
fn hinge_axis(fa: Quat) -> Vec3 {
    fa * Vec3::X
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_twist_angle_is_the_rotation_about_x_and_ignores_swing() {
        let a = Quat::from_rotation_y(0.7);
        for angle in [-3.0f32, -1.0, 0.0, 0.4, 2.5, PI] {
            let b = a * Quat::from_rotation_x(angle);
            assert!(
                (twist_angle(a, b) - wrap_angle(angle)).abs() < 1e-5,
                "{angle}"
            );
        }
        // Past ±π it wraps.
        let b = a * Quat::from_rotation_x(3.5);
        assert!((twist_angle(a, b) - (3.5 - TAU)).abs() < 1e-5);
        // A pure swing (about a perpendicular axis) has no twist.
        assert!(twist_angle(Quat::IDENTITY, Quat::from_rotation_z(0.8)).abs() < 1e-6);
    }
}
