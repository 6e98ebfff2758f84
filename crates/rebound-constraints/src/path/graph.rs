//! The direct solve of a joint graph (every solve and relax pass and the projection): the rows of joints
//! that form no path — a ladder (two ropes per gap), a tree (a ragdoll), a loop (a closed chain, a four-bar
//! linkage) — solved together, exactly, as a path is ([`crate::path`]), through a sparse `L·D·Lᵀ` of
//! `K = J·M⁻¹·Jᵀ` over the joints' rows in a minimum degree order ([`DirectGraph`]).
//!
//! `K` is assembled over the joint rows, the bodies eliminated (`K`'s entries are `J·M⁻¹·Jᵀ` through the
//! bodies two rows share), rather than the saddle point system over bodies and rows together: a joint graph
//! has about as many rows as body coordinates, `K` is as sparse as the joints' adjacency, it is positive
//! semi-definite (so `L·D·Lᵀ` without pivoting holds, as for a path), and the path solver's rows, soft step,
//! active set and updates serve unchanged. See `docs/physics.md`, "Joint graphs".

#![allow(
    clippy::needless_range_loop,
    reason = "the assembly of K reads as its formula with row and column indices"
)]

use super::link::{Link, Mode};
use super::min_degree::{OrderScratch, minimum_degree_order};
use super::row::{MAX_ROWS, Real, Row};
use super::sparse_ldl::{SparseLdl, UpperColumns};
use super::sweep::{Solved, path_shape};
use crate::pair::{BodyPair, dynamic_bodies};
use rebound_dynamics::SolverBody;
use rebound_math::glam::DVec3;
use rebound_math::{Vec3, Vec4};

/// The most joints a graph solved directly may have; a larger component of joints is solved as paths and
/// Gauss–Seidel, as before graphs were solved directly.
pub(crate) const MAX_GRAPH_JOINTS: usize = 256;

/// The most block entries the factorisation of a graph's joints may have (the fill of its minimum degree
/// order, [`minimum_degree_order`]): a graph denser than this — every joint on one body, a mesh — costs more
/// to factorise than Gauss–Seidel does to iterate, and is solved as paths and Gauss–Seidel.
pub(crate) const MAX_GRAPH_FILL: usize = 4 * MAX_GRAPH_JOINTS;

/// Added to each row's own `K` entry as a fraction of it in a graph's system (see
/// [`DirectGraph::assemble`]). A dependent row's pivot is the regularisation of the rows it depends on,
/// which where a linear row depends on a thin bar's angular rows (entries thousands of times larger) puts
/// its pivot ratio near 10⁻⁵: below [`DEPENDENT_PIVOT`](super::sparse_ldl::DEPENDENT_PIVOT) still.
pub(crate) const GRAPH_REGULARIZATION: Real = 1e-9;

/// How far the rows of a graph may move from those its factorisation was made with, as a fraction of each
/// row's Jacobian (`|J − J₀| ≤ ε·|J₀|`), for a pass to keep that factorisation (see [`DirectGraph::solve`]):
/// 1 %, about 0.01 rad of turn of a joint's bodies.
pub(crate) const GRAPH_KEEP_TOLERANCE: f32 = 0.01;

/// One member's rows as a graph's factorisation was made with them: the count, which were in the system,
/// their compliance in `K` (0 but for a projection's stiffening rows) and each row's Jacobian `[J_a,linear,
/// J_a,angular, J_b,linear, J_b,angular]`.
#[derive(Debug, Clone, Copy, PartialEq)]
struct FactoredRows {
    count: usize,
    live: [bool; MAX_ROWS],
    compliance: [Real; MAX_ROWS],
    jacobians: [[Vec3; 4]; MAX_ROWS],
}

impl FactoredRows {
    fn of(link: &Link) -> Self {
        Self {
            count: link.rows.count,
            live: link.live_rows(),
            compliance: compliance(link),
            jacobians: core::array::from_fn(|k| jacobian(&link.rows.rows[k])),
        }
    }

