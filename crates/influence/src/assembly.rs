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

use std::f64::consts::PI;

use faer::prelude::*;
use faer::{Mat, MatMut};

use crate::error::InfluenceError;
use crate::kernels::{boussinesq, love_rectangle, plane_strain_strip};
use crate::models::{Body, Model};
use crate::points::{Cell, Dimension, PointSet};

/// A table may hold at most this many entries per point before the direct
/// path is cheaper (a sparse set on a fine lattice).
const TABLE_ENTRIES_PER_POINT: usize = 4;

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
///   an empty slice).
pub fn assemble(points: &PointSet, bodies: &[&Body]) -> Result<Mat<f64>, InfluenceError> {
    let terms = Terms::collect(points, bodies)?;
    let mut s = if terms.kernels.is_empty() {
        Mat::zeros(points.len(), points.len())
    } else {
        match table_layout(points) {
            Some(layout) => fill_from_table(points, &terms, &layout),
            None => fill_direct(points, &terms),
        }
    };
    terms.add_local(points, &mut s);
    Ok(s)
}

/// The folded influence matrix of a mirror-symmetric problem (see
/// [`Folding`](crate::Folding)): for representatives a, b,
/// `M_ab = (1 / s_a) sum_{j in O(b)} S_{rep(a) j}`, symmetric positive
/// definite, of order `folding.len()`. The full S is never formed.
///
/// # Errors
/// As [`assemble`].
pub fn assemble_folded(
    points: &PointSet,
    bodies: &[&Body],
    folding: &crate::Folding,
) -> Result<Mat<f64>, InfluenceError> {
    let terms = Terms::collect(points, bodies)?;
    // The half-space part as in `assemble`: none, gathered from the lattice
    // table, or evaluated from the coordinates; chosen once, not per entry.
    let m = if terms.kernels.is_empty() {
        fold(points, &terms, folding, |_, _| 0.0)
    } else {
        match table_layout(points) {
            Some(layout) => {
                let table = terms.table(&layout);
                fold(points, &terms, folding, |k, j| table[layout.offset(k, j)])
            }
            None => {
                let (xs, ys) = (points.xs(), points.ys());
                fold(points, &terms, folding, |k, j| {
                    terms.coefficient(xs[k] - xs[j], ys[k] - ys[j], k == j)
                })
            }
        }
    };
    Ok(m)
}

/// The folded matrix from `half(k, j)`, the half-space part of `S_kj`, plus
/// the local terms. M is symmetric (`s_b T_ab = s_a T_ba`, see
/// [`Folding`](crate::Folding)): the lower triangle is summed and mirrored,
/// which halves the work and makes the symmetry exact.
fn fold(
    points: &PointSet,
    terms: &Terms,
    folding: &crate::Folding,
    half: impl Fn(usize, usize) -> f64,
) -> Mat<f64> {
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
    let mut m = Mat::<f64>::zeros(n, n);
    for b in 0..n {
        let orbit = folding.orbit(b);
        for a in b..n {
            let k = folding.rep(a);
            let t: f64 = orbit.iter().map(|&j| entry(k, j)).sum();
            let v = t / folding.stabilizer(a);
            m[(a, b)] = v;
            m[(b, a)] = v;
        }
    }
    m
}

/// The same S as [`assemble`], always evaluating every entry of the lower
/// triangle directly from the coordinates (no lattice table): the reference
/// the table path is tested against, and a fallback for callers who want it.
///
/// # Errors
/// As [`assemble`].
pub fn assemble_direct(points: &PointSet, bodies: &[&Body]) -> Result<Mat<f64>, InfluenceError> {
    let terms = Terms::collect(points, bodies)?;
    let mut s = fill_direct(points, &terms);
    terms.add_local(points, &mut s);
    Ok(s)
}

/// A translation-invariant kernel shared by half-space bodies.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Kernel {
    PointForce,
    UniformPatch,
    Strip { reference_distance: f64 },
}

/// The bodies reduced to distinct kernels with summed compliances, plus the
/// summed Winkler compliance `sum 1/k` and the beams' summed flexibilities
/// `sum 1/(E I)` per loaded point.
#[derive(Debug)]
struct Terms {
    kernels: Vec<(Kernel, f64)>,
    winkler_compliance: f64,
    /// (x0, sum of 1/(E I)) per distinct loaded point.
    beams: Vec<(f64, f64)>,
    cell: Cell,
    /// love_rectangle(0, 0, dx, dy): the point-force self-term's kernel.
    centre: f64,
}

