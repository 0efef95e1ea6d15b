//! Checks of a scene as a whole: what the solve or the design would
//! otherwise refuse only once it runs (or answer meaninglessly) is refused
//! by validation, so `elcon check` and `elcon run` agree; the knobs that
//! cost time or memory are bounded; a grid too coarse for the contact
//! warns. Each message names the field.

mod common;

use common::{BEAM, scene, with_table};
use elcon_scene::SceneError;

/// Refused, naming `field`, with `reason` in the message.
fn refused(text: &str, field: &str, reason: &str) {
    let e = scene(text).unwrap_err();
    assert!(matches!(e, SceneError::Invalid { .. }), "{e}");
    let m = e.to_string();
    assert!(m.contains(&format!("`{field}`")), "{field}: {m}");
    assert!(m.contains(reason), "{reason}: {m}");
}

/// Example 1's spheres on an absolute disk grid: spacing 0.002 in, radius
/// 0.02 in (the Hertz radius is 0.016 in).
fn spheres() -> String {
    common::spheres("spacing = 0.002\nradius = 0.02")
}

/// [`BEAM`] with a `[design]` table of `lines`.
fn beam_design(lines: &str) -> String {
    with_table(BEAM, "design", lines)
}

const STRIPS: &str = r#"
[units]
length = "mm"
force = "N"

[body1]
model = "plane-strain"
youngs_modulus = 210e3
poissons_ratio = 0.3
reference_distance = 10.0

[body2]
model = "plane-strain"
youngs_modulus = 210e3
poissons_ratio = 0.3
reference_distance = 10.0

[geometry]
surface1 = { shape = "cylinder", radius = 5.0 }

[points]
grid = "line"
start = -0.2
end = 0.2
n = 41

[loading]
load = 100.0
"#;

#[test]
fn a_concave_surface_must_be_the_larger_radius() {
    scene(&spheres()).unwrap();
    // A ball in a larger socket is a contact.
    scene(&spheres().replace("radius = 10.0 }", "radius = -20.0 }")).unwrap();
    // R1 = 1 inside a concave R2 = -0.5: interpenetration everywhere.
    refused(
        &spheres().replace("radius = 10.0 }", "radius = -0.5 }"),
        "geometry.surface2.radius",
        "a concave surface must have the larger radius",
    );
    // R1 = -1 against R2 = 10 (the concave one first).
    let e = scene(&spheres().replace("radius = 1.0 }", "radius = -1.0 }")).unwrap_err();
    assert!(
        e.to_string().starts_with(
            "test.toml:17:41: `geometry.surface1.radius` = -1: a concave surface must have the \
             larger radius: against the convex radius 10"
        ),
        "{e}"
    );
    // A concave cylinder against a plane.
    refused(
        &STRIPS.replace("radius = 5.0 }", "radius = -5.0 }"),
        "geometry.surface1.radius",
        "against a plane",
    );
}

#[test]
fn the_plane_strain_datum_must_lie_beyond_the_grid() {
    scene(STRIPS).unwrap();
    // The grid spans 0.4 mm plus a cell; a datum of 0.3 mm is inside it.
    refused(
        &STRIPS.replacen("reference_distance = 10.0", "reference_distance = 0.3", 1),
        "body1.reference_distance",
        "must be at least the extent of the grid",
    );
}

#[test]
fn a_beams_loaded_point_must_be_on_the_beam() {
    scene(&BEAM.replace(
        "second_moment = 5.0",
        "second_moment = 5.0\nloaded_point = 3.9",
    ))
    .unwrap();
    refused(
        &BEAM.replace(
            "second_moment = 5.0",
            "second_moment = 5.0\nloaded_point = 10.0",
        ),
        "body1.loaded_point",
        "is outside the beam, which is the line grid from -4 to 4",
    );
    // The default, 0, off a line from 1 to 9.
    refused(
        &BEAM.replace("start = -4.0\nend = 4.0", "start = 1.0\nend = 9.0"),
        "body1.loaded_point",
        "is outside the beam",
    );
}

#[test]
fn a_design_degree_needs_the_stations_and_is_bounded() {
    let short = BEAM.replace("n = 16", "n = 4");
    scene(&with_table(
        &short,
        "design",
        "family = \"polynomial\"\ndegree = 3",
    ))
    .unwrap();
    refused(
        &with_table(&short, "design", "family = \"polynomial\"\ndegree = 4"),
        "design.degree",
        "degree 4 needs at least 5 axial stations (distinct positions along x), the grid has 4",
    );
    refused(
        &with_table(
            &BEAM.replace("n = 16", "n = 2"),
            "design",
            "family = \"quadratic\"",
        ),
        "design.family",
        "degree 2 needs at least 3 axial stations",
    );
    refused(
        &beam_design("family = \"polynomial\"\ndegree = 13"),
        "design.degree",
        "at most 12",
    );
}

