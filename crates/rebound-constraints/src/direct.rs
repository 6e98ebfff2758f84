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
//! # Positions
//!
//! The same machinery projects positions after the substeps (`JointSolver::project_positions`): with the
//! rows' biases set to their position errors `C`, the solve of `K·x = C` moves the bodies by `−M⁻¹·Jᵀ·x`
//! (`project_rows` is the one-joint Gauss–Seidel version used after it). Derivations and measurements are
//! in `docs/physics.md`, "Chains solved directly".

#![allow(
    clippy::needless_range_loop,
    reason = "dense block algebra (Thomas sweep, Gaussian elimination) reads as the formulas with indices"
)]

use crate::part::RowTarget;
use rebound_dynamics::{Softness, SolverBody};
use rebound_math::quat::{RotationIntegrator, integrate_rotation};
use rebound_math::{Mat3, Vec3};

/// The most rows one joint gives the direct solve: a hinge's 3 point rows and 2 alignment rows.
pub(crate) const MAX_ROWS: usize = 5;

/// A `MAX_ROWS × MAX_ROWS` block, row-major; only the top-left `k × k` is used.
pub(crate) type Block = [[Real; MAX_ROWS]; MAX_ROWS];

/// The precision of the path solve.
pub(crate) type Real = f64;

/// One body's side of a row's Jacobian: `Ċ` gains `linear·v + angular·ω`.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub(crate) struct Side {
    pub linear: Vec3,
    pub angular: Vec3,
}

/// A body's inverse mass (1/kg) and world inverse inertia (1/(kg·m²)) at the start of the step.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct InvMass {
    pub mass: f32,
    pub inertia: Mat3,
}

impl Side {
    /// `J_side·M⁻¹·other_sideᵀ`: how an impulse on `other` changes this row's `Ċ` through one body.
    #[inline]
    fn coupling(&self, m: &InvMass, other: &Side) -> f32 {
        self.coupling_turned(m, other, m.inertia * other.angular)
    }

    /// [`Side::coupling`] with `other`'s angular part already turned by the inverse inertia
    /// (`turned = I⁻¹·other.angular`, shared by every row it is coupled with).
    #[inline]
    fn coupling_turned(&self, m: &InvMass, other: &Side, turned: Vec3) -> f32 {
        self.linear.dot(other.linear) * m.mass + self.angular.dot(turned)
    }

    /// The velocity change an impulse `lambda` along this side gives the body.
    #[inline]
    fn apply(&self, m: &InvMass, body: &mut SolverBody, lambda: f32) {
        body.linear_velocity += self.linear * (m.mass * lambda);
        body.angular_velocity += m.inertia * (self.angular * lambda);
    }

    /// The displacement a position impulse `p` (kg·m) along this side gives the body: `Δx = M⁻¹·Jᵀ·p`, the
    /// rotation as a small rotation vector.
    #[inline]
    fn displace(&self, m: &InvMass, body: &mut SolverBody, p: f32) {
        body.delta_position += self.linear * (m.mass * p);
        let turn = m.inertia * (self.angular * p);
        if turn != Vec3::ZERO {
            body.delta_rotation = integrate_rotation(
                body.delta_rotation,
                turn,
                1.0,
                RotationIntegrator::FirstOrder,
            );
        }
    }

    #[inline]
    fn velocity(&self, body: &SolverBody) -> f32 {
        self.linear.dot(body.linear_velocity) + self.angular.dot(body.angular_velocity)
    }
}

/// One row: its Jacobian on bodies A and B, what it drives toward, and its impulse bounds.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Row {
    pub a: Side,
    pub b: Side,
    pub target: RowTarget,
    pub lower: f32,
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

    /// `Ċ` (m/s or rad/s).
    #[inline]
    fn velocity(&self, a: &SolverBody, b: &SolverBody) -> f32 {
        self.a.velocity(a) + self.b.velocity(b)
    }

    /// `J·M⁻¹·Jᵀ` of the row with itself.
    #[inline]
    fn self_coupling(&self, ma: &InvMass, mb: &InvMass) -> f32 {
        self.a.coupling(ma, &self.a) + self.b.coupling(mb, &self.b)
    }

    /// Applies the impulse `lambda` to both bodies.
    #[inline]
    fn apply(
        &self,
        ma: &InvMass,
        mb: &InvMass,
        a: &mut SolverBody,
        b: &mut SolverBody,
        lambda: f32,
    ) {
        if lambda != 0.0 {
            self.a.apply(ma, a, lambda);
            self.b.apply(mb, b, lambda);
        }
    }
}

