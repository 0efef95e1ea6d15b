//! Quadric surfaces and elliptical Hertz contacts in scenes: the
//! ball-bearing example against Hertz's elliptical solution, the circular
//! limit against today's spheres, and the refusals of bad quadrics.

use std::path::Path;

use crate::common::{SPHERES, assert_ellipse_errors, scene, spheres};
use elcon_runner::run;
use elcon_scene::{Scene, SceneError};

#[test]
fn the_ball_bearing_example_meets_hertz_s_ellipse() {
    let file =
        Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples/scenes/ball-bearing.toml");
    let r = run(&Scene::from_file(&file).unwrap()).unwrap();
    let reference = r.result.reference.as_ref().unwrap();
    assert_eq!(reference.kind, "hertz-ellipse");
    // The ellipse lies along y (the groove's direction): a / b = 9.34.
    let [a, b] = reference.semi_axes.unwrap();
    assert!((a / b - 9.34).abs() < 0.01, "{a} {b}");
    assert_eq!(reference.angle, Some(90.0));
    // Measured at 31 points across each axis: approach -3.7e-5, peak
    // +3.7e-4, semi-axes (the pressure's moments, converging as h^2)
    // +1.8e-3 and +2.5e-3 (docs/validation.md §2b). Bounds three times
    // those.
    assert_ellipse_errors(&reference.errors, [1.2e-4, 1.2e-3, 5.5e-3, 7.5e-3]);
}

#[test]
fn equal_radii_reproduce_the_spheres_reference() {
    // Example 1 on an absolute disk, the second sphere written as a
    // quadric of equal radii: the elliptical reference at e = 0 is the
    // spheres' to rounding, and the runs are the same problem.
    let grid = "spacing = 0.0008\nradius = 0.0185";
    let sphere = run(&scene(&spheres(grid)).unwrap()).unwrap();
    let quadric_text = spheres(grid).replace(
        "surface2 = { shape = \"sphere\", radius = 10.0 }",
        "surface2 = { shape = \"quadric\", radius_x = 10.0, radius_y = 10.0, angle = 30.0 }",
    );
    let quadric = run(&scene(&quadric_text).unwrap()).unwrap();
    let (rs, rq) = (
        sphere.result.reference.as_ref().unwrap(),
        quadric.result.reference.as_ref().unwrap(),
    );
    assert_eq!(
        (rs.kind.as_str(), rq.kind.as_str()),
        ("hertz-spheres", "hertz-ellipse")
    );
    let close = |x: f64, y: f64| (x / y - 1.0).abs() < 1e-13;
    assert!(close(rq.approach.unwrap(), rs.approach.unwrap()));
    assert!(close(rq.max_pressure.unwrap(), rs.max_pressure.unwrap()));
    assert!(close(
        rq.contact_extent.unwrap(),
        rs.contact_extent.unwrap()
    ));
    // The turned form's rounding (1e-16 of the curvature) moves the
    // separations by as little: the approach agrees to 1e-12.
    let (s, q) = (&sphere.result.solution, &quadric.result.solution);
    assert!((q.approach / s.approach - 1.0).abs() < 1e-12);
}

#[test]
fn an_ellipse_grid_lays_out_the_ellipse_s_extents() {
    // A sphere on a cylinder crossed with it: ellipse grid of 11 across,
    // zone 1.3: 2 round(1.3 * 5) + 1 = 15 cells each way.
    let text = spheres("across = 11\nzone = 1.3")
        .replace("grid = \"disk\"", "grid = \"ellipse\"")
        .replace(
            "surface2 = { shape = \"sphere\", radius = 10.0 }",
            "surface2 = { shape = \"quadric\", radius_x = 10.0 }",
        );
    let s = scene(&text).unwrap();
    assert_eq!(s.points().len(), 15 * 15);
    assert_eq!(s.reference().map(|r| r.kind()), Some("hertz-ellipse"));
}

/// The field an invalid scene names.
fn field(text: &str) -> String {
    match scene(text) {
        Err(SceneError::Invalid { field, .. }) => field,
        other => panic!("{other:?}"),
    }
}

#[test]
fn bad_quadrics_are_refused_by_field() {
    let with = |surface: &str| {
        SPHERES.replace("surface2 = { shape = \"sphere\", radius = 10.0 }", surface)
    };
    assert_eq!(
        field(&with(
            "surface2 = { shape = \"quadric\", radius_x = 0.0, radius_y = 1.0 }"
        )),
        "geometry.surface2.radius_x"
    );
    assert_eq!(
        field(&with(
            "surface2 = { shape = \"quadric\", radius = 1.0, radius_y = 1.0 }"
        )),
        "geometry.surface2.radius"
    );
    assert_eq!(
        field(&with("surface2 = { shape = \"quadric\" }")),
        "geometry.surface2.radius_x"
    );
    assert_eq!(
        field(&with(
            "surface2 = { shape = \"sphere\", radius = 10.0, angle = 3.0 }"
        )),
        "geometry.surface2.angle"
    );
    // A groove tighter than the ball at 45 degrees: the gap is a saddle.
    assert_eq!(
        field(&with(
            "surface2 = { shape = \"quadric\", radius_x = 5.0, radius_y = -0.9, angle = 45.0 }"
        )),
        "geometry"
    );
    // An ellipse grid between planes has no Hertz ellipse to size it.
    let planes = SPHERES
        .replace("grid = \"disk\"", "grid = \"ellipse\"")
        .replace("surface1 = { shape = \"sphere\", radius = 1.0 }\n", "")
        .replace("surface2 = { shape = \"sphere\", radius = 10.0 }\n", "");
    assert_eq!(field(&planes), "points");
}
