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
//! solves `K·x = r` in O(n). Each row then takes the soft step `Δλ = −mass_scale·x − impulse_scale·λ`
//! (for one row this is exactly the Gauss–Seidel row update of [`crate::part::solve_row`]) and is clamped to
//! its bounds. A rope that is slack and not closing its slack this substep is left out of the system (its
//! row is released); a rope the solution would make push is dropped and the rest solved again (up to 4
//! rounds), so slack links never push. The sweep runs in f64 (a 500-link chain's `K` has a condition number
//! near 10⁵), each row's diagonal gets a 10⁻⁶ relative regularisation and a vanishing pivot gives 0 — a bridge
//! hung from two anchors has redundant rows and a singular `K`. A path of one-row joints (a rope chain) takes a
//! scalar sweep.
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
        self.linear.dot(other.linear) * m.mass + self.angular.dot(m.inertia * other.angular)
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
    /// place. Equality rows take part; a rope only if it is stretched or within [`TAUT_MARGIN`] of its length —
    /// then with target "no longer than now", so that it may pull if moving its neighbours would stretch it
    /// (the active-set rounds drop it if it would have to push).
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
                c > -TAUT_MARGIN
            } else if row.lower == 0.0 {
                c < TAUT_MARGIN
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

    /// The diagonal block `B` (identity for inactive rows, so that they solve to 0).
    fn diagonal(&self) -> Block {
        let mut block = [[0.0; MAX_ROWS]; MAX_ROWS];
        let (ma, mb, rows) = (&self.rows.mass_a, &self.rows.mass_b, self.rows.rows());
        for (i, ri) in rows.iter().enumerate() {
            for (j, rj) in rows.iter().enumerate() {
                block[i][j] = if self.active[i] && self.active[j] {
                    let k = Real::from(ri.a.coupling(ma, &rj.a) + ri.b.coupling(mb, &rj.b));
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
        for (i, ri) in self.rows.rows().iter().enumerate() {
            if !self.active[i] {
                continue;
            }
            let si = if this_b { &ri.b } else { &ri.a };
            for (j, rj) in next.rows.rows().iter().enumerate() {
                if next.active[j] {
                    let sj = if next_b { &rj.b } else { &rj.a };
                    block[i][j] = Real::from(si.coupling(mass, sj));
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
            let new = self.lambda[i] + soft_delta(row, x[i], self.lambda[i]);
            if (row.upper == 0.0 && new > 0.0) || (row.lower == 0.0 && new < 0.0) {
                self.active[i] = false;
                row.apply(&ma, &mb, a, b, -self.lambda[i]);
                self.lambda[i] = 0.0;
                any = true;
            }
        }
        any
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
            let delta = soft_delta(row, x[i], self.lambda[i]);
            let new = (self.lambda[i] + delta).max(row.lower).min(row.upper);
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

/// The soft step of one row from its solution `x`: `Δλ = −mass_scale·x − impulse_scale·λ`.
#[inline]
fn soft_delta(row: &Row, x: Real, lambda: f32) -> f32 {
    let s: Softness = row.target.softness;
    -s.mass_scale * x as f32 - s.impulse_scale * lambda
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
/// bodies), then the block Thomas sweep; returns the solution of each link in `out`.
pub(crate) fn solve_path(
    links: &mut [Link],
    load: impl Fn(usize) -> Option<(SolverBody, SolverBody)>,
    out: &mut Vec<[Real; MAX_ROWS]>,
) {
    out.clear();
    out.resize(links.len(), [0.0; MAX_ROWS]);
    if links.iter().all(|link| link.rows.count <= 1) {
        solve_scalar_path(links, load, out);
        return;
    }
    // Forward sweep. `previous` holds Cᵢ₋₁ and r'ᵢ₋₁; C'ᵢ₋₁ is stored in link i − 1. Loops run over the
    // links' own row counts (1 for a rope, 5 for a hinge).
    let mut previous: Option<(Block, [Real; MAX_ROWS])> = None;
    for i in 0..links.len() {
        let n = links[i].rows.count.min(MAX_ROWS);
        let r = load(i).map_or([0.0; MAX_ROWS], |(a, b)| links[i].residual(&a, &b));
        let mut s = links[i].diagonal();
        let mut rhs = r;
        if let (Some((c_prev, r_prev)), Some(prev)) =
            (previous, i.checked_sub(1).map(|p| &links[p]))
        {
            // S = B − Cᵢ₋₁ᵀ·C'ᵢ₋₁,   rhs = r − Cᵢ₋₁ᵀ·r'ᵢ₋₁
            let m = prev.rows.count.min(MAX_ROWS);
            for row in 0..n {
                for col in 0..n {
                    let sum: Real = (0..m).map(|k| c_prev[k][row] * prev.c_prime[k][col]).sum();
                    s[row][col] -= sum;
                }
                let sum: Real = (0..m).map(|k| c_prev[k][row] * r_prev[k]).sum();
                rhs[row] -= sum;
            }
        }
        let next_rows = links
            .get(i + 1)
            .map_or(0, |next| next.rows.count.min(MAX_ROWS));
        let c = links
            .get(i + 1)
            .map_or([[0.0; MAX_ROWS]; MAX_ROWS], |next| links[i].coupling(next));
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
        previous = Some((c, link.r_prime));
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
        out[i] = x;
        next = Some((x, n));
    }
}

/// [`solve_path`] for a path of one-row joints (a rope chain): the scalar Thomas algorithm, without the
/// block machinery.
fn solve_scalar_path(
    links: &mut [Link],
    load: impl Fn(usize) -> Option<(SolverBody, SolverBody)>,
    out: &mut [[Real; MAX_ROWS]],
) {
    // Forward sweep: c'ᵢ = cᵢ/sᵢ, r'ᵢ = (rᵢ − cᵢ₋₁·r'ᵢ₋₁)/sᵢ with sᵢ = bᵢ − cᵢ₋₁·c'ᵢ₋₁.
    let mut previous: Option<(Real, Real, Real)> = None; // (cᵢ₋₁, c'ᵢ₋₁, r'ᵢ₋₁)
    for i in 0..links.len() {
        let link = &links[i];
        let active = link.rows.count == 1 && link.active[0];
        let (mut s, mut r) = if active {
            let row = &link.rows.rows[0];
            let k = Real::from(row.self_coupling(&link.rows.mass_a, &link.rows.mass_b));
            let residual = load(i).map_or(0.0, |(a, b)| link.row_residual(row, &a, &b));
            (k * (1.0 + REGULARIZATION), residual)
        } else {
            (1.0, 0.0)
        };
        if let Some((c, c_prime, r_prime)) = previous {
            s -= c * c_prime;
            r -= c * r_prime;
        }
        let c = links
            .get(i + 1)
            .map_or(0.0, |next| links[i].coupling_scalar(next));
        let scale = Real::from(links[i].rows.mass_a.mass.max(links[i].rows.mass_b.mass));
        let (c_prime, r_prime) = if s.abs() <= (scale * RELATIVE_PIVOT).max(Real::MIN_POSITIVE) {
            (0.0, 0.0)
        } else {
            (c / s, r / s)
        };
        let link = &mut links[i];
        link.c_prime[0][0] = c_prime;
        link.r_prime[0] = r_prime;
        previous = Some((c, c_prime, r_prime));
    }
    // Back substitution.
    let mut next = 0.0;
    for i in (0..links.len()).rev() {
        let x = links[i].r_prime[0] - links[i].c_prime[0][0] * next;
        out[i][0] = x;
        next = x;
    }
}

/// Added to each row's own `K` entry as a fraction of it: a little compliance that keeps the system of a
/// path with redundant rows (a bridge hung from two anchors constrains more than its bodies' degrees of
/// freedom) well conditioned, as constraint force mixing does.
const REGULARIZATION: Real = 1e-6;

/// How close to taut (m or rad) a one-sided row must be to take part in the position projection.
const TAUT_MARGIN: f32 = 1e-2;

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
