//! Small dense helpers over faer: an LU factorization with an explicit
//! parallelism and a singularity check, matrix-vector products and norms.
//!
//! `B = P^T L U` (partial pivoting); `solve` overwrites `X` with `B^{-1} X`.

use faer::dyn_stack::{MemBuffer, MemStack};
use faer::linalg::lu::partial_pivoting::{factor, solve};
use faer::linalg::matmul::matmul;
use faer::perm::Perm;
use faer::{Accum, Col, ColRef, Conj, Mat, MatMut, MatRef, Par};

/// LU factorization `B = P^T L U` kept packed in one matrix.
pub(crate) struct Lu {
    lu: Mat<f64>,
    perm: Perm<usize>,
    par: Par,
    /// Smallest over largest magnitude on U's diagonal: 0 means singular.
    pub(crate) pivot_ratio: f64,
}

impl Lu {
    /// Factors a square matrix (consumed).
    pub(crate) fn new(mut lu: Mat<f64>, par: Par) -> Self {
        let n = lu.nrows();
        debug_assert_eq!(n, lu.ncols());
        let mut fwd = vec![0usize; n];
        let mut bwd = vec![0usize; n];
        let mut mem = MemBuffer::new(factor::lu_in_place_scratch::<usize, f64>(
            n,
            n,
            par,
            Default::default(),
        ));
        factor::lu_in_place(
            lu.as_mut(),
            &mut fwd,
            &mut bwd,
            par,
            MemStack::new(&mut mem),
            Default::default(),
        );
        let (mut lo, mut hi) = (f64::INFINITY, 0.0f64);
        for i in 0..n {
            let d = lu[(i, i)].abs();
            lo = lo.min(d);
            hi = hi.max(d);
        }
        let pivot_ratio = if n == 0 {
            1.0
        } else if hi > 0.0 && lo.is_finite() {
            lo / hi
        } else {
            0.0
        };
        let perm = Perm::new_checked(fwd.into_boxed_slice(), bwd.into_boxed_slice(), n);
        Self {
            lu,
            perm,
            par,
            pivot_ratio,
        }
    }

    /// Overwrites `rhs` with `B^{-1} rhs`.
    pub(crate) fn solve_in_place(&self, rhs: MatMut<'_, f64>) {
        let n = self.lu.nrows();
        let k = rhs.ncols();
        let mut mem = MemBuffer::new(solve::solve_in_place_scratch::<usize, f64>(n, k, self.par));
        solve::solve_in_place_with_conj(
            self.lu.as_ref(),
            self.lu.as_ref(),
            self.perm.as_ref(),
            Conj::No,
            rhs,
            self.par,
            MemStack::new(&mut mem),
        );
    }
}

/// `y = a x` for a dense `a`.
pub(crate) fn matvec(a: MatRef<'_, f64>, x: ColRef<'_, f64>) -> Col<f64> {
    let mut y = Col::<f64>::zeros(a.nrows());
    matmul(y.as_mat_mut(), Accum::Replace, a, x.as_mat(), 1.0, Par::Seq);
    y
}

/// `y = |a| |x|` entry-wise absolute values: the magnitude of the terms that
/// sum to `a x`, the scale against which a residual of `a x` is judged.
pub(crate) fn abs_matvec(a: MatRef<'_, f64>, x: ColRef<'_, f64>) -> Col<f64> {
    // Column by column, without forming |a| (an N x N copy).
    let mut y = Col::<f64>::zeros(a.nrows());
    for j in 0..a.ncols() {
        let xj = x[j].abs();
        if xj == 0.0 {
            continue;
        }
        let col = a.col(j);
        for i in 0..a.nrows() {
            y[i] += col[i].abs() * xj;
        }
    }
    y
}

/// Largest magnitude of a column vector (0 for an empty one).
pub(crate) fn norm_inf(x: ColRef<'_, f64>) -> f64 {
    x.iter().fold(0.0f64, |m, v| m.max(v.abs()))
}

/// The first non-finite entry of a matrix, as (row-major flat index, value).
pub(crate) fn first_non_finite(a: MatRef<'_, f64>) -> Option<(usize, f64)> {
    // Scanned by columns (contiguous in faer's layout); the entry reported
    // is the first in row-major order among the non-finite ones.
    let mut first: Option<(usize, f64)> = None;
    for j in 0..a.ncols() {
        let col = a.col(j);
        for i in 0..a.nrows() {
            let v = col[i];
            if !v.is_finite() {
                let flat = i * a.ncols() + j;
                if first.is_none_or(|(f, _)| flat < f) {
                    first = Some((flat, v));
                }
                break;
            }
        }
    }
    first
}

/// The power of two nearest `1 / v` (1 when `v` is 0 or not finite): an
/// exact change of units that brings a magnitude `v` to order 1.
pub(crate) fn unit_of(v: f64) -> f64 {
    if v > 0.0 && v.is_finite() {
        2f64.powi(-v.log2().round() as i32)
    } else {
        1.0
    }
}
