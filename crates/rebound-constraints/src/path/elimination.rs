//! The steps of the sweeps that solve a path ([`super::solve_path`]): one side of the path eliminated link by
//! link toward its end — from the first link forward, or from the last link backward toward a meeting link
//! — the meeting link that joins two sides, and the back substitution of a side. A short path is one side
//! swept forward to its last link; a long one is two sides swept at once toward the link in its middle (see
//! [`meet_of`] and `docs/physics.md`, "A path solved from both ends").

#![allow(
    clippy::needless_range_loop,
    reason = "dense block algebra (Thomas sweep) reads as the formulas with indices"
)]

use super::factor::{
    REGULARIZATION, RELATIVE_PIVOT, back_substitute, forward_substitute, forward_substitute_block,
    ldl_factor,
};
use super::link::{FactorKey, Link, ScalarEntries};
use super::row::{MAX_ROWS, Real, one_row};
use rebound_dynamics::{Softness, SolverBody};

/// Paths of at least this many links are solved from both ends at once, meeting at the link in the middle
/// ([`meet_of`]): long enough that each side's sweep (some 25 links' elimination and back substitution)
/// outweighs handing one side to a second thread. Every build and thread count solves a path the same way,
/// so the bits do not depend on the pool.
pub(super) const TWO_SIDED_MIN_LINKS: usize = 32;

/// The link where the two sides of a path of `len` links meet (`len / 2`), or `None` for a path solved
/// from its first link to its last (shorter than [`TWO_SIDED_MIN_LINKS`]).
#[inline]
pub(super) fn meet_of(len: usize) -> Option<usize> {
    (len >= TWO_SIDED_MIN_LINKS).then_some(len / 2)
}

/// The part of a path's factorisation keys ([`FactorKey`]'s `width`) that says how the path of `len` links
/// is swept: 0 from its first link to its last, `len × 8` from both ends (the length places the meeting link,
/// and so which way each link is eliminated; block widths are below 8).
#[inline]
pub(super) fn layout(len: usize) -> usize {
    meet_of(len).map_or(0, |_| len << 3)
}

/// The links whose factorisation a sweep makes again: `None` when every link keeps its own, else the
/// first and the last link whose [`FactorKey`] changed. A link's factorisation depends on the links it
/// eliminates from and on the neighbour it passes its block on to, so a link before the meeting link keeps
/// it while every link up to the next one is unchanged, one after it while every link from the previous one
/// on is, and the meeting link only while all are.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) struct Stale(pub(super) Option<(usize, usize)>);

impl Stale {
    /// Whether link `i` keeps its factorisation, eliminated toward the next link (`backward` false) or the
    /// previous one.
    #[inline]
    pub(super) fn keeps(self, i: usize, backward: bool) -> bool {
        match self.0 {
            None => true,
            Some((first, _)) if !backward => i + 1 < first,
            Some((_, last)) => i > last + 1,
        }
    }

    /// Whether the meeting link keeps its factorisation.
    #[inline]
    pub(super) fn keeps_meet(self) -> bool {
        self.0.is_none()
    }
}

/// What every step of one sweep shares: the bodies of each link (`load(i)`, `i` the link's index in the
/// path), the common softness ([`super::solve_path`]), the stale factorisations and the path's [`layout`].
pub(super) struct Sweep<'l, L> {
    pub(super) load: &'l L,
    pub(super) uniform: Option<Softness>,
    pub(super) stale: Stale,
    pub(super) layout: usize,
}

/// A link of a side with its neighbours ([`neighbours`]).
type Neighbours<'s> = (
    &'s mut Link,
    Option<(&'s Link, (bool, bool))>,
    Option<&'s Link>,
);

/// Link `j` of a side with its neighbours in the elimination order (`BACKWARD`: from the side's last link
/// to its first): the neighbour it passes its block on to — the next link of the side in that order, or the
/// meeting link `boundary` past its end — with the sharing of their body (this link's side first), and the
/// neighbour eliminated before it.
#[inline(always)]
fn neighbours<'s, const BACKWARD: bool>(
    side: &'s mut [Link],
    j: usize,
    boundary: Option<&'s Link>,
) -> Option<Neighbours<'s>> {
    let (before, rest) = side.split_at_mut(j);
    let (link, after) = rest.split_first_mut()?;
    if BACKWARD {
        let ahead = before.last().or(boundary);
        // The sharing is stored with the link before: (its side, this link's side).
        let shared = ahead
            .and_then(|a| a.shared_with_next)
            .map(|(a, this)| (this, a));
        Some((link, ahead.zip(shared), after.first()))
    } else {
        let ahead = after.first().or(boundary);
        let shared = link.shared_with_next;
        Some((link, ahead.zip(shared), before.last()))
    }
}

