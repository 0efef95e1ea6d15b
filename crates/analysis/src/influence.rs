//! How a contact problem holds its influence matrix `S = A(1) + A(2)`:
//! dense (every entry, 8 N^2 bytes: what the exact pivoting methods need),
//! or matrix-free on a lattice (`elcon_influence::LatticeKernel`: the
//! product `S F` by an FFT convolution, O(N) memory: what the conjugate
//! gradient needs on grids too large to store); and what each offers,
//! whatever the storage: the products `y = S x`, the engine's bordered LCP
//! `w = S z - B λ + q`, `B^T z = b` on it, and the entries where held.
//! The one place in the workspace that branches on how S is held.

use std::cell::RefCell;
use std::sync::Arc;

use elcon_influence::{LatticeKernel, LatticePreconditioner, LatticeWorkspace};
use elcon_lcp::{
    BorderedLcpRef, LcpSolution, LinearSolution, LinearSystem, Method, Operator, OperatorLcp,
    Options,
};
use faer::{ColRef, Mat, MatRef};

use crate::AnalysisError;
use crate::storage::Storage;

/// The influence matrix of a problem, as it is held.
#[derive(Debug, Clone)]
pub(crate) enum Influence {
    /// Every entry of S (or of the folded matrix).
    Dense(Arc<Mat<f64>>),
    /// S by its products on a lattice.
    Lattice(Arc<LatticeKernel>),
}

impl Influence {
    /// The number of unknowns.
    pub fn len(&self) -> usize {
        match self {
            Influence::Dense(s) => s.nrows(),
            Influence::Lattice(op) => op.len(),
        }
    }

    /// How S is held (`folded`: the dense matrix is a folded problem's).
    pub fn storage(&self, folded: bool) -> Storage {
        match self {
            Influence::Dense(_) if folded => Storage::Folded,
            Influence::Dense(_) => Storage::Dense,
            Influence::Lattice(_) => Storage::Lattice,
        }
    }

    /// The entries, where held.
    pub fn entries(&self) -> Option<MatRef<'_, f64>> {
        match self {
            Influence::Dense(s) => Some(Mat::as_ref(s)),
            Influence::Lattice(_) => None,
        }
    }

    /// The engine's bordered LCP `w = S z - B λ + q`, `B^T z = b` on S as
    /// held, solved by `method`.
    pub fn solve_bordered(
        &self,
        q: ColRef<'_, f64>,
        border: MatRef<'_, f64>,
        resultant: ColRef<'_, f64>,
        method: Method,
        options: &Options,
    ) -> Result<LcpSolution, AnalysisError> {
        Ok(match self {
            Influence::Dense(s) => BorderedLcpRef::new(Mat::as_ref(s), q)?
                .with_border(border, resultant)?
                .solve(method, options)?,
            Influence::Lattice(kernel) => {
                let mut products = LatticeProducts::new(kernel)?;
                if options.preconditioner {
                    products = products.with_preconditioner()?;
                }
                OperatorLcp::new(&products, q)?
                    .with_border(border, resultant)?
                    .solve(method, options)?
            }
        })
    }
}

impl Influence {
    /// `S_JJ X = R` on the unknowns `contact` (J), `rhs` R of `|J|` rows,
    /// by the engine's certified linear solve (`elcon_lcp::LinearSystem`):
    /// dense, a Cholesky factor of the block `S_JJ` (LU, logged as a
    /// fallback, where it is not numerically positive definite);
    /// matrix-free, the conjugate gradient on the products restricted to J.
    pub fn restricted_solve(
        &self,
        contact: &[usize],
        rhs: MatRef<'_, f64>,
        options: &Options,
    ) -> Result<LinearSolution, AnalysisError> {
        Ok(match self {
            Influence::Dense(s) => {
                let nj = contact.len();
                let block = Mat::from_fn(nj, nj, |a, b| s[(contact[a], contact[b])]);
                LinearSystem::dense(block.as_ref(), rhs)?.solve(options)?
            }
            Influence::Lattice(kernel) => {
                let restricted = Restricted {
                    products: LatticeProducts::new(kernel)?,
                    contact,
                    full: RefCell::new(vec![0.0; kernel.len()]),
                    product: RefCell::new(vec![0.0; kernel.len()]),
                };
                LinearSystem::operator(&restricted, rhs)?.solve(options)?
            }
        })
    }
}

/// An operator's products restricted to the unknowns `contact`:
/// `(S_JJ x) = (S [x on J, 0 elsewhere])_J`, through two buffers of n.
struct Restricted<'a> {
    products: LatticeProducts<'a>,
    contact: &'a [usize],
    full: RefCell<Vec<f64>>,
    product: RefCell<Vec<f64>>,
}

