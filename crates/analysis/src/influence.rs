//! How a contact problem holds its influence matrix `S = A(1) + A(2)`:
//! dense (every entry, 8 N^2 bytes: what the exact pivoting methods need),
//! or matrix-free on a lattice (`elcon_influence::LatticeKernel`: the
//! product `S F` by an FFT convolution, O(N) memory: what the conjugate
//! gradient needs on grids too large to store); and what each offers,
//! whatever the storage: the products `y = S x`, the engine's bordered LCP
//! `w = S z - B λ + q`, `B^T z = b` on it, and the entries where held.
//! The one place in the workspace that branches on how S is held.

use std::sync::Arc;

use elcon_influence::{LatticeKernel, LatticePreconditioner};
use elcon_lcp::{
    BorderedLcpRef, LcpSolution, LinearSolution, LinearSystem, Method, Operator, OperatorLcp,
    Options, PodStack, Preconditioner, StackReq,
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
                let products = LatticeProducts(kernel);
                // None where S has no half-space kernel: a foundation's S
                // is a multiple of the identity.
                let inverse = match options.preconditioner {
                    true => kernel.preconditioner()?,
                    false => None,
                };
                let inverse = inverse.map(|preconditioner| LatticeInverse {
                    kernel,
                    preconditioner,
                });
                let lcp = OperatorLcp::new(&products, q)?.with_border(border, resultant)?;
                match &inverse {
                    Some(inverse) => lcp.with_preconditioner(inverse)?,
                    None => lcp,
                }
                .solve(method, options)?
            }
        })
    }
}

impl Influence {
    /// S restricted to the unknowns `contact` (J): dense, the block `S_JJ`
    /// copied out; matrix-free, the products restricted to J.
    pub fn restricted<'a>(&'a self, contact: &'a [usize]) -> RestrictedInfluence<'a> {
        match self {
            Influence::Dense(s) => {
                let nj = contact.len();
                RestrictedInfluence::Dense(Mat::from_fn(nj, nj, |a, b| s[(contact[a], contact[b])]))
            }
            Influence::Lattice(kernel) => RestrictedInfluence::Lattice(Restricted {
                products: LatticeProducts(kernel),
                contact,
            }),
        }
    }
}

/// `S_JJ`, S restricted to a set of unknowns J ([`Influence::restricted`]).
pub(crate) enum RestrictedInfluence<'a> {
    /// The block `S_JJ`.
    Dense(Mat<f64>),
    /// The products restricted to J.
    Lattice(Restricted<'a>),
}

impl RestrictedInfluence<'_> {
    /// `S_JJ X = R`, `rhs` R of `|J|` rows, by the engine's certified
    /// linear solve (`elcon_lcp::LinearSystem`): dense, a Cholesky factor
    /// of the block (LU, logged as a fallback, where it is not numerically
    /// positive definite); matrix-free, the conjugate gradient on the
    /// restricted products.
    pub fn solve(
        &self,
        rhs: MatRef<'_, f64>,
        options: &Options,
    ) -> Result<LinearSolution, AnalysisError> {
        Ok(match self {
            RestrictedInfluence::Dense(block) => {
                LinearSystem::dense(block.as_ref(), rhs)?.solve(options)?
            }
            RestrictedInfluence::Lattice(restricted) => {
                LinearSystem::operator(restricted, rhs)?.solve(options)?
            }
        })
    }
}

/// An operator's products restricted to the unknowns `contact`:
/// `(S_JJ x) = (S [x on J, 0 elsewhere])_J`, through two vectors of n in
/// the caller's scratch.
pub(crate) struct Restricted<'a> {
    products: LatticeProducts<'a>,
    contact: &'a [usize],
}

impl Restricted<'_> {
    fn restricted(&self, x: &[f64], y: &mut [f64], stack: &mut PodStack) {
        let n = self.products.size();
        // `full` is 0 off J; `product` is written whole.
        let (full, stack) = stack.make_with(n, |_| 0.0);
        let (product, stack) = stack.make_raw::<f64>(n);
        for (&k, &v) in self.contact.iter().zip(x) {
            full[k] = v;
        }
        self.products.apply(full, product, stack);
        for (y, &k) in y.iter_mut().zip(self.contact) {
            *y = product[k];
        }
    }
}

