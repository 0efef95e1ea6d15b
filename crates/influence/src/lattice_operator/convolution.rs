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

use faer::dyn_stack::{PodStack, StackReq};
use rayon::prelude::*;
use realfft::RealFftPlanner;

use super::gather::GatherOrder;
use super::grid::{C64, COLUMN_BATCH, Grid, Plans, RowBuffers};
use super::spectrum::kernel_spectrum;
use crate::error::InfluenceError;
use crate::error::try_vec;
use crate::points::{LatticeBox, PointSet};
use crate::terms::Terms;

/// Rows of the box a thread takes up at least at once: a few dozen
/// microseconds of transforms, worth a hand-over to the pool.
const ROWS_PER_TASK: usize = 8;

/// Calls `body(state, i, item)` for each item `i` of `items`, `state` a
/// thread's buffers made by `init`: shared among the threads of the current
/// rayon pool (at least `min_len` items a task) when it has several and
/// there are more than `min_len` items, else on the caller's thread, in
/// order, with one `state` (a hand-over to a pool of one thread costs two
/// context switches a pass and buys nothing). `body` must write each
/// item from the item and `i` alone (the state is scratch): the results
/// are then the same to the bit on either path.
pub(super) fn share<I: Send, S>(
    items: Vec<I>,
    min_len: usize,
    init: impl Fn() -> S + Sync + Send,
    body: impl Fn(&mut S, usize, I) + Sync + Send,
) {
    if items.len() > min_len && rayon::current_num_threads() > 1 {
        items
            .into_par_iter()
            .with_min_len(min_len)
            .enumerate()
            .for_each_init(init, |state, (i, item)| body(state, i, item));
    } else {
        let mut state = init();
        for (i, item) in items.into_iter().enumerate() {
            body(&mut state, i, item);
        }
    }
}

/// A wave of transformed columns back into the rows they were read from:
/// entry `i` of column `t` (`columns[t * len + i]`, each `len` long) to
/// `rows[i][first + t]`, the rows shared among the threads as [`share`]
/// does (copies only: the same values for any thread count).
pub(super) fn columns_back(
    rows: Vec<&mut [C64]>,
    min_len: usize,
    first: usize,
    columns: &[C64],
    len: usize,
) {
    let width = columns.len() / len;
    share(
        rows,
        min_len,
        || (),
        |_, i, row| {
            for (t, v) in row[first..first + width].iter_mut().enumerate() {
                *v = columns[t * len + i];
            }
        },
    );
}

/// The half-space part of S on the lattice: the gather order, the kernel
/// spectrum and the FFT plans (immutable after construction).
pub(super) struct Convolution {
    pub(super) grid: Grid,
    pub(super) gather: GatherOrder,
    /// `DFT(Kc) / (P1 P2)` at frequency `(m1, m2)`, `m1 <= P1/2`,
    /// `m2 <= P2/2`, at `m2 (P1/2 + 1) + m1` (real: Kc is even).
    pub(super) spectrum: Vec<f64>,
    /// The kernel table K on the box's offsets, `(di, dj)` at `di n2 + dj`
    /// (`di < n1`, `dj < n2`; K is even in both): a column of S is this
    /// table shifted to the column's point
    /// ([`add_columns`](Self::add_columns)).
    pub(super) table: Vec<f64>,
    /// The FFT plans of its grid.
    plans: Plans,
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
/// the box (`n1 ceil((P2/2 + 1) / 2)` complex values), and a wave of
/// columns that the threads transform at once (a batch of 16 columns of
/// P1 complex values per thread of the pool it was made in); the same
/// buffers serve an application of the preconditioner (its row spectra on
/// the half-size grid are the band's size,
/// [`LatticeKernel::precondition_with`](super::LatticeKernel::precondition_with)). Made by
/// [`LatticeKernel::workspace`](super::LatticeKernel::workspace) for one operator (or one of the same grid);
/// reused across calls, its contents between calls mean nothing. Its
/// size changes nothing of a product's values: used in a pool of another
/// size it works in smaller or larger waves, to the same bits.
#[derive(Debug)]
pub struct LatticeWorkspace {
    /// The grid it was made for (`None`: an operator without convolution).
    grid: Option<Grid>,
    spectra: Vec<C64>,
    /// Columns of the band, zero-padded to P1, transformed together.
    columns: Vec<C64>,
}

impl LatticeWorkspace {
    /// The workspace of a product with `convolution` (empty for an operator
    /// without convolution), with waves for the current rayon pool's
    /// threads.
    ///
    /// # Errors
    /// [`InfluenceError::AllocationFailed`] when the memory cannot be
    /// allocated.
    pub(super) fn new(convolution: Option<&Convolution>) -> Result<Self, InfluenceError> {
        let Some(c) = convolution else {
            return Ok(Self {
                grid: None,
                spectra: Vec::new(),
                columns: Vec::new(),
            });
        };
        let g = c.grid;
        let zero = C64::new(0.0, 0.0);
        let (spectra, columns) = g.buffer_lens();
        Ok(Self {
            grid: Some(g),
            spectra: try_vec(spectra, zero, "lattice row spectra")?,
            columns: try_vec(columns, zero, "lattice column wave")?,
        })
    }

