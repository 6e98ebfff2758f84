//! The row format of the path solver: one Jacobian row ([`Row`]: a side per body, a target, impulse
//! bounds) and the rows one joint gives a pass ([`JointRows`]), with each row's position error and the rule
//! its target follows from ([`TargetRule`]). Joints write their rows here in *prepare*-time geometry at every
//! pass that builds them (solve, relax, projection); the rest of the path solver reads them.

use crate::part::RowTarget;
use crate::stage::Stage;
use rebound_dynamics::SolverBody;
use rebound_math::quat::{RotationIntegrator, integrate_rotation};
use rebound_math::{Mat3, Vec3};

/// The most rows one joint gives the direct solve: a fixed joint's 3 point rows and 3 rotation rows, a
/// limited hinge's 3 point rows, 2 alignment rows and its limit row.
pub(crate) const MAX_ROWS: usize = 6;

/// The precision of the path solve.
pub(crate) type Real = f64;

/// One body's side of a row's Jacobian: `Ċ` gains `linear·v + angular·ω`.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub(crate) struct Side {
    pub linear: Vec3,
    pub angular: Vec3,
}

/// A body's inverse mass (1/kg) and world inverse inertia (1/(kg·m²)) at the start of the step.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub(crate) struct InvMass {
    pub mass: f32,
    pub inertia: Mat3,
}

/// How a row's target follows from its position error `C` (m or rad) and the stage, so that a pass at an
/// unchanged pose recomputes the targets alone ([`JointRows::retarget`]) from the errors stored when the rows
/// were built — with the very functions that built them, so the targets are the same bits.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub(crate) enum TargetRule {
    /// An equality row (a rod, the point rows of ball joints and hinges, a hinge's alignment rows):
    /// [`RowTarget::equality`], `bias = bias_rate·C` with the joint softness in the bias pass, `Ċ = 0`, rigid,
    /// in the relax pass.
    Equality,
    /// An upper limit (a rope's length, a limit's upper bound): [`RowTarget::upper_limit`], speculative
    /// (`bias = C·inv_h`, rigid) while `C < 0`.
    UpperLimit,
    /// A lower limit (a hinge's lower bound): [`RowTarget::lower_limit`], speculative while `C > 0`.
    LowerLimit,
}

impl TargetRule {
    /// The target of a row with position error `c` in a pass of `stage`.
    #[inline]
    pub fn target(self, c: f32, stage: &Stage) -> RowTarget {
        match self {
            Self::Equality => RowTarget::equality(c, stage.bias, stage.joint_softness),
            Self::UpperLimit => {
                RowTarget::upper_limit(c, stage.bias, stage.joint_softness, stage.inv_h)
            }
            Self::LowerLimit => {
                RowTarget::lower_limit(c, stage.bias, stage.joint_softness, stage.inv_h)
            }
        }
    }
}

impl Side {
    /// `J_side·M⁻¹·other_sideᵀ`: how an impulse on `other` changes this row's `Ċ` through one body, with
    /// `other`'s angular part already turned by the body's inverse inertia (`turned = I⁻¹·other.angular`,
    /// see [`JointRows::turned`]): `m⁻¹·(linear·other.linear) + angular·turned`.
    #[inline]
    pub(super) fn coupling_turned(&self, m: &InvMass, other: &Side, turned: Vec3) -> f32 {
        self.linear.dot(other.linear) * m.mass + self.angular.dot(turned)
    }

    /// The velocity change an impulse `lambda` along this side gives the body (`turned = I⁻¹·angular`):
    /// `Δv = m⁻¹·linear·λ`, `Δω = I⁻¹·angular·λ`.
    #[inline]
    pub(super) fn apply(&self, m: &InvMass, turned: Vec3, body: &mut SolverBody, lambda: f32) {
        body.linear_velocity += self.linear * (m.mass * lambda);
        body.angular_velocity += turned * lambda;
    }

    /// The displacement a position impulse `p` (kg·m) along this side gives the body (`turned =
    /// I⁻¹·angular`): `Δx = M⁻¹·Jᵀ·p`, the rotation as a small rotation vector.
    #[inline]
    pub(super) fn displace(&self, m: &InvMass, turned: Vec3, body: &mut SolverBody, p: f32) {
        displace_body(body, self.linear * (m.mass * p), turned * p);
    }