impl Terms {
    /// Validates every body against the point set and groups the kernels.
    fn collect(points: &PointSet, bodies: &[&Body]) -> Result<Self, InfluenceError> {
        let dimension = points.dimension();
        let cell = points.cell();
        let mut kernels: Vec<(Kernel, f64)> = Vec::new();
        let mut winkler_compliance = 0.0;
        let mut beams: Vec<(f64, f64)> = Vec::new();
        let mut elastic = 0;
        for body in bodies {
            let model = body.model();
            let mismatch = |hint| InfluenceError::DimensionMismatch {
                model: model.name(),
                dimension,
                hint,
            };
            let (kernel, compliance) = match *model {
                Model::Rigid => continue,
                Model::PointForce { material } | Model::UniformPatch { material } => {
                    if dimension != Dimension::Surface {
                        return Err(mismatch(
                            "use Body::plane_strain on a line, or a surface point set \
                             (PointSet::grid_disk, grid_rectangle)",
                        ));
                    }
                    let kernel = if matches!(model, Model::PointForce { .. }) {
                        Kernel::PointForce
                    } else {
                        Kernel::UniformPatch
                    };
                    (kernel, material.compliance())
                }
                Model::PlaneStrainStrip {
                    material,
                    reference_distance,
                } => {
                    if dimension != Dimension::Line {
                        return Err(mismatch(
                            "use Body::uniform_patch or Body::point_force on a surface, \
                             or a line point set (PointSet::line)",
                        ));
                    }
                    check_reference_distance(model.name(), reference_distance, points)?;
                    (Kernel::Strip { reference_distance }, material.compliance())
                }
                Model::Winkler { modulus } => {
                    let bad = |reason: &str| InfluenceError::InvalidModel {
                        model: model.name(),
                        field: "modulus",
                        value: modulus,
                        reason: reason.into(),
                    };
                    if !modulus.is_finite() {
                        return Err(bad("must be finite"));
                    }
                    if modulus <= 0.0 {
                        return Err(bad("must be positive"));
                    }
                    winkler_compliance += 1.0 / modulus;
                    elastic += 1;
                    continue;
                }
                Model::Beam {
                    flexural_rigidity,
                    loaded_point,
                } => {
                    if dimension != Dimension::Line {
                        return Err(mismatch(
                            "a beam lies along x: use a line point set (PointSet::line)",
                        ));
                    }
                    let bad = |field, value, reason: &str| InfluenceError::InvalidModel {
                        model: model.name(),
                        field,
                        value,
                        reason: reason.into(),
                    };
                    if !(flexural_rigidity.is_finite() && flexural_rigidity > 0.0) {
                        return Err(bad(
                            "flexural_rigidity",
                            flexural_rigidity,
                            "E I must be finite and positive",
                        ));
                    }
                    if !loaded_point.is_finite() {
                        return Err(bad("loaded_point", loaded_point, "must be finite"));
                    }
                    match beams.iter_mut().find(|(x0, _)| *x0 == loaded_point) {
                        Some((_, f)) => *f += 1.0 / flexural_rigidity,
                        None => beams.push((loaded_point, 1.0 / flexural_rigidity)),
                    }
                    elastic += 1;
                    continue;
                }
            };
            elastic += 1;
            match kernels.iter_mut().find(|(k, _)| *k == kernel) {
                Some((_, c)) => *c += compliance,
                None => kernels.push((kernel, compliance)),
            }
        }
        if elastic == 0 {
            return Err(InfluenceError::AllRigid {
                bodies: bodies.len(),
            });
        }
        Ok(Self {
            kernels,
            winkler_compliance,
            beams,
            cell,
            centre: love_rectangle(0.0, 0.0, cell.dx, cell.dy),
        })
    }

    /// Adds the terms that are not translation invariant: the Winkler
    /// diagonal `1 / (k A_k)` and the beams' cantilever coefficients.
    /// S must be symmetric (the beams' terms are added to the lower triangle
    /// and mirrored).
    fn add_local(&self, points: &PointSet, s: &mut Mat<f64>) {
        if self.winkler_compliance > 0.0 {
            let diagonal = self.winkler_diagonal(points);
            for k in 0..points.len() {
                s[(k, k)] += diagonal;
            }
        }
        if self.beams.is_empty() {
            return;
        }
        let xs = points.xs();
        for c in 0..xs.len() {
            for r in c..xs.len() {
                let v = self.add_beams(s[(r, c)], xs[r], xs[c]);
                s[(r, c)] = v;
                s[(c, r)] = v;
            }
        }
    }

