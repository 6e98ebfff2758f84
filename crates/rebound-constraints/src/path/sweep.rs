//! The sweeps that solve a path's system (every solve and relax pass and the projection): the block Thomas
//! algorithm over `N × N` blocks for paths of multi-row joints, the scalar one for rope chains, and what a
//! sweep keeps for the next active-set round ([`Resume`]) and the next pass (the factorisation).

#![allow(
    clippy::needless_range_loop,
    reason = "dense block algebra (Thomas sweep) reads as the formulas with indices"
)]

use super::elimination::{
    Stale, Sweep, block_back, block_meet, block_side, layout, meet_of, scalar_back, scalar_meet,
    scalar_side,
};
use super::link::{FactorKey, Link};
use super::row::{MAX_ROWS, Real, one_row};
use rebound_dynamics::{Softness, SolverBody};
use rebound_math::par;

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
    load: impl Fn(usize) -> Option<(&'b SolverBody, &'b SolverBody)> + Sync,
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
    // sweep starts at the first link and (rarely) the keys are scanned again from there. A path solved
    // from both ends resumes only the side before its meeting link.
    let meet = meet_of(links.len());
    let resumable = resume.swept.map_or(0, |_| resume.from.min(links.len()));
    let resumable = meet.map_or(resumable, |m| resumable.min(m));
    let shape = path_shape(links, resumable);
    let widest = shape.widest;
    let key = (widest, shape.uniform.map(softness_bits));
    let (start, stale) = match resume.swept {
        Some(swept) if swept == key => (resumable, shape.stale(links)),
        _ if resumable == 0 => (0, shape.stale(links)),
        _ if meet.is_some() => (0, Stale(Some((0, links.len())))),
        _ => {
            let first = first_stale(links, widest.max(1) + layout(links.len()), 0);
            (
                0,
                Stale((first < links.len()).then_some((first, links.len()))),
            )
        }
    };
    resume.swept = Some(key);
    resume.from = links.len();
    let sweep = Sweep {
        load: &load,
        uniform: shape.uniform,
        stale,
        layout: layout(links.len()),
    };
    let released = if widest <= 1 {
        solve_scalar_path(links, out, &sweep, (start, meet))
    } else {
        solve_block_path(links, out, &sweep, widest, (start, meet))
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
    pub(super) swept: Option<(usize, Option<u64>)>,
    /// The first link whose forward sweep must run again.
    pub(super) from: usize,
}

impl Resume {
    /// Records that link `link`'s active set (and, by a release, its bodies' velocities) changed since the
    /// last sweep.
    pub fn changed(&mut self, link: usize) {
        self.from = self.from.min(link.saturating_sub(1));
    }
}

/// A softness by its bits: the same bits make the split form of [`solve_path`] exactly the per-row one.
pub(super) fn softness_bits(s: Softness) -> u64 {
    (u64::from(s.mass_scale.to_bits()) << 32) | u64::from(s.impulse_scale.to_bits())
}

/// What one scan of the path gives `solve_path` ([`path_shape`]).
pub(super) struct PathShape {
    /// The largest row count of the links.
    pub(super) widest: usize,
    /// The softness every active row shares, if they all do (the first active row's, or rigid without one).
    pub(super) uniform: Option<Softness>,
    /// Whether a row bounded at 0 is left out of the system ([`Link::left_out`]).
    pub(super) left_out: bool,
    /// From the scan's `start` on: the first link without a factorisation for its current active set and
    /// link to the next one ([`FactorKey`] but its width), and the first whose factorisation's width differs
    /// from that of the link at `start` (`None`: none).
    pub(super) first_unkeyed: usize,
    pub(super) first_width_change: usize,
    pub(super) start_width: Option<usize>,
    /// Where the keys were first looked at.
    pub(super) start: usize,
    /// The number of links.
    pub(super) len: usize,
}

impl PathShape {
    /// [`first_stale`] from the scan's `start` for the sweep `solve_path` makes — scalar (keys of width 1)
    /// up to one row, else blocks `widest` wide, laid out as [`layout`] says: the first link whose [`FactorKey`] differs, or the number of
    /// links if there is none.
    pub(super) fn first_stale(&self) -> usize {
        match self.start_width {
            Some(width) if width == self.widest.max(1) + layout(self.len) => {
                self.first_unkeyed.min(self.first_width_change)
            }
            // The link at `start` is keyed for another width (and `first_unkeyed` is past it).
            Some(_) => self.start,
            None => self.first_unkeyed,
        }
    }

