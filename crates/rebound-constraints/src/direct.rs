//! The direct solve of joint chains: the equality rows of a path of joints solved together, exactly, instead
//! of one joint after another.
//!
//! # Why
//!
//! A soft row settles where its spring force balances the load: `C = λ/(h²·m_eff·ω²)` per substep, with
//! `m_eff` the effective mass *of that row alone*. In a chain of light links carrying a heavy load — a rope of
//! 500 balls swinging, a bridge deck under its own weight — the load is many times the link mass, and solved
//! link by link every link stretches by `load / (m_link·ω²)`: 23 % for the SCENES.md chain. Solving the rows
//! of the whole path as one system (`K·x = Ċ + bias`, `K = J·M⁻¹·Jᵀ`) gives each row the effective mass of
//! the chain behind it, so the stretch no longer grows with the load (Baraff, "Linear-Time Dynamics using
//! Lagrange Multipliers", SIGGRAPH 1996; here specialised to paths, where `K` is block-tridiagonal).
//!
//! # How
//!
//! A path is a sequence of joints in which each consecutive pair shares one dynamic body and every inner
//! body belongs to exactly two joints of the path (fixed bodies couple nothing, so a deck hung between two
//! anchors is a path). With `Bᵢ` the diagonal blocks (`J·M⁻¹·Jᵀ` of joint `i`'s rows over both its bodies)
//! and `Cᵢ` the coupling of joint `i` to joint `i + 1` through their shared body, the block Thomas algorithm
//!
//! ```text
//! S₁ = B₁,                      C'₁ = S₁⁻¹·C₁,   r'₁ = S₁⁻¹·r₁
//! Sᵢ = Bᵢ − Cᵢ₋₁ᵀ·C'ᵢ₋₁,        C'ᵢ = Sᵢ⁻¹·Cᵢ,   r'ᵢ = Sᵢ⁻¹·(rᵢ − Cᵢ₋₁ᵀ·r'ᵢ₋₁)
//! xₙ = r'ₙ,                     xᵢ = r'ᵢ − C'ᵢ·xᵢ₊₁
//! ```
//!
//! solves `K·x = r` in O(n). The soft step of all rows at once takes `r = mass_scale∘(Ċ + bias) +
//! impulse_scale∘(K·λ)` row by row and `Δλ = −x` (for one row this is exactly the Gauss–Seidel row update of
//! [`crate::part::solve_row`]; see `solve_path` for why not each row's soft step from one solve), clamped
//! to the bounds. A rope that is slack and not closing its slack this substep is left out of the system (its
//! row is released); after a solve, a rope the solution would make push is dropped, a rope left out that it
//! would stretch is added, and the system solved again (up to 4 rounds), so slack links never push and links
//! left out are not pulled past their length. The sweep runs in f64 (a 500-link chain's `K` has a condition
//! number near 10⁵), each row's diagonal gets a 10⁻⁶ relative regularisation and a vanishing pivot gives 0 —
//! a bridge hung from two anchors has redundant rows and a singular `K`. A path of one-row joints (a rope
//! chain) takes a scalar sweep.
//!
//! Each `Sᵢ` is symmetric positive semi-definite (a Schur complement of `K`), so it is factorised as
//! `L·D·Lᵀ` without pivoting (`ldl_factor`), and the sweep is carried in the factors: `Cᵢ₋₁ᵀ·C'ᵢ₋₁ =
//! Wᵀ·D⁻¹·W` with `W = L⁻¹·Cᵢ₋₁`, symmetric, so only its upper triangle is formed (see `block_sweep`). The
//! blocks are as wide as the path's widest joint (5 × 5 for hinges, 3 × 3 for ball joints), with fixed loop
//! bounds; rows of a narrower link, and rows not in the system, are zero rows and columns, whose pivots
//! vanish and whose unknowns are 0. `Bᵢ` is built from its upper triangle, with each row's `I⁻¹·J_angular`
//! turned once when the row is built (`JointRows::turned`), shared by `Bᵢ`, `Cᵢ` and the impulses' updates.
//!
//! # Positions
//!
//! The same machinery projects positions after the substeps (`JointSolver::project_positions`): with the
//! rows' biases set to their position errors `C`, the solve of `K·x = C` moves the bodies by `−M⁻¹·Jᵀ·x`
//! (`project_rows` is the one-joint Gauss–Seidel version used after it). Where that step kinks a pulled,
//! curved chain, it is solved again with each rope and rod stiffened against turning by two compliant rows
//! across it (`Link::stiffen`: the geometric stiffness, which makes a rope chain a path of 3-row links for
//! the block sweep). Derivations and measurements are in `docs/physics.md`, "Chains solved directly".
//!
//! # Rows and factorisations kept between passes
//!
//! A step runs `solve` (bias on), the world integrates positions, `relax` (bias off), per substep, then the
//! projection. Between a relax pass and the next substep's solve pass (and the projection after the last
//! one) only velocities change, so both passes see the same Jacobians and the same `K`. A `Link` therefore
//! stays with its joint from pass to pass (one per path member, in the solver) and records the pose its rows
//! were built at (`PoseKey`: the bits of both bodies' `delta_position` and `delta_rotation`, all that row
//! building reads of the bodies). At an unchanged pose the pass keeps the rows — Jacobians, turned vectors
//! and position errors `C` — and recomputes only the targets, which depend on the stage, from the stored
//! `C` with the functions that built them (`TargetRule`); any other pose, and the first pass of a step,
//! builds them again. The sweep then keeps each link's factorisation (`B`, `C`, `L`, `D⁻¹`, `W`, `V`) while
//! it and its neighbours have the rows and the rows in the system (`FactorKey`) it was made for — a rope
//! joining or leaving the system refactorises from the link before it on — and sweeps only the right-hand
//! side. Everything kept is what the same operations on the same values would give again, so a pass gives
//! the bits it gave when it rebuilt everything. Within a pass, an active-set round that changes the system
//! from some link on sweeps forward again only from the link before it (`Resume`), and a rope's or rod's warm
//! start at the pose its link's row was built at applies the impulse along that row
//! (`Link::warm_start_row`).
//!
//! # Rows carried through the step
//!
//! A hinge's rows (3 point rows, 2 alignment rows) have Jacobians that depend on its bodies' rotations alone.
//! A velocity pass at a new pose therefore keeps a hinge's rows, and the factorisation, while neither body
//! has turned by more than `CARRY_ANGLE` (0.01 rad) since they were built this step, and carries only the
//! position errors to the new pose, to first order: `C = C₀ + J·Δ` (`Link::carry`). A deck whose planks
//! swing slowly then factorises once per step instead of at every pose (five times: the first solve pass
//! and each relax pass). Exact errors with the kept rows would not do: see `Link::carry`. The projection
//! always builds its rows at the pose (its Newton steps need the pose's Jacobians). Ball joints are not
//! carried: at the whip of the SCENES.md `chain_spherical` (balls turning with their links) carrying at
//! 0.01 rad let the worst link stretch 4.8 % against 0.045 %.
//!
//! The rows outlive the step, too. The last relax pass of a step builds every hinge's rows at the step's
//! final pose for the projection; the next step's passes carry those rows (and their factorisation) from
//! there instead of building them again at the step's first pass, measuring the turn and the displacement
//! in world terms (`BuiltAt`: both joint frames and the vector between the centres of mass at the build).
//! A path keeps its rows only whole (same joints, same bodies, same inverse masses) and every link of it
//! keeps the inverse inertias its rows were turned with until the last relax pass builds them all again:
//! `K` must use one inverse inertia per body — a link built with the new step's next to links kept with
//! the last step's made the SCENES.md bridge's singular `K` inconsistent, and the regularisation blew it up
//! within 18 steps. The kept rows are state: a snapshot holds them ([`crate::KeptRows`]).

#![allow(
    clippy::needless_range_loop,
    reason = "dense block algebra (Thomas sweep, LDLᵀ factorisation) reads as the formulas with indices"
)]

use crate::pair::{BodyPair, Distance};
use crate::part::{RowTarget, block_target, clamp_impulse, rotation_error};
use crate::solver::Stage;
use rebound_dynamics::{Softness, SolverBody};
use rebound_math::quat::{RotationIntegrator, integrate_rotation};
use rebound_math::{Mat3, Mat4, Quat, Vec3, Vec4};

/// The most rows one joint gives the direct solve: a hinge's 3 point rows and 2 alignment rows.
pub(crate) const MAX_ROWS: usize = 5;

/// A `MAX_ROWS × MAX_ROWS` block, row-major; only the top-left `k × k` is used.
pub(crate) type Block = [[Real; MAX_ROWS]; MAX_ROWS];

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
    /// A component of an equality block (the point rows of ball joints and hinges): [`block_target`],
    /// `bias = bias_rate·C` with the joint softness in the bias pass, `bias = 0`, rigid, in the relax pass.
    Block,
    /// An equality row (a rod, a hinge's alignment rows): [`RowTarget::equality`].
    Equality,
    /// A rope's upper limit: [`RowTarget::upper_limit`], speculative (`bias = C·inv_h`, rigid) while slack.
    UpperLimit,
}

impl TargetRule {
    /// The target of a row with position error `c` in a pass of `stage`.
    #[inline]
    pub fn target(self, c: f32, stage: &Stage) -> RowTarget {
        match self {
            Self::Block => {
                let (bias, softness) =
                    block_target(Vec3::new(c, 0.0, 0.0), stage.bias, stage.joint_softness);
                RowTarget {
                    bias: bias.x,
                    softness,
                }
            }
            Self::Equality => RowTarget::equality(c, stage.bias, stage.joint_softness),
            Self::UpperLimit => {
                RowTarget::upper_limit(c, stage.bias, stage.joint_softness, stage.inv_h)
            }
        }
    }
}

/// The bits of what a link's rows are built from that changes within a step: both bodies' displacement and
/// rotation since the step began (`SolverBody::delta_position`, `delta_rotation`; the anchors, distance and
/// frames of [`crate::BodyPair`] read nothing else of the bodies). Equal keys mean the rows would be built
/// again bit for bit; any difference, even of a zero's sign, means they are built again.
#[derive(Debug, Clone, Copy, Eq)]
pub(crate) struct PoseKey([u32; 14]);

/// Word by word, inline: the derived comparison of the 56 bytes called the C library's `memcmp`
/// (a path compares a key per link and pass — 10 % of the SCENES.md chain's wall time went to the calls).
impl PartialEq for PoseKey {
    #[inline]
    fn eq(&self, other: &Self) -> bool {
        self.0.iter().zip(&other.0).all(|(a, b)| a == b)
    }
}

impl PoseKey {
    /// The key of bodies `a` and `b`'s current pose.
    #[inline]
    pub fn of(a: &SolverBody, b: &SolverBody) -> Self {
        let mut key = [0; 14];
        let fields = [
            a.delta_position.x,
            a.delta_position.y,
            a.delta_position.z,
            a.delta_rotation.x,
            a.delta_rotation.y,
            a.delta_rotation.z,
            a.delta_rotation.w,
            b.delta_position.x,
            b.delta_position.y,
            b.delta_position.z,
            b.delta_rotation.x,
            b.delta_rotation.y,
            b.delta_rotation.z,
            b.delta_rotation.w,
        ];
        for (key, field) in key.iter_mut().zip(fields) {
            *key = field.to_bits();
        }
        Self(key)
    }
}

/// How far (rad) either body of a hinge on a path may turn within a step before a velocity pass builds the
/// hinge's rows again instead of carrying them ([`Link::carry`]). The Jacobians of a hinge's rows depend on
/// the bodies' rotations alone, and a row turned by `θ` acts up to `θ` off its direction. Measured on the
/// SCENES.md bridge, with the projection switched off to see the velocity passes alone: worst joint gap
/// 5.02 mm when every pass builds its rows, 5.02 mm at 0.001 rad, 4.98 mm at 0.01, 18 cm at 0.05 and
/// 92 cm at 0.2 (with the projection: 0.07 mm built, 0.11 mm carried at 0.01).
pub(crate) const CARRY_ANGLE: f32 = 0.01;

/// What a link's stored factorisation was made for: the block width of the sweep (1 for the scalar sweep),
/// the rows in the system and the sharing with the next link. Together with unchanged rows (the key is
/// dropped when they are built again) and the same key for every link of the path, the factorisation would
/// come out the same bits, so [`solve_path`] keeps it.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
struct FactorKey {
    width: usize,
    active: [bool; MAX_ROWS],
    shared: Option<(bool, bool)>,
}

impl FactorKey {
    /// The key of `link`'s current rows in the system, for a sweep of blocks `width` wide.
    #[inline]
    fn of(link: &Link, width: usize) -> Self {
        Self {
            width,
            active: link.active,
            shared: link.shared_with_next,
        }
    }
}

impl Side {
    /// `J_side·M⁻¹·other_sideᵀ`: how an impulse on `other` changes this row's `Ċ` through one body, with
    /// `other`'s angular part already turned by the body's inverse inertia (`turned = I⁻¹·other.angular`,
    /// see [`JointRows::turned`]): `m⁻¹·(linear·other.linear) + angular·turned`.
    #[inline]
    fn coupling_turned(&self, m: &InvMass, other: &Side, turned: Vec3) -> f32 {
        self.linear.dot(other.linear) * m.mass + self.angular.dot(turned)
    }

