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
use super::row::{MAX_ROWS, Real};
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

/// Which neighbour a link's elimination passes its block on to: the next link (the side before the meeting
/// link, and every link of a path solved from one end), the previous one (the side after the meeting link,
/// eliminated from the last link backward) or neither (the meeting link, which takes both sides' blocks).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Toward {
    /// The next link.
    Next,
    /// The previous link.
    Previous,
    /// Neither: the meeting link.
    Both,
}

impl Toward {
    /// The role of link `i` in a path whose sides meet at `meet` ([`meet_of`]).
    #[inline]
    pub(super) fn of(i: usize, meet: Option<usize>) -> Self {
        match meet {
            Some(m) if i > m => Self::Previous,
            Some(m) if i == m => Self::Both,
            _ => Self::Next,
        }
    }
}

/// The links whose factorisation a sweep makes again: `None` when every link keeps its own, else the
/// first and the last link whose [`FactorKey`] changed. A link's factorisation depends on the links it
/// eliminates from and on the neighbour it passes its block on to, so a link before the meeting link keeps
/// it while every link up to the next one is unchanged, one after it while every link from the previous one
/// on is, and the meeting link only while all are.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) struct Stale(pub(super) Option<(usize, usize)>);

impl Stale {
    /// Whether link `i`, eliminated toward `toward`, keeps its factorisation.
    #[inline]
    pub(super) fn keeps(self, i: usize, toward: Toward) -> bool {
        match (self.0, toward) {
            (None, _) => true,
            (Some((first, _)), Toward::Next) => i + 1 < first,
            (Some((_, last)), Toward::Previous) => i > last + 1,
            (Some(_), Toward::Both) => false,
        }
    }
}

/// What every step of one sweep shares: the bodies of each link (`load(i)`, `i` the link's index in the
/// path), the common softness ([`super::solve_path`]) and the stale factorisations.
pub(super) struct Sweep<'l, L> {
    pub(super) load: &'l L,
    pub(super) uniform: Option<Softness>,
    pub(super) stale: Stale,
}

/// One side's links in elimination order — `side[from..]` forward, or all of `side` backward — each with
/// its index in the path, the neighbour it passes its block on to (the next link of the side, or the
/// meeting link `boundary` past its end) with the sharing of their body (this link's side first), and the
/// neighbour eliminated before it.
fn for_each_in_order(
    side: &mut [Link],
    (offset, toward, from): (usize, Toward, usize),
    boundary: Option<&Link>,
    mut step: impl FnMut(usize, &mut Link, Option<(&Link, (bool, bool))>, Option<&Link>),
) {
    let len = side.len();
    for k in from..len {
        let j = if toward == Toward::Previous {
            len - 1 - k
        } else {
            k
        };
        let (before, rest) = side.split_at_mut(j);
        let Some((link, after)) = rest.split_first_mut() else {
            break;
        };
        if toward == Toward::Previous {
            let ahead = before.last().or(boundary);
            // The sharing is stored with the link before: (its side, this link's side).
            let shared = ahead
                .and_then(|a| a.shared_with_next)
                .map(|(a, this)| (this, a));
            step(offset + j, link, ahead.zip(shared), after.first());
        } else {
            let ahead = after.first().or(boundary);
            let shared = link.shared_with_next;
            step(offset + j, link, ahead.zip(shared), before.last());
        }
    }
}

/// The forward step of the block Thomas sweep over one side ([`super::sweep`]'s `block_sweep`): each link's
/// `Sᵢ` from the links eliminated before it, factorised (kept when [`Stale::keeps`]), and its `y`.
pub(super) fn block_side<'b, const N: usize, L>(
    side: &mut [Link],
    order: (usize, Toward, usize),
    boundary: Option<&Link>,
    sweep: &Sweep<'_, L>,
) where
    L: Fn(usize) -> Option<(&'b SolverBody, &'b SolverBody)> + Sync,
{
    let toward = order.1;
    for_each_in_order(side, order, boundary, |i, link, ahead, done| {
        let keep = sweep.stale.keeps(i, toward);
        block_step::<N>(
            link,
            ahead,
            [done, None],
            (sweep.load)(i),
            sweep.uniform,
            keep,
            toward,
        );
    });
}

/// The meeting link of a path solved from both ends: its `S` from both sides (`before`, the last link
/// eliminated forward, and `after`, the last eliminated backward), its solution `x` at once; returns it.
pub(super) fn block_meet<'b, const N: usize>(
    link: &mut Link,
    (before, after): (Option<&Link>, Option<&Link>),
    bodies: Option<(&'b SolverBody, &'b SolverBody)>,
    uniform: Option<Softness>,
    keep: bool,
) -> [Real; MAX_ROWS] {
    block_step::<N>(
        link,
        None,
        [before, after],
        bodies,
        uniform,
        keep,
        Toward::Both,
    );
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
    keep: bool,
    toward: Toward,
) {
    let split = uniform.is_some();
    if !keep {
        link.fill_blocks::<N>(ahead, toward == Toward::Previous);
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
        let shared = match toward {
            Toward::Previous => ahead.map(|(_, shared)| shared),
            Toward::Next | Toward::Both => link.shared_with_next,
        };
        link.factored = Some(FactorKey::toward(link, N, toward, shared));
    }
    // y = D⁻¹·L⁻¹·rhs
    forward_substitute::<N>(&link.factor, &mut rhs);
    for row in 0..N {
        link.y[row] = rhs[row] * link.inv_pivot[row];
    }
}