    #[inline]
    pub(super) fn velocity(&self, body: &SolverBody) -> f32 {
        self.linear.dot(body.linear_velocity) + self.angular.dot(body.angular_velocity)
    }
}

/// One row: its Jacobian on bodies A and B, what it drives toward, and its impulse bounds.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub(crate) struct Row {
    pub a: Side,
    pub b: Side,
    pub target: RowTarget,
    #[cfg_attr(feature = "serde", serde(with = "crate::bounds::unbounded_below"))]
    pub lower: f32,
    #[cfg_attr(feature = "serde", serde(with = "crate::bounds::unbounded"))]
    pub upper: f32,
}

impl Row {
    /// The row with Jacobian sides `a` (body A's) and `b` (body B's) and target `target`, unbounded. The
    /// parts state the sides ([`crate::part`]: each its Jacobian once).
    #[inline]
    pub fn new([a, b]: [Side; 2], target: RowTarget) -> Self {
        Self {
            a,
            b,
            target,
            lower: f32::NEG_INFINITY,
            upper: f32::INFINITY,
        }
    }

    /// The row with impulse bounds `[lower, upper]`.
    #[inline]
    pub fn clamped(mut self, lower: f32, upper: f32) -> Self {
        self.lower = lower;
        self.upper = upper;
        self
    }

    /// Whether an impulse bound is 0 (a rope, a limit): the row can leave the system, and be released.
    #[inline]
    pub(super) fn is_bounded_at_zero(&self) -> bool {
        self.upper == 0.0 || self.lower == 0.0
    }

    /// `Ċ` (m/s or rad/s).
    #[inline]
    pub(super) fn velocity(&self, a: &SolverBody, b: &SolverBody) -> f32 {
        self.a.velocity(a) + self.b.velocity(b)
    }
}

/// `J·M⁻¹·Jᵀ` of `row` with itself for bodies of inverse masses `mass_a`, `mass_b`, with `turned` its
/// `[I_a⁻¹·J_a,angular, I_b⁻¹·J_b,angular]` ([`JointRows::turned`]).
#[inline]
pub(super) fn row_self_coupling(
    row: &Row,
    turned: [Vec3; 2],
    mass_a: &InvMass,
    mass_b: &InvMass,
) -> f32 {
    let [ta, tb] = turned;
    row.a.coupling_turned(mass_a, &row.a, ta) + row.b.coupling_turned(mass_b, &row.b, tb)
}

/// The rows one joint contributes to a pass, with its bodies' inverse masses.
///
/// Laid out in the order a pass reads it (`repr(C)`: the compiler would otherwise order fields by alignment):
/// the masses, the per-row scalars, the turned vectors, then the rows. A one-row link (a rope of a chain)
/// reads nothing after its first row; see [`Link`] for why that matters.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[repr(C)]
pub(crate) struct JointRows {
    pub count: usize,
    /// Whether a row bounded at 0 (a rope, a limit) may be among the rows: set when one is pushed, cleared
    /// when the rows are (a hinge's or ball joint's equality rows can never be released, and the checks for
    /// a release skip them).
    pub may_release: bool,
    pub mass_a: InvMass,
    pub mass_b: InvMass,
    /// `J·M⁻¹·Jᵀ` of each row bounded at 0 (a rope, a limit), computed once when the row is pushed: the
    /// activation of every pass at the pose reads it ([`Link::activate`]); `None` for the other rows, whose
    /// value is computed where it is needed ([`JointRows::self_coupling`]).
    pub(super) bounded_couplings: [Option<f32>; MAX_ROWS],
    /// Each row's position error `C` (m or rad) and how its target follows from it (see [`TargetRule`]).
    pub(super) errors: [(f32, TargetRule); MAX_ROWS],
    /// `[I_a⁻¹·J_a,angular, I_b⁻¹·J_b,angular]` of each row, turned once when the row is pushed (with the
    /// masses given to [`JointRows::new`] or [`Link::reset`], which no row outlives).
    pub(super) turned: [[Vec3; 2]; MAX_ROWS],
    pub rows: [Row; MAX_ROWS],
}

