//! Tests of `set` (the parent module).

use super::*;

/// A disk, a rectangle and a line.
fn grids() -> [PointSet; 3] {
    [
        PointSet::grid_disk(0.1, 0.73).unwrap(),
        PointSet::grid_rectangle(1.0, 2.5, 4, 7).unwrap(),
        PointSet::line(-1.0, 2.0, 9).unwrap(),
    ]
}

#[test]
fn positions_walk_the_coordinates_of_each_point() {
    for grid in grids() {
        let listed = PointSet::from_points(
            grid.dimension(),
            grid.xs().to_vec(),
            grid.ys().to_vec(),
            grid.cell(),
        )
        .unwrap();
        for set in [&grid, &listed] {
            // Every point has lattice indices of its own: a grid by
            // construction, the listed set by its check.
            assert!(set.lattice_is_distinct(&set.lattice_index().unwrap()));
            let positions: Vec<(f64, f64)> = set.positions().collect();
            assert_eq!(set.map_positions(|at| at), positions);
            // The walk (`fold`) from a started iterator, within a run
            // or runs later, gives the rest; so does the lattice's.
            let indices = set.lattice().unwrap().to_vec();
            for start in [0, 1, set.len() / 2, set.len()] {
                let mut walk = set.positions();
                walk.by_ref().take(start).for_each(drop);
                let rest = walk.fold(Vec::new(), |mut v, at| {
                    v.push(at);
                    v
                });
                assert_eq!(rest, positions[start..]);
                let mut walk = set.lattice().unwrap().iter();
                walk.by_ref().take(start).for_each(drop);
                let rest = walk.fold(Vec::new(), |mut v, ij| {
                    v.push(ij);
                    v
                });
                assert_eq!(rest, indices[start..]);
            }
            let lookups: Vec<(f64, f64)> = (0..set.len()).map(|k| (set.x(k), set.y(k))).collect();
            assert_eq!(positions, lookups);
            let lattice = set.lattice().unwrap();
            for (k, at) in positions.iter().enumerate() {
                assert_eq!(set.position_at(k, lattice.get(k)), *at);
            }
        }
    }
}

#[test]
fn a_grid_stores_runs_and_equals_the_same_points_listed() {
    for grid in grids() {
        let lattice = grid.lattice().unwrap();
        let (xs, ys) = (grid.xs(), grid.ys());
        assert!(matches!(xs, Cow::Owned(_)));
        for (k, ij) in lattice.iter().enumerate() {
            assert_eq!(lattice.get(k), ij);
            assert_eq!((grid.x(k), grid.y(k)), (xs[k], ys[k]));
        }
        assert_eq!(lattice.iter().len(), grid.len());
        // The same coordinates listed: the same set, stored otherwise.
        let listed =
            PointSet::from_points(grid.dimension(), xs.to_vec(), ys.to_vec(), grid.cell()).unwrap();
        assert!(matches!(listed.xs(), Cow::Borrowed(_)));
        let shifted = |p: &PointSet| {
            let l = p.lattice().unwrap().to_vec();
            l.iter()
                .map(|&(i, j)| (i - l[0].0, j - l[0].1))
                .collect::<Vec<_>>()
        };
        assert_eq!(shifted(&listed), shifted(&grid));
        assert_eq!(listed.extent(), grid.extent());
        assert_eq!(listed, grid);
        assert_eq!(
            (0..grid.len())
                .map(|k| grid.open_sides(k))
                .collect::<Vec<_>>(),
            (0..listed.len())
                .map(|k| listed.open_sides(k))
                .collect::<Vec<_>>()
        );
    }
    let p = PointSet::grid_rectangle(1.0, 1.0, 2, 2).unwrap();
    assert_eq!(p, p.clone());
    assert_ne!(p, PointSet::grid_rectangle(1.0, 1.0, 2, 3).unwrap());
}

