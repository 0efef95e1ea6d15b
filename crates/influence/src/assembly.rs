//! Assembly of the influence matrix of the bodies in contact,
//!
//! ```text
//!     S = A(1) + A(2) (+ ...),    S_kj = sum_b a_kj^(b)
//! ```
//!
//! into a dense faer matrix (column-major, N x N, length per force).
//!
//! Half-space bodies that share a kernel K (same model, same datum d0) are
//! summed before any kernel is evaluated: `c1 K + c2 K = (c1 + c2) K`, with
//! `c1 + c2 = 1/E*` the combined compliance. On a lattice the kernels depend
//! only on the lattice offset `(|i_k - i_j|, |j_k - j_j|)` (translation
//! invariance, and the cell's symmetry), so they are evaluated once per
//! offset into a table that the matrix gathers from; without a lattice every
//! entry of the lower triangle is evaluated and mirrored. Beams are not
//! translation invariant (they depend on the distance from the loaded
//! point): their cantilever coefficients
//!
//! ```text
//!     a_kj = a^2 (3 b - a) / (6 E I),   a = min(|x_k - x0|, |x_j - x0|), b = max(...)
//! ```
//!
//! (k and j on the same side of x0, else 0) are added entry by entry.

use faer::prelude::*;
use faer::{Mat, MatMut};

use crate::error::InfluenceError;
use crate::models::Body;
use crate::points::{MAX_DENSE_POINTS, PointSet};
use crate::symmetry::Folding;
use crate::terms::{TableLayout, Terms, table_layout};

/// Tile size of the mirroring copy (64 x 64 doubles = 32 kB).
const MIRROR_TILE: usize = 64;

/// The influence matrix `A` of one body on `points`, or `None` for a rigid
/// body (it contributes nothing). `A_kj` = deflection at k due to a unit force
/// at j (length/force; per unit width on a line).
///
/// # Errors
/// As [`assemble`], except that a rigid body is not an error here.
pub fn influence(points: &PointSet, body: &Body) -> Result<Option<Mat<f64>>, InfluenceError> {
    if body.is_rigid() {
        return Ok(None);
    }
    assemble(points, &[body]).map(Some)
}

/// The influence matrix `S = sum_b A(b)` of the bodies in contact on
/// `points`: `S_kj` = the total deflection at point k of all the bodies due to
/// a unit force at point j (length/force; per unit width on a line). For the
/// models of this crate S is symmetric positive definite.
///
/// A rigid body adds nothing. Half-space bodies sharing a kernel are
/// assembled once with their summed compliance.
///
/// # Errors
/// - [`InfluenceError::DimensionMismatch`]: a surface model (point force,
///   uniform patch) on a line set, or the plane-strain model on a surface set;
/// - [`InfluenceError::InvalidModel`]: a Winkler modulus that is not finite
///   and positive, or a plane-strain reference distance that is not finite
///   or is below the extent of the point set (`PointSet::extent().0`);
/// - [`InfluenceError::AllRigid`]: no elastic body among `bodies` (also for
///   an empty slice);
/// - [`InfluenceError::InvalidPoints`]: more than [`MAX_DENSE_POINTS`]
///   points.
pub fn assemble(points: &PointSet, bodies: &[&Body]) -> Result<Mat<f64>, InfluenceError> {
    dense_size(points.len())?;
    let terms = Terms::collect(points, bodies)?;
    let mut s = if terms.kernels.is_empty() {
        zeroed(points.len())?
    } else {
        match table_layout(points) {
            Some(layout) => fill_from_table(points, &terms, &layout)?,
            None => fill_direct(points, &terms)?,
        }
    };
    terms.add_local(points, &mut s);
    Ok(s)
}

/// Refuses a dense matrix of more than [`MAX_DENSE_POINTS`] unknowns.
fn dense_size(n: usize) -> Result<(), InfluenceError> {
    if n > MAX_DENSE_POINTS {
        let gb = 8.0 * (n as f64) * (n as f64) / 1e9;
        return Err(InfluenceError::points(
            "number of points",
            n,
            format!(
                "a dense influence matrix of more than MAX_DENSE_POINTS = {MAX_DENSE_POINTS} \
                 unknowns ({gb:.0} GB here); solve it matrix-free (LatticeOperator)"
            ),
        ));
    }
    Ok(())
}

