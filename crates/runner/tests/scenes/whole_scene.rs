//! Checks of a scene as a whole: what the solve or the design would
//! otherwise refuse only once it runs (or answer meaninglessly) is refused
//! by validation, so `elcon check` and `elcon run` agree; the knobs that
//! cost time or memory are bounded; a grid too coarse for the contact
//! warns. Each message names the field.

use crate::common;
use crate::common::{BEAM, assert_warns, scene, with_table};
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
    // The line's 16 cells of 0.5 in from -4 to 4 have their points from
    // -3.75 to 3.75: a load at the last point is balanced there.
    scene(&BEAM.replace(
        "second_moment = 5.0",
        "second_moment = 5.0\nloaded_point = 3.75",
    ))
    .unwrap();
    // On the beam but past its last point: no contact force balances it
    // (the solve would end in a ray).
    refused(
        &BEAM.replace(
            "second_moment = 5.0",
            "second_moment = 5.0\nloaded_point = 3.9",
        ),
        "body1.loaded_point",
        "is outside the beam's points, not between its first and last, -3.75 and 3.75",
    );
    refused(
        &BEAM.replace(
            "second_moment = 5.0",
            "second_moment = 5.0\nloaded_point = 10.0",
        ),
        "body1.loaded_point",
        "is outside the beam's points",
    );
    // The default, 0, off a line from 1 to 9.
    refused(
        &BEAM.replace("start = -4.0\nend = 4.0", "start = 1.0\nend = 9.0"),
        "body1.loaded_point",
        "is outside the beam's points",
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
    // Spacing 0.01 in: about four points across the Hertz contact diameter
    // (0.032 in), a warning.
    let s = scene(&spheres().replace("spacing = 0.002", "spacing = 0.01")).unwrap();
    assert_eq!(s.warnings().len(), 1, "{:?}", s.warnings());
    assert!(
        s.warnings()[0].contains("about 4 points across the Hertz contact diameter"),
        "{:?}",
        s.warnings()
    );
    // A line of 3 points across the width counts 3 (its spacing is the
    // width over 2, rounded), as a disk does.
    let line = include_str!("../../../../examples/scenes/hertz-cylinders.toml");
    let across = line.lines().find(|l| l.starts_with("across")).unwrap();
    let s = scene(&line.replace(across, "across = 3")).unwrap();
    assert_warns(&s, &["about 3 points across the Hertz contact width"]);
    // Spacing equal to the disk radius: two points across, refused.
    refused(
        &spheres().replace("spacing = 0.002", "spacing = 0.02"),
        "points.spacing",
        "puts 2 point(s) across the Hertz contact diameter",
    );
    // Without a closed form, the disk itself.
    let flat = spheres()
        .replace("surface1 = { shape = \"sphere\", radius = 1.0 }\n", "")
        .replace("surface2 = { shape = \"sphere\", radius = 10.0 }\n", "")
        .replace("spacing = 0.002", "spacing = 0.02");
    let s = scene(&flat).unwrap();
    assert_warns(&s, &["the candidate disk has about 3 points across"]);
}

#[test]
fn hetenyi_on_a_beam_that_lifts_off_carries_a_note() {
    // Example 2's beam on 8 in: every point in contact, Hetenyi's bonded
    // solution applies and no note. On 30 in the tensionless foundation
    // lets the ends lift: the note says what the errors then measure.
    let short = elcon_runner::run(&scene(BEAM).unwrap()).unwrap();
    let reference = short.result.reference.as_ref().unwrap();
    assert_eq!(reference.kind, "hetenyi-beam");
    assert_eq!(reference.note, None);
    let long = BEAM
        .replace("start = -4.0", "start = -15.0")
        .replace("end = 4.0", "end = 15.0")
        .replace("n = 16", "n = 60");
    let lifted = elcon_runner::run(&scene(&long).unwrap()).unwrap();
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
    let example = include_str!("../../../../examples/scenes/example1-spheres.toml");
    let lines: Vec<&str> = example
        .lines()
        .map(|l| l.split('#').next().unwrap_or("").trim_end())
        .collect();
    for line in common::SPHERES.lines() {
        assert!(lines.contains(&line), "`{line}` is not in the example");
    }
}

#[test]
fn a_load_beyond_small_strain_is_refused() {
    // 100 lbf over the disk's 1.26e-3 in^2 strains by 5e-3 of E*; 1e4 lbf
    // by 0.48, 1e300 lbf by far more than any model describes.
    scene(&spheres()).unwrap();
    for load in ["1e4", "1e300"] {
        refused(
            &spheres().replace("load = 100.0", &format!("load = {load}")),
            "loading.load",
            "times E* = 16480000 ",
        );
    }
    // The same 100 lbf on bodies of E = 1e-300 psi.
    refused(
        &spheres().replace("youngs_modulus = 30e6", "youngs_modulus = 1e-300"),
        "loading.load",
        "beyond the small strain (at most 0.1)",
    );
}