/// The rows one joint contributes to a pass, with its bodies' inverse masses.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct JointRows {
    pub rows: [Row; MAX_ROWS],
    pub count: usize,
    pub mass_a: InvMass,
    pub mass_b: InvMass,
}

impl JointRows {
    /// No rows yet, for a joint whose bodies have the given inverse masses.
    pub fn new(mass_a: InvMass, mass_b: InvMass) -> Self {
        Self {
            rows: [Row::angular(Vec3::ZERO, RowTarget::speed(0.0)); MAX_ROWS],
            count: 0,
            mass_a,
            mass_b,
        }
    }

    /// Adds a row (ignored past [`MAX_ROWS`]).
    pub fn push(&mut self, row: Row) {
        if let Some(slot) = self.rows.get_mut(self.count) {
            *slot = row;
            self.count += 1;
        }
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

/// One link of a path as the direct solve sees it: the joint's rows, which of its bodies it shares with the
/// next link (`true` = body B), its accumulated impulses and which rows take part.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Link {
    pub rows: JointRows,
    pub lambda: [f32; MAX_ROWS],
    pub active: [bool; MAX_ROWS],
    /// The side of this joint on the body shared with the next link, and the side of the next link on it.
    pub shared_with_next: Option<(bool, bool)>,
    /// Whether this is a position projection: the rows' biases hold their position errors `C`, the solve is
    /// `K·x = C` and the result moves the bodies instead of changing their velocities.
    positions: bool,
    /// Scratch of the Thomas sweep: `C'` and `r'`.
    c_prime: Block,
    r_prime: [Real; MAX_ROWS],
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
            c_prime: [[0.0; MAX_ROWS]; MAX_ROWS],
            r_prime: [0.0; MAX_ROWS],
        }
    }

    /// Makes this (reused) link empty, for a joint whose bodies have the given inverse masses: no rows, no
    /// impulses, not linked. Reusing links keeps a pass from copying 700-byte records around.
    pub fn reset(&mut self, mass_a: InvMass, mass_b: InvMass) {
        self.rows.count = 0;
        self.rows.mass_a = mass_a;
        self.rows.mass_b = mass_b;
        self.lambda = [0.0; MAX_ROWS];
        self.active = [false; MAX_ROWS];
        self.shared_with_next = None;
        self.positions = false;
    }

    /// Turns a link whose rows' biases are their position errors into a link of the position projection, in
    /// place. Equality rows take part; a rope only if it is stretched (`C > 0`). A slack rope gets the target
    /// "no longer than now" and joins through the active-set rounds ([`activate_violations`]) if moving its
    /// neighbours would lengthen it: it may then pull, but the linear step never spends its slack (which a
    /// curved chain's linearisation would overshoot).
    pub fn make_positional(&mut self) {
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
                c > 0.0
            } else if row.lower == 0.0 {
                c < 0.0
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
    }

    /// Step 1 of a pass: decides which rows take part and releases the others' impulses. A row bounded at 0
    /// on one side (a rope, a limit) takes part if, without its own impulse, the bodies would violate it this
    /// substep (`Ċ + bias` on the wrong side); equality rows always take part.
    pub fn activate(&mut self, a: &mut SolverBody, b: &mut SolverBody) {
        let (ma, mb) = (self.rows.mass_a, self.rows.mass_b);
        for (i, row) in self.rows.rows.iter().enumerate().take(self.rows.count) {
            let own = row.self_coupling(&ma, &mb) * self.lambda[i];
            let free = row.velocity(a, b) - own + row.target.bias;
            let active = if row.upper == 0.0 {
                free > 0.0
            } else if row.lower == 0.0 {
                free < 0.0
            } else {
                true
            };
            self.active[i] = active;
            if !active {
                row.apply(&ma, &mb, a, b, -self.lambda[i]);
                self.lambda[i] = 0.0;
            }
        }
    }

    /// The residual `Ċ + bias` of each active row (0 for the others).
    fn residual(&self, a: &SolverBody, b: &SolverBody) -> [Real; MAX_ROWS] {
        let mut r = [0.0; MAX_ROWS];
        for (i, row) in self.rows.rows().iter().enumerate() {
            if self.active[i] {
                r[i] = self.row_residual(row, a, b);
            }
        }
        r
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

    /// The diagonal block `B` (identity for inactive rows, so that they solve to 0).
    fn diagonal(&self) -> Block {
        let mut block = [[0.0; MAX_ROWS]; MAX_ROWS];
        let (ma, mb, rows) = (&self.rows.mass_a, &self.rows.mass_b, self.rows.rows());
        // `I⁻¹·J_angular` of each row, once (not once per pair of rows).
        let mut turned = [(Vec3::ZERO, Vec3::ZERO); MAX_ROWS];
        for (t, r) in turned.iter_mut().zip(rows) {
            *t = (ma.inertia * r.a.angular, mb.inertia * r.b.angular);
        }
        for (i, ri) in rows.iter().enumerate() {
            for (j, rj) in rows.iter().enumerate() {
                block[i][j] = if self.active[i] && self.active[j] {
                    let (ta, tb) = turned[j];
                    let k = Real::from(
                        ri.a.coupling_turned(ma, &rj.a, ta) + ri.b.coupling_turned(mb, &rj.b, tb),
                    );
                    if i == j {
                        k * (1.0 + REGULARIZATION)
                    } else {
                        k
                    }
                } else if i == j {
                    1.0
                } else {
                    0.0
                };
            }
        }
        block
    }

    /// The coupling block `C` of this link's rows with the next link's through their shared body.
    fn coupling(&self, next: &Link) -> Block {
        let mut block = [[0.0; MAX_ROWS]; MAX_ROWS];
        let Some((this_b, next_b)) = self.shared_with_next else {
            return block;
        };
        let mass = if this_b {
            &self.rows.mass_b
        } else {
            &self.rows.mass_a
        };
        // The next link's sides on the shared body, with `I⁻¹·J_angular` computed once per row.
        let mut sides = [(Side::default(), Vec3::ZERO); MAX_ROWS];
        for (side, rj) in sides.iter_mut().zip(next.rows.rows()) {
            let sj = if next_b { rj.b } else { rj.a };
            *side = (sj, mass.inertia * sj.angular);
        }
        for (i, ri) in self.rows.rows().iter().enumerate() {
            if !self.active[i] {
                continue;
            }
            let si = if this_b { &ri.b } else { &ri.a };
            for (j, (sj, turned)) in sides.iter().enumerate().take(next.rows.count) {
                if next.active[j] {
                    block[i][j] = Real::from(si.coupling_turned(mass, sj, *turned));
                }
            }
        }
        block
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
        let (ma, mb) = (self.rows.mass_a, self.rows.mass_b);
        let mut any = false;
        for (i, row) in self.rows.rows.iter().enumerate().take(self.rows.count) {
            if !self.active[i] {
                continue;
            }
            let new = self.lambda[i] - x[i] as f32;
            if (row.upper == 0.0 && new > 0.0) || (row.lower == 0.0 && new < 0.0) {
                self.active[i] = false;
                row.apply(&ma, &mb, a, b, -self.lambda[i]);
                self.lambda[i] = 0.0;
                any = true;
            }
        }
        any
    }

    /// What active row `k` would get from its solution `x`: the clamped soft update of its impulse, as an
    /// increment (velocity pass) or as the position impulse itself (projection, where `lambda` is 0).
    fn increment(&self, k: usize, x: Real) -> f32 {
        let row = &self.rows.rows[k];
        let new = (self.lambda[k] - x as f32).max(row.lower).min(row.upper);
        new - self.lambda[k]
    }

    /// The change of row `row`'s `Ċ` (or `C`) that the increments of this link's active rows, solved as `x`,
    /// make: through both bodies (`shared` = `None`, `row` is one of this link's rows), or through the one
    /// body `row`'s link shares with this link, given as (`row` acts on it as its body B, this link does).
    fn effect_on(&self, row: &Row, shared: Option<(bool, bool)>, x: &[Real; MAX_ROWS]) -> f32 {
        let mut change = 0.0;
        for (k, other) in self.rows.rows().iter().enumerate() {
            if !self.active[k] {
                continue;
            }
            let coupling = match shared {
                None => {
                    row.a.coupling(&self.rows.mass_a, &other.a)
                        + row.b.coupling(&self.rows.mass_b, &other.b)
                }
                Some((row_b, own_b)) => {
                    let side = if row_b { &row.b } else { &row.a };
                    let (other, mass) = if own_b {
                        (&other.b, &self.rows.mass_b)
                    } else {
                        (&other.a, &self.rows.mass_a)
                    };
                    side.coupling(mass, other)
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
        let (ri, rj) = (&self.rows.rows[0], &next.rows.rows[0]);
        let (si, mass) = if this_b {
            (&ri.b, &self.rows.mass_b)
        } else {
            (&ri.a, &self.rows.mass_a)
        };
        let sj = if next_b { &rj.b } else { &rj.a };
        Real::from(si.coupling(mass, sj))
    }

    /// Step 4: the soft update of each active row from the solution `x`, clamped; applies the increments.
    pub fn apply_solution(&mut self, x: &[Real; MAX_ROWS], a: &mut SolverBody, b: &mut SolverBody) {
        let (ma, mb) = (self.rows.mass_a, self.rows.mass_b);
        for (i, row) in self.rows.rows.iter().enumerate().take(self.rows.count) {
            if !self.active[i] {
                continue;
            }
            let new = (self.lambda[i] - x[i] as f32).max(row.lower).min(row.upper);
            if self.positions {
                row.a.displace(&ma, a, new);
                row.b.displace(&mb, b, new);
                continue;
            }
            row.apply(&ma, &mb, a, b, new - self.lambda[i]);
            self.lambda[i] = new;
        }
    }
}

/// Active-set step for the rows left out: activates every one-sided row (a rope) that is not in the system
/// but that the solution `solution` of the rows around it would violate — a slack rope whose neighbours would
/// pull its bodies apart past its length, or a taut rope that was closing before the solve and would no
/// longer be. Returns whether any row was activated, so that the system is solved again with them. Without
/// this step a rope left out at the start of a pass is pulled past its length by the solve of its neighbours
/// (a chain whipping round stretched links by 30 % within a substep).
pub(crate) fn activate_violations(
    links: &mut [Link],
    solution: &[[Real; MAX_ROWS]],
    load: impl Fn(usize) -> Option<(SolverBody, SolverBody)>,
) -> bool {
    let mut any = false;
    for i in 0..links.len() {
        for r in 0..links[i].rows.count.min(MAX_ROWS) {
            let link = &links[i];
            let row = &link.rows.rows[r];
            if link.active[r] || (row.upper != 0.0 && row.lower != 0.0) {
                continue;
            }
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
                free += row.velocity(&a, &b);
            }
            let violated = if row.upper == 0.0 {
                free > 0.0
            } else {
                free < 0.0
            };
            if violated {
                links[i].active[r] = true;
                any = true;
            }
        }
    }
    any
}

/// One nonlinear Gauss–Seidel projection of one joint's rows (Box2D v2's position solver): each row whose
/// position error `C` (its bias) is violated moves the two bodies by `−M⁻¹·Jᵀ·C/K` — exactly onto the row to
/// first order, never past it, so repeated sweeps cannot diverge. Used after the direct projection to take
/// back what its linearisation missed.
pub(crate) fn project_rows(rows: &JointRows, a: &mut SolverBody, b: &mut SolverBody) {
    let (ma, mb) = (rows.mass_a, rows.mass_b);
    for row in rows.rows() {
        let c = row.target.bias;
        let violated = if row.upper == 0.0 {
            c > 0.0
        } else if row.lower == 0.0 {
            c < 0.0
        } else {
            c != 0.0
        };
        let k = row.self_coupling(&ma, &mb);
        if !violated || k <= 0.0 {
            continue;
        }
        let p = -c / k;
        row.a.displace(&ma, a, p);
        row.b.displace(&mb, b, p);
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
pub(crate) fn solve_path(
    links: &mut [Link],
    load: impl Fn(usize) -> Option<(SolverBody, SolverBody)>,
    out: &mut Vec<[Real; MAX_ROWS]>,
) {
    out.clear();
    out.resize(links.len(), [0.0; MAX_ROWS]);
    // With one softness along the path (a settled or straight chain, a bridge, every relax pass and
    // projection) the soft step splits into `K·x = r` and `y = mass_scale·x + impulse_scale·λ`: the same
    // result, without `K·λ`, and bit for bit that of the per-row form.
    let uniform = uniform_softness(links);
    if links.iter().all(|link| link.rows.count <= 1) {
        solve_scalar_path(links, load, out, uniform);
    } else {
        solve_block_path(links, load, out, uniform);
    }
}

/// The softness every active row of the path shares, if they all do.
fn uniform_softness(links: &[Link]) -> Option<Softness> {
    let mut common: Option<Softness> = None;
    for link in links {
        for (row, &active) in link.rows.rows().iter().zip(&link.active) {
            if !active {
                continue;
            }
            let s = row.target.softness;
            match common {
                None => common = Some(s),
                // The same bits: then the split form of `solve_path` is exactly the per-row one.
                Some(c)
                    if c.mass_scale.to_bits() == s.mass_scale.to_bits()
                        && c.impulse_scale.to_bits() == s.impulse_scale.to_bits() => {}
                Some(_) => return None,
            }
        }
    }
    Some(common.unwrap_or(Softness::RIGID))
}

/// [`solve_path`] for paths with multi-row joints: the block Thomas algorithm. With a `uniform` softness the
/// right-hand side is the residual alone and the soft step is finished in the back substitution.
fn solve_block_path(
    links: &mut [Link],
    load: impl Fn(usize) -> Option<(SolverBody, SolverBody)>,
    out: &mut [[Real; MAX_ROWS]],
    uniform: Option<Softness>,
) {
    let split = uniform.is_some();
    // Forward sweep. `previous` holds Cᵢ₋₁, λᵢ₋₁ and r'ᵢ₋₁; C'ᵢ₋₁ is stored in link i − 1. Loops run over the
    // links' own row counts (1 for a rope, 5 for a hinge).
    let mut previous: Option<(Block, [Real; MAX_ROWS], [Real; MAX_ROWS])> = None;
    for i in 0..links.len() {
        let n = links[i].rows.count.min(MAX_ROWS);
        let r = load(i).map_or([0.0; MAX_ROWS], |(a, b)| links[i].residual(&a, &b));
        let mut s = links[i].diagonal();
        let lambda = if split {
            [0.0; MAX_ROWS]
        } else {
            links[i].active_lambda()
        };
        // K·λ, for the soft rows only: this link's block, then the couplings to the next and the previous
        // link. (No row is soft in the relax pass and in a projection.)
        let soft_rows = !split && links[i].has_soft_rows();
        let mut k_lambda = [0.0; MAX_ROWS];
        if soft_rows {
            for row in 0..n {
                k_lambda[row] = (0..n).map(|k| s[row][k] * lambda[k]).sum();
            }
        }
        let next_rows = links
            .get(i + 1)
            .map_or(0, |next| next.rows.count.min(MAX_ROWS));
        let c = links
            .get(i + 1)
            .map_or([[0.0; MAX_ROWS]; MAX_ROWS], |next| links[i].coupling(next));
        if let Some(next) = links.get(i + 1).filter(|_| soft_rows) {
            let lambda_next = next.active_lambda();
            for row in 0..n {
                k_lambda[row] += (0..next_rows)
                    .map(|k| c[row][k] * lambda_next[k])
                    .sum::<Real>();
            }
        }
        let mut rhs = if split { r } else { [0.0; MAX_ROWS] };
        if let (Some((c_prev, lambda_prev, r_prev)), Some(prev)) =
            (previous, i.checked_sub(1).map(|p| &links[p]))
        {
            // S = B − Cᵢ₋₁ᵀ·C'ᵢ₋₁,   rhs = r̃ − Cᵢ₋₁ᵀ·r'ᵢ₋₁
            let m = prev.rows.count.min(MAX_ROWS);
            for row in 0..n {
                for col in 0..n {
                    let sum: Real = (0..m).map(|k| c_prev[k][row] * prev.c_prime[k][col]).sum();
                    s[row][col] -= sum;
                }
                if soft_rows {
                    k_lambda[row] += (0..m)
                        .map(|k| c_prev[k][row] * lambda_prev[k])
                        .sum::<Real>();
                }
                rhs[row] -= (0..m).map(|k| c_prev[k][row] * r_prev[k]).sum::<Real>();
            }
        }
        if !split {
            let soft = links[i].soft_rhs(&r, &k_lambda);
            for row in 0..n {
                rhs[row] += soft[row];
            }
        }
        // [C' | r'] = S⁻¹·[C | rhs]: the first `next_rows` columns are C, the last is rhs.
        let mut columns = [[0.0; MAX_ROWS + 1]; MAX_ROWS];
        for row in 0..n {
            columns[row][..next_rows].copy_from_slice(&c[row][..next_rows]);
            columns[row][MAX_ROWS] = rhs[row];
        }
        gauss_solve(&mut s, n, &mut columns, next_rows);
        let link = &mut links[i];
        for row in 0..MAX_ROWS {
            link.c_prime[row].copy_from_slice(&columns[row][..MAX_ROWS]);
            link.r_prime[row] = columns[row][MAX_ROWS];
        }
        previous = Some((c, lambda, link.r_prime));
    }
    // Back substitution.
    let mut next: Option<([Real; MAX_ROWS], usize)> = None;
    for i in (0..links.len()).rev() {
        let link = &links[i];
        let n = link.rows.count.min(MAX_ROWS);
        let mut x = link.r_prime;
        if let Some((x_next, m)) = next {
            for (row, value) in x.iter_mut().enumerate().take(n) {
                let sum: Real = (0..m).map(|k| link.c_prime[row][k] * x_next[k]).sum();
                *value -= sum;
            }
        }
        out[i] = link.finish(x, uniform);
        next = Some((x, n));
    }
}

/// [`solve_path`] for a path of one-row joints (a rope chain): the scalar Thomas algorithm, without the
/// block machinery. `uniform` as in [`solve_block_path`].
fn solve_scalar_path(
    links: &mut [Link],
    load: impl Fn(usize) -> Option<(SolverBody, SolverBody)>,
    out: &mut [[Real; MAX_ROWS]],
    uniform: Option<Softness>,
) {
    let split = uniform.is_some();
    // Forward sweep: c'ᵢ = cᵢ/sᵢ, r'ᵢ = (r̃ᵢ − cᵢ₋₁·r'ᵢ₋₁)/sᵢ with sᵢ = bᵢ − cᵢ₋₁·c'ᵢ₋₁ and r̃ the soft
    // right-hand side of `solve_path`.
    let mut previous: Option<(Real, Real, Real, Real)> = None; // (cᵢ₋₁, c'ᵢ₋₁, r'ᵢ₋₁, λᵢ₋₁)
    for i in 0..links.len() {
        let link = &links[i];
        let active = link.rows.count == 1 && link.active[0];
        let lambda = link.active_lambda()[0];
        let c = links
            .get(i + 1)
            .map_or(0.0, |next| links[i].coupling_scalar(next));
        let (mut s, mut r) = if active {
            let row = &link.rows.rows[0];
            let k = Real::from(row.self_coupling(&link.rows.mass_a, &link.rows.mass_b));
            let diagonal = k * (1.0 + REGULARIZATION);
            let residual = load(i).map_or(0.0, |(a, b)| link.row_residual(row, &a, &b));
            let softness = row.target.softness;
            if split {
                (diagonal, residual)
            } else {
                let mut rhs = Real::from(softness.mass_scale) * residual;
                if softness.impulse_scale > 0.0 {
                    let mut k_lambda = diagonal * lambda;
                    if let Some(next) = links.get(i + 1) {
                        k_lambda += c * next.active_lambda()[0];
                    }
                    if let Some((c_prev, _, _, lambda_prev)) = previous {
                        k_lambda += c_prev * lambda_prev;
                    }
                    rhs += Real::from(softness.impulse_scale) * k_lambda;
                }
                (diagonal, rhs)
            }
        } else {
            (1.0, 0.0)
        };
        if let Some((c_prev, c_prime, r_prime, _)) = previous {
            s -= c_prev * c_prime;
            r -= c_prev * r_prime;
        }
        let scale = Real::from(links[i].rows.mass_a.mass.max(links[i].rows.mass_b.mass));
        let (c_prime, r_prime) = if s.abs() <= (scale * RELATIVE_PIVOT).max(Real::MIN_POSITIVE) {
            (0.0, 0.0)
        } else {
            (c / s, r / s)
        };
        let link = &mut links[i];
        link.c_prime[0][0] = c_prime;
        link.r_prime[0] = r_prime;
        previous = Some((c, c_prime, r_prime, lambda));
    }
    // Back substitution.
    let mut next = 0.0;
    for i in (0..links.len()).rev() {
        let x = links[i].r_prime[0] - links[i].c_prime[0][0] * next;
        out[i][0] = x;
        out[i] = links[i].finish(out[i], uniform);
        next = x;
    }
}

/// Added to each row's own `K` entry as a fraction of it: a little compliance that keeps the system of a
/// path with redundant rows (a bridge hung from two anchors constrains more than its bodies' degrees of
/// freedom) well conditioned, as constraint force mixing does.
const REGULARIZATION: Real = 1e-6;

/// Pivots smaller than this fraction of the largest diagonal entry count as zero: the row is redundant.
const RELATIVE_PIVOT: Real = 1e-5;

/// Solves `s·X = columns` in place (Gaussian elimination with partial pivoting) for the top-left `n × n` of
/// `s`, with right-hand sides in the first `m` columns and the last column of `columns`. A pivot that vanishes
/// — a row no body can move along, or a row redundant with the rows before it (a bridge hung from two
/// anchors constrains more than its bodies' degrees of freedom) — gives 0 for that unknown, never a NaN or a
/// huge impulse.
fn gauss_solve(s: &mut Block, n: usize, columns: &mut [[Real; MAX_ROWS + 1]; MAX_ROWS], m: usize) {
    let n = n.min(MAX_ROWS);
    let used = |k: usize| k < m || k == MAX_ROWS;
    let scale = (0..n).map(|i| s[i][i].abs()).fold(0.0, Real::max);
    let tiny = (scale * RELATIVE_PIVOT).max(Real::MIN_POSITIVE);
    let mut singular = [false; MAX_ROWS];
    for c in 0..n {
        let pivot = (c..n)
            .max_by(|&i, &j| s[i][c].abs().total_cmp(&s[j][c].abs()))
            .unwrap_or(c);
        if s[pivot][c].abs() <= tiny {
            singular[c] = true;
            continue;
        }
        s.swap(c, pivot);
        columns.swap(c, pivot);
        let inv = 1.0 / s[c][c];
        for i in (c + 1)..n {
            let factor = s[i][c] * inv;
            if factor == 0.0 {
                continue;
            }
            for k in c..n {
                s[i][k] -= factor * s[c][k];
            }
            for k in (0..=MAX_ROWS).filter(|&k| used(k)) {
                columns[i][k] -= factor * columns[c][k];
            }
        }
    }
    for c in (0..n).rev() {
        if singular[c] {
            columns[c] = [0.0; MAX_ROWS + 1];
            continue;
        }
        for k in (0..=MAX_ROWS).filter(|&k| used(k)) {
            let mut value = columns[c][k];
            for j in (c + 1)..n {
                value -= s[c][j] * columns[j][k];
            }
            columns[c][k] = value / s[c][c];
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn gauss_solve_inverts_a_symmetric_positive_matrix_and_zeroes_singular_unknowns() {
        let mut s = [[0.0; MAX_ROWS]; MAX_ROWS];
        let m = [
            [4.0, 1.0, 0.5, 0.0, 0.0],
            [1.0, 3.0, 0.2, 0.1, 0.0],
            [0.5, 0.2, 2.0, 0.3, 0.0],
            [0.0, 0.1, 0.3, 1.5, 0.0],
            [0.0, 0.0, 0.0, 0.0, 0.0],
        ];
        s.copy_from_slice(&m);
        let x_true = [1.0, -2.0, 0.5, 3.0, 0.0];
        let mut columns = [[0.0; MAX_ROWS + 1]; MAX_ROWS];
        for (row, line) in m.iter().enumerate() {
            columns[row][0] = line.iter().zip(&x_true).map(|(a, x)| a * x).sum();
        }
        gauss_solve(&mut s, MAX_ROWS, &mut columns, 1);
        for (row, x) in x_true.iter().enumerate() {
            assert!((columns[row][0] - x).abs() < 1e-5, "{row}: {columns:?}");
        }
    }
}