    /// Whether `link` has as many rows as these, the same ones in the system.
    fn has_pattern_of(&self, link: &Link) -> bool {
        self.count == link.rows.count && self.live == link.live_rows()
    }

    /// Whether `link` has rows with the same compliance as these, each within [`GRAPH_KEEP_TOLERANCE`] of
    /// them.
    fn moved_within_tolerance(&self, link: &Link) -> bool {
        // The same bits, not merely close values: the compliance enters `K` as it is.
        let bits = |c: &[Real; MAX_ROWS]| c.map(Real::to_bits);
        if bits(&self.compliance) != bits(&compliance(link)) {
            return false;
        }
        let tolerance = GRAPH_KEEP_TOLERANCE * GRAPH_KEEP_TOLERANCE;
        link.rows
            .rows()
            .iter()
            .zip(&self.jacobians)
            .all(|(row, kept)| {
                let now = jacobian(row);
                let (mut change, mut size) = (0.0, 0.0);
                for (now, kept) in now.iter().zip(kept) {
                    change += (*now - *kept).length_squared();
                    size += kept.length_squared();
                }
                change <= tolerance * size
            })
    }
}

/// Whether row `k` of `link` is a one-sided row a joint appends to its equality rows (a ball joint's
/// limits, after its point rows): such rows enter and leave the system as the limits are reached, and a
/// pass whose only change from the rows the factorisation was made with is a few of them keeps it
/// ([`DirectGraph::solve_changed`]). A rope's row (a link's first) is not one.
fn is_appended(link: &Link, k: usize) -> bool {
    k > 0 && k < link.rows.count && link.rows.rows[k].is_bounded_at_zero()
}

/// The most appended rows ([`is_appended`]) a pass may have in or out of the system against the rows the
/// factorisation was made with, for it to keep that factorisation.
const MAX_CHANGED_ROWS: usize = 4;

/// The compliance each row of `link` adds to its diagonal of `K` ([`DirectGraph::assemble`]).
fn compliance(link: &Link) -> [Real; MAX_ROWS] {
    match link.mode {
        Mode::Position => link.compliance,
        Mode::Velocity => [0.0; MAX_ROWS],
    }
}

/// A row's Jacobian, side A's then side B's.
fn jacobian(row: &Row) -> [Vec3; 4] {
    [row.a.linear, row.a.angular, row.b.linear, row.b.angular]
}

/// How a joint of a graph is coupled with another one: through one or two shared dynamic bodies, each given
/// as (the side of this joint on it, the side of the other joint on it), `true` = body B.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
struct Coupling {
    other: usize,
    sides: [Option<(bool, bool)>; 2],
}

/// One joint graph solved directly: its joints' couplings and elimination order, made once a step
/// ([`DirectGraph::build`]), and the buffers of its factorisation, reused from pass to pass.
#[derive(Debug, Clone, Default)]
pub(crate) struct DirectGraph {
    /// Per member (slot), the joints it is coupled with (by slot) and through which sides.
    couplings: Vec<Vec<Coupling>>,
    /// The members in elimination order, and each member's place in it.
    order: Vec<usize>,
    position: Vec<usize>,
    /// Per member, its dynamic bodies as indices into `deltas` (the active-set check's body changes).
    bodies: Vec<[Option<usize>; 2]>,
    body_count: usize,
    /// Scratch of a solve: each member's first row in the system, `K`, its factorisation, the right-hand
    /// side (then the solution), `λ` and `K·λ`, and each body's change from a solution.
    offset: Vec<usize>,
    inverse: Vec<[[DVec3; 4]; MAX_ROWS]>,
    matrix: UpperColumns,
    ldl: SparseLdl,
    rhs: Vec<Real>,
    lambda: Vec<Real>,
    k_lambda: Vec<Real>,
    deltas: Vec<[Vec3; 2]>,
    /// Scratch of a solve whose appended rows differ from the factorisation's
    /// ([`DirectGraph::solve_changed`]): each changed row's (slot, row, index in `K`, whether it is in the
    /// system now), their columns over the factorised rows (dense, `n` each), those solved with the factors,
    /// their bordered Schur complement (row-major) and its right-hand side.
    changed: Vec<(usize, usize, usize, bool)>,
    changed_columns: Vec<Real>,
    solved_columns: Vec<Real>,
    schur: Vec<Real>,
    schur_rhs: Vec<Real>,
    /// Whether `matrix` and `ldl` hold a factorisation of this step, and per member the rows it was made
    /// for.
    factored: bool,
    kept: Vec<FactoredRows>,
    /// Scratch of `build`: the joints' dynamic sides sorted by body, the adjacency by slot and the order's.
    ends: Vec<(usize, usize, bool)>,
    adjacency: Vec<Vec<usize>>,
    order_scratch: OrderScratch,
}