    /// The Winkler foundations' diagonal `sum 1/k` over the cell's measure
    /// (0 without a foundation).
    fn winkler_diagonal(&self, points: &PointSet) -> f64 {
        self.winkler_compliance / points.cell().measure(points.dimension())
    }

    /// `v` plus the beams' coefficients between abscissae `xk` and `xj`,
    /// added beam by beam.
    fn add_beams(&self, v: f64, xk: f64, xj: f64) -> f64 {
        self.beams.iter().fold(v, |v, &(x0, flexibility)| {
            v + cantilever(flexibility, xk - x0, xj - x0)
        })
    }

    /// The half-space part of S at every lattice offset `(di, dj) >= 0` of
    /// `layout`, at index `di * nj + dj` ([`TableLayout::offset`]).
    fn table(&self, layout: &TableLayout) -> Vec<f64> {
        let Cell { dx, dy } = self.cell;
        let nj = layout.nj;
        (0..layout.ni * nj)
            .map(|t| {
                let (di, dj) = (t / nj, t % nj);
                self.coefficient(di as f64 * dx, dj as f64 * dy, t == 0)
            })
            .collect()
    }

    /// The half-space part of S for an offset (x, y) = field point minus
    /// loaded point; `same_point` selects the self-terms.
    fn coefficient(&self, x: f64, y: f64, same_point: bool) -> f64 {
        let Cell { dx, dy } = self.cell;
        self.kernels
            .iter()
            .map(|&(kernel, compliance)| {
                let k = match kernel {
                    Kernel::PointForce if same_point => self.centre / PI,
                    Kernel::PointForce => boussinesq(x, y) / PI,
                    Kernel::UniformPatch => love_rectangle(x, y, dx, dy) / PI,
                    Kernel::Strip { reference_distance } => {
                        2.0 / PI * plane_strain_strip(x, dx, reference_distance)
                    }
                };
                compliance * k
            })
            .sum()
    }
}

/// The cantilever coefficient `a^2 (3 b - a) / (6 E I)` of a beam of
/// flexibility `1 / (E I)` between points at signed distances `dk`, `dj`
/// from its clamp, `a` and `b` the smaller and larger distance; 0 for points
/// on opposite sides or at the clamp.
fn cantilever(flexibility: f64, dk: f64, dj: f64) -> f64 {
    if dk * dj <= 0.0 {
        return 0.0;
    }
    let (a, b) = (dk.abs().min(dj.abs()), dk.abs().max(dj.abs()));
    flexibility * a * a * (3.0 * b - a) / 6.0
}

/// d0 must be finite, positive and at least the extent of the set.
fn check_reference_distance(
    model: &'static str,
    d0: f64,
    points: &PointSet,
) -> Result<(), InfluenceError> {
    let bad = |reason: String| InfluenceError::InvalidModel {
        model,
        field: "reference_distance",
        value: d0,
        reason,
    };
    if !d0.is_finite() {
        return Err(bad("must be finite".into()));
    }
    let extent = points.extent().0;
    if !(d0 >= extent) {
        return Err(bad(format!(
            "must be at least the extent of the point set ({extent}): the 2D displacement is \
             measured from a datum outside the loaded zone, and the logarithmic kernel is \
             positive definite only when d0 exceeds a quarter of the extent"
        )));
    }
    Ok(())
}

/// Where a lattice table applies: the points' lattice indices shifted to
/// start at 0, and the table's extent.
struct TableLayout {
    i: Vec<usize>,
    j: Vec<usize>,
    ni: usize,
    nj: usize,
}

impl TableLayout {
    /// The table index of the offset between points k and j.
    fn offset(&self, k: usize, j: usize) -> usize {
        self.i[k].abs_diff(self.i[j]) * self.nj + self.j[k].abs_diff(self.j[j])
    }
}

