//! Small dense helpers over faer: an LU factorization with an explicit
//! parallelism and a singularity check (`B = P^T L U`, partial pivoting;
//! `solve` overwrites `X` with `B^{-1} X`), an in-place Cholesky of a lower
//! triangle (`A = L L^T`), matrix-vector products and norms, a symmetry
//! test, and a 1-norm condition estimate.

use faer::dyn_stack::{MemBuffer, MemStack};
use faer::linalg::lu::partial_pivoting::{factor, solve};
use faer::linalg::matmul::matmul;
use faer::perm::Perm;
use faer::{Accum, Col, ColMut, ColRef, Conj, Mat, MatMut, MatRef, Par};

use crate::LcpError;
use crate::tolerance::{SINGULAR_PER_ROW, SYMMETRY};

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

    /// Whether the factor is numerically singular: its pivot ratio at most
    /// [`SINGULAR_PER_ROW`] times its order.
    pub(crate) fn is_singular(&self) -> bool {
        self.pivot_ratio <= SINGULAR_PER_ROW * self.lu.nrows() as f64
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

/// A matrix or vector that could not be allocated: what it was for and
/// the bytes asked for (`LcpError::AllocationFailed` to the user).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) struct AllocationFailed {
    pub what: &'static str,
    pub bytes: usize,
}

impl From<AllocationFailed> for LcpError {
    fn from(AllocationFailed { what, bytes }: AllocationFailed) -> Self {
        LcpError::AllocationFailed { what, bytes }
    }
}

/// A `rows` x `cols` matrix of `f(i, j)`, its storage reserved fallibly:
/// [`AllocationFailed`] naming `what` when it cannot be.
pub(crate) fn try_mat(
    rows: usize,
    cols: usize,
    what: &'static str,
    f: impl FnMut(usize, usize) -> f64,
) -> Result<Mat<f64>, AllocationFailed> {
    let mut m = Mat::new();
    m.try_reserve(rows, cols).map_err(|_| AllocationFailed {
        what,
        bytes: rows.saturating_mul(cols).saturating_mul(8),
    })?;
    m.resize_with(rows, cols, f);
    Ok(m)
}

/// A vector of `len` zeros, reserved fallibly (see [`try_mat`]).
pub(crate) fn try_zeros(len: usize, what: &'static str) -> Result<Vec<f64>, AllocationFailed> {
    let mut v = Vec::new();
    v.try_reserve_exact(len).map_err(|_| AllocationFailed {
        what,
        bytes: len.saturating_mul(8),
    })?;
    v.resize(len, 0.0);
    Ok(v)
}

/// `y = a x` for a dense `a`.
pub(crate) fn matvec(a: MatRef<'_, f64>, x: ColRef<'_, f64>) -> Col<f64> {
    let mut y = Col::<f64>::zeros(a.nrows());
    matmul(y.as_mat_mut(), Accum::Replace, a, x.as_mat(), 1.0, Par::Seq);
    y
}

/// The Gram matrix `a^T a`.
pub(crate) fn gram(a: MatRef<'_, f64>) -> Mat<f64> {
    let mut g = Mat::<f64>::zeros(a.ncols(), a.ncols());
    matmul(g.as_mut(), Accum::Replace, a.transpose(), a, 1.0, Par::Seq);
    g
}

/// `y = |a| |x|` entry-wise absolute values: the magnitude of the terms that
/// sum to `a x`, the scale against which a residual of `a x` is judged.
pub(crate) fn abs_matvec(a: MatRef<'_, f64>, x: ColRef<'_, f64>) -> Col<f64> {
    let mut y = Col::<f64>::zeros(a.nrows());
    add_abs_matvec(y.as_mut(), a, x);
    y
}