impl DirectGraph {
    /// Makes the graph of the joints `members` (joint `i` between the bodies of `pair(i)`): which members
    /// share a dynamic body, and the minimum degree order. Returns the fill of that order.
    pub fn build<'p>(&mut self, members: &[usize], pair: impl Fn(usize) -> &'p BodyPair) -> usize {
        let m = members.len();
        // (body, slot, side) for every dynamic side, sorted by body: each run is the joints on one body.
        let mut ends = core::mem::take(&mut self.ends);
        ends.clear();
        for (slot, &index) in members.iter().enumerate() {
            let [a, b] = dynamic_bodies(pair(index));
            ends.extend(a.map(|body| (body, slot, false)));
            ends.extend(b.map(|body| (body, slot, true)));
        }
        ends.sort_unstable();
        self.couplings
            .resize_with(m.max(self.couplings.len()), Vec::new);
        self.couplings.truncate(m);
        self.couplings.iter_mut().for_each(Vec::clear);
        self.bodies.clear();
        self.bodies.resize(m, [None; 2]);
        self.body_count = 0;
        let mut run = 0;
        while run < ends.len() {
            let body = ends[run].0;
            let end = run + ends[run..].iter().take_while(|e| e.0 == body).count();
            let local = self.body_count;
            self.body_count += 1;
            for &(_, slot, side) in &ends[run..end] {
                self.bodies[slot][usize::from(side)] = Some(local);
                for &(_, other, other_side) in &ends[run..end] {
                    if other == slot {
                        continue;
                    }
                    let list = &mut self.couplings[slot];
                    match list.iter_mut().find(|c| c.other == other) {
                        Some(c) => c.sides[1] = Some((side, other_side)),
                        None => list.push(Coupling {
                            other,
                            sides: [Some((side, other_side)), None],
                        }),
                    }
                }
            }
            run = end;
        }
        self.ends = ends;
        self.adjacency
            .resize_with(m.max(self.adjacency.len()), Vec::new);
        for (slot, set) in self.adjacency.iter_mut().enumerate().take(m) {
            set.clear();
            set.extend(self.couplings[slot].iter().map(|c| c.other));
        }
        let adjacency = &self.adjacency;
        let fill = minimum_degree_order(
            m,
            |i| &adjacency[i],
            &mut self.order_scratch,
            &mut self.order,
        );
        self.position.clear();
        self.position.resize(m, 0);
        for (place, &slot) in self.order.iter().enumerate() {
            self.position[slot] = place;
        }
        // A new step: new inverse masses, and perhaps new members.
        self.factored = false;
        fill
    }

    /// Whether the factorisation made last serves a pass over `links`: the same rows in the system but at
    /// most [`MAX_CHANGED_ROWS`] appended ones ([`is_appended`], taken in or out by
    /// [`DirectGraph::solve_changed`]), with the same compliance, each moved by less than
    /// [`GRAPH_KEEP_TOLERANCE`].
    fn keeps_factorisation(&self, links: &[Link]) -> bool {
        if !self.factored || self.kept.len() != links.len() {
            return false;
        }
        let mut changed = 0;
        for (link, kept) in links.iter().zip(&self.kept) {
            let live = link.live_rows();
            for k in 0..MAX_ROWS {
                if live[k] != kept.live[k] {
                    if !is_appended(link, k) {
                        return false;
                    }
                    changed += 1;
                }
            }
            if kept.count != link.rows.count || !kept.moved_within_tolerance(link) {
                return false;
            }
        }
        changed <= MAX_CHANGED_ROWS
    }

    /// One solve of the graph's system (as [`super::solve_path`] of a path): the residuals from the bodies'
    /// velocities (`load(i)` gives member `i`'s bodies), `K` over the rows in the system, its factorisation
    /// and solve; the solution `y` of each link in `out`, the change of its accumulated impulses being `−y`.
    pub fn solve<'b>(
        &mut self,
        links: &mut [Link],
        load: impl Fn(usize) -> Option<(&'b SolverBody, &'b SolverBody)>,
        out: &mut Vec<[Real; MAX_ROWS]>,
    ) -> Solved {
        out.clear();
        out.resize(links.len(), [0.0; MAX_ROWS]);
        // The updates (`Link::impulse`, `M⁻¹·Jᵀ` in f32) and the residuals (the lanes) at the rows of the pass.
        for link in links.iter_mut() {
            link.fill_impulses::<MAX_ROWS>();
            link.fill_lanes();
        }
        let shape = path_shape(links, links.len());
        // `K` and its factorisation at the rows they were made with while those stay within 1 % of the
        // pass's: the solve is then a step of an iterative refinement of the exact one, see `docs/physics.md`,
        // "Joint graphs".
        if !self.keeps_factorisation(links) {
            // The same rows in the system in the same order give `K` the same pattern, and its factors too.
            let same_pattern = self.factored
                && self.kept.len() == links.len()
                && links
                    .iter()
                    .zip(&self.kept)
                    .all(|(link, kept)| kept.has_pattern_of(link));
            self.assemble(links);
            self.ldl.factor(&self.matrix, same_pattern);
            self.kept.clear();
            self.kept.extend(links.iter().map(FactoredRows::of));
            self.factored = true;
        }
        let n = self.matrix.order();
        self.rhs.clear();
        self.rhs.resize(n, 0.0);
        for (slot, link) in links.iter().enumerate() {
            let r = load(slot).map_or([0.0; MAX_ROWS], |(a, b)| link.residual(a, b));
            let at = self.offset[slot];
            for (k, &r) in r.iter().enumerate().take(link.rows.count) {
                self.rhs[at + k] = r;
            }
        }
        self.couple_changed(links);
        if shape.uniform.is_none() {
            // The soft step of every row at once: rhs = mass_scale∘r + impulse_scale∘(K·λ).
            self.lambda.clear();
            self.lambda.resize(n, 0.0);
            for (slot, link) in links.iter().enumerate() {
                let at = self.offset[slot];
                let lambda = link.active_lambda();
                self.lambda[at..at + link.rows.count].copy_from_slice(&lambda[..link.rows.count]);
            }
            self.k_lambda.resize(n, 0.0);
            self.matrix.multiply(&self.lambda, &mut self.k_lambda);
            self.multiply_changed();
            for (slot, link) in links.iter().enumerate() {
                let (at, count) = (self.offset[slot], link.rows.count);
                let mut r = [0.0; MAX_ROWS];
                let mut k_lambda = [0.0; MAX_ROWS];
                r[..count].copy_from_slice(&self.rhs[at..at + count]);
                k_lambda[..count].copy_from_slice(&self.k_lambda[at..at + count]);
                let soft = link.soft_rhs(&r, &k_lambda);
                self.rhs[at..at + count].copy_from_slice(&soft[..count]);
            }
        }
        if self.changed.is_empty() {
            self.ldl.solve(&mut self.rhs);
        } else {
            self.solve_changed();
        }
        let mut released = false;
        for ((slot, link), out) in links.iter().enumerate().zip(out.iter_mut()) {
            let (at, count) = (self.offset[slot], link.rows.count);
            let mut x = [0.0; MAX_ROWS];
            x[..count].copy_from_slice(&self.rhs[at..at + count]);
            *out = link.finish(x, shape.uniform);
            released |= link.would_deactivate(out);
        }
        Solved {
            left_out: shape.left_out,
            released,
        }
    }

    /// `K` over the links' rows in elimination order (each link's rows together), upper triangle by
    /// column: a link's own block (over both its bodies, each diagonal entry regularised as a path's, with
    /// a stiffening row's compliance in a projection) and its couplings with the links before it in the
    /// order. A row not in the system has a 1 on the diagonal and nothing else.
    ///
    /// The entries are computed in f64 from the rows' f32 Jacobians and the bodies' inverse masses: rows
    /// that are redundant (a loop of hinges constrains its out-of-plane motion more than once) are then
    /// dependent to the rounding of their Jacobians, and their pivots fall to the regularisation, far
    /// below [`DEPENDENT_PIVOT`](super::sparse_ldl::DEPENDENT_PIVOT) of their diagonal. Summed in f32, as
    /// a path's blocks are, the rounding of thin bars' large inverse inertias left such a pivot near it.
    fn assemble(&mut self, links: &[Link]) {
        self.offset.clear();
        self.offset.resize(links.len(), 0);
        let mut rows = 0;
        for &slot in &self.order {
            self.offset[slot] = rows;
            rows += links[slot].rows.count;
        }
        self.inverse.clear();
        self.inverse.extend(links.iter().map(inverse_jacobians));
        let a = &mut self.matrix;
        a.clear();
        for (place, &q) in self.order.iter().enumerate() {
            let link = &links[q];
            let live = link.live_rows();
            let inverse = &self.inverse[q];
            let own = [Some((false, false)), Some((true, true))];
            // The diagonal: regularised, with a stiffening row's compliance in a projection; 1 for a row
            // not in the system.
            let diagonals: [Real; MAX_ROWS] =
                core::array::from_fn(|l| match link.rows.rows().get(l) {
                    Some(row) if live[l] => {
                        let mut d = coupling(row, &inverse[l], own) * (1.0 + GRAPH_REGULARIZATION);
                        if link.mode == Mode::Position {
                            d += link.compliance[l];
                        }
                        d
                    }
                    _ => 1.0,
                });
            for l in 0..link.rows.count {
                if live[l] {
                    for c in &self.couplings[q] {
                        if self.position[c.other] >= place {
                            continue;
                        }
                        let other = &links[c.other];
                        let other_live = other.live_rows();
                        for (k, row) in other.rows.rows().iter().enumerate() {
                            if other_live[k] {
                                let value = coupling(row, &inverse[l], c.sides);
                                a.entries.push((self.offset[c.other] + k, value));
                            }
                        }
                    }
                }
                let column = self.offset[q];
                for (k, row) in link.rows.rows().iter().enumerate().take(l) {
                    if live[k] && live[l] {
                        a.entries
                            .push((column + k, coupling(row, &inverse[l], own)));
                    }
                }
                a.entries.push((column + l, diagonals[l]));
                a.end_column();
            }
        }
    }

    /// The appended rows whose place in the system differs from the factorisation's (added, or left out)
    /// and, for an added one, its column of `K` at the pass's rows over the factorised rows still in the
    /// system (dense, in `changed_columns`) and its entries with the other added rows (`schur`, before the
    /// complement is taken), each diagonal entry regularised as in [`DirectGraph::assemble`].
    fn couple_changed(&mut self, links: &[Link]) {
        self.changed.clear();
        for (slot, (link, kept)) in links.iter().zip(&self.kept).enumerate() {
            let live = link.live_rows();
            for k in (0..link.rows.count).filter(|&k| live[k] != kept.live[k]) {
                self.changed.push((slot, k, self.offset[slot] + k, live[k]));
            }
        }
        let (n, s) = (self.matrix.order(), self.changed.len());
        self.changed_columns.clear();
        self.changed_columns.resize(n * s, 0.0);
        self.schur.clear();
        self.schur.resize(s * s, 0.0);
        let own = [Some((false, false)), Some((true, true))];
        let kept = &self.kept;
        for (e, &(q, k, at, added)) in self.changed.iter().enumerate() {
            let column = &mut self.changed_columns[e * n..(e + 1) * n];
            if !added {
                // Left out: its unknown is held at 0 by a multiplier on the unit column.
                column[at] = 1.0;
                continue;
            }
            let inverse = inverse_jacobians(&links[q])[k];
            let mut add = |slot: usize, sides: [Option<(bool, bool)>; 2]| {
                let link = &links[slot];
                let live = link.live_rows();
                for (i, row) in link.rows.rows().iter().enumerate() {
                    if live[i] && kept[slot].live[i] {
                        column[self.offset[slot] + i] = coupling(row, &inverse, sides);
                    }
                }
            };
            add(q, own);
            for c in &self.couplings[q] {
                add(c.other, c.sides);
            }
            for (f, &(slot, l, _, other_added)) in self.changed.iter().enumerate() {
                if !other_added {
                    continue;
                }
                let row = &links[slot].rows.rows[l];
                let sides = if slot == q {
                    Some(own)
                } else {
                    self.couplings[q]
                        .iter()
                        .find(|c| c.other == slot)
                        .map(|c| c.sides)
                };
                let mut value = sides.map_or(0.0, |sides| coupling(row, &inverse, sides));
                if f == e {
                    value *= 1.0 + GRAPH_REGULARIZATION;
                    if links[q].mode == Mode::Position {
                        value += links[q].compliance[k];
                    }
                }
                self.schur[e * s + f] = value;
            }
        }
    }

    /// Makes `k_lambda` (`A·λ` of the factorised matrix `A`) the pass's `K·λ`: the added rows' couplings
    /// (their entries of `A·λ` are `λ` itself, `A` having a 1 on their diagonals). A row left out has
    /// `λ = 0` and an entry no one reads.
    fn multiply_changed(&mut self) {
        let (n, s) = (self.matrix.order(), self.changed.len());
        for (e, &(_, _, at, added)) in self.changed.iter().enumerate() {
            if !added {
                continue;
            }
            let column = &self.changed_columns[e * n..(e + 1) * n];
            let lambda = self.lambda[at];
            let mut own = 0.0;
            for (i, &value) in column.iter().enumerate() {
                self.k_lambda[i] += value * lambda;
                own += value * self.lambda[i];
            }
            for (f, &(_, _, other, _)) in self.changed.iter().enumerate() {
                own += self.schur[e * s + f] * self.lambda[other];
            }
            self.k_lambda[at] = own;
        }
    }

    /// `K·x = rhs` (in `rhs`) with the factorisation of `A`, made with other appended rows in the system:
    /// with `G` the changed rows' columns (an added row's coupling with the rows of `A` still in the
    /// system, a left-out row's unit column, whose multiplier holds its unknown at 0) and `E` the added
    /// rows' block (0 for the left-out ones), the bordered system's Schur complement
    ///
    /// ```text
    /// z = A⁻¹·r_A,   Y = A⁻¹·G,   S = E − Gᵀ·Y,   u = S⁻¹·(r_E − Gᵀ·z),   x = z − Y·u
    /// ```
    ///
    /// (`r_E` the added rows' right-hand sides, 0 for the others) — `s + 1` solves with the kept factors
    /// and a dense `s × s` elimination, `s ≤` [`MAX_CHANGED_ROWS`]. An added row takes its `u`, a left-out
    /// row 0.
    fn solve_changed(&mut self) {
        let (n, s) = (self.matrix.order(), self.changed.len());
        self.schur_rhs.clear();
        for &(_, _, at, added) in &self.changed {
            self.schur_rhs.push(if added { self.rhs[at] } else { 0.0 });
            self.rhs[at] = 0.0;
        }
        self.ldl.solve(&mut self.rhs);
        self.solved_columns.clear();
        self.solved_columns.extend_from_slice(&self.changed_columns);
        for f in 0..s {
            self.ldl.solve(&mut self.solved_columns[f * n..(f + 1) * n]);
        }
        for e in 0..s {
            let column = &self.changed_columns[e * n..(e + 1) * n];
            self.schur_rhs[e] -= dot(column, &self.rhs);
            for f in 0..s {
                self.schur[e * s + f] -= dot(column, &self.solved_columns[f * n..(f + 1) * n]);
            }
        }
        eliminate(&mut self.schur, &mut self.schur_rhs, s);
        for (f, &u) in self.schur_rhs.iter().enumerate() {
            for (r, &y) in self
                .rhs
                .iter_mut()
                .zip(&self.solved_columns[f * n..(f + 1) * n])
            {
                *r -= y * u;
            }
        }
        for (&(_, _, at, added), &u) in self.changed.iter().zip(&self.schur_rhs) {
            self.rhs[at] = if added { u } else { 0.0 };
        }
    }

    /// Activates every row bounded at 0 left out of the system that the solution `out` of the others would
    /// violate (see [`super::activate_violations`]): its `Ċ + bias` (or `C` in a projection) with the
    /// bodies' changes from every link's update. `load(i)` gives member `i`'s bodies. Returns whether any
    /// row was activated.
    pub fn activate_violations<'b>(
        &mut self,
        links: &mut [Link],
        out: &[[Real; MAX_ROWS]],
        load: impl Fn(usize) -> Option<(&'b SolverBody, &'b SolverBody)>,
    ) -> bool {
        self.deltas.clear();
        self.deltas.resize(self.body_count, [Vec3::ZERO; 2]);
        for (slot, (link, x)) in links.iter().zip(out).enumerate() {
            let mut change = [Vec4::ZERO; 4];
            for k in 0..link.rows.count {
                if link.active[k] {
                    let amount = link.increment(k, x[k]);
                    for (change, &unit) in change.iter_mut().zip(&link.impulse[k]) {
                        *change += unit * amount;
                    }
                }
            }
            for (side, body) in self.bodies[slot].iter().enumerate() {
                if let Some(body) = body {
                    let delta = &mut self.deltas[*body];
                    delta[0] += change[2 * side].truncate();
                    delta[1] += change[2 * side + 1].truncate();
                }
            }
        }
        let mut any = false;
        for (slot, link) in links.iter_mut().enumerate() {
            let left_out = link.left_out();
            if !left_out.contains(&true) {
                continue;
            }
            let bodies = load(slot);
            let zero = [Vec3::ZERO; 2];
            let [da, db] = self.bodies[slot].map(|b| b.map_or(zero, |b| self.deltas[b]));
            for r in (0..MAX_ROWS).filter(|&r| left_out[r]) {
                let row = &link.rows.rows[r];
                let mut free = row.target.bias
                    + (row.a.linear.dot(da[0]) + row.a.angular.dot(da[1]))
                    + (row.b.linear.dot(db[0]) + row.b.angular.dot(db[1]));
                if link.mode == Mode::Velocity
                    && let Some((a, b)) = bodies
                {
                    free += row.velocity(a, b);
                }
                let violated = if row.upper == 0.0 {
                    free > 0.0
                } else {
                    free < 0.0
                };
                if violated {
                    link.active[r] = true;
                    any = true;
                }
            }
        }
        any
    }
}

