//! Swing–twist limits of a ball joint ([`SwingTwistLimits`]): an elliptical cone for the joint axis (A's
//! joint-frame X) and a range for the twist about it, each a one-sided angular row, rigid and speculative or
//! soft, with restitution. Stages *prepare*, *solve* and *relax*, *restitution*. The measure is
//! [`crate::part::SwingTwist`]; the derivation is in `docs/physics.md`, "Swing–twist limits".
//!
//! ```text
//! swing:  C = (φ − φ_max(u))·(n·u) ≤ 0,  row about F_a·(0, n), λ ≤ 0          → JointState::axial_impulse
//! twist:  θ − θ_min ≥ 0 (λ ≥ 0),  θ − θ_max ≤ 0 (λ ≤ 0), row about j_t      → lower_impulse, upper_impulse
//! rigid:  speculative inside (Ċ ≤ −C/h), joint softness outside, bias and relax passes
//! soft:   inactive inside, the limit's own spring outside, bias pass only
//! bounce: after the substeps, a limit that acted during the step and was approached faster than the world's restitution
//!         threshold gets Ċ = −e·Ċ⁻ (Ċ⁻ its rate at the start of the step)
//! ```

use crate::error::{ConstraintError, check_in_range};
use crate::limits::Limits;
use crate::pair::BodyPair;
use crate::part::{AnglePart, PivotAnglePart, PointPart, Row, RowTarget, SwingTwist};
use crate::path::{JointRows, TargetRule};
use crate::soft_spring::SoftSpring;
use crate::stage::Stage;
use crate::state::JointState;
use core::f32::consts::PI;
use rebound_dynamics::{Bias, Softness, SolverBody, StepContext};
use rebound_math::{Quat, Vec2, Vec3};

/// The smallest swing half-angle (rad): a narrower cone is a hinge or a fixed joint.
pub const MIN_SWING_HALF_ANGLE: f32 = 1e-3;

/// Limits on a ball joint's rotation, split as a swing of the joint axis and a twist about it.
///
/// The joint axis is the X axis of each body's joint frame ([`crate::Joint::local_basis_a`]): the swing is
/// the angle between A's and B's X axes, kept inside an elliptical cone of half-angle `θ_y` for swings about
/// A's Y axis and `θ_z` about its Z axis; the twist is the rotation of B about its X axis relative to A,
/// zero when the frames coincide.
///
/// Default: no cone, no twist range, rigid, no restitution.
///
/// # Examples
///
/// ```
/// use rebound_constraints::{BallJoint, SwingTwistLimits};
/// let shoulder = SwingTwistLimits::new()
///     .with_cone(1.2, 0.8)?
///     .with_twist(-0.5, 0.5)?
///     .with_restitution(0.2)?;
/// let joint = BallJoint::new().with_limits(shoulder);
/// assert_eq!(joint.limits().and_then(|l| l.cone()), Some((1.2, 0.8)));
/// assert!(SwingTwistLimits::new().with_cone(0.0, 0.5).is_err());
/// # Ok::<(), rebound_constraints::ConstraintError>(())
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Default)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[cfg_attr(feature = "serde", serde(default))]
pub struct SwingTwistLimits {
    cone: Option<(f32, f32)>,
    twist: Option<Limits>,
    softness: Option<SoftSpring>,
    restitution: f32,
}

impl SwingTwistLimits {
    /// No limits yet: add a cone and a twist range.
    #[must_use]
    pub const fn new() -> Self {
        Self {
            cone: None,
            twist: None,
            softness: None,
            restitution: 0.0,
        }
    }

    /// Limits the swing to the elliptical cone of half-angles `half_angle_y` (about A's joint-frame Y) and
    /// `half_angle_z` (about its Z), rad, each in `[MIN_SWING_HALF_ANGLE, π]`; equal angles give a circular
    /// cone.
    ///
    /// # Errors
    /// A half-angle out of range or not finite (fields `half_angle_y`, `half_angle_z`).
    pub fn with_cone(
        mut self,
        half_angle_y: f32,
        half_angle_z: f32,
    ) -> Result<Self, ConstraintError> {
        self.set_cone(Some((half_angle_y, half_angle_z)))?;
        Ok(self)
    }

