//! The operator `x -> S x` on a lattice point set, `(S x)_k = Y[i_k, j_k] +
//! x_k / (k_w A_k)` (the convolution Y of the half-space kernels plus the
//! Winkler diagonal): the bodies and points validated, the product with a
//! workspace of its own ([`LatticeOperator`]) or a caller's
//! ([`LatticeKernel`]), and its memory, counted before it is built.

use faer::dyn_stack::{PodStack, StackReq};

use super::convolution::{Buffers, Convolution, LatticeWorkspace};
use super::gather::{GatherOrder, segments};
use super::grid::Grid;
use super::preconditioner::LatticePreconditioner;
use crate::error::InfluenceError;
use crate::models::{Body, Model};
use crate::points::{LatticeBox, PointSet};
use crate::terms::Terms;

/// The influence operator `x -> S x` of the bodies in contact on a lattice
/// point set, applied by FFT without forming S; see the
/// [module documentation](super) for the equation, the cost and the models.
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
/// // O(N): 64 bytes per point here on one thread, 72 on two (a batch of
/// // columns per thread), ~30 on large grids (a dense S: 8 N per point).
/// assert!(op.memory_bytes() < 80 * points.len());
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
        let gather_bytes = GatherOrder::bytes_for(segments, setup.bounds.ni);
        Ok(base + Grid::new(&setup.bounds).operator_bytes(gather_bytes))
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
            let (convolution, self_term) = Convolution::new(points, &setup.terms, &setup.bounds)?;
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
        LatticeWorkspace::new(self.convolution.as_ref())
    }

    /// An approximate inverse of S for a preconditioned conjugate gradient
    /// (the inverse of the kernel's symbol on the periodic half-size grid,
    /// [`LatticePreconditioner`]), applied by
    /// [`precondition_with`](Self::precondition_with) in a product's
    /// workspace; `None` when there is no half-space kernel (only
    /// foundations: S is a multiple of the identity).
    ///
    /// # Errors
    /// [`InfluenceError::AllocationFailed`] when its symbol (about 2 bytes
    /// a cell of the lattice's bounding box) cannot be allocated.
    pub fn preconditioner(&self) -> Result<Option<LatticePreconditioner>, InfluenceError> {
        self.convolution
            .as_ref()
            .map(|c| LatticePreconditioner::new(c, self.winkler))
            .transpose()
    }

    /// `z ≈ S^{-1} r` by `preconditioner` (made by
    /// [`preconditioner`](Self::preconditioner) of this kernel), in the
    /// point set's order, in the buffers of `workspace` (one
    /// [`workspace`](Self::workspace) of this kernel serves its products and
    /// its preconditioner's applications in turn: the application needs no
    /// memory of the box's size besides; its contents between calls mean
    /// nothing).
    ///
    /// # Panics
    /// If `r` or `z` does not have [`len`](Self::len) entries, the kernel
    /// has no convolution, or the workspace was made for an operator of
    /// another grid.
    pub fn precondition_with(
        &self,
        r: &[f64],
        z: &mut [f64],
        preconditioner: &LatticePreconditioner,
        workspace: &mut LatticeWorkspace,
    ) {
        let c = self.preconditioned(r, z);
        assert_eq!(
            workspace.grid(),
            Some(c.grid),
            "the workspace was made for an operator of another grid"
        );
        preconditioner.apply(c, r, z, workspace.buffers());
    }

    /// The scratch of one product ([`apply_in`](Self::apply_in)) or one
    /// application of the preconditioner
    /// ([`precondition_in`](Self::precondition_in)) in a caller's stack
    /// (`faer::dyn_stack`'s `PodStack`, made from a `PodBuffer` of this
    /// request once for many products): the buffers of a
    /// [`workspace`](Self::workspace), for the current rayon pool's
    /// threads; empty without a convolution.
    pub fn apply_scratch(&self) -> StackReq {
        self.convolution
            .as_ref()
            .map_or(StackReq::EMPTY, |c| Buffers::scratch(&c.grid))
    }

    /// `y = S x` as [`apply_with`](Self::apply_with), its buffers made in
    /// `stack` (at least [`apply_scratch`](Self::apply_scratch) of this
    /// kernel; their contents between calls mean nothing, as a
    /// [`LatticeWorkspace`]'s).
    ///
    /// # Panics
    /// If `x` or `y` does not have [`len`](Self::len) entries, or `stack`
    /// is smaller than [`apply_scratch`](Self::apply_scratch).
    pub fn apply_in(&self, x: &[f64], y: &mut [f64], stack: &mut PodStack) {
        self.check_lens(x, y);
        match &self.convolution {
            Some(c) => Buffers::in_stack(&c.grid, stack, |buffers| c.apply(x, y, buffers)),
            None => y.fill(0.0),
        }
        self.add_winkler(x, y);
    }

    /// `z ≈ S^{-1} r` as [`precondition_with`](Self::precondition_with),
    /// its buffers made in `stack` (see [`apply_in`](Self::apply_in)).
    ///
    /// # Panics
    /// As [`precondition_with`](Self::precondition_with), or if `stack`
    /// is smaller than [`apply_scratch`](Self::apply_scratch).
    pub fn precondition_in(
        &self,
        r: &[f64],
        z: &mut [f64],
        preconditioner: &LatticePreconditioner,
        stack: &mut PodStack,
    ) {
        let c = self.preconditioned(r, z);
        Buffers::in_stack(&c.grid, stack, |buffers| {
            preconditioner.apply(c, r, z, buffers);
        });
    }

    /// `y = S x` as [`LatticeOperator::apply`], with a caller's workspace:
    /// the kernel is shared (`&self`, it is `Sync`), so threads may apply
    /// it at once, each with its own workspace.
    ///
    /// # Panics
    /// If `x` or `y` does not have [`len`](Self::len) entries, or the
    /// workspace was made for an operator of another grid.
    pub fn apply_with(&self, x: &[f64], y: &mut [f64], workspace: &mut LatticeWorkspace) {
        self.check_lens(x, y);
        assert_eq!(
            workspace.grid(),
            self.convolution.as_ref().map(|c| c.grid),
            "the workspace was made for an operator of another grid"
        );
        match &self.convolution {
            Some(c) => c.apply(x, y, workspace.buffers()),
            None => y.fill(0.0),
        }
        self.add_winkler(x, y);
    }

    /// `y += S d` for `d = Σ_t v_t e_{p_t}`, the `columns` `(p_t, v_t)`:
    /// each column of S is the kernel table shifted to its point (plus the
    /// Winkler diagonal), added in O(N) without a transform; the same
    /// entries as [`apply_with`](Self::apply_with)'s product to its FFT's
    /// rounding. Cheaper than a product for up to about
    /// [`columns_per_product`](Self::columns_per_product) columns. Each
    /// entry of `y` adds its terms in the order of `columns`, on any
    /// number of threads.
    ///
    /// # Panics
    /// If `y` does not have [`len`](Self::len) entries or a `p_t` is not
    /// below it.
    pub fn add_columns(&self, columns: &[(usize, f64)], y: &mut [f64]) {
        assert_eq!(
            y.len(),
            self.len,
            "y has {} entries for {} points",
            y.len(),
            self.len
        );
        assert!(
            columns.iter().all(|&(p, _)| p < self.len),
            "a column index is not below {}",
            self.len
        );
        if let Some(c) = &self.convolution {
            c.add_columns(columns, y);
        }
        if self.winkler != 0.0 {
            for &(p, v) in columns {
                y[p] += self.winkler * v;
            }
        }
    }

    /// How many columns [`add_columns`](Self::add_columns) adds in about
    /// the time of one product (an estimate from the grid's size: a column
    /// costs N multiply-adds, a product `O(P1 P2 log(P1 P2))` on the
    /// padded grid); at least 1.
    pub fn columns_per_product(&self) -> usize {
        self.convolution
            .as_ref()
            .map_or(self.len, |c| c.columns_per_product(self.len))
    }

    /// The convolution a preconditioner applies on; panics unless `r` and
    /// `z` have [`len`](Self::len) entries and there is one.
    fn preconditioned(&self, r: &[f64], z: &[f64]) -> &Convolution {
        assert!(
            r.len() == self.len && z.len() == self.len,
            "r and z have {} and {} entries for {} points",
            r.len(),
            z.len(),
            self.len
        );
        self.convolution
            .as_ref()
            .expect("a preconditioner is made for a kernel with a convolution")
    }

    /// Panics unless `x` and `y` have [`len`](Self::len) entries.
    fn check_lens(&self, x: &[f64], y: &[f64]) {
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
    }

    /// `y += x / (k A)`, the Winkler diagonal (nothing without a
    /// foundation).
    fn add_winkler(&self, x: &[f64], y: &mut [f64]) {
        if self.winkler != 0.0 {
            for (y, x) in y.iter_mut().zip(x) {
                *y += self.winkler * x;
            }
        }
    }
}
