//! The matrix-free influence operator on a lattice: `y = S x` by a
//! zero-padded (non-periodic, "DC-FFT") convolution, in O(N) memory and
//! O(N log N) time, never forming the N x N matrix S.
//!
//! On a lattice grid (the points at `(i_k dx, j_k dy)` up to a shift,
//! [`PointSet::lattice`]) the half-space part of S depends only on the
//! offset between two points, `S_kj = K(i_k - i_j, j_k - j_j)`, with K the
//! bodies' kernels summed with their compliances, the self-term at (0, 0)
//! (see [`assemble`](crate::assemble) and [`crate::models`]); a Winkler
//! foundation adds `1 / (k A_k)` on the diagonal. With the forces spread on
//! the lattice's bounding box, `X[i, j] = x_k` at `(i, j) = (i_k, j_k)` and 0
//! on the cells that hold no point, the product is the linear (aperiodic)
//! convolution
//!
//! ```text
//!     Y[i, j] = sum_{i' < n1} sum_{j' < n2} K(i - i', j - j') X[i', j'],     (S x)_k = Y[i_k, j_k] + x_k / (k_w A_k)
//! ```
//!
//! over the `n1 x n2` box. K is even in both offsets and only
//! `|i - i'| <= n1 - 1`, `|j - j'| <= n2 - 1` occur, so K embedded in a
//! `P1 x P2` circulant with `P_a >= 2 n_a - 1`,
//!
//! ```text
//!     Kc[a, b] = K(a*, b*),   a* = a (a < n1), a - P1 (a > P1 - n1), no term otherwise (Kc = 0)
//! ```
//!
//! and X zero-padded to `P1 x P2` give the same Y on the box through the
//! circular convolution theorem, `Y = IDFT(DFT(Kc) . DFT(X))`, without
//! wrap-around: the padding keeps the images of the box out of it. The
//! padded lengths are the smallest even 5-smooth numbers `>= 2 n - 1`, fast
//! for the FFT. Kc is real and even, so `DFT(Kc)` is real and even: it is
//! stored on `(P1/2 + 1) x (P2/2 + 1)` frequencies, scaled by `1/(P1 P2)`.
//!
//! The kernel table is the one the dense assembly gathers from (one kernel
//! evaluation per lattice offset, the same functions and self-term), so the
//! operator reproduces `assemble`'s S to the FFT's rounding (about 1e-15 of
//! the largest `|S x|`).
//!
//! Each product, in two bands of the row frequencies (`BANDS`): for each
//! band, `n1` real-to-complex row transforms of length P2 (the rows beyond
//! the box are zero and skipped) of which the band's frequencies are kept,
//! the band's complex column transforms of length P1 forward and back with
//! the product by `DFT(Kc)` between, and `n1` complex-to-real row
//! transforms of the band (the others zero), added into y: the inverse is
//! linear, so the bands add up to the whole (realfft over rustfft, planned
//! once). The second band costs a second pass of row transforms, about a
//! third more work, and halves the workspace.
//! Memory: the stored spectrum (`8 (P1/2 + 1)(P2/2 + 1)` bytes, about
//! `8 n1 n2`), the gather order (12 bytes per segment of consecutive points
//! in a lattice row: one a row on a surface grid, one a point on a line,
//! whose rows hold a point each) and one workspace of a band,
//! `n1 ceil((P2/2 + 1) / 2)` complex values (about `8 n1 n2` bytes), plus
//! buffers and plans of O(P1 + P2): 19 bytes per point on a 256 x 256
//! grid, 27 on a disk of 51,433 points (its bounding box holds 4/pi as many
//! cells). A grid's point set takes 2 bytes per point.
//! [`LatticeOperator::estimate_bytes`] gives the figure before anything is
//! built; the construction holds nothing of the box's size but the
//! spectrum (the kernel table is made a row at a time).
//!
//! Units: as S. With x the forces F (force; per unit width on a line), y is
//! the deflection (length); S's entries are in length per force.
//!
//! Models: the point-force and uniform-patch half-spaces on a surface grid,
//! the plane-strain strip on a line, any of them with a Winkler foundation
//! (a diagonal term), rigid bodies (nothing). Beams are refused
//! ([`InfluenceError::NotTranslationInvariant`]). The periodic convolution
//! (periodic surfaces) is not provided: the half-space kernels' lattice sums
//! diverge, so it needs a different kernel (the spectral `2 / (E* |q|)` with
//! the mean load set apart), not a different padding.

use std::ops::Range;
use std::sync::Arc;

use realfft::{ComplexToReal, RealFftPlanner, RealToComplex};
use rustfft::num_complex::Complex;
use rustfft::{Fft, FftPlanner};

use crate::error::InfluenceError;
use crate::models::{Body, Model};
use crate::points::{Lattice, LatticeBox, MAX_POINTS, PointSet};
use crate::terms::Terms;

type C64 = Complex<f64>;

/// Columns of the half spectrum transformed together: 16 complex values
/// (256 bytes) of each row are read at once, and the batch (16 columns of
/// P1 values, 256 kB at P1 = 1024) stays in the level-2 cache.
const COLUMN_BATCH: usize = 16;

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

// Point indices, lattice columns and row starts are stored as u32: a box
// holds at most `LatticeBox::cell_limit(MAX_POINTS)` cells.
const _: () = assert!(LatticeBox::cell_limit(MAX_POINTS) <= u32::MAX as usize);

