//! A symmetric positive definite linear system, as data:
//!
//! ```text
//!     M X = R,   M (n x n) symmetric positive definite,   R (n x m): m right-hand sides
//! ```
//!
//! with `M` dense or an [`Operator`] known only by its products (the
//! sensitivities of a contact solution, `S_JJ X = R` on its contact set
//! `J`). The strategy solves it (a Cholesky factorization of a dense `M`,
//! an LU where `M` is not numerically symmetric positive definite, the
//! conjugate gradient for an operator) and certifies every column from
//! products of the original data:
//!
//! ```text
//!     residual = max_c ‖R_c - M X_c‖∞ / ‖|M| |X_c| + |R_c|‖∞
//! ```
//!
//! which must be at most the certificate's tolerance
//! ([`Tolerances::certificate`](crate::Tolerances::certificate)). This
//! module only holds and validates the data.

use faer::MatRef;

use crate::LcpError;
use crate::operator::Operator;
use crate::problem::{check_dims, check_finite_mat};

/// The matrix of a linear system: dense, or known by its products.
#[derive(Clone, Copy)]
pub(crate) enum Matrix<'a> {
    /// A dense `M`: factorizations apply.
    Dense(MatRef<'a, f64>),
    /// `M` by its products: the conjugate gradient applies.
    Operator(&'a dyn Operator),
}

impl Matrix<'_> {
    /// `M` as the operator of its products (a dense `M` too).
    pub(crate) fn operator(&self) -> &dyn Operator {
        match self {
            Matrix::Dense(m) => m,
            Matrix::Operator(op) => *op,
        }
    }
}

/// A symmetric positive definite linear system `M X = R` (see the module
/// documentation): build it with [`LinearSystem::dense`] or
/// [`LinearSystem::operator`], solve it with
/// [`solve`](LinearSystem::solve). Nothing large is copied.
///
/// ```
/// use elcon_lcp::{LinearMethod, LinearSystem, Options};
/// use faer::mat;
///
/// // M = [[4, 1], [1, 3]]: M^{-1} = [[3, -1], [-1, 4]] / 11.
/// let m = mat![[4.0, 1.0], [1.0, 3.0]];
/// let r = mat![[1.0, 0.0], [2.0, 1.0]];
/// let sol = LinearSystem::dense(m.as_ref(), r.as_ref())
///     .unwrap()
///     .solve(&Options::default())
///     .unwrap();
/// assert!(sol.residual <= 1e-12);
/// assert!((sol.x[(0, 0)] - 1.0 / 11.0).abs() < 1e-15 && (sol.x[(1, 1)] - 4.0 / 11.0).abs() < 1e-15);
/// assert_eq!(sol.statistics.returned().unwrap().method, LinearMethod::Cholesky);
///
/// // The same system by its products: the conjugate gradient.
/// let products = m.as_ref();
/// let sol = LinearSystem::operator(&products, r.as_ref())
///     .unwrap()
///     .solve(&Options::default())
///     .unwrap();
/// assert!(sol.residual <= 1e-12);
/// assert_eq!(sol.statistics.returned().unwrap().method, LinearMethod::ConjugateGradient);
/// ```
#[derive(Clone, Copy)]
pub struct LinearSystem<'a> {
    pub(crate) matrix: Matrix<'a>,
    pub(crate) rhs: MatRef<'a, f64>,
}

impl std::fmt::Debug for LinearSystem<'_> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let matrix = match self.matrix {
            Matrix::Dense(_) => "dense",
            Matrix::Operator(_) => "operator",
        };
        f.debug_struct("LinearSystem")
            .field("matrix", &matrix)
            .field("size", &self.size())
            .field("columns", &self.columns())
            .finish()
    }
}

impl<'a> LinearSystem<'a> {
    /// The system `M X = R` with a dense `m` (square, of the rows of `rhs`)
    /// and right-hand sides `rhs` (at least one column), all finite.
    pub fn dense(m: MatRef<'a, f64>, rhs: MatRef<'a, f64>) -> Result<Self, LcpError> {
        let n = m.nrows();
        check_dims("m", n, m.ncols(), n, n)?;
        check_dims("rhs", rhs.nrows(), rhs.ncols(), n, rhs.ncols())?;
        check_rhs(rhs)?;
        check_finite_mat("m", m)?;
        Ok(Self {
            matrix: Matrix::Dense(m),
            rhs,
        })
    }

    /// The system `M X = R` with `M` the operator of its products (of the
    /// size of the rows of `rhs`) and right-hand sides `rhs` (at least one
    /// column), finite.
    pub fn operator(operator: &'a dyn Operator, rhs: MatRef<'a, f64>) -> Result<Self, LcpError> {
        check_dims(
            "rhs",
            rhs.nrows(),
            rhs.ncols(),
            operator.size(),
            rhs.ncols(),
        )?;
        check_rhs(rhs)?;
        Ok(Self {
            matrix: Matrix::Operator(operator),
            rhs,
        })
    }

    /// Number of unknowns `n` of each right-hand side.
    pub fn size(&self) -> usize {
        self.rhs.nrows()
    }

    /// Number of right-hand sides (columns of `R`).
    pub fn columns(&self) -> usize {
        self.rhs.ncols()
    }

    /// The right-hand sides `R` (n x m).
    pub fn rhs(&self) -> MatRef<'a, f64> {
        self.rhs
    }
}

/// Checks the right-hand sides: at least one row and one column, finite.
fn check_rhs(rhs: MatRef<'_, f64>) -> Result<(), LcpError> {
    if rhs.nrows() == 0 || rhs.ncols() == 0 {
        return Err(LcpError::Empty { field: "rhs" });
    }
    check_finite_mat("rhs", rhs)
}