/// The back substitution of one side of the block sweep, from the link next to `boundary` (the meeting
/// link's solution, 0 past the end of a path solved from one end) outward: `xᵢ = Lᵢ⁻ᵀ·(yᵢ − Vᵢ·xₐ)`, `xₐ`
/// the solution of the link ahead, a column of V (a row of the stored Vᵀ) at a time. Writes each link's
/// solution ([`Link::finish`]) into `out`; returns whether one would release a row.
pub(super) fn block_back<const N: usize>(
    side: &[Link],
    out: &mut [[Real; MAX_ROWS]],
    toward: Toward,
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
    let links = side.iter().zip(out.iter_mut());
    if toward == Toward::Previous {
        links.for_each(|(link, out)| step(link, out));
    } else {
        links.rev().for_each(|(link, out)| step(link, out));
    }
    released
}

/// The forward step of the scalar Thomas sweep over one side (`solve_scalar_path`): `c'ᵢ = cᵢ/sᵢ`, `r'ᵢ =
/// (r̃ᵢ − cₚ·r'ₚ)/sᵢ` with `sᵢ = bᵢ − cₚ·c'ₚ`, `p` the link eliminated before it and `cᵢ` the coupling with
/// the link ahead; `b`, `c`, `1/s` and `c'` kept when [`Stale::keeps`].
pub(super) fn scalar_side<'b, L>(
    side: &mut [Link],
    order: (usize, Toward, usize),
    boundary: Option<&Link>,
    sweep: &Sweep<'_, L>,
) where
    L: Fn(usize) -> Option<(&'b SolverBody, &'b SolverBody)> + Sync,
{
    let toward = order.1;
    for_each_in_order(side, order, boundary, |i, link, ahead, done| {
        let keep = sweep.stale.keeps(i, toward);
        let ahead = ahead.map(|(a, _)| a);
        scalar_step(link, (ahead, toward), [done, None], (i, sweep), keep);
    });
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
    scalar_step(
        link,
        (None, Toward::Both),
        [before, after],
        (i, sweep),
        keep,
    );
    link.scalar.r_prime
}

/// One link of the scalar sweep: its entries (when not `keep`), coupled to `ahead`, less the links in
/// `done`, and `r'`.
#[inline(always)]
fn scalar_step<'b, L>(
    link: &mut Link,
    (ahead, toward): (Option<&Link>, Toward),
    done: [Option<&Link>; 2],
    (i, sweep): (usize, &Sweep<'_, L>),
    keep: bool,
) where
    L: Fn(usize) -> Option<(&'b SolverBody, &'b SolverBody)> + Sync,
{
    let split = sweep.uniform.is_some();
    let active = link.rows.count == 1 && link.active[0];
    if !keep {
        // The coupling is computed as the link before in the path computes it with the link after.
        let c = match (ahead, toward) {
            (Some(next), Toward::Next) => link.coupling_scalar(next),
            (Some(prev), Toward::Previous) => prev.coupling_scalar(link),
            _ => 0.0,
        };
        let diagonal = if active {
            Real::from(link.rows.self_coupling(0)) * (1.0 + REGULARIZATION)
        } else {
            1.0
        };
        let mut s = diagonal;
        for prev in done.into_iter().flatten() {
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
        link.scalar = ScalarEntries {
            b: diagonal,
            c,
            inv_s,
            c_prime: c * inv_s,
            r_prime: link.scalar.r_prime,
        };
        let shared = match toward {
            Toward::Previous => ahead.and_then(|a| a.shared_with_next).map(|(a, t)| (t, a)),
            _ => link.shared_with_next,
        };
        link.factored = Some(FactorKey::toward(link, 1, toward, shared));
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
                let mut k_lambda = diagonal * link.active_lambda()[0];
                if let Some(next) = ahead {
                    k_lambda += c * next.active_lambda()[0];
                }
                for prev in done.into_iter().flatten() {
                    k_lambda += prev.scalar.c * prev.active_lambda()[0];
                }
                rhs += Real::from(softness.impulse_scale) * k_lambda;
            }
            rhs
        }
    } else {
        0.0
    };
    for prev in done.into_iter().flatten() {
        r -= prev.scalar.c * prev.scalar.r_prime;
    }
    link.scalar.r_prime = r * link.scalar.inv_s;
}

/// The back substitution of one side of the scalar sweep ([`block_back`]): `xᵢ = r'ᵢ − c'ᵢ·xₐ`.
pub(super) fn scalar_back(
    side: &[Link],
    out: &mut [[Real; MAX_ROWS]],
    toward: Toward,
    boundary: Real,
    uniform: Option<Softness>,
) -> bool {
    let mut next = boundary;
    let mut released = false;
    let mut step = |link: &Link, out: &mut [Real; MAX_ROWS]| {
        let x = link.scalar.r_prime - link.scalar.c_prime * next;
        *out = link.finish([x, 0.0, 0.0, 0.0, 0.0], uniform);
        released |= link.would_deactivate(out);
        next = x;
    };
    let links = side.iter().zip(out.iter_mut());
    if toward == Toward::Previous {
        links.for_each(|(link, out)| step(link, out));
    } else {
        links.rev().for_each(|(link, out)| step(link, out));
    }
    released
}