#[test]
fn line_is_cell_centred_and_symmetric() {
    let p = PointSet::line(-1.0, 1.0, 5).unwrap();
    assert_eq!(p.len(), 5);
    assert_eq!(p.dimension(), Dimension::Line);
    assert_eq!(p.cell(), Cell { dx: 0.4, dy: 1.0 });
    // Centres -0.8, -0.4, 0, 0.4, 0.8: exact symmetry, apex on a point (n odd).
    assert_eq!(*p.xs(), [-0.8, -0.4, 0.0, 0.4, 0.8]);
    assert!(p.ys().iter().all(|&y| y == 0.0));
    assert_eq!(p.measure(2), 0.4);
    assert!((p.total_measure() - 2.0).abs() < 1e-15);
    assert!((p.extent().0 - 2.0).abs() < 1e-15);
    // n even: no point at the apex.
    let q = PointSet::line(-1.0, 1.0, 4).unwrap();
    assert!(q.xs().iter().all(|&x| x != 0.0));
    assert_eq!(q.x(1), -q.x(2));
    // Only the two end points are on the boundary.
    let b: Vec<bool> = (0..5).map(|k| p.is_on_boundary(k)).collect();
    assert_eq!(b, [true, false, false, false, true]);
    // A single cell is all boundary.
    let one = PointSet::line(2.0, 3.0, 1).unwrap();
    assert_eq!(*one.xs(), [2.5]);
    assert!(one.is_on_boundary(0));
}

#[test]
fn grid_disk_matches_the_peers_build() {
    // qp_dense.py build(m): i, j in [-m, m], keep i^2 + j^2 <= m^2;
    // count for m = 6 is the number of lattice points in a disk: 113.
    let a = 0.0123_f64;
    let m = 6;
    let h = 1.3 * a / m as f64;
    let p = PointSet::grid_disk(h, 1.3 * a).unwrap();
    let expected = (-m..=m)
        .flat_map(|i| (-m..=m).map(move |j| (i, j)))
        .filter(|(i, j)| i * i + j * j <= m * m)
        .count();
    assert_eq!(expected, 113);
    assert_eq!(p.len(), expected);
    assert_eq!(p.cell(), Cell::square(h));
    // The origin is a point; the four axis end points (radius m h) are kept.
    let lat = p.lattice().unwrap();
    assert!(lat.iter().any(|l| l == (0, 0)));
    for t in [(m, 0), (-m, 0), (0, m), (0, -m)] {
        let k = lat.iter().position(|l| l == t).unwrap();
        assert!((p.radius(k) / (1.3 * a) - 1.0).abs() < 1e-14);
        assert!(p.is_on_boundary(k));
    }
    let centre = lat.iter().position(|l| l == (0, 0)).unwrap();
    assert!(!p.is_on_boundary(centre));
    assert_eq!(p.x(centre), 0.0);
    assert!((p.measure(0) - h * h).abs() < 1e-30);
    // Every point with a missing lattice neighbour has radius > (m - 1) h.
    for k in 0..p.len() {
        if p.is_on_boundary(k) {
            assert!(p.radius(k) > (m - 1) as f64 * h);
        }
    }
}

#[test]
fn grid_disk_smaller_than_a_cell_is_the_origin() {
    let p = PointSet::grid_disk(1.0, 0.5).unwrap();
    assert_eq!(p.len(), 1);
    assert_eq!((p.x(0), p.y(0)), (0.0, 0.0));
}

#[test]
fn grid_rectangle_is_cell_centred() {
    let p = PointSet::grid_rectangle(1.0, 3.0, 2, 3).unwrap();
    assert_eq!(p.len(), 6);
    assert_eq!(p.cell(), Cell { dx: 1.0, dy: 2.0 });
    assert_eq!(*p.xs(), [-0.5, -0.5, -0.5, 0.5, 0.5, 0.5]);
    assert_eq!(*p.ys(), [-2.0, 0.0, 2.0, -2.0, 0.0, 2.0]);
    assert_eq!(p.measure(0), 2.0);
    assert_eq!(p.total_measure(), 12.0);
    assert_eq!(p.extent(), (2.0, 6.0));
    // 2 columns: every point misses a neighbour along x; along y only the ends.
    assert!((0..6).all(|k| p.is_on_boundary(k)));
    assert_eq!(p.open_sides(0), (true, true));
    assert_eq!(p.open_sides(1), (true, false));
    let q = PointSet::grid_rectangle(1.5, 1.5, 3, 3).unwrap();
    let interior: Vec<usize> = (0..9).filter(|&k| !q.is_on_boundary(k)).collect();
    assert_eq!(interior, [4]);
    assert_eq!((q.x(4), q.y(4)), (0.0, 0.0));
}

