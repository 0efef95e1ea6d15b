//! Columns of S without a transform: on a lattice `S_kj = K(i_k - i_j,
//! j_k - j_j)`, so column j is the kernel table shifted to point j's cell,
//! and `y += S d` for a `d` with few non-zero entries costs `O(N)` a
//! column instead of a product's `O(N log N)`:
//!
//! ```text
//!     y_k += Σ_t v_t K(|i_k - i_t|, |j_k - j_t|)      (d = Σ_t v_t e_{p_t})
//! ```
//!
//! What an iterative solver uses to keep `u = S z` after a step that
//! changed a few entries of `z` besides the ones it moved along a
//! direction whose product it has (the points that entered or left the
//! contact).

use super::convolution::{Convolution, share};

/// Rows of the box a thread takes up at least at once.
const ROWS_PER_TASK: usize = 8;

/// Products' worth of work a column's sum is taken to cost, per point of
/// the box, against a product's per cell of the padded grid and per
/// factor of two of its size: `columns_per_product` is
/// `COLUMN_RATIO P1 P2 log2(P1 P2) / N` (measured on this machine's
/// AVX-512 and AVX2 paths: the sum of a column runs about 2 N multiply-adds
/// a nanosecond, a product about `0.9 P1 P2 log2(P1 P2)` nanoseconds a
/// thousand, on one thread).
const COLUMN_RATIO: f64 = 0.9;

impl Convolution {
    /// `y +=` the half-space part of `S d`, `d = Σ_t v_t e_{p_t}` for the
    /// `columns` `(p_t, v_t)` (point indices below the point set's size):
    /// each column the kernel table shifted to its point's cell. Each
    /// entry of `y` adds its terms in the order of `columns`, whatever
    /// the threads (the rows are shared among them when the points are in
    /// lattice-row order).
    pub(super) fn add_columns(&self, columns: &[(usize, f64)], y: &mut [f64]) {
        if columns.is_empty() {
            return;
        }
        let cells = self.cells_of(columns);
        let n2 = self.grid.columns;
        let row_sums = |i: usize, out: &mut [f64], base: usize| {
            for s in self.gather.row(i) {
                let (first, points) = (s.columns().start, s.points());
                let out = &mut out[points.start - base..points.end - base];
                for (&(ic, jc), &(_, v)) in cells.iter().zip(columns) {
                    let kernel = &self.table[ic.abs_diff(i) * n2..][..n2];
                    add_shifted(out, first, jc, kernel, v);
                }
            }
        };
        match self.gather.row_slices(y) {
            Some(slices) => share(
                slices,
                ROWS_PER_TASK,
                || (),
                |_, i, out| {
                    let base = self.gather.row(i).first().map_or(0, |s| s.points().start);
                    row_sums(i, out, base);
                },
            ),
            None => (0..self.grid.rows).for_each(|i| row_sums(i, y, 0)),
        }
    }

    /// The columns whose [`add_columns`](Self::add_columns) costs about
    /// one product, on `points` points (at least 1).
    pub(super) fn columns_per_product(&self, points: usize) -> usize {
        let cells = (self.grid.padded_rows * self.grid.padded_columns) as f64;
        let columns = COLUMN_RATIO * cells * cells.log2() / points.max(1) as f64;
        (columns as usize).max(1)
    }

    /// The lattice cell `(i, j)` in the box of each column's point.
    ///
    /// # Panics
    /// If a point index is not a point of the set.
    fn cells_of(&self, columns: &[(usize, f64)]) -> Vec<(usize, usize)> {
        let mut order: Vec<usize> = (0..columns.len()).collect();
        order.sort_unstable_by_key(|&t| columns[t].0);
        let mut cells = vec![(usize::MAX, usize::MAX); columns.len()];
        for i in 0..self.grid.rows {
            for s in self.gather.row(i) {
                let points = s.points();
                let from = order.partition_point(|&t| columns[t].0 < points.start);
                for &t in order[from..]
                    .iter()
                    .take_while(|&&t| columns[t].0 < points.end)
                {
                    cells[t] = (i, s.columns().start + columns[t].0 - points.start);
                }
            }
        }
        assert!(
            cells.iter().all(|c| c.0 != usize::MAX),
            "a column index is not a point of the set"
        );
        cells
    }
}

/// `out[t] += v K(|first + t - jc|)`: a segment of a lattice row (its
/// first lattice column `first`) plus `v` times the kernel row `kernel`
/// shifted to lattice column `jc`, in two runs (left of `jc`, the kernel
/// read backwards, and from `jc` on) that the compiler vectorizes.
fn add_shifted(out: &mut [f64], first: usize, jc: usize, kernel: &[f64], v: f64) {
    let split = jc.saturating_sub(first).min(out.len());
    let (left, right) = out.split_at_mut(split);
    if split > 0 {
        // Lattice column first + t < jc: offset jc - first - t.
        let high = jc - first;
        let offsets = kernel[high + 1 - split..=high].iter().rev();
        left.iter_mut().zip(offsets).for_each(|(o, &k)| *o += v * k);
    }
    if !right.is_empty() {
        // Lattice column first + split + t >= jc: offset first + split + t - jc.
        let low = first + split - jc;
        let offsets = &kernel[low..low + right.len()];
        right
            .iter_mut()
            .zip(offsets)
            .for_each(|(o, &k)| *o += v * k);
    }
}
