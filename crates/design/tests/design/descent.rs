//! The case-decomposed descent against the paper's program (the exact
//! reference) on problems small enough for the program: the same optimum
//! to the agreement design() demands of a re-analysis (1e-9 relative), or
//! a better one (both are local minima of a non-convex problem; the
//! descent never ends above the program's optimum on these cases,
//! measured). Families: quadratic, polynomial, free; cases: Example 2's
//! beam under one and several loads, off-centre loads, and a roller under
//! loads x misalignments (each case a prescribed tilt).

use crate::common;

use elcon_analysis::references::HertzCylinders;
use elcon_analysis::{ContactProblem, Geometry, Loading, Surface};
use elcon_design::{Axis, Design, DesignMethod, DesignOptions, Family, Solver, Stop, design};
use elcon_fixtures::design_cases;
use elcon_influence::{Beam, Body, Material, PointSet, combined_modulus};

/// The agreement between the two methods' optima (see the module docs).
const SAME_OPTIMUM: f64 = 1e-9;

/// Example 2's beam at `per_half` points per half under `load` at `x0`,
/// its rotation held at the loaded point.
fn beam(per_half: usize, load: f64, x0: f64) -> ContactProblem {
    design_cases::example2(2 * per_half, x0, Loading::load(load).with_tilt_y(0.0))
}

/// The misaligned roller on a coarse 5 x 12 grid.
fn roller(loads: &[f64], misalignments: &[f64]) -> (Vec<ContactProblem>, Vec<f64>) {
    design_cases::misaligned_roller(loads, misalignments, (5, 12))
}

/// Each of `cases` under `loading` of its own load.
fn reloaded(cases: &[ContactProblem], loading: impl Fn(f64) -> Loading) -> Vec<ContactProblem> {
    cases
        .iter()
        .map(|c| {
            let load = c.loading().load_value().unwrap();
            c.with_loading(loading(load)).unwrap()
        })
        .collect()
}

fn solve(
    cases: &[ContactProblem],
    axis: Axis,
    family: Family,
    method: DesignMethod,
    references: Option<Vec<f64>>,
) -> Design {
    design(
        cases,
        axis,
        family,
        &design_cases::options(method, references),
    )
    .unwrap_or_else(|e| panic!("{method:?} {family:?}: {e}"))
}

/// Both methods on `cases`; the descent's optimum equals the program's or
/// is lower, and every re-analysis is certified.
fn same_optimum(
    label: &str,
    cases: &[ContactProblem],
    axis: Axis,
    family: Family,
    references: Option<Vec<f64>>,
) {
    let program = solve(
        cases,
        axis,
        family,
        DesignMethod::Program,
        references.clone(),
    );
    let descent = solve(cases, axis, family, DesignMethod::Descent, references);
    for d in [&program, &descent] {
        for s in &d.evaluation.solutions {
            assert!(s.certificate.holds(), "{label}: {}", s.certificate);
        }
    }
    match &descent.solver {
        Solver::Descent { stop, .. } => assert_ne!(*stop, Stop::IterationLimit, "{label}"),
        other => panic!("{label}: the descent reported {other:?}"),
    }
    let relative = (descent.objective - program.objective) / program.objective;
    assert!(
        relative <= SAME_OPTIMUM,
        "{label} {family:?}: descent {} against program {} ({relative:e})",
        descent.objective,
        program.objective
    );
}

#[test]
fn the_descent_reaches_the_programs_optimum_on_the_beam() {
    for family in [
        Family::Quadratic,
        Family::Polynomial { degree: 4 },
        Family::Free,
    ] {
        same_optimum("central", &[beam(20, 5e4, 0.0)], Axis::X, family, None);
        same_optimum("off centre", &[beam(20, 5e4, 1.0)], Axis::X, family, None);
        let loads = [beam(15, 2e4, 0.0), beam(15, 5e4, 0.0), beam(15, 8e4, 0.0)];
        let means = Some(vec![2e4 / 8.9, 5e4 / 8.9, 8e4 / 8.9]);
        same_optimum("three loads", &loads, Axis::X, family, means);
    }
}

#[test]
fn the_descent_reaches_the_programs_optimum_on_a_misaligned_roller() {
    let (cases, references) = roller(&[2e3, 5e3], &[0.0, 5e-4]);
    for family in [Family::Quadratic, Family::Free] {
        same_optimum("roller", &cases, Axis::Y, family, Some(references.clone()));
    }
}

#[test]
fn the_descent_reaches_the_programs_optimum_under_moments() {
    // Each load with a moment about x (its centre of pressure 0.5 mm off
    // the middle along the roller), the rotation free: the rigid unknowns'
    // resultants are the load and the moment.
    let (aligned, references) = roller(&[2e3, 5e3], &[0.0]);
    let cases = reloaded(&aligned, |load| {
        Loading::load(load).with_moment_x(0.5 * load)
    });
    for family in [Family::Quadratic, Family::Free] {
        same_optimum("moments", &cases, Axis::Y, family, Some(references.clone()));
    }
}