/// The folded influence matrix of a mirror-symmetric problem (see
/// [`Folding`]): for representatives a, b,
/// `M_ab = (1 / s_a) sum_{j in O(b)} S_{rep(a) j}`, symmetric positive
/// definite, of order `folding.len()`. The full S is never formed.
///
/// # Errors
/// As [`assemble`].
pub fn assemble_folded(
    points: &PointSet,
    bodies: &[&Body],
    folding: &Folding,
) -> Result<Mat<f64>, InfluenceError> {
    dense_size(folding.len())?;
    let terms = Terms::collect(points, bodies)?;
    // The half-space part as in `assemble`: none, gathered from the lattice
    // table, or evaluated from the coordinates; chosen once, not per entry.
    let m = if terms.kernels.is_empty() {
        fold(points, &terms, folding, |_, _| 0.0)?
    } else {
        match table_layout(points) {
            Some(layout) => {
                let table = terms.table(layout.ni, layout.nj);
                fold(points, &terms, folding, |k, j| table[layout.offset(k, j)])?
            }
            None => {
                let (xs, ys) = (points.xs(), points.ys());
                fold(points, &terms, folding, |k, j| {
                    terms.coefficient(xs[k] - xs[j], ys[k] - ys[j], k == j)
                })?
            }
        }
    };
    Ok(m)
}

/// The folded matrix from `half(k, j)`, the half-space part of `S_kj`, plus
/// the local terms. M is symmetric (`s_b T_ab = s_a T_ba`, see
/// [`Folding`]): the lower triangle is summed and mirrored,
/// which halves the work and makes the symmetry exact.
fn fold(
    points: &PointSet,
    terms: &Terms,
    folding: &Folding,
    half: impl Fn(usize, usize) -> f64,
) -> Result<Mat<f64>, InfluenceError> {
    let n = folding.len();
    let xs = points.xs();
    let diagonal = terms.winkler_diagonal(points);
    // S_kj in the order `assemble` adds its parts: half-space, Winkler, beams.
    let entry = |k: usize, j: usize| {
        let mut v = half(k, j);
        if k == j {
            v += diagonal;
        }
        terms.add_beams(v, xs[k], xs[j])
    };
    let mut m = zeroed(n)?;
    for b in 0..n {
        let orbit = folding.orbit(b);
        for a in b..n {
            let k = folding.rep(a);
            let t: f64 = orbit.clone().map(|j| entry(k, j)).sum();
            let v = t / folding.stabilizer(a);
            m[(a, b)] = v;
            m[(b, a)] = v;
        }
    }
    Ok(m)
}

/// An n x n matrix of zeros, its storage reserved fallibly:
/// [`InfluenceError::AllocationFailed`] when it cannot be.
fn zeroed(n: usize) -> Result<Mat<f64>, InfluenceError> {
    let mut m = Mat::new();
    m.try_reserve(n, n)
        .map_err(|_| InfluenceError::AllocationFailed {
            what: "the influence matrix S",
            bytes: n.saturating_mul(n).saturating_mul(8),
        })?;
    m.resize_with(n, n, |_, _| 0.0);
    Ok(m)
}

/// The same S as [`assemble`], always evaluating every entry of the lower
/// triangle directly from the coordinates (no lattice table): the reference
/// the table path is tested against, and a fallback for callers who want it.
///
/// # Errors
/// As [`assemble`].
pub fn assemble_direct(points: &PointSet, bodies: &[&Body]) -> Result<Mat<f64>, InfluenceError> {
    let terms = Terms::collect(points, bodies)?;
    let mut s = fill_direct(points, &terms)?;
    terms.add_local(points, &mut s);
    Ok(s)
}

