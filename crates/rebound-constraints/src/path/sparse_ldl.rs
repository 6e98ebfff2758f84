//! The sparse factorisation behind the direct solve of joint graphs (every solve and relax pass and the
//! projection of a graph, [`crate::path`]): `A = L·D·Lᵀ` of a symmetric positive semi-definite matrix given
//! by its upper triangle column by column, without pivoting, and the solve of `A·x = b` with its factors.
//!
//! The algorithm is the up-looking one (Davis, *Direct Methods for Sparse Linear Systems*, SIAM 2006, §4.4
//! and §4.7): row `k` of `L` is the solution of a triangular system with the rows before it, whose pattern is
//! the set of nodes reached from the entries of column `k` of `A` by walking up the elimination tree. The
//! symbolic pass (the tree, each column's count and each row's pattern) runs only when the caller says the
//! pattern changed: that of a joint graph's `K` changes only with its rows in the system, and a graph is
//! factorised several times a step with the same ones. Written here rather than taken from a crate: the
//! sparse crates that do this (faer, sprs with sprs-ldl) are large for a system this size, and this one is
//! a hundred lines that give the same bits for the same calls.
//!
//! The factorisation reveals the rank. A row whose pivot `d_k` is at most [`DEPENDENT_PIVOT`] of its own
//! diagonal entry `A_kk` — what is left of it after the rows before it, measured against the row before
//! elimination — is *dependent*: it lies within 0.01 rad of the span of those rows (two hinges on one
//! axis, a loop of hinges in a plane, a row of zeros). Its unknown is 0 and its column of `L` is 0, so the
//! other rows are solved exactly and it holds as far as they imply it. The ratio `d_k / A_kk` is the
//! squared sine of the angle between the row and the span of the rows before it (in the metric of `M⁻¹`),
//! independent of units and of how large the row's bodies' inverse masses are. A near-dependent row kept
//! in the system would take the part of its residual the others do not explain times `1 / d_k`: a
//! runaway impulse. The rank is kept from factorisation to factorisation of one pattern (the passes of a
//! step): a row found dependent stays so until its ratio exceeds [`DEPENDENT_RELEASE`] ×
//! [`DEPENDENT_PIVOT`], so that a row near the bound does not flip between 0 and a large impulse from
//! pass to pass.

#![allow(
    clippy::needless_range_loop,
    reason = "sparse triangular algebra reads as the formulas with indices"
)]

use super::row::Real;

/// A pivot at or below this fraction of its row's diagonal entry (before elimination) marks the row as
/// dependent on the rows before it (see the module doc).
pub(crate) const DEPENDENT_PIVOT: Real = 1e-4;

/// How many times [`DEPENDENT_PIVOT`] a dependent row's pivot ratio must reach, in a factorisation of the
/// same pattern, to count again (see the module doc).
pub(crate) const DEPENDENT_RELEASE: Real = 3.0;

/// `A = L·D·Lᵀ` of one matrix, and the buffers it is made in (reused from factorisation to factorisation).
#[derive(Debug, Clone, Default)]
pub(crate) struct SparseLdl {
    /// The order of the matrix.
    n: usize,
    /// The elimination tree: each column's parent (`usize::MAX` for a root).
    parent: Vec<usize>,
    /// Where each column of `L` starts in `rows` and `values`, and how many entries it has so far.
    start: Vec<usize>,
    count: Vec<usize>,
    /// The strictly lower part of the unit lower triangular `L`, by column: row indices and values.
    rows: Vec<usize>,
    values: Vec<Real>,
    /// `D⁻¹`, 0 for a dependent row.
    inv_pivot: Vec<Real>,
    /// Which rows the last factorisation found dependent (kept for one of the same pattern).
    dependent: Vec<bool>,
    /// Scratch: the row being solved for, which column last marked a node, and the pattern of a row.
    work: Vec<Real>,
    flag: Vec<usize>,
    pattern: Vec<usize>,
    /// The pattern of every row of `L` (the nodes of its triangular solve, in topological order), row `k`'s
    /// at `patterns[pattern_start[k]..pattern_start[k + 1]]`: kept for a matrix of the same pattern.
    patterns: Vec<usize>,
    pattern_start: Vec<usize>,
}

