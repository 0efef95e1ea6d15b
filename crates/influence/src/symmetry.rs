//! Mirror symmetry of a contact problem, and the folded influence matrix.
//!
//! If the candidate points and every body's influence model are invariant
//! under a group G of reflections (about x = 0, about y = 0, and the swap
//! of x and y on a square grid), and so are the initial separations, the
//! contact forces are too (the solution is unique for S positive definite):
//! F is constant on every orbit, and only one representative per orbit is
//! an unknown. For representatives i, j (orbits O(i), O(j), stabilizer
//! sizes s_i = |G| / |O(i)|):
//!
//! ```text
//!     (S F)_i = sum_j T_ij F_j,         T_ij = sum_{j' in O(j)} S_{i j'}
//!     M_ij = T_ij / s_i                 (symmetric: s_j T_ij = s_i T_ji)
//! ```
//!
//! so the folded problem keeps a symmetric positive definite matrix, of
//! order a little above N / |G| instead of N (points on a mirror line have
//! smaller orbits). The ideal is a quarter (an eighth on a square grid) of
//! the unknowns, a sixteenth (sixty-fourth) of the memory, 64 (512) times
//! less work for a dense factorization; Hertz spheres on a square grid fold
//! 1653 points to 227 unknowns (1/7.3) and 26,565 to 3400 (1/7.8), about
//! 1/390 and 1/480 of the work. elcon-analysis scales its rows to match.
//!
//! Points are compared on the doubled lattice `(round(2x/dx), round(2y/dy))`,
//! which holds both node-centred (disk) and cell-centred (rectangle, line)
//! grids, and each image's coordinates must match to 1e-12 of the cell.

use std::collections::HashMap;

use crate::models::{Body, Model};
use crate::points::{Dimension, PointSet};

/// A group element acting on doubled lattice coordinates `(u, v)`: `(u, v)`
/// maps to `(su * (u or v), sv * (v or u))`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
struct Element {
    swap: bool,
    su: i64,
    sv: i64,
}

impl Element {
    /// `None` when a coordinate does not fit (points beyond 4.6e18 cells).
    fn apply(self, (u, v): (i64, i64)) -> Option<(i64, i64)> {
        let (a, b) = if self.swap { (v, u) } else { (u, v) };
        Some((self.su.checked_mul(a)?, self.sv.checked_mul(b)?))
    }

    fn apply_xy(self, (x, y): (f64, f64)) -> (f64, f64) {
        let (a, b) = if self.swap { (y, x) } else { (x, y) };
        (self.su as f64 * a, self.sv as f64 * b)
    }
}

/// The symmetry groups tried, largest first.
fn candidates(dimension: Dimension, square: bool) -> Vec<(&'static str, Vec<Element>)> {
    let e = |swap, su, sv| Element { swap, su, sv };
    let klein = vec![
        e(false, 1, 1),
        e(false, -1, 1),
        e(false, 1, -1),
        e(false, -1, -1),
    ];
    match dimension {
        Dimension::Line => vec![("mirror x", vec![e(false, 1, 1), e(false, -1, 1)])],
        Dimension::Surface => {
            let mut groups = Vec::new();
            if square {
                let mut d4 = klein.clone();
                d4.extend([
                    e(true, 1, 1),
                    e(true, -1, 1),
                    e(true, 1, -1),
                    e(true, -1, -1),
                ]);
                groups.push(("mirror x, mirror y, swap x-y", d4));
            }
            groups.push(("mirror x, mirror y", klein));
            groups.push(("mirror x", vec![e(false, 1, 1), e(false, -1, 1)]));
            groups.push(("mirror y", vec![e(false, 1, 1), e(false, 1, -1)]));
            groups
        }
    }
}

/// The orbits of the points under a mirror-symmetry group: which points are
/// unknowns (representatives) and which copy them.
#[derive(Debug, Clone, PartialEq)]
pub struct Folding {
    group: &'static str,
    order: usize,
    /// The orbits, each sorted; its first point is its representative
    /// (the first point of the set not in an earlier orbit).
    orbits: Vec<Vec<usize>>,
    rep_of: Vec<usize>,
}

impl Folding {
    /// The largest reflection group under which `points` and every body's
    /// model are invariant, with at least two elements; `None` if there is
    /// none (then nothing can be folded).
    ///
    /// Models: half-space kernels and Winkler foundations are invariant
    /// under every reflection (the swap of x and y needs square cells); a
    /// beam is invariant under the mirror about its loaded point only if that
    /// point is x = 0.
    pub fn detect(points: &PointSet, bodies: &[&Body]) -> Option<Self> {
        Self::detect_all(points, bodies).into_iter().next()
    }