/// The forward step of the block Thomas sweep over one side ([`super::sweep`]'s `block_sweep`): each link's
/// `Sᵢ` from the link eliminated before it, factorised (kept when [`Stale::keeps`]), and its `y`; the links
/// from `from` on (forward; all of them backward), `offset` the side's first link in the path.
pub(super) fn block_side<'b, const N: usize, const BACKWARD: bool, L>(
    side: &mut [Link],
    (offset, from): (usize, usize),
    boundary: Option<&Link>,
    sweep: &Sweep<'_, L>,
) where
    L: Fn(usize) -> Option<(&'b SolverBody, &'b SolverBody)> + Sync,
{
    let len = side.len();
    for k in from..len {
        let j = if BACKWARD { len - 1 - k } else { k };
        let Some((link, ahead, done)) = neighbours::<BACKWARD>(side, j, boundary) else {
            break;
        };
        let i = offset + j;
        let step = Step {
            keep: sweep.stale.keeps(i, BACKWARD),
            before: BACKWARD,
            key: N + sweep.layout,
        };
        block_step::<N>(
            link,
            ahead,
            [done, None],
            (sweep.load)(i),
            sweep.uniform,
            step,
        );
    }
}

/// How one link is eliminated: whether it keeps its factorisation, whether the neighbour it passes its
/// block on to is the previous link, and the layout its key records.
#[derive(Clone, Copy)]
struct Step {
    keep: bool,
    before: bool,
    key: usize,
}

/// The meeting link of a path solved from both ends: its `S` from both sides (`before`, the last link
/// eliminated forward, and `after`, the last eliminated backward), its solution `x` at once; returns it.
pub(super) fn block_meet<'b, const N: usize>(
    link: &mut Link,
    (before, after): (Option<&Link>, Option<&Link>),
    bodies: Option<(&'b SolverBody, &'b SolverBody)>,
    (uniform, layout): (Option<Softness>, usize),
    keep: bool,
) -> [Real; MAX_ROWS] {
    let step = Step {
        keep,
        before: false,
        key: N + layout,
    };
    block_step::<N>(link, None, [before, after], bodies, uniform, step);
    let mut x = link.y;
    back_substitute::<N>(&link.factor, &mut x);
    x
}