/// The table layout if the set has a lattice and the table (one entry per
/// offset in the bounding box) is not much larger than the set.
fn table_layout(points: &PointSet) -> Option<TableLayout> {
    let lattice = points.lattice()?;
    let (mut i_min, mut i_max, mut j_min, mut j_max) = (i64::MAX, i64::MIN, i64::MAX, i64::MIN);
    for &(i, j) in lattice {
        i_min = i_min.min(i);
        i_max = i_max.max(i);
        j_min = j_min.min(j);
        j_max = j_max.max(j);
    }
    let ni = u128::try_from(i128::from(i_max) - i128::from(i_min) + 1).ok()?;
    let nj = u128::try_from(i128::from(j_max) - i128::from(j_min) + 1).ok()?;
    let limit = (TABLE_ENTRIES_PER_POINT * points.len() + 64) as u128;
    if ni.checked_mul(nj)? > limit {
        return None;
    }
    Some(TableLayout {
        i: lattice.iter().map(|&(i, _)| (i - i_min) as usize).collect(),
        j: lattice.iter().map(|&(_, j)| (j - j_min) as usize).collect(),
        ni: ni as usize,
        nj: nj as usize,
    })
}

/// S from one kernel evaluation per lattice offset `(di, dj) >= 0`, gathered
/// column by column.
fn fill_from_table(points: &PointSet, terms: &Terms, layout: &TableLayout) -> Mat<f64> {
    let n = points.len();
    let nj = layout.nj;
    let table = terms.table(layout);
    let mut s = Mat::<f64>::zeros(n, n);
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
    s
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
fn fill_direct(points: &PointSet, terms: &Terms) -> Mat<f64> {
    let n = points.len();
    let (xs, ys) = (points.xs(), points.ys());
    let mut s = Mat::<f64>::zeros(n, n);
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
    s
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::Material;

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
            .position(|&l| l == (0, 0))
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
        let a = influence(&line, &Body::beam(1.0e4, 3.0, 0.0))
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
        let s = assemble(
            &line,
            &[&Body::beam(1.0e4, 3.0, 0.0), &Body::winkler(100.0)],
        )
        .unwrap();
        assert!((s[(5, 5)] - a[(5, 5)] - 1.0 / (100.0 * 0.5)).abs() < 1e-18);
        assert_eq!(s[(5, 6)], a[(5, 6)]);
        // Off-centre loaded point: points on one side only.
        let b = influence(&line, &Body::beam(1.0e4, 3.0, -2.0))
            .unwrap()
            .unwrap();
        let expected = 0.25f64.powi(2) * (3.0 * 3.75 - 0.25) / (6.0 * ei);
        assert!((b[(0, 7)] / expected - 1.0).abs() < 1e-14);
    }

    #[test]
    fn beam_parameters_are_validated() {
        let line = PointSet::line(-1.0, 1.0, 4).unwrap();
        let e = assemble(&line, &[&Body::beam(0.0, 1.0, 0.0)]).unwrap_err();
        assert_eq!(
            e.to_string(),
            "invalid Euler-Bernoulli beam parameter: flexural_rigidity = 0: E I must be finite and positive"
        );
        let e = assemble(&line, &[&Body::beam(1.0, 1.0, f64::NAN)]).unwrap_err();
        assert!(e.to_string().contains("loaded_point = NaN"), "{e}");
        let disk = PointSet::grid_disk(0.1, 0.3).unwrap();
        let e = assemble(&disk, &[&Body::beam(1.0, 1.0, 0.0)]).unwrap_err();
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
                vec![Body::beam(1e3, 1.0, 0.0), Body::winkler(50.0)],
            ),
            (
                PointSet::line(-1.0, 1.0, 8).unwrap(),
                vec![Body::plane_strain(steel, 5.0)],
            ),
        ];
        for (points, bodies) in cases {
            let refs: Vec<&Body> = bodies.iter().collect();
            let f = crate::Folding::detect(&points, &refs).unwrap();
            let s = assemble(&points, &refs).unwrap();
            let m = assemble_folded(&points, &refs, &f).unwrap();
            for a in 0..f.len() {
                for b in 0..f.len() {
                    let t: f64 = f.orbit(b).iter().map(|&j| s[(f.rep(a), j)]).sum();
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
                    Body::beam(1e3, 1.0, 0.0),
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
        let p = PointSet::from_points(
            Dimension::Surface,
            vec![0.0, 1000.0],
            vec![0.0, 0.0],
            Cell::square(1.0),
        )
        .unwrap();
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