/// The influence operator `x -> S x` of the bodies in contact on a lattice
/// point set, applied by FFT without forming S; see the
/// [module documentation](self) for the equation, the cost and the models.
///
/// Built once per point set and bodies; [`apply`](Self::apply) is then called
/// as often as needed (an iterative solver calls it once per iteration). The
/// operator keeps one workspace for [`apply`](Self::apply) (`&mut self`);
/// threads that share one operator call [`apply_with`](LatticeKernel::apply_with)
/// (`&self`), each with its own [`LatticeWorkspace`]. The two are the same
/// code and equally fast.
///
/// ```
/// use elcon_influence::{Body, LatticeOperator, Material, PointSet, assemble};
///
/// let steel = Material::new(210e9, 0.3).unwrap(); // Pa
/// let points = PointSet::grid_disk(1e-5, 2e-4).unwrap(); // m, 1257 points
/// let bodies = [&Body::uniform_patch(steel), &Body::point_force(steel)];
/// let mut op = LatticeOperator::new(&points, &bodies).unwrap();
///
/// let forces = vec![1e-3; points.len()]; // N
/// let mut deflection = vec![0.0; points.len()]; // m
/// op.apply(&forces, &mut deflection);
///
/// // The same as the dense S, to the FFT's rounding.
/// let s = assemble(&points, &bodies).unwrap();
/// let k = points.len() / 2;
/// let dense: f64 = (0..points.len()).map(|j| s[(k, j)] * forces[j]).sum();
/// assert!((deflection[k] / dense - 1.0).abs() < 1e-12);
/// assert_eq!(op.diagonal(), s[(k, k)]);
/// // O(N): 56 bytes per point here, ~20 on large grids (a dense S: 8 N per point).
/// assert!(op.memory_bytes() < 60 * points.len());
/// ```
#[derive(Debug)]
pub struct LatticeOperator {
    kernel: LatticeKernel,
    /// The workspace [`LatticeOperator::apply`] uses.
    workspace: LatticeWorkspace,
}

/// The operator without a workspace: `S` on a lattice as the products
/// [`apply_with`](Self::apply_with) computes, each caller or thread with
/// its own [`LatticeWorkspace`] (the kernel is `Sync`). What a problem that
/// is solved by several threads, or holds no workspace between solves,
/// keeps; a [`LatticeOperator`] is one of these with a workspace, and
/// dereferences to it.
#[derive(Debug)]
pub struct LatticeKernel {
    len: usize,
    /// S_kk: the self-term plus the Winkler diagonal.
    diagonal: f64,
    /// The Winkler diagonal `sum 1/(k A_k)` (0 without a foundation).
    winkler: f64,
    /// The half-space part; `None` when the only elastic bodies are
    /// foundations.
    convolution: Option<Convolution>,
}

/// The padded FFT grid of a lattice box.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
struct Grid {
    /// Lattice rows (along i, x) and columns (along j, y) of the box.
    rows: usize,
    columns: usize,
    /// Padded lengths P1 (rows) and P2 (columns).
    padded_rows: usize,
    padded_columns: usize,
}

impl Grid {
    fn new(bounds: &LatticeBox) -> Self {
        Self {
            rows: bounds.ni,
            columns: bounds.nj,
            padded_rows: padded_length(bounds.ni),
            padded_columns: padded_length(bounds.nj),
        }
    }

    /// Frequencies kept by a real-to-complex row transform, `P2/2 + 1`.
    fn half_columns(&self) -> usize {
        self.padded_columns / 2 + 1
    }

    /// Distinct frequencies of the even spectrum along the rows, `P1/2 + 1`.
    fn half_rows(&self) -> usize {
        self.padded_rows / 2 + 1
    }

    /// Frequencies of a band of the row spectra (the last may hold fewer).
    fn band_width(&self) -> usize {
        self.half_columns().div_ceil(BANDS)
    }

    /// Values of the stored kernel spectrum.
    fn spectrum_len(&self) -> usize {
        self.half_rows() * self.half_columns()
    }

    /// An upper bound on the FFT scratch (complex values) of the plans; the
    /// planned lengths are 5-smooth, whose in-place scratch is at most the
    /// length.
    fn scratch_bound(&self) -> usize {
        self.padded_rows + self.padded_columns
    }

    /// Bytes of the plans (an estimate, [`PLAN_BYTES_PER_LENGTH`]).
    fn plan_bytes(&self) -> usize {
        PLAN_BYTES_PER_LENGTH * (self.padded_rows + self.padded_columns)
    }

    /// Bytes of a workspace with `scratch` complex values of FFT scratch.
    fn workspace_bytes(&self, scratch: usize) -> usize {
        let complex = self.rows * self.band_width()
            + self.half_columns()
            + COLUMN_BATCH * self.padded_rows
            + scratch;
        16 * complex + 8 * self.padded_columns
    }

    /// Bytes held by an operator with `segments` gather segments on this
    /// grid, its workspace included (the gather order, the spectrum, the
    /// plans, the workspace).
    fn operator_bytes(&self, segments: usize) -> usize {
        GatherOrder::bytes_for(segments, self.rows)
            + 8 * self.spectrum_len()
            + self.plan_bytes()
            + self.workspace_bytes(self.scratch_bound())
    }
}

/// The smallest even 5-smooth number `>= 2 n - 1` (at least 2): a padded
/// length without wrap-around and fast for the FFT.
fn padded_length(n: usize) -> usize {
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

/// The half-space part of S on the lattice: the gather order, the kernel
/// spectrum and the FFT plans (immutable after construction).
struct Convolution {
    grid: Grid,
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
            .field("segments", &self.gather.segments.len())
            .finish_non_exhaustive()
    }
}

/// The scratch memory of one product `S x`: a band of the row spectra of
/// the box (`n1 ceil((P2/2 + 1) / 2)` complex values), a row and its
/// spectrum, a batch of columns and the FFT scratch. Made by
/// [`LatticeKernel::workspace`] for one operator (or one of the same grid);
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

