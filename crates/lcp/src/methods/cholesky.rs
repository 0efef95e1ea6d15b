//! A linear system's Cholesky factorization: for a dense symmetric
//! positive definite `M`,
//!
//! ```text
//!     M = L L^T,   X = L^{-T} (L^{-1} R)
//! ```
//!
//! by faer's in-place Cholesky (LLT) and triangular solves, with the
//! options' parallelism. A breakdown (`NotPositiveDefinite`) where `M` is
//! not symmetric (to the symmetry test's tolerance) or a pivot is not
//! positive: `M` is then not numerically symmetric positive definite, and
//! the strategy's route goes on to the LU factorization.

use faer::dyn_stack::{MemBuffer, MemStack, StackReq};
use faer::linalg::cholesky::llt::solve::solve_in_place_with_conj;
use faer::{Conj, MatRef, Par};

use crate::linalg::{asymmetry, cholesky_lower};
use crate::methods::{Failure, LinearAnswer, LinearAttempted, copied};
use crate::statistics::{Breakdown, Work};

/// Solves `m x = rhs` by a Cholesky factorization of `m` (see the module
/// documentation) with the parallelism `par`.
pub(crate) fn attempt(m: MatRef<'_, f64>, rhs: MatRef<'_, f64>, par: Par) -> LinearAttempted {
    let mut work = Work::default();
    if asymmetry(m).is_some() {
        return Err(Failure::new(Breakdown::NotPositiveDefinite, work));
    }
    let mut l = copied(m, "the Cholesky factor", work)?;
    work.factorizations = 1;
    if cholesky_lower(l.as_mut(), par).is_err() {
        return Err(Failure::new(Breakdown::NotPositiveDefinite, work));
    }
    let mut x = copied(rhs, "the solution", work)?;
    let mut mem = MemBuffer::new(StackReq::EMPTY);
    solve_in_place_with_conj(
        l.as_ref(),
        Conj::No,
        x.as_mut(),
        par,
        MemStack::new(&mut mem),
    );
    Ok(LinearAnswer { x, work })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::options::Options;
    use faer::mat;

    #[test]
    fn only_a_symmetric_positive_definite_matrix_is_factored() {
        let rhs = mat![[1.0], [1.0]];
        let opts = Options::default().par(2, 2);
        let x = attempt(mat![[2.0, 1.0], [1.0, 2.0]].as_ref(), rhs.as_ref(), opts).unwrap();
        assert!((x.x[(0, 0)] - 1.0 / 3.0).abs() < 1e-15 && x.work.factorizations == 1);
        for m in [mat![[1.0, 2.0], [2.0, 1.0]], mat![[2.0, 1.0], [0.0, 2.0]]] {
            let failure = attempt(m.as_ref(), rhs.as_ref(), opts).unwrap_err();
            assert_eq!(failure.breakdown, Breakdown::NotPositiveDefinite);
        }
    }
}