/// `y += |a| |x|` (see [`abs_matvec`]), in place.
pub(crate) fn add_abs_matvec(mut y: ColMut<'_, f64>, a: MatRef<'_, f64>, x: ColRef<'_, f64>) {
    // Column by column, without forming |a| (an N x N copy); over
    // slices where both are contiguous (a loop the compiler vectorizes),
    // the same operations in the same order.
    for j in 0..a.ncols() {
        let xj = x[j].abs();
        if xj == 0.0 {
            continue;
        }
        let col = a.col(j);
        match (y.as_mut().try_as_col_major_mut(), col.try_as_col_major()) {
            (Some(y), Some(col)) => {
                let (y, col) = (y.as_slice_mut(), col.as_slice());
                y.iter_mut().zip(col).for_each(|(y, c)| *y += c.abs() * xj);
            }
            _ => {
                for i in 0..a.nrows() {
                    y[i] += col[i].abs() * xj;
                }
            }
        }
    }
}

/// `a b`, on the calling thread (the same bits on any thread count).
pub(crate) fn matmul_seq(a: MatRef<'_, f64>, b: MatRef<'_, f64>) -> Mat<f64> {
    let mut c = Mat::zeros(a.nrows(), b.ncols());
    matmul(c.as_mut(), Accum::Replace, a, b, 1.0, Par::Seq);
    c
}

