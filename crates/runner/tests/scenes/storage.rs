//! `solver.method`'s choice of storage: `"auto"` (the default) keeps the
//! dense S and block pivoting while the unknowns are few, and goes
//! matrix-free (the lattice operator, the conjugate gradient) above
//! `AUTO_DENSE_LIMIT`; an explicit `"conjugate-gradient"` runs matrix-free
//! unless the scene folds; the estimate of a matrix-free scene is O(N).

use std::path::Path;

use crate::common;
use crate::common::with_table;
use elcon_analysis::Method;
use elcon_analysis::{AUTO_DENSE_LIMIT, Storage};
use elcon_runner::{Estimate, run};
use elcon_scene::Scene;

fn spheres(across: usize, solver: &str) -> Scene {
    Scene::from_str(Path::new("storage.toml"), &spheres_text(across, solver)).expect("valid scene")
}

/// Example 1's spheres, `across` points across the Hertz diameter, with
/// `solver` under `[solver]`.
fn spheres_text(across: usize, solver: &str) -> String {
    let spheres = common::spheres(&format!("across = {across}\nzone = 1.15"));
    with_table(&spheres, "solver", solver)
}

#[test]
fn auto_is_block_pivoting_on_the_dense_s_for_few_unknowns() {
    // Symmetric about both axes: folded, an eighth of the unknowns.
    let scene = spheres(21, "");
    assert_eq!(
        (scene.method(), scene.storage()),
        (Method::BlockPivoting, Storage::Folded)
    );
    let given = spheres(21, r#"method = "auto""#);
    assert_eq!(given.storage(), Storage::Folded);
}

#[test]
fn auto_goes_matrix_free_above_the_limit_and_meets_hertz() {
    // 81 across, not folded: N = 6,609 unknowns, above the limit.
    let scene = spheres(81, r#"symmetry = "none""#);
    assert!(scene.points().len() > AUTO_DENSE_LIMIT);
    assert_eq!(
        (scene.method(), scene.storage()),
        (Method::ConjugateGradient, Storage::Lattice)
    );
    // O(N): the operator and a few vectors, not 8 N^2 bytes.
    let estimate = Estimate::of(&scene).expect("estimate");
    assert!(
        estimate.solve_bytes < 1000 * scene.points().len() as u64,
        "{}",
        estimate.solve_bytes
    );
    let run = run(&scene).expect("runs");
    assert_eq!(run.problem.storage(), Storage::Lattice);
    assert!(run.solution.certificate.holds());
    let result = &run.result;
    assert_eq!(result.header.influence.name(), "matrix-free");
    assert_eq!(result.header.method.name(), "conjugate-gradient");
    let reference = result.reference.as_ref().expect("Hertz applies");
    let error = reference.errors.approach.expect("approach error");
    assert!(error.abs() < 2e-3, "approach against Hertz {error:e}");
    // Folded, the same grid is small enough to stay dense.
    let folded = spheres(81, "");
    assert_eq!(folded.storage(), Storage::Folded);
}

#[test]
fn an_explicit_conjugate_gradient_is_matrix_free_unless_the_scene_folds() {
    let unfolded = spheres(21, "method = \"conjugate-gradient\"\nsymmetry = \"none\"");
    assert_eq!(unfolded.storage(), Storage::Lattice);
    let folded = spheres(21, r#"method = "conjugate-gradient""#);
    assert_eq!(
        (folded.method(), folded.storage()),
        (Method::ConjugateGradient, Storage::Folded)
    );
    let a = run(&unfolded).expect("matrix-free");
    let b = run(&folded).expect("dense, folded");
    assert!((a.solution.approach / b.solution.approach - 1.0).abs() < 1e-9);
}

#[test]
fn an_unknown_method_names_auto_among_the_choices() {
    let text = with_table(
        &common::sphere_on_rigid_plane("across = 11\nzone = 1.3"),
        "solver",
        "method = \"fastest\"",
    );
    let e = Scene::from_str(Path::new("bad.toml"), &text)
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("`solver.method`: unknown variant `fastest`, expected one of `auto`,"),
        "{e}"
    );
}

#[test]
fn a_matrix_free_scene_designs_by_the_descent_without_forming_s() {
    // Spheres solved matrix-free, their profile along y designed for two
    // loads: the design cases are lattice problems, the method the descent.
    // On the scene's grid alone, in a zone of 1.5 Hertz radii (the design
    // keeps the contact off the zone's rim along y; the uncorrected contact
    // of this coarse grid reaches the rim of a 1.15 zone).
    let design = "method = \"conjugate-gradient\"\nsymmetry = \"none\"\n\n[design]\nfamily = \"quadratic\"\naxis = \"y\"\nloads = [80.0, 100.0]\nrefine = false\n";
    let scene = Scene::from_str(
        Path::new("storage.toml"),
        &with_table(
            &common::spheres("across = 15\nzone = 1.5"),
            "solver",
            design,
        ),
    )
    .unwrap();
    assert_eq!(scene.storage(), Storage::Lattice);
    let estimate = Estimate::of(&scene).unwrap();
    let d = estimate.design.clone().unwrap();
    assert_eq!(d.method, Some(elcon_design::DesignMethod::Descent));
    // No N x N: at N = 1653 (41 across) the matrix-free design stage holds
    // less than one dense S (21.9 MB), the dense one several.
    let large = |solver: &str| {
        let text = spheres_text(
            41,
            &design.replace("method = \"conjugate-gradient\"", solver),
        );
        let scene = Scene::from_str(Path::new("storage.toml"), &text).unwrap();
        Estimate::of(&scene).unwrap().design.unwrap().bytes
    };
    let n = 1653u64;
    let (free, dense) = (
        large("method = \"conjugate-gradient\""),
        large("method = \"block-pivoting\""),
    );
    assert!(free < 8 * n * n, "{free} bytes");
    assert!(dense > 3 * 8 * n * n, "{dense} bytes");
    // Its time is the conjugate gradient's, linear in N: at 68,085 points
    // (257 across) the design runs in about a minute, not the hours a
    // dense analysis's N^3 would take.
    let text = spheres_text(257, design);
    let finest = Scene::from_str(Path::new("storage.toml"), &text).unwrap();
    let seconds = Estimate::of(&finest).unwrap().seconds;
    assert!((10.0..3600.0).contains(&seconds), "{seconds} s");
    let r = run(&scene).unwrap();
    let cases = &r.design.as_ref().unwrap().cases;
    assert!(cases.iter().all(|c| c.storage() == Storage::Lattice));
    let json = r.result.design.as_ref().unwrap();
    assert_eq!(json.method.name(), "descent");
    assert!(json.cases.iter().all(|c| c.certificate_holds));
    assert!(json.objective <= json.objective_before * (1.0 + 1e-12));
    // The program is refused for such a scene, naming the key.
    let text = design.replace(
        "family = \"quadratic\"",
        "family = \"quadratic\"\nmethod = \"program\"",
    );
    let e = Scene::from_str(Path::new("storage.toml"), &spheres_text(15, &text)).unwrap_err();
    assert!(e.to_string().contains("`design.method`"), "{e}");
    assert!(
        e.to_string().contains("the program reads S's entries"),
        "{e}"
    );
}

#[test]
fn result_json_writes_the_statistics_totals_then_each_attempt() {
    // result.json writes the statistics as the totals in this order, then the attempts; a block-pivoting
    // attempt has no tableau.
    let r = run(&spheres(11, r#"method = "block-pivoting""#)).unwrap();
    let text = serde_json::to_string(&r.result.header.statistics).unwrap();
    let order = |keys: &[&str], within: &str| {
        let at: Vec<usize> = keys
            .iter()
            .map(|k| within.find(&format!("\"{k}\":")).expect(k))
            .collect();
        assert!(at.windows(2).all(|w| w[0] < w[1]), "{keys:?} in {within}");
    };
    order(
        &[
            "pivots",
            "degenerate_pivots",
            "refactorizations",
            "refinement_steps",
            "iterations",
            "factorizations",
            "symmetric_tableau",
            "attempts",
        ],
        &text,
    );
    let attempt = &text[text.find("\"attempts\":").unwrap()..];
    order(
        &[
            "method",
            "reason",
            "pivots",
            "iterations",
            "seconds",
            "outcome",
        ],
        attempt,
    );
    assert!(!attempt.contains("\"tableau\""), "{attempt}");
    let json: serde_json::Value = serde_json::from_str(&text).unwrap();
    assert_eq!(json["pivots"], r.solution.statistics.pivots());
    assert_eq!(json["attempts"][0]["method"], "block-pivoting");
    assert_eq!(json["attempts"][0]["reason"], "first");
    assert_eq!(json["attempts"][0]["outcome"], "returned");
}

#[test]
fn result_json_writes_the_certificate_with_its_worst_residual_and_verdict() {
    // result.json writes the contact certificate as the stored residuals
    // with the computed `worst` and `holds` between them.
    let r = run(&spheres(11, r#"method = "block-pivoting""#)).unwrap();
    let c = &r.solution.certificate;
    let text = serde_json::to_string(&r.result.solution.certificate).unwrap();
    let keys = [
        "equilibrium",
        "min_force",
        "min_gap",
        "complementarity",
        "worst",
        "tolerance",
        "holds",
    ];
    let at: Vec<usize> = keys
        .iter()
        .map(|k| text.find(&format!("\"{k}\":")).expect(k))
        .collect();
    assert!(at.windows(2).all(|w| w[0] < w[1]), "{text}");
    let json: serde_json::Value = serde_json::from_str(&text).unwrap();
    assert_eq!(json["worst"], c.worst());
    assert_eq!(json["holds"], c.holds());
    assert!(c.holds());
    assert_eq!(json["min_gap"], c.min_gap);
}
