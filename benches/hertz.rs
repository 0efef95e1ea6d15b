//! The benchmark problem and the benchmark sizes, in one place (read by
//! benches/scaling.rs, benches/large.rs, examples/scaling_probe.rs and
//! examples/peers_compare.rs, like faer's bench list).
//!
//! Conry & Seireg's Example 1 (steel spheres, R = 1 in and 10 in, P = 100
//! lb) on Love patches: a square grid clipped to the disk r <= 1.3 a (a the
//! Hertz radius), the spacing chosen so the disk holds close to the asked
//! number of points. Solved in full (not folded by its symmetry): the
//! subject is how the engine's cost grows with the size of its problem.

#![allow(dead_code)]

// Example 1's data, as the analysis tests have it; the path is relative to
// this file's directory.
#[path = "../crates/analysis/tests/common/scenes.rs"]
mod scenes;

pub use scenes::Build;

use elcon::analysis::references::HertzSpheres;
use elcon::analysis::{ContactProblem, Geometry, Loading};
use elcon::influence::{Body, PointSet};

/// The sizes the scaling benchmark runs (candidate points N, approximately).
pub const SIZES: [usize; 7] = [64, 128, 256, 512, 1024, 2048, 4096];

/// The Hertz solution of the benchmark problem.
pub fn reference() -> HertzSpheres {
    scenes::example1_hertz()
}

/// The Hertz radius of the benchmark problem (in).
pub fn hertz_radius() -> f64 {
    reference().contact_radius()
}

/// The candidate points: the grid in the disk r <= 1.3 a whose number of
/// points is closest to `n`.
pub fn points(n: usize) -> PointSet {
    let zone = 1.3 * hertz_radius();
    // pi m^2 points for m cells per zone radius; try the neighbours of the estimate.
    let m0 = (n as f64 / std::f64::consts::PI).sqrt().round().max(1.0) as usize;
    (m0.saturating_sub(2).max(1)..=m0 + 2)
        .map(|m| PointSet::grid_disk(zone / m as f64, zone).expect("a disk grid"))
        .min_by_key(|p| p.len().abs_diff(n))
        .expect("candidates")
}

/// The two bodies (Love patches, steel) and the sphere-on-sphere geometry.
pub fn bodies() -> (Body, Geometry) {
    scenes::example1_bodies()
}

/// The benchmark problem of about `n` points, in full.
pub fn problem(n: usize) -> ContactProblem {
    held(ContactProblem::new, points(n))
}

/// The benchmark problem at `points`, S held as `build` holds it
/// (`ContactProblem::new`, dense, or `ContactProblem::lattice`,
/// matrix-free).
pub fn held(build: Build, points: PointSet) -> ContactProblem {
    scenes::example1(build, points, Loading::load(100.0)).expect("the benchmark problem")
}
