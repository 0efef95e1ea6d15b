//! One test per `DesignError` variant: the error a user gets, and that its
//! message names the field and the reason.

use elcon_analysis::{AnalysisError, ContactProblem, ContactSolution, Loading, Method, Options};
use elcon_design::{
    Analysis, Axis, DesignError, DesignOptions, Family, Profile, design, evaluate,
    target_separation,
};
use elcon_fixtures::design_cases;
use elcon_fixtures::errors::{assert_pivot_limit_passes_through, one_pivot};
use elcon_lcp::LcpError;

/// Example 2's beam on 12 points under `loading`.
fn beam(loading: Loading) -> ContactProblem {
    design_cases::example2(12, 0.0, loading)
}

#[test]
fn invalid_input_names_the_field() {
    let case = beam(Loading::load(5e4));
    let opts = DesignOptions {
        max_constant: Some(-1.0),
        ..DesignOptions::default()
    };
    let e = design(
        std::slice::from_ref(&case),
        Axis::X,
        Family::Quadratic,
        &opts,
    )
    .unwrap_err();
    assert_eq!(e.to_string(), "`max_constant` = -1: must be finite and > 0");
    let e = target_separation(&case, &[0.0; 12]).unwrap_err();
    assert!(
        matches!(
            e,
            DesignError::InvalidInput {
                field: "weights",
                ..
            }
        ),
        "{e}"
    );
    let crown = Profile::CircularCrown {
        radius: f64::INFINITY,
        flat_length: 0.0,
    };
    let e = evaluate(
        &[case],
        Axis::X,
        &crown,
        &Analysis::new(Method::Lemke, &Options::default()),
    )
    .unwrap_err();
    assert_eq!(
        e.to_string(),
        "`circular_crown.radius` = inf: must be finite and > 0"
    );
}

/// The error of evaluating `case`, uncorrected, from the solutions `known`.
fn known_error(case: &ContactProblem, known: &[Option<&ContactSolution>]) -> DesignError {
    elcon_design::evaluate(
        std::slice::from_ref(case),
        Axis::X,
        &Profile::none(),
        &elcon_design::Analysis::new(Method::Lemke, &Options::default()).with_known(known),
    )
    .unwrap_err()
}

#[test]
fn incompatible_inputs_say_what_to_give() {
    let e = design(&[], Axis::X, Family::Free, &DesignOptions::default()).unwrap_err();
    assert_eq!(e.to_string(), "`cases`: no load case given");
    let e = design(
        &[beam(Loading::approach(1e-3))],
        Axis::X,
        Family::Free,
        &DesignOptions::default(),
    )
    .unwrap_err();
    assert!(
        e.to_string()
            .contains("load case 0 is displacement controlled"),
        "{e}"
    );
    let e = design(
        &[beam(Loading::load(1.0))],
        Axis::X,
        Family::Polynomial { degree: 12 },
        &DesignOptions::default(),
    )
    .unwrap_err();
    assert_eq!(
        e.to_string(),
        "`family.degree`: degree 12 needs at least 13 axial stations, the cases have 12"
    );
    // Known solutions: one entry per case, one value per point.
    let case = beam(Loading::load(5e4));
    let e = known_error(&case, &[]);
    assert_eq!(
        e.to_string(),
        "`known`: has 0 entries, expected 1 (one per load case)"
    );
    let other = design_cases::example2(8, 0.0, Loading::load(5e4))
        .solve(Method::Lemke, &Options::default())
        .unwrap();
    let e = known_error(&case, &[Some(&other)]);
    assert_eq!(
        e.to_string(),
        "`known`: the solution of load case 0 has 8 values, the case 12 points"
    );
    // The quadratic family too (a least-squares fit needs three stations).
    let two = elcon_design::fit_profile(Family::Quadratic, &[0.0, 1.0], &[0.0, 1.0]).unwrap_err();
    assert!(
        two.to_string()
            .contains("degree 2 needs at least 3 axial stations"),
        "{two}"
    );
}

/// The error of the quadratic design of the beam under 5e4 lb with `opts`.
fn quadratic_design_error(opts: &DesignOptions) -> DesignError {
    design(
        &[beam(Loading::load(5e4))],
        Axis::X,
        Family::Quadratic,
        opts,
    )
    .unwrap_err()
}

#[test]
fn analysis_failures_name_the_stage() {
    // A pivot limit of 1 in the re-analysis.
    let e = quadratic_design_error(&DesignOptions {
        reanalysis: Method::Lemke,
        reanalysis_options: one_pivot(),
        ..DesignOptions::default()
    });
    assert!(
        matches!(
            &e,
            DesignError::Analysis {
                source: AnalysisError::Engine(LcpError::PivotLimit { .. }),
                ..
            }
        ),
        "{e:?}"
    );
    assert!(
        e.to_string()
            .starts_with("analysis of load case 0 with the quadratic profile failed"),
        "{e}"
    );
}

#[test]
fn engine_failures_pass_through() {
    let e = quadratic_design_error(&DesignOptions {
        engine: one_pivot(),
        ..DesignOptions::default()
    });
    assert!(
        matches!(
            e,
            DesignError::Engine(LcpError::PivotLimit { limit: 1, .. })
        ),
        "{e:?}"
    );
    assert_pivot_limit_passes_through(&e, "the design program failed: pivot limit 1");
}

// DesignError::Disagreement: a unit test in src/optimize.rs (a re-analysis
// that disagrees cannot be produced from the outside on purpose).