    /// The grid it was made for (`None`: an operator without convolution).
    pub(super) fn grid(&self) -> Option<Grid> {
        self.grid
    }

    /// Its buffers, for a product or the preconditioner's application.
    pub(super) fn buffers(&mut self) -> Buffers<'_> {
        Buffers {
            spectra: &mut self.spectra,
            columns: &mut self.columns,
        }
    }

    /// Bytes held by the workspace.
    pub fn memory_bytes(&self) -> usize {
        std::mem::size_of::<Self>() + 16 * (self.spectra.capacity() + self.columns.capacity())
    }
}

/// The buffers a product works in, borrowed from a [`LatticeWorkspace`]
/// or from a caller's scratch stack ([`Buffers::in_stack`]): the row
/// spectra (`n1` rows of [`Grid::spectra_width`] values) and the wave of
/// columns. Their contents on entry mean nothing.
pub(super) struct Buffers<'a> {
    pub(super) spectra: &'a mut [C64],
    pub(super) columns: &'a mut [C64],
}

impl Buffers<'_> {
    /// The scratch stack request of the buffers on `grid` (faer's idiom:
    /// a caller's `PodBuffer` of at least this many bytes).
    pub(super) fn scratch(grid: &Grid) -> StackReq {
        let (spectra, columns) = grid.buffer_lens();
        StackReq::new::<C64>(spectra).and(StackReq::new::<C64>(columns))
    }

    /// Calls `body` with the buffers of `grid` made in `stack`, as they
    /// are (a `PodStack` holds initialized bytes: nothing is cleared, and
    /// a product overwrites what it reads).
    ///
    /// # Panics
    /// If `stack` holds less than [`Buffers::scratch`].
    pub(super) fn in_stack<R>(
        grid: &Grid,
        stack: &mut PodStack,
        body: impl FnOnce(Buffers<'_>) -> R,
    ) -> R {
        let (spectra, columns) = grid.buffer_lens();
        let (spectra, stack) = stack.make_raw::<C64>(spectra);
        let (columns, _) = stack.make_raw::<C64>(columns);
        body(Buffers { spectra, columns })
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
        let (spectrum, table, self_term) = kernel_spectrum(terms, &grid, &mut real_planner)?;
        let plans = Plans::new(&mut real_planner, grid.padded_rows, grid.padded_columns);
        let convolution = Self {
            grid,
            gather,
            spectrum,
            table,
            plans,
        };
        Ok((convolution, self_term))
    }

    /// Bytes held (without a workspace).
    pub(super) fn bytes(&self) -> usize {
        self.gather.bytes()
            + 8 * (self.spectrum.capacity() + self.table.capacity())
            + self.grid.plan_bytes()
    }

    /// `y` = the half-space part of `S x`, band by band of the row
    /// spectra: the inverse row transforms are linear, so the bands' rows
    /// add up to the whole. Each row's and each column's transform is
    /// done by one thread, with nothing summed across them: the values do
    /// not depend on the threads.
    pub(super) fn apply(&self, x: &[f64], y: &mut [f64], mut ws: Buffers<'_>) {
        let g = self.grid;
        let (half, width) = (g.half_columns(), g.band_width());
        for first in (0..half).step_by(width) {
            let band = first..(first + width).min(half);
            self.rows_forward(x, band.clone(), &mut ws);
            self.columns_times_kernel(band.clone(), &mut ws);
            self.rows_inverse(y, band, &ws);
        }
    }

    /// The forces of each lattice row, zero-padded to P2, to their half
    /// spectrum, of which the frequencies `band` are kept (the rows shared
    /// among the threads).
    fn rows_forward(&self, x: &[f64], band: Range<usize>, ws: &mut Buffers<'_>) {
        let rows = self.grid.rows * band.len();
        let spectra: Vec<&mut [C64]> = ws.spectra[..rows].chunks_mut(band.len()).collect();
        share(
            spectra,
            ROWS_PER_TASK,
            || self.plans.row_buffers(),
            |b, i, spectrum| {
                self.spread_row(i, x, &mut b.row);
                self.plans
                    .row_forward
                    .process_with_scratch(&mut b.row, &mut b.spectrum, &mut b.scratch)
                    .expect("buffer lengths follow the plan");
                spectrum.copy_from_slice(&b.spectrum[band.clone()]);
            },
        );
    }

    /// Rows back from the frequencies `band` (the others zero): the first
    /// n2 values of each inverse are the box's, written to `y` for the
    /// first band and added for the others. The rows are shared among the
    /// threads when the points are in lattice-row order (each row writes
    /// its own slice of `y`), else done on the caller's thread.
    fn rows_inverse(&self, y: &mut [f64], band: Range<usize>, ws: &Buffers<'_>) {
        let stride = band.len();
        let spectra = &ws.spectra[..self.grid.rows * stride];
        let first = band.start == 0;
        let one_row = |b: &mut RowBuffers, i: usize, spectrum: &[C64], out: &mut [f64], base| {
            self.row_back(b, band.clone(), spectrum);
            for s in self.gather.row(i) {
                let points = s.points();
                let out = &mut out[points.start - base..points.end - base];
                let row = &b.row[s.columns()];
                if first {
                    out.copy_from_slice(row);
                } else {
                    out.iter_mut().zip(row).for_each(|(y, r)| *y += r);
                }
            }
        };
        match self.gather.row_slices(y) {
            Some(slices) => share(
                slices,
                ROWS_PER_TASK,
                || self.plans.row_buffers(),
                |b, i, out| {
                    let base = self.gather.row(i).first().map_or(0, |s| s.points().start);
                    one_row(b, i, &spectra[i * stride..(i + 1) * stride], out, base);
                },
            ),
            None => {
                let mut b = self.plans.row_buffers();
                for (i, spectrum) in spectra.chunks_exact(stride).enumerate() {
                    one_row(&mut b, i, spectrum, y, 0);
                }
            }
        }
    }

    /// `row` (P2 values, garbage in: the transforms use their input as
    /// scratch) = lattice row i of the box spread from `x`, zero on the
    /// cells without a point and on the padding. A row of one segment (a
    /// grid's, a disk's) clears only the cells around it.
    fn spread_row(&self, i: usize, x: &[f64], row: &mut [f64]) {
        match self.gather.row(i) {
            [s] => {
                let columns = s.columns();
                row[..columns.start].fill(0.0);
                row[columns.end..].fill(0.0);
                row[columns].copy_from_slice(&x[s.points()]);
            }
            segments => {
                row.fill(0.0);
                for s in segments {
                    row[s.columns()].copy_from_slice(&x[s.points()]);
                }
            }
        }
    }

    /// The inverse row transform of one row's frequencies `band` (the
    /// others zero) into `b.row`.
    fn row_back(&self, b: &mut RowBuffers, band: Range<usize>, spectrum: &[C64]) {
        let half = self.grid.half_columns();
        // Only the frequencies outside the band are cleared: the band's
        // are overwritten.
        let zero = C64::new(0.0, 0.0);
        b.spectrum[..band.start].fill(zero);
        b.spectrum[band.end..].fill(zero);
        b.spectrum[band].copy_from_slice(spectrum);
        // DC and Nyquist of a real row are real; drop the rounding.
        b.spectrum[0].im = 0.0;
        b.spectrum[half - 1].im = 0.0;
        self.plans
            .row_inverse
            .process_with_scratch(&mut b.spectrum, &mut b.row, &mut b.scratch)
            .expect("buffer lengths follow the plan");
    }

    /// The column stage on a band of the row spectra, a wave of columns at
    /// a time, in batches of [`COLUMN_BATCH`] columns shared among the
    /// threads: zero-pad each column from n1 to P1, transform, multiply by
    /// the kernel's spectrum, transform back; then the first n1 values of
    /// each back into the band (the rows shared among the threads).
    fn columns_times_kernel(&self, band: Range<usize>, ws: &mut Buffers<'_>) {
        let (n1, p1) = (self.grid.rows, self.grid.padded_rows);
        let stride = band.len();
        let rows = n1 * stride;
        let wave = ws.columns.len() / p1;
        for first in band.clone().step_by(wave) {
            let width = wave.min(band.end - first);
            let offset = first - band.start;
            let spectra = &ws.spectra[..rows];
            share(
                ws.columns[..width * p1]
                    .chunks_mut(COLUMN_BATCH * p1)
                    .collect(),
                1,
                || self.plans.scratch(),
                |scratch, b, batch| {
                    let at = offset + b * COLUMN_BATCH;
                    self.batch_times_kernel(spectra, stride, at, first - offset, batch, scratch);
                },
            );
            columns_back(
                ws.spectra[..rows].chunks_mut(stride).collect(),
                ROWS_PER_TASK,
                offset,
                &ws.columns[..width * p1],
                p1,
            );
        }
    }

    /// One batch of columns: the band's columns `at..` (offsets in the band
    /// whose first frequency is `band_start`) read from `spectra`,
    /// zero-padded to P1, transformed, multiplied by the kernel's spectrum
    /// (even in m1: frequency `P1 - m` is `m`'s) and transformed back in
    /// `batch`.
    fn batch_times_kernel(
        &self,
        spectra: &[C64],
        stride: usize,
        at: usize,
        band_start: usize,
        batch: &mut [C64],
        scratch: &mut [C64],
    ) {
        let g = self.grid;
        let (n1, p1, half_rows) = (g.rows, g.padded_rows, g.half_rows());
        let width = batch.len() / p1;
        for column in batch.chunks_exact_mut(p1) {
            column[n1..].fill(C64::new(0.0, 0.0));
        }
        for (i, row) in spectra.chunks_exact(stride).enumerate() {
            for (t, &z) in row[at..at + width].iter().enumerate() {
                batch[t * p1 + i] = z;
            }
        }
        self.plans
            .column_forward
            .process_with_scratch(batch, scratch);
        for (t, column) in batch.chunks_exact_mut(p1).enumerate() {
            let m2 = band_start + at + t;
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
        self.plans
            .column_inverse
            .process_with_scratch(batch, scratch);
    }
}

#[cfg(test)]
mod tests {
    use std::sync::atomic::{AtomicUsize, Ordering};

    use super::share;

    /// `share` on pools of 1 to 3 threads: every item written once from its
    /// index, the same bits on each; on one thread, on the caller's thread
    /// with one state (the inline path: no task handed over).
    #[test]
    fn shared_items_are_the_same_inline_and_on_the_pool() {
        let run = |threads: usize| {
            let pool = rayon::ThreadPoolBuilder::new()
                .num_threads(threads)
                .build()
                .unwrap();
            let states = AtomicUsize::new(0);
            let mut out = vec![0.0f64; 100 * 3];
            pool.install(|| {
                let caller = std::thread::current().id();
                share(
                    out.chunks_mut(3).collect(),
                    2,
                    || {
                        states.fetch_add(1, Ordering::Relaxed);
                        [0.0f64; 3]
                    },
                    |scratch, i, item: &mut [f64]| {
                        if threads == 1 {
                            assert_eq!(std::thread::current().id(), caller);
                        }
                        for (t, v) in item.iter_mut().enumerate() {
                            scratch[t] = (i as f64 + 0.1).sqrt() * (t as f64 + 1.0);
                            *v += scratch[t];
                        }
                    },
                );
            });
            (out, states.into_inner())
        };
        let (one, states) = run(1);
        assert_eq!(states, 1, "one state on the caller's thread");
        assert_eq!(one[3 * 7 + 2], (7.1f64).sqrt() * 3.0);
        for threads in [2, 3] {
            let (many, _) = run(threads);
            let bits = |v: &[f64]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
            assert_eq!(bits(&one), bits(&many), "{threads} threads");
        }
    }
}