impl Restricted<'_> {
    fn restricted(&self, x: &[f64], y: &mut [f64], abs: bool) {
        let (mut full, mut product) = (self.full.borrow_mut(), self.product.borrow_mut());
        for (&k, &v) in self.contact.iter().zip(x) {
            full[k] = v;
        }
        if abs {
            self.products.apply_abs(&full, &mut product);
        } else {
            self.products.apply(&full, &mut product);
        }
        for (y, &k) in y.iter_mut().zip(self.contact) {
            *y = product[k];
        }
    }
}

impl Operator for Restricted<'_> {
    fn size(&self) -> usize {
        self.contact.len()
    }

    fn apply(&self, x: &[f64], y: &mut [f64]) {
        self.restricted(x, y, false);
    }

    fn apply_abs(&self, x: &[f64], y: &mut [f64]) {
        self.restricted(x, y, true);
    }
}

/// The lattice operator with a workspace of its own, as the engine applies
/// it (one solve, one thread), and for the conjugate gradient its
/// preconditioner (`elcon_influence::LatticePreconditioner`: the inverse of
/// the kernel's symbol by a periodic FFT on the half-size grid), applied
/// in the same workspace (products and applications take turns: one
/// buffer of the box's spectra serves both).
pub(crate) struct LatticeProducts<'a> {
    operator: &'a LatticeKernel,
    workspace: RefCell<LatticeWorkspace>,
    /// Boxed: its plans would make every `LatticeProducts` large.
    preconditioner: Option<Box<LatticePreconditioner>>,
}

impl<'a> LatticeProducts<'a> {
    /// The products of `operator`, with a new workspace.
    pub fn new(operator: &'a LatticeKernel) -> Result<Self, elcon_influence::InfluenceError> {
        Ok(Self {
            operator,
            workspace: RefCell::new(operator.workspace()?),
            preconditioner: None,
        })
    }

    /// The same with the operator's preconditioner (none where S has no
    /// half-space kernel: a foundation's S is a multiple of the identity).
    pub fn with_preconditioner(self) -> Result<Self, elcon_influence::InfluenceError> {
        let preconditioner = self.operator.preconditioner()?.map(Box::new);
        Ok(Self {
            preconditioner,
            ..self
        })
    }
}

impl Operator for LatticeProducts<'_> {
    fn size(&self) -> usize {
        self.operator.len()
    }

    fn apply(&self, x: &[f64], y: &mut [f64]) {
        self.operator
            .apply_with(x, y, &mut self.workspace.borrow_mut());
    }

    /// Every half-space kernel and the Winkler diagonal are positive, so
    /// `|S| x = S x` for `x >= 0`.
    fn apply_abs(&self, x: &[f64], y: &mut [f64]) {
        self.apply(x, y);
    }

    fn entries_nonnegative(&self) -> bool {
        true
    }

    fn has_preconditioner(&self) -> bool {
        self.preconditioner.is_some()
    }

    fn precondition(&self, r: &[f64], z: &mut [f64]) {
        match &self.preconditioner {
            Some(p) => self
                .operator
                .precondition_with(r, z, p, &mut self.workspace.borrow_mut()),
            None => z.copy_from_slice(r),
        }
    }
}

/// The products `y = S F` of a problem's influence matrix, for a caller that
/// applies them many times (an iterative solve of its own): made once by
/// `ContactProblem::products`, with the workspace a matrix-free S needs.
pub struct Products<'a>(ProductsOf<'a>);

enum ProductsOf<'a> {
    Dense(faer::MatRef<'a, f64>),
    Lattice(LatticeProducts<'a>),
}

impl<'a> Products<'a> {
    /// The products of `influence`.
    pub(crate) fn of(influence: &'a Influence) -> Result<Self, elcon_influence::InfluenceError> {
        Ok(Self(match influence {
            Influence::Dense(s) => ProductsOf::Dense(Mat::as_ref(s)),
            Influence::Lattice(kernel) => ProductsOf::Lattice(LatticeProducts::new(kernel)?),
        }))
    }

    fn operator(&self) -> &dyn Operator {
        match &self.0 {
            ProductsOf::Dense(s) => s,
            ProductsOf::Lattice(p) => p,
        }
    }
}

impl Operator for Products<'_> {
    fn size(&self) -> usize {
        self.operator().size()
    }

    fn apply(&self, x: &[f64], y: &mut [f64]) {
        self.operator().apply(x, y);
    }

    fn apply_abs(&self, x: &[f64], y: &mut [f64]) {
        self.operator().apply_abs(x, y);
    }
}
