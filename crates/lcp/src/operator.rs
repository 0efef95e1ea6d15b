//! Matrix-free problems: `M` known only by its products.
//!
//! A bordered LCP whose matrix is an [`Operator`] ([`OperatorLcp`]):
//!
//! ```text
//!     w = M z - B λ + q,   B^T z = b,   z >= 0, w >= 0, z^T w = 0,   λ free
//! ```
//!
//! with `M` symmetric positive definite, given by `y = M x` (an FFT
//! convolution of an influence kernel on a lattice, a sparse matrix, or a
//! dense one: `MatRef` is an operator too) and `B` a small dense `n x k`
//! border. The pivoting methods need `M`'s entries and refuse such a
//! problem; the conjugate-gradient method ([`Method::ConjugateGradient`](crate::Method::ConjugateGradient))
//! needs only products, and its certificate is computed from products of
//! the original operator and the original data.

use faer::{ColRef, MatRef};

use crate::LcpError;
use crate::problem::{Bordered, check_finite_col};

/// A symmetric linear map `M` (n x n) applied without storing it.
pub trait Operator {
    /// The size `n`.
    fn size(&self) -> usize;

    /// `y = M x` (`x` and `y` of length `n`).
    fn apply(&self, x: &[f64], y: &mut [f64]);

    /// `y = |M| x` for `x >= 0`, `|M|` entry-wise absolute values: the
    /// magnitude of the terms that sum to `M x`, the scale a residual is
    /// judged against. An operator with non-negative entries (every
    /// half-space influence kernel) returns `M x`.
    fn apply_abs(&self, x: &[f64], y: &mut [f64]);

    /// Whether every entry of `M` is non-negative (every half-space
    /// influence kernel, a Winkler diagonal), so that `|M| x = M x` for
    /// `x >= 0`: the certificate then reads the magnitude of `M z`'s terms
    /// from `M z` itself, one product instead of two. Default: no.
    fn entries_nonnegative(&self) -> bool {
        false
    }

    /// Whether [`precondition`](Self::precondition) applies an
    /// approximation of `M^{-1}` (default: no preconditioner). The
    /// conjugate gradient then runs preconditioned (module
    /// `methods::conjugate_gradient`; [`Options::preconditioner`](crate::Options::preconditioner)
    /// turns it off).
    fn has_preconditioner(&self) -> bool {
        false
    }

    /// `z = P r`, `P` a symmetric positive definite approximation of
    /// `M^{-1}` that is cheaper than a product (the conjugate gradient
    /// restricts it to its contact set: `r` is 0 off it, and `z` is read
    /// on it only). The default, for an operator without one, is the
    /// identity. The values must not depend on the number of threads.
    fn precondition(&self, r: &[f64], z: &mut [f64]) {
        z.copy_from_slice(r);
    }
}

impl Operator for MatRef<'_, f64> {
    fn size(&self) -> usize {
        self.nrows()
    }

    fn apply(&self, x: &[f64], y: &mut [f64]) {
        let x = ColRef::from_slice(x);
        let product = crate::linalg::matvec(*self, x);
        for (yi, pi) in y.iter_mut().zip(product.iter()) {
            *yi = *pi;
        }
    }

    fn apply_abs(&self, x: &[f64], y: &mut [f64]) {
        let x = ColRef::from_slice(x);
        let product = crate::linalg::abs_matvec(*self, x);
        for (yi, pi) in y.iter_mut().zip(product.iter()) {
            *yi = *pi;
        }
    }
}

/// A bordered LCP whose `M` is an [`Operator`] (see the module
/// documentation; a [`Bordered`] problem): build it with [`OperatorLcp::new`]
/// and, for `k > 0` rigid-body rows, [`Bordered::with_border`]; solve it with
/// [`Method::ConjugateGradient`](crate::Method::ConjugateGradient).
///
/// ```
/// use elcon_lcp::{Method, OperatorLcp, Options};
/// use faer::{col, mat};
///
/// // The crate documentation's two points pressed by a load 3, M given
/// // only by its products (here a dense matrix).
/// let m = mat![[2.0, 1.0], [1.0, 2.0]];
/// let m = m.as_ref();
/// let q = col![0.0, 1.0];
/// let border = mat![[1.0], [1.0]];
/// let load = col![3.0];
/// let lcp = OperatorLcp::new(&m, q.as_ref())
///     .unwrap()
///     .with_border(border.as_ref(), load.as_ref())
///     .unwrap();
/// let sol = lcp.solve(Method::ConjugateGradient, &Options::default()).unwrap();
/// assert!(sol.certificate.holds());
/// assert!((sol.z[0] - 2.0).abs() < 1e-10 && (sol.z[1] - 1.0).abs() < 1e-10);
/// assert!((sol.u[0] - 5.0).abs() < 1e-10);
/// ```
pub type OperatorLcp<'a> = Bordered<'a, &'a dyn Operator>;

impl std::fmt::Debug for OperatorLcp<'_> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("OperatorLcp")
            .field("size", &self.size())
            .field("border_size", &self.border_size())
            .finish()
    }
}

impl<'a> OperatorLcp<'a> {
    /// The LCP `w = M z + q` with no border yet; `operator` of the size of
    /// `q`, `q` finite.
    pub fn new(operator: &'a dyn Operator, q: ColRef<'a, f64>) -> Result<Self, LcpError> {
        if operator.size() != q.nrows() {
            return Err(LcpError::DimensionMismatch {
                field: "q",
                expected: operator.size(),
                found: q.nrows(),
                unit: "rows",
            });
        }
        if q.nrows() == 0 {
            return Err(LcpError::Empty { field: "q" });
        }
        check_finite_col("q", q)?;
        Ok(Self::unchecked(operator, q))
    }
}