/// `y -= a x`, in place (faer's product, accumulated).
pub(crate) fn sub_matvec(y: ColMut<'_, f64>, a: MatRef<'_, f64>, x: ColRef<'_, f64>) {
    matmul(y.as_mat_mut(), Accum::Add, a, x.as_mat(), -1.0, Par::Seq);
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

/// An entry `(i, j)` where `M` is not symmetric (to [`SYMMETRY`] of its
/// largest diagonal entry), compared tile by tile so that the transposed
/// reads stay in cache.
pub(crate) fn asymmetry(m: MatRef<'_, f64>) -> Option<(usize, usize)> {
    const TILE: usize = 64;
    let n = m.nrows();
    let scale = (0..n).fold(0.0f64, |a, i| a.max(m[(i, i)].abs()));
    let tolerance = SYMMETRY * scale;
    for j0 in (0..n).step_by(TILE) {
        for i0 in (0..=j0).step_by(TILE) {
            for j in j0..(j0 + TILE).min(n) {
                for i in i0..(i0 + TILE).min(j) {
                    if (m[(i, j)] - m[(j, i)]).abs() > tolerance {
                        return Some((i, j));
                    }
                }
            }
        }
    }
    None
}

/// The Cholesky factor of the lower triangle of `a`, in place (the upper
/// triangle is left as it was); `Err` when `a` is not positive definite.
pub(crate) fn cholesky_lower(a: MatMut<'_, f64>, par: Par) -> Result<(), NotPositiveDefinite> {
    use faer::linalg::cholesky::llt::factor::{
        LltRegularization, cholesky_in_place, cholesky_in_place_scratch,
    };
    let mut mem = MemBuffer::new(cholesky_in_place_scratch::<f64>(
        a.nrows(),
        par,
        Default::default(),
    ));
    cholesky_in_place(
        a,
        LltRegularization {
            dynamic_regularization_delta: 0.0,
            dynamic_regularization_epsilon: 0.0,
        },
        par,
        MemStack::new(&mut mem),
        Default::default(),
    )
    .map(|_| ())
    .map_err(|_| NotPositiveDefinite)
}

/// A matrix that is not positive definite (a Cholesky met a non-positive pivot).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) struct NotPositiveDefinite;

/// An estimate of the 1-norm condition number `kappa_1(M) = ||M||_1
/// ||M^{-1}||_1` of a square matrix (`inf` for a singular one, 1 for an
/// empty one), without forming the inverse: Hager's (1984) method as
/// refined by Higham (1988, LAPACK's xLACON): a few solves with M and M^T
/// on vectors chosen to maximize `||M^{-1} x||_1` over `||x||_1 = 1`, and
/// Higham's alternating vector as a safeguard. The estimate is a lower
/// bound, usually within a factor 3 of the true value; it costs one LU of
/// M (O(n^3)) and a handful of O(n^2) solves.
pub fn condition_estimate(m: MatRef<'_, f64>) -> f64 {
    let n = m.nrows();
    if n == 0 {
        return 1.0;
    }
    let norm1 = (0..n).map(|j| m.col(j).norm_l1()).fold(0.0f64, f64::max);
    use faer::linalg::solvers::{PartialPivLu, Solve};
    let lu: PartialPivLu<f64> = PartialPivLu::new(m);
    let mut x = Col::<f64>::from_fn(n, |_| 1.0 / n as f64);
    let mut estimate = 0.0f64;
    for _ in 0..HAGER_ITERATIONS {
        let y = lu.solve(&x);
        let ynorm = y.norm_l1();
        if !ynorm.is_finite() {
            return f64::INFINITY;
        }
        estimate = estimate.max(ynorm);
        let xi = Col::<f64>::from_fn(n, |i| if y[i] >= 0.0 { 1.0 } else { -1.0 });
        let z = lu.solve_transpose(&xi);
        let (j, zmax) = (0..n)
            .map(|i| (i, z[i].abs()))
            .fold((0, f64::NEG_INFINITY), |a, b| if b.1 > a.1 { b } else { a });
        let ztx: f64 = (0..n).map(|i| z[i] * x[i]).sum();
        if zmax <= ztx {
            break;
        }
        x = Col::zeros(n);
        x[j] = 1.0;
    }
    // Higham's safeguard: x_i = (-1)^i (1 + i / (n - 1)).
    let alt = Col::<f64>::from_fn(n, |i| {
        let s = if i % 2 == 0 { 1.0 } else { -1.0 };
        s * (1.0
            + if n > 1 {
                i as f64 / (n - 1) as f64
            } else {
                0.0
            })
    });
    let y = lu.solve(&alt);
    estimate = estimate.max(2.0 * y.norm_l1() / (3.0 * n as f64));
    norm1 * estimate
}

/// Most Hager iterations of [`condition_estimate`] (LAPACK uses 5).
const HAGER_ITERATIONS: usize = 5;

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_matrix_too_big_to_allocate_is_an_error_not_an_abort() {
        // 2^61 x 4 doubles: more than any address space.
        let e = try_mat(1 << 61, 4, "the test tableau", |_, _| 0.0).unwrap_err();
        assert!(matches!(
            e,
            AllocationFailed {
                what: "the test tableau",
                ..
            }
        ));
        // The user sees it as the engine's error, naming what and how much.
        let message = crate::LcpError::from(e).to_string();
        assert!(
            message
                .starts_with("could not allocate 18446744073709551615 bytes for the test tableau"),
            "{message}"
        );
        let e = try_zeros(usize::MAX / 4, "the test vector").unwrap_err();
        assert!(matches!(e, AllocationFailed { .. }));
        // What fits is built as asked.
        let m = try_mat(2, 3, "small", |i, j| (10 * i + j) as f64).unwrap();
        assert_eq!(m[(1, 2)], 12.0);
        assert_eq!(try_zeros(3, "small").unwrap(), vec![0.0; 3]);
    }

    #[test]
    fn diagonal_and_known_matrices() {
        // A diagonal matrix: kappa_1 = max / min exactly.
        let d = Mat::from_fn(5, 5, |i, j| {
            if i == j {
                [1.0, 10.0, 1e-3, 4.0, 2.0][i]
            } else {
                0.0
            }
        });
        assert!((condition_estimate(d.as_ref()) / 1e4 - 1.0).abs() < 1e-12);
        // [[1, 1], [0, 1]]: ||A||_1 = 2, ||A^-1||_1 = 2, kappa_1 = 4; the
        // estimate is a lower bound, here 2.
        let a = faer::mat![[1.0, 1.0], [0.0, 1.0f64]];
        let k = condition_estimate(a.as_ref());
        assert!((4.0 / 3.0..=4.0).contains(&k), "{k}");
        // The Hilbert matrix of order 6: kappa_1 = 2.907e7 (Higham, Table 28.1 gives kappa_2 = 1.5e7).
        let h = Mat::from_fn(6, 6, |i, j| 1.0 / (i + j + 1) as f64);
        let k = condition_estimate(h.as_ref());
        assert!(k > 0.3 * 2.907e7 && k <= 1.01 * 2.907e7, "{k:e}");
        assert_eq!(condition_estimate(Mat::<f64>::zeros(0, 0).as_ref()), 1.0);
    }
}
