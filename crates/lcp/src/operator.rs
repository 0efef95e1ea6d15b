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

use faer::dyn_stack::{PodBuffer, PodStack, StackReq};
use faer::{ColRef, MatRef};

use crate::LcpError;
use crate::linalg::AllocationFailed;
use crate::problem::{Bordered, check_finite_col, check_size};

/// A symmetric linear map `M` (n x n) applied without storing it, after
/// faer's `LinOp`: the operator declares the scratch memory an
/// application needs ([`apply_scratch`](Self::apply_scratch)), and the
/// caller lends it to every application in a [`PodStack`] (one
/// [`PodBuffer`] made once, for as many products as a solve takes). The
/// operator itself keeps no mutable state: `&self` applies it.
///
/// Where faer lends a `MemStack` (uninitialized bytes, which safe code can
/// only use by writing them first), the engine lends a `PodStack` of
/// initialized bytes: an operator carves its buffers from it
/// (`PodStack::make_raw`) without clearing them on every product, in safe
/// code. Their contents on entry are whatever the last application left.
pub trait Operator {
    /// The size `n`.
    fn size(&self) -> usize;

    /// The scratch one application of [`apply`](Self::apply) or
    /// [`apply_abs`](Self::apply_abs) needs (`StackReq::EMPTY` for none).
    fn apply_scratch(&self) -> StackReq;

    /// `y = M x` (`x` and `y` of length `n`), in `stack`'s memory (at
    /// least [`apply_scratch`](Self::apply_scratch); its contents between
    /// calls mean nothing).
    fn apply(&self, x: &[f64], y: &mut [f64], stack: &mut PodStack);

    /// `y = |M| x` for `x >= 0`, `|M|` entry-wise absolute values: the
    /// magnitude of the terms that sum to `M x`, the scale a residual is
    /// judged against. An operator with non-negative entries (every
    /// half-space influence kernel) returns `M x`.
    fn apply_abs(&self, x: &[f64], y: &mut [f64], stack: &mut PodStack);

    /// Whether every entry of `M` is non-negative (every half-space
    /// influence kernel, a Winkler diagonal), so that `|M| x = M x` for
    /// `x >= 0`: the certificate then reads the magnitude of `M z`'s terms
    /// from `M z` itself, one product instead of two. Default: no.
    fn entries_nonnegative(&self) -> bool {
        false
    }

    /// How many columns [`add_columns`](Self::add_columns) adds in about
    /// the time of one product: 0 (the default) where the operator has no
    /// columns cheaper than a product. The conjugate gradient keeps `M z`
    /// by columns after a step that changed the contact set at up to
    /// about this many points (fewer than a product's worth), else by a
    /// product.
    fn columns_per_product(&self) -> usize {
        0
    }

    /// `y += M d` for `d = Σ_t v_t e_{p_t}`, the `columns` `(p_t, v_t)`
    /// (a `p_t` may repeat), each column of `M` added whole; returns
    /// whether it did (the default adds nothing and returns `false`: only
    /// called where [`columns_per_product`](Self::columns_per_product) is
    /// positive). Each entry of `y` must add its terms in the order of
    /// `columns`, so that the values do not depend on the threads.
    fn add_columns(&self, columns: &[(usize, f64)], y: &mut [f64]) -> bool {
        let _ = (columns, y);
        false
    }
}

/// A preconditioner of an [`Operator`], after faer's `Precond`: `z = P r`,
/// `P` a symmetric positive definite approximation of `M^{-1}` that is
/// cheaper than a product. The conjugate gradient takes one with its
/// problem ([`OperatorLcp::with_preconditioner`]; module
/// `methods::conjugate_gradient`, after Vollebregt 2014) and restricts it
/// to its contact set: `r` is 0 off it, and `z` is read on it only.
pub trait Preconditioner {
    /// The size `n` (the operator's).
    fn size(&self) -> usize;

    /// The scratch one application of [`precondition`](Self::precondition)
    /// needs (`StackReq::EMPTY` for none). The conjugate gradient lends the
    /// same memory to the operator's products and to the preconditioner in
    /// turn: it holds the larger of the two requests.
    fn precondition_scratch(&self) -> StackReq;

    /// `z = P r` (`r` and `z` of length `n`), in `stack`'s memory. The
    /// values must not depend on the number of threads.
    fn precondition(&self, r: &[f64], z: &mut [f64], stack: &mut PodStack);
}

