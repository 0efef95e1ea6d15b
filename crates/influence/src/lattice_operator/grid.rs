//! The padded FFT grid of a lattice box, `P_a` the smallest even 5-smooth
//! number with
//!
//! ```text
//!     P_a >= 2 n_a - 1      (no wrap-around of the n1 x n2 box)
//! ```
//!
//! its bands of row frequencies, and the bytes an operator on it holds
//! (the estimate made before anything is built); its buffers are
//! allocated fallibly (`crate::error::try_vec`).

use std::sync::Arc;

use realfft::{ComplexToReal, RealFftPlanner, RealToComplex};
use rustfft::num_complex::Complex;
use rustfft::{Fft, FftPlanner};

use crate::points::LatticeBox;

/// A complex value of the spectra.
pub(super) type C64 = Complex<f64>;

/// Columns of the half spectrum transformed together: 16 complex values
/// (256 bytes) of each row are read at once, and the batch (16 columns of
/// P1 values, 256 kB at P1 = 1024) stays in the level-2 cache: a thread's
/// share of a wave of columns.
pub(super) const COLUMN_BATCH: usize = 16;

/// The row spectra are taken in this many bands of frequencies per
/// product: the workspace holds one band, half the row spectra (8 bytes a
/// cell of the box instead of 16), and each row is transformed once per
/// band (the row transforms are about a third of a product's work).
const BANDS: usize = 2;

/// Bytes counted per unit of FFT length for the plans, an upper estimate:
/// rustfft keeps about one complex twiddle factor (16 bytes) per unit of
/// length in a plan, each axis has a forward and an inverse plan, and the
/// count is doubled for their sub-plans. O(P1 + P2): negligible beside the
/// O(P1 P2) buffers.
const PLAN_BYTES_PER_LENGTH: usize = 64;

/// The padded FFT grid of a lattice box.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) struct Grid {
    /// Lattice rows (along i, x) and columns (along j, y) of the box.
    pub(super) rows: usize,
    pub(super) columns: usize,
    /// Padded lengths P1 (rows) and P2 (columns).
    pub(super) padded_rows: usize,
    pub(super) padded_columns: usize,
}

impl Grid {
    pub(super) fn new(bounds: &LatticeBox) -> Self {
        Self {
            rows: bounds.ni,
            columns: bounds.nj,
            padded_rows: padded_length(bounds.ni),
            padded_columns: padded_length(bounds.nj),
        }
    }

    /// Frequencies kept by a real-to-complex row transform, `P2/2 + 1`.
    pub(super) fn half_columns(&self) -> usize {
        self.padded_columns / 2 + 1
    }

    /// Distinct frequencies of the even spectrum along the rows, `P1/2 + 1`.
    pub(super) fn half_rows(&self) -> usize {
        self.padded_rows / 2 + 1
    }

    /// Frequencies of a band of the row spectra (the last may hold fewer).
    pub(super) fn band_width(&self) -> usize {
        self.half_columns().div_ceil(BANDS)
    }

    /// Frequencies kept by a real-to-complex row transform on the
    /// preconditioner's periodic half-size grid, `Q2/2 + 1` with `Q2 = P2/2`
    /// (the same as [`band_width`](Self::band_width) with two bands).
    pub(super) fn periodic_half_columns(&self) -> usize {
        self.padded_columns / 2 / 2 + 1
    }

    /// Values a row of a workspace's spectra holds: a band's for a product,
    /// the periodic grid's half spectrum for the preconditioner, which
    /// borrows them (equal with two bands, for every P2).
    pub(super) fn spectra_width(&self) -> usize {
        self.band_width().max(self.periodic_half_columns())
    }

    /// Values of the stored kernel spectrum.
    pub(super) fn spectrum_len(&self) -> usize {
        self.half_rows() * self.half_columns()
    }

    /// Bytes of the plans (an estimate, [`PLAN_BYTES_PER_LENGTH`]).
    pub(super) fn plan_bytes(&self) -> usize {
        PLAN_BYTES_PER_LENGTH * (self.padded_rows + self.padded_columns)
    }

    /// Bytes of a workspace made in the current rayon pool: a band of the
    /// row spectra and the wave of columns
    /// ([`wave_len`] of them).
    fn workspace_bytes(&self) -> usize {
        let (spectra, columns) = self.buffer_lens();
        16 * (spectra + columns)
    }

    /// The lengths of a product's buffers on this grid: the row spectra
    /// and the wave of columns, the wave for the current rayon pool's
    /// threads.
    pub(super) fn buffer_lens(&self) -> (usize, usize) {
        (
            self.rows * self.spectra_width(),
            wave_len(self) * self.padded_rows,
        )
    }

