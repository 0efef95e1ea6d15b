//! A design carried over finer grids until it holds on one
//! (`DesignRequest::run_converged`), its free profile a spline on fixed
//! knots, a roller's singular ends kept out of contact.

use elcon_analysis::ContactProblem;
use elcon_design::{
    Axis, DesignError, DesignFamily, DesignRequest, EDGE_WEIGHT, Family, GridSequence, Level,
    Profile,
};
use elcon_fixtures::design_cases::misaligned_roller;

/// The roller's cases on a grid `fineness` times the 5 x 12 cells.
fn roller(fineness: f64) -> (Vec<ContactProblem>, Vec<f64>) {
    let cells = |n: f64| (n * fineness).round() as usize;
    misaligned_roller(&[5e3, 10e3], &[0.0, 5e-4], (cells(5.0), cells(12.0)))
}

fn request(references: Vec<f64>) -> DesignRequest {
    DesignRequest {
        reference_intensities: Some(references),
        ..DesignRequest::new(DesignFamily::Linear(Family::Free), Axis::Y)
    }
}

#[test]
fn a_free_design_holds_on_the_next_finer_grid_and_keeps_the_ends_clear() {
    let (_, references) = roller(1.0);
    let sequence = GridSequence {
        fineness: vec![1.0, 2.0, 3.0, 4.0],
        tolerance: 0.02,
        max_points: 2_000,
    };
    let mut reported: Vec<Level> = Vec::new();
    let converged = request(references.clone())
        .run_converged(&sequence, |f| Ok(Some(roller(f).0)), |l| reported.push(*l))
        .expect("converges");
    let designed = converged.levels.last().expect("a design grid");
    let verification = converged.verification.expect("verified");
    // Held on a finer grid than its own, to the tolerance.
    assert!(verification.fineness > designed.fineness);
    let agreement = (verification.objective - designed.objective).abs() / designed.objective;
    assert!(agreement <= sequence.tolerance, "{agreement}");
    // Every grid was reported as it was done, the verification last.
    assert_eq!(reported.last(), Some(&verification));
    assert_eq!(reported.len(), 2 * converged.levels.len());
    // A spline through the first grid's 12 stations, whatever the grid.
    match &converged.outcome.profile {
        Profile::Spline { positions, .. } => assert_eq!(positions.len(), 12),
        other => panic!("{other:?}"),
    }
    // The ends carry at most a hundredth of the worst intensity
    // (EDGE_WEIGHT) in every case, and every case is certified.
    let evaluation = &converged.outcome.evaluation;
    let cases = converged.cases.iter().zip(&evaluation.solutions);
    for (l, (case, solution)) in cases.enumerate() {
        assert!(solution.certificate.holds());
        let edges = case.singular_edge_points();
        assert!(!edges.is_empty());
        for k in edges {
            let intensity = solution.pressures[k] / references[l];
            assert!(
                intensity * EDGE_WEIGHT <= designed.objective * (1.0 + 1e-9),
                "case {l}, end point {k}: {intensity} of {}",
                designed.objective
            );
        }
    }
}

#[test]
fn a_design_that_does_not_hold_within_the_points_allowed_is_refused() {
    let (_, references) = roller(1.0);
    let sequence = GridSequence {
        fineness: vec![1.0, 2.0, 3.0],
        tolerance: 1e-6,
        max_points: 2_000,
    };
    let e = request(references)
        .run_converged(&sequence, |f| Ok(Some(roller(f).0)), |_| {})
        .unwrap_err();
    match &e {
        DesignError::NotConverged { objectives, .. } => assert!(!objectives.is_empty()),
        other => panic!("{other:?}"),
    }
    assert!(e.to_string().contains("design.max_points"), "{e}");
    // A grid beyond what may be built ends the sequence as well.
    let e = request(roller(1.0).1)
        .run_converged(&sequence, |f| Ok((f < 2.0).then(|| roller(f).0)), |_| {})
        .unwrap_err();
    assert!(matches!(e, DesignError::NotConverged { .. }), "{e:?}");
    // A tolerance out of (0, 1) is refused by name.
    let bad = GridSequence {
        tolerance: 0.0,
        ..GridSequence::default()
    };
    let e = request(roller(1.0).1)
        .run_converged(&bad, |f| Ok(Some(roller(f).0)), |_| {})
        .unwrap_err();
    assert!(e.to_string().contains("grid_tolerance"), "{e}");
}
