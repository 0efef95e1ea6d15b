//! A 1-norm condition estimate, `kappa_1(M) = ||M||_1 ||M^{-1}||_1`, without
//! forming the inverse: Hager's (1984) method as refined by Higham (1988,
//! LAPACK's xLACON): a few solves with M and M^T on vectors chosen to
//! maximize `||M^{-1} x||_1` over `||x||_1 = 1`, and Higham's alternating
//! vector as a safeguard. The estimate is a lower bound, usually within a
//! factor 3 of the true value; it costs one LU of M (O(n^3)) and a handful of
//! O(n^2) solves. faer 0.24 has no condition estimator.

use faer::linalg::solvers::{PartialPivLu, Solve};
use faer::{Col, MatRef};

/// Most Hager iterations (LAPACK uses 5).
const ITERATIONS: usize = 5;

/// An estimate of the 1-norm condition number of a square matrix (`inf`
/// for a singular one, 1 for an empty one).
pub fn condition_estimate(m: MatRef<'_, f64>) -> f64 {
    let n = m.nrows();
    if n == 0 {
        return 1.0;
    }
    let norm1 = (0..n).map(|j| m.col(j).norm_l1()).fold(0.0f64, f64::max);
    let lu: PartialPivLu<f64> = PartialPivLu::new(m);
    let mut x = Col::<f64>::from_fn(n, |_| 1.0 / n as f64);
    let mut estimate = 0.0f64;
    for _ in 0..ITERATIONS {
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

#[cfg(test)]
mod tests {
    use super::*;
    use faer::Mat;

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