/// A symmetric matrix by the upper triangle of its columns: column `j`'s entries (row `i ≤ j`, value) are
/// `entries[start[j]..start[j + 1]]`, in any order, each `(i, j)` at most once.
#[derive(Debug, Clone, Default)]
pub(crate) struct UpperColumns {
    pub start: Vec<usize>,
    pub entries: Vec<(usize, Real)>,
}

impl UpperColumns {
    /// Empties the matrix (keeping its buffers) for one of order 0; columns are then added in order.
    pub fn clear(&mut self) {
        self.start.clear();
        self.start.push(0);
        self.entries.clear();
    }

    /// Ends the current column: the entries pushed since the last call are its own.
    pub fn end_column(&mut self) {
        self.start.push(self.entries.len());
    }

    /// The order of the matrix (the number of columns ended).
    pub fn order(&self) -> usize {
        self.start.len().saturating_sub(1)
    }

    /// Column `j`'s entries.
    pub fn column(&self, j: usize) -> &[(usize, Real)] {
        let (Some(&from), Some(&to)) = (self.start.get(j), self.start.get(j + 1)) else {
            return &[];
        };
        self.entries.get(from..to).unwrap_or_default()
    }

    /// `out = A·x` for the symmetric matrix (both triangles from the stored one).
    pub fn multiply(&self, x: &[Real], out: &mut [Real]) {
        out.fill(0.0);
        for j in 0..self.order() {
            for &(i, value) in self.column(j) {
                if let (Some(&xi), Some(&xj)) = (x.get(i), x.get(j)) {
                    out[j] += value * xi;
                    if i != j {
                        out[i] += value * xj;
                    }
                }
            }
        }
    }
}

impl SparseLdl {
    /// Factorises `a` (symmetric positive semi-definite): the elimination tree, column counts and each row's
    /// pattern — kept from the last factorisation if `same_pattern` (the caller's word that `a` has the
    /// pattern of the matrix factorised last), as is which rows are dependent, with the hysteresis of
    /// [`DEPENDENT_RELEASE`] — then the rows of `L` and `D` one after another. Returns the number of entries
    /// of `L`.
    pub fn factor(&mut self, a: &UpperColumns, same_pattern: bool) -> usize {
        let n = a.order();
        let same_pattern = same_pattern && self.n == n && self.pattern_start.len() == n + 1;
        self.n = n;
        if !same_pattern {
            self.symbolic(a);
            self.row_patterns(a);
        }
        let Self {
            start,
            count,
            rows,
            values,
            inv_pivot,
            dependent,
            work,
            patterns,
            pattern_start,
            ..
        } = self;
        if !same_pattern || dependent.len() != n {
            dependent.clear();
            dependent.resize(n, false);
        }
        inv_pivot.clear();
        inv_pivot.resize(n, 0.0);
        work.clear();
        work.resize(n, 0.0);
        count.fill(0);
        for k in 0..n {
            // Scatter column k of A into `work`.
            for &(i, value) in a.column(k) {
                work[i] += value;
            }
            // Row k of L: a sparse triangular solve with the rows before it; D_k what remains of A_kk.
            let diagonal = work[k];
            let mut d = diagonal;
            work[k] = 0.0;
            for &i in &patterns[pattern_start[k]..pattern_start[k + 1]] {
                let y = work[i];
                work[i] = 0.0;
                let column = start[i]..start[i] + count[i];
                for (&row, &l) in rows[column.clone()].iter().zip(&values[column]) {
                    work[row] -= l * y;
                }
                let l = y * inv_pivot[i];
                d -= l * y;
                let slot = start[i] + count[i];
                rows[slot] = k;
                values[slot] = l;
                count[i] += 1;
            }
            let bound = if dependent[k] {
                DEPENDENT_RELEASE * DEPENDENT_PIVOT
            } else {
                DEPENDENT_PIVOT
            };
            dependent[k] = !(d > bound * diagonal && d > 0.0);
            inv_pivot[k] = if dependent[k] { 0.0 } else { 1.0 / d };
        }
        start.get(n).copied().unwrap_or(0)
    }

