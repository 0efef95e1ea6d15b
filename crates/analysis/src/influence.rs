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

use elcon_influence::{LatticeKernel, LatticeWorkspace};
use elcon_lcp::{BorderedLcpRef, LcpSolution, Method, Operator, OperatorLcp, Options};
use faer::{ColRef, Mat, MatRef};

use crate::AnalysisError;
use crate::contact::Storage;

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
                let products = LatticeProducts::new(kernel)?;
                OperatorLcp::new(&products, q)?
                    .with_border(border, resultant)?
                    .solve(method, options)?
            }
        })
    }
}

/// The relative residual of a matrix-free restricted solve: far below
/// its use (a design step's linear prediction), above rounding.
const RESTRICTED_RESIDUAL: f64 = 1e-12;

impl Influence {
    /// `S_JJ X = R` on the unknowns `contact` (J), `rhs` R of `|J|` rows:
    /// dense by a Cholesky factor of the block `S_JJ` (LU where it is not
    /// numerically positive definite), matrix-free by conjugate gradients
    /// on the products restricted to J, each column to
    /// [`RESTRICTED_RESIDUAL`] of its right-hand side.
    pub fn restricted_solve(
        &self,
        contact: &[usize],
        rhs: MatRef<'_, f64>,
    ) -> Result<Mat<f64>, AnalysisError> {
        match self {
            Influence::Dense(s) => {
                let nj = contact.len();
                let block = Mat::from_fn(nj, nj, |a, b| s[(contact[a], contact[b])]);
                Ok(match block.llt(faer::Side::Lower) {
                    Ok(llt) => faer::linalg::solvers::Solve::solve(&llt, rhs),
                    Err(_) => faer::linalg::solvers::Solve::solve(&block.partial_piv_lu(), rhs),
                })
            }
            Influence::Lattice(kernel) => {
                let products = LatticeProducts::new(kernel)?;
                Ok(restricted_cg(&products, contact, rhs))
            }
        }
    }
}

/// `S_JJ^{-1} rhs` by conjugate gradients on `products` restricted to the
/// contact set J (S_JJ is symmetric positive definite), column by column.
fn restricted_cg(products: &dyn Operator, contact: &[usize], rhs: MatRef<'_, f64>) -> Mat<f64> {
    let (n, nj) = (products.size(), contact.len());
    // One workspace and two buffers of n for every product of every column.
    let (mut full, mut y) = (vec![0.0; n], vec![0.0; n]);
    let mut product = |p: &[f64], q: &mut [f64]| {
        for (a, &k) in contact.iter().enumerate() {
            full[k] = p[a];
        }
        products.apply(&full, &mut y);
        for (q, &k) in q.iter_mut().zip(contact) {
            *q = y[k];
        }
    };
    let dot = |u: &[f64], v: &[f64]| u.iter().zip(v).map(|(a, b)| a * b).sum::<f64>();
    let mut out = Mat::<f64>::zeros(nj, rhs.ncols());
    for c in 0..rhs.ncols() {
        let b: Vec<f64> = (0..nj).map(|a| rhs[(a, c)]).collect();
        let target = (RESTRICTED_RESIDUAL * dot(&b, &b).sqrt()).powi(2);
        let (mut x, mut r) = (vec![0.0; nj], b.clone());
        let mut p = r.clone();
        let mut rr = dot(&r, &r);
        let mut q = vec![0.0; nj];
        for _ in 0..(10 * nj + 100) {
            if rr <= target {
                break;
            }
            product(&p, &mut q);
            let alpha = rr / dot(&p, &q);
            x.iter_mut().zip(&p).for_each(|(x, p)| *x += alpha * p);
            r.iter_mut().zip(&q).for_each(|(r, q)| *r -= alpha * q);
            let next = dot(&r, &r);
            let beta = next / rr;
            p.iter_mut().zip(&r).for_each(|(p, r)| *p = r + beta * *p);
            rr = next;
        }
        for (a, v) in x.into_iter().enumerate() {
            out[(a, c)] = v;
        }
    }
    out
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
