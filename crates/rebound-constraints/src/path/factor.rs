//! The dense factorisation behind the block sweep: `S = L·D·Lᵀ` of a symmetric positive semi-definite
//! block without pivoting, and the forward and back substitutions with its factor. Used by every pass that
//! solves a path (solve, relax, projection).

#![allow(
    clippy::needless_range_loop,
    reason = "dense block algebra (LDLᵀ factorisation) reads as the formulas with indices"
)]

use super::row::{MAX_ROWS, Real};

/// A `MAX_ROWS × MAX_ROWS` block, row-major; only the top-left `k × k` is used.
pub(crate) type Block = [[Real; MAX_ROWS]; MAX_ROWS];

/// Added to each row's own `K` entry as a fraction of it: a little compliance that keeps the system of a
/// path with redundant rows (a bridge hung from two anchors constrains more than its bodies' degrees of
/// freedom) well conditioned, as constraint force mixing does.
pub(super) const REGULARIZATION: Real = 1e-6;

/// Pivots smaller than this fraction of the largest diagonal entry count as zero: the row is redundant.
pub(super) const RELATIVE_PIVOT: Real = 1e-5;

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
pub(super) fn ldl_factor<const N: usize>(block: &mut Block, inv_pivots: &mut [Real; MAX_ROWS]) {
    // `S` is read on and above the diagonal, `L` written below it: no entry is both.
    let l = block;
    let mut scale: Real = 0.0;
    for k in 0..N {
        scale = scale.max(l[k][k]);
    }
    let tiny = (scale * RELATIVE_PIVOT).max(Real::MIN_POSITIVE);
    let mut pivots: [Real; N] = [0.0; N];
    for j in 0..N {
        // lj_d[k] = Lⱼₖ·dₖ, shared by the pivot and the column below it.
        let mut lj_d: [Real; N] = [0.0; N];
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
/// triangular factor of [`ldl_factor`]): `wᵢ = cᵢ − Σₖ<ᵢ Lᵢₖ·wₖ`, a row at a time (no copy of `C` first,
/// which would call `memcpy`), the first `N` entries of each (the entries past them are left as they are:
/// the sweep reads `W`'s top-left `N × N` alone).
#[inline(always)]
pub(super) fn forward_substitute_block<const N: usize>(l: &Block, c: &Block, w: &mut Block) {
    for i in 0..N {
        let mut row: [Real; N] = core::array::from_fn(|col| c[i][col]);
        for k in 0..i {
            let f = l[i][k];
            for col in 0..N {
                row[col] -= f * w[k][col];
            }
        }
        w[i][..N].copy_from_slice(&row);
    }
}

/// `L⁻¹` applied in place to `z` (as [`forward_substitute_block`], one column): `zᵢ −= Lᵢₖ·zₖ`, k < i.
pub(super) fn forward_substitute<const N: usize>(l: &Block, z: &mut [Real; MAX_ROWS]) {
    for i in 1..N {
        for k in 0..i {
            z[i] -= l[i][k] * z[k];
        }
    }
}

/// `L⁻ᵀ` applied in place to `x` (back substitution with the transpose of [`ldl_factor`]'s factor).
pub(super) fn back_substitute<const N: usize>(l: &Block, x: &mut [Real; MAX_ROWS]) {
    for j in (0..N).rev() {
        let mut value = x[j];
        for i in (j + 1)..N {
            value -= l[i][j] * x[i];
        }
        x[j] = value;
    }
}