impl JointRows {
    /// No rows yet, for a joint whose bodies have the given inverse masses.
    pub fn new(mass_a: InvMass, mass_b: InvMass) -> Self {
        Self {
            rows: [Row::new([Side::default(); 2], RowTarget::speed(0.0)); MAX_ROWS],
            turned: [[Vec3::ZERO; 2]; MAX_ROWS],
            errors: [(0.0, TargetRule::Equality); MAX_ROWS],
            bounded_couplings: [None; MAX_ROWS],
            count: 0,
            may_release: false,
            mass_a,
            mass_b,
        }
    }

    /// Adds a row (ignored past [`MAX_ROWS`]) whose target is `rule`'s for the position error `c` (the
    /// row's target must be `rule.target(c, stage)` of the pass's stage), and turns its angular parts by the
    /// inverse inertias (and, for a row bounded at 0, computes its `J·M⁻¹·Jᵀ` once). Inlined so that the
    /// row is written where it goes rather than built and copied (every row of every rebuilt link).
    #[inline(always)]
    pub fn push(&mut self, row: Row, c: f32, rule: TargetRule) {
        let turned = [
            self.mass_a.inertia * row.a.angular,
            self.mass_b.inertia * row.b.angular,
        ];
        self.push_turned(row, c, rule, turned);
    }

    /// [`JointRows::push`] with the row's turned angular parts `[I_a⁻¹·J_a,angular, I_b⁻¹·J_b,angular]`.
    #[inline]
    pub(crate) fn push_turned(
        &mut self,
        row: Row,
        c: f32,
        rule: TargetRule,
        turned_parts: [Vec3; 2],
    ) {
        if let (Some(slot), Some(turned), Some(error), Some(coupling)) = (
            self.rows.get_mut(self.count),
            self.turned.get_mut(self.count),
            self.errors.get_mut(self.count),
            self.bounded_couplings.get_mut(self.count),
        ) {
            *slot = row;
            *error = (c, rule);
            *turned = turned_parts;
            *coupling = row
                .is_bounded_at_zero()
                .then(|| row_self_coupling(&row, *turned, &self.mass_a, &self.mass_b));
            self.may_release |= coupling.is_some();
            self.count += 1;
        }
    }

    /// Recomputes each row's target for a pass of `stage` from its stored position error: the rows of a pass
    /// at the pose they were built at, whose Jacobians and turned vectors are still those of the pose.
    pub fn retarget(&mut self, stage: &Stage) {
        for (row, &(c, rule)) in self.rows.iter_mut().zip(&self.errors).take(self.count) {
            row.target = rule.target(c, stage);
        }
    }

    /// `[I_a⁻¹·J_a,angular, I_b⁻¹·J_b,angular]` of row `k` (zero past the rows pushed).
    #[inline]
    pub(super) fn turned(&self, k: usize) -> [Vec3; 2] {
        self.turned.get(k).copied().unwrap_or([Vec3::ZERO; 2])
    }

    /// `J·M⁻¹·Jᵀ` of row `k` with itself (0 past the rows pushed): the value computed when a row bounded at 0
    /// was pushed, the same bits as computing it again.
    #[inline]
    pub(super) fn self_coupling(&self, k: usize) -> f32 {
        if k < self.count
            && let Some(&Some(coupling)) = self.bounded_couplings.get(k)
        {
            return coupling;
        }
        let Some(row) = self.rows.get(k) else {
            return 0.0;
        };
        row_self_coupling(row, self.turned(k), &self.mass_a, &self.mass_b)
    }

    /// Applies the impulse `lambda` along row `k` to both bodies.
    #[inline]
    pub(super) fn apply(&self, k: usize, a: &mut SolverBody, b: &mut SolverBody, lambda: f32) {
        if let (Some(row), true) = (self.rows.get(k), lambda != 0.0) {
            let [ta, tb] = self.turned(k);
            row.a.apply(&self.mass_a, ta, a, lambda);
            row.b.apply(&self.mass_b, tb, b, lambda);
        }
    }

    /// [`JointRows::apply`] of row 0, for a link known to have it.
    #[inline]
    pub(super) fn apply_first(&self, a: &mut SolverBody, b: &mut SolverBody, lambda: f32) {
        if lambda != 0.0 {
            let (row, [ta, tb]) = (&self.rows[0], self.turned[0]);
            row.a.apply(&self.mass_a, ta, a, lambda);
            row.b.apply(&self.mass_b, tb, b, lambda);
        }
    }

