//! The contact conditions of a solution, recomputed here from a problem's
//! own S, eps and loading (not taken from the engine's certificate).

#![allow(dead_code)]

use elcon_analysis::{ContactProblem, ContactSolution, Loading};
use proptest::prelude::*;

/// Tolerance of the checks below, relative to the scale of each quantity:
/// the engine certifies 1e-12 (a folded problem's rows are divided by at
/// most 8, so its certificate bounds the full residuals by 8e-12); a
/// recomputation here adds a dot product's rounding, N u < 2.5e-13 for the
/// N < 2000 of these tests.
pub const TOL: f64 = 1e-11;

/// Checks the contact conditions of `sol` from the data of `problem`, which
/// must be a problem solved in full (check a folded problem's solution
/// against the full problem of the same scene): sum F = P under load
/// control, F >= 0, gaps Y = S F + eps - alpha e >= 0 (and equal to
/// `sol.gaps`), F_k Y_k = 0, and the reported load.
pub fn check(problem: &ContactProblem, sol: &ContactSolution) -> Result<(), TestCaseError> {
    prop_assert!(
        problem.folding().is_none(),
        "check against the full problem: a folded one's matrix is not S"
    );
    let load = match problem.loading() {
        Loading::Load(p) => Some(p),
        Loading::Approach(_) => None,
    };
    let s = problem.influence();
    let eps = problem.separation();
    let n = eps.len();
    prop_assert_eq!(sol.forces.len(), n);
    let fmax = sol.forces.iter().fold(0.0f64, |a, f| a.max(*f));
    let mut gap_scale = 0.0f64;
    let mut gaps = vec![0.0; n];
    for k in 0..n {
        let mut sf = 0.0;
        let mut terms = 0.0;
        for j in 0..n {
            sf += s[(k, j)] * sol.forces[j];
            terms += (s[(k, j)] * sol.forces[j]).abs();
        }
        gaps[k] = sf + eps[k] - sol.approach;
        gap_scale = gap_scale.max(terms + eps[k].abs() + sol.approach.abs());
    }
    for k in 0..n {
        prop_assert!(sol.forces[k] >= -TOL * fmax, "F[{k}] = {}", sol.forces[k]);
        prop_assert!(
            gaps[k] >= -TOL * gap_scale,
            "Y[{k}] = {} (scale {gap_scale})",
            gaps[k]
        );
        prop_assert!(
            (sol.forces[k] * gaps[k]).abs() <= TOL * fmax * gap_scale,
            "F Y at {k}: {} {}",
            sol.forces[k],
            gaps[k]
        );
        prop_assert!((gaps[k] - sol.gaps[k]).abs() <= TOL * gap_scale);
    }
    let total: f64 = sol.forces.iter().sum();
    if let Some(p) = load {
        prop_assert!((total - p).abs() <= TOL * p, "sum F = {total}, P = {p}");
    }
    prop_assert!((total - sol.load).abs() <= TOL * total.abs().max(f64::MIN_POSITIVE));
    prop_assert!(sol.certificate.holds(), "{}", sol.certificate);
    Ok(())
}

/// [`check`] outside a property test: panics with `label` and the failure.
pub fn assert_solves(problem: &ContactProblem, sol: &ContactSolution, label: &str) {
    if let Err(e) = check(problem, sol) {
        panic!("{label}: {e}");
    }
}