/// `a·b` over the common length.
fn dot(a: &[Real], b: &[Real]) -> Real {
    a.iter().zip(b).map(|(a, b)| a * b).sum()
}

/// Solves `S·u = b` in place (`u` in `b`) for the `s × s` matrix `S` (row-major, destroyed) by Gaussian
/// elimination with partial pivoting (`S` of [`DirectGraph::solve_changed`] is symmetric but indefinite); a
/// pivot at or below 10⁻¹² of the largest entry counts as zero and its unknown is 0.
fn eliminate(a: &mut [Real], b: &mut [Real], s: usize) {
    let tiny = 1e-12 * a.iter().fold(0.0, |m: Real, v| m.max(v.abs()));
    // `s ≤ MAX_CHANGED_ROWS`: a pass with more changed rows factorises again.
    let mut zero = [false; MAX_CHANGED_ROWS];
    for j in 0..s {
        let Some(pivot) = (j..s).max_by(|&p, &q| a[p * s + j].abs().total_cmp(&a[q * s + j].abs()))
        else {
            continue;
        };
        if a[pivot * s + j].abs() <= tiny {
            if let Some(zero) = zero.get_mut(j) {
                *zero = true;
            }
            continue;
        }
        if pivot != j {
            for c in 0..s {
                a.swap(j * s + c, pivot * s + c);
            }
            b.swap(j, pivot);
        }
        for i in j + 1..s {
            let factor = a[i * s + j] / a[j * s + j];
            if factor != 0.0 {
                for c in j..s {
                    a[i * s + c] -= factor * a[j * s + c];
                }
                b[i] -= factor * b[j];
            }
        }
    }
    for j in (0..s).rev() {
        if zero.get(j).copied().unwrap_or(true) {
            b[j] = 0.0;
            continue;
        }
        let mut value = b[j];
        for c in j + 1..s {
            value -= a[j * s + c] * b[c];
        }
        b[j] = value / a[j * s + j];
    }
}