/// S from one kernel evaluation per lattice offset `(di, dj) >= 0`, gathered
/// column by column.
fn fill_from_table(
    points: &PointSet,
    terms: &Terms,
    layout: &TableLayout,
) -> Result<Mat<f64>, InfluenceError> {
    let n = points.len();
    let nj = layout.nj;
    let table = terms.table(layout.ni, layout.nj);
    let mut s = zeroed(n)?;
    let threads = threads_for(n);
    let splits: Vec<usize> = (0..=threads).map(|t| t * n / threads).collect();
    fill_columns(s.as_mut(), &splits, |first, mut block| {
        for k in 0..block.ncols() {
            let c = first + k;
            let (ic, jc) = (layout.i[c], layout.j[c]);
            let column = block
                .rb_mut()
                .col_mut(k)
                .try_as_col_major_mut()
                .expect("a column of an owned matrix is contiguous")
                .as_slice_mut();
            // TableLayout::offset(r, c), with the column's indices hoisted
            // and the rows' zipped (no bounds checks in the hot loop).
            for ((entry, &ir), &jr) in column.iter_mut().zip(&layout.i).zip(&layout.j) {
                *entry = table[ir.abs_diff(ic) * nj + jr.abs_diff(jc)];
            }
        }
    });
    Ok(s)
}

/// Threads worth using to fill an n x n matrix: one below 2^18 entries, else
/// the machine's (at most 8).
fn threads_for(n: usize) -> usize {
    if n * n < 1 << 18 {
        1
    } else {
        std::thread::available_parallelism().map_or(1, |t| t.get().min(8))
    }
}