    /// The pattern of each row of `L` (after [`SparseLdl::symbolic`]): the nodes reached from the entries of
    /// column `k` of `a` by walking up the elimination tree, in topological order.
    fn row_patterns(&mut self, a: &UpperColumns) {
        let n = self.n;
        let Self {
            parent,
            flag,
            pattern,
            patterns,
            pattern_start,
            ..
        } = self;
        flag.clear();
        flag.resize(n, usize::MAX);
        pattern.clear();
        pattern.resize(n, 0);
        patterns.clear();
        pattern_start.clear();
        pattern_start.push(0);
        for k in 0..n {
            let mut top = n;
            flag[k] = k;
            for &(i, _) in a.column(k) {
                let mut length = 0;
                let mut node = i;
                while flag[node] != k {
                    pattern[length] = node;
                    length += 1;
                    flag[node] = k;
                    node = parent[node];
                }
                // The walk from `i` sits below what earlier walks found: push it on the stack whole.
                while length > 0 {
                    top -= 1;
                    length -= 1;
                    pattern[top] = pattern[length];
                }
            }
            patterns.extend_from_slice(&pattern[top..n]);
            pattern_start.push(patterns.len());
        }
    }

    /// The elimination tree of `a` and the number of entries of each column of `L`, with the columns' starts.
    fn symbolic(&mut self, a: &UpperColumns) {
        let n = self.n;
        let Self {
            parent,
            start,
            count,
            flag,
            rows,
            values,
            ..
        } = self;
        parent.clear();
        parent.resize(n, usize::MAX);
        count.clear();
        count.resize(n, 0);
        flag.clear();
        flag.resize(n, usize::MAX);
        for k in 0..n {
            flag[k] = k;
            for &(i, _) in a.column(k) {
                let mut node = i;
                while node < k && flag[node] != k {
                    if parent[node] == usize::MAX {
                        parent[node] = k;
                    }
                    count[node] += 1;
                    flag[node] = k;
                    node = parent[node];
                }
            }
        }
        start.clear();
        start.push(0);
        let mut total = 0;
        for &c in count.iter() {
            total += c;
            start.push(total);
        }
        rows.clear();
        rows.resize(total, 0);
        values.clear();
        values.resize(total, 0.0);
    }