#[test]
fn design_cases_and_the_constant_are_bounded() {
    let loads: Vec<String> = (1..=11).map(|i| format!("{i}.0e4")).collect();
    let angles: Vec<String> = (0..100).map(|i| format!("{i}.0e-5")).collect();
    refused(
        &beam_design(&format!(
            "family = \"quadratic\"\nloads = [{}]\nmisalignments = [{}]",
            loads.join(", "),
            angles.join(", ")
        )),
        "design.misalignments",
        "at most 1000 design cases",
    );
    refused(
        &beam_design(&format!(
            "family = \"quadratic\"\nmisalignments = [{}, 0.0]",
            angles.join(", ")
        )),
        "design.misalignments",
        "give 1 to 100 angles",
    );
    refused(
        &beam_design("family = \"quadratic\"\nmisalignments = []"),
        "design.misalignments",
        "give 1 to 100 angles",
    );
    refused(
        &beam_design("family = \"quadratic\"\nmisalignments = [0.0, 0.2]"),
        "design.misalignments[1]",
        "at most 0.1 rad",
    );
    // An unknown name is refused by the parser, with the names it takes.
    let e = scene(&beam_design("family = \"quadratic\"\nmethod = \"newton\"")).unwrap_err();
    assert!(matches!(e, SceneError::Syntax { .. }), "{e}");
    assert!(
        e.to_string().contains(
            "`design.method`: unknown variant `newton`, expected one of `auto`, `program`, `descent`"
        ),
        "{e}"
    );
    refused(
        &beam_design(
            "family = \"circular-crown\"\nradius_range = [1.0, 100.0]\nmethod = \"descent\"",
        ),
        "design.method",
        "only for the families quadratic, polynomial and free",
    );
    scene(&beam_design("family = \"quadratic\"\nmax_constant = 1.0")).unwrap();
    refused(
        &beam_design("family = \"quadratic\"\nmax_constant = 1e308"),
        "design.max_constant",
        "at most 1e6 times the candidate zone's size",
    );
}

#[test]
fn a_stress_objective_needs_a_field_a_linear_family_and_the_descent() {
    refused(
        &beam_design("family = \"quadratic\"\nobjective = \"von-mises\""),
        "design.objective",
        "needs an elastic half-space body",
    );
    refused(
        &beam_design(
            "family = \"circular-crown\"\nradius_range = [1.0, 100.0]\nobjective = \"max-shear\"",
        ),
        "design.objective",
        "only for the families quadratic, polynomial and free",
    );
    refused(
        &with_table(
            &spheres(),
            "design",
            "family = \"quadratic\"\nmethod = \"program\"\nobjective = \"von-mises\"",
        ),
        "design.objective",
        "needs design.method = \"descent\"",
    );
    scene(&with_table(
        &spheres(),
        "design",
        "family = \"quadratic\"\nobjective = \"von-mises\"",
    ))
    .unwrap();
    scene(&beam_design(
        "family = \"quadratic\"\nobjective = \"pressure\"",
    ))
    .unwrap();
}

#[test]
fn solver_knobs_are_bounded() {
    refused(
        &with_table(&spheres(), "solver", "refinement_steps = 1000000000"),
        "solver.refinement_steps",
        "at most 20",
    );
    scene(&with_table(
        &spheres(),
        "solver",
        "refinement_steps = 20\nmax_pivots = 10000",
    ))
    .unwrap();
    refused(
        &with_table(&spheres(), "solver", "max_pivots = 1000000000"),
        "solver.max_pivots",
        "at most 100 N + 10000",
    );
}

#[test]
fn messages_name_the_field_at_fault() {
    // A modulus too small for floating point names the modulus, not the points.
    let e = scene(&spheres().replacen("youngs_modulus = 30e6", "youngs_modulus = 1e-308", 1))
        .unwrap_err();
    assert!(
        e.to_string()
            .contains("`body1.youngs_modulus` = 1e-308: must be at least 2.2e-308"),
        "{e}"
    );
    // Hertz-relative points: the condition the scene misses, not a list.
    let relative = spheres().replace("spacing = 0.002\nradius = 0.02", "across = 11\nzone = 1.2");
    scene(&relative).unwrap();
    refused(
        &relative.replace("load = 100.0", "approach = 0.0001"),
        "points",
        "need loading.load: under displacement control",
    );
    refused(
        &relative.replace(
            "model = \"uniform-patch\"\nyoungs_modulus = 30e6\npoissons_ratio = 0.3\n\n[geometry]",
            "model = \"winkler\"\nmodulus = 1e6\n\n[geometry]",
        ),
        "points",
        "the \"winkler\" model has no Hertz contact",
    );
    // No empty value or empty list in a message.
    let e = scene(&spheres().replace("radius = 0.02\n", "radius = 0.02\nnx = 3\n")).unwrap_err();
    assert!(
        e.to_string().contains("`points.nx`: is not a parameter"),
        "{e}"
    );
    let rigid = spheres().replace(
        "[body2]\nmodel = \"uniform-patch\"\nyoungs_modulus = 30e6",
        "[body2]\nmodel = \"rigid\"\nyoungs_modulus = 30e6",
    );
    let e = scene(&rigid).unwrap_err();
    assert!(
        e.to_string()
            .contains("is not a parameter of the rigid model (it takes none)"),
        "{e}"
    );
}