    /// Limits the twist to `[lower, upper]` (rad, each in `[−π, π]`).
    ///
    /// # Errors
    /// Bounds out of range or not finite (fields `lower`, `upper`), `lower > upper`.
    pub fn with_twist(mut self, lower: f32, upper: f32) -> Result<Self, ConstraintError> {
        self.set_twist(Some(Limits::new(lower, upper)?))?;
        Ok(self)
    }

    /// Makes the limits soft: outside them a spring of this stiffness pushes back (Hz/ζ, or N·m/rad and
    /// N·m·s/rad); inside they do nothing. Default: rigid.
    ///
    /// # Errors
    /// An invalid spring (see [`SoftSpring::validated`]).
    pub fn with_softness(mut self, softness: SoftSpring) -> Result<Self, ConstraintError> {
        self.softness = Some(softness.validated()?);
        Ok(self)
    }

    /// Sets the coefficient of restitution of a limit being hit (dimensionless, in `[0, 1]`). Default: 0.
    ///
    /// # Errors
    /// `restitution` outside `[0, 1]` or NaN.
    pub fn with_restitution(mut self, restitution: f32) -> Result<Self, ConstraintError> {
        self.restitution = check_in_range("restitution", restitution, 0.0, 1.0)?;
        Ok(self)
    }

    /// The cone's half-angles `(θ_y, θ_z)` (rad), if the swing is limited.
    #[must_use]
    pub fn cone(&self) -> Option<(f32, f32)> {
        self.cone
    }

    /// The twist range (rad), if the twist is limited.
    #[must_use]
    pub fn twist(&self) -> Option<Limits> {
        self.twist
    }

    /// The limits' spring, if they are soft.
    #[must_use]
    pub fn softness(&self) -> Option<SoftSpring> {
        self.softness
    }

    /// The coefficient of restitution (dimensionless).
    #[must_use]
    pub fn restitution(&self) -> f32 {
        self.restitution
    }

    /// Sets or removes the cone (half-angles in rad, see [`SwingTwistLimits::with_cone`]); nothing changes on
    /// error.
    ///
    /// # Errors
    /// A half-angle out of range or not finite.
    pub fn set_cone(&mut self, cone: Option<(f32, f32)>) -> Result<(), ConstraintError> {
        if let Some((y, z)) = cone {
            check_in_range("half_angle_y", y, MIN_SWING_HALF_ANGLE, PI)?;
            check_in_range("half_angle_z", z, MIN_SWING_HALF_ANGLE, PI)?;
        }
        self.cone = cone;
        Ok(())
    }

    /// Sets or removes the twist range (rad, within `[−π, π]`); nothing changes on error.
    ///
    /// # Errors
    /// Bounds outside `[−π, π]`.
    pub fn set_twist(&mut self, twist: Option<Limits>) -> Result<(), ConstraintError> {
        if let Some(l) = twist {
            check_in_range("lower", l.lower(), -PI, PI)?;
            check_in_range("upper", l.upper(), -PI, PI)?;
        }
        self.twist = twist;
        Ok(())
    }

    /// Returns `self` if every field is valid, checked as the setters check it (for values that bypassed
    /// them: deserialized descriptions).
    ///
    /// # Errors
    /// The first invalid field.
    pub fn validated(self) -> Result<Self, ConstraintError> {
        let mut checked = Self::new();
        checked.set_cone(self.cone)?;
        let twist = self
            .twist
            .map(|l| Limits::new(l.lower(), l.upper()))
            .transpose()?;
        checked.set_twist(twist)?;
        if let Some(s) = self.softness {
            checked = checked.with_softness(s)?;
        }
        checked.with_restitution(self.restitution)?;
        Ok(self)
    }

    /// Whether there is nothing to limit.
    pub(crate) fn is_empty(&self) -> bool {
        self.cone.is_none() && self.twist.is_none()
    }

    pub(crate) fn prepare(
        &self,
        pair: &BodyPair,
        (a, b): (&SolverBody, &SolverBody),
        ctx: &StepContext,
        state: &mut JointState,
    ) -> PreparedLimits {
        if self.cone.is_none() {
            state.axial_impulse = 0.0;
        }
        if self.twist.is_none() {
            state.lower_impulse = 0.0;
            state.upper_impulse = 0.0;
        }
        let rows = LimitRows::new(self, pair.frames(a, b));
        let rate =
            |axis: Option<Vec3>| axis.map_or(0.0, |axis| AnglePart::new(pair, axis).velocity(a, b));
        PreparedLimits {
            limits: *self,
            softness: self
                .softness
                .map_or(Softness::RIGID, |s| s.softness(0.0, ctx.h)),
            swing_rate: rate(rows.swing.map(|(_, axis)| axis)),
            twist_rate: rate(rows.twist_axis),
            acted: [false; 3],
            direct: DirectLimitRows::default(),
        }
    }
}

