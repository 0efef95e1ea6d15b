//! The scenes the tests of elcon-scene start from, each written once; a test
//! makes the variant it needs by a visible edit of one of them (a
//! `replace`, or a table appended). Example 1's spheres and the beam are
//! the files spheres.toml and beam.toml beside this one (estimate.rs's unit
//! tests read them too).
//!
//! Each text starts with a blank line, so its first table is on line 2: the
//! tests that expect a message at a line and column count the lines of
//! these texts (`whole_scene.rs`, `errors.rs`). An edit here moves them.

#![allow(dead_code)]

use std::path::Path;

use elcon_report::Errors;
use elcon_scene::{Scene, SceneError};

/// `text` read as the scene file `test.toml`.
pub fn scene(text: &str) -> Result<Scene, SceneError> {
    Scene::from_str(Path::new("test.toml"), text)
}

/// Conry & Seireg's Example 1 as examples/scenes/example1-spheres.toml has
/// it, without its comments and optional tables: two steel spheres (R1 =
/// 1 in, R2 = 10 in) on Love patches under 100 lbf, on a disk of 41 points
/// across the Hertz diameter reaching 1.15 Hertz radii ([`EXAMPLE1_GRID`]).
pub const SPHERES: &str = include_str!("spheres.toml");

/// The lines of [`SPHERES`]'s disk grid after `grid = "disk"`.
pub const EXAMPLE1_GRID: &str = "across = 41\nzone = 1.15";

/// [`SPHERES`] on the disk grid `grid` (its lines after `grid = "disk"`,
/// e.g. `"spacing = 0.002\nradius = 0.02"`).
pub fn spheres(grid: &str) -> String {
    SPHERES.replace(EXAMPLE1_GRID, grid)
}

/// Example 1's first sphere (R = 1 in) on a rigid plane: [`spheres`] with
/// body 2 `"rigid"` and no second surface (a plane by default).
pub fn sphere_on_rigid_plane(grid: &str) -> String {
    spheres(grid)
        .replace(
            "[body2]\nmodel = \"uniform-patch\"\nyoungs_modulus = 30e6\npoissons_ratio = 0.3\n",
            "[body2]\nmodel = \"rigid\"\n",
        )
        .replace("surface2 = { shape = \"sphere\", radius = 10.0 }\n", "")
}

/// A steel beam (E = 30e6 psi, I = 5 in^4) on a tensionless Winkler
/// foundation (1e7 lbf/in per in), a line of 16 points from -4 in to 4 in,
/// 1000 lbf at x = 0.
pub const BEAM: &str = include_str!("beam.toml");

/// The paper's Example 2 (examples/scenes/example2-beam-design.toml):
/// [`BEAM`] as a section 1 in wide and 4 in deep, 8.9 in long on a line of
/// `n` points, under 50,000 lbf.
pub fn example2_beam(n: usize) -> String {
    BEAM.replace("second_moment = 5.0", "width = 1.0\ndepth = 4.0")
        .replace(
            "start = -4.0\nend = 4.0\nn = 16",
            &format!("start = -4.45\nend = 4.45\nn = {n}"),
        )
        .replace("load = 1000.0", "load = 50000.0")
}

/// A steel roller (R = 5 mm, its axis along y) on a steel plane, both on
/// Love patches, on the rectangle grid `grid` (its lines after `grid =
/// "rectangle"`) under `load` N; units mm, N, MPa.
pub fn roller(grid: &str, load: &str) -> String {
    format!(
        r#"
[units]
length = "mm"
force = "N"
pressure = "MPa"

[body1]
model = "uniform-patch"
youngs_modulus = 210e3
poissons_ratio = 0.3

[body2]
model = "uniform-patch"
youngs_modulus = 210e3
poissons_ratio = 0.3

[geometry]
surface1 = {{ shape = "cylinder", radius = 5.0 }}

[points]
grid = "rectangle"
{grid}

[loading]
load = {load}
"#
    )
}

/// `scene` with the table `[name]` of `lines` appended.
pub fn with_table(scene: &str, name: &str, lines: &str) -> String {
    format!("{scene}\n[{name}]\n{lines}\n")
}

/// Asserts that one of `scene`'s warnings says each of `parts`.
#[track_caller]
pub fn assert_warns(scene: &Scene, parts: &[&str]) {
    assert!(
        scene
            .warnings()
            .iter()
            .any(|w| parts.iter().all(|p| w.contains(p))),
        "{parts:?}: {:?}",
        scene.warnings()
    );
}

/// Asserts that each relative error of an elliptical reference, the
/// approach's, the peak's and the semi-axes' (major, then minor), is
/// within its bound of `bounds` in size.
#[track_caller]
pub fn assert_ellipse_errors(e: &Errors, bounds: [f64; 4]) {
    let errors = [e.approach, e.max_pressure, e.semi_major, e.semi_minor];
    let names = ["approach", "max_pressure", "semi_major", "semi_minor"];
    for ((name, error), bound) in names.iter().zip(errors).zip(bounds) {
        assert!(error.unwrap().abs() < bound, "{name}: {e:?}");
    }
}