#[test]
fn a_grid_coarser_than_the_contact_warns() {
    assert!(scene(&spheres()).unwrap().warnings().is_empty());
    // Spacing equal to the disk radius: about two points across the Hertz
    // contact diameter (0.032 in).
    let s = scene(&spheres().replace("spacing = 0.002", "spacing = 0.02")).unwrap();
    assert_eq!(s.warnings().len(), 1, "{:?}", s.warnings());
    assert!(
        s.warnings()[0].contains("about 2 points across the Hertz contact diameter"),
        "{:?}",
        s.warnings()
    );
    // Without a closed form, the disk itself.
    let flat = spheres()
        .replace("surface1 = { shape = \"sphere\", radius = 1.0 }\n", "")
        .replace("surface2 = { shape = \"sphere\", radius = 10.0 }\n", "")
        .replace("spacing = 0.002", "spacing = 0.02");
    let s = scene(&flat).unwrap();
    assert!(
        s.warnings()
            .iter()
            .any(|w| w.contains("the candidate disk has about 3 points across")),
        "{:?}",
        s.warnings()
    );
}

#[test]
fn hetenyi_on_a_beam_that_lifts_off_carries_a_note() {
    // Example 2's beam on 8 in: every point in contact, Hetenyi's bonded
    // solution applies and no note. On 30 in the tensionless foundation
    // lets the ends lift: the note says what the errors then measure.
    let short = elcon_scene::run(&scene(BEAM).unwrap()).unwrap();
    let reference = short.result.reference.as_ref().unwrap();
    assert_eq!(reference.kind, "hetenyi-beam");
    assert_eq!(reference.note, None);
    let long = BEAM
        .replace("start = -4.0", "start = -15.0")
        .replace("end = 4.0", "end = 15.0")
        .replace("n = 16", "n = 60");
    let lifted = elcon_scene::run(&scene(&long).unwrap()).unwrap();
    assert!(lifted.solution.contact.len() < 60);
    let note = lifted
        .result
        .reference
        .as_ref()
        .unwrap()
        .note
        .clone()
        .unwrap();
    assert!(note.contains("lifted off"), "{note}");
}

#[test]
fn model_kinds_are_named_as_scenes_name_them() {
    use elcon_scene::ModelKind;
    for m in ModelKind::ALL {
        assert_eq!(ModelKind::of(m.name()), Some(m));
        assert_eq!(m.to_string(), m.name());
        assert!(!(m.is_line() && m.is_surface()));
    }
    assert_eq!(ModelKind::of("jelly"), None);
    // A scene's body reads as the kind it names.
    let s = scene(BEAM).unwrap();
    assert_eq!(s.bodies()[0].model(), ModelKind::Beam);
    assert_eq!(s.bodies()[1].model(), ModelKind::Winkler);
    assert!(s.bodies()[0].model().is_line());
}

#[test]
fn a_batch_is_told_from_a_scene_by_its_batch_table() {
    assert!(elcon_scene::is_batch_text(
        "[batch]\nscene = \"base.toml\"\n[[batch.group]]\n\"loading.load\" = [1.0]\n"
    ));
    assert!(!elcon_scene::is_batch_text(BEAM));
    assert!(!elcon_scene::is_batch_text("this is = = not toml"));
}

#[test]
fn the_spheres_of_these_tests_are_example_1s() {
    // common::SPHERES says nothing that examples/scenes/example1-spheres.toml
    // does not: each of its lines is a line of the example, comments aside.
    let example = include_str!("../../../examples/scenes/example1-spheres.toml");
    let lines: Vec<&str> = example
        .lines()
        .map(|l| l.split('#').next().unwrap_or("").trim_end())
        .collect();
    for line in common::SPHERES.lines() {
        assert!(lines.contains(&line), "`{line}` is not in the example");
    }
}