/// One link of the block sweep: `B` and `C` toward `ahead` (when not `keep`), the right-hand side less the
/// blocks of the links in `done`, `S = B − Σ Wᵀ·D⁻¹·W` over them, its factorisation, `W`, `V` and `y`.
#[inline(always)]
fn block_step<const N: usize>(
    link: &mut Link,
    ahead: Option<(&Link, (bool, bool))>,
    done: [Option<&Link>; 2],
    bodies: Option<(&SolverBody, &SolverBody)>,
    uniform: Option<Softness>,
    Step { keep, before, key }: Step,
) {
    let split = uniform.is_some();
    if !keep {
        link.fill_blocks::<N>(ahead, before);
        link.fill_lanes();
    }
    let r = bodies.map_or([0.0; MAX_ROWS], |(a, b)| link.residual(a, b));
    let lambda = if split {
        [0.0; MAX_ROWS]
    } else {
        link.active_lambda()
    };
    // K·λ, for the soft rows only: this link's block, then the couplings to the link ahead and the links
    // eliminated before it. (No row is soft in the relax pass and in a projection.)
    let soft_rows = !split && link.has_soft_rows();
    let mut k_lambda = [0.0; MAX_ROWS];
    if soft_rows {
        let lambda_next = ahead.map_or([0.0; MAX_ROWS], |(a, _)| a.active_lambda());
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
    // Plain loops over `done` here and in `S` below, not `each`: a closure this long is compiled as a call
    // inside the entry loops.
    for prev in done.into_iter().flatten() {
        // rhs = r̃ − Wₚᵀ·yₚ, a row of W at a time (contiguous, so the rows pair into SIMD lanes).
        for k in 0..N {
            let (w, y) = (&prev.w[k], prev.y[k]);
            for row in 0..N {
                rhs[row] -= w[row] * y;
            }
        }
        if soft_rows {
            let lambda_prev = prev.active_lambda();
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
    // S = B − Σ Wₚᵀ·D⁻¹ₚ·Wₚ (upper triangle);  S = L·D·Lᵀ;  W = L⁻¹·C,  Vᵀ = (D⁻¹·W)ᵀ  (kept when `keep`)
    if !keep {
        // `S` (upper triangle) straight into the factor storage, an entry at a time (copying the 200-byte
        // `B` first would call `memcpy`), then factorised there.
        let s = &mut link.factor;
        for row in 0..N {
            for col in row..N {
                let mut value = link.b_block[row][col];
                for prev in done.into_iter().flatten() {
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
        link.factored = Some(FactorKey::of(link, key));
    }
    // y = D⁻¹·L⁻¹·rhs
    forward_substitute::<N>(&link.factor, &mut rhs);
    for row in 0..N {
        link.y[row] = rhs[row] * link.inv_pivot[row];
    }
}

/// The back substitution of one side of the block sweep, from the link next to `boundary` (the meeting
/// link's solution, 0 past the end of a path solved from one end) outward (`BACKWARD`: the side after the
/// meeting link, from its first link to its last): `xᵢ = Lᵢ⁻ᵀ·(yᵢ − Vᵢ·xₐ)`, `xₐ` the solution of the link
/// ahead, a column of V (a row of the stored Vᵀ) at a time. Writes each link's solution ([`Link::finish`])
/// into `out`; returns whether one would release a row.
pub(super) fn block_back<const N: usize, const BACKWARD: bool>(
    side: &[Link],
    out: &mut [[Real; MAX_ROWS]],
    boundary: [Real; MAX_ROWS],
    uniform: Option<Softness>,
) -> bool {
    let mut x_next = boundary;
    let mut released = false;
    let mut step = |link: &Link, out: &mut [Real; MAX_ROWS]| {
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
    };
    // One of the two loops is compiled for each direction.
    if BACKWARD {
        side.iter().zip(out).for_each(|(link, out)| step(link, out));
    } else {
        side.iter()
            .zip(out)
            .rev()
            .for_each(|(link, out)| step(link, out));
    }
    released
}

/// The forward step of the scalar Thomas sweep over one side (`solve_scalar_path`): `c'ᵢ = cᵢ/sᵢ`, `r'ᵢ =
/// (r̃ᵢ − cₚ·r'ₚ)/sᵢ` with `sᵢ = bᵢ − cₚ·c'ₚ`, `p` the link eliminated before it and `cᵢ` the coupling with
/// the link ahead; `b`, `c`, `1/s` and `c'` kept when [`Stale::keeps`]. The links as [`block_side`] takes
/// them.
pub(super) fn scalar_side<'b, const BACKWARD: bool, L>(
    side: &mut [Link],
    (offset, from): (usize, usize),
    boundary: Option<&Link>,
    sweep: &Sweep<'_, L>,
) where
    L: Fn(usize) -> Option<(&'b SolverBody, &'b SolverBody)> + Sync,
{
    let len = side.len();
    for k in from..len {
        let j = if BACKWARD { len - 1 - k } else { k };
        let Some((link, ahead, done)) = neighbours::<BACKWARD>(side, j, boundary) else {
            break;
        };
        let i = offset + j;
        let step = Step {
            keep: sweep.stale.keeps(i, BACKWARD),
            before: BACKWARD,
            key: 1 + sweep.layout,
        };
        scalar_step(link, ahead.map(|(a, _)| a), [done, None], (i, sweep), step);
    }
}

/// The meeting link of a scalar sweep from both ends ([`block_meet`]); returns its solution.
pub(super) fn scalar_meet<'b, L>(
    link: &mut Link,
    (before, after): (Option<&Link>, Option<&Link>),
    (i, sweep): (usize, &Sweep<'_, L>),
    keep: bool,
) -> Real
where
    L: Fn(usize) -> Option<(&'b SolverBody, &'b SolverBody)> + Sync,
{
    let step = Step {
        keep,
        before: false,
        key: 1 + sweep.layout,
    };
    scalar_step(link, None, [before, after], (i, sweep), step);
    link.scalar.r_prime
}

/// One link of the scalar sweep: its entries (when not `keep`), coupled to `ahead`, less the links in
/// `done`, and `r'`.
#[inline(always)]
fn scalar_step<'b, L>(
    link: &mut Link,
    ahead: Option<&Link>,
    done: [Option<&Link>; 2],
    (i, sweep): (usize, &Sweep<'_, L>),
    Step { keep, before, key }: Step,
) where
    L: Fn(usize) -> Option<(&'b SolverBody, &'b SolverBody)> + Sync,
{
    let split = sweep.uniform.is_some();
    let active = link.rows.count == 1 && link.active[0];
    if !keep {
        // The coupling is computed as the link before in the path computes it with the link after.
        let c = match ahead {
            Some(prev) if before => prev.coupling_scalar(link),
            Some(next) => link.coupling_scalar(next),
            None => 0.0,
        };
        let diagonal = if active {
            Real::from(link.rows.self_coupling(0)) * (1.0 + REGULARIZATION)
        } else {
            1.0
        };
        let mut s = diagonal;
        each(done, |prev| {
            s -= prev.scalar.c * prev.scalar.c_prime;
        });
        let scale = Real::from(link.rows.mass_a.mass.max(link.rows.mass_b.mass));
        // A vanishing pivot gets 1/s = 0 (never a pivot that passes the test: |s| > MIN_POSITIVE). The
        // reciprocal is kept so that the sweeps multiply: the forward sweep's chain from link to link is
        // then a multiply-add, not a division (some 15 cycles of latency each, 500 in a row for a chain).
        let inv_s = if s.abs() <= (scale * RELATIVE_PIVOT).max(Real::MIN_POSITIVE) {
            0.0
        } else {
            1.0 / s
        };
        link.scalar = ScalarEntries {
            b: diagonal,
            c,
            inv_s,
            c_prime: c * inv_s,
            r_prime: link.scalar.r_prime,
        };
        link.factored = Some(FactorKey::of(link, key));
    }
    let (diagonal, c) = (link.scalar.b, link.scalar.c);
    let mut r = if active {
        let row = &link.rows.rows[0];
        let residual = (sweep.load)(i).map_or(0.0, |(a, b)| link.row_residual(row, a, b));
        let softness = row.target.softness;
        if split {
            residual
        } else {
            let mut rhs = Real::from(softness.mass_scale) * residual;
            if softness.impulse_scale > 0.0 {
                let mut k_lambda = diagonal * first_lambda(link);
                if let Some(next) = ahead {
                    k_lambda += c * first_lambda(next);
                }
                each(done, |prev| {
                    k_lambda += prev.scalar.c * first_lambda(prev);
                });
                rhs += Real::from(softness.impulse_scale) * k_lambda;
            }
            rhs
        }
    } else {
        0.0
    };
    each(done, |prev| {
        r -= prev.scalar.c * prev.scalar.r_prime;
    });
    link.scalar.r_prime = r * link.scalar.inv_s;
}

/// The back substitution of one side of the scalar sweep ([`block_back`]): `xᵢ = r'ᵢ − c'ᵢ·xₐ`.
pub(super) fn scalar_back<const BACKWARD: bool>(
    side: &[Link],
    out: &mut [[Real; MAX_ROWS]],
    boundary: Real,
    uniform: Option<Softness>,
) -> bool {
    let mut next = boundary;
    let mut released = false;
    let mut step = |link: &Link, out: &mut [Real; MAX_ROWS]| {
        let x = link.scalar.r_prime - link.scalar.c_prime * next;
        *out = link.finish(one_row(x), uniform);
        released |= link.would_deactivate(out);
        next = x;
    };
    if BACKWARD {
        side.iter().zip(out).for_each(|(link, out)| step(link, out));
    } else {
        side.iter()
            .zip(out)
            .rev()
            .for_each(|(link, out)| step(link, out));
    }
    released
}

/// The first row's accumulated impulse as the scalar sweep's unknown (0 when it is not in the system): what
/// `Link::active_lambda` gives for it, without the other rows.
#[inline(always)]
fn first_lambda(link: &Link) -> Real {
    if link.active[0] {
        Real::from(link.lambda[0])
    } else {
        0.0
    }
}

/// Calls `f` with each link of `done` there is, in order — written out for the two places, so that a side's
/// step, whose second place is always empty, compiles to the one-neighbour loop.
#[inline(always)]
fn each<'l>(done: [Option<&'l Link>; 2], mut f: impl FnMut(&'l Link)) {
    if let Some(prev) = done[0] {
        f(prev);
    }
    if let Some(prev) = done[1] {
        f(prev);
    }
}