    /// Every reflection group (of at least two elements) under which
    /// `points` and the models are invariant, largest first: a caller whose
    /// data (separations) break the largest can fold by a smaller one (a
    /// cylinder on a square grid: both mirrors, not the swap of x and y).
    pub fn detect_all(points: &PointSet, bodies: &[&Body]) -> Vec<Self> {
        Self::detect_each(points, bodies).collect()
    }

    /// The groups of [`detect_all`](Self::detect_all), largest first, each
    /// found when the iterator reaches it: a caller that stops at the first
    /// group its data respect holds one group's orbits at a time (about
    /// 60 bytes a point each), not all of them.
    pub fn detect_each<'p>(
        points: &'p PointSet,
        bodies: &[&Body],
    ) -> impl Iterator<Item = Self> + 'p {
        let beam_at_origin = bodies.iter().all(|b| match b.model() {
            Model::Beam { loaded_point, .. } => *loaded_point == 0.0,
            _ => true,
        });
        let cell = points.cell();
        let key = move |k: usize| {
            (
                (2.0 * points.x(k) / cell.dx).round() as i64,
                (2.0 * points.y(k) / cell.dy).round() as i64,
            )
        };
        let index: Option<HashMap<(i64, i64), usize>> = beam_at_origin
            .then(|| (0..points.len()).map(|k| (key(k), k)).collect())
            .filter(|index: &HashMap<_, _>| index.len() == points.len());
        let square = cell.dx == cell.dy;
        let tolerance = 1e-12 * cell.dx.max(cell.dy);
        let groups = match index {
            Some(_) => candidates(points.dimension(), square),
            None => Vec::new(),
        };
        groups.into_iter().filter_map(move |(group, elements)| {
            let index = index.as_ref()?;
            let image = |g: Element, k: usize| -> Option<usize> {
                let j = *index.get(&g.apply(key(k))?)?;
                let (x, y) = g.apply_xy((points.x(k), points.y(k)));
                ((points.x(j) - x).abs() <= tolerance && (points.y(j) - y).abs() <= tolerance)
                    .then_some(j)
            };
            let (orbits, rep_of) = orbits_of(points.len(), &elements, image)?;
            (orbits.len() < points.len()).then_some(Self {
                group,
                order: elements.len(),
                orbits,
                rep_of,
            })
        })
    }

    /// The group's name ("mirror x, mirror y", ...).
    pub fn group(&self) -> &'static str {
        self.group
    }

    /// The group's order |G|.
    pub fn order(&self) -> usize {
        self.order
    }

    /// The number of representatives (the folded problem's size).
    pub fn len(&self) -> usize {
        self.orbits.len()
    }

    /// Whether there is no representative (never: a point set is not empty).
    pub fn is_empty(&self) -> bool {
        self.orbits.is_empty()
    }

    /// The point that represents orbit `a`: its smallest index.
    pub fn rep(&self, a: usize) -> usize {
        self.orbits[a][0]
    }

    /// The points of orbit `a`.
    pub fn orbit(&self, a: usize) -> &[usize] {
        &self.orbits[a]
    }

    /// The orbit of point `k`.
    pub fn rep_of(&self, k: usize) -> usize {
        self.rep_of[k]
    }

    /// The stabilizer size `s_a = |G| / |O(a)|` of orbit `a`.
    pub fn stabilizer(&self, a: usize) -> f64 {
        (self.order / self.orbits[a].len()) as f64
    }

    /// Whether `values` (one per point) are constant on every orbit, to
    /// `tolerance` times their largest magnitude.
    pub fn is_invariant(&self, values: &[f64], tolerance: f64) -> bool {
        let scale = values.iter().fold(0.0f64, |a, v| a.max(v.abs()));
        self.orbits.iter().all(|orbit| {
            let v0 = values[orbit[0]];
            orbit
                .iter()
                .all(|&j| (values[j] - v0).abs() <= tolerance * scale)
        })
    }

    /// Values on the representatives, copied to every point of each orbit.
    pub fn unfold(&self, folded: &[f64]) -> Vec<f64> {
        self.rep_of.iter().map(|&a| folded[a]).collect()
    }
}