    /// The velocity change an impulse `lambda` along this side gives the body (`turned = I⁻¹·angular`):
    /// `Δv = m⁻¹·linear·λ`, `Δω = I⁻¹·angular·λ`.
    #[inline]
    fn apply(&self, m: &InvMass, turned: Vec3, body: &mut SolverBody, lambda: f32) {
        body.linear_velocity += self.linear * (m.mass * lambda);
        body.angular_velocity += turned * lambda;
    }

    /// The displacement a position impulse `p` (kg·m) along this side gives the body (`turned =
    /// I⁻¹·angular`): `Δx = M⁻¹·Jᵀ·p`, the rotation as a small rotation vector.
    #[inline]
    fn displace(&self, m: &InvMass, turned: Vec3, body: &mut SolverBody, p: f32) {
        displace_body(body, self.linear * (m.mass * p), turned * p);
    }

    #[inline]
    fn velocity(&self, body: &SolverBody) -> f32 {
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
    #[cfg_attr(feature = "serde", serde(with = "crate::joint::unbounded_below"))]
    pub lower: f32,
    #[cfg_attr(feature = "serde", serde(with = "crate::joint::unbounded"))]
    pub upper: f32,
}

impl Row {
    /// A linear row along `axis` (unit, world) between anchors `r_a`, `r_b` (m, from each centre of mass):
    /// `Ċ = axis·(v_b + ω_b × r_b − v_a − ω_a × r_a)`.
    #[inline]
    pub fn linear(axis: Vec3, r_a: Vec3, r_b: Vec3, target: RowTarget) -> Self {
        Self {
            a: Side {
                linear: -axis,
                angular: -r_a.cross(axis),
            },
            b: Side {
                linear: axis,
                angular: r_b.cross(axis),
            },
            target,
            lower: f32::NEG_INFINITY,
            upper: f32::INFINITY,
        }
    }

    /// [`Row::linear`] between the two centres of mass (`r_a = r_b = 0`): no angular parts, without the cross
    /// products of zero lever arms.
    #[inline]
    pub fn between_centres(axis: Vec3, target: RowTarget) -> Self {
        Self {
            a: Side {
                linear: -axis,
                angular: Vec3::ZERO,
            },
            b: Side {
                linear: axis,
                angular: Vec3::ZERO,
            },
            target,
            lower: f32::NEG_INFINITY,
            upper: f32::INFINITY,
        }
    }