/// Calls `fill(first_column, columns)` on the column ranges
/// `splits[t]..splits[t + 1]` of `s`, each in its own thread (disjoint
/// columns: no synchronisation).
fn fill_columns(
    mut s: MatMut<'_, f64>,
    splits: &[usize],
    fill: impl Fn(usize, MatMut<'_, f64>) + Sync,
) {
    if splits.len() <= 2 {
        fill(0, s);
        return;
    }
    std::thread::scope(|scope| {
        let fill = &fill;
        let mut rest = s.rb_mut();
        let mut done = 0;
        for w in splits.windows(2) {
            let (block, tail) = rest.split_at_col_mut(w[1] - done);
            let first = done;
            scope.spawn(move || fill(first, block));
            rest = tail;
            done = w[1];
        }
    });
}

/// S from a kernel evaluation per entry of the lower triangle, mirrored.
fn fill_direct(points: &PointSet, terms: &Terms) -> Result<Mat<f64>, InfluenceError> {
    let n = points.len();
    let (xs, ys) = (points.xs(), points.ys());
    let mut s = zeroed(n)?;
    // Column c of the lower triangle has n - c entries: split where each
    // thread gets an equal share of the triangle, c_t = n (1 - sqrt(1 - t/T)).
    let threads = threads_for(n);
    let splits: Vec<usize> = (0..=threads)
        .map(|t| ((n as f64) * (1.0 - (1.0 - t as f64 / threads as f64).sqrt())).round() as usize)
        .collect();
    fill_columns(s.as_mut(), &splits, |first, mut block| {
        for k in 0..block.ncols() {
            let c = first + k;
            let (xc, yc) = (xs[c], ys[c]);
            let mut column = block.rb_mut().col_mut(k);
            for r in c..n {
                column[r] = terms.coefficient(xs[r] - xc, ys[r] - yc, r == c);
            }
        }
    });
    // Upper triangle from the lower, tile by tile to stay in cache.
    for c0 in (0..n).step_by(MIRROR_TILE) {
        for r0 in (0..=c0).step_by(MIRROR_TILE) {
            for c in c0..(c0 + MIRROR_TILE).min(n) {
                for r in r0..(r0 + MIRROR_TILE).min(c) {
                    s[(r, c)] = s[(c, r)];
                }
            }
        }
    }
    Ok(s)
}

#[cfg(test)]
mod tests {
    use std::f64::consts::PI;

    use super::*;
    use crate::error::InfluenceError;
    use crate::kernels::love_rectangle;

    #[test]
    fn an_influence_matrix_too_big_to_allocate_is_an_error() {
        let e = zeroed(1 << 31).unwrap_err();
        assert!(
            matches!(
                e,
                InfluenceError::AllocationFailed {
                    what: "the influence matrix S",
                    bytes
                } if bytes == usize::MAX
            ),
            "{e}"
        );
        assert_eq!(zeroed(2).unwrap(), Mat::<f64>::zeros(2, 2));
    }
    use crate::Material;
    use crate::fixtures::{BEAM, UNIT_BEAM, sparse_pair};
    use crate::models::{Beam, Body, Model};

    fn steel() -> Material {
        Material::new(30e6, 0.3).unwrap()
    }

    #[test]
    fn self_term_of_love_and_point_force_is_the_square_closed_form() {
        let h = 0.01;
        let p = PointSet::grid_disk(h, 0.05).unwrap();
        let centre = p
            .lattice()
            .unwrap()
            .iter()
            .position(|l| l == (0, 0))
            .unwrap();
        let expected = steel().compliance() * 4.0 * (1.0 + 2f64.sqrt()).ln() / (PI * h);
        for body in [Body::uniform_patch(steel()), Body::point_force(steel())] {
            let a = influence(&p, &body).unwrap().unwrap();
            for k in [0, centre] {
                assert!((a[(k, k)] / expected - 1.0).abs() < 1e-14, "{body:?}");
            }
        }
    }

    #[test]
    fn point_force_off_diagonal_is_compliance_over_pi_d() {
        let p = PointSet::grid_rectangle(1.0, 1.0, 4, 4).unwrap();
        let a = influence(&p, &Body::point_force(steel())).unwrap().unwrap();
        for (k, j) in [(0, 1), (0, 15), (5, 10), (3, 12)] {
            let d = (p.x(k) - p.x(j)).hypot(p.y(k) - p.y(j));
            let expected = steel().compliance() / (PI * d);
            assert!((a[(k, j)] / expected - 1.0).abs() < 1e-14);
        }
    }

    #[test]
    fn winkler_is_diagonal_over_modulus_and_measure() {
        let p = PointSet::grid_rectangle(1.0, 2.0, 4, 2).unwrap(); // cells 0.5 x 2
        let a = influence(&p, &Body::winkler(8.0)).unwrap().unwrap();
        for k in 0..p.len() {
            for j in 0..p.len() {
                let expected = if k == j { 1.0 / (8.0 * 1.0) } else { 0.0 };
                assert_eq!(a[(k, j)], expected);
            }
        }
        // On a line the measure is the cell length: 1 / (k dx).
        let line = PointSet::line(0.0, 2.0, 8).unwrap();
        let a = influence(&line, &Body::winkler(8.0)).unwrap().unwrap();
        assert_eq!(a[(3, 3)], 1.0 / (8.0 * 0.25));
        assert_eq!(a[(3, 4)], 0.0);
    }

    #[test]
    fn shared_kernels_are_grouped_and_rigid_bodies_dropped() {
        let aluminium = Material::new(10e6, 0.33).unwrap();
        let p = PointSet::grid_disk(0.1, 0.3).unwrap();
        let (b1, b2, rigid) = (
            Body::uniform_patch(steel()),
            Body::uniform_patch(aluminium),
            Body::rigid(),
        );
        let terms = Terms::collect(&p, &[&b1, &rigid, &b2]).unwrap();
        assert_eq!(terms.kernels.len(), 1);
        assert_eq!(
            terms.kernels[0].1,
            steel().compliance() + aluminium.compliance()
        );
        let strip_a = Body::plane_strain(steel(), 10.0);
        let strip_b = Body::plane_strain(steel(), 20.0);
        let line = PointSet::line(-1.0, 1.0, 5).unwrap();
        let terms = Terms::collect(&line, &[&strip_a, &strip_a, &strip_b]).unwrap();
        assert_eq!(
            terms.kernels.len(),
            2,
            "different datums are different kernels"
        );
        assert!(influence(&p, &rigid).unwrap().is_none());
    }

    #[test]
    fn beam_is_two_cantilevers_clamped_at_the_loaded_point() {
        let line = PointSet::line(-2.0, 2.0, 8).unwrap(); // x = -1.75 .. 1.75, h = 0.5
        let ei = 3.0e4;
        let a = influence(&line, &Body::beam(BEAM).unwrap())
            .unwrap()
            .unwrap();
        // Tip of a cantilever under a tip load: L^3 / (3 E I).
        assert!((a[(7, 7)] / (1.75f64.powi(3) / (3.0 * ei)) - 1.0).abs() < 1e-15);
        // Maxwell-Betti: deflection at 0.25 due to a load at 1.75 is a^2 (3b - a) / 6EI.
        let expected = 0.25f64.powi(2) * (3.0 * 1.75 - 0.25) / (6.0 * ei);
        assert!((a[(4, 7)] / expected - 1.0).abs() < 1e-15);
        assert_eq!(a[(4, 7)], a[(7, 4)]);
        // The two halves do not interact; the set is symmetric about x0.
        assert_eq!(a[(3, 4)], 0.0);
        assert_eq!(a[(0, 0)], a[(7, 7)]);
        // A beam on a foundation: S = beam + 1/(k A_k) on the diagonal.
        let s = assemble(&line, &[&Body::beam(BEAM).unwrap(), &Body::winkler(100.0)]).unwrap();
        assert!((s[(5, 5)] - a[(5, 5)] - 1.0 / (100.0 * 0.5)).abs() < 1e-18);
        assert_eq!(s[(5, 6)], a[(5, 6)]);
        // Off-centre loaded point: points on one side only.
        let b = influence(
            &line,
            &Body::beam(Beam {
                loaded_point: -2.0,
                ..BEAM
            })
            .unwrap(),
        )
        .unwrap()
        .unwrap();
        let expected = 0.25f64.powi(2) * (3.0 * 3.75 - 0.25) / (6.0 * ei);
        assert!((b[(0, 7)] / expected - 1.0).abs() < 1e-14);
    }

    #[test]
    fn beam_parameters_are_validated() {
        let line = PointSet::line(-1.0, 1.0, 4).unwrap();
        let e = assemble(
            &line,
            &[&Body::new(Model::Beam {
                flexural_rigidity: 0.0,
                loaded_point: 0.0,
            })],
        )
        .unwrap_err();
        assert_eq!(
            e.to_string(),
            "invalid Euler-Bernoulli beam parameter: flexural_rigidity = 0: E I must be finite and positive"
        );
        let e = assemble(
            &line,
            &[&Body::new(Model::Beam {
                flexural_rigidity: 1.0,
                loaded_point: f64::NAN,
            })],
        )
        .unwrap_err();
        assert!(e.to_string().contains("loaded_point = NaN"), "{e}");
        let disk = PointSet::grid_disk(0.1, 0.3).unwrap();
        let e = assemble(&disk, &[&Body::beam(UNIT_BEAM).unwrap()]).unwrap_err();
        assert!(matches!(e, InfluenceError::DimensionMismatch { .. }), "{e}");
    }

    #[test]
    fn the_folded_matrix_is_the_full_one_summed_over_orbits() {
        let steel = Material::new(30e6, 0.3).unwrap();
        let cases: Vec<(PointSet, Vec<Body>)> = vec![
            (
                PointSet::grid_disk(0.1, 0.45).unwrap(),
                vec![Body::uniform_patch(steel)],
            ),
            (
                PointSet::grid_disk(0.1, 0.45).unwrap(),
                vec![Body::point_force(steel), Body::winkler(1e9)],
            ),
            (
                PointSet::grid_rectangle(0.3, 1.0, 5, 8).unwrap(),
                vec![Body::uniform_patch(steel)],
            ),
            (
                PointSet::line(-1.0, 1.0, 9).unwrap(),
                vec![
                    Body::beam(Beam {
                        youngs_modulus: 1e3,
                        ..UNIT_BEAM
                    })
                    .unwrap(),
                    Body::winkler(50.0),
                ],
            ),
            (
                PointSet::line(-1.0, 1.0, 8).unwrap(),
                vec![Body::plane_strain(steel, 5.0)],
            ),
        ];
        for (points, bodies) in cases {
            let refs: Vec<&Body> = bodies.iter().collect();
            let f = Folding::detect(&points, &refs).unwrap();
            let s = assemble(&points, &refs).unwrap();
            let m = assemble_folded(&points, &refs, &f).unwrap();
            for a in 0..f.len() {
                for b in 0..f.len() {
                    let t: f64 = f.orbit(b).map(|j| s[(f.rep(a), j)]).sum();
                    let expected = t / f.stabilizer(a);
                    assert!(
                        (m[(a, b)] - expected).abs() <= 1e-14 * expected.abs(),
                        "{a} {b}"
                    );
                    // Symmetric, as the folded LCP needs.
                    assert!(
                        (m[(a, b)] - m[(b, a)]).abs() <= 1e-14 * m[(a, b)].abs(),
                        "{a} {b}"
                    );
                    // Exactly: the lower triangle is mirrored.
                    assert_eq!(m[(a, b)], m[(b, a)], "{a} {b}");
                }
            }
        }
    }

    #[test]
    fn the_table_path_matches_the_direct_reference() {
        // The table evaluates each kernel at the lattice offset (di dx, dj dy);
        // the direct path at the difference of two stored coordinates, which
        // differs from it by rounding of the coordinates (a few ulps of the
        // set's extent). The kernels' slope is at most about their value over
        // the offset, so an entry moves by ~1e-16 (extent / cell) of the
        // largest entry (the self-term): below 2e-15 for these sets of at most
        // 16 cells across (measured 2.6e-16 on the disk, 0 on the other two),
        // and 1e-14 leaves a margin while still catching any wrong offset
        // (neighbouring offsets differ by percents).
        let aluminium = Material::new(10e6, 0.33).unwrap();
        let cases: Vec<(&str, PointSet, Vec<Body>)> = vec![
            (
                "disk",
                PointSet::grid_disk(0.1, 0.75).unwrap(),
                vec![
                    Body::uniform_patch(steel()),
                    Body::point_force(aluminium),
                    Body::winkler(1e9),
                ],
            ),
            (
                "oblong rectangle",
                PointSet::grid_rectangle(0.3, 1.0, 5, 8).unwrap(),
                vec![Body::uniform_patch(steel()), Body::uniform_patch(aluminium)],
            ),
            (
                "line",
                PointSet::line(-1.0, 1.0, 16).unwrap(),
                vec![
                    Body::plane_strain(steel(), 5.0),
                    Body::beam(Beam {
                        youngs_modulus: 1e3,
                        ..UNIT_BEAM
                    })
                    .unwrap(),
                    Body::winkler(50.0),
                ],
            ),
        ];
        for (name, points, bodies) in cases {
            let refs: Vec<&Body> = bodies.iter().collect();
            assert!(table_layout(&points).is_some(), "{name}: a table applies");
            let table = assemble(&points, &refs).unwrap();
            let direct = assemble_direct(&points, &refs).unwrap();
            let n = points.len();
            let largest = (0..n)
                .flat_map(|c| (0..n).map(move |r| (r, c)))
                .fold(0.0f64, |m, rc| m.max(direct[rc].abs()));
            for c in 0..n {
                for r in 0..n {
                    assert!(
                        (table[(r, c)] - direct[(r, c)]).abs() <= 1e-14 * largest,
                        "{name} ({r}, {c}): {} vs {}",
                        table[(r, c)],
                        direct[(r, c)]
                    );
                }
            }
        }
    }

    #[test]
    fn no_body_is_all_rigid() {
        let p = PointSet::line(0.0, 1.0, 3).unwrap();
        assert_eq!(
            assemble(&p, &[]).unwrap_err(),
            InfluenceError::AllRigid { bodies: 0 }
        );
    }

    #[test]
    fn sparse_lattice_falls_back_to_direct() {
        // Two points 1000 cells apart: a 1001-entry table for 2 points.
        let p = sparse_pair();
        assert!(p.lattice().is_some());
        assert!(table_layout(&p).is_none());
        let s = assemble(&p, &[&Body::uniform_patch(steel())]).unwrap();
        let expected = steel().compliance() / PI * love_rectangle(1000.0, 0.0, 1.0, 1.0);
        // Same kernel, same arguments (the direct path evaluates x_r - x_c):
        // equal to the last bits of the kernel's evaluation.
        assert!((s[(0, 1)] / expected - 1.0).abs() < 1e-15);
        assert_eq!(s[(1, 0)], s[(0, 1)]);
    }
}
