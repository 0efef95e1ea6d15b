//! A scene's sections one at a time (elcon-scene's `problem_parts`,
//! `design_over`, `scene_with_design`: what the Python package calls),
//! each checked by the scene's own parser and checks, naming the field.

use std::path::Path;

use elcon_analysis::{Body, ContactProblem, Geometry, Loading, Material, Surface};
use elcon_design::Roller;
use elcon_influence::PointSet;
use elcon_scene::{DesignFamily, RelativeTo, design_over, problem_parts, scene_with_design};

fn file() -> &'static Path {
    Path::new("<parts>")
}

fn line_points() -> PointSet {
    PointSet::line(-1.0, 1.0, 8).unwrap()
}

/// `text` under a load of 1.
fn loaded(text: &str) -> String {
    format!("{text}[loading]\nload = 1.0\n")
}

#[test]
fn the_loading_is_the_scenes_with_its_rotation_bound() {
    let parts = problem_parts(file(), &loaded(""), Some(line_points())).unwrap();
    assert_eq!(parts.loading, Loading::load(1.0));
    let text = "[loading]\nload = 2.0\ntilt_x = 0.01\nmoment_y = 3.0\n";
    let parts = problem_parts(file(), text, Some(line_points())).unwrap();
    assert_eq!(
        parts.loading,
        Loading::load(2.0).with_tilt_x(0.01).with_moment_y(3.0)
    );
    let e = problem_parts(file(), "[loading]\nload = 1.0\ntilt_x = 0.5\n", None).unwrap_err();
    assert!(
        e.to_string()
            .contains("`loading.tilt_x` = 0.5: at most 0.1 rad in size"),
        "{e}"
    );
    let e = problem_parts(file(), "[loading]\nmoment_x = 0.0\n", None).unwrap_err();
    assert!(e.to_string().contains("give exactly one of load"), "{e}");
    let e = problem_parts(file(), "", Some(line_points())).unwrap_err();
    assert!(e.to_string().contains("`loading` = (missing)"), "{e}");
}

#[test]
fn a_body_is_checked_by_the_scenes_body_parser_naming_the_field() {
    let text = "[body1]\nmodel = \"beam\"\nyoungs_modulus = -30e6\nsecond_moment = 1.0\n\
                [body2]\nmodel = \"winkler\"\nmodulus = 1e7\n";
    let e = problem_parts(file(), &loaded(text), Some(line_points())).unwrap_err();
    assert!(e.is_input_error());
    assert!(
        e.to_string()
            .contains("`body1.youngs_modulus` = -30000000: must be > 0"),
        "{e}"
    );
    let text = "[body1]\nmodel = \"winkler\"\nmodulus = 1e7\nloaded_pt = 3.0\n\
                [body2]\nmodel = \"rigid\"\n";
    let e = problem_parts(file(), &loaded(text), Some(line_points())).unwrap_err();
    assert!(e.to_string().contains("unknown field `loaded_pt`"), "{e}");
    let text = "[body1]\nmodel = \"winkler\"\nmodulus = 1e7\n";
    let e = problem_parts(file(), &loaded(text), Some(line_points())).unwrap_err();
    assert!(e.to_string().contains("`body2` = (missing)"), "{e}");
}

#[test]
fn surfaces_and_a_layout_are_the_scenes_sections() {
    let text = "[body1]\nmodel = \"uniform-patch\"\nyoungs_modulus = 30e6\n\
                poissons_ratio = 0.3\n[body2]\nmodel = \"rigid\"\n\
                [geometry]\nsurface1 = { shape = \"sphere\", radius = 1.0 }\n\
                [points]\ngrid = \"disk\"\nspacing = 0.01\nradius = 0.05\n";
    let parts = problem_parts(file(), &loaded(text), None).unwrap();
    assert_eq!(parts.points, PointSet::grid_disk(0.01, 0.05).unwrap());
    assert_eq!(
        parts.geometry,
        Some(Geometry::Surfaces(
            Surface::Sphere { radius: 1.0 },
            Surface::Plane
        ))
    );
    assert!(parts.bodies.is_some() && parts.points_spec.is_some());
    // A sphere on a line, as a scene refuses it.
    let text = "[geometry]\nsurface1 = { shape = \"sphere\", radius = 1.0 }\n";
    let e = problem_parts(file(), &loaded(text), Some(line_points())).unwrap_err();
    assert!(
        e.to_string()
            .contains("`geometry.surface1.shape` = \"sphere\""),
        "{e}"
    );
}