/// Which side of a range a limit row holds.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Side {
    /// `C = x − x_min ≥ 0`, `λ ≥ 0`.
    Lower,
    /// `C = x − x_max ≤ 0`, `λ ≤ 0`.
    Upper,
}

/// The limits' rows at one pose: the swing row's error and axis, the twist angle and its Jacobian axis.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct LimitRows {
    /// `(C, unit axis)` of the swing row, if the swing is limited.
    pub swing: Option<(f32, Vec3)>,
    /// The twist angle θ (rad).
    pub twist: f32,
    /// The twist row's axis `j_t`, if the twist is limited and defined.
    pub twist_axis: Option<Vec3>,
}

impl LimitRows {
    #[inline]
    pub(crate) fn new(limits: &SwingTwistLimits, (fa, fb): (Quat, Quat)) -> Self {
        let st = SwingTwist::new(fa, fb);
        Self {
            swing: limits.cone.map(|(y, z)| st.cone_error(fa, Vec2::new(y, z))),
            twist: st.twist,
            twist_axis: limits.twist.and_then(|_| SwingTwist::twist_axis(fa, fb)),
        }
    }

    /// The angular impulse `Jᵀλ` (N·m·s, world) of the limit rows' impulses in `state` and the point impulse
    /// (N·s) each carries with it ([`PivotAnglePart`]), for a warm start at the pivot of `point`.
    #[inline]
    pub(crate) fn warm_impulses(
        &self,
        pair: &BodyPair,
        point: &PointPart,
        state: &JointState,
    ) -> (Vec3, Vec3) {
        let mut twist = Vec3::ZERO;
        let mut linear = Vec3::ZERO;
        let rows = [
            self.swing.map(|(_, axis)| (axis, state.axial_impulse)),
            self.twist_axis
                .map(|axis| (axis, state.lower_impulse + state.upper_impulse)),
        ];
        for (axis, impulse) in rows.into_iter().flatten() {
            if impulse != 0.0 {
                twist += axis * impulse;
                linear += PivotAnglePart::new(pair, point, axis).point_impulse() * impulse;
            }
        }
        (twist, linear)
    }
}

/// Swing–twist limits ready for the substeps.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct PreparedLimits {
    limits: SwingTwistLimits,
    /// The soft limits' coefficients in frequency form (the stiffness form is computed per row).
    softness: Softness,
    /// `Ċ` of the swing row at the start of the step (rad/s; positive while the swing grows).
    swing_rate: f32,
    /// `θ̇` at the start of the step (rad/s).
    twist_rate: f32,
    /// Whether the swing, lower twist and upper twist rows pushed in any pass of the step (for restitution).
    acted: [bool; 3],
    /// The limit rows the last build of the direct rows pushed after the point rows
    /// ([`PreparedLimits::push_direct_rows`]).
    direct: DirectLimitRows,
}

/// Which limit rows a build of a ball joint's direct rows pushed after its point rows, in that order: the
/// swing row, and the twist row of the bound nearer the twist angle (a lower bound pushed as an upper one,
/// its row and error negated).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
struct DirectLimitRows {
    swing: bool,
    twist: Option<Side>,
}

impl PreparedLimits {
    /// The limits' description.
    pub(crate) fn limits(&self) -> &SwingTwistLimits {
        &self.limits
    }

    /// Whether the limits are solved with the point rows when the joint is on a directly solved path or
    /// graph ([`PreparedLimits::push_direct_rows`]): rigid ones are; soft ones, whose rows are springs
    /// outside the limits and absent inside, stay with [`PreparedLimits::solve`].
    pub(crate) fn is_direct(&self) -> bool {
        self.limits.softness.is_none()
    }

