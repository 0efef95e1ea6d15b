//! The half-space part of the product on the padded grid, by the circular
//! convolution theorem, a band of the row frequencies at a time:
//!
//! ```text
//!     Y = IDFT(DFT(Kc) . DFT(X)) = sum_b IDFT_rows(B_b IDFT_cols(DFT(Kc) . DFT_cols(B_b DFT_rows(X))))
//! ```
//!
//! with `B_b` the restriction to band b (the inverse row transform is
//! linear, so the bands add up to the whole); and the workspace one product
//! needs ([`LatticeWorkspace`]).

use std::ops::Range;
use std::sync::Arc;

use realfft::{ComplexToReal, RealFftPlanner, RealToComplex};
use rustfft::{Fft, FftPlanner};

use super::gather::GatherOrder;
use super::grid::{C64, COLUMN_BATCH, Grid, try_vec};
use super::spectrum::kernel_spectrum;
use crate::error::InfluenceError;
use crate::points::{LatticeBox, PointSet};
use crate::terms::Terms;

/// The half-space part of S on the lattice: the gather order, the kernel
/// spectrum and the FFT plans (immutable after construction).
pub(super) struct Convolution {
    pub(super) grid: Grid,
    gather: GatherOrder,
    /// `DFT(Kc) / (P1 P2)` at frequency `(m1, m2)`, `m1 <= P1/2`,
    /// `m2 <= P2/2`, at `m2 (P1/2 + 1) + m1` (real: Kc is even).
    spectrum: Vec<f64>,
    row_forward: Arc<dyn RealToComplex<f64>>,
    row_inverse: Arc<dyn ComplexToReal<f64>>,
    column_forward: Arc<dyn Fft<f64>>,
    column_inverse: Arc<dyn Fft<f64>>,
    /// FFT scratch (complex values) the plans need.
    scratch_len: usize,
}

impl std::fmt::Debug for Convolution {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Convolution")
            .field("grid", &self.grid)
            .field("segments", &self.gather.segment_count())
            .finish_non_exhaustive()
    }
}

/// The scratch memory of one product `S x`: a band of the row spectra of
/// the box (`n1 ceil((P2/2 + 1) / 2)` complex values), a row and its
/// spectrum, a batch of columns and the FFT scratch. Made by
/// [`LatticeKernel::workspace`](super::LatticeKernel::workspace) for one operator (or one of the same grid);
/// reused across calls, its contents between calls mean nothing.
#[derive(Debug)]
pub struct LatticeWorkspace {
    /// The grid it was made for (`None`: an operator without convolution).
    grid: Option<Grid>,
    spectra: Vec<C64>,
    row: Vec<f64>,
    row_spectrum: Vec<C64>,
    batch: Vec<C64>,
    scratch: Vec<C64>,
}

impl LatticeWorkspace {
    /// The workspace of a product with `convolution` (empty for an operator
    /// without convolution).
    ///
    /// # Errors
    /// [`InfluenceError::AllocationFailed`] when the memory cannot be
    /// allocated.
    pub(super) fn new(convolution: Option<&Convolution>) -> Result<Self, InfluenceError> {
        let Some(c) = convolution else {
            return Ok(Self {
                grid: None,
                spectra: Vec::new(),
                row: Vec::new(),
                row_spectrum: Vec::new(),
                batch: Vec::new(),
                scratch: Vec::new(),
            });
        };
        let g = c.grid;
        let zero = C64::new(0.0, 0.0);
        Ok(Self {
            grid: Some(g),
            spectra: try_vec(g.rows * g.band_width(), zero, "lattice row spectra")?,
            row: try_vec(g.padded_columns, 0.0, "lattice row")?,
            row_spectrum: try_vec(g.half_columns(), zero, "lattice row spectrum")?,
            batch: try_vec(COLUMN_BATCH * g.padded_rows, zero, "lattice column batch")?,
            scratch: try_vec(c.scratch_len, zero, "FFT scratch")?,
        })
    }

    /// The grid it was made for (`None`: an operator without convolution).
    pub(super) fn grid(&self) -> Option<Grid> {
        self.grid
    }

    /// Bytes held by the workspace.
    pub fn memory_bytes(&self) -> usize {
        std::mem::size_of::<Self>()
            + 16 * (self.spectra.capacity()
                + self.row_spectrum.capacity()
                + self.batch.capacity()
                + self.scratch.capacity())
            + 8 * self.row.capacity()
    }
}

impl Convolution {
    /// The gather order, the kernel spectrum and the plans; also returns the
    /// kernel table's self-term (its (0, 0) entry).
    pub(super) fn new(
        points: &PointSet,
        terms: &Terms,
        bounds: &LatticeBox,
    ) -> Result<(Self, f64), InfluenceError> {
        let grid = Grid::new(bounds);
        let gather = GatherOrder::new(points, bounds)?;
        let mut real_planner = RealFftPlanner::<f64>::new();
        let (spectrum, self_term) = kernel_spectrum(terms, &grid, &mut real_planner)?;
        let row_forward = real_planner.plan_fft_forward(grid.padded_columns);
        let row_inverse = real_planner.plan_fft_inverse(grid.padded_columns);
        let mut planner = FftPlanner::<f64>::new();
        let column_forward = planner.plan_fft_forward(grid.padded_rows);
        let column_inverse = planner.plan_fft_inverse(grid.padded_rows);
        let scratch_len = [
            row_forward.get_scratch_len(),
            row_inverse.get_scratch_len(),
            column_forward.get_inplace_scratch_len(),
            column_inverse.get_inplace_scratch_len(),
        ]
        .into_iter()
        .max()
        .unwrap_or(0);
        let convolution = Self {
            grid,
            gather,
            spectrum,
            row_forward,
            row_inverse,
            column_forward,
            column_inverse,
            scratch_len,
        };
        Ok((convolution, self_term))
    }