    /// Displaces both bodies by the position impulse `p` along row `k`.
    #[inline]
    pub(super) fn displace(&self, k: usize, a: &mut SolverBody, b: &mut SolverBody, p: f32) {
        if let Some(row) = self.rows.get(k) {
            let [ta, tb] = self.turned(k);
            row.a.displace(&self.mass_a, ta, a, p);
            row.b.displace(&self.mass_b, tb, b, p);
        }
    }

    /// Whether the rows, their turned vectors, errors and the masses are finite (the bounds not NaN) and the
    /// row count in range: what rows restored from a snapshot must be.
    pub fn is_valid(&self) -> bool {
        let finite_side = |s: &Side| s.linear.is_finite() && s.angular.is_finite();
        let finite_mass = |m: &InvMass| m.mass.is_finite() && m.inertia.is_finite();
        self.count <= MAX_ROWS
            && finite_mass(&self.mass_a)
            && finite_mass(&self.mass_b)
            && self.rows.iter().all(|row| {
                finite_side(&row.a)
                    && finite_side(&row.b)
                    && row.target.bias.is_finite()
                    && !row.lower.is_nan()
                    && !row.upper.is_nan()
            })
            && self.turned.iter().flatten().all(|v| v.is_finite())
            && self.errors.iter().all(|(c, _)| c.is_finite())
            && self
                .bounded_couplings
                .iter()
                .flatten()
                .all(|c| c.is_finite())
    }

    /// The rows in use.
    pub fn rows(&self) -> &[Row] {
        &self.rows[..self.count.min(MAX_ROWS)]
    }

    /// The largest violation among rows whose biases are their position errors (m or rad): `|C|` of an
    /// equality row, `C` of a stretched rope (`C > 0` past an upper bound of 0), 0 for a slack one.
    pub fn violation(&self) -> f32 {
        self.rows()
            .iter()
            .map(|row| row_violation(row.target.bias, row.lower, row.upper))
            .fold(0.0, f32::max)
    }
}

/// How far a row with position error `c` (m or rad) and impulse bounds `[lower, upper]` is violated: `|C|`
/// for an equality, `C` past an upper bound of 0 (a stretched rope), `−C` past a lower bound of 0, and 0 for
/// a row bounded at 0 on its allowed side (a slack rope).
#[inline]
pub(super) fn row_violation(c: f32, lower: f32, upper: f32) -> f32 {
    if upper == 0.0 {
        c.max(0.0)
    } else if lower == 0.0 {
        (-c).max(0.0)
    } else {
        c.abs()
    }
}

/// [`JointRows::violation`] of rows that are all equalities (no bound at 0: a ball joint's, a hinge's), from
/// their position errors and target rules alone: the largest `|bias|` of the targets `rule.target(C, stage)`
/// the rows would be built with, in row order — the same bits, without building the rows.
pub(crate) fn equality_violation(errors: &[(f32, TargetRule)], stage: &Stage) -> f32 {
    errors
        .iter()
        .map(|&(c, rule)| {
            row_violation(rule.target(c, stage).bias, f32::NEG_INFINITY, f32::INFINITY)
        })
        .fold(0.0, f32::max)
}

/// `[x, 0, …, 0]`: the values of a one-row joint (a rope, a rod) in row order.
#[inline(always)]
pub(crate) fn one_row<T: Copy + Default>(x: T) -> [T; MAX_ROWS] {
    let mut out = [T::default(); MAX_ROWS];
    out[0] = x;
    out
}

/// Moves `body` by `shift` (m) and turns it by the small rotation vector `turn` (rad): a position impulse's
/// `M⁻¹·Jᵀ·p`, as [`Side::displace`] moves a body for one row.
#[inline]
pub(super) fn displace_body(body: &mut SolverBody, shift: Vec3, turn: Vec3) {
    body.delta_position += shift;
    if turn != Vec3::ZERO {
        body.delta_rotation = integrate_rotation(
            body.delta_rotation,
            turn,
            1.0,
            RotationIntegrator::FirstOrder,
        );
    }
}