    /// Bytes held by an operator on this grid whose gather order takes
    /// `gather_bytes`, its workspace included (the gather order, the
    /// spectrum, the kernel table, the plans, the workspace).
    pub(super) fn operator_bytes(&self, gather_bytes: usize) -> usize {
        gather_bytes
            + 8 * (self.spectrum_len() + self.rows * self.columns)
            + self.plan_bytes()
            + self.workspace_bytes()
    }
}

/// The smallest even 5-smooth number `>= 2 n - 1` (at least 2): a padded
/// length without wrap-around and fast for the FFT.
pub(crate) fn padded_length(n: usize) -> usize {
    let smooth = |mut m: usize| {
        for p in [2, 3, 5] {
            while m.is_multiple_of(p) {
                m /= p;
            }
        }
        m == 1
    };
    let least = (2 * n).saturating_sub(1).max(2);
    (least..)
        .find(|&m| m.is_multiple_of(2) && smooth(m))
        .expect("a power of two >= least exists")
}

/// Columns of a wave on `grid`: [`COLUMN_BATCH`] per thread of the
/// current rayon pool, at most a band's.
pub(super) fn wave_len(grid: &Grid) -> usize {
    let threads = rayon::current_num_threads().max(1);
    (COLUMN_BATCH * threads).min(grid.band_width())
}

/// The four FFT plans of a 2-D transform on a `rows x columns` grid (real
/// transforms of length `columns` along the rows, complex ones of length
/// `rows` along the columns) and the scratch they need: the product's on
/// its padded grid, the preconditioner's on its periodic one.
pub(super) struct Plans {
    pub(super) row_forward: Arc<dyn RealToComplex<f64>>,
    pub(super) row_inverse: Arc<dyn ComplexToReal<f64>>,
    pub(super) column_forward: Arc<dyn Fft<f64>>,
    pub(super) column_inverse: Arc<dyn Fft<f64>>,
    /// FFT scratch (complex values) the plans need.
    pub(super) scratch_len: usize,
    columns: usize,
}

/// A thread's buffers for row transforms: a row, its half spectrum and the
/// FFT scratch (O(columns), made when a thread takes up a share of the rows).
pub(super) struct RowBuffers {
    pub(super) row: Vec<f64>,
    pub(super) spectrum: Vec<C64>,
    pub(super) scratch: Vec<C64>,
}

impl Plans {
    /// The plans of a `rows x columns` grid, the row plans from `real_planner`
    /// (which caches them across its callers).
    pub(super) fn new(real_planner: &mut RealFftPlanner<f64>, rows: usize, columns: usize) -> Self {
        let row_forward = real_planner.plan_fft_forward(columns);
        let row_inverse = real_planner.plan_fft_inverse(columns);
        let mut planner = FftPlanner::<f64>::new();
        let column_forward = planner.plan_fft_forward(rows);
        let column_inverse = planner.plan_fft_inverse(rows);
        let scratch_len = [
            row_forward.get_scratch_len(),
            row_inverse.get_scratch_len(),
            column_forward.get_inplace_scratch_len(),
            column_inverse.get_inplace_scratch_len(),
        ]
        .into_iter()
        .max()
        .unwrap_or(0);
        Self {
            row_forward,
            row_inverse,
            column_forward,
            column_inverse,
            scratch_len,
            columns,
        }
    }

    /// The FFT scratch of one thread.
    pub(super) fn scratch(&self) -> Vec<C64> {
        vec![C64::new(0.0, 0.0); self.scratch_len]
    }

    /// A thread's buffers for the row transforms.
    pub(super) fn row_buffers(&self) -> RowBuffers {
        RowBuffers {
            row: vec![0.0; self.columns],
            spectrum: vec![C64::new(0.0, 0.0); self.columns / 2 + 1],
            scratch: self.scratch(),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::{Grid, padded_length};

    /// The preconditioner's row spectra fit a product's band on every grid:
    /// borrowing the workspace's spectra costs it nothing more.
    #[test]
    fn the_periodic_half_spectrum_is_a_band() {
        for n in 1..3000 {
            let p = padded_length(n);
            let g = Grid {
                rows: 1,
                columns: n,
                padded_rows: 2,
                padded_columns: p,
            };
            assert_eq!(
                g.periodic_half_columns(),
                g.band_width(),
                "n = {n}, P = {p}"
            );
            assert_eq!(g.spectra_width(), g.band_width(), "n = {n}");
        }
    }
}
