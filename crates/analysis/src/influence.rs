//! How a contact problem holds its influence matrix `S = A(1) + A(2)`:
//! dense (every entry, 8 N^2 bytes: what the exact pivoting methods need),
//! or matrix-free on a lattice (`elcon_influence::LatticeKernel`: the
//! product `S F` by an FFT convolution, O(N) memory: what the conjugate
//! gradient needs on grids too large to store).

use std::cell::RefCell;
use std::sync::Arc;

use elcon_influence::{LatticeKernel, LatticeWorkspace};
use elcon_lcp::Operator;
use faer::Mat;

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
}

/// The lattice operator with a workspace of its own, as the engine applies
/// it (one solve, one thread).
pub(crate) struct LatticeProducts<'a> {
    operator: &'a LatticeKernel,
    workspace: RefCell<LatticeWorkspace>,
}

impl<'a> LatticeProducts<'a> {
    /// The products of `operator`, with a new workspace.
    pub fn new(operator: &'a LatticeKernel) -> Result<Self, elcon_influence::InfluenceError> {
        Ok(Self {
            operator,
            workspace: RefCell::new(operator.workspace()?),
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