    /// An angular row about `axis` (world): `Ċ = axis·(ω_b − ω_a)`.
    #[inline]
    pub fn angular(axis: Vec3, target: RowTarget) -> Self {
        Self {
            a: Side {
                linear: Vec3::ZERO,
                angular: -axis,
            },
            b: Side {
                linear: Vec3::ZERO,
                angular: axis,
            },
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
    fn is_bounded_at_zero(&self) -> bool {
        self.upper == 0.0 || self.lower == 0.0
    }

    /// `Ċ` (m/s or rad/s).
    #[inline]
    fn velocity(&self, a: &SolverBody, b: &SolverBody) -> f32 {
        self.a.velocity(a) + self.b.velocity(b)
    }
}

/// `J·M⁻¹·Jᵀ` of `row` with itself for bodies of inverse masses `mass_a`, `mass_b`, with `turned` its
/// `[I_a⁻¹·J_a,angular, I_b⁻¹·J_b,angular]` ([`JointRows::turned`]).
#[inline]
fn row_self_coupling(row: &Row, turned: [Vec3; 2], mass_a: &InvMass, mass_b: &InvMass) -> f32 {
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
    bounded_couplings: [Option<f32>; MAX_ROWS],
    /// Each row's position error `C` (m or rad) and how its target follows from it (see [`TargetRule`]).
    errors: [(f32, TargetRule); MAX_ROWS],
    /// `[I_a⁻¹·J_a,angular, I_b⁻¹·J_b,angular]` of each row, turned once when the row is pushed (with the
    /// masses given to [`JointRows::new`] or [`Link::reset`], which no row outlives).
    turned: [[Vec3; 2]; MAX_ROWS],
    pub rows: [Row; MAX_ROWS],
}

impl JointRows {
    /// No rows yet, for a joint whose bodies have the given inverse masses.
    pub fn new(mass_a: InvMass, mass_b: InvMass) -> Self {
        Self {
            rows: [Row::angular(Vec3::ZERO, RowTarget::speed(0.0)); MAX_ROWS],
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
    #[inline]
    pub fn push(&mut self, row: Row, c: f32, rule: TargetRule) {
        let turned = [
            self.mass_a.inertia * row.a.angular,
            self.mass_b.inertia * row.b.angular,
        ];
        self.push_turned(row, c, rule, turned);
    }

    /// Pushes the row along `dist`'s axis between the joint's anchors (a rope's, a rod's), with the impulse
    /// bounds `[lower, upper]`: [`Row::linear`], or for a joint between both centres of mass
    /// ([`BodyPair::is_between_centres`]) [`Row::between_centres`], which has nothing to turn.
    #[inline]
    pub fn push_distance(
        &mut self,
        pair: &BodyPair,
        dist: &Distance,
        target: RowTarget,
        (lower, upper): (f32, f32),
        (c, rule): (f32, TargetRule),
    ) {
        if pair.is_between_centres() {
            let row = Row::between_centres(dist.axis, target).clamped(lower, upper);
            self.push_turned(row, c, rule, [Vec3::ZERO; 2]);
        } else {
            let row = Row::linear(dist.axis, dist.anchors.r_a, dist.anchors.r_b, target)
                .clamped(lower, upper);
            self.push(row, c, rule);
        }
    }

    /// [`JointRows::push`] with the row's turned angular parts `[I_a⁻¹·J_a,angular, I_b⁻¹·J_b,angular]`.
    #[inline]
    fn push_turned(&mut self, row: Row, c: f32, rule: TargetRule, turned_parts: [Vec3; 2]) {
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
    fn turned(&self, k: usize) -> [Vec3; 2] {
        self.turned.get(k).copied().unwrap_or([Vec3::ZERO; 2])
    }

    /// `J·M⁻¹·Jᵀ` of row `k` with itself (0 past the rows pushed): the value computed when a row bounded at 0
    /// was pushed, the same bits as computing it again.
    #[inline]
    fn self_coupling(&self, k: usize) -> f32 {
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
    fn apply(&self, k: usize, a: &mut SolverBody, b: &mut SolverBody, lambda: f32) {
        if let (Some(row), true) = (self.rows.get(k), lambda != 0.0) {
            let [ta, tb] = self.turned(k);
            row.a.apply(&self.mass_a, ta, a, lambda);
            row.b.apply(&self.mass_b, tb, b, lambda);
        }
    }

    /// [`JointRows::apply`] of row 0, for a link known to have it.
    #[inline]
    fn apply_first(&self, a: &mut SolverBody, b: &mut SolverBody, lambda: f32) {
        if lambda != 0.0 {
            let (row, [ta, tb]) = (&self.rows[0], self.turned[0]);
            row.a.apply(&self.mass_a, ta, a, lambda);
            row.b.apply(&self.mass_b, tb, b, lambda);
        }
    }

    /// Displaces both bodies by the position impulse `p` along row `k`.
    #[inline]
    fn displace(&self, k: usize, a: &mut SolverBody, b: &mut SolverBody, p: f32) {
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
            .map(|row| {
                let c = row.target.bias;
                if row.upper == 0.0 {
                    c.max(0.0)
                } else if row.lower == 0.0 {
                    (-c).max(0.0)
                } else {
                    c.abs()
                }
            })
            .fold(0.0, f32::max)
    }
}

/// [`JointRows::violation`] of rows that are all equalities (no bound at 0: a ball joint's, a hinge's), from
/// their position errors and target rules alone: the largest `|bias|` of the targets `rule.target(C, stage)`
/// the rows would be built with, in row order — the same bits, without building the rows.
pub(crate) fn equality_violation(errors: &[(f32, TargetRule)], stage: &Stage) -> f32 {
    errors
        .iter()
        .map(|&(c, rule)| rule.target(c, stage).bias.abs())
        .fold(0.0, f32::max)
}

/// One link of a path as the direct solve sees it: the joint's rows, which of its bodies it shares with the
/// next link (`true` = body B), its accumulated impulses and which rows take part.
///
/// Laid out hot fields first (`repr(C)`): what every pass reads of every link — impulses, active set, the
/// keys of the kept rows and factorisation, the scalar sweep's entries, then the rows ([`JointRows`], also
/// ordered so) — and the 5 × 5 blocks of the block sweep last. A link is about 2 kB; a 500-rope chain's links
/// are a megabyte, far more than the first-level cache, and each pass sweeps them several times (rows and
/// activation, forward and back substitution, the active-set check, the update). With the blocks' `[0][0]`
/// entries serving the scalar sweep and the compiler's field order, a one-row link's reads were spread over
/// the whole record; packed, they sit in its first lines (first-level misses of the SCENES.md chain −11 %,
/// `docs/performance.md`, tenth session).
#[derive(Debug, Clone, Copy, PartialEq)]
#[repr(C)]
pub(crate) struct Link {
    pub lambda: [f32; MAX_ROWS],
    pub active: [bool; MAX_ROWS],
    /// The side of this joint on the body shared with the next link, and the side of the next link on it.
    pub shared_with_next: Option<(bool, bool)>,
    /// Whether this is a position projection: the rows' biases hold their position errors `C`, the solve is
    /// `K·x = C` and the result moves the bodies instead of changing their velocities.
    positions: bool,
    /// Whether the rows were kept from the last step ([`Link::new_step`]): rows built again in this step
    /// before its last relax pass take the inverse masses of the kept ones, so that every link of the path
    /// turns by the same inverse inertia of a body.
    pub from_last_step: bool,
    /// What the factorisation (`scalar`, or `factor`, `v`, `w`, `inv_pivot` and the blocks) was made for;
    /// `None` when it is stale.
    factored: Option<FactorKey>,
    /// The scalar sweep's entries of a one-row link ([`solve_scalar_path`]).
    scalar: ScalarEntries,
    /// The pose the rows were built at ([`PoseKey`]); `None` when the rows are to be built.
    pose: Option<PoseKey>,
    /// The pose the rows were last carried to ([`Link::carry`]) and each row's position error there, `C₀ + J·Δ`:
    /// the next pass at that pose (the solve pass after a relax pass) recomputes only the targets
    /// ([`Link::recarry`]). `None` when the rows were built since.
    carried_at: Option<PoseKey>,
    carried: [f32; MAX_ROWS],
    pub rows: JointRows,
    /// Each row's compliance in a position projection (1/kg, added to its diagonal of `K`): that of the rows
    /// that stiffen a pulled rope or rod against turning ([`Link::stiffen`]), 0 for every other row. Set by
    /// [`Link::make_positional`] and read only while `positions` holds.
    compliance: [Real; MAX_ROWS],
    /// Scratch of the block Thomas sweep (see [`solve_block_path`]): the strictly lower part of the unit
    /// lower triangular `L` of `Sᵢ = L·D·Lᵀ` (with `Sᵢ`'s upper triangle above it, factorised in place by
    /// [`ldl_factor`]), then `V = D⁻¹·L⁻¹·Cᵢ`, stored transposed (`v_t[k]` is column
    /// `k` of `V`: the back substitution sweeps it a column at a time), and `y = D⁻¹·L⁻¹·r̃ᵢ`.
    y: [Real; MAX_ROWS],
    inv_pivot: [Real; MAX_ROWS],
    factor: Block,
    v_t: Block,
    /// The rest of the factorisation, kept for the next pass ([`FactorKey`]): the link's blocks `B` and `C`
    /// (`K·λ` of a soft row reads them), `W = L⁻¹·C` (the next link's forward step reads it) and `D⁻¹`
    /// (`inv_pivot`).
    w: Block,
    b_block: Block,
    c_block: Block,
    /// The Jacobians of the first [`LANES`] rows four lanes wide, lane `k` holding row `k`: for `a.linear`,
    /// `a.angular`, `b.linear` and `b.angular` in turn, their x, y and z components. The block sweep's
    /// residuals read them ([`Link::residual`]); they are made with the blocks ([`Link::fill_lanes`]),
    /// which are made again whenever the rows are.
    lanes: [[Vec4; 3]; 4],
    /// `M⁻¹·Jᵀ` of each row four lanes wide (w = 0), in the order `[m_a⁻¹·J_a,linear, I_a⁻¹·J_a,angular,
    /// m_b⁻¹·J_b,linear, I_b⁻¹·J_b,angular]`, zero for a row not in the system: the velocity change of a unit
    /// impulse along the row. Made with the blocks ([`Link::fill_blocks`]), whose `C` and `B` it serves;
    /// a velocity pass's update sums the rows' increments through it and changes each body once
    /// ([`Link::apply_solution`]).
    impulse: [[Vec4; 4]; MAX_ROWS],
    /// Where the rows were built, in world terms ([`BuiltAt`]): what [`Link::carry`] measures the turn and
    /// the displacement from, in this step or a later one. `None` for rows that are not carried (a rope's,
    /// a ball joint's): the solver sets it where it builds a hinge's rows and clears it where a link starts
    /// from nothing ([`Link::drop_built`]); last, so that a rope's passes never touch it.
    pub built: Option<BuiltAt>,
}

/// Where a link's rows were built, in world terms, and for which joint: what carries them to a later pose of
/// the same step or of a later one ([`Link::carry`]).
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub(crate) struct BuiltAt {
    /// Both bodies' joint frames (world orientation) at the build.
    pub frames: (Quat, Quat),
    /// `c_b − c_a`, the vector between the bodies' centres of mass at the build (m, world).
    pub relative: Vec3,
    /// The joint (its index in the slice given to [`crate::JointSolver::prepare`]) and its bodies' solver
    /// indices: rows are kept into a step only for the same joint between the same bodies.
    pub owner: (usize, usize, usize),
}

/// The entries of the scalar Thomas sweep of a one-row link ([`solve_scalar_path`]): its row's regularised
/// `K` entry `b` (1 for a row not in the system), the coupling `c` with the next link, the reciprocal `1/s`
/// of the Schur complement `s` (0 for a vanishing pivot), `c' = c/s` and `r' = r̃/s`. All but `r'` are kept
/// while the link's [`FactorKey`] holds.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
struct ScalarEntries {
    b: Real,
    c: Real,
    inv_s: Real,
    c_prime: Real,
    r_prime: Real,
}

impl Link {
    /// A link for `rows` with accumulated impulses `lambda`.
    pub fn new(rows: JointRows, lambda: [f32; MAX_ROWS]) -> Self {
        Self {
            rows,
            lambda,
            active: [false; MAX_ROWS],
            shared_with_next: None,
            positions: false,
            compliance: [0.0; MAX_ROWS],
            scalar: ScalarEntries::default(),
            factor: [[0.0; MAX_ROWS]; MAX_ROWS],
            v_t: [[0.0; MAX_ROWS]; MAX_ROWS],
            y: [0.0; MAX_ROWS],
            b_block: [[0.0; MAX_ROWS]; MAX_ROWS],
            c_block: [[0.0; MAX_ROWS]; MAX_ROWS],
            w: [[0.0; MAX_ROWS]; MAX_ROWS],
            inv_pivot: [0.0; MAX_ROWS],
            lanes: [[Vec4::ZERO; 3]; 4],
            impulse: [[Vec4::ZERO; 4]; MAX_ROWS],
            factored: None,
            pose: None,
            carried_at: None,
            carried: [0.0; MAX_ROWS],
            built: None,
            from_last_step: false,
        }
    }

    /// Makes this (reused) link empty, for a joint whose bodies have the given inverse masses: no rows, no
    /// impulses, nothing kept from an earlier pass but the link to the next one (the path's shape). Reusing
    /// links keeps a pass from copying 2-kilobyte records around.
    pub fn reset(&mut self, mass_a: InvMass, mass_b: InvMass) {
        self.rows.mass_a = mass_a;
        self.rows.mass_b = mass_b;
        self.clear();
    }

    /// [`Link::reset`] keeping the inverse masses the link has.
    pub fn clear(&mut self) {
        self.rows.count = 0;
        self.rows.may_release = false;
        self.forget();
        self.restart();
    }

    /// Starts a pass with the rows as they are: no impulses, no row in the system, a velocity pass. The link
    /// to the next one (`shared_with_next`) stays: it is the path's shape, set once a step.
    fn restart(&mut self) {
        self.lambda = [0.0; MAX_ROWS];
        self.active = [false; MAX_ROWS];
        self.positions = false;
    }

    /// Drops what is kept from earlier passes (the pose of the rows, the factorisation): the next pass
    /// builds the rows and factorises again.
    pub fn forget(&mut self) {
        self.forget_poses();
        self.factored = None;
    }

    /// Forgets the poses the rows were built and carried at (they are rebuilt or carried at the next pass).
    fn forget_poses(&mut self) {
        self.pose = None;
        self.carried_at = None;
    }

    /// Forgets everything kept ([`Link::forget`]), from the last step too ([`Link::end_last_step`]), and
    /// where the rows were built: a link that starts from nothing.
    pub fn drop_built(&mut self) {
        self.forget();
        self.end_last_step();
        self.built = None;
    }

    /// Starts a new step with the rows of the last one, kept to be carried ([`Link::carry`]) with the inverse
    /// masses they were built with: the poses of this step ([`PoseKey`], displacements since the step began)
    /// are unrelated to the last step's, so neither the build pose nor a carried one is reused as is.
    pub fn new_step(&mut self) {
        self.forget_poses();
        self.from_last_step = true;
    }

    /// Ends what [`Link::new_step`] started: rows built from now on take this step's inverse masses, and
    /// kept rows are built again at the next pass (the solver calls it for every link of a path at once:
    /// before the step's last relax pass, and for a path it does not keep).
    pub fn end_last_step(&mut self) {
        if self.from_last_step {
            self.forget_poses();
            self.from_last_step = false;
        }
    }

    /// Whether the rows were built at the pose `pose`, as recorded by [`Link::built_at`] (never when none
    /// was, or it was forgotten). Compares in place: the key is 56 bytes, checked for every link of every pass.
    #[inline]
    pub fn is_built_at(&self, pose: &PoseKey) -> bool {
        self.pose.as_ref() == Some(pose)
    }

    /// Applies the impulse `lambda` along the first row to both bodies: the warm start of a one-row joint (a
    /// rope, a rod) whose row was built at the bodies' current pose, which is what the joint's own warm start
    /// applies — `∓axis·(m⁻¹·λ)` and `±I⁻¹·(r × axis)·λ` of the same values — bit for bit.
    pub fn warm_start_row(&self, a: &mut SolverBody, b: &mut SolverBody, lambda: f32) {
        if self.rows.count == 1 {
            self.rows.apply(0, a, b, lambda);
        }
    }

    /// Starts a velocity pass of `stage` at the bodies' current pose — their joint `frames` (world) and the
    /// vector `relative` between their centres of mass; `now`, its key, is recorded with the carried errors
    /// for [`Link::recarry`] — with the rows built earlier (in this step or, kept, in the last one), if
    /// neither body has turned by more than `max_angle` (rad) since: the Jacobians, turned vectors and the
    /// factorisation stay, and each row's position error is carried to the current pose to first order,
    /// `C = C₀ + J·Δ`, with `Δ` the bodies' relative displacement and small rotations since the build
    /// ([`BuiltAt`]). Returns `false`, changing nothing, when the link holds no carried rows, `max_angle` is
    /// not positive or a body turned further. For rows whose Jacobians depend on the rotations alone and
    /// whose linear parts are opposite on the two bodies (a hinge's, a ball joint's: `J·Δ` then needs only
    /// the relative displacement): the solver carries hinges ([`CARRY_ANGLE`]).
    ///
    /// Carried to first order, the errors stay in the range of the rows' `J`: a bridge hung between two
    /// anchors has redundant rows (a singular `K`, kept solvable by [`REGULARIZATION`]), and errors measured
    /// exactly at the new pose but solved with the old rows have a component `K` cannot reach, which the
    /// regularisation turns into impulses a million times too large (the SCENES.md bridge blew up within
    /// 40 steps).
    pub fn carry(
        &mut self,
        frames: (Quat, Quat),
        relative: Vec3,
        now: &PoseKey,
        stage: &Stage,
        max_angle: f32,
    ) -> bool {
        let (Some(built), true) = (self.built, max_angle > 0.0) else {
            return false;
        };
        // The small rotations (rad, world) since the build: the rotation error from the built frames.
        let (ta, tb) = (
            rotation_error(built.frames.0, frames.0),
            rotation_error(built.frames.1, frames.1),
        );
        let limit = max_angle * max_angle;
        if ta.length_squared() > limit || tb.length_squared() > limit {
            return false;
        }
        let d = relative - built.relative;
        // The first [`LANES`] rows four lanes wide from the Jacobians in `lanes` while they are current (the
        // factorisation is: both are made again with the rows), each lane the operations of the row-by-row
        // line below — the same bits.
        let (lanes, in_lanes) = if self.factored.is_some() {
            let dot = |j: &[Vec4; 3], v: Vec3| (j[0] * v.x + j[1] * v.y) + j[2] * v.z;
            let l = &self.lanes;
            let moved = dot(&l[2], d) + (dot(&l[1], ta) + dot(&l[3], tb));
            (moved.to_array(), LANES)
        } else {
            ([0.0; LANES], 0)
        };
        let rows = &self.rows;
        for (k, ((row, &(c, _)), carried)) in rows
            .rows()
            .iter()
            .zip(&rows.errors)
            .zip(&mut self.carried)
            .enumerate()
        {
            let moved = match lanes.get(k) {
                Some(&moved) if k < in_lanes => moved,
                _ => row.b.linear.dot(d) + (row.a.angular.dot(ta) + row.b.angular.dot(tb)),
            };
            *carried = c + moved;
        }
        self.carried_at = Some(*now);
        self.restart_carried(stage);
        true
    }

    /// Starts a pass of `stage` at the pose `now` the rows were last carried to ([`Link::carry`]), from the
    /// errors carried there: the targets [`Link::carry`] would compute again, bit for bit, without measuring
    /// the turn and the displacement again. Returns `false`, changing nothing, at any other pose.
    pub fn recarry(&mut self, now: &PoseKey, stage: &Stage) -> bool {
        if !self.carried_at.as_ref().is_some_and(|at| at == now) {
            return false;
        }
        self.restart_carried(stage);
        true
    }

    /// Starts a pass of `stage` with each row's target made from its carried error.
    fn restart_carried(&mut self, stage: &Stage) {
        self.restart();
        let JointRows {
            rows,
            errors,
            count,
            ..
        } = &mut self.rows;
        for ((row, &(_, rule)), &carried) in rows
            .iter_mut()
            .zip(errors.iter())
            .zip(&self.carried)
            .take(*count)
        {
            row.target = rule.target(carried, stage);
        }
    }

    /// Records that the rows just built (after [`Link::reset`]) are those of the pose `pose`.
    pub fn built_at(&mut self, pose: Option<PoseKey>) {
        self.pose = pose;
    }

    /// Starts a pass of `stage` at the pose the rows were built at (the caller has checked
    /// [`Link::is_built_at`]): the Jacobians, turned vectors and position errors stay, the targets are
    /// recomputed from the errors, and the factorisation stays for [`solve_path`] to reuse if the same rows
    /// end up in the system.
    pub fn reuse(&mut self, stage: &Stage) {
        self.restart();
        self.rows.retarget(stage);
    }

    /// Turns a link whose rows' biases are their position errors into a link of the position projection, in
    /// place (the rows stay reusable: [`Link::reuse`] recomputes the targets and starts a velocity pass).
    /// Equality rows take part; a rope only if it is stretched or within `taut` (m) of its length (`C >
    /// −taut`). A slack rope gets the target "no longer than now"; one further from its length joins through
    /// the active-set rounds ([`activate_violations`]) if moving its neighbours would lengthen it: it may then
    /// pull, but the linear step never spends its slack (which a curved chain's linearisation would
    /// overshoot). Ropes at their length join at once because the rounds add only the ropes next to those in
    /// the system: along a straight run of ropes at their length (a falling chain) they crept a few links per
    /// round, and the step stretched the first rope left out by as much as it closed elsewhere.
    pub fn make_positional(&mut self, taut: f32) {
        let mut active = [false; MAX_ROWS];
        for (row, active) in self
            .rows
            .rows
            .iter_mut()
            .zip(&mut active)
            .take(self.rows.count)
        {
            let c = row.target.bias;
            *active = if row.upper == 0.0 {
                c > -taut
            } else if row.lower == 0.0 {
                c < taut
            } else {
                true
            };
            if (row.upper == 0.0 && c < 0.0) || (row.lower == 0.0 && c > 0.0) {
                row.target.bias = 0.0;
            }
        }
        self.lambda = [0.0; MAX_ROWS];
        self.positions = true;
        self.active = active;
        self.compliance = [0.0; MAX_ROWS];
    }

    /// Stiffens a projection link of one pulled rope or rod row against turning, with `stiffness` (kg): two
    /// linear rows across its axis, between the bodies' centres, with target 0 and compliance `1/stiffness`.
    /// Solved with them, the projection minimises `½·ΔᵀMΔ + ½·stiffness·|Δ⊥|²` (`Δ⊥` the bodies' relative
    /// displacement across the link) instead of `½·ΔᵀMΔ`, subject to the linearised rows: with `stiffness =
    /// |p|/L` (`p` the link's position impulse, `L` its length) that is the Newton step of the projection
    /// with the Hessian of the link's length, `(I − u·uᵀ)/L`, weighted by its multiplier (the geometric
    /// stiffness), which the plain step leaves out. Returns whether the rows were added (a link of one row
    /// and a positive, finite stiffness only). The rows and factorisation are dropped for the next pass.
    pub fn stiffen(&mut self, stiffness: f32) -> bool {
        if !self.positions || self.rows.count != 1 || !(stiffness > 0.0 && stiffness.is_finite()) {
            return false;
        }
        let row = self.rows.rows[0];
        let (across, other) = row.b.linear.any_orthonormal_pair();
        let target = RowTarget {
            bias: 0.0,
            softness: row.target.softness,
        };
        for axis in [across, other] {
            self.rows.push(
                Row::linear(axis, Vec3::ZERO, Vec3::ZERO, target),
                0.0,
                TargetRule::Equality,
            );
        }
        for k in 1..self.rows.count {
            self.active[k] = true;
            self.lambda[k] = 0.0;
            self.compliance[k] = 1.0 / Real::from(stiffness);
        }
        self.forget();
        true
    }

    /// Step 1 of a pass: decides which rows take part and releases the others' impulses. A row bounded at 0
    /// on one side (a rope, a limit) takes part if, without its own impulse, the bodies would violate it this
    /// substep (`Ċ + bias` on the wrong side); equality rows always take part.
    pub fn activate(&mut self, a: &mut SolverBody, b: &mut SolverBody) {
        // A one-row link bounded at 0 (a rope, a rod's limit): the loop below for its one row, with the
        // coupling stored when it was pushed.
        if self.rows.count == 1
            && let Some(coupling) = self.rows.bounded_couplings[0]
        {
            let row = &self.rows.rows[0];
            let lambda = self.lambda[0];
            let own = coupling * lambda;
            let free = row.velocity(a, b) - own + row.target.bias;
            let active = if row.upper == 0.0 {
                free > 0.0
            } else {
                free < 0.0
            };
            self.active[0] = active;
            if !active {
                self.rows.apply_first(a, b, -lambda);
                self.lambda[0] = 0.0;
            }
            return;
        }
        // Equality rows only (a hinge's, a ball joint's): all take part, whatever the velocities.
        if !self.rows.may_release {
            for (k, active) in self.active.iter_mut().enumerate() {
                *active = k < self.rows.count;
            }
            return;
        }
        let rows = &self.rows;
        for (i, ((row, lambda), active)) in rows
            .rows()
            .iter()
            .zip(&mut self.lambda)
            .zip(&mut self.active)
            .enumerate()
        {
            let (upper, lower) = (row.upper == 0.0, row.lower == 0.0);
            // An equality row takes part whatever its state: no need for its free velocity.
            if !upper && !lower {
                *active = true;
                continue;
            }
            let own = rows.self_coupling(i) * *lambda;
            let free = row.velocity(a, b) - own + row.target.bias;
            *active = if upper { free > 0.0 } else { free < 0.0 };
            if !*active {
                rows.apply(i, a, b, -*lambda);
                *lambda = 0.0;
            }
        }
    }

    /// The residual `Ċ + bias` of each active row (0 for the others), in the block sweep: the first
    /// [`LANES`] rows four lanes wide from the Jacobians in `lanes` ([`Link::fill_lanes`], current with
    /// the blocks), each lane the very operations of [`Row::velocity`] — `(j.x·v.x + j.y·v.y) + j.z·v.z` per
    /// vector, `(a.linear + a.angular) + (b.linear + b.angular)`, then `+ bias` — so the same bits as one row
    /// at a time; the rows after them one at a time.
    fn residual(&self, a: &SolverBody, b: &SolverBody) -> [Real; MAX_ROWS] {
        let mut r = [0.0; MAX_ROWS];
        let rows = self.rows.rows();
        if self.positions {
            for (i, row) in rows.iter().enumerate() {
                if self.active[i] {
                    r[i] = self.row_residual(row, a, b);
                }
            }
            return r;
        }
        let dot = |j: &[Vec4; 3], v: Vec3| (j[0] * v.x + j[1] * v.y) + j[2] * v.z;
        let l = &self.lanes;
        let velocity = (dot(&l[0], a.linear_velocity) + dot(&l[1], a.angular_velocity))
            + (dot(&l[2], b.linear_velocity) + dot(&l[3], b.angular_velocity));
        let bias = Vec4::from_array(core::array::from_fn(|k| {
            rows.get(k).map_or(0.0, |row| row.target.bias)
        }));
        let lanes: [f32; LANES] = (velocity + bias).to_array();
        for (i, row) in rows.iter().enumerate() {
            if self.active[i] {
                r[i] = match lanes.get(i) {
                    Some(&lane) => Real::from(lane),
                    None => self.row_residual(row, a, b),
                };
            }
        }
        r
    }

    /// Writes the Jacobians of the first [`LANES`] rows four lanes wide into `lanes`, as [`Link::residual`]
    /// reads them (rows past the row count are zero).
    fn fill_lanes(&mut self) {
        // One 4 × 4 transpose per vector of a side: columns = rows of the link, rows = x, y, z (and w).
        let mut sides = [[Vec4::ZERO; LANES]; 4];
        for (k, row) in self.rows.rows().iter().take(LANES).enumerate() {
            sides[0][k] = row.a.linear.extend(0.0);
            sides[1][k] = row.a.angular.extend(0.0);
            sides[2][k] = row.b.linear.extend(0.0);
            sides[3][k] = row.b.angular.extend(0.0);
        }
        for (out, [c0, c1, c2, c3]) in self.lanes.iter_mut().zip(sides) {
            let t = Mat4::from_cols(c0, c1, c2, c3).transpose();
            *out = [t.x_axis, t.y_axis, t.z_axis];
        }
    }

    /// One row's right-hand side: `Ċ + bias`, or `C` (its bias) in a position projection.
    fn row_residual(&self, row: &Row, a: &SolverBody, b: &SolverBody) -> Real {
        if self.positions {
            Real::from(row.target.bias)
        } else {
            Real::from(row.velocity(a, b) + row.target.bias)
        }
    }

    /// The right-hand side of the soft step of each active row (0 for the others): `mass_scale·r +
    /// impulse_scale·(K·λ)`, from its residual `r` and its row of `K·λ` (see [`solve_path`]).
    fn soft_rhs(&self, r: &[Real; MAX_ROWS], k_lambda: &[Real; MAX_ROWS]) -> [Real; MAX_ROWS] {
        let mut out = [0.0; MAX_ROWS];
        for (k, row) in self.rows.rows().iter().enumerate() {
            if self.active[k] {
                let s = row.target.softness;
                out[k] =
                    Real::from(s.mass_scale) * r[k] + Real::from(s.impulse_scale) * k_lambda[k];
            }
        }
        out
    }

    /// The solution `y` of this link's rows from the solution `x` of `K·x = r` when every row of the path
    /// has the softness `uniform`: `y = mass_scale·x + impulse_scale·λ`, in f32 as the per-row soft step
    /// computes it (so that `λ − y` is bit for bit its `λ + Δλ`). Without a uniform softness `x` is `y`.
    fn finish(&self, mut x: [Real; MAX_ROWS], uniform: Option<Softness>) -> [Real; MAX_ROWS] {
        // Rigid rows (relax pass, projection): `y = x`, which `λ − y` rounds to f32 as the per-row step did.
        if let Some(s) =
            uniform.filter(|s| s.impulse_scale != 0.0 || s.mass_scale.to_bits() != 1.0f32.to_bits())
        {
            for (k, x) in x.iter_mut().enumerate().take(self.rows.count) {
                if self.active[k] {
                    *x = Real::from(s.mass_scale * *x as f32 + s.impulse_scale * self.lambda[k]);
                }
            }
        }
        x
    }

    /// Whether an active row is soft (`impulse_scale > 0`): only then does the right-hand side need `K·λ`.
    fn has_soft_rows(&self) -> bool {
        self.rows
            .rows()
            .iter()
            .zip(&self.active)
            .any(|(row, &active)| active && row.target.softness.impulse_scale > 0.0)
    }

    /// The accumulated impulses as the solve's unknowns (0 for rows not in the system).
    fn active_lambda(&self) -> [Real; MAX_ROWS] {
        let mut out = [0.0; MAX_ROWS];
        for ((out, &lambda), &active) in out.iter_mut().zip(&self.lambda).zip(&self.active) {
            if active {
                *out = Real::from(lambda);
            }
        }
        out
    }

    /// The rows bounded at 0 (ropes, limits) that are not in the system.
    fn left_out(&self) -> [bool; MAX_ROWS] {
        let mut out = [false; MAX_ROWS];
        for ((out, row), &active) in out.iter_mut().zip(self.rows.rows()).zip(&self.active) {
            *out = !active && row.is_bounded_at_zero();
        }
        out
    }

    /// The rows that take part in the system: active ones (never one past the row count).
    fn live_rows(&self) -> [bool; MAX_ROWS] {
        let mut live = [false; MAX_ROWS];
        for (k, (live, &active)) in live.iter_mut().zip(&self.active).enumerate() {
            *live = active && k < self.rows.count;
        }
        live
    }

    /// Makes the diagonal block `B` of this link (`J·M⁻¹·Jᵀ` of its rows over both bodies, each diagonal
    /// entry regularised) and its coupling block `C` with `next` through their shared body, over the first
    /// `N` rows, in `b_block` and `c_block`. A row not in the system — inactive, or past the link's row count
    /// — has a zero row and column in both, which the factorisation ([`ldl_factor`]) solves to 0.
    ///
    /// `B` is symmetric: its upper triangle is computed and mirrored. Each row's `I⁻¹·J_angular`, turned once
    /// when the row was pushed ([`JointRows::turned`]), serves both blocks: with `sᵢ` this link's side of row
    /// `i` on the shared body and `sⱼ` the next link's, `Cᵢⱼ = sⱼ·M⁻¹·sᵢᵀ = m⁻¹·(sⱼ.linear·sᵢ.linear) +
    /// sⱼ.angular·(I⁻¹·sᵢ.angular)`, so the next link's rows are not turned again here. The entries are
    /// summed in f32 (the precision of the rows), four lanes at a time, and the blocks kept in f64.
    fn fill_blocks<const N: usize>(&mut self, next: Option<&Link>) {
        let live = self.live_rows();
        let (ma, mb, rows) = (&self.rows.mass_a, &self.rows.mass_b, &self.rows.rows);
        // Each row's Jacobian `[J_a,linear, J_a,angular, J_b,linear, J_b,angular]` and `M⁻¹·Jᵀ` in the same
        // order, as 4-lane vectors (w = 0), zero for a row not in the system: an entry is then four lane
        // products summed once. Every entry is written once, here and below, rather than the arrays and
        // blocks cleared first: each clear of these few hundred bytes was a call to the C library's `memset`.
        let lanes = |v: Vec3| v.extend(0.0);
        let jacobian: [[Vec4; 4]; MAX_ROWS] = core::array::from_fn(|k| match rows.get(k) {
            Some(row) if k < N && live[k] => {
                [row.a.linear, row.a.angular, row.b.linear, row.b.angular].map(lanes)
            }
            _ => [Vec4::ZERO; 4],
        });
        for k in 0..MAX_ROWS {
            self.impulse[k] = match rows.get(k) {
                Some(row) if k < N && live[k] => {
                    let [ta, tb] = self.rows.turned(k);
                    [row.a.linear * ma.mass, ta, row.b.linear * mb.mass, tb].map(lanes)
                }
                _ => [Vec4::ZERO; 4],
            };
        }
        let inverse = &self.impulse;
        // Bᵢⱼ = Jᵢ·M⁻¹·Jⱼᵀ over both bodies, i ≤ j;   Bᵢᵢ·(1 + ε)
        let b = &mut self.b_block;
        for i in 0..N {
            let ji = &jacobian[i];
            for j in i..N {
                let k = if live[i] && live[j] {
                    let wj = &inverse[j];
                    Real::from(
                        (ji[0] * wj[0] + ji[1] * wj[1] + ji[2] * wj[2] + ji[3] * wj[3])
                            .element_sum(),
                    )
                } else {
                    0.0
                };
                if i == j {
                    b[i][i] = k * (1.0 + REGULARIZATION);
                    if self.positions && live[i] {
                        b[i][i] += self.compliance[i];
                    }
                } else {
                    b[i][j] = k;
                    b[j][i] = k;
                }
            }
        }
        // Cᵢⱼ = sⱼ·(M⁻¹·sᵢᵀ) through the shared body (`s` = `[linear, angular]` of a row's side on it); 0
        // without a next link.
        let c = &mut self.c_block;
        let Some((next, (this_b, next_b))) = next.zip(self.shared_with_next) else {
            for row in c.iter_mut().take(N) {
                row[..N].fill(0.0);
            }
            return;
        };
        let shared = if this_b { 2 } else { 0 };
        let next_live = next.live_rows();
        let next_sides: [[Vec4; 2]; MAX_ROWS] =
            core::array::from_fn(|j| match next.rows.rows.get(j) {
                Some(row) if j < N && next_live[j] => {
                    let side = if next_b { &row.b } else { &row.a };
                    [side.linear, side.angular].map(lanes)
                }
                _ => [Vec4::ZERO; 2],
            });
        for i in 0..N {
            let (wl, wa) = (inverse[i][shared], inverse[i][shared + 1]);
            for j in 0..N {
                c[i][j] = if live[i] && next_live[j] {
                    let [sl, sa] = next_sides[j];
                    Real::from((sl * wl + sa * wa).element_sum())
                } else {
                    0.0
                };
            }
        }
    }

    /// Active-set step: deactivates (and releases) every active row whose update from `x` would cross a bound
    /// of 0 — a rope that would push; returns whether any did, so that the system is solved again without
    /// them.
    pub fn deactivate_violations(
        &mut self,
        x: &[Real; MAX_ROWS],
        a: &mut SolverBody,
        b: &mut SolverBody,
    ) -> bool {
        let rows = &self.rows;
        let mut any = false;
        for (i, (((row, &x), lambda), active)) in rows
            .rows()
            .iter()
            .zip(x)
            .zip(&mut self.lambda)
            .zip(&mut self.active)
            .enumerate()
        {
            if *active && crosses_zero(row, *lambda, x) {
                *active = false;
                rows.apply(i, a, b, -*lambda);
                *lambda = 0.0;
                any = true;
            }
        }
        any
    }

    /// Whether [`Link::deactivate_violations`] would deactivate a row for the solution `x` (checked without
    /// the bodies, which only a row released needs).
    pub fn would_deactivate(&self, x: &[Real; MAX_ROWS]) -> bool {
        self.rows.may_release
            && self
                .rows
                .rows()
                .iter()
                .zip(x)
                .zip(&self.lambda)
                .zip(&self.active)
                .any(|(((row, &x), &lambda), &active)| active && crosses_zero(row, lambda, x))
    }

    /// What active row `k` would get from its solution `x`: the clamped soft update of its impulse, as an
    /// increment (velocity pass) or as the position impulse itself (projection, where `lambda` is 0).
    fn increment(&self, k: usize, x: Real) -> f32 {
        let row = &self.rows.rows[k];
        let new = clamp_impulse(self.lambda[k] - x as f32, row.lower, row.upper);
        new - self.lambda[k]
    }

    /// The change of row `row`'s `Ċ` (or `C`) that the increments of this link's active rows, solved as `x`,
    /// make: through both bodies (`shared` = `None`, `row` is one of this link's rows), or through the one
    /// body `row`'s link shares with this link, given as (`row` acts on it as its body B, this link does).
    fn effect_on(&self, row: &Row, shared: Option<(bool, bool)>, x: &[Real; MAX_ROWS]) -> f32 {
        let mut change = 0.0;
        for ((k, other), _) in self
            .rows
            .rows()
            .iter()
            .enumerate()
            .zip(&self.active)
            .filter(|(_, active)| **active)
        {
            let [ta, tb] = self.rows.turned(k);
            let coupling = match shared {
                None => {
                    row.a.coupling_turned(&self.rows.mass_a, &other.a, ta)
                        + row.b.coupling_turned(&self.rows.mass_b, &other.b, tb)
                }
                Some((row_b, own_b)) => {
                    let side = if row_b { &row.b } else { &row.a };
                    let (other, mass, turned) = if own_b {
                        (&other.b, &self.rows.mass_b, tb)
                    } else {
                        (&other.a, &self.rows.mass_a, ta)
                    };
                    side.coupling_turned(mass, other, turned)
                }
            };
            change += coupling * self.increment(k, x[k]);
        }
        change
    }

    /// [`Link::coupling`] for two one-row links: the single entry, without building a block.
    fn coupling_scalar(&self, next: &Link) -> Real {
        let Some((this_b, next_b)) = self.shared_with_next else {
            return 0.0;
        };
        if self.rows.count != 1 || next.rows.count != 1 || !self.active[0] || !next.active[0] {
            return 0.0;
        }
        // As in `Link::fill_blocks`: this link's side turned, the next link's side dotted with it.
        let (ri, rj) = (&self.rows.rows[0], &next.rows.rows[0]);
        let [ta, tb] = self.rows.turned(0);
        let (si, mass, turned) = if this_b {
            (&ri.b, &self.rows.mass_b, tb)
        } else {
            (&ri.a, &self.rows.mass_a, ta)
        };
        let sj = if next_b { &rj.b } else { &rj.a };
        Real::from(sj.coupling_turned(mass, si, turned))
    }

    /// Step 4: the soft update of each active row from the solution `x`, clamped; applies the increments.
    pub fn apply_solution(&mut self, x: &[Real; MAX_ROWS], a: &mut SolverBody, b: &mut SolverBody) {
        // A one-row link of a velocity pass (every rope of a chain): the loop below for its one row.
        if self.rows.count == 1 && !self.positions {
            if self.active[0] {
                let row = &self.rows.rows[0];
                let lambda = self.lambda[0];
                let new = clamp_impulse(lambda - x[0] as f32, row.lower, row.upper);
                self.rows.apply_first(a, b, new - lambda);
                self.lambda[0] = new;
            }
            return;
        }
        let rows = &self.rows;
        // A one-row link of a projection (a rope chain's, solved by the scalar sweep, which makes no map).
        if self.positions && rows.count == 1 {
            if self.active[0] {
                let row = &rows.rows[0];
                let p = clamp_impulse(self.lambda[0] - x[0] as f32, row.lower, row.upper);
                rows.displace(0, a, b, p);
            }
            return;
        }
        // The rows' increments — in a projection, their position impulses — summed through `M⁻¹·Jᵀ` (made
        // with the blocks this sweep used: the rows in the system now are those they were made for), then
        // each body changed once.
        let positions = self.positions;
        let mut change = [Vec4::ZERO; 4];
        for ((((row, &x), lambda), &active), impulse) in rows
            .rows()
            .iter()
            .zip(x)
            .zip(&mut self.lambda)
            .zip(&self.active)
            .zip(&self.impulse)
        {
            if !active {
                continue;
            }
            let new = clamp_impulse(*lambda - x as f32, row.lower, row.upper);
            let amount = if positions { new } else { new - *lambda };
            for (change, &unit) in change.iter_mut().zip(impulse) {
                *change += unit * amount;
            }
            if !positions {
                *lambda = new;
            }
        }
        if positions {
            displace_body(a, change[0].truncate(), change[1].truncate());
            displace_body(b, change[2].truncate(), change[3].truncate());
            return;
        }
        a.linear_velocity += change[0].truncate();
        a.angular_velocity += change[1].truncate();
        b.linear_velocity += change[2].truncate();
        b.angular_velocity += change[3].truncate();
    }
}

/// Moves `body` by `shift` (m) and turns it by the small rotation vector `turn` (rad): a position impulse's
/// `M⁻¹·Jᵀ·p`, as [`Side::displace`] moves a body for one row.
#[inline]
fn displace_body(body: &mut SolverBody, shift: Vec3, turn: Vec3) {
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

/// Whether the update `λ − x` of a row bounded at 0 (a rope, a limit) would cross that bound — a rope that
/// would push; never for a row without a bound at 0.
#[inline]
fn crosses_zero(row: &Row, lambda: f32, x: Real) -> bool {
    let new = lambda - x as f32;
    (row.upper == 0.0 && new > 0.0) || (row.lower == 0.0 && new < 0.0)
}

/// Active-set step for the rows left out: activates every one-sided row (a rope) that is not in the system
/// but that the solution `solution` of the rows around it would violate — a slack rope whose neighbours would
/// pull its bodies apart past its length, or a taut rope that was closing before the solve and would no
/// longer be. Returns the first link that had a row activated (`None`: none), so that the system is solved
/// again with them — from the link before it on ([`Resume`]). Without this step a rope left out at the start
/// of a pass is pulled past its length by the solve of its neighbours (a chain whipping round stretched links
/// by 30 % within a substep).
pub(crate) fn activate_violations<'b>(
    links: &mut [Link],
    solution: &[[Real; MAX_ROWS]],
    load: impl Fn(usize) -> Option<(&'b SolverBody, &'b SolverBody)>,
) -> Option<usize> {
    let mut first = None;
    for i in 0..links.len() {
        // Most links of a rope chain are a one-row link in the system (a taut rope): nothing left out.
        let link = &links[i];
        if link.rows.count == 1 && link.active[0] {
            continue;
        }
        let left_out = link.left_out();
        if !left_out.contains(&true) {
            continue;
        }
        for r in (0..MAX_ROWS).filter(|&r| left_out[r]) {
            let link = &links[i];
            let row = &link.rows.rows[r];
            // A row just added has no solution yet (0), so it changes nothing for the rows after it.
            let mut free = row.target.bias + link.effect_on(row, None, &solution[i]);
            if let Some(prev) = i.checked_sub(1).and_then(|p| links.get(p))
                && let Some((prev_b, this_b)) = prev.shared_with_next
            {
                free += prev.effect_on(row, Some((this_b, prev_b)), &solution[i - 1]);
            }
            if let (Some((this_b, next_b)), Some(next)) = (link.shared_with_next, links.get(i + 1))
            {
                free += next.effect_on(row, Some((this_b, next_b)), &solution[i + 1]);
            }
            if !link.positions
                && let Some((a, b)) = load(i)
            {
                free += row.velocity(a, b);
            }
            let violated = if row.upper == 0.0 {
                free > 0.0
            } else {
                free < 0.0
            };
            if violated {
                links[i].active[r] = true;
                first = first.or(Some(i));
            }
        }
    }
    first
}

/// One nonlinear Gauss–Seidel projection of one joint's rows (Box2D v2's position solver): each row whose
/// position error `C` (its bias) is violated moves the two bodies by `−M⁻¹·Jᵀ·C/K` — exactly onto the row to
/// first order, never past it, so repeated sweeps cannot diverge. Used after the direct projection to take
/// back what its linearisation missed.
pub(crate) fn project_rows(rows: &JointRows, a: &mut SolverBody, b: &mut SolverBody) {
    for (k, row) in rows.rows().iter().enumerate() {
        let c = row.target.bias;
        let violated = if row.upper == 0.0 {
            c > 0.0
        } else if row.lower == 0.0 {
            c < 0.0
        } else {
            c != 0.0
        };
        let mass = rows.self_coupling(k);
        if !violated || mass <= 0.0 {
            continue;
        }
        rows.displace(k, a, b, -c / mass);
    }
}

/// Steps 2 and 3 of a pass: the residuals from the bodies' current velocities (`load(i)` gives link `i`'s
/// bodies), then the block Thomas sweep; returns the solution `y` of each link in `out`, the change of its
/// accumulated impulses being `−y`.
///
/// The system is the soft step of every row at once: `K·y = mass_scale∘r + impulse_scale∘(K·λ)`, `r = Ċ +
/// bias` (or `C` in a projection), `∘` row by row. After the update each row holds `r' + c·(K·λ')ᵢ = 0` with
/// `c = impulse_scale/mass_scale`: a soft row is compliant against its row of `K·λ` — the difference of the
/// loads on either side of it, one ball's weight in a hanging chain whatever the load below — and a rigid
/// row (`impulse_scale = 0`: a slack rope closing its slack, a projection) holds exactly. For one row this is
/// the Gauss–Seidel soft step `Δλ = −mass_scale·r/K − impulse_scale·λ`; when every row has the same softness,
/// `Δλ = −mass_scale·K⁻¹·r − impulse_scale·λ`. Taking each row's soft step from one exact solve of `K·x = r`
/// instead is wrong as soon as the softness differs along the path: the leak `impulse_scale·λ` of the soft
/// rows, which carry the chain's load, lands on a rigid row in between, and a chain whipping round came apart
/// in a zigzag of links stretched and slackened by several centimetres each.
///
/// `resume` carries what the last solve of this pass left (see [`Resume`]): its forward sweep is kept for the
/// links before the first one an active-set round changed, when the path's shape and softness are still the
/// ones it was made with.
pub(crate) fn solve_path<'b>(
    links: &mut [Link],
    load: impl Fn(usize) -> Option<(&'b SolverBody, &'b SolverBody)>,
    out: &mut Vec<[Real; MAX_ROWS]>,
    resume: &mut Resume,
) -> Solved {
    // One solution per link. The back substitution of either sweep writes every one of them whole, so the
    // entries kept from the last solve are not cleared first (a 500-link chain's 20 kB per round).
    out.truncate(links.len());
    out.resize(links.len(), [0.0; MAX_ROWS]);
    // With one softness along the path (a settled or straight chain, a bridge, every relax pass and
    // projection) the soft step splits into `K·x = r` and `y = mass_scale·x + impulse_scale·λ`: the same
    // result, without `K·λ`, and bit for bit that of the per-row form.
    // The factorisation keys are scanned from where a resumed sweep would start; if the shape changed, the
    // sweep starts at the first link and (rarely) the keys are scanned again from there.
    let resumable = resume.swept.map_or(0, |_| resume.from.min(links.len()));
    let shape = path_shape(links, resumable);
    let widest = shape.widest;
    let key = (widest, shape.uniform.map(softness_bits));
    let (start, stale) = match resume.swept {
        Some(swept) if swept == key => (resumable, shape.first_stale()),
        _ if resumable == 0 => (0, shape.first_stale()),
        _ => (0, first_stale(links, widest.max(1), 0)),
    };
    resume.swept = Some(key);
    resume.from = links.len();
    let released = if widest <= 1 {
        solve_scalar_path(links, load, out, shape.uniform, start, stale)
    } else {
        solve_block_path(links, load, out, (widest, stale), shape.uniform, start)
    };
    Solved {
        left_out: shape.left_out,
        released,
    }
}

/// What a solve of a path tells the active-set step that follows it ([`activate_violations`],
/// [`Link::would_deactivate`]), gathered by the scans the solve makes anyway: each step is a sweep over every
/// link (a 500-rope chain's links are a megabyte), skipped when it has nothing to look at.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) struct Solved {
    /// Whether a row bounded at 0 was left out of the system (only then can one be activated).
    pub left_out: bool,
    /// Whether the solution would release a row (a rope that would push).
    pub released: bool,
}

/// What the next active-set round's solve of a path can keep of the last one: the forward sweep of the links
/// before `from`. A round changes the system only at the links whose rows it activated or released (a
/// released row also changes its bodies' velocities); the forward sweep of link `i` reads links `0..=i + 1`'s
/// active sets, links `0..=i`'s residuals and, through the shared bodies, the velocities link `i + 1`'s
/// release changes — so from the link before the first one changed on, the sweep differs, and before it
/// every stored `y`, `V`, `W`, `D⁻¹`, `L` and block is what the sweep would compute again, bit for bit.
/// Kept only while the path's widest link and common softness ([`path_shape`]) are those of the last sweep.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub(crate) struct Resume {
    /// The widest link and the common softness's bits of the last sweep (`None`: no sweep yet this pass).
    swept: Option<(usize, Option<u64>)>,
    /// The first link whose forward sweep must run again.
    from: usize,
}

impl Resume {
    /// Records that link `link`'s active set (and, by a release, its bodies' velocities) changed since the
    /// last sweep.
    pub fn changed(&mut self, link: usize) {
        self.from = self.from.min(link.saturating_sub(1));
    }
}

/// A softness by its bits: the same bits make the split form of [`solve_path`] exactly the per-row one.
fn softness_bits(s: Softness) -> u64 {
    (u64::from(s.mass_scale.to_bits()) << 32) | u64::from(s.impulse_scale.to_bits())
}

/// What one scan of the path gives `solve_path` ([`path_shape`]).
struct PathShape {
    /// The largest row count of the links.
    widest: usize,
    /// The softness every active row shares, if they all do (the first active row's, or rigid without one).
    uniform: Option<Softness>,
    /// Whether a row bounded at 0 is left out of the system ([`Link::left_out`]).
    left_out: bool,
    /// From the scan's `start` on: the first link without a factorisation for its current active set and
    /// link to the next one ([`FactorKey`] but its width), and the first whose factorisation's width differs
    /// from that of the link at `start` (`None`: none).
    first_unkeyed: usize,
    first_width_change: usize,
    start_width: Option<usize>,
    /// Where the keys were first looked at.
    start: usize,
}

impl PathShape {
    /// [`first_stale`] from the scan's `start` for the sweep `solve_path` makes — scalar (keys of width 1)
    /// up to one row, else blocks `widest` wide: the first link whose [`FactorKey`] differs, or the number of
    /// links if there is none.
    fn first_stale(&self) -> usize {
        match self.start_width {
            Some(width) if width == self.widest.max(1) => {
                self.first_unkeyed.min(self.first_width_change)
            }
            // The link at `start` is keyed for another width (and `first_unkeyed` is past it).
            Some(_) => self.start,
            None => self.first_unkeyed,
        }
    }
}

/// One scan of the path for what `solve_path` decides on ([`PathShape`]), the factorisation keys looked at
/// from `start` on — made in the same scan so that the links are swept once.
fn path_shape(links: &[Link], start: usize) -> PathShape {
    let bits = softness_bits;
    let mut widest = 0;
    let mut common: Option<(Softness, u64)> = None;
    let mut uniform = true;
    let mut left_out = false;
    let (mut first_unkeyed, mut first_width_change) = (links.len(), links.len());
    let mut start_width = None;
    for (i, link) in links.iter().enumerate() {
        widest = widest.max(link.rows.count);
        if i >= start {
            match link.factored {
                Some(key) if key.active == link.active && key.shared == link.shared_with_next => {
                    match start_width {
                        None if i == start => start_width = Some(key.width),
                        Some(width) if width != key.width => {
                            first_width_change = first_width_change.min(i);
                        }
                        _ => {}
                    }
                }
                _ => first_unkeyed = first_unkeyed.min(i),
            }
        }
        for (row, &active) in link.rows.rows().iter().zip(&link.active) {
            if !active {
                left_out |= row.is_bounded_at_zero();
                continue;
            }
            if !uniform {
                continue;
            }
            let s = row.target.softness;
            match common {
                None => common = Some((s, bits(s))),
                Some((_, c)) if c == bits(s) => {}
                Some(_) => uniform = false,
            }
        }
    }
    let uniform = uniform.then(|| common.map_or(Softness::RIGID, |(s, _)| s));
    PathShape {
        widest,
        uniform,
        left_out,
        first_unkeyed,
        first_width_change,
        start_width,
        start,
    }
}

/// [`solve_path`] for paths with multi-row joints: the block Thomas algorithm, over blocks of the path's
/// largest row count (a link with fewer rows is padded with rows that solve to 0; a path of hinges runs the
/// 5 × 5 sweep, one of ball joints the 3 × 3). With a `uniform` softness the right-hand side is the residual
/// alone and the soft step is finished in the back substitution. `rows` is the largest row count of the links.
fn solve_block_path<'b>(
    links: &mut [Link],
    load: impl Fn(usize) -> Option<(&'b SolverBody, &'b SolverBody)>,
    out: &mut [[Real; MAX_ROWS]],
    (rows, stale): (usize, usize),
    uniform: Option<Softness>,
    start: usize,
) -> bool {
    let sweep = (start, stale);
    match rows {
        0..=2 => block_sweep::<2>(links, load, out, uniform, sweep),
        3 => block_sweep::<3>(links, load, out, uniform, sweep),
        4 => block_sweep::<4>(links, load, out, uniform, sweep),
        _ => block_sweep::<MAX_ROWS>(links, load, out, uniform, sweep),
    }
}

/// The block Thomas sweep of [`solve_block_path`] over `N × N` blocks, with each `Sᵢ` factorised as
/// `L·D·Lᵀ` ([`ldl_factor`]) and the sweep written in its factors (`W = L⁻¹·C`, `V = D⁻¹·W`,
/// `y = D⁻¹·L⁻¹·rhs`):
///
/// ```text
/// Sᵢ = Bᵢ − Wᵢ₋₁ᵀ·Vᵢ₋₁          (= Bᵢ − Cᵢ₋₁ᵀ·Sᵢ₋₁⁻¹·Cᵢ₋₁, symmetric: upper triangle only)
/// rhsᵢ = r̃ᵢ − Wᵢ₋₁ᵀ·yᵢ₋₁        (= r̃ᵢ − Cᵢ₋₁ᵀ·r'ᵢ₋₁)
/// xᵢ = Lᵢ⁻ᵀ·(yᵢ − Vᵢ·xᵢ₊₁)       (= Sᵢ⁻¹·(rhsᵢ − Cᵢ·xᵢ₊₁))
/// ```
///
/// The products are written as sums of scaled rows (`rhs −= yₖ·(row k of W)`, `x −= xₖ·(column k of V)`,
/// with `V` stored transposed), not as dot products: the rows are contiguous, so the compiler pairs them
/// into two-lane f64 instructions (the SCENES.md bridge −0.8 % instructions, `docs/performance.md`).
///
/// `B`, `C`, `L`, `D⁻¹`, `W` and `V` depend on the rows and on which of them are in the system, not on the
/// velocities: while the links up to the next one still have the rows and the active sets they were
/// factorised with ([`FactorKey`], [`keeps_factor`]; a pass at an unchanged pose), they are kept and only the
/// right-hand side is swept (`rhsᵢ`, then `y = D⁻¹·L⁻¹·rhsᵢ`) — the same operations on the same values, so
/// the same bits.
fn block_sweep<'b, const N: usize>(
    links: &mut [Link],
    load: impl Fn(usize) -> Option<(&'b SolverBody, &'b SolverBody)>,
    out: &mut [[Real; MAX_ROWS]],
    uniform: Option<Softness>,
    (start, stale): (usize, usize),
) -> bool {
    let split = uniform.is_some();
    // Forward sweep from link `start` on (the links before it are as the last sweep left them, see
    // [`Resume`]). `lambda_prev` holds λᵢ₋₁; Cᵢ₋₁, Wᵢ₋₁, Vᵢ₋₁ and yᵢ₋₁ are stored in link i − 1.
    let mut lambda_prev = match start.checked_sub(1).and_then(|p| links.get(p)) {
        Some(prev) if !split => prev.active_lambda(),
        _ => [0.0; MAX_ROWS],
    };
    for i in start..links.len() {
        let reuse = keeps_factor(i, stale, links.len());
        let (done, rest) = links.split_at_mut(i);
        let Some((link, after)) = rest.split_first_mut() else {
            break;
        };
        let next = after.first();
        if !reuse {
            link.fill_blocks::<N>(next);
            link.fill_lanes();
        }
        let r = load(i).map_or([0.0; MAX_ROWS], |(a, b)| link.residual(a, b));
        let lambda = if split {
            [0.0; MAX_ROWS]
        } else {
            link.active_lambda()
        };
        // K·λ, for the soft rows only: this link's block, then the couplings to the next and the previous
        // link. (No row is soft in the relax pass and in a projection.)
        let soft_rows = !split && link.has_soft_rows();
        let mut k_lambda = [0.0; MAX_ROWS];
        if soft_rows {
            let lambda_next = next.map_or([0.0; MAX_ROWS], Link::active_lambda);
            let (b, c) = (&link.b_block, &link.c_block);
            for row in 0..N {
                let mut sum = 0.0;
                for k in 0..N {
                    sum += b[row][k] * lambda[k] + c[row][k] * lambda_next[k];
                }
                k_lambda[row] = sum;
            }
        }
        let mut rhs = if split { r } else { [0.0; MAX_ROWS] };
        if let Some(prev) = done.last() {
            // rhs = r̃ − Wᵢ₋₁ᵀ·yᵢ₋₁, a row of W at a time (contiguous, so the rows pair into SIMD lanes).
            for k in 0..N {
                let (w, y) = (&prev.w[k], prev.y[k]);
                for row in 0..N {
                    rhs[row] -= w[row] * y;
                }
            }
            if soft_rows {
                for k in 0..N {
                    let (c, l) = (&prev.c_block[k], lambda_prev[k]);
                    for row in 0..N {
                        k_lambda[row] += c[row] * l;
                    }
                }
            }
        }
        if !split {
            let soft = link.soft_rhs(&r, &k_lambda);
            for row in 0..N {
                rhs[row] += soft[row];
            }
        }
        // S = B − Wᵢ₋₁ᵀ·D⁻¹ᵢ₋₁·Wᵢ₋₁ (upper triangle);  S = L·D·Lᵀ;  W = L⁻¹·C,  Vᵀ = (D⁻¹·W)ᵀ  (kept when
        // `reuse`)
        if !reuse {
            // `S` (upper triangle) straight into the factor storage, an entry at a time (a copy of the
            // 200-byte `B` first was a call to `memcpy`), then factorised there.
            let s = &mut link.factor;
            for row in 0..N {
                for col in row..N {
                    let mut value = link.b_block[row][col];
                    if let Some(prev) = done.last() {
                        for k in 0..N {
                            value -= (prev.w[k][row] * prev.inv_pivot[k]) * prev.w[k][col];
                        }
                    }
                    s[row][col] = value;
                }
            }
            ldl_factor::<N>(&mut link.factor, &mut link.inv_pivot);
            forward_substitute_block::<N>(&link.factor, &link.c_block, &mut link.w);
            for row in 0..N {
                for col in 0..N {
                    link.v_t[col][row] = link.w[row][col] * link.inv_pivot[row];
                }
            }
            link.factored = Some(FactorKey::of(link, N));
        }
        // y = D⁻¹·L⁻¹·rhs
        forward_substitute::<N>(&link.factor, &mut rhs);
        for row in 0..N {
            link.y[row] = rhs[row] * link.inv_pivot[row];
        }
        lambda_prev = lambda;
    }
    // Back substitution: xᵢ = Lᵢ⁻ᵀ·(yᵢ − Vᵢ·xᵢ₊₁) (`V` of the last link is 0), a column of V (a row of the
    // stored Vᵀ) at a time.
    let mut x_next = [0.0; MAX_ROWS];
    let mut released = false;
    for (link, out) in links.iter().zip(out.iter_mut()).rev() {
        let mut x = link.y;
        for k in 0..N {
            let (v, f) = (&link.v_t[k], x_next[k]);
            for row in 0..N {
                x[row] -= v[row] * f;
            }
        }
        back_substitute::<N>(&link.factor, &mut x);
        *out = link.finish(x, uniform);
        released |= link.would_deactivate(out);
        x_next = x;
    }
    released
}

/// The first link of the path whose stored factorisation is not for its current rows and active set in a
/// sweep of blocks `width` wide (its [`FactorKey`] differs), or the number of links if there is none; the
/// links before `start` are not looked at (a resumed sweep: the last sweep left their keys current).
fn first_stale(links: &[Link], width: usize, start: usize) -> usize {
    links
        .iter()
        .enumerate()
        .skip(start)
        .find(|(_, link)| link.factored != Some(FactorKey::of(link, width)))
        .map_or(links.len(), |(i, _)| i)
}

/// Whether link `i` of a path of `len` links keeps its factorisation when link `stale` is the first one
/// whose key changed ([`first_stale`]): `Sᵢ` depends on links `0..=i` and `Cᵢ` on link `i + 1`, so every
/// link before `stale − 1` does (all of them when none changed). A kept link's factorisation is then the
/// one that the links it depends on had — they were factorised in the same sweep or kept with it.
#[inline]
fn keeps_factor(i: usize, stale: usize, len: usize) -> bool {
    stale == len || i + 1 < stale
}

/// [`solve_path`] for a path of one-row joints (a rope chain): the scalar Thomas algorithm, without the
/// block machinery. `uniform` as in [`solve_block_path`]. As there, the entries `b`, `c`, `s` and `c'` of a
/// link are kept from the last pass while it and the links before and after it have the rows and active
/// sets they were computed for ([`keeps_factor`]).
fn solve_scalar_path<'b>(
    links: &mut [Link],
    load: impl Fn(usize) -> Option<(&'b SolverBody, &'b SolverBody)>,
    out: &mut [[Real; MAX_ROWS]],
    uniform: Option<Softness>,
    start: usize,
    stale: usize,
) -> bool {
    let split = uniform.is_some();
    // Forward sweep: c'ᵢ = cᵢ/sᵢ, r'ᵢ = (r̃ᵢ − cᵢ₋₁·r'ᵢ₋₁)/sᵢ with sᵢ = bᵢ − cᵢ₋₁·c'ᵢ₋₁ and r̃ the soft
    // right-hand side of `solve_path`; bᵢ is the row's regularised `K` (1 for a row not in the system).
    // Link i − 1 holds cᵢ₋₁, c'ᵢ₋₁ and r'ᵢ₋₁ (`scalar`); `lambda_prev` is λᵢ₋₁.
    // The sweep starts at link `start` (see [`Resume`]).
    let mut lambda_prev = start
        .checked_sub(1)
        .and_then(|p| links.get(p))
        .map_or(0.0, |prev| prev.active_lambda()[0]);
    for i in start..links.len() {
        if !keeps_factor(i, stale, links.len()) {
            let link = &links[i];
            let active = link.rows.count == 1 && link.active[0];
            let c = links
                .get(i + 1)
                .map_or(0.0, |next| links[i].coupling_scalar(next));
            let diagonal = if active {
                Real::from(link.rows.self_coupling(0)) * (1.0 + REGULARIZATION)
            } else {
                1.0
            };
            let mut s = diagonal;
            if let Some(prev) = i.checked_sub(1).and_then(|p| links.get(p)) {
                s -= prev.scalar.c * prev.scalar.c_prime;
            }
            let scale = Real::from(link.rows.mass_a.mass.max(link.rows.mass_b.mass));
            // A vanishing pivot gets 1/s = 0 (never a pivot that passes the test: |s| > MIN_POSITIVE). The
            // reciprocal is kept so that the sweeps multiply: the forward sweep's chain from link to link is
            // then a multiply-add, not a division (some 15 cycles of latency each, 500 in a row for a chain).
            let inv_s = if s.abs() <= (scale * RELATIVE_PIVOT).max(Real::MIN_POSITIVE) {
                0.0
            } else {
                1.0 / s
            };
            let link = &mut links[i];
            link.scalar = ScalarEntries {
                b: diagonal,
                c,
                inv_s,
                c_prime: c * inv_s,
                r_prime: link.scalar.r_prime,
            };
            link.factored = Some(FactorKey::of(link, 1));
        }
        let link = &links[i];
        let active = link.rows.count == 1 && link.active[0];
        let lambda = link.active_lambda()[0];
        let (diagonal, c) = (link.scalar.b, link.scalar.c);
        let prev = i.checked_sub(1).and_then(|p| links.get(p));
        let mut r = if active {
            let row = &link.rows.rows[0];
            let residual = load(i).map_or(0.0, |(a, b)| link.row_residual(row, a, b));
            let softness = row.target.softness;
            if split {
                residual
            } else {
                let mut rhs = Real::from(softness.mass_scale) * residual;
                if softness.impulse_scale > 0.0 {
                    let mut k_lambda = diagonal * lambda;
                    if let Some(next) = links.get(i + 1) {
                        k_lambda += c * next.active_lambda()[0];
                    }
                    if let Some(prev) = prev {
                        k_lambda += prev.scalar.c * lambda_prev;
                    }
                    rhs += Real::from(softness.impulse_scale) * k_lambda;
                }
                rhs
            }
        } else {
            0.0
        };
        if let Some(prev) = prev {
            r -= prev.scalar.c * prev.scalar.r_prime;
        }
        links[i].scalar.r_prime = r * link.scalar.inv_s;
        lambda_prev = lambda;
    }
    // Back substitution.
    let mut next = 0.0;
    let mut released = false;
    for i in (0..links.len()).rev() {
        let x = links[i].scalar.r_prime - links[i].scalar.c_prime * next;
        out[i] = links[i].finish([x, 0.0, 0.0, 0.0, 0.0], uniform);
        released |= links[i].would_deactivate(&out[i]);
        next = x;
    }
    released
}

/// The rows whose residuals the block sweep computes four lanes wide ([`Link::residual`]).
const LANES: usize = 4;

/// Added to each row's own `K` entry as a fraction of it: a little compliance that keeps the system of a
/// path with redundant rows (a bridge hung from two anchors constrains more than its bodies' degrees of
/// freedom) well conditioned, as constraint force mixing does.
const REGULARIZATION: Real = 1e-6;

/// Pivots smaller than this fraction of the largest diagonal entry count as zero: the row is redundant.
const RELATIVE_PIVOT: Real = 1e-5;

/// The factorisation `S = L·D·Lᵀ` of the symmetric positive semi-definite top-left `N × N` of `block`, in
/// place: only the upper triangle of `S` (row ≤ column) is read, and the strictly lower part of the unit lower
/// triangular `L` is written below it, into the same block, with the reciprocal pivots `D⁻¹` into
/// `inv_pivots` (every entry of both, whatever they held before; nothing reads the rest). One block and no
/// copies: the sweep writes `S` into the link's factor storage and factorises it there. No pivoting: `S` is a
/// Schur complement of `K = J·M⁻¹·Jᵀ`, whose pivots are positive. A pivot at or below [`RELATIVE_PIVOT`] ×
/// the largest diagonal entry — a row no body can move along, a row of zeros (not in the system), or a row
/// redundant with the rows before it (a bridge hung from two anchors constrains more than its bodies' degrees
/// of freedom) — gets a reciprocal of 0 and a zero column of `L`: that unknown solves to 0 and its equation is
/// dropped, never a NaN or a huge impulse.
///
/// ```text
/// dⱼ = Sⱼⱼ − Σₖ<ⱼ Lⱼₖ²·dₖ,        Lᵢⱼ = (Sⱼᵢ − Σₖ<ⱼ Lᵢₖ·Lⱼₖ·dₖ) / dⱼ,   i > j
/// ```
fn ldl_factor<const N: usize>(block: &mut Block, inv_pivots: &mut [Real; MAX_ROWS]) {
    // `S` is read on and above the diagonal, `L` written below it: no entry is both.
    let l = block;
    let mut scale: Real = 0.0;
    for k in 0..N {
        scale = scale.max(l[k][k]);
    }
    let tiny = (scale * RELATIVE_PIVOT).max(Real::MIN_POSITIVE);
    let mut pivots = [0.0; MAX_ROWS];
    for j in 0..N {
        // lj_d[k] = Lⱼₖ·dₖ, shared by the pivot and the column below it.
        let mut lj_d = [0.0; MAX_ROWS];
        let mut pivot = l[j][j];
        for k in 0..j {
            lj_d[k] = l[j][k] * pivots[k];
            pivot -= l[j][k] * lj_d[k];
        }
        // Written so that a NaN pivot counts as vanishing too.
        if pivot > tiny {
            let inv = 1.0 / pivot;
            pivots[j] = pivot;
            inv_pivots[j] = inv;
            for i in (j + 1)..N {
                let mut value = l[j][i];
                for k in 0..j {
                    value -= l[i][k] * lj_d[k];
                }
                l[i][j] = value * inv;
            }
        } else {
            inv_pivots[j] = 0.0;
            for i in (j + 1)..N {
                l[i][j] = 0.0;
            }
        }
    }
}

/// `W = L⁻¹·C` for the top-left `N × N` of `c`, written into `w` (forward substitution with the unit lower
/// triangular factor of [`ldl_factor`]): `wᵢ = cᵢ − Σₖ<ᵢ Lᵢₖ·wₖ`, a row at a time (no copy of `C` first: the
/// 200-byte copy was a call to `memcpy`).
fn forward_substitute_block<const N: usize>(l: &Block, c: &Block, w: &mut Block) {
    for i in 0..N {
        let mut row = c[i];
        for k in 0..i {
            let f = l[i][k];
            for col in 0..N {
                row[col] -= f * w[k][col];
            }
        }
        w[i] = row;
    }
}

/// `L⁻¹` applied in place to `z` (as [`forward_substitute_block`], one column): `zᵢ −= Lᵢₖ·zₖ`, k < i.
fn forward_substitute<const N: usize>(l: &Block, z: &mut [Real; MAX_ROWS]) {
    for i in 1..N {
        for k in 0..i {
            z[i] -= l[i][k] * z[k];
        }
    }
}

/// `L⁻ᵀ` applied in place to `x` (back substitution with the transpose of [`ldl_factor`]'s factor).
fn back_substitute<const N: usize>(l: &Block, x: &mut [Real; MAX_ROWS]) {
    for j in (0..N).rev() {
        let mut value = x[j];
        for i in (j + 1)..N {
            value -= l[i][j] * x[i];
        }
        x[j] = value;
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use rebound_math::Quat;

    /// Solves `s·x = b` with the block path's factorisation: `x = L⁻ᵀ·D⁻¹·L⁻¹·b`.
    fn ldl_solve<const N: usize>(s: &Block, b: [Real; MAX_ROWS]) -> [Real; MAX_ROWS] {
        let (mut l, mut inv_pivots) = (*s, [0.0; MAX_ROWS]);
        ldl_factor::<N>(&mut l, &mut inv_pivots);
        let mut x = b;
        forward_substitute::<N>(&l, &mut x);
        for (x, inv) in x.iter_mut().zip(&inv_pivots) {
            *x *= inv;
        }
        back_substitute::<N>(&l, &mut x);
        x
    }

    /// `m·x`.
    fn product(m: &Block, x: &[Real; MAX_ROWS]) -> [Real; MAX_ROWS] {
        m.map(|line| line.iter().zip(x).map(|(a, x)| a * x).sum())
    }

    #[test]
    fn ldl_solves_a_symmetric_positive_system_and_zeroes_a_row_of_zeros() {
        let s = [
            [4.0, 1.0, 0.5, 0.0, 0.0],
            [1.0, 3.0, 0.2, 0.1, 0.0],
            [0.5, 0.2, 2.0, 0.3, 0.0],
            [0.0, 0.1, 0.3, 1.5, 0.0],
            [0.0, 0.0, 0.0, 0.0, 0.0],
        ];
        let x_true = [1.0, -2.0, 0.5, 3.0, 0.0];
        let x = ldl_solve::<MAX_ROWS>(&s, product(&s, &x_true));
        for (row, (x, t)) in x.iter().zip(&x_true).enumerate() {
            assert!((x - t).abs() <= 1e-9 * t.abs().max(1.0), "{row}: {x:?}");
        }
        assert!(x[4] == 0.0, "{x:?}");
    }

    #[test]
    fn ldl_gives_a_redundant_row_zero_and_solves_the_rest() {
        // `S = J·Jᵀ` with row 2 of `J` the sum of rows 0 and 1: rank 3 of 4, row 2 redundant.
        let j = [
            [1.0, 0.5, 0.0, 0.2],
            [0.0, 1.0, 0.3, 0.0],
            [1.0, 1.5, 0.3, 0.2],
            [0.1, 0.0, 0.0, 2.0],
        ];
        let mut s = [[0.0; MAX_ROWS]; MAX_ROWS];
        for r in 0..4 {
            for c in 0..4 {
                s[r][c] = (0..4).map(|k| j[r][k] * j[c][k]).sum();
            }
        }
        // A consistent right-hand side: `S·x₀` for some `x₀`.
        let b = product(&s, &[0.3, -1.0, 0.7, 2.0, 0.0]);
        let x = ldl_solve::<4>(&s, b);
        assert!(x.iter().all(|x| x.is_finite()), "{x:?}");
        assert!(x[2] == 0.0, "{x:?}");
        let residual = product(&s, &x);
        for (row, (r, b)) in residual.iter().zip(&b).enumerate() {
            assert!(
                (r - b).abs() <= 1e-9 * b.abs().max(1.0),
                "{row}: {residual:?} vs {b:?}"
            );
        }
    }

    #[test]
    fn ldl_solves_an_identity_row_to_its_right_hand_side_of_zero() {
        // Row 1 not in the system, given an identity row: it solves to 0, the others as without it.
        let s = [
            [2.0, 0.0, 0.4, 0.0, 0.0],
            [0.0, 1.0, 0.0, 0.0, 0.0],
            [0.4, 0.0, 0.5, 0.0, 0.0],
            [0.0; MAX_ROWS],
            [0.0; MAX_ROWS],
        ];
        let x_true = [0.25, 0.0, -4.0, 0.0, 0.0];
        let x = ldl_solve::<3>(&s, product(&s, &x_true));
        for (row, (x, t)) in x.iter().zip(&x_true).enumerate() {
            assert!((x - t).abs() <= 1e-9 * t.abs().max(1.0), "{row}: {x:?}");
        }
        assert!(x[1] == 0.0, "{x:?}");
    }

    /// A path of `widths.len()` links between consecutive bodies with inverse masses `masses` (link `i`'s body
    /// B is link `i + 1`'s body A), link `i` with `widths[i]` rows — a rope's one row, else a hinge's rows cut to the
    /// width — every row soft, in the system and carrying an impulse.
    fn soft_path(widths: &[usize], masses: &[InvMass]) -> Vec<Link> {
        let soft = RowTarget {
            bias: 0.05,
            softness: Softness {
                bias_rate: 10.0,
                mass_scale: 0.9,
                impulse_scale: 0.1,
            },
        };
        widths
            .iter()
            .enumerate()
            .map(|(i, &width)| {
                let (r_a, r_b) = (Vec3::new(0.5, 0.1, 0.0), Vec3::new(-0.4, 0.0, 0.2));
                let axis = Vec3::new(1.0, 0.1 * i as f32, 0.0).normalize();
                let mut rows = if width == 1 {
                    let mut rows = JointRows::new(masses[i], masses[i + 1]);
                    let row = Row::linear(axis, r_a, r_b, soft).clamped(f32::NEG_INFINITY, 0.0);
                    rows.push(row, 0.0, TargetRule::UpperLimit);
                    rows
                } else {
                    hinge_rows(r_a, r_b, axis, masses[i], masses[i + 1])
                };
                rows.count = width;
                for row in &mut rows.rows {
                    row.target = soft;
                }
                let lambda = core::array::from_fn(|k| -0.1 * (1 + i + k) as f32);
                let mut link = Link::new(rows, lambda);
                link.active[..width].fill(true);
                link.shared_with_next = (i + 1 < widths.len()).then_some((true, false));
                link
            })
            .collect()
    }

    /// The inverse masses of eight bodies for [`soft_path`]: unequal, with unequal inertias.
    fn path_masses() -> [InvMass; 8] {
        core::array::from_fn(|k| InvMass {
            mass: 0.5 + 0.25 * k as f32,
            inertia: Mat3::from_diagonal(Vec3::new(2.0 + k as f32, 1.0, 0.5)),
        })
    }

    /// Eight bodies moving and turning, each differently.
    fn path_bodies() -> [SolverBody; 8] {
        core::array::from_fn(|k| SolverBody {
            linear_velocity: Vec3::new(0.3 * k as f32, -1.0, 0.5),
            angular_velocity: Vec3::new(0.2, 0.1 * k as f32, -0.4),
            ..SolverBody::STATIC
        })
    }

    #[test]
    fn a_resumed_sweep_gives_the_bits_of_a_full_one() {
        // Rope chains (the scalar sweep) and hinge decks (the block sweep): solve, take a row out of the
        // system at link 3 as an active-set round does, then solve again resuming from link 2 and from
        // scratch.
        let (masses, bodies) = (path_masses(), path_bodies());
        let load = |i: usize| Some((&bodies[i], &bodies[i + 1]));
        for width in [1, MAX_ROWS] {
            let mut resumed = soft_path(&[width; 7], &masses);
            let mut full = resumed.clone();
            let (mut out_resumed, mut out_full) = (Vec::new(), Vec::new());
            let mut resume = Resume::default();
            solve_path(&mut resumed, load, &mut out_resumed, &mut resume);
            solve_path(&mut full, load, &mut out_full, &mut Resume::default());
            for links in [&mut resumed, &mut full] {
                links[3].active[0] = false;
                links[3].lambda[0] = 0.0;
            }
            resume.changed(3);
            solve_path(&mut resumed, load, &mut out_resumed, &mut resume);
            solve_path(&mut full, load, &mut out_full, &mut Resume::default());
            let bits = |out: &[[Real; MAX_ROWS]]| {
                out.iter()
                    .flat_map(|x| x.map(Real::to_bits))
                    .collect::<Vec<_>>()
            };
            assert_eq!(bits(&out_resumed), bits(&out_full), "width {width}");
            assert!(out_full.iter().any(|x| x[0] != 0.0), "width {width}");
        }
    }

    #[test]
    fn the_shape_scan_finds_the_first_stale_link_as_the_key_scan_does() {
        // Paths of ropes, of hinges, and mixed (a rope between hinges: blocks 5 wide), factorised at one
        // width; then links unkeyed, re-keyed at another width, their active set or link to the next changed.
        let (masses, bodies) = (path_masses(), path_bodies());
        let load = |i: usize| Some((&bodies[i], &bodies[i + 1]));
        let edits: [fn(&mut [Link]); 6] = [
            |_| {},
            |links| links[4].forget(),
            |links| links[2].active[0] = false,
            |links| links[5].shared_with_next = None,
            |links| {
                if let Some(key) = links[3].factored.as_mut() {
                    key.width = 2;
                }
            },
            |links| {
                for link in links.iter_mut() {
                    if let Some(key) = link.factored.as_mut() {
                        key.width = 3;
                    }
                }
            },
        ];
        for widths in [[1; 7], [MAX_ROWS; 7], [5, 5, 1, 5, 5, 5, 5]] {
            for edit in edits {
                for start in [0, 1, 3, 6, 7] {
                    let mut links = soft_path(&widths, &masses);
                    let _ = solve_path(&mut links, load, &mut Vec::new(), &mut Resume::default());
                    edit(&mut links);
                    let shape = path_shape(&links, start);
                    let width = shape.widest.max(1);
                    assert_eq!(
                        shape.first_stale(),
                        first_stale(&links, width, start),
                        "widths {widths:?}, start {start}"
                    );
                    let left_out = links.iter().any(|link| link.left_out().contains(&true));
                    assert_eq!(shape.left_out, left_out, "widths {widths:?}");
                }
            }
        }
    }

    #[test]
    fn a_solve_reports_whether_its_solution_would_release_a_row() {
        // A rope chain pulled together (every rope would push: all released) and pulled apart (none).
        let masses: [InvMass; 6] = core::array::from_fn(|k| InvMass {
            mass: 1.0 + k as f32,
            inertia: Mat3::IDENTITY,
        });
        for (speed, released) in [(1.0, true), (-1.0, false)] {
            let bodies: [SolverBody; 6] = core::array::from_fn(|k| SolverBody {
                linear_velocity: Vec3::new(-speed * k as f32, 0.0, 0.0),
                ..SolverBody::STATIC
            });
            let load = |i: usize| Some((&bodies[i], &bodies[i + 1]));
            for widths in [[1; 5], [1, 1, 5, 1, 1]] {
                let mut links = soft_path(&widths, &masses);
                let mut out = Vec::new();
                let solved = solve_path(&mut links, load, &mut out, &mut Resume::default());
                let would = links
                    .iter()
                    .zip(&out)
                    .any(|(link, x)| link.would_deactivate(x));
                assert_eq!(solved.released, would, "speed {speed}, widths {widths:?}");
                assert_eq!(would, released, "speed {speed}, widths {widths:?}");
            }
        }
    }

    #[test]
    fn only_rows_bounded_at_zero_can_be_released() {
        let mass = InvMass {
            mass: 1.0,
            inertia: Mat3::IDENTITY,
        };
        let (r_a, r_b) = (Vec3::new(0.5, 0.0, 0.0), Vec3::new(-0.5, 0.0, 0.0));
        // A hinge's equality rows: no solution releases them, however it pushes.
        let mut link = Link::new(hinge_rows(r_a, r_b, Vec3::Z, mass, mass), [1.0; MAX_ROWS]);
        link.active = [true; MAX_ROWS];
        assert!(!link.rows.may_release);
        assert!(!link.would_deactivate(&[1e3; MAX_ROWS]));
        // A rope's row (upper bound 0) pushed after them: a solution that would make it push releases it.
        let rope =
            Row::linear(Vec3::X, r_a, r_b, RowTarget::speed(0.0)).clamped(f32::NEG_INFINITY, 0.0);
        let mut rows = JointRows::new(mass, mass);
        rows.push(rope, 0.0, TargetRule::UpperLimit);
        let mut link = Link::new(rows, [-1.0, 0.0, 0.0, 0.0, 0.0]);
        link.active[0] = true;
        assert!(link.rows.may_release);
        assert!(link.would_deactivate(&[-2.0, 0.0, 0.0, 0.0, 0.0]));
        assert!(!link.would_deactivate(&[0.5, 0.0, 0.0, 0.0, 0.0]));
        // Emptied for another joint: nothing left to release.
        link.reset(mass, mass);
        assert!(!link.rows.may_release);
    }

    /// A hinge's five rows between bodies with anchors `r_a`, `r_b` and hinge axis `axis`.
    fn hinge_rows(r_a: Vec3, r_b: Vec3, axis: Vec3, mass_a: InvMass, mass_b: InvMass) -> JointRows {
        let mut rows = JointRows::new(mass_a, mass_b);
        for direction in [Vec3::X, Vec3::Y, Vec3::Z] {
            rows.push(
                Row::linear(direction, r_a, r_b, RowTarget::speed(0.0)),
                0.0,
                TargetRule::Equality,
            );
        }
        let axis = axis.normalize();
        let side = axis.any_orthonormal_vector();
        for perpendicular in [side, axis.cross(side)] {
            rows.push(
                Row::angular(perpendicular, RowTarget::speed(0.0)),
                0.0,
                TargetRule::Equality,
            );
        }
        rows
    }

    #[test]
    fn the_block_sweep_solves_the_path_system_as_a_dense_solve_does() {
        // Four bodies, link i joins bodies i and i + 1 (its body B is the next link's body A). Link 1 is a
        // ball joint (3 rows, padded in the 5 × 5 sweep) with one row left out.
        let inertia = |k: f32| {
            let turn = Quat::from_rotation_y(0.3 * k) * Quat::from_rotation_x(0.2 + k);
            let m = Mat3::from_quat(turn);
            m * Mat3::from_diagonal(Vec3::new(2.0 + k, 1.0, 0.5 + 0.3 * k)) * m.transpose()
        };
        let masses: [InvMass; 4] = core::array::from_fn(|k| InvMass {
            mass: 0.5 + 0.25 * k as f32,
            inertia: inertia(k as f32),
        });
        let bodies: [SolverBody; 4] = core::array::from_fn(|k| SolverBody {
            linear_velocity: Vec3::new(0.3 * k as f32, -1.0, 0.5),
            angular_velocity: Vec3::new(0.2, 0.1 * k as f32, -0.4),
            ..SolverBody::STATIC
        });
        let r_a = Vec3::new(0.5, 0.1, 0.0);
        let r_b = Vec3::new(-0.4, 0.0, 0.2);
        let mut links = [0, 1, 2].map(|i| {
            let mut rows = hinge_rows(
                r_a,
                r_b,
                Vec3::new(0.1 * i as f32, 0.0, 1.0),
                masses[i],
                masses[i + 1],
            );
            if i == 1 {
                rows.count = 3;
            }
            let mut link = Link::new(rows, [0.0; MAX_ROWS]);
            link.active = [true; MAX_ROWS];
            link.active[rows.count..].fill(false);
            link.shared_with_next = (i < 2).then_some((true, false));
            link
        });
        links[1].active[1] = false;
        let mut out = Vec::new();
        solve_path(
            &mut links,
            |i| Some((&bodies[i], &bodies[i + 1])),
            &mut out,
            &mut Resume::default(),
        );

        // The dense system over the active rows: K = J·M⁻¹·Jᵀ (diagonal regularised), r = Ċ.
        let mut index = Vec::new();
        for (i, link) in links.iter().enumerate() {
            for k in 0..link.rows.count {
                if link.active[k] {
                    index.push((i, k));
                }
            }
        }
        let n = index.len();
        // `J_p·M⁻¹·J_qᵀ` through one body, from scratch.
        let coupling = |p: &Side, m: &InvMass, q: &Side| {
            p.linear.dot(q.linear) * m.mass + p.angular.dot(m.inertia * q.angular)
        };
        let mut k_dense = vec![vec![0.0; n + 1]; n];
        for (p, &(i, a)) in index.iter().enumerate() {
            let row_p = &links[i].rows.rows[a];
            k_dense[p][n] = Real::from(row_p.velocity(&bodies[i], &bodies[i + 1]));
            for (q, &(j, b)) in index.iter().enumerate() {
                let row_q = &links[j].rows.rows[b];
                let value = if i == j {
                    coupling(&row_p.a, &masses[i], &row_q.a)
                        + coupling(&row_p.b, &masses[i + 1], &row_q.b)
                } else if j == i + 1 {
                    coupling(&row_p.b, &masses[j], &row_q.a)
                } else if i == j + 1 {
                    coupling(&row_p.a, &masses[i], &row_q.b)
                } else {
                    0.0
                };
                k_dense[p][q] = Real::from(value) * if p == q { 1.0 + REGULARIZATION } else { 1.0 };
            }
        }
        // Gauss–Jordan with partial pivoting.
        for c in 0..n {
            let pivot = (c..n)
                .max_by(|&x, &y| k_dense[x][c].abs().total_cmp(&k_dense[y][c].abs()))
                .unwrap_or(c);
            k_dense.swap(c, pivot);
            for r in 0..n {
                if r != c {
                    let f = k_dense[r][c] / k_dense[c][c];
                    for k in c..=n {
                        k_dense[r][k] -= f * k_dense[c][k];
                    }
                }
            }
        }
        let largest = index
            .iter()
            .map(|&(i, k)| out[i][k].abs())
            .fold(0.0, Real::max);
        assert!(largest > 0.1, "{out:?}");
        for (p, &(i, k)) in index.iter().enumerate() {
            let dense = k_dense[p][n] / k_dense[p][p];
            assert!(
                (out[i][k] - dense).abs() <= 1e-7 * largest,
                "link {i} row {k}: {} vs {dense}",
                out[i][k]
            );
        }
        assert!(out[1][1] == 0.0, "a row left out solves to 0");
        assert!(out[1][3..].iter().all(|&x| x == 0.0), "padding solves to 0");
    }
}