impl Operator for Restricted<'_> {
    fn size(&self) -> usize {
        self.contact.len()
    }

    fn apply_scratch(&self) -> StackReq {
        let vector = StackReq::new::<f64>(self.products.size());
        StackReq::all_of(&[vector, vector, self.products.apply_scratch()])
    }

    fn apply(&self, x: &[f64], y: &mut [f64], stack: &mut PodStack) {
        self.restricted(x, y, stack);
    }

    /// S's entries are non-negative ([`LatticeProducts::apply_abs`]), and
    /// so are `S_JJ`'s.
    fn apply_abs(&self, x: &[f64], y: &mut [f64], stack: &mut PodStack) {
        self.restricted(x, y, stack);
    }
}

/// The lattice operator's products as the engine applies them, in the
/// engine's scratch (`elcon_influence::LatticeKernel::apply_in`: the
/// buffers of one product, lent by the caller for every product of a
/// solve).
struct LatticeProducts<'a>(&'a LatticeKernel);

impl Operator for LatticeProducts<'_> {
    fn size(&self) -> usize {
        self.0.len()
    }

    fn apply_scratch(&self) -> StackReq {
        self.0.apply_scratch()
    }

    fn apply(&self, x: &[f64], y: &mut [f64], stack: &mut PodStack) {
        self.0.apply_in(x, y, stack);
    }

    /// Every half-space kernel and the Winkler diagonal are positive, so
    /// `|S| x = S x` for `x >= 0`.
    fn apply_abs(&self, x: &[f64], y: &mut [f64], stack: &mut PodStack) {
        self.apply(x, y, stack);
    }

    fn entries_nonnegative(&self) -> bool {
        true
    }

    /// The kernel table shifted to each column's point
    /// (`elcon_influence::LatticeKernel::add_columns`).
    fn columns_per_product(&self) -> usize {
        self.0.columns_per_product()
    }

    fn add_columns(&self, columns: &[(usize, f64)], y: &mut [f64]) -> bool {
        self.0.add_columns(columns, y);
        true
    }
}

/// The lattice operator's preconditioner for the conjugate gradient
/// (`elcon_influence::LatticePreconditioner`: the inverse of the kernel's
/// symbol by a periodic FFT on the half-size grid), applied in the same
/// scratch as the products (they take turns: one buffer of the box's
/// spectra serves both).
struct LatticeInverse<'a> {
    kernel: &'a LatticeKernel,
    preconditioner: LatticePreconditioner,
}

impl Preconditioner for LatticeInverse<'_> {
    fn size(&self) -> usize {
        self.kernel.len()
    }

    fn precondition_scratch(&self) -> StackReq {
        self.kernel.apply_scratch()
    }

    fn precondition(&self, r: &[f64], z: &mut [f64], stack: &mut PodStack) {
        self.kernel
            .precondition_in(r, z, &self.preconditioner, stack);
    }
}

/// The products `y = S F` of a problem's influence matrix, for a caller that
/// applies them many times (an iterative solve of its own): made once by
/// `ContactProblem::products`; the caller lends each product the scratch
/// it declares ([`Operator::apply_scratch`]: the buffers of a matrix-free
/// S's product, none for a dense S).
pub struct Products<'a>(ProductsOf<'a>);

enum ProductsOf<'a> {
    Dense(faer::MatRef<'a, f64>),
    Lattice(LatticeProducts<'a>),
}

impl<'a> Products<'a> {
    /// The products of `influence`.
    pub(crate) fn of(influence: &'a Influence) -> Self {
        Self(match influence {
            Influence::Dense(s) => ProductsOf::Dense(Mat::as_ref(s)),
            Influence::Lattice(kernel) => ProductsOf::Lattice(LatticeProducts(kernel)),
        })
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

    fn apply_scratch(&self) -> StackReq {
        self.operator().apply_scratch()
    }

    fn apply(&self, x: &[f64], y: &mut [f64], stack: &mut PodStack) {
        self.operator().apply(x, y, stack);
    }

    fn apply_abs(&self, x: &[f64], y: &mut [f64], stack: &mut PodStack) {
        self.operator().apply_abs(x, y, stack);
    }

    fn entries_nonnegative(&self) -> bool {
        self.operator().entries_nonnegative()
    }

    fn columns_per_product(&self) -> usize {
        self.operator().columns_per_product()
    }

    fn add_columns(&self, columns: &[(usize, f64)], y: &mut [f64]) -> bool {
        self.operator().add_columns(columns, y)
    }
}