/// A vector of `len` copies of `value`, or [`InfluenceError::AllocationFailed`]
/// naming `what` when the memory cannot be reserved.
fn try_vec<T: Clone>(len: usize, value: T, what: &'static str) -> Result<Vec<T>, InfluenceError> {
    let mut v = Vec::new();
    v.try_reserve_exact(len)
        .map_err(|_| InfluenceError::AllocationFailed {
            what,
            bytes: len.saturating_mul(std::mem::size_of::<T>()),
        })?;
    v.resize(len, value);
    Ok(v)
}

/// The bodies' terms and the lattice's box, validated for the operator.
struct Setup {
    terms: Terms,
    bounds: LatticeBox,
}

impl Setup {
    /// Validates the bodies (as [`assemble`](crate::assemble) does, and no
    /// beam) and the point set (a lattice not much sparser than its box).
    fn new(points: &PointSet, bodies: &[&Body]) -> Result<Self, InfluenceError> {
        let terms = Terms::collect(points, bodies)?;
        if let Some(beam) = bodies
            .iter()
            .find(|b| matches!(b.model(), Model::Beam { .. }))
        {
            return Err(InfluenceError::NotTranslationInvariant {
                model: beam.model().name(),
            });
        }
        let bounds = points
            .lattice()
            .and_then(LatticeBox::of_lattice)
            .ok_or_else(|| InfluenceError::LatticeRequired {
                reason: "the points lie on no lattice of the cell's spacing \
                     (PointSet::from_points found none)"
                    .into(),
            })?;
        if !bounds.is_dense(points.len()) {
            return Err(InfluenceError::LatticeRequired {
                reason: format!(
                    "the lattice's bounding box of {} x {} cells is more than {} cells for \
                     {} points: the zero-padded grid would cost more than the points",
                    bounds.ni,
                    bounds.nj,
                    LatticeBox::cell_limit(points.len()),
                    points.len()
                ),
            });
        }
        Ok(Self { terms, bounds })
    }

    /// Whether there is a half-space kernel to convolve with.
    fn has_kernel(&self) -> bool {
        !self.terms.kernels.is_empty()
    }
}

impl LatticeOperator {
    /// The operator `x -> S x` of `bodies` (`S = sum_b A(b)`, as
    /// [`assemble`](crate::assemble)) on the lattice point set `points`: the
    /// kernel table and its spectrum are computed here, once, then the
    /// workspace of [`apply`](Self::apply).
    ///
    /// # Errors
    /// - as [`assemble`](crate::assemble): [`InfluenceError::DimensionMismatch`],
    ///   [`InfluenceError::InvalidModel`], [`InfluenceError::AllRigid`];
    /// - [`InfluenceError::NotTranslationInvariant`]: a beam among `bodies`;
    /// - [`InfluenceError::LatticeRequired`]: `points` has no lattice, its
    ///   bounding box holds more than 4 cells per point (plus 64), or two
    ///   points fall on one lattice cell;
    /// - [`InfluenceError::AllocationFailed`]: the memory
    ///   ([`estimate_bytes`](Self::estimate_bytes)) cannot be allocated.
    pub fn new(points: &PointSet, bodies: &[&Body]) -> Result<Self, InfluenceError> {
        let kernel = LatticeKernel::new(points, bodies)?;
        let workspace = kernel.workspace()?;
        Ok(Self { kernel, workspace })
    }

    /// The memory [`LatticeOperator::new`] would allocate for `points` and
    /// `bodies`, in bytes, computed without allocating it: the figure
    /// [`memory_bytes`](Self::memory_bytes) reports once built (to the FFT
    /// plans' scratch and twiddles, estimated from above); a
    /// [`LatticeKernel`] and the one workspace its products need. The
    /// construction never holds more at once (the kernel table is made a
    /// row at a time, its spectrum in the stored one).
    ///
    /// # Errors
    /// As [`LatticeOperator::new`], except [`InfluenceError::AllocationFailed`]
    /// and two points on one lattice cell (found while building).
    pub fn estimate_bytes(points: &PointSet, bodies: &[&Body]) -> Result<usize, InfluenceError> {
        let setup = Setup::new(points, bodies)?;
        let base = std::mem::size_of::<Self>();
        if !setup.has_kernel() {
            return Ok(base);
        }
        let segments = segments(points, &setup.bounds).count();
        Ok(base + Grid::new(&setup.bounds).operator_bytes(segments))
    }

    /// The operator's kernel, to share (`&LatticeKernel` is `Sync`).
    pub fn kernel(&self) -> &LatticeKernel {
        &self.kernel
    }

    /// Bytes held by the operator, its workspace included.
    pub fn memory_bytes(&self) -> usize {
        // Both sizes count their own struct; the operator's is both.
        self.kernel.memory_bytes() + self.workspace.memory_bytes()
    }

    /// `y = S x`: `y_k` = the deflection at point k under the forces `x_j`
    /// at the points j, in the point set's order (x in force, y in length),
    /// with the operator's own workspace.
    ///
    /// # Panics
    /// If `x` or `y` does not have [`len`](LatticeKernel::len) entries.
    pub fn apply(&mut self, x: &[f64], y: &mut [f64]) {
        self.kernel.apply_with(x, y, &mut self.workspace);
    }
}

impl std::ops::Deref for LatticeOperator {
    type Target = LatticeKernel;

    fn deref(&self) -> &LatticeKernel {
        &self.kernel
    }
}