    /// Bytes held (without a workspace).
    pub(super) fn bytes(&self) -> usize {
        self.gather.bytes() + 8 * self.spectrum.capacity() + self.grid.plan_bytes()
    }

    /// `y` = the half-space part of `S x`, band by band of the row
    /// spectra: the inverse row transforms are linear, so the bands' rows
    /// add up to the whole.
    pub(super) fn apply(&self, x: &[f64], y: &mut [f64], ws: &mut LatticeWorkspace) {
        let g = self.grid;
        let (half, width) = (g.half_columns(), g.band_width());
        for first in (0..half).step_by(width) {
            let band = first..(first + width).min(half);
            self.rows_forward(x, band.clone(), ws);
            self.columns_times_kernel(band.clone(), ws);
            self.rows_inverse(y, band, ws);
        }
    }

    /// The forces of each lattice row, zero-padded to P2, to their half
    /// spectrum, of which the frequencies `band` are kept.
    fn rows_forward(&self, x: &[f64], band: Range<usize>, ws: &mut LatticeWorkspace) {
        let rows = self.grid.rows * band.len();
        for (i, spectrum) in ws.spectra[..rows].chunks_exact_mut(band.len()).enumerate() {
            ws.row.fill(0.0);
            for s in self.gather.row(i) {
                ws.row[s.columns()].copy_from_slice(&x[s.points()]);
            }
            self.row_forward
                .process_with_scratch(&mut ws.row, &mut ws.row_spectrum, &mut ws.scratch)
                .expect("buffer lengths follow the plan");
            spectrum.copy_from_slice(&ws.row_spectrum[band.clone()]);
        }
    }

    /// Rows back from the frequencies `band` (the others zero): the first
    /// n2 values of each inverse are the box's, written to `y` for the
    /// first band and added for the others.
    fn rows_inverse(&self, y: &mut [f64], band: Range<usize>, ws: &mut LatticeWorkspace) {
        let half = self.grid.half_columns();
        let rows = self.grid.rows * band.len();
        let first = band.start == 0;
        for (i, spectrum) in ws.spectra[..rows].chunks_exact(band.len()).enumerate() {
            ws.row_spectrum.fill(C64::new(0.0, 0.0));
            ws.row_spectrum[band.clone()].copy_from_slice(spectrum);
            // DC and Nyquist of a real row are real; drop the rounding.
            ws.row_spectrum[0].im = 0.0;
            ws.row_spectrum[half - 1].im = 0.0;
            self.row_inverse
                .process_with_scratch(&mut ws.row_spectrum, &mut ws.row, &mut ws.scratch)
                .expect("buffer lengths follow the plan");
            for s in self.gather.row(i) {
                let (out, row) = (&mut y[s.points()], &ws.row[s.columns()]);
                if first {
                    out.copy_from_slice(row);
                } else {
                    out.iter_mut().zip(row).for_each(|(y, r)| *y += r);
                }
            }
        }
    }

    /// The column stage on a band of the row spectra, in batches of
    /// [`COLUMN_BATCH`] columns: zero-pad each column from n1 to P1,
    /// transform, multiply by the kernel's spectrum (even in m1: frequency
    /// `P1 - m` is `m`'s), transform back, keep the first n1 values.
    fn columns_times_kernel(&self, band: Range<usize>, ws: &mut LatticeWorkspace) {
        let g = self.grid;
        let (n1, p1, half_rows) = (g.rows, g.padded_rows, g.half_rows());
        let stride = band.len();
        let rows = n1 * stride;
        for first in band.clone().step_by(COLUMN_BATCH) {
            let width = COLUMN_BATCH.min(band.end - first);
            let offset = first - band.start;
            let batch = &mut ws.batch[..width * p1];
            for column in batch.chunks_exact_mut(p1) {
                column[n1..].fill(C64::new(0.0, 0.0));
            }
            for (i, row) in ws.spectra[..rows].chunks_exact(stride).enumerate() {
                for (t, &z) in row[offset..offset + width].iter().enumerate() {
                    batch[t * p1 + i] = z;
                }
            }
            self.column_forward
                .process_with_scratch(batch, &mut ws.scratch);
            for (t, column) in batch.chunks_exact_mut(p1).enumerate() {
                let m2 = first + t;
                let kernel = &self.spectrum[m2 * half_rows..(m2 + 1) * half_rows];
                let (low, high) = column.split_at_mut(half_rows);
                for (z, &k) in low.iter_mut().zip(kernel) {
                    *z *= k;
                }
                // Frequency m >= P1/2 + 1 takes P1 - m, from P1/2 - 1 down to 1.
                for (z, &k) in high
                    .iter_mut()
                    .zip(kernel[1..p1 - half_rows + 1].iter().rev())
                {
                    *z *= k;
                }
            }
            self.column_inverse
                .process_with_scratch(batch, &mut ws.scratch);
            for (i, row) in ws.spectra[..rows].chunks_exact_mut(stride).enumerate() {
                for (t, z) in row[offset..offset + width].iter_mut().enumerate() {
                    *z = batch[t * p1 + i];
                }
            }
        }
    }
}
