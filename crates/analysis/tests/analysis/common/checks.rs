//! The contact conditions of a solution, recomputed here from a problem's
//! own S, eps and loading (not taken from the engine's certificate).

#![allow(dead_code)]

use elcon_analysis::{ContactProblem, ContactSolution, Normal, Tilt};
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
/// control, F >= 0, gaps Y = S F + eps - (alpha + θ_x (y - y0) - θ_y (x -
/// x0)) >= 0 (and equal to `sol.gaps`), F_k Y_k = 0, the moments of a free
/// rotation, and the reported load and moments.
pub fn check(problem: &ContactProblem, sol: &ContactSolution) -> Result<(), TestCaseError> {
    prop_assert!(
        problem.folding().is_none(),
        "check against the full problem: a folded one's matrix is not S"
    );
    let load = match problem.loading().normal {
        Normal::Load(p) => Some(p),
        Normal::Approach(_) => None,
    };
    let s = problem.entries("the check").expect("a dense problem");
    let eps = problem.separation();
    let n = eps.len();
    prop_assert_eq!(sol.forces.len(), n);
    let (x0, y0) = problem.rigid().load_point;
    let points = problem.points();
    // The rigid motion toward body 2 at point k.
    let rigid =
        |k: usize| sol.approach + sol.tilt_x * (points.y(k) - y0) - sol.tilt_y * (points.x(k) - x0);
    let mut gap_scale = 0.0f64;
    let mut gaps = vec![0.0; n];
    for k in 0..n {
        let mut sf = 0.0;
        let mut terms = 0.0;
        for j in 0..n {
            sf += s[(k, j)] * sol.forces[j];
            terms += (s[(k, j)] * sol.forces[j]).abs();
        }
        gaps[k] = sf + eps[k] - rigid(k);
        gap_scale = gap_scale.max(terms + eps[k].abs() + rigid(k).abs());
    }
    let fmax = force_scale(problem, sol, gap_scale);
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
    // Moments of the forces about the load point, against the reported ones
    // and, for a free rotation, the moment it balances (each to the scale
    // of the moments the forces can make, sum |F| times the largest lever:
    // a contact on the axis alone makes none).
    let loading = problem.loading();
    let force_sum: f64 = sol.forces.iter().map(|f| f.abs()).sum();
    let reach = (0..n).fold(0.0f64, |a, k| {
        a.max((points.x(k) - x0).abs())
            .max((points.y(k) - y0).abs())
    });
    // The forces' moment on the lever arms `arm`, and the sum of its terms'
    // sizes.
    // The terms' sizes are floored, as the engine's equality rows are, by
    // the force scale on every lever: `fmax sum_k |arm(k)|`.
    let moment_on = |arm: &dyn Fn(usize) -> f64| {
        let terms = (0..n).map(|k| sol.forces[k] * arm(k));
        let floor = fmax * (0..n).map(|k| arm(k).abs()).sum::<f64>();
        (
            terms.clone().sum::<f64>(),
            terms.map(f64::abs).sum::<f64>().max(floor),
        )
    };
    let (about_x, lever_x) = moment_on(&|k| points.y(k) - y0);
    let (about_y, lever_y) = moment_on(&|k| points.x(k) - x0);
    for (moment, reported, lever, tilt) in [
        (about_x, sol.moment_x, lever_x, loading.tilt_x),
        (-about_y, sol.moment_y, lever_y, loading.tilt_y),
    ] {
        let scale = lever.max(force_sum * reach).max(f64::MIN_POSITIVE);
        prop_assert!(
            (moment - reported).abs() <= TOL * scale,
            "moment {moment} reported {reported}"
        );
        if let Tilt::Free { moment: applied } = tilt {
            prop_assert!(
                (moment - applied).abs() <= TOL * (scale + applied.abs()),
                "moment {moment} against the applied {applied}"
            );
        }
    }
    prop_assert!(sol.certificate.holds(), "{}", sol.certificate);
    Ok(())
}

/// The scale forces are judged on: the largest force, floored (as the
/// engine's certificate is) by the force that alone would move a gap by
/// `gap_scale`, `gap_scale / max |S_kj|`. Bodies that separate have F = 0,
/// and a pivoting method returns the zeros as differences of pivots:
/// rounding of the natural forces, not of the largest (zero) one.
pub fn force_scale(problem: &ContactProblem, sol: &ContactSolution, gap_scale: f64) -> f64 {
    let s = problem.entries("the check").expect("a dense problem");
    let largest = s.norm_max();
    let fmax = sol.forces.iter().fold(0.0f64, |a, f| a.max(*f));
    if largest > 0.0 {
        fmax.max(gap_scale / largest)
    } else {
        fmax
    }
}

/// The gap scale of [`check`]: the largest `|S| |F| + |eps| + |rigid|`.
pub fn gap_scale(problem: &ContactProblem, sol: &ContactSolution) -> f64 {
    let s = problem.entries("the check").expect("a dense problem");
    let eps = problem.separation();
    let (x0, y0) = problem.rigid().load_point;
    let points = problem.points();
    (0..eps.len()).fold(0.0f64, |g, k| {
        let rigid =
            sol.approach + sol.tilt_x * (points.y(k) - y0) - sol.tilt_y * (points.x(k) - x0);
        let terms: f64 = (0..eps.len())
            .map(|j| (s[(k, j)] * sol.forces[j]).abs())
            .sum();
        g.max(terms + eps[k].abs() + rigid.abs())
    })
}

/// [`check`] outside a property test: panics with `label` and the failure.
pub fn assert_solves(problem: &ContactProblem, sol: &ContactSolution, label: &str) {
    if let Err(e) = check(problem, sol) {
        panic!("{label}: {e}");
    }
}