#[test]
fn auto_takes_the_program_for_few_points_and_the_descent_above() {
    // The quadratic correction of the beam at `per_half` points per half, by
    // the method "auto" picks.
    let auto = |per_half| {
        let beam = [beam(per_half, 5e4, 0.0)];
        solve(&beam, Axis::X, Family::Quadratic, DesignMethod::Auto, None)
    };
    let small = auto(20);
    assert_eq!(small.solver.method(), DesignMethod::Program);
    assert!(matches!(small.solver, Solver::Program { .. }));
    let per_half = elcon_design::PROGRAM_LIMIT / 2 + 1;
    let large = auto(per_half);
    assert_eq!(large.solver.method(), DesignMethod::Descent);
    assert!(matches!(large.solver, Solver::Descent { .. }));
}

#[test]
fn the_descent_never_ends_above_its_start() {
    // A flexible beam on a stiff foundation (local minima: the uncorrected
    // start leaves the load on a few points) from the uncorrected start
    // only: the objective at the end is at most the uncorrected p_max.
    let n = 30;
    let case = ContactProblem::new(
        PointSet::line(-4.45, 4.45, n).unwrap(),
        &Body::beam(Beam {
            youngs_modulus: 30e6,
            second_moment: 0.01,
            loaded_point: 0.0,
        })
        .unwrap(),
        &Body::winkler(1e9),
        &Geometry::Separation(vec![0.0; n]),
        Loading::load(5e4),
    )
    .unwrap();
    let d = design(
        std::slice::from_ref(&case),
        Axis::X,
        Family::Free,
        &DesignOptions {
            method: DesignMethod::Descent,
            fitted_start: false,
            ..DesignOptions::default()
        },
    )
    .unwrap();
    let uncorrected = case
        .solve(elcon_analysis::Method::BlockPivoting, &Default::default())
        .unwrap()
        .max_pressure;
    assert!(d.objective <= uncorrected * (1.0 + 1e-12));
    assert_eq!(d.starts.len(), 1);
}

#[test]
fn a_zero_iteration_limit_is_refused_naming_the_field() {
    let e = design(
        &[beam(10, 5e4, 0.0)],
        Axis::X,
        Family::Quadratic,
        &DesignOptions {
            max_iterations: 0,
            ..DesignOptions::default()
        },
    )
    .unwrap_err();
    assert!(e.to_string().contains("max_iterations"), "{e}");
}

#[test]
fn a_line_the_free_rotation_absorbs_is_taken_out_of_the_profile() {
    // Aligned roller cases leave the rotation about x free: a straight line
    // along y added to the profile changes no force, so the descent's
    // trust-region steps may drift along it. The design takes the line out:
    // on these symmetric cases the free profile comes out symmetric.
    let (misaligned, references) = roller(&[2e3, 5e3], &[0.0]);
    let cases = reloaded(&misaligned, Loading::load);
    let d = solve(
        &cases,
        Axis::Y,
        Family::Free,
        DesignMethod::Descent,
        Some(references),
    );
    let drops = match &d.profile {
        elcon_design::Profile::Free { drops, .. } => drops.clone(),
        other => panic!("{other:?}"),
    };
    let largest = drops.iter().fold(0.0f64, |a, v| a.max(*v));
    assert!(largest > 0.0);
    let n = drops.len();
    for i in 0..n / 2 {
        assert!(
            (drops[i] - drops[n - 1 - i]).abs() <= 1e-9 * largest,
            "station {i}: {} against {}",
            drops[i],
            drops[n - 1 - i]
        );
    }
}

#[test]
fn a_matrix_free_case_is_designed_by_the_descent_as_the_dense_one() {
    // The roller of the tests above on a lattice: S as an FFT operator,
    // the analyses by the conjugate gradient, the sensitivities by
    // conjugate gradients on the contact set. Same optimum as the dense S,
    // to the conjugate gradient's certificate (1e-12) times the model's use.
    let steel = Material::new(210e3, 0.3).unwrap();
    let hertz = HertzCylinders::new(combined_modulus(&steel, &steel), 5.0, 500.0).unwrap();
    let points = PointSet::grid_rectangle(1.6 * hertz.half_width(), 5.0, 5, 12).unwrap();
    let body = Body::uniform_patch(steel);
    let geometry = Geometry::Surfaces(Surface::Cylinder { radius: 5.0 }, Surface::Plane);
    let loading = Loading::load(5e3).with_tilt_x(2e-4);
    let dense = ContactProblem::new(points.clone(), &body, &body, &geometry, loading).unwrap();
    let lattice = ContactProblem::lattice(points, &body, &body, &geometry, loading).unwrap();
    for family in [Family::Quadratic, Family::Free] {
        let exact = solve(
            std::slice::from_ref(&dense),
            Axis::Y,
            family,
            DesignMethod::Descent,
            None,
        );
        let options = DesignOptions {
            reanalysis: elcon_analysis::Method::ConjugateGradient,
            ..DesignOptions::default()
        };
        let free = design(std::slice::from_ref(&lattice), Axis::Y, family, &options)
            .unwrap_or_else(|e| panic!("{family:?}: {e}"));
        assert_eq!(
            free.solver.method(),
            DesignMethod::Descent,
            "auto takes the descent"
        );
        let relative = (free.objective - exact.objective) / exact.objective;
        assert!(relative.abs() < 1e-8, "{family:?}: {relative:e}");
        assert!(free.evaluation.solutions[0].certificate.holds());
    }
    // The program reads S's entries; pivoting re-analyses need them too.
    let e = common::design_one(&lattice, Axis::Y, Family::Quadratic).unwrap_err();
    assert!(e.to_string().contains("`reanalysis`"), "{e}");
}
