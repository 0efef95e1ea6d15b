//! The design stage reuses the scene's own analysis where it can, and what
//! it reuses is what it would have computed.

use std::path::Path;

use crate::common;
use crate::common::{example2_beam, with_table};
use elcon_design::{Analysis, Profile, evaluate};
use elcon_runner::run;
use elcon_scene::Scene;

/// The paper's beam on a foundation (Example 2: 1 in x 4 in, 8.9 in long,
/// 40 points, 50,000 lbf), solved in full (no folding), designed for two
/// loads, the second the scene's own, on the scene's grid alone (what is
/// shared is the scene's own S and solution).
fn beam() -> String {
    let unfolded = with_table(&example2_beam(40), "solver", "symmetry = \"none\"");
    with_table(
        &unfolded,
        "design",
        "family = \"quadratic\"\nloads = [25000.0, 50000.0]\nrefine = false",
    )
}

#[test]
fn the_design_stage_shares_the_scenes_matrix_and_solution() {
    let scene = Scene::from_str(Path::new("beam.toml"), &beam()).unwrap();
    let r = run(&scene).unwrap();
    assert!(r.problem.folding().is_none());
    let d = r.design.as_ref().unwrap();
    // Both cases are on the scene's points: S is shared, not assembled again.
    for case in &d.cases {
        assert_eq!(
            case.entries("a test").expect("dense").as_ptr(),
            r.problem.entries("a test").expect("dense").as_ptr()
        );
    }
    // At the scene's load the uncorrected case is the scene's own solution.
    assert_eq!(d.before.solutions[1].pressures, r.solution.pressures);
    // And it is what solving again gives, to the bit.
    let fresh = evaluate(
        &d.cases,
        scene.design().unwrap().axis(),
        &Profile::none(),
        &Analysis::new(scene.method(), scene.options()),
    )
    .unwrap();
    assert_eq!(fresh.max_intensities, d.before.max_intensities);
    for (a, b) in fresh.solutions.iter().zip(&d.before.solutions) {
        assert_eq!(a.pressures, b.pressures);
        assert_eq!(a.approach, b.approach);
    }
    let json = r.result.design.as_ref().unwrap();
    assert_eq!(json.cases[1].max_pressure_before, r.result.max_pressure);
}

/// The beam designed for two loads at three misalignments (prescribed
/// rotations about y, rad), by `method`.
fn misaligned(method: &str) -> String {
    let base = beam().replace("loads = [25000.0, 50000.0]\n", "");
    format!(
        "{base}loads = [25000.0, 50000.0]\nmisalignments = [0.0, 2e-5, 4e-5]\nmethod = \"{method}\"\n"
    )
}

#[test]
fn misalignments_make_a_case_of_each_load_at_each_angle() {
    let scene = Scene::from_str(Path::new("beam.toml"), &misaligned("descent")).unwrap();
    let r = run(&scene).unwrap();
    let d = r.design.as_ref().unwrap();
    assert_eq!(d.cases.len(), 6);
    let json = r.result.design.as_ref().unwrap();
    assert_eq!(json.method.name(), "descent");
    let expected = [
        (25000.0, 0.0),
        (25000.0, 2e-5),
        (25000.0, 4e-5),
        (50000.0, 0.0),
        (50000.0, 2e-5),
        (50000.0, 4e-5),
    ];
    for ((case, row), (load, angle)) in d.cases.iter().zip(&json.cases).zip(expected) {
        assert_eq!(row.load, load);
        assert_eq!(row.misalignment, Some(angle));
        assert!(row.certificate_holds);
        // The rotation is prescribed, and every case shares the scene's S.
        let rigid = case.rigid();
        assert!(
            rigid
                .prescribed
                .iter()
                .any(|&(m, v)| m == elcon_analysis::RigidMode::TiltY && v == angle)
        );
        assert_eq!(
            case.entries("a test").expect("dense").as_ptr(),
            r.problem.entries("a test").expect("dense").as_ptr()
        );
    }
    // A misaligned case is not the scene's own (free-rotation) analysis;
    // each is its own, so the worst before is at the largest angle.
    let worst_before = json
        .cases
        .iter()
        .map(|c| c.max_pressure_before)
        .fold(0.0f64, f64::max);
    assert_eq!(worst_before, json.cases[5].max_pressure_before);
    // The design evens the worst case out: the objective falls.
    assert!(json.objective < json.objective_before);
}

#[test]
fn the_scenes_descent_and_program_reach_one_optimum() {
    let objective = |method: &str| {
        let scene = Scene::from_str(Path::new("beam.toml"), &misaligned(method)).unwrap();
        let r = run(&scene).unwrap();
        let json = r.result.design.clone().unwrap();
        assert_eq!(json.method.name(), method);
        json.objective
    };
    let (descent, program) = (objective("descent"), objective("program"));
    // Both local minima of one problem from the same starts: equal to the
    // agreement a design demands of its re-analysis (measured: 1e-15).
    assert!(
        ((descent - program) / program).abs() < 1e-9,
        "{descent} vs {program}"
    );
}

/// Example 1's spheres designed for `objective` (a quadratic along y on
/// the scene's grid alone).
fn spheres_for(objective: &str) -> String {
    let unfolded = with_table(
        &common::spheres("spacing = 0.002\nradius = 0.02"),
        "solver",
        "symmetry = \"none\"",
    );
    with_table(
        &unfolded,
        "design",
        &format!("family = \"quadratic\"\nrefine = false\nobjective = \"{objective}\""),
    )
}

#[test]
fn a_von_mises_design_states_its_objective_and_worst_stress() {
    let designed = |objective: &str| {
        let scene = Scene::from_str(Path::new("spheres.toml"), &spheres_for(objective)).unwrap();
        run(&scene).unwrap().result.design.unwrap()
    };
    let stress = designed("von-mises");
    assert_eq!(stress.minimized.name(), "von-mises");
    assert_eq!(stress.method.name(), "descent");
    assert!(stress.cases.iter().all(|c| c.certificate_holds));
    let worst = stress.worst_stress.expect("a stress objective's value");
    assert!(worst > 0.0 && worst.is_finite(), "{worst}");
    let pressure = designed("pressure");
    assert_eq!(pressure.minimized.name(), "pressure");
    assert_eq!(pressure.worst_stress, None);
}