impl LatticeKernel {
    /// The kernel of `bodies` on `points`, as [`LatticeOperator::new`]
    /// without its workspace (about 16 bytes per cell of the lattice's
    /// bounding box fewer).
    ///
    /// # Errors
    /// As [`LatticeOperator::new`].
    pub fn new(points: &PointSet, bodies: &[&Body]) -> Result<Self, InfluenceError> {
        let setup = Setup::new(points, bodies)?;
        let winkler = setup.terms.winkler_diagonal(points);
        let (convolution, self_term) = if setup.has_kernel() {
            let (convolution, self_term) = Convolution::new(points, &setup)?;
            (Some(convolution), self_term)
        } else {
            (None, 0.0)
        };
        Ok(Self {
            len: points.len(),
            // In the order assemble adds them: the table's (0, 0), then Winkler.
            diagonal: self_term + winkler,
            winkler,
            convolution,
        })
    }

    /// The number of points N (the length of x and y).
    pub fn len(&self) -> usize {
        self.len
    }

    /// Always false: a point set holds at least one point.
    pub fn is_empty(&self) -> bool {
        self.len == 0
    }

    /// The diagonal entry `S_kk`, the same for every point of a lattice (the
    /// self-term of the kernels plus the Winkler `1/(k A_k)`; length/force):
    /// a Jacobi preconditioner is this scalar.
    pub fn diagonal(&self) -> f64 {
        self.diagonal
    }

    /// The padded FFT grid `(P1, P2)` (rows along the lattice's i, columns
    /// along j), or `None` when no half-space body needs a convolution (only
    /// foundations).
    pub fn fft_shape(&self) -> Option<(usize, usize)> {
        self.convolution
            .as_ref()
            .map(|c| (c.grid.padded_rows, c.grid.padded_columns))
    }

    /// Bytes held by the kernel (no workspace).
    pub fn memory_bytes(&self) -> usize {
        std::mem::size_of::<Self>() + self.convolution.as_ref().map_or(0, Convolution::bytes)
    }