    /// The links of the path `links` (the one scanned) whose factorisations the sweep makes again
    /// ([`Stale`]): from [`PathShape::first_stale`] to the last link whose [`FactorKey`] differs, looked for
    /// from the end (only a path solved from both ends needs it: its links after the meeting link depend
    /// on the links after them) — every link from the first one on when the link at `start` is keyed for
    /// another width or not at all.
    pub(super) fn stale(&self, links: &[Link]) -> Stale {
        let first = self.first_stale();
        if first >= self.len {
            return Stale(None);
        }
        let width = self.widest.max(1) + layout(self.len);
        let last = match self.start_width {
            Some(start) if start == width && layout(self.len) > 0 => links
                .iter()
                .rposition(|link| link.factored != Some(FactorKey::of(link, width)))
                .unwrap_or(self.len),
            _ => self.len,
        };
        Stale(Some((first, last)))
    }
}

/// One scan of the path for what `solve_path` decides on ([`PathShape`]), the factorisation keys looked at
/// from `start` on — made in the same scan so that the links are swept once.
pub(super) fn path_shape(links: &[Link], start: usize) -> PathShape {
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
        len: links.len(),
    }
}

/// [`solve_path`] for paths with multi-row joints: the block Thomas algorithm, over blocks of the path's
/// largest row count `rows` (a link with fewer rows is padded with rows that solve to 0; a path of hinges
/// runs the 5 × 5 sweep, one of ball joints the 3 × 3, one with a fixed joint or a limited hinge the 6 × 6). With a `uniform` softness the right-hand side is the
/// residual alone and the soft step is finished in the back substitution.
pub(super) fn solve_block_path<'b, L>(
    links: &mut [Link],
    out: &mut [[Real; MAX_ROWS]],
    sweep: &Sweep<'_, L>,
    rows: usize,
    from: (usize, Option<usize>),
) -> bool
where
    L: Fn(usize) -> Option<(&'b SolverBody, &'b SolverBody)> + Sync,
{
    match rows {
        0..=2 => block_sweep::<2, L>(links, out, sweep, from),
        3 => block_sweep::<3, L>(links, out, sweep, from),
        4 => block_sweep::<4, L>(links, out, sweep, from),
        5 => block_sweep::<5, L>(links, out, sweep, from),
        _ => block_sweep::<MAX_ROWS, L>(links, out, sweep, from),
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
/// from link `start` on (the links before it are as the last sweep left them, see [`Resume`]). A path with
/// a meeting link `m` ([`meet_of`]) is swept so from its first link to `m − 1` and, with `C` the coupling
/// to the previous link, from its last link back to `m + 1`, both at once (on two threads if the pool has
/// them); link `m` takes both sides' blocks, `Sₘ = Bₘ − Wₘ₋₁ᵀ·Vₘ₋₁ − Wₘ₊₁ᵀ·Vₘ₊₁`, and is solved first, and
/// the back substitutions run outward from it, again both at once.
///
/// The products are written as sums of scaled rows (`rhs −= yₖ·(row k of W)`, `x −= xₖ·(column k of V)`,
/// with `V` stored transposed), not as dot products: the rows are contiguous, so the compiler pairs them
/// into two-lane f64 operations.
///
/// `B`, `C`, `L`, `D⁻¹`, `W` and `V` depend on the rows and on which of them are in the system, not on the
/// velocities: while the links a link depends on still have the rows and the active sets they were
/// factorised with ([`FactorKey`], [`Stale`]; a pass at an unchanged pose), they are kept and only the
/// right-hand side is swept (`rhsᵢ`, then `y = D⁻¹·L⁻¹·rhsᵢ`) — the same operations on the same values, so
/// the same bits.
pub(super) fn block_sweep<'b, const N: usize, L>(
    links: &mut [Link],
    out: &mut [[Real; MAX_ROWS]],
    sweep: &Sweep<'_, L>,
    (start, meet): (usize, Option<usize>),
) -> bool
where
    L: Fn(usize) -> Option<(&'b SolverBody, &'b SolverBody)> + Sync,
{
    let Some(m) = meet.filter(|&m| m < links.len()) else {
        block_side::<N, false, L>(links, (0, start), None, sweep);
        return block_back::<N, false>(links, out, [0.0; MAX_ROWS], sweep.uniform);
    };
    let (before, rest) = links.split_at_mut(m);
    let Some((link, after)) = rest.split_first_mut() else {
        return false;
    };
    let middle = &*link;
    par::join(
        || block_side::<N, false, L>(before, (0, start), Some(middle), sweep),
        || block_side::<N, true, L>(after, (m + 1, 0), Some(middle), sweep),
    );
    let keep = sweep.stale.keeps_meet();
    let bodies = (sweep.load)(m);
    let ends = (before.last(), after.first());
    let x = block_meet::<N>(link, ends, bodies, (sweep.uniform, sweep.layout), keep);
    let (out_before, out_rest) = out.split_at_mut(m);
    let Some((out_middle, out_after)) = out_rest.split_first_mut() else {
        return false;
    };
    *out_middle = link.finish(x, sweep.uniform);
    let released = link.would_deactivate(out_middle);
    let uniform = sweep.uniform;
    let (a, b) = par::join(
        || block_back::<N, false>(before, out_before, x, uniform),
        || block_back::<N, true>(after, out_after, x, uniform),
    );
    released | a | b
}

/// The first link of the path whose stored factorisation is not for its current rows and active set in a
/// sweep of blocks `width` wide (its [`FactorKey`] differs), or the number of links if there is none; the
/// links before `start` are not looked at (a resumed sweep: the last sweep left their keys current).
pub(super) fn first_stale(links: &[Link], width: usize, start: usize) -> usize {
    links
        .iter()
        .enumerate()
        .skip(start)
        .find(|(_, link)| link.factored != Some(FactorKey::of(link, width)))
        .map_or(links.len(), |(i, _)| i)
}

/// [`solve_path`] for a path of one-row joints (a rope chain): the scalar Thomas algorithm, without the
/// block machinery, from both ends at once for a path with a meeting link as [`block_sweep`]. As there, the
/// entries `b`, `c`, `s` and `c'` of a link are kept from the last pass while the links it depends on have
/// the rows and active sets they were computed for ([`Stale`]).
pub(super) fn solve_scalar_path<'b, L>(
    links: &mut [Link],
    out: &mut [[Real; MAX_ROWS]],
    sweep: &Sweep<'_, L>,
    (start, meet): (usize, Option<usize>),
) -> bool
where
    L: Fn(usize) -> Option<(&'b SolverBody, &'b SolverBody)> + Sync,
{
    // Forward sweep: c'ᵢ = cᵢ/sᵢ, r'ᵢ = (r̃ᵢ − cᵢ₋₁·r'ᵢ₋₁)/sᵢ with sᵢ = bᵢ − cᵢ₋₁·c'ᵢ₋₁ and r̃ the soft
    // right-hand side of `solve_path`; bᵢ is the row's regularised `K` (1 for a row not in the system).
    // Link i − 1 holds cᵢ₋₁, c'ᵢ₋₁ and r'ᵢ₋₁ (`scalar`). The sweep starts at link `start` (see [`Resume`]).
    let Some(m) = meet.filter(|&m| m < links.len()) else {
        scalar_side::<false, L>(links, (0, start), None, sweep);
        return scalar_back::<false>(links, out, 0.0, sweep.uniform);
    };
    let (before, rest) = links.split_at_mut(m);
    let Some((link, after)) = rest.split_first_mut() else {
        return false;
    };
    let middle = &*link;
    par::join(
        || scalar_side::<false, L>(before, (0, start), Some(middle), sweep),
        || scalar_side::<true, L>(after, (m + 1, 0), Some(middle), sweep),
    );
    let keep = sweep.stale.keeps_meet();
    let x = scalar_meet(link, (before.last(), after.first()), (m, sweep), keep);
    let (out_before, out_rest) = out.split_at_mut(m);
    let Some((out_middle, out_after)) = out_rest.split_first_mut() else {
        return false;
    };
    *out_middle = link.finish(one_row(x), sweep.uniform);
    let released = link.would_deactivate(out_middle);
    let uniform = sweep.uniform;
    let (a, b) = par::join(
        || scalar_back::<false>(before, out_before, x, uniform),
        || scalar_back::<true>(after, out_after, x, uniform),
    );
    released | a | b
}
