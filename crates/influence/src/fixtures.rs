//! Point sets, beams and thread pools shared by the crate's unit tests
//! (no equation: inputs that several modules' tests build alike).

use crate::models::Beam;
use crate::points::{Cell, Dimension, PointSet};

/// Points at `(xs[k], ys[k])` on square cells of side `h` (a surface set).
pub(crate) fn surface(xs: Vec<f64>, ys: Vec<f64>, h: f64) -> PointSet {
    PointSet::from_points(Dimension::Surface, xs, ys, Cell::square(h)).unwrap()
}

/// A disk of unit cells, radius 40, in lattice-row order (a lattice
/// operator writes its rows in parallel), and the same points reversed
/// (their rows' values gathered on the caller's thread): what the tests
/// of results the same to the bit on any number of threads run on.
pub(crate) fn disk_and_reversed() -> [(&'static str, PointSet); 2] {
    let disk = PointSet::grid_disk(1.0, 40.0).unwrap();
    let (xs, ys): (Vec<f64>, Vec<f64>) = (0..disk.len())
        .rev()
        .map(|k| (disk.x(k), disk.y(k)))
        .unzip();
    let reversed = surface(xs, ys, 1.0);
    [("disk", disk), ("reversed", reversed)]
}

/// A rayon pool of `threads` threads.
pub(crate) fn pool(threads: usize) -> rayon::ThreadPool {
    rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .unwrap()
}

/// Three points on no lattice of their cells of side 0.1.
pub(crate) fn scattered() -> PointSet {
    surface(vec![0.0, 0.13, 0.5], vec![0.0, 0.02, 0.31], 0.1)
}

/// Two points 1000 cells apart: a lattice far sparser than its box.
pub(crate) fn sparse_pair() -> PointSet {
    surface(vec![0.0, 1000.0], vec![0.0, 0.0], 1.0)
}

/// A beam of E I = 3e4 loaded at x0 = 0.
pub(crate) const BEAM: Beam = Beam {
    youngs_modulus: 1.0e4,
    second_moment: 3.0,
    loaded_point: 0.0,
};

/// A beam of unit E and I loaded at x0 = 0.
pub(crate) const UNIT_BEAM: Beam = Beam {
    youngs_modulus: 1.0,
    second_moment: 1.0,
    loaded_point: 0.0,
};