    /// Solves `A·x = b` in place with the factors (`x` holds `b` on entry); an unknown whose pivot vanished
    /// is 0.
    pub fn solve(&self, x: &mut [Real]) {
        let n = self.n.min(x.len());
        // L·y = b
        for j in 0..n {
            let column = self.start[j]..self.start[j] + self.count[j];
            let xj = x[j];
            for (&row, &l) in self.rows[column.clone()].iter().zip(&self.values[column]) {
                x[row] -= l * xj;
            }
        }
        // D·z = y
        for (x, &inv) in x.iter_mut().zip(&self.inv_pivot).take(n) {
            *x *= inv;
        }
        // Lᵀ·x = z
        for j in (0..n).rev() {
            let column = self.start[j]..self.start[j] + self.count[j];
            let mut sum = x[j];
            for (&row, &l) in self.rows[column.clone()].iter().zip(&self.values[column]) {
                sum -= l * x[row];
            }
            x[j] = sum;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::{SparseLdl, UpperColumns};
    use crate::path::row::Real;

    /// A symmetric positive definite matrix with a sparse pattern (a band and a corner, as a loop gives),
    /// dense, row-major.
    fn matrix(n: usize) -> Vec<Vec<Real>> {
        let mut a = vec![vec![0.0; n]; n];
        let mut seed = 12345u64;
        let mut next = || {
            seed = seed
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            ((seed >> 33) as Real) / ((1u64 << 31) as Real) - 0.5
        };
        // A = Bᵀ·B + I with B sparse: rows i couple to i + 1 and to n − 1.
        let mut b = vec![vec![0.0; n]; n];
        for i in 0..n {
            b[i][i] = 1.0 + next();
            b[i][(i + 1) % n] = next();
            b[i][n - 1] += next();
        }
        for i in 0..n {
            for j in 0..n {
                a[i][j] = (0..n).map(|k| b[k][i] * b[k][j]).sum::<Real>();
            }
            a[i][i] += 1.0;
        }
        a
    }

    fn upper(a: &[Vec<Real>]) -> UpperColumns {
        let mut m = UpperColumns::default();
        m.clear();
        for j in 0..a.len() {
            for i in (0..=j).rev() {
                if a[i][j] != 0.0 {
                    m.entries.push((i, a[i][j]));
                }
            }
            m.end_column();
        }
        m
    }

    #[test]
    fn the_factorisation_solves_a_sparse_system_to_rounding() {
        for n in [1, 2, 5, 12, 40] {
            let a = matrix(n);
            let m = upper(&a);
            let mut ldl = SparseLdl::default();
            ldl.factor(&m, false);
            let b: Vec<Real> = (0..n).map(|i| (i as Real * 0.37).sin()).collect();
            let mut x = b.clone();
            ldl.solve(&mut x);
            let mut ax = vec![0.0; n];
            m.multiply(&x, &mut ax);
            for (ax, b) in ax.iter().zip(&b) {
                assert!((ax - b).abs() < 1e-10, "n = {n}: {ax} for {b}");
            }
        }
    }

    #[test]
    fn a_factorisation_with_the_kept_pattern_gives_the_bits_of_a_fresh_one() {
        let a = matrix(12);
        let mut m = upper(&a);
        let mut kept = SparseLdl::default();
        kept.factor(&m, false);
        // New values, same pattern.
        for (_, value) in &mut m.entries {
            *value *= 1.5;
        }
        kept.factor(&m, true);
        let mut fresh = SparseLdl::default();
        fresh.factor(&m, false);
        let b: Vec<Real> = (0..12).map(|i| (Real::from(i) * 0.71).cos()).collect();
        let (mut x, mut y) = (b.clone(), b);
        kept.solve(&mut x);
        fresh.solve(&mut y);
        assert!(x.iter().zip(&y).all(|(x, y)| x.to_bits() == y.to_bits()));
    }

    #[test]
    fn a_row_found_dependent_stays_so_within_the_release_band_of_one_pattern() {
        use super::{DEPENDENT_PIVOT, DEPENDENT_RELEASE};
        // Row 1 is row 0 plus `e` in a direction of its own: its pivot ratio is e² / (1 + e²).
        let with = |e: Real| {
            let a = vec![vec![1.0, 1.0], vec![1.0, 1.0 + e * e]];
            upper(&a)
        };
        let solve = |ldl: &SparseLdl| {
            let mut x = vec![0.0, 1.0];
            ldl.solve(&mut x);
            x[1]
        };
        let mut ldl = SparseLdl::default();
        ldl.factor(&with(0.0), false);
        assert!(solve(&ldl).abs() < 1e-12);
        // Above the bound but within the release band: still dependent, as a fresh factorisation is not.
        let e = (2.0 * DEPENDENT_PIVOT).sqrt();
        const { assert!(2.0 < DEPENDENT_RELEASE) };
        ldl.factor(&with(e), true);
        assert!(solve(&ldl).abs() < 1e-12);
        let mut fresh = SparseLdl::default();
        fresh.factor(&with(e), false);
        assert!((solve(&fresh) - 1.0 / (e * e)).abs() < 1e-6 / (e * e));
        // Past the band it counts again.
        let e = (2.0 * DEPENDENT_RELEASE * DEPENDENT_PIVOT).sqrt();
        ldl.factor(&with(e), true);
        assert!((solve(&ldl) - 1.0 / (e * e)).abs() < 1e-6 / (e * e));
    }

    #[test]
    fn a_redundant_row_solves_to_zero_and_the_rest_hold() {
        // Rows 0 and 2 are the same constraint: K has rank 2.
        let a = vec![
            vec![2.0, 1.0, 2.0],
            vec![1.0, 3.0, 1.0],
            vec![2.0, 1.0, 2.0],
        ];
        let mut ldl = SparseLdl::default();
        ldl.factor(&upper(&a), false);
        let mut x = vec![1.0, 2.0, 1.0];
        ldl.solve(&mut x);
        assert!(x.iter().all(|v| v.is_finite()));
        assert!(x[2].abs() < 1e-12, "{x:?}");
        // The first two rows hold (the third is the first).
        assert!((2.0 * x[0] + x[1] - 1.0).abs() < 1e-12 && (x[0] + 3.0 * x[1] - 2.0).abs() < 1e-12);
    }
}
