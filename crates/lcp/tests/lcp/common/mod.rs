//! Helpers shared by the integration tests (each test file uses some of
//! them).

#![allow(dead_code)]

use elcon_lcp::{Operator, PodStack, Preconditioner, StackReq};
use faer::Col;

/// The largest difference of `a` and `b`, relative to their largest entry.
pub fn rel_diff(a: &Col<f64>, b: &Col<f64>) -> f64 {
    let scale = a
        .iter()
        .chain(b.iter())
        .fold(0.0f64, |m, v| m.max(v.abs()))
        .max(1e-300);
    (a - b).iter().fold(0.0f64, |m, v| m.max(v.abs())) / scale
}

/// `M` tridiagonal, `[c, d, c]` with `c, d > 0` (non-negative entries, as
/// an influence operator's; symmetric positive definite for `d > 2 c`),
/// applied by its products. Its [`Preconditioner`] is the first two
/// terms of its inverse's Neumann series, `P = (I - (c/d) T) / d` (`T` the
/// neighbours' sum; positive definite for `2 c < d`), which the tests give
/// their problem where `preconditioned` is set; with
/// `says_nonnegative`, it tells the certificate that its entries are
/// non-negative (`Operator::entries_nonnegative`).
pub struct Tridiagonal {
    pub n: usize,
    pub d: f64,
    pub c: f64,
    pub preconditioned: bool,
    pub says_nonnegative: bool,
}

impl Tridiagonal {
    /// `[c, d, c]` of size `n`, without a preconditioner, saying nothing
    /// of its entries.
    pub fn new(n: usize, d: f64, c: f64) -> Self {
        Self {
            n,
            d,
            c,
            preconditioned: false,
            says_nonnegative: false,
        }
    }

    fn neighbours(&self, x: &[f64], i: usize) -> f64 {
        let left = if i > 0 { x[i - 1] } else { 0.0 };
        let right = if i + 1 < self.n { x[i + 1] } else { 0.0 };
        left + right
    }
}

impl Operator for Tridiagonal {
    fn size(&self) -> usize {
        self.n
    }

    fn apply_scratch(&self) -> StackReq {
        StackReq::EMPTY
    }

    fn apply(&self, x: &[f64], y: &mut [f64], _: &mut PodStack) {
        for i in 0..self.n {
            y[i] = self.d * x[i] + self.c * self.neighbours(x, i);
        }
    }

    fn apply_abs(&self, x: &[f64], y: &mut [f64], stack: &mut PodStack) {
        self.apply(x, y, stack);
    }

    fn entries_nonnegative(&self) -> bool {
        self.says_nonnegative
    }
}

impl Preconditioner for Tridiagonal {
    fn size(&self) -> usize {
        self.n
    }

    fn precondition_scratch(&self) -> StackReq {
        StackReq::EMPTY
    }

    fn precondition(&self, r: &[f64], z: &mut [f64], _: &mut PodStack) {
        for i in 0..self.n {
            z[i] = (r[i] - self.c / self.d * self.neighbours(r, i)) / self.d;
        }
    }
}