impl Operator for MatRef<'_, f64> {
    fn size(&self) -> usize {
        self.nrows()
    }

    fn apply_scratch(&self) -> StackReq {
        StackReq::EMPTY
    }

    fn apply(&self, x: &[f64], y: &mut [f64], _: &mut PodStack) {
        let x = ColRef::from_slice(x);
        let product = crate::linalg::matvec(*self, x);
        for (yi, pi) in y.iter_mut().zip(product.iter()) {
            *yi = *pi;
        }
    }

    fn apply_abs(&self, x: &[f64], y: &mut [f64], _: &mut PodStack) {
        let x = ColRef::from_slice(x);
        let product = crate::linalg::abs_matvec(*self, x);
        for (yi, pi) in y.iter_mut().zip(product.iter()) {
            *yi = *pi;
        }
    }

    /// A column costs `n` of a product's `n^2` multiply-adds.
    fn columns_per_product(&self) -> usize {
        self.nrows()
    }

    fn add_columns(&self, columns: &[(usize, f64)], y: &mut [f64]) -> bool {
        for &(p, v) in columns {
            for (yi, &m) in y.iter_mut().zip(self.col(p).iter()) {
                *yi += m * v;
            }
        }
        true
    }
}

/// The scratch memory of `request`, allocated fallibly: the error names
/// `what` it is for.
pub(crate) fn scratch(
    request: StackReq,
    what: &'static str,
) -> Result<PodBuffer, AllocationFailed> {
    PodBuffer::try_new(request).map_err(|_| AllocationFailed {
        what,
        bytes: request.unaligned_bytes_required(),
    })
}

/// `M` of an [`OperatorLcp`]: the operator of its products, and the
/// preconditioner the conjugate gradient may apply
/// ([`Options::preconditioner`](crate::Options::preconditioner)).
#[derive(Clone, Copy)]
pub struct MatrixFree<'a> {
    /// `M` by its products.
    pub operator: &'a dyn Operator,
    /// An approximation of `M^{-1}`, if there is one.
    pub preconditioner: Option<&'a dyn Preconditioner>,
}

impl MatrixFree<'_> {
    /// The scratch of the operator's products and, where `preconditioned`,
    /// of the preconditioner's applications, which take turns in it.
    pub(crate) fn scratch(&self, preconditioned: bool) -> StackReq {
        let preconditioner = match self.preconditioner {
            Some(p) if preconditioned => p.precondition_scratch(),
            _ => StackReq::EMPTY,
        };
        StackReq::any_of(&[self.operator.apply_scratch(), preconditioner])
    }
}

/// A bordered LCP whose `M` is an [`Operator`] (see the module
/// documentation; a [`Bordered`] problem): build it with [`OperatorLcp::new`],
/// for `k > 0` rigid-body rows [`Bordered::with_border`], and where `M`
/// has one [`OperatorLcp::with_preconditioner`]; solve it with
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
pub type OperatorLcp<'a> = Bordered<'a, MatrixFree<'a>>;

impl std::fmt::Debug for OperatorLcp<'_> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("OperatorLcp")
            .field("size", &self.size())
            .field("border_size", &self.border_size())
            .field("preconditioned", &self.m.preconditioner.is_some())
            .finish()
    }
}

impl<'a> OperatorLcp<'a> {
    /// The LCP `w = M z + q` with no border yet; `operator` of the size of
    /// `q`, `q` finite.
    pub fn new(operator: &'a dyn Operator, q: ColRef<'a, f64>) -> Result<Self, LcpError> {
        check_size("q", q.nrows(), operator.size(), "rows")?;
        if q.nrows() == 0 {
            return Err(LcpError::Empty { field: "q" });
        }
        check_finite_col("q", q)?;
        let m = MatrixFree {
            operator,
            preconditioner: None,
        };
        Ok(Self::unchecked(m, q))
    }

    /// The same problem with `preconditioner`, an approximation of
    /// `M^{-1}` of `M`'s size, which the conjugate gradient applies where
    /// [`Options::preconditioner`](crate::Options::preconditioner) is set.
    pub fn with_preconditioner(
        self,
        preconditioner: &'a dyn Preconditioner,
    ) -> Result<Self, LcpError> {
        check_size("preconditioner", preconditioner.size(), self.size(), "rows")?;
        let m = MatrixFree {
            preconditioner: Some(preconditioner),
            ..self.m
        };
        Ok(Bordered { m, ..self })
    }
}