#[test]
fn an_approach_beyond_small_strain_is_refused() {
    // The disk is 0.042 in across: 1e-4 in is 2.4e-3 of it, 0.01 in 0.24.
    scene(&spheres().replace("load = 100.0", "approach = 1e-4")).unwrap();
    for approach in ["0.01", "-0.01", "1e300"] {
        refused(
            &spheres().replace("load = 100.0", &format!("approach = {approach}")),
            "loading.approach",
            "times the candidate zone's smaller extent",
        );
    }
}

#[test]
fn a_foundation_or_a_beam_strained_beyond_small_strain_is_refused() {
    // 1000 lbf over 8 in on k = 1e-3 lbf/in per in: a compression of
    // 1.25e5 in.
    refused(
        &BEAM.replace("modulus = 1e7", "modulus = 1e-3"),
        "loading.load",
        "the foundation's mean compression",
    );
    // I = 1e-290 in^4: the beam bends by a slope of 1e287 rad.
    refused(
        &BEAM.replace("second_moment = 5.0", "second_moment = 1e-290"),
        "loading.load",
        "bends the beam",
    );
    // Each design load is bounded as the scene's own.
    scene(&beam_design(
        "family = \"quadratic\"\nloads = [500.0, 1000.0]",
    ))
    .unwrap();
    refused(
        &beam_design("family = \"quadratic\"\nloads = [1000.0, 1e12]"),
        "design.loads[1]",
        "the foundation's mean compression",
    );
}

#[test]
fn separations_beyond_the_zones_size_are_refused() {
    let values = |last: &str| {
        let mut v = vec!["0.0"; 15];
        v.push(last);
        format!("separation = [{}]", v.join(", "))
    };
    scene(&with_table(BEAM, "geometry", &values("1e-3"))).unwrap();
    refused(
        &with_table(BEAM, "geometry", &values("-1e300")),
        "geometry.separation",
        "the separation varies along x by 1e300 in, from -1e300 at x = 3.75",
    );
}

#[test]
fn curvatures_that_cancel_to_rounding_are_refused() {
    scene(&spheres().replace("radius = 10.0 }", "radius = -10.0 }")).unwrap();
    refused(
        &spheres().replace("radius = 10.0 }", "radius = -1.0000000000001 }"),
        "geometry.surface2.radius",
        "geometry.surface1's radius along x is 1 and geometry.surface2's -1.0000000000001",
    );
    // Exactly conforming: no gap at all.
    refused(
        &spheres().replace("radius = 10.0 }", "radius = -1.0 }"),
        "geometry.surface2.radius",
        "cancels the other surface",
    );
    // Turned 45 degrees, the radius along x is twice the one written; the
    // message quotes the value as the file writes it.
    let turned = |r: &str| format!("{{ shape = \"quadric\", radius_x = {r}, angle = 45.0 }}");
    refused(
        &spheres()
            .replace("{ shape = \"sphere\", radius = 1.0 }", &turned("3.0"))
            .replace("{ shape = \"sphere\", radius = 10.0 }", &turned("-3.0")),
        "geometry.surface2.radius_x",
        "` = -3: cancels the other surface",
    );
}

#[test]
fn a_quadrics_angle_is_bounded() {
    let quadric = |angle: &str| {
        spheres().replace(
            "surface2 = { shape = \"sphere\", radius = 10.0 }",
            &format!(
                "surface2 = {{ shape = \"quadric\", radius_x = 10.0, radius_y = 20.0, angle = {angle} }}"
            ),
        )
    };
    scene(&quadric("-30.0")).unwrap();
    for angle in ["400.0", "1e300"] {
        refused(
            &quadric(angle),
            "geometry.surface2.angle",
            "must be within -360 to 360 degrees",
        );
    }
}

/// A roller on an absolute 11 x 8 grid (0.4 mm by 10 mm, 1000 N) with a
/// `[design]` table of `lines`.
fn roller_design(lines: &str) -> String {
    with_table(
        &common::roller("half_x = 0.2\nhalf_y = 5.0\nnx = 11\nny = 8", "1000.0"),
        "design",
        lines,
    )
}

#[test]
fn a_log_crowns_flat_part_is_shorter_than_the_roller() {
    let log = "family = \"logarithmic-crown\"\naxis = \"y\"\n";
    scene(&roller_design(&format!("{log}flat_length = 4.0"))).unwrap();
    let text = roller_design(&format!("{log}flat_length = 20.0"));
    refused(&text, "design.flat_length", "must be in [0, length)");
    // Located at the key, as every refusal of check is.
    let m = scene(&text).unwrap_err().to_string();
    assert!(m.starts_with("test.toml:"), "{m}");
}

#[test]
fn design_max_points_admits_the_verifying_grid() {
    let free = "family = \"free\"\naxis = \"y\"\n";
    // 88 points on the scene's grid, 352 on the second (h / 2).
    scene(&roller_design(&format!("{free}max_points = 352"))).unwrap();
    refused(
        &roller_design(&format!("{free}max_points = 5")),
        "design.max_points",
        "the largest load case has 352 points on the second grid",
    );
}