#[test]
fn a_design_over_problems_is_checked_against_their_kind() {
    let bed = Body::winkler(1e7);
    let rigid = Body::rigid();
    let flat = Geometry::Surfaces(Surface::Plane, Surface::Plane);
    let line = ContactProblem::new(line_points(), &rigid, &bed, &flat, Loading::load(1.0)).unwrap();
    let steel = Body::uniform_patch(Material::new(30e6, 0.3).unwrap());
    let sphere = Geometry::Surfaces(Surface::Sphere { radius: 1.0 }, Surface::Plane);
    let surface = ContactProblem::new(
        PointSet::grid_disk(0.01, 0.05).unwrap(),
        &steel,
        &steel,
        &sphere,
        Loading::load(1.0),
    )
    .unwrap();
    let free = "[design]\nfamily = \"free\"\n";
    let spec = design_over(file(), free, std::slice::from_ref(&line), None, None).unwrap();
    assert_eq!(spec.axis(), elcon_design::Axis::X);
    let e = design_over(file(), free, &[line.clone(), surface], None, None).unwrap_err();
    assert!(e.to_string().contains("`problems[1]`: is a surface"), "{e}");
    let along_y = "[design]\nfamily = \"free\"\naxis = \"y\"\n";
    let e = design_over(file(), along_y, std::slice::from_ref(&line), None, None).unwrap_err();
    assert!(
        e.to_string()
            .contains("`design.axis` = \"y\": a line grid lies along x"),
        "{e}"
    );
    let loads = "[design]\nfamily = \"free\"\nloads = [1.0]\n";
    let e = design_over(file(), loads, std::slice::from_ref(&line), None, None).unwrap_err();
    assert!(e.to_string().contains("`design.loads`"), "{e}");
    let log = "[design]\nfamily = \"logarithmic-crown\"\n";
    let e = design_over(file(), log, std::slice::from_ref(&line), None, None).unwrap_err();
    assert!(e.to_string().contains("set for a roller"), "{e}");
    // A roller given with the design (Python's `roller=`) is named by
    // its own key, not by the scene's grid it was not derived from.
    let roller = Roller {
        combined_modulus: 30e6,
        radius: 1.0,
        length: 8.9,
    };
    let heavy = "[design]\nfamily = \"logarithmic-crown\"\ndesign_load = 1e12\n";
    let e = design_over(
        file(),
        heavy,
        std::slice::from_ref(&line),
        None,
        Some(roller),
    )
    .unwrap_err()
    .to_string();
    assert!(e.contains("`design.design_load`"), "{e}");
    assert!(e.contains("roller.length") && !e.contains("half_y"), "{e}");
}

#[test]
fn a_scenes_design_is_replaced_whole() {
    let path =
        Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples/scenes/crowned-roller.toml");
    let text = std::fs::read_to_string(&path).unwrap();
    let log = "[design]\nfamily = \"logarithmic-crown\"\nloads = [1000.0, 10000.0]\n\
               axis = \"y\"\n";
    let scene = scene_with_design(&path, &text, log).unwrap();
    let spec = scene.design().unwrap();
    assert!(matches!(
        spec.family(),
        DesignFamily::LogarithmicCrown { .. }
    ));
    assert_eq!(spec.loads(), &[1000.0, 10000.0]);
    assert_eq!(scene.name(), "crowned-roller");
    // The scene's own [design] is gone: its relative_to with it.
    assert_eq!(spec.relative_to(), RelativeTo::Absolute);
    let e = scene_with_design(&path, &text, "[design]\nfamily = \"cubic\"\n").unwrap_err();
    assert!(e.to_string().contains("unknown variant `cubic`"), "{e}");
}

#[test]
fn a_beam_s_listed_points_are_a_line_grid_sorted_and_evenly_spaced() {
    use elcon_influence::{Cell, Dimension};
    let beam = "[body1]\nmodel = \"beam\"\nyoungs_modulus = 30e6\nsecond_moment = 5.0\n\
                [body2]\nmodel = \"winkler\"\nmodulus = 1e7\n";
    let h = 8.9 / 80.0;
    let even: Vec<f64> = (0..80).map(|k| (k as f64 + 0.5) * h - 4.45).collect();
    let listed = |xs: Vec<f64>| {
        PointSet::from_points(Dimension::Line, xs, Vec::new(), Cell { dx: h, dy: 1.0 }).unwrap()
    };
    // Evenly spaced at the spacing, as grid = "line" lays them out.
    problem_parts(file(), &loaded(beam), Some(listed(even.clone()))).unwrap();
    // Uneven: the first step that is not the spacing is named.
    let mut uneven = even.clone();
    uneven[40] += 0.3 * h;
    let e = problem_parts(file(), &loaded(beam), Some(listed(uneven)))
        .unwrap_err()
        .to_string();
    assert!(e.contains("`points` = x[40]"), "{e}");
    assert!(e.contains("not the spacing"), "{e}");
    assert!(e.contains("a line grid"), "{e}");
    // Unsorted: named as such, not as a loaded point off the beam.
    let mut unsorted = even.clone();
    unsorted.swap(3, 4);
    let e = problem_parts(file(), &loaded(beam), Some(listed(unsorted)))
        .unwrap_err()
        .to_string();
    assert!(e.contains("x[4]") && e.contains("is not above x[3]"), "{e}");
    assert!(!e.contains("loaded_point"), "{e}");
    let reversed: Vec<f64> = even.iter().rev().copied().collect();
    let e = problem_parts(file(), &loaded(beam), Some(listed(reversed)))
        .unwrap_err()
        .to_string();
    assert!(e.contains("is not above"), "{e}");
}
