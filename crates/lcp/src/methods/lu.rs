//! A linear system's LU factorization: for a dense `M` that is not
//! numerically symmetric positive definite (the Cholesky factorization's
//! fallback),
//!
//! ```text
//!     M = P^T L U   (partial pivoting),   X = U^{-1} L^{-1} P R
//! ```
//!
//! with the options' parallelism. It does not judge `M`'s conditioning:
//! the certificate does, from the residual of the original data (an
//! exactly singular `M` gives a non-finite `X`, which never certifies).

use faer::{MatRef, Par};

use crate::linalg::Lu;
use crate::methods::{LinearAnswer, LinearAttempted, copied};
use crate::statistics::Work;

/// Solves `m x = rhs` by an LU factorization of `m` (see the module
/// documentation) with the parallelism `par`.
pub(crate) fn attempt(m: MatRef<'_, f64>, rhs: MatRef<'_, f64>, par: Par) -> LinearAttempted {
    let mut work = Work::default();
    let lu = Lu::new(copied(m, "the LU factor", work)?, par);
    work.factorizations = 1;
    let mut x = copied(rhs, "the solution", work)?;
    lu.solve_in_place(x.as_mut());
    Ok(LinearAnswer { x, work })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::options::Options;
    use faer::mat;

    #[test]
    fn an_indefinite_matrix_is_solved() {
        let m = mat![[1.0, 2.0], [2.0, 1.0]];
        let par = Options::default().par(2, 2);
        let answer = attempt(m.as_ref(), mat![[3.0], [3.0]].as_ref(), par).unwrap();
        assert!((answer.x[(0, 0)] - 1.0).abs() < 1e-15 && (answer.x[(1, 0)] - 1.0).abs() < 1e-15);
        assert_eq!(answer.work.factorizations, 1);
    }
}