#[test]
fn a_punch_that_does_not_press_has_a_note_not_a_reference() {
    let punch = |approach: &str| {
        common::sphere_on_rigid_plane("spacing = 0.002\nradius = 0.02")
            .replace("surface1 = { shape = \"sphere\", radius = 1.0 }\n", "")
            .replace("load = 100.0", &format!("approach = {approach}"))
    };
    let pressed = scene(&punch("1e-5")).unwrap();
    assert_eq!(pressed.reference().map(|r| r.kind()), Some("flat-punch"));
    for (approach, word) in [("-1e-5", "tensile"), ("0.0", "zero")] {
        let s = scene(&punch(approach)).unwrap();
        assert!(s.reference().is_none(), "{approach}");
        assert!(
            s.warnings()
                .iter()
                .any(|w| w.starts_with("no flat-punch reference") && w.contains(word)),
            "{approach}: {:?}",
            s.warnings()
        );
    }
}

#[test]
fn every_example_scene_passes_check() {
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples/scenes");
    let mut checked = 0;
    for entry in std::fs::read_dir(&dir).unwrap().flatten() {
        let path = entry.path();
        if path.extension().is_none_or(|x| x != "toml") {
            continue;
        }
        let text = std::fs::read_to_string(&path).unwrap();
        if elcon_scene::is_batch_text(&text) {
            let batch = elcon_scene::Batch::from_file(&path).unwrap();
            for i in 0..batch.len() {
                let run = batch.run(i).unwrap();
                if let Err(e) = batch.scene(&run) {
                    panic!("{}: run {i}: {e}", path.display());
                }
            }
        } else if elcon_scene::is_bearing_text(&text) {
            // A bearing scene: its own reader and estimate.
            let bearing = elcon_scene::BearingScene::from_file(&path)
                .unwrap_or_else(|e| panic!("{}: {e}", path.display()));
            let estimate = elcon_runner::BearingEstimate::of(&bearing);
            assert!(estimate.peak_bytes > 0 && estimate.zones > 0);
        } else if let Err(e) = elcon_scene::Scene::from_file(&path) {
            panic!("{e}");
        }
        checked += 1;
    }
    assert!(checked >= 10, "{checked} example scenes");
}

#[test]
fn a_height_map_does_not_let_a_concave_surface_through() {
    // The rough sphere with its sphere made concave against the plane: the
    // height map's departures do not change the quadrics' interpenetration.
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples/scenes");
    let text = std::fs::read_to_string(dir.join("rough-sphere.toml"))
        .unwrap()
        .replace(
            "file = \"data/rough-surface.npy\"",
            &format!("file = {:?}", dir.join("data/rough-surface.npy")),
        );
    scene(&text).unwrap();
    let concave = text.replace(
        "surface1 = { shape = \"sphere\", radius = 10.0 }",
        "surface1 = { shape = \"sphere\", radius = -10.0 }",
    );
    assert_ne!(concave, text);
    refused(
        &concave,
        "geometry.surface1.radius",
        "a concave surface must have the larger radius: against a plane",
    );
}

#[test]
fn a_reference_tilt_within_rounding_of_zero_has_no_relative_error() {
    let tilted = |moment: &str| {
        let s = scene(&spheres().replace(
            "load = 100.0",
            &format!("load = 100.0\nmoment_x = {moment}"),
        ))
        .unwrap();
        elcon_runner::run(&s).unwrap().result.reference.unwrap()
    };
    let r = tilted("-1e-300");
    assert_eq!(r.errors.tilt_x, None);
    assert!(
        r.note.as_deref().unwrap().contains("tilt_x"),
        "{:?}",
        r.note
    );
    // A moment that moves the centre by a resolvable fraction of the
    // contact is compared.
    let r = tilted("-0.1");
    assert!(r.errors.tilt_x.unwrap().abs() < 0.5, "{:?}", r.errors);
    assert_eq!(r.note, None);
}

#[test]
fn a_huge_contact_s_extent_and_errors_are_finite() {
    // A sphere of radius 1e240 on a plane: a contact radius near 1e78 and
    // pressures near 1e-155, whose squares underflow (a radius of 1e301,
    // pressures near 1e-196, is refused by check: its influence
    // coefficients times the squared residuals underflow too).
    let s = scene(
        &common::spheres("across = 11\nzone = 1.4")
            .replace("surface1 = { shape = \"sphere\", radius = 1.0 }\n", "")
            .replace("radius = 10.0 }", "radius = 1e240 }"),
    )
    .unwrap();
    let r = elcon_runner::run(&s).unwrap().result;
    assert!(r.contact_extent.is_finite(), "{}", r.contact_extent);
    let reference = r.reference.unwrap();
    assert!(
        reference.errors.contact_extent.unwrap().abs() < 0.05,
        "{:?}",
        reference.errors
    );
    assert!(reference.errors.pressure_l2.unwrap().is_finite());
}
