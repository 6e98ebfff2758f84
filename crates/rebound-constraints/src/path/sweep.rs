//! The sweeps that solve a path's system (every solve and relax pass and the projection): the block Thomas
//! algorithm over `N × N` blocks for paths of multi-row joints, the scalar one for rope chains, and what a
//! sweep keeps for the next active-set round ([`Resume`]) and the next pass (the factorisation).

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
}

impl PathShape {
    /// [`first_stale`] from the scan's `start` for the sweep `solve_path` makes — scalar (keys of width 1)
    /// up to one row, else blocks `widest` wide: the first link whose [`FactorKey`] differs, or the number of
    /// links if there is none.
    pub(super) fn first_stale(&self) -> usize {
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
    }
}

/// [`solve_path`] for paths with multi-row joints: the block Thomas algorithm, over blocks of the path's
/// largest row count (a link with fewer rows is padded with rows that solve to 0; a path of hinges runs the
/// 5 × 5 sweep, one of ball joints the 3 × 3). With a `uniform` softness the right-hand side is the residual
/// alone and the soft step is finished in the back substitution. `rows` is the largest row count of the links.
pub(super) fn solve_block_path<'b>(
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
/// into two-lane f64 operations.
///
/// `B`, `C`, `L`, `D⁻¹`, `W` and `V` depend on the rows and on which of them are in the system, not on the
/// velocities: while the links up to the next one still have the rows and the active sets they were
/// factorised with ([`FactorKey`], [`keeps_factor`]; a pass at an unchanged pose), they are kept and only the
/// right-hand side is swept (`rhsᵢ`, then `y = D⁻¹·L⁻¹·rhsᵢ`) — the same operations on the same values, so
/// the same bits.
pub(super) fn block_sweep<'b, const N: usize>(
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
            // `S` (upper triangle) straight into the factor storage, an entry at a time (copying the
            // 200-byte `B` first would call `memcpy`), then factorised there.
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
pub(super) fn first_stale(links: &[Link], width: usize, start: usize) -> usize {
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
pub(super) fn keeps_factor(i: usize, stale: usize, len: usize) -> bool {
    stale == len || i + 1 < stale
}

/// [`solve_path`] for a path of one-row joints (a rope chain): the scalar Thomas algorithm, without the
/// block machinery. `uniform` as in [`solve_block_path`]. As there, the entries `b`, `c`, `s` and `c'` of a
/// link are kept from the last pass while it and the links before and after it have the rows and active
/// sets they were computed for ([`keeps_factor`]).
pub(super) fn solve_scalar_path<'b>(
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