    /// The limit rows for the direct solve of the joint's rows ([`crate::path`]), pushed into `out` after
    /// the point rows at the frames `frames` (world), about the pivot of `point` (built with its effective
    /// mass) with the anchors' separation `d` (m): the swing row and the twist row of the nearer bound, each
    /// one-sided (`λ ≤ 0`) on its pivot row ([`PivotAnglePart::direct_row`]) with the error of that row,
    /// `C + P·d`. In the system while the limit is reached or about to be within the substep
    /// (speculative inside, as [`PreparedLimits::solve`]'s rows), released by the active set where it
    /// would pull.
    pub(crate) fn push_direct_rows(
        &mut self,
        pair: &BodyPair,
        point: &PointPart,
        d: Vec3,
        frames: (Quat, Quat),
        stage: &Stage,
        out: &mut JointRows,
    ) {
        let rows = LimitRows::new(&self.limits, frames);
        let mut pushed = DirectLimitRows::default();
        let mut push = |axis: Vec3, c: f32| {
            let part = PivotAnglePart::new(pair, point, axis);
            let c = c + part.point_impulse().dot(d);
            let rule = TargetRule::UpperLimit;
            let row = part
                .direct_row(axis, rule.target(c, stage))
                .clamped(f32::NEG_INFINITY, 0.0);
            out.push(row, c, rule);
        };
        if let Some((c, axis)) = rows.swing {
            push(axis, c);
            pushed.swing = true;
        }
        if let (Some(range), Some(axis)) = (self.limits.twist, rows.twist_axis) {
            let (c_lower, c_upper) = (rows.twist - range.lower(), rows.twist - range.upper());
            if c_lower < -c_upper {
                push(-axis, -c_lower);
                pushed.twist = Some(Side::Lower);
            } else {
                push(axis, c_upper);
                pushed.twist = Some(Side::Upper);
            }
        }
        self.direct = pushed;
    }

    /// The accumulated impulses of the limit rows [`PreparedLimits::push_direct_rows`] pushed last, in row
    /// order (a lower twist bound's negated, as its row is), and how many there are.
    pub(crate) fn direct_impulses(&self, state: &JointState) -> ([f32; 2], usize) {
        let mut out = [0.0; 2];
        let mut count = 0;
        if self.direct.swing {
            out[0] = state.axial_impulse;
            count = 1;
        }
        if let Some(side) = self.direct.twist {
            out[count] = match side {
                Side::Lower => -state.lower_impulse,
                Side::Upper => state.upper_impulse,
            };
            count += 1;
        }
        (out, count)
    }

    /// Writes the impulses `lambda` a direct solve gave the limit rows [`PreparedLimits::push_direct_rows`]
    /// pushed last (in row order) back into `state`; the twist bound not pushed holds none.
    pub(crate) fn store_direct_impulses(&mut self, state: &mut JointState, lambda: &[f32]) {
        let mut rows = lambda.iter().copied();
        if self.direct.swing {
            state.axial_impulse = rows.next().unwrap_or(0.0);
            self.acted[0] |= state.axial_impulse != 0.0;
        }
        if let Some(side) = self.direct.twist {
            let impulse = rows.next().unwrap_or(0.0);
            (state.lower_impulse, state.upper_impulse) = match side {
                Side::Lower => (-impulse, 0.0),
                Side::Upper => (0.0, impulse),
            };
            self.acted[1] |= state.lower_impulse != 0.0;
            self.acted[2] |= state.upper_impulse != 0.0;
        }
    }

    /// The largest angle (rad) by which frames `frames` (world) are past the limits: the swing row's error
    /// past the cone, the twist past its range; 0 within them.
    pub(crate) fn excess(&self, frames: (Quat, Quat)) -> f32 {
        let rows = LimitRows::new(&self.limits, frames);
        let swing = rows.swing.map_or(0.0, |(c, _)| c.max(0.0));
        let twist = match (self.limits.twist, rows.twist_axis) {
            (Some(range), Some(_)) => (range.lower() - rows.twist)
                .max(rows.twist - range.upper())
                .max(0.0),
            _ => 0.0,
        };
        swing.max(twist)
    }