    /// A new workspace for [`apply_with`](Self::apply_with), e.g. one per
    /// thread ([`LatticeWorkspace::memory_bytes`] each, about 16 bytes per
    /// cell of the lattice's bounding box).
    ///
    /// # Errors
    /// [`InfluenceError::AllocationFailed`] when the memory cannot be
    /// allocated.
    pub fn workspace(&self) -> Result<LatticeWorkspace, InfluenceError> {
        let Some(c) = &self.convolution else {
            return Ok(LatticeWorkspace {
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
        Ok(LatticeWorkspace {
            grid: Some(g),
            spectra: try_vec(g.rows * g.band_width(), zero, "lattice row spectra")?,
            row: try_vec(g.padded_columns, 0.0, "lattice row")?,
            row_spectrum: try_vec(g.half_columns(), zero, "lattice row spectrum")?,
            batch: try_vec(COLUMN_BATCH * g.padded_rows, zero, "lattice column batch")?,
            scratch: try_vec(c.scratch_len, zero, "FFT scratch")?,
        })
    }

    /// `y = S x` as [`LatticeOperator::apply`], with a caller's workspace:
    /// the kernel is shared (`&self`, it is `Sync`), so threads may apply
    /// it at once, each with its own workspace.
    ///
    /// # Panics
    /// If `x` or `y` does not have [`len`](Self::len) entries, or the
    /// workspace was made for an operator of another grid.
    pub fn apply_with(&self, x: &[f64], y: &mut [f64], workspace: &mut LatticeWorkspace) {
        assert_eq!(
            x.len(),
            self.len,
            "x has {} entries for {} points",
            x.len(),
            self.len
        );
        assert_eq!(
            y.len(),
            self.len,
            "y has {} entries for {} points",
            y.len(),
            self.len
        );
        assert_eq!(
            workspace.grid,
            self.convolution.as_ref().map(|c| c.grid),
            "the workspace was made for an operator of another grid"
        );
        match &self.convolution {
            Some(c) => c.apply(x, y, workspace),
            None => y.fill(0.0),
        }
        if self.winkler != 0.0 {
            for (y, x) in y.iter_mut().zip(x) {
                *y += self.winkler * x;
            }
        }
    }
}

impl Convolution {
    /// The gather order, the kernel spectrum and the plans; also returns the
    /// kernel table's self-term (its (0, 0) entry).
    fn new(points: &PointSet, setup: &Setup) -> Result<(Self, f64), InfluenceError> {
        let grid = Grid::new(&setup.bounds);
        let gather = GatherOrder::new(points, &setup.bounds)?;
        let mut real_planner = RealFftPlanner::<f64>::new();
        let (spectrum, self_term) = kernel_spectrum(&setup.terms, &grid, &mut real_planner)?;
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
    fn bytes(&self) -> usize {
        self.gather.bytes() + 8 * self.spectrum.capacity() + self.grid.plan_bytes()
    }

    /// `y` = the half-space part of `S x`, band by band of the row
    /// spectra: the inverse row transforms are linear, so the bands' rows
    /// add up to the whole.
    fn apply(&self, x: &[f64], y: &mut [f64], ws: &mut LatticeWorkspace) {
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

/// The points grouped by lattice row, as segments of consecutive points on
/// consecutive lattice columns (a grid's row is one segment): to spread x
/// on the box row by row and gather y back, a slice at a time.
struct GatherOrder {
    /// Segments by lattice row: row i holds
    /// `segments[row_start[i]..row_start[i + 1]]`.
    segments: Vec<Segment>,
    row_start: Vec<u32>,
}

/// Points `point..point + len` on the lattice columns `column..column +
/// len` of one row.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
struct Segment {
    column: u32,
    point: u32,
    len: u32,
}

impl Segment {
    fn columns(&self) -> Range<usize> {
        self.column as usize..(self.column + self.len) as usize
    }

    fn points(&self) -> Range<usize> {
        self.point as usize..(self.point + self.len) as usize
    }
}

/// The segments of a point set on a lattice box, in the points' order,
/// each with its lattice row.
fn segments(points: &PointSet, bounds: &LatticeBox) -> impl Iterator<Item = (usize, Segment)> {
    let lattice = points.lattice().expect("Setup checked the lattice");
    let mut cells = lattice.iter().map(|l| bounds.local(l)).enumerate();
    let mut current: Option<(usize, Segment)> = None;
    std::iter::from_fn(move || {
        loop {
            let Some((k, (i, j))) = cells.next() else {
                return current.take();
            };
            // Bounded by the box and MAX_POINTS (the const assertion above).
            let (k, j) = (k as u32, j as u32);
            match &mut current {
                Some((row, s)) if *row == i && s.column + s.len == j && s.point + s.len == k => {
                    s.len += 1;
                }
                _ => {
                    let next = Segment {
                        column: j,
                        point: k,
                        len: 1,
                    };
                    if let Some(done) = current.replace((i, next)) {
                        return Some(done);
                    }
                }
            }
        }
    })
}

impl GatherOrder {
    /// # Errors
    /// [`InfluenceError::LatticeRequired`] when two points fall on one
    /// lattice cell (possible for [`PointSet::from_points`] within its
    /// lattice tolerance); [`InfluenceError::AllocationFailed`].
    fn new(points: &PointSet, bounds: &LatticeBox) -> Result<Self, InfluenceError> {
        let mut row_start = try_vec(bounds.ni + 1, 0u32, "lattice row starts")?;
        for (i, _) in segments(points, bounds) {
            row_start[i + 1] += 1;
        }
        for i in 0..bounds.ni {
            row_start[i + 1] += row_start[i];
        }
        let count = row_start[bounds.ni] as usize;
        let mut next = row_start.clone();
        let empty = Segment {
            column: 0,
            point: 0,
            len: 0,
        };
        let mut placed = try_vec(count, empty, "lattice gather order")?;
        for (i, s) in segments(points, bounds) {
            placed[next[i] as usize] = s;
            next[i] += 1;
        }
        let gather = Self {
            segments: placed,
            row_start,
        };
        let lattice = points.lattice().expect("Setup checked the lattice");
        gather.check_distinct_cells(lattice, bounds.nj)?;
        Ok(gather)
    }

    /// Bytes of an order of `segments` segments on `rows` lattice rows.
    fn bytes_for(segments: usize, rows: usize) -> usize {
        std::mem::size_of::<Segment>() * segments + 4 * (rows + 1)
    }

    /// Two points on one cell would be summed into one value of the grid:
    /// an error naming them.
    fn check_distinct_cells(&self, lattice: Lattice<'_>, nj: usize) -> Result<(), InfluenceError> {
        // The last row that filled each column, and the point that did.
        let mut seen = try_vec(nj, (u32::MAX, 0u32), "lattice row occupancy")?;
        for i in 0..self.row_start.len() - 1 {
            for s in self.row(i) {
                for (j, k) in s.columns().zip(s.points()) {
                    let (row, a) = seen[j];
                    if row == i as u32 {
                        return Err(InfluenceError::LatticeRequired {
                            reason: format!(
                                "points {a} and {k} fall on one lattice cell (i, j) = {:?}",
                                lattice.get(k)
                            ),
                        });
                    }
                    seen[j] = (i as u32, k as u32);
                }
            }
        }
        Ok(())
    }

    /// The segments of lattice row `i`.
    fn row(&self, i: usize) -> &[Segment] {
        &self.segments[self.row_start[i] as usize..self.row_start[i + 1] as usize]
    }

    /// Bytes held.
    fn bytes(&self) -> usize {
        std::mem::size_of::<Segment>() * self.segments.capacity() + 4 * self.row_start.capacity()
    }
}

/// The kernel table of the bodies on the lattice's offsets (the one
/// [`assemble`](crate::assemble) gathers from, computed a row at a time)
/// and its spectrum `DFT(Kc) / (P1 P2)` on `(P1/2 + 1) x (P2/2 + 1)`
/// frequencies (see [`Convolution::spectrum`]); also the table's self-term.
/// Kc is even along both axes, so both stages are real transforms of even
/// sequences whose real parts are kept (the imaginary parts are rounding).
/// The row stage writes its spectra into the result, transposed (frequency
/// m2's values over i where the column stage reads them, `n1 <= P1/2 + 1`),
/// and the column stage transforms them in place: nothing of the box's
/// size is allocated but the result.
fn kernel_spectrum(
    terms: &Terms,
    grid: &Grid,
    planner: &mut RealFftPlanner<f64>,
) -> Result<(Vec<f64>, f64), InfluenceError> {
    let (n1, n2) = (grid.rows, grid.columns);
    let half_rows = grid.half_rows();
    let row_fft = planner.plan_fft_forward(grid.padded_columns);
    let column_fft = planner.plan_fft_forward(grid.padded_rows);
    let zero = C64::new(0.0, 0.0);
    let mut scratch = vec![zero; row_fft.get_scratch_len().max(column_fft.get_scratch_len())];
    let mut spectrum = try_vec(grid.spectrum_len(), 0.0, "kernel spectrum")?;
    // Rows: the even extension of each offset row di, transformed along j.
    let mut values = vec![0.0; n2];
    let mut row = vec![0.0; grid.padded_columns];
    let mut row_spectrum = vec![zero; grid.half_columns()];
    let mut self_term = 0.0;
    for di in 0..n1 {
        terms.table_row(di, &mut values);
        if di == 0 {
            self_term = values[0];
        }
        even_extension(&values, &mut row);
        row_fft
            .process_with_scratch(&mut row, &mut row_spectrum, &mut scratch)
            .expect("buffer lengths follow the plan");
        for (m2, z) in row_spectrum.iter().enumerate() {
            spectrum[m2 * half_rows + di] = z.re;
        }
    }
    // Columns: the even extension along i of each frequency m2.
    let scale = 1.0 / (grid.padded_rows as f64 * grid.padded_columns as f64);
    let mut values = vec![0.0; n1];
    let mut column = vec![0.0; grid.padded_rows];
    let mut column_spectrum = vec![zero; half_rows];
    for out in spectrum.chunks_exact_mut(half_rows) {
        values.copy_from_slice(&out[..n1]);
        even_extension(&values, &mut column);
        column_fft
            .process_with_scratch(&mut column, &mut column_spectrum, &mut scratch)
            .expect("buffer lengths follow the plan");
        for (o, z) in out.iter_mut().zip(&column_spectrum) {
            *o = z.re * scale;
        }
    }
    Ok((spectrum, self_term))
}

/// `out` (length `P >= 2 n - 1`) = the even periodic extension of the
/// offsets `values[0..n]`: `out[b] = out[P - b] = values[b]`, 0 between.
fn even_extension(values: &[f64], out: &mut [f64]) {
    let (n, p) = (values.len(), out.len());
    debug_assert!(p + 1 >= 2 * n);
    out.fill(0.0);
    out[..n].copy_from_slice(values);
    for b in 1..n {
        out[p - b] = values[b];
    }
}

#[cfg(test)]
mod tests {
    use faer::{Col, Mat};

    use super::*;
    use crate::points::{Cell, Dimension};
    use crate::{Material, assemble};

    /// `max |S x - op x| / max |S x|` is at most this. The FFT's rounding is
    /// a few eps log2(P1 P2) of the sum of |K| |x| entering a value, about
    /// 1e-15 on these grids (measured at most 1.2e-15 over every case here,
    /// signed x included); a wrong offset, padding or scale gives 1e-2 to 1.
    const TOLERANCE: f64 = 1e-12;

    fn steel() -> Material {
        Material::new(30e6, 0.3).unwrap()
    }

    fn aluminium() -> Material {
        Material::new(10e6, 0.33).unwrap()
    }

    /// A reproducible x in [lo, 1) (xorshift; no dev-dependency needed).
    fn random_vector(n: usize, seed: u64, lo: f64) -> Vec<f64> {
        let mut state = seed.wrapping_mul(0x9E37_79B9_7F4A_7C15) | 1;
        (0..n)
            .map(|_| {
                state ^= state << 13;
                state ^= state >> 7;
                state ^= state << 17;
                lo + (1.0 - lo) * (state >> 11) as f64 / (1u64 << 53) as f64
            })
            .collect()
    }

    /// The relative error of the operator against the dense S on x.
    fn relative_error(s: &Mat<f64>, op: &mut LatticeOperator, x: &[f64]) -> f64 {
        let dense = s * Col::<f64>::from_fn(x.len(), |k| x[k]);
        let mut y = vec![0.0; x.len()];
        op.apply(x, &mut y);
        let scale = dense.iter().fold(0.0f64, |m, v| m.max(v.abs()));
        let error = (0..x.len()).fold(0.0f64, |m, k| m.max((dense[k] - y[k]).abs()));
        error / scale
    }

    /// The grids: disks (odd extents), rectangles odd and even, square and
    /// oblong cells, a single row and a single point.
    fn grids() -> Vec<(&'static str, PointSet)> {
        vec![
            ("disk r = 3.2 h", PointSet::grid_disk(0.1, 0.32).unwrap()),
            ("disk r = 5 h", PointSet::grid_disk(0.2, 1.0).unwrap()),
            (
                "rectangle 7 x 5, oblong cells",
                PointSet::grid_rectangle(0.7, 2.0, 7, 5).unwrap(),
            ),
            (
                "rectangle 8 x 6, square cells",
                PointSet::grid_rectangle(0.4, 0.3, 8, 6).unwrap(),
            ),
            (
                "rectangle 4 x 9",
                PointSet::grid_rectangle(1.0, 3.0, 4, 9).unwrap(),
            ),
            (
                "row 12 x 1",
                PointSet::grid_rectangle(1.0, 0.05, 12, 1).unwrap(),
            ),
            (
                "one point",
                PointSet::grid_rectangle(1.0, 1.0, 1, 1).unwrap(),
            ),
        ]
    }

    fn surface_bodies() -> Vec<(&'static str, Vec<Body>)> {
        vec![
            (
                "patch + patch",
                vec![Body::uniform_patch(steel()), Body::uniform_patch(steel())],
            ),
            (
                "point + point, two materials",
                vec![Body::point_force(steel()), Body::point_force(aluminium())],
            ),
            (
                "patch + point",
                vec![Body::uniform_patch(aluminium()), Body::point_force(steel())],
            ),
            (
                "rigid + patch",
                vec![Body::rigid(), Body::uniform_patch(aluminium())],
            ),
            (
                "patch on a foundation",
                vec![Body::uniform_patch(steel()), Body::winkler(3e8)],
            ),
            ("foundation alone", vec![Body::winkler(3e8), Body::rigid()]),
        ]
    }

    fn check(name: &str, points: &PointSet, bodies: &[Body]) {
        let refs: Vec<&Body> = bodies.iter().collect();
        let s = assemble(points, &refs).unwrap();
        let mut op = LatticeOperator::new(points, &refs).unwrap();
        assert_eq!(op.len(), points.len());
        for (seed, lo) in [(1, 0.0), (2, -1.0)] {
            let x = random_vector(points.len(), seed, lo);
            let e = relative_error(&s, &mut op, &x);
            assert!(e <= TOLERANCE, "{name}, x in [{lo}, 1): {e:e}");
        }
        for k in 0..points.len() {
            assert_eq!(op.diagonal(), s[(k, k)], "{name}: S_{k}{k}");
        }
    }

    #[test]
    fn equals_the_dense_s_on_every_surface_grid_and_model() {
        for (grid, points) in grids() {
            for (models, bodies) in surface_bodies() {
                check(&format!("{grid}, {models}"), &points, &bodies);
            }
        }
    }

    #[test]
    fn equals_the_dense_s_on_a_line() {
        // The plane-strain strip is a translation-invariant kernel too.
        for n in [1, 2, 9, 16] {
            let line = PointSet::line(-1.0, 1.0, n).unwrap();
            check(
                &format!("line of {n}, strips"),
                &line,
                &[
                    Body::plane_strain(steel(), 3.0),
                    Body::plane_strain(aluminium(), 3.0),
                ],
            );
            check(
                &format!("line of {n}, strip on a foundation"),
                &line,
                &[Body::plane_strain(steel(), 10.0), Body::winkler(5e6)],
            );
        }
    }

    #[test]
    fn follows_the_order_of_a_shuffled_irregular_lattice() {
        // An L-shaped set on a lattice, in a scrambled order, from
        // PointSet::from_points: the gather order is not the lattice order.
        let (mut xs, mut ys) = (Vec::new(), Vec::new());
        for t in 0..60usize {
            let k = (t * 37) % 60;
            let (i, j) = (k / 6, k % 6);
            if i < 4 || j < 2 {
                xs.push(0.5 + i as f64 * 0.25);
                ys.push(-1.0 + j as f64 * 0.4);
            }
        }
        let points =
            PointSet::from_points(Dimension::Surface, xs, ys, Cell { dx: 0.25, dy: 0.4 }).unwrap();
        assert!(points.lattice().is_some());
        for (models, bodies) in surface_bodies() {
            check(&format!("L-shape, {models}"), &points, &bodies);
        }
    }

    #[test]
    fn a_shared_workspace_gives_the_same_product() {
        let points = PointSet::grid_disk(0.1, 0.55).unwrap();
        let bodies = [&Body::uniform_patch(steel()), &Body::point_force(steel())];
        let mut op = LatticeOperator::new(&points, &bodies).unwrap();
        let x = random_vector(points.len(), 7, -1.0);
        let (mut a, mut b, mut c) = (vec![0.0; x.len()], vec![0.0; x.len()], vec![0.0; x.len()]);
        op.apply(&x, &mut a);
        op.apply(&x, &mut b); // the workspace holds the last product's values
        let mut ws = op.workspace().unwrap();
        op.apply_with(&x, &mut c, &mut ws);
        assert_eq!(a, b);
        assert_eq!(a, c);
        // A kernel alone: the same product, the workspace's bytes fewer.
        let kernel = LatticeKernel::new(&points, &bodies).unwrap();
        assert_eq!(kernel.memory_bytes() + ws.memory_bytes(), op.memory_bytes());
        assert_eq!(kernel.memory_bytes(), op.kernel().memory_bytes());
        let mut d = vec![0.0; x.len()];
        kernel.apply_with(&x, &mut d, &mut ws);
        assert_eq!(a, d);
        // Shared between threads, one workspace each.
        let shared = &op;
        std::thread::scope(|scope| {
            for seed in [1, 2] {
                scope.spawn(move || {
                    let mut ws = shared.workspace().unwrap();
                    let x = random_vector(shared.len(), seed, 0.0);
                    let mut y = vec![0.0; x.len()];
                    shared.apply_with(&x, &mut y, &mut ws);
                    assert!(y.iter().all(|v| *v > 0.0));
                });
            }
        });
    }

    #[test]
    fn memory_is_linear_in_the_points_and_estimated_before() {
        // Held bytes: 16 per cell of the padded box's quarter (the spectrum
        // 8, one band of the row spectra 8), 12 per segment of the gather
        // order (one a lattice row on these grids), and O(sqrt N) for the
        // plans, a row, a column batch and the scratch. A rectangle's box is
        // its points, a disk's 4/pi of them; padding to 5-smooth lengths adds
        // up to ~10 %. Measured: 22.9 and 19.4 B/point on the squares, 31.4
        // and 26.8 on the disks; the bounds leave a few percent.
        let bodies = [&Body::uniform_patch(steel()), &Body::uniform_patch(steel())];
        for (name, small, large, bound) in [
            (
                "square 128 x 128 and 256 x 256",
                PointSet::grid_rectangle(1.0, 1.0, 128, 128).unwrap(),
                PointSet::grid_rectangle(1.0, 1.0, 256, 256).unwrap(),
                24.0,
            ),
            (
                "disks of radius 64 h and 128 h",
                PointSet::grid_disk(1.0, 64.0).unwrap(),
                PointSet::grid_disk(1.0, 128.0).unwrap(),
                33.0,
            ),
        ] {
            let mut per_point = Vec::new();
            for points in [&small, &large] {
                let estimate = LatticeOperator::estimate_bytes(points, &bodies).unwrap();
                let op = LatticeOperator::new(points, &bodies).unwrap();
                let held = op.memory_bytes();
                // The estimate bounds the FFT scratch from above by at most
                // the bound itself, P1 + P2 complex values.
                let (p1, p2) = op.fft_shape().unwrap();
                assert!(held <= estimate, "{name}: {held} > {estimate}");
                assert!(
                    estimate <= held + 16 * (p1 + p2),
                    "{name}: {estimate} vs {held}"
                );
                per_point.push(held as f64 / points.len() as f64);
            }
            // Four times the points: the bytes per point do not grow (a
            // term in N^2 would multiply them by 4) and stay under the bound.
            assert!(per_point[1] <= per_point[0], "{name}: {per_point:?}");
            assert!(
                per_point.iter().all(|&b| b < bound),
                "{name}: {per_point:?}"
            );
        }
    }

    #[test]
    fn padded_lengths_avoid_wrap_around_and_are_fast() {
        for (n, expected) in [
            (1, 2),
            (2, 4),
            (3, 6),
            (5, 10),
            (6, 12),
            (65, 144),
            (512, 1024),
        ] {
            assert_eq!(padded_length(n), expected, "n = {n}");
        }
        for n in 1..300 {
            let p = padded_length(n);
            assert!(p + 1 >= 2 * n && p.is_multiple_of(2), "n = {n}: {p}");
        }
        let points = PointSet::grid_rectangle(1.0, 1.0, 20, 3).unwrap();
        let op = LatticeOperator::new(&points, &[&Body::uniform_patch(steel())]).unwrap();
        assert_eq!(op.fft_shape(), Some((40, 6)));
        let foundation = LatticeOperator::new(&points, &[&Body::winkler(1.0)]).unwrap();
        assert_eq!(foundation.fft_shape(), None);
    }

    #[test]
    fn refuses_points_off_a_lattice() {
        let patch = Body::uniform_patch(steel());
        let scattered = PointSet::from_points(
            Dimension::Surface,
            vec![0.0, 0.13, 0.5],
            vec![0.0, 0.02, 0.31],
            Cell::square(0.1),
        )
        .unwrap();
        assert!(scattered.lattice().is_none());
        let e = LatticeOperator::new(&scattered, &[&patch]).unwrap_err();
        assert!(matches!(e, InfluenceError::LatticeRequired { .. }), "{e}");
        assert!(
            e.to_string()
                .starts_with("the lattice operator needs the points on a compact lattice: the points lie on no lattice"),
            "{e}"
        );
        assert_eq!(
            LatticeOperator::estimate_bytes(&scattered, &[&patch]),
            Err(e)
        );
        // A lattice far sparser than its box: 2 points 1000 cells apart.
        let sparse = PointSet::from_points(
            Dimension::Surface,
            vec![0.0, 1000.0],
            vec![0.0, 0.0],
            Cell::square(1.0),
        )
        .unwrap();
        let e = LatticeOperator::new(&sparse, &[&patch]).unwrap_err();
        assert!(
            e.to_string()
                .contains("bounding box of 1001 x 1 cells is more than 72 cells for 2 points"),
            "{e}"
        );
        // Two points within the lattice tolerance of one cell.
        let twins = PointSet::from_points(
            Dimension::Surface,
            vec![0.0, 1e-14, 1.0],
            vec![0.0, 0.0, 0.0],
            Cell::square(1.0),
        )
        .unwrap();
        assert_eq!(twins.lattice().unwrap().to_vec(), [(0, 0), (0, 0), (1, 0)]);
        let e = LatticeOperator::new(&twins, &[&patch]).unwrap_err();
        assert!(
            e.to_string()
                .contains("points 0 and 1 fall on one lattice cell (i, j) = (0, 0)"),
            "{e}"
        );
    }

    #[test]
    fn refuses_beams_and_what_assemble_refuses() {
        let line = PointSet::line(-1.0, 1.0, 8).unwrap();
        let e = LatticeOperator::new(&line, &[&Body::beam(1e4, 3.0, 0.0), &Body::winkler(1e3)])
            .unwrap_err();
        assert_eq!(
            e,
            InfluenceError::NotTranslationInvariant {
                model: "Euler-Bernoulli beam"
            }
        );
        assert!(
            e.to_string()
                .starts_with("the Euler-Bernoulli beam model is not translation invariant"),
            "{e}"
        );
        let rigid = Body::rigid();
        assert_eq!(
            LatticeOperator::new(&line, &[&rigid, &rigid]).unwrap_err(),
            InfluenceError::AllRigid { bodies: 2 }
        );
        let e = LatticeOperator::new(&line, &[&Body::uniform_patch(steel())]).unwrap_err();
        assert!(matches!(e, InfluenceError::DimensionMismatch { .. }), "{e}");
        let e = LatticeOperator::new(&line, &[&Body::plane_strain(steel(), 0.5)]).unwrap_err();
        assert!(matches!(e, InfluenceError::InvalidModel { .. }), "{e}");
    }

    #[test]
    fn a_failed_allocation_is_an_error() {
        let e = try_vec(usize::MAX / 4, 0.0f64, "kernel spectrum").unwrap_err();
        assert_eq!(
            e,
            InfluenceError::AllocationFailed {
                what: "kernel spectrum",
                bytes: usize::MAX
            }
        );
        assert!(
            e.to_string().starts_with(&format!(
                "could not allocate {} bytes for the kernel spectrum",
                usize::MAX
            )),
            "{e}"
        );
    }

    #[test]
    #[should_panic(expected = "x has 3 entries for 4 points")]
    fn a_wrong_length_panics_with_the_lengths() {
        let points = PointSet::grid_rectangle(1.0, 1.0, 2, 2).unwrap();
        let mut op = LatticeOperator::new(&points, &[&Body::uniform_patch(steel())]).unwrap();
        op.apply(&[1.0; 3], &mut [0.0; 4]);
    }

    #[test]
    fn is_send_and_sync() {
        fn shared<T: Send + Sync>() {}
        shared::<LatticeKernel>();
        shared::<LatticeOperator>();
        shared::<LatticeWorkspace>();
    }
}