/// `M⁻¹·Jᵀ` of each row of `link` in f64, `[m_a⁻¹·J_a,linear, I_a⁻¹·J_a,angular, m_b⁻¹·J_b,linear,
/// I_b⁻¹·J_b,angular]`, from its f32 Jacobians and inverse masses (see [`DirectGraph::assemble`]).
fn inverse_jacobians(link: &Link) -> [[DVec3; 4]; MAX_ROWS] {
    let (ma, mb) = (&link.rows.mass_a, &link.rows.mass_b);
    let (ia, ib) = (ma.inertia.as_dmat3(), mb.inertia.as_dmat3());
    let (wa, wb) = (f64::from(ma.mass), f64::from(mb.mass));
    core::array::from_fn(|k| match link.rows.rows().get(k) {
        Some(row) => [
            row.a.linear.as_dvec3() * wa,
            ia * row.a.angular.as_dvec3(),
            row.b.linear.as_dvec3() * wb,
            ib * row.b.angular.as_dvec3(),
        ],
        None => [DVec3::ZERO; 4],
    })
}

/// The entry of `K` between a row of one link (`row`) and a row of another (or the same) link given by its
/// `M⁻¹·Jᵀ` (`inverse`, [`inverse_jacobians`]), through the bodies they share (`sides`: on each, the side
/// of the other row's link and the side of `row`'s link, `true` = body B): `Σ s_row·(M⁻¹·s_otherᵀ)`.
fn coupling(row: &Row, inverse: &[DVec3; 4], sides: [Option<(bool, bool)>; 2]) -> Real {
    let mut sum = 0.0;
    for (other_b, row_b) in sides.into_iter().flatten() {
        let side = if row_b { &row.b } else { &row.a };
        let at = if other_b { 2 } else { 0 };
        sum +=
            side.linear.as_dvec3().dot(inverse[at]) + side.angular.as_dvec3().dot(inverse[at + 1]);
    }
    sum
}