    /// Stages *solve* and *relax*: the twist rows, then the swing row, at the frames `frames` (world), each
    /// about the pivot of `point`.
    pub(crate) fn solve(
        &mut self,
        pair: &BodyPair,
        point: &PointPart,
        frames: (Quat, Quat),
        state: &mut JointState,
        a: &mut SolverBody,
        b: &mut SolverBody,
        stage: &Stage,
    ) {
        if self.limits.softness.is_some() && stage.bias == Bias::Off {
            return;
        }
        let rows = LimitRows::new(&self.limits, frames);
        if let (Some(range), Some(axis)) = (self.limits.twist, rows.twist_axis) {
            let part = PivotAnglePart::new(pair, point, axis);
            let c_lower = rows.twist - range.lower();
            self.limit(
                &part,
                pair,
                a,
                b,
                c_lower,
                Side::Lower,
                stage,
                &mut state.lower_impulse,
            );
            self.acted[1] |= state.lower_impulse != 0.0;
            let c_upper = rows.twist - range.upper();
            self.limit(
                &part,
                pair,
                a,
                b,
                c_upper,
                Side::Upper,
                stage,
                &mut state.upper_impulse,
            );
            self.acted[2] |= state.upper_impulse != 0.0;
        }
        if let Some((c, axis)) = rows.swing {
            let part = PivotAnglePart::new(pair, point, axis);
            self.limit(
                &part,
                pair,
                a,
                b,
                c,
                Side::Upper,
                stage,
                &mut state.axial_impulse,
            );
            self.acted[0] |= state.axial_impulse != 0.0;
        }
    }

    /// One limit row on `part` with error `c`: rigid (speculative inside) or soft (inactive inside).
    fn limit(
        &self,
        part: &PivotAnglePart,
        pair: &BodyPair,
        a: &mut SolverBody,
        b: &mut SolverBody,
        c: f32,
        side: Side,
        stage: &Stage,
        accumulated: &mut f32,
    ) {
        let (lower, upper) = match side {
            Side::Lower => (0.0, f32::INFINITY),
            Side::Upper => (f32::NEG_INFINITY, 0.0),
        };
        let target = match (self.limits.softness, side) {
            (None, Side::Lower) => {
                RowTarget::lower_limit(c, stage.bias, stage.joint_softness, stage.inv_h)
            }
            (None, Side::Upper) => {
                RowTarget::upper_limit(c, stage.bias, stage.joint_softness, stage.inv_h)
            }
            (Some(spring), _) => {
                let violated = match side {
                    Side::Lower => c < 0.0,
                    Side::Upper => c > 0.0,
                };
                if !violated {
                    // Inactive: whatever was warm-started is taken back.
                    part.apply_impulse(pair, a, b, -*accumulated);
                    *accumulated = 0.0;
                    return;
                }
                let softness = if spring.depends_on_mass() {
                    spring.softness(part.effective_mass(), stage.h)
                } else {
                    self.softness
                };
                RowTarget::spring(c, softness)
            }
        };
        part.solve_clamped(pair, a, b, target, accumulated, lower, upper);
    }

    /// Stage *restitution*: each limit that acted during the step and was approached faster than the
    /// restitution threshold at the start of the step gets `Ċ = −e·Ċ⁻`.
    pub(crate) fn apply_restitution(
        &self,
        pair: &BodyPair,
        point: &PointPart,
        frames: (Quat, Quat),
        state: &mut JointState,
        a: &mut SolverBody,
        b: &mut SolverBody,
        ctx: &StepContext,
    ) {
        let e = self.limits.restitution;
        if e == 0.0 {
            return;
        }
        let rows = LimitRows::new(&self.limits, frames);
        let threshold = ctx.restitution_threshold;
        if let Some((_, axis)) = rows.swing
            && self.acted[0]
            && self.swing_rate > threshold
        {
            let target = RowTarget::speed(-e * self.swing_rate);
            PivotAnglePart::new(pair, point, axis).solve_clamped(
                pair,
                a,
                b,
                target,
                &mut state.axial_impulse,
                f32::NEG_INFINITY,
                0.0,
            );
        }
        if let Some(axis) = rows.twist_axis {
            let part = PivotAnglePart::new(pair, point, axis);
            let target = RowTarget::speed(-e * self.twist_rate);
            if self.acted[2] && self.twist_rate > threshold {
                part.solve_clamped(
                    pair,
                    a,
                    b,
                    target,
                    &mut state.upper_impulse,
                    f32::NEG_INFINITY,
                    0.0,
                );
            }
            if self.acted[1] && -self.twist_rate > threshold {
                part.solve_clamped(
                    pair,
                    a,
                    b,
                    target,
                    &mut state.lower_impulse,
                    0.0,
                    f32::INFINITY,
                );
            }
        }
    }
}