#[test]
fn from_points_detects_a_lattice() {
    let cell = Cell::square(0.5);
    let xs = vec![0.0, 0.5, 1.0, 0.5];
    let ys = vec![0.0, 0.0, 0.0, 0.5];
    let p = PointSet::from_points(Dimension::Surface, xs, ys, cell).unwrap();
    assert_eq!(
        p.lattice().unwrap().to_vec(),
        [(0, 0), (1, 0), (2, 0), (1, 1)]
    );
    // Off-lattice by a tenth of a cell: no lattice.
    let q =
        PointSet::from_points(Dimension::Surface, vec![0.0, 0.55], vec![0.0, 0.0], cell).unwrap();
    assert!(q.lattice().is_none());
}

#[test]
fn from_points_line_accepts_empty_ys() {
    let p = PointSet::from_points(
        Dimension::Line,
        vec![0.0, 1.0, 2.7],
        vec![],
        Cell { dx: 1.0, dy: 7.0 },
    )
    .unwrap();
    assert_eq!(*p.ys(), [0.0, 0.0, 0.0]);
    assert_eq!(p.cell().dy, 1.0);
    assert!(p.lattice().is_none());
    assert_eq!(p.measure(0), 1.0);
    // 0 and 1 are adjacent; but 1's cell to the right ([1.5, 2.5]) and both of
    // 2.7's ([1.2, 2.2], [3.2, 4.2]) hold no point.
    assert_eq!(
        (0..3).map(|k| p.is_on_boundary(k)).collect::<Vec<_>>(),
        [true, true, true]
    );
}

#[test]
fn constructors_reject_bad_input() {
    let field = |r: Result<PointSet, InfluenceError>| match r {
        Err(InfluenceError::InvalidPoints { field, .. }) => field,
        Err(other) => panic!("expected InvalidPoints, got {other:?}"),
        Ok(p) => panic!("expected InvalidPoints, got a set of {} points", p.len()),
    };
    assert_eq!(field(PointSet::line(f64::NAN, 1.0, 3)), "start");
    assert_eq!(field(PointSet::line(1.0, 1.0, 3)), "end");
    assert_eq!(field(PointSet::line(0.0, 1.0, MAX_POINTS + 1)), "n");
    assert_eq!(field(PointSet::grid_disk(-1.0, 1.0)), "spacing");
    assert_eq!(field(PointSet::grid_disk(1.0, f64::INFINITY)), "radius");
    assert_eq!(field(PointSet::grid_disk(1e-9, 1.0)), "radius / spacing");
    // A huge ratio in its shortest form, not 301 digits.
    let why = PointSet::grid_disk(1.0, 1e300).unwrap_err().to_string();
    assert!(why.contains("= 1e300:"), "{why}");
    assert_eq!(field(PointSet::grid_rectangle(1.0, 0.0, 2, 2)), "half_y");
    assert_eq!(field(PointSet::grid_rectangle(1.0, 1.0, 0, 2)), "nx");
    assert_eq!(
        field(PointSet::grid_rectangle(1.0, 1.0, 3000, 3000)),
        "nx * ny"
    );
    assert_eq!(
        field(PointSet::grid_rectangle(1.0, 1.0, usize::MAX, 2)),
        "nx"
    );
    let s = Dimension::Surface;
    let c = Cell::square(1.0);
    assert_eq!(
        field(PointSet::from_points(s, vec![0.0], vec![], c)),
        "ys.len()"
    );
    assert_eq!(
        field(PointSet::from_points(
            s,
            vec![0.0, f64::NAN],
            vec![0.0, 0.0],
            c
        )),
        "xs[1]"
    );
    assert_eq!(
        field(PointSet::from_points(
            s,
            vec![0.0, 1.0],
            vec![0.0, f64::INFINITY],
            c
        )),
        "ys[1]"
    );
    assert_eq!(
        field(PointSet::from_points(
            s,
            vec![0.0],
            vec![0.0],
            Cell { dx: 1.0, dy: 0.0 }
        )),
        "cell.dy"
    );
    assert_eq!(
        field(PointSet::from_points(
            Dimension::Line,
            vec![0.0],
            vec![1.0],
            c
        )),
        "ys[0]"
    );
    let dup = PointSet::from_points(s, vec![1.0, 0.0, 1.0], vec![2.0, 0.0, 2.0], c);
    assert_eq!(field(dup.clone()), "(xs[2], ys[2])");
    assert!(
        dup.unwrap_err().to_string().contains("repeats point 0"),
        "names both points"
    );
}