/// The orbits of the points `0..n` under `elements` (a group: the identity
/// first), each sorted, and the orbit of every point; `None` as soon as a
/// point has no image under some element.
///
/// The points are visited in order and a point not yet in an orbit starts
/// one, so every orbit's first (smallest) point is the one that started it:
/// any smaller point of the orbit would have been visited earlier and put
/// this one in its orbit (orbits of a group are disjoint).
fn orbits_of(
    n: usize,
    elements: &[Element],
    image: impl Fn(Element, usize) -> Option<usize>,
) -> Option<(Vec<Vec<usize>>, Vec<usize>)> {
    let mut rep_of = vec![usize::MAX; n];
    let mut orbits: Vec<Vec<usize>> = Vec::new();
    for k in 0..n {
        if rep_of[k] != usize::MAX {
            continue;
        }
        let mut orbit = Vec::with_capacity(elements.len());
        for &g in elements {
            let j = image(g, k)?;
            if !orbit.contains(&j) {
                orbit.push(j);
            }
        }
        orbit.sort_unstable();
        debug_assert_eq!(orbit[0], k, "an orbit starts at its smallest point");
        for &j in &orbit {
            rep_of[j] = orbits.len();
        }
        orbits.push(orbit);
    }
    Some((orbits, rep_of))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::Material;

    #[test]
    fn a_disk_has_the_square_group() {
        let p = PointSet::grid_disk(1.0, 3.0).unwrap();
        let steel = Material::new(30e6, 0.3).unwrap();
        let f = Folding::detect(&p, &[&Body::uniform_patch(steel)]).unwrap();
        assert_eq!(f.order(), 8);
        // Every point is in exactly one orbit, the orbits cover the set.
        let total: usize = (0..f.len()).map(|a| f.orbit(a).len()).sum();
        assert_eq!(total, p.len());
        // The centre is its own orbit (stabilizer 8); a generic point has 8 images.
        let centre = (0..p.len()).find(|&k| p.radius(k) == 0.0).unwrap();
        assert_eq!(f.stabilizer(f.rep_of(centre)), 8.0);
        assert!((0..f.len()).any(|a| f.orbit(a).len() == 8));
        // 29 points of radius <= 3: orbits of the octant 0 <= y <= x.
        assert_eq!(p.len(), 29);
        assert_eq!(f.len(), 7); // (0,0), (1,0), (2,0), (3,0), (1,1), (2,1), (2,2)
    }

    #[test]
    fn each_representative_is_the_smallest_point_of_its_orbit() {
        let steel = Material::new(30e6, 0.3).unwrap();
        let disk = PointSet::grid_disk(1.0, 4.0).unwrap();
        let rectangle = PointSet::grid_rectangle(1.0, 5.0, 4, 7).unwrap();
        let line = PointSet::line(-2.0, 2.0, 9).unwrap();
        let patch = Body::uniform_patch(steel);
        let winkler = Body::winkler(1.0);
        for (p, body) in [(&disk, &patch), (&rectangle, &patch), (&line, &winkler)] {
            for f in Folding::detect_all(p, &[body]) {
                for a in 0..f.len() {
                    let orbit = f.orbit(a);
                    assert_eq!(f.rep(a), *orbit.iter().min().unwrap(), "{}", f.group());
                    assert!(orbit.iter().all(|&j| f.rep_of(j) == a));
                }
                // Every point is in the orbit it is filed under.
                for k in 0..p.len() {
                    assert!(f.orbit(f.rep_of(k)).contains(&k));
                }
            }
        }
    }

    #[test]
    fn a_rectangle_of_oblong_cells_has_the_two_mirrors() {
        let p = PointSet::grid_rectangle(1.0, 5.0, 4, 7).unwrap();
        let f = Folding::detect(&p, &[&Body::winkler(3.0)]).unwrap();
        assert_eq!((f.order(), f.group()), (4, "mirror x, mirror y"));
        assert_eq!(f.len(), 2 * 4);
    }

    #[test]
    fn a_beam_folds_only_about_its_loaded_point_at_the_origin() {
        let line = PointSet::line(-2.0, 2.0, 10).unwrap();
        let f = Folding::detect(&line, &[&Body::beam(1.0, 1.0, 0.0), &Body::winkler(1.0)]).unwrap();
        assert_eq!((f.order(), f.len()), (2, 5));
        assert_eq!(f.unfold(&[1.0, 2.0, 3.0, 4.0, 5.0])[9], 1.0);
        assert!(Folding::detect(&line, &[&Body::beam(1.0, 1.0, 0.5)]).is_none());
        // An asymmetric set does not fold.
        let shifted = PointSet::line(-2.0, 3.0, 10).unwrap();
        assert!(Folding::detect(&shifted, &[&Body::winkler(1.0)]).is_none());
    }

    #[test]
    fn every_group_is_offered_largest_first() {
        let p = PointSet::grid_disk(1.0, 3.0).unwrap();
        let groups: Vec<usize> = Folding::detect_all(&p, &[&Body::winkler(1.0)])
            .iter()
            .map(|f| f.order())
            .collect();
        assert_eq!(groups, [8, 4, 2, 2]);
    }

    #[test]
    fn invariance_of_values() {
        let line = PointSet::line(-1.0, 1.0, 4).unwrap();
        let f = Folding::detect(&line, &[&Body::winkler(1.0)]).unwrap();
        assert!(f.is_invariant(&[1.0, 2.0, 2.0, 1.0], 0.0));
        assert!(!f.is_invariant(&[1.0, 2.0, 2.0, 1.5], 1e-12));
    }
}
