//! The design stage reuses the scene's own analysis where it can, and what
//! it reuses is what it would have computed.

use std::path::Path;

use elcon_design::{Profile, evaluate};
use elcon_scene::{Scene, run};

/// The paper's beam on a foundation, solved in full (no folding), designed
/// for two loads, the second the scene's own.
const BEAM: &str = r#"
[units]
length = "in"
force = "lbf"

[body1]
model = "beam"
youngs_modulus = 30e6
width = 1.0
depth = 4.0

[body2]
model = "winkler"
modulus = 1e7

[points]
grid = "line"
start = -4.45
end = 4.45
n = 40

[loading]
load = 50000.0

[solver]
symmetry = "none"

[design]
family = "quadratic"
loads = [25000.0, 50000.0]
"#;

#[test]
fn the_design_stage_shares_the_scenes_matrix_and_solution() {
    let scene = Scene::from_str(Path::new("beam.toml"), BEAM).unwrap();
    let r = run(&scene).unwrap();
    assert!(r.problem.folding().is_none());
    let d = r.design.as_ref().unwrap();
    // Both cases are on the scene's points: S is shared, not assembled again.
    for case in &d.cases {
        assert_eq!(
            case.influence().expect("dense").as_ptr(),
            r.problem.influence().expect("dense").as_ptr()
        );
    }
    // At the scene's load the uncorrected case is the scene's own solution.
    assert_eq!(d.before.solutions[1].pressures, r.solution.pressures);
    // And it is what solving again gives, to the bit.
    let fresh = evaluate(
        &d.cases,
        scene.design.as_ref().unwrap().axis,
        &Profile::none(),
        scene.method,
        &scene.options,
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
