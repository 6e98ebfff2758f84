//! A link's share of the path's linear system `K·x = r` (every solve and relax pass and the projection):
//! its diagonal and coupling blocks of `K = J·M⁻¹·Jᵀ` ([`Link::fill_blocks`]), the residuals and the soft
//! right-hand side, and the update of impulses and bodies from the solution ([`Link::apply_solution`]).

#![allow(
    clippy::needless_range_loop,
    reason = "dense block algebra reads as the formulas with indices"
)]

use super::factor::Block;
use super::factor::REGULARIZATION;
use super::link::{LANES, Link, Mode};
use super::row::{MAX_ROWS, Real, Row, displace_body};
use crate::part::clamp_impulse;
use rebound_dynamics::{Softness, SolverBody};
use rebound_math::{Mat4, Vec3, Vec4};

impl Link {
    /// The residual `Ċ + bias` of each active row (0 for the others), in the block sweep: the first
    /// [`LANES`] rows four lanes wide from the Jacobians in `lanes` ([`Link::fill_lanes`], current with
    /// the blocks), each lane the very operations of [`Row::velocity`] — `(j.x·v.x + j.y·v.y) + j.z·v.z` per
    /// vector, `(a.linear + a.angular) + (b.linear + b.angular)`, then `+ bias` — so the same bits as one row
    /// at a time; the rows after them one at a time.
    pub(super) fn residual(&self, a: &SolverBody, b: &SolverBody) -> [Real; MAX_ROWS] {
        let mut r = [0.0; MAX_ROWS];
        let rows = self.rows.rows();
        if self.mode == Mode::Position {
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
    pub(super) fn fill_lanes(&mut self) {
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
    pub(super) fn row_residual(&self, row: &Row, a: &SolverBody, b: &SolverBody) -> Real {
        if self.mode == Mode::Position {
            Real::from(row.target.bias)
        } else {
            Real::from(row.velocity(a, b) + row.target.bias)
        }
    }

    /// The right-hand side of the soft step of each active row (0 for the others): `mass_scale·r +
    /// impulse_scale·(K·λ)`, from its residual `r` and its row of `K·λ` (see [`solve_path`]).
    pub(super) fn soft_rhs(
        &self,
        r: &[Real; MAX_ROWS],
        k_lambda: &[Real; MAX_ROWS],
    ) -> [Real; MAX_ROWS] {
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
    #[inline(always)]
    pub(super) fn finish(
        &self,
        mut x: [Real; MAX_ROWS],
        uniform: Option<Softness>,
    ) -> [Real; MAX_ROWS] {
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
    pub(super) fn has_soft_rows(&self) -> bool {
        self.rows
            .rows()
            .iter()
            .zip(&self.active)
            .any(|(row, &active)| active && row.target.softness.impulse_scale > 0.0)
    }

    /// The accumulated impulses as the solve's unknowns (0 for rows not in the system).
    pub(super) fn active_lambda(&self) -> [Real; MAX_ROWS] {
        let mut out = [0.0; MAX_ROWS];
        for ((out, &lambda), &active) in out.iter_mut().zip(&self.lambda).zip(&self.active) {
            if active {
                *out = Real::from(lambda);
            }
        }
        out
    }

    /// The rows bounded at 0 (ropes, limits) that are not in the system.
    pub(super) fn left_out(&self) -> [bool; MAX_ROWS] {
        let mut out = [false; MAX_ROWS];
        for ((out, row), &active) in out.iter_mut().zip(self.rows.rows()).zip(&self.active) {
            *out = !active && row.is_bounded_at_zero();
        }
        out
    }

    /// The rows that take part in the system: active ones (never one past the row count).
    pub(super) fn live_rows(&self) -> [bool; MAX_ROWS] {
        let mut live = [false; MAX_ROWS];
        for (k, (live, &active)) in live.iter_mut().zip(&self.active).enumerate() {
            *live = active && k < self.rows.count;
        }
        live
    }

    /// Makes the diagonal block `B` of this link (`J·M⁻¹·Jᵀ` of its rows over both bodies, each diagonal
    /// entry regularised) and its coupling block `C` with `next` through their shared body (`next`'s second
    /// element: this link's side on it, then `next`'s; `true` = body B) — the next link, or, `before`, the
    /// previous one in a path's side solved backward — over the first `N` rows, in `b_block` and `c_block`. A row not in the system — inactive, or past the link's row count
    /// — has a zero row and column in both, which the factorisation ([`ldl_factor`]) solves to 0.
    ///
    /// `B` is symmetric: its upper triangle is computed and mirrored. Each row's `I⁻¹·J_angular`, turned once
    /// when the row was pushed ([`JointRows::turned`]), serves both blocks: with `sᵢ` this link's side of row
    /// `i` on the shared body and `sⱼ` the next link's, `Cᵢⱼ = sⱼ·M⁻¹·sᵢᵀ = m⁻¹·(sⱼ.linear·sᵢ.linear) +
    /// sⱼ.angular·(I⁻¹·sᵢ.angular)`, so the next link's rows are not turned again here. The entries are
    /// summed in f32 (the precision of the rows), four lanes at a time, and the blocks kept in f64.
    pub(super) fn fill_blocks<const N: usize>(
        &mut self,
        next: Option<(&Link, (bool, bool))>,
        before: bool,
    ) {
        let live = self.live_rows();
        let rows = &self.rows.rows;
        // Each row's Jacobian `[J_a,linear, J_a,angular, J_b,linear, J_b,angular]` and `M⁻¹·Jᵀ` in the same
        // order, as 4-lane vectors (w = 0), zero for a row not in the system: an entry is then four lane
        // products summed once. Every entry is written once, here and below, rather than the arrays and
        // blocks cleared first: clearing these few hundred bytes would call the C library's `memset`.
        let lanes = |v: Vec3| v.extend(0.0);
        let jacobian: [[Vec4; 4]; N] = core::array::from_fn(|k| match rows.get(k) {
            Some(row) if live[k] => {
                [row.a.linear, row.a.angular, row.b.linear, row.b.angular].map(lanes)
            }
            _ => [Vec4::ZERO; 4],
        });
        self.fill_impulses::<N>();
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
                    if self.mode == Mode::Position && live[i] {
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
        let Some((next, (this_b, next_b))) = next else {
            for row in c.iter_mut().take(N) {
                row[..N].fill(0.0);
            }
            return;
        };
        let shared = if this_b { 2 } else { 0 };
        let next_live = next.live_rows();
        if before {
            // Toward the link before, in a path's side solved backward: `C` of that link transposed, each
            // entry its lane products (which commute) summed as that link sums them — its `M⁻¹·sⱼᵀ`, turned
            // when its rows were built, dotted with this link's side — so the same bits.
            let next_rows = &next.rows;
            let next_impulses: [[Vec4; 2]; N] =
                core::array::from_fn(|j| match next_rows.rows.get(j) {
                    Some(row) if next_live[j] => {
                        let [ta, tb] = next_rows.turned(j);
                        if next_b {
                            [row.b.linear * next_rows.mass_b.mass, tb].map(lanes)
                        } else {
                            [row.a.linear * next_rows.mass_a.mass, ta].map(lanes)
                        }
                    }
                    _ => [Vec4::ZERO; 2],
                });
            let sides: [[Vec4; 2]; N] =
                core::array::from_fn(|i| [jacobian[i][shared], jacobian[i][shared + 1]]);
            fill_coupling::<N>(c, &sides, &next_impulses, (live, next_live));
            return;
        }
        let next_sides: [[Vec4; 2]; N] = core::array::from_fn(|j| match next.rows.rows.get(j) {
            Some(row) if next_live[j] => {
                let side = if next_b { &row.b } else { &row.a };
                [side.linear, side.angular].map(lanes)
            }
            _ => [Vec4::ZERO; 2],
        });
        let impulses: [[Vec4; 2]; N] =
            core::array::from_fn(|i| [inverse[i][shared], inverse[i][shared + 1]]);
        fill_coupling::<N>(c, &impulses, &next_sides, (live, next_live));
    }

    /// Writes `M⁻¹·Jᵀ` of the first `N` rows into `impulse` ([`Link::impulse`]: zero for a row not in the
    /// system), as [`Link::fill_blocks`] makes it with the blocks. The entries past `N` are left as they
    /// are: a sweep `N` wide reads the rows below the link's row count, at most `N`.
    pub(super) fn fill_impulses<const N: usize>(&mut self) {
        let live = self.live_rows();
        let (ma, mb, rows) = (&self.rows.mass_a, &self.rows.mass_b, &self.rows.rows);
        let lanes = |v: Vec3| v.extend(0.0);
        for k in 0..N {
            self.impulse[k] = match rows.get(k) {
                Some(row) if live[k] => {
                    let [ta, tb] = self.rows.turned(k);
                    [row.a.linear * ma.mass, ta, row.b.linear * mb.mass, tb].map(lanes)
                }
                _ => [Vec4::ZERO; 4],
            };
        }
    }

    /// [`Link::coupling`] for two one-row links: the single entry, without building a block.
    pub(super) fn coupling_scalar(&self, next: &Link) -> Real {
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
        if self.rows.count == 1 && self.mode != Mode::Position {
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
        if self.mode == Mode::Position && rows.count == 1 {
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
        let positions = self.mode == Mode::Position;
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

/// The coupling block `C` of [`Link::fill_blocks`] over the first `N` rows: `Cᵢⱼ = (uᵢ·vⱼ)`, with `uᵢ` the two
/// 4-lane vectors of row `i` of one link and `vⱼ` those of row `j` of its neighbour on the shared body (one of
/// them a side of a row's Jacobian, the other `M⁻¹·Jᵀ` of a row; w = 0), 0 where row `i` or row `j` is not
/// in the system (`live`).
///
/// Each entry is the lane products' sum `a = u₀∘v₀ + u₁∘v₁` added up as `(a.x + a.y) + (a.z + a.w)` — what
/// `(u₀ * v₀ + u₁ * v₁).element_sum()` gives with glam's SIMD (and, as `a.w` is +0, without it) — but four
/// entries at a time: the neighbour's vectors of four rows transposed, so that each lane of one product is
/// one entry's. The same operations on the same values in each lane, so the same bits, without a horizontal
/// sum per entry. The rows' and columns' fourth components must be +0 (they are built from three).
#[inline(always)]
fn fill_coupling<const N: usize>(
    c: &mut Block,
    rows: &[[Vec4; 2]; N],
    columns: &[[Vec4; 2]; N],
    live: ([bool; MAX_ROWS], [bool; MAX_ROWS]),
) {
    debug_assert!(
        rows.iter()
            .chain(columns)
            .flatten()
            .all(|v| v.w.to_bits() == 0)
    );
    coupling_columns::<N, 0>(c, rows, columns, live);
    if N > LANES {
        coupling_columns::<N, LANES>(c, rows, columns, live);
    }
}

/// The columns `FIRST..FIRST + 4` (those below `N`) of [`fill_coupling`]'s block.
#[inline(always)]
fn coupling_columns<const N: usize, const FIRST: usize>(
    c: &mut Block,
    rows: &[[Vec4; 2]; N],
    columns: &[[Vec4; 2]; N],
    (live, next_live): ([bool; MAX_ROWS], [bool; MAX_ROWS]),
) {
    // t[p][k]: component k (x, y, z) of vector p of the four columns (0 past `N`), one column a lane.
    let column = |j: usize, p: usize| columns.get(FIRST + j).map_or(Vec4::ZERO, |v| v[p]);
    let t: [[Vec4; 3]; 2] = core::array::from_fn(|p| {
        let m = Mat4::from_cols(column(0, p), column(1, p), column(2, p), column(3, p)).transpose();
        [m.x_axis, m.y_axis, m.z_axis]
    });
    let in_system: [bool; LANES] =
        core::array::from_fn(|j| FIRST + j < N && next_live.get(FIRST + j) == Some(&true));
    let in_system = lane_mask(&Vec4::ZERO.cmpeq(Vec4::ZERO), in_system);
    for ((i, [u0, u1]), out) in rows.iter().enumerate().zip(c.iter_mut()) {
        let x = t[0][0] * u0.x + t[1][0] * u1.x;
        let y = t[0][1] * u0.y + t[1][1] * u1.y;
        let z = t[0][2] * u0.z + t[1][2] * u1.z;
        let sum = (x + y) + (z + Vec4::ZERO);
        let entries = if live[i] {
            Vec4::select(in_system, sum, Vec4::ZERO)
        } else {
            Vec4::ZERO
        };
        let entries = entries.as_dvec4().to_array();
        for (j, (out, entry)) in out.iter_mut().skip(FIRST).zip(entries).enumerate() {
            if FIRST + j < N {
                *out = entry;
            }
        }
    }
}

/// The lane mask of `flags`, of the type `like` is: glam's mask of a `Vec4` comparison, which differs with
/// and without its SIMD (`enhanced-determinism`).
#[inline(always)]
fn lane_mask<M: From<[bool; LANES]>>(like: &M, flags: [bool; LANES]) -> M {
    let _ = like;
    M::from(flags)
}
