//! The pressure plot: a map with the contact's boundary and a colour bar for
//! a surface whose pressure is not a function of the radius, pressure
//! against the radius with the closed form for one that is.

use std::path::Path;

use crate::common;
use crate::common::with_table;
use elcon_runner::run;
use elcon_scene::{Plot, Scene};

/// A roller (cylinder on a plane) on a 9 x 12 rectangle: not axisymmetric.
fn roller() -> String {
    let roller = common::roller("zone = 1.6\nhalf_y = 5.0\nnx = 9\nny = 12", "5000.0");
    with_table(&roller, "outputs", "plots = [\"pressure\"]")
}

/// Example 1's spheres, 11 across: axisymmetric.
fn spheres() -> String {
    let spheres = common::spheres("across = 11\nzone = 1.2");
    with_table(&spheres, "outputs", "plots = [\"pressure\"]")
}

fn pressure_svg(text: &str) -> (String, usize, usize) {
    let scene = Scene::from_str(Path::new("plot.toml"), text).unwrap();
    assert_eq!(scene.outputs().plots(), vec![Plot::Pressure]);
    let r = run(&scene).unwrap();
    // Each call its own directory: the tests run in parallel, and their
    // scenes share a name.
    static CALLS: std::sync::atomic::AtomicUsize = std::sync::atomic::AtomicUsize::new(0);
    let call = CALLS.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
    let dir = std::env::temp_dir().join(format!(
        "elcon-plots-{}-{call}-{}",
        std::process::id(),
        scene.name()
    ));
    let written = elcon_report::write_run(&r, &dir).unwrap();
    let svg = std::fs::read_to_string(written.join("pressure.svg")).unwrap();
    let contact = r.solution.contact.len();
    let points = r.problem.points().len();
    let _ = std::fs::remove_dir_all(&dir);
    (svg, points, contact)
}

#[test]
fn a_roller_gets_a_pressure_map_with_its_boundary_and_a_colour_bar() {
    let (svg, points, contact) = pressure_svg(&roller());
    assert!(svg.contains("pressure map"), "the map's caption");
    assert!(svg.contains("contact boundary"), "the boundary's legend");
    assert!(svg.contains("pressure (MPa)"), "the colour bar's label");
    assert!(svg.contains("along x, at y =") && svg.contains("along y, at x ="));
    // One rectangle per cell (a grid this small is drawn cell by cell) and
    // a hundred for the colour bar, besides the frames.
    let rects = svg.matches("<rect").count();
    assert!(
        rects >= points + 100,
        "{rects} rectangles for {points} cells"
    );
    // The boundary: black faces of width 2, at least four (a closed outline)
    // and at most four per cell in contact.
    let faces = svg
        .matches(r##"stroke="#000000" stroke-width="2""##)
        .count();
    assert!(
        faces >= 4 && faces <= 4 * contact + 1,
        "{faces} faces, {contact} cells in contact"
    );
}

#[test]
fn axisymmetric_spheres_keep_pressure_against_the_radius() {
    let (svg, ..) = pressure_svg(&spheres());
    assert!(!svg.contains("pressure map"));
    assert!(svg.contains("radius (in)"));
    assert!(svg.contains("hertz-spheres"), "the closed form's legend");
}

/// A misaligned roller of 10,400 points, more than 512 cells along x
/// (MAX_DRAWN = 256): its map is drawn in 174 x 7 blocks of 3 x 3 cells,
/// each its largest pressure. Any grid is drawn in at most 256 x 256 blocks, about
/// 90 bytes each: under 6 MB.
#[test]
fn a_large_grid_s_map_is_drawn_in_blocks_of_bounded_size() {
    let roller = common::roller("zone = 1.6\nhalf_y = 5.0\nnx = 520\nny = 20", "10000.0")
        .replace("load = 10000.0", "load = 10000.0\ntilt_x = 2e-4");
    let text = with_table(
        &with_table(&roller, "outputs", "plots = [\"pressure\"]"),
        "solver",
        "method = \"conjugate-gradient\"\nerror_estimate = false",
    );
    let (svg, points, _) = pressure_svg(&text);
    assert_eq!(points, 10_400);
    assert!(
        svg.contains("pressure map (174 x 7 blocks of 3 x 3 cells, each its largest)"),
        "the caption says how the map is drawn: {}",
        &svg[svg.find("pressure map").unwrap_or(0)..][..80]
    );
    let rects = svg.matches("<rect").count();
    assert!(rects <= 174 * 7 + 100 + 10, "{rects} rectangles");
    assert!(svg.len() < 400_000, "{} bytes", svg.len());
}
