//! The answers of a solve: certified solutions with their statistics.

use faer::{Col, Mat};

use crate::certificate::Certificate;
use crate::statistics::Statistics;

/// A certified solution of an LCP, a bordered LCP or a mixed LCP.
#[derive(Debug, Clone)]
pub struct LcpSolution {
    /// The complementary unknowns `z`.
    pub z: Col<f64>,
    /// `w`, computed from the original data (`w = M z - B λ + q` for a
    /// bordered problem, `M z + B u + q` for a mixed one).
    pub w: Col<f64>,
    /// The free unknowns: `λ` of a bordered problem, `u` of a mixed one
    /// (empty for a standard LCP).
    pub u: Col<f64>,
    /// `basic[i]` is true when `z_i` (rather than `w_i`) is basic in the
    /// final complementary basis: the active set, for warm starts.
    pub basic: Vec<bool>,
    /// Residuals from the original data.
    pub certificate: Certificate,
    /// What the solve cost, attempt by attempt.
    pub statistics: Statistics,
}

/// A certified solution of a [`ComplementaryProgram`](crate::ComplementaryProgram).
#[derive(Debug, Clone)]
pub struct ProgramSolution {
    /// Every unknown, in the order they were added.
    pub x: Col<f64>,
    /// `c^T x`, when the program has an objective.
    pub objective: Option<f64>,
    /// The basic unknowns of the final basis (warm-start data).
    pub basis: Vec<usize>,
    /// Residuals from the original data: of a complementary pair, the unknown
    /// with the lower index counts as `z` and the other as `w`; unpaired
    /// non-negative unknowns count as `u`. Each unknown is measured by its
    /// activity `max_r |A_rj| |x_j|` relative to the constraint scale
    /// `max_r (|A| |x| + |b|)_r`.
    pub certificate: Certificate,
    /// What the solve cost, attempt by attempt.
    pub statistics: Statistics,
}

/// A certified solution of a [`LinearSystem`](crate::LinearSystem) `M X = R`.
#[derive(Debug, Clone)]
pub struct LinearSolution {
    /// `X` (n x m), a column for each right-hand side.
    pub x: Mat<f64>,
    /// The worst relative residual over the columns,
    /// `max_c ‖R_c - M X_c‖∞ / ‖|M| |X_c| + |R_c|‖∞`, from products of the
    /// original data (at most the certificate's tolerance).
    pub residual: f64,
    /// What the solve cost, attempt by attempt (which factorization or
    /// iteration answered, and any fallback).
    pub statistics: Statistics,
}
