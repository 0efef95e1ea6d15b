//! The boundary flags of a set: which sides of each point are open, i.e.
//! hold no point in the adjacent cell,
//!
//! ```text
//!     open along x = no point at (x + dx, y) or (x - dx, y)
//!     open along y = no point at (x, y + dy) or (x, y - dy)     (Surface only)
//! ```
//!
//! by the lattice neighbour test on a lattice, else by bucketing the points
//! by cell (O(N)).

use std::collections::HashMap;

use super::cell::Cell;
use super::lattice::{Lattice, LatticeIndex};
use crate::dimension::Dimension;

/// `(along x, along y)`: whether a neighbour cell is missing, given a test
/// `present(di, dj)` of the lattice neighbour at offset (di, dj).
fn open_sides(dimension: Dimension, present: impl Fn(i64, i64) -> bool) -> (bool, bool) {
    let x = !present(1, 0) || !present(-1, 0);
    let y = dimension == Dimension::Surface && (!present(0, 1) || !present(0, -1));
    (x, y)
}

/// Boundary flags of a set on a lattice: the lattice neighbour test.
pub(super) fn lattice_boundary(dimension: Dimension, lattice: Lattice<'_>) -> Vec<(bool, bool)> {
    let members = LatticeIndex::of(lattice);
    lattice
        .iter()
        .map(|(i, j)| open_sides(dimension, |di, dj| members.get((i + di, j + dj)).is_some()))
        .collect()
}

/// Boundary flags of a set without a lattice: a point is on the boundary
/// when an adjacent cell contains no point centre. Points are bucketed by
/// cell so the test is O(N).
pub(super) fn boundary_by_cells(
    dimension: Dimension,
    cell: Cell,
    xs: &[f64],
    ys: &[f64],
) -> Vec<(bool, bool)> {
    let x_min = xs.iter().copied().fold(f64::INFINITY, f64::min);
    let y_min = ys.iter().copied().fold(f64::INFINITY, f64::min);
    // `as` saturates, so far-away buckets merely share a key.
    let key = |x: f64, y: f64| {
        (
            ((x - x_min) / cell.dx).floor() as i64,
            ((y - y_min) / cell.dy).floor() as i64,
        )
    };
    let mut buckets: HashMap<(i64, i64), Vec<usize>> = HashMap::new();
    for (k, (&x, &y)) in xs.iter().zip(ys).enumerate() {
        buckets.entry(key(x, y)).or_default().push(k);
    }
    let (hx, hy) = (0.5 * cell.dx * (1.0 + 1e-9), 0.5 * cell.dy * (1.0 + 1e-9));
    let occupied = |tx: f64, ty: f64| {
        let (i0, j0) = key(tx - hx, ty - hy);
        let (i1, j1) = key(tx + hx, ty + hy);
        (i0..=i1).any(|i| {
            (j0..=j1).any(|j| {
                buckets.get(&(i, j)).is_some_and(|ks| {
                    ks.iter()
                        .any(|&l| (xs[l] - tx).abs() <= hx && (ys[l] - ty).abs() <= hy)
                })
            })
        })
    };
    xs.iter()
        .zip(ys)
        .map(|(&x, &y)| {
            open_sides(dimension, |di, dj| {
                occupied(x + di as f64 * cell.dx, y + dj as f64 * cell.dy)
            })
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use crate::points::{Cell, Dimension, PointSet};

    #[test]
    fn from_points_boundary_without_lattice() {
        // A 3 x 3 block of cells, jittered by 0.1 cell: only the centre is interior.
        let h = 1.0;
        let mut xs = Vec::new();
        let mut ys = Vec::new();
        for i in -1..=1 {
            for j in -1..=1 {
                let jitter = 0.1 * ((i * 3 + j) as f64).sin();
                xs.push(i as f64 * h + jitter);
                ys.push(j as f64 * h - jitter);
            }
        }
        let p = PointSet::from_points(Dimension::Surface, xs, ys, Cell::square(h)).unwrap();
        assert!(p.lattice().is_none());
        let interior: Vec<usize> = (0..9).filter(|&k| !p.is_on_boundary(k)).collect();
        assert_eq!(interior, [4]);
    }
}
