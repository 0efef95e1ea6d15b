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
//! A point's image is looked up in the set's lattice index (a grid's runs;
//! a table over a listed lattice's box, about 5 bytes a point) or, for a
//! set without a lattice, in a map of the doubled lattice
//! `(round(2x/dx), round(2y/dy))`,
//! which holds both node-centred (disk) and cell-centred (rectangle, line)
//! grids; each image's coordinates must match to 1e-12 of the cell. The
//! orbits are stored flat, 4 bytes a point and 4 an orbit, with the orbit
//! of each point (4 bytes a point).

use std::collections::HashMap;

use crate::models::{Body, Model};
use crate::points::{Cell, Dimension, LatticeIndex, PointSet};

/// A group element acting on coordinates: `(x, y)` maps to
/// `(su * (x or y), sv * (y or x))`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
struct Element {
    swap: bool,
    su: i64,
    sv: i64,
}

/// The identity, every group's first element.
const IDENTITY: Element = Element {
    swap: false,
    su: 1,
    sv: 1,
};

impl Element {
    fn apply_xy(self, (x, y): (f64, f64)) -> (f64, f64) {
        let (a, b) = if self.swap { (y, x) } else { (x, y) };
        (self.su as f64 * a, self.sv as f64 * b)
    }
}

/// The symmetry groups tried, largest first.
fn candidates(dimension: Dimension, square: bool) -> Vec<(&'static str, Vec<Element>)> {
    let e = |swap, su, sv| Element { swap, su, sv };
    let klein = vec![IDENTITY, e(false, -1, 1), e(false, 1, -1), e(false, -1, -1)];
    match dimension {
        Dimension::Line => vec![("mirror x", vec![IDENTITY, e(false, -1, 1)])],
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
            groups.push(("mirror x", vec![IDENTITY, e(false, -1, 1)]));
            groups.push(("mirror y", vec![IDENTITY, e(false, 1, -1)]));
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
    /// The points of the orbits, orbit by orbit, each orbit sorted; its
    /// first point is its representative (the first point of the set not
    /// in an earlier orbit).
    members: Vec<u32>,
    /// Orbit a is `members[starts[a]..starts[a + 1]]`.
    starts: Vec<u32>,
    /// The orbit of each point.
    rep_of: Vec<u32>,
}

/// Where the point at a position is: a lattice set's index, or a map of
/// the doubled lattice's keys.
enum Lookup {
    Lattice {
        index: LatticeIndex,
        /// Point 0's coordinates and lattice indices.
        origin: (f64, f64),
        base: (i64, i64),
        cell: Cell,
    },
    Keys {
        map: HashMap<(i64, i64), u32>,
        cell: Cell,
    },
}

impl Lookup {
    /// `None` when two points share a lattice cell or a doubled key (then
    /// no image is unique and nothing folds).
    fn new(points: &PointSet) -> Option<Self> {
        let cell = points.cell();
        if let (Some(lattice), Some(index)) = (points.lattice(), points.lattice_index()) {
            let distinct = points.lattice_is_distinct(&index);
            return distinct.then(|| Self::Lattice {
                index,
                origin: (points.x(0), points.y(0)),
                base: lattice.get(0),
                cell,
            });
        }
        let map: HashMap<(i64, i64), u32> = (0..points.len())
            .map(|k| (doubled_key((points.x(k), points.y(k)), cell), k as u32))
            .collect();
        (map.len() == points.len()).then_some(Self::Keys { map, cell })
    }

    /// The point of `points` nearest `(x, y)` on the lattice, if the set
    /// holds one there, and its coordinates.
    fn find(&self, points: &PointSet, (x, y): (f64, f64)) -> Option<(usize, (f64, f64))> {
        match self {
            Self::Lattice {
                index,
                origin,
                base,
                cell,
            } => {
                let i = base.0.checked_add(nearest((x - origin.0) / cell.dx))?;
                let j = base.1.checked_add(nearest((y - origin.1) / cell.dy))?;
                let k = index.get((i, j))?;
                Some((k, points.position_at(k, (i, j))))
            }
            Self::Keys { map, cell } => {
                let k = *map.get(&doubled_key((x, y), *cell))? as usize;
                Some((k, (points.x(k), points.y(k))))
            }
        }
    }
}

/// `v.round() as i64` (halves away from zero; NaN to 0, beyond the
/// integers' range to their ends), without the call to libm's `round` that
/// the baseline x86-64 target makes of it: the truncation and the
/// fraction it leaves (exact, `|v - trunc(v)| < 1`) decide.
fn nearest(v: f64) -> i64 {
    let t = v as i64;
    let fraction = v - t as f64;
    if fraction >= 0.5 {
        t.saturating_add(1)
    } else if fraction <= -0.5 {
        t.saturating_sub(1)
    } else {
        t
    }
}

/// The doubled lattice coordinates `(round(2x/dx), round(2y/dy))`.
fn doubled_key((x, y): (f64, f64), cell: Cell) -> (i64, i64) {
    (nearest(2.0 * x / cell.dx), nearest(2.0 * y / cell.dy))
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
    /// group its data respect holds one group's orbits at a time (about 8.5
    /// bytes a point; 13 with a listed lattice's index), not all of them.
    pub fn detect_each<'p>(
        points: &'p PointSet,
        bodies: &[&Body],
    ) -> impl Iterator<Item = Self> + 'p {
        let beam_at_origin = bodies.iter().all(|b| match b.model() {
            Model::Beam { loaded_point, .. } => *loaded_point == 0.0,
            _ => true,
        });
        let cell = points.cell();
        let lookup = if beam_at_origin {
            Lookup::new(points)
        } else {
            None
        };
        let square = cell.dx == cell.dy;
        let tolerance = 1e-12 * cell.dx.max(cell.dy);
        let groups = match lookup {
            Some(_) => candidates(points.dimension(), square),
            None => Vec::new(),
        };
        groups.into_iter().filter_map(move |(group, elements)| {
            let lookup = lookup.as_ref()?;
            let image = |g: Element, at: (f64, f64)| -> Option<usize> {
                let (x, y) = g.apply_xy(at);
                let (j, (xj, yj)) = lookup.find(points, (x, y))?;
                ((xj - x).abs() <= tolerance && (yj - y).abs() <= tolerance).then_some(j)
            };
            let orbits = orbits_of(points.len(), points.positions(), &elements, image)?;
            (orbits.starts.len() - 1 < points.len()).then_some(Self {
                group,
                order: elements.len(),
                members: orbits.members,
                starts: orbits.starts,
                rep_of: orbits.rep_of,
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
        self.starts.len() - 1
    }

    /// Whether there is no representative (never: a point set is not empty).
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// The point that represents orbit `a`: its smallest index.
    pub fn rep(&self, a: usize) -> usize {
        self.members[self.starts[a] as usize] as usize
    }

    /// The points of orbit `a`, in increasing order.
    pub fn orbit(&self, a: usize) -> impl ExactSizeIterator<Item = usize> + Clone + '_ {
        let range = self.starts[a] as usize..self.starts[a + 1] as usize;
        self.members[range].iter().map(|&k| k as usize)
    }

    /// The orbit of point `k`.
    pub fn rep_of(&self, k: usize) -> usize {
        self.rep_of[k] as usize
    }

    /// The stabilizer size `s_a = |G| / |O(a)|` of orbit `a`.
    pub fn stabilizer(&self, a: usize) -> f64 {
        (self.order / (self.starts[a + 1] - self.starts[a]) as usize) as f64
    }

    /// Whether `values` (one per point) are constant on every orbit, to
    /// `tolerance` times their largest magnitude.
    pub fn is_invariant(&self, values: &[f64], tolerance: f64) -> bool {
        let scale = values.iter().fold(0.0f64, |a, v| a.max(v.abs()));
        (0..self.len()).all(|a| {
            let v0 = values[self.rep(a)];
            self.orbit(a)
                .all(|j| (values[j] - v0).abs() <= tolerance * scale)
        })
    }

    /// Values on the representatives, copied to every point of each orbit.
    pub fn unfold(&self, folded: &[f64]) -> Vec<f64> {
        self.rep_of.iter().map(|&a| folded[a as usize]).collect()
    }
}

/// Orbits stored flat (see [`Folding`]'s fields).
struct Orbits {
    members: Vec<u32>,
    starts: Vec<u32>,
    rep_of: Vec<u32>,
}

/// The orbits of the points `0..n` at `positions` under `elements` (a
/// group: the identity first), each sorted, and the orbit of every point;
/// `None` as soon as a point has no image under some element
/// (`image(g, position)`).
///
/// The points are visited in order and a point not yet in an orbit starts
/// one, so every orbit's first (smallest) point is the one that started it:
/// any smaller point of the orbit would have been visited earlier and put
/// this one in its orbit (orbits of a group are disjoint).
fn orbits_of(
    n: usize,
    positions: impl Iterator<Item = (f64, f64)>,
    elements: &[Element],
    image: impl Fn(Element, (f64, f64)) -> Option<usize>,
) -> Option<Orbits> {
    debug_assert_eq!(elements.first(), Some(&IDENTITY), "the identity first");
    // Indices fit in u32: a point set holds at most MAX_POINTS = 2^22.
    let mut rep_of = vec![u32::MAX; n];
    let mut members = Vec::with_capacity(n);
    let mut starts = vec![0u32];
    let mut orbit = Vec::with_capacity(elements.len());
    // One walk of the `n` points (`fold`: a grid's run by run); after a
    // point without an image the rest are passed over.
    let complete = positions.enumerate().fold(true, |complete, (k, at)| {
        if !complete || rep_of[k] != u32::MAX {
            return complete;
        }
        // The identity (first) maps k to itself: not looked up.
        orbit.clear();
        orbit.push(k);
        for &g in &elements[1..] {
            let Some(j) = image(g, at) else {
                return false;
            };
            if !orbit.contains(&j) {
                orbit.push(j);
            }
        }
        orbit.sort_unstable();
        debug_assert_eq!(orbit[0], k, "an orbit starts at its smallest point");
        let a = (starts.len() - 1) as u32;
        for &j in &orbit {
            rep_of[j] = a;
            members.push(j as u32);
        }
        starts.push(members.len() as u32);
        true
    });
    if !complete {
        return None;
    }
    members.shrink_to_fit();
    starts.shrink_to_fit();
    Some(Orbits {
        members,
        starts,
        rep_of,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::Material;
    use crate::fixtures::{UNIT_BEAM, surface};
    use crate::models::Beam;

    #[test]
    fn nearest_rounds_as_round_does() {
        let halves = [
            0.5,
            1.5,
            2.5,
            -0.5,
            -1.5,
            0.49999999999999994,
            4503599627370495.5,
        ];
        let ends = [
            f64::NAN,
            f64::INFINITY,
            f64::NEG_INFINITY,
            1e300,
            -1e300,
            9.3e18,
        ];
        let plain = [
            0.0,
            -0.0,
            0.3,
            -0.7,
            12.999999999999998,
            1e-320,
            2.0f64.powi(60),
        ];
        for v in halves.into_iter().chain(ends).chain(plain) {
            assert_eq!(nearest(v), v.round() as i64, "{v}");
            assert_eq!(nearest(-v), (-v).round() as i64, "{}", -v);
        }
    }

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
                    let mut orbit = f.orbit(a);
                    assert_eq!(f.rep(a), orbit.clone().min().unwrap(), "{}", f.group());
                    assert!(orbit.all(|j| f.rep_of(j) == a));
                }
                // Every point is in the orbit it is filed under.
                for k in 0..p.len() {
                    assert!(f.orbit(f.rep_of(k)).any(|j| j == k));
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
        let f = Folding::detect(
            &line,
            &[&Body::beam(UNIT_BEAM).unwrap(), &Body::winkler(1.0)],
        )
        .unwrap();
        assert_eq!((f.order(), f.len()), (2, 5));
        assert_eq!(f.unfold(&[1.0, 2.0, 3.0, 4.0, 5.0])[9], 1.0);
        assert!(
            Folding::detect(
                &line,
                &[&Body::beam(Beam {
                    loaded_point: 0.5,
                    ..UNIT_BEAM
                })
                .unwrap()]
            )
            .is_none()
        );
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
    fn images_are_found_on_and_off_a_lattice_and_twins_do_not_fold() {
        let winkler = Body::winkler(1.0);
        // Off any lattice: the doubled keys; symmetric about x = 0 only.
        let scattered = surface(vec![-0.37, 0.37, 0.0], vec![0.11, 0.11, 0.5], 0.1);
        assert!(scattered.lattice().is_none());
        let f = Folding::detect(&scattered, &[&winkler]).unwrap();
        assert_eq!((f.group(), f.len()), ("mirror x", 2));
        assert_eq!(f.orbit(0).collect::<Vec<_>>(), [0, 1]);
        // On a lattice not centred on the origin's cell: the lattice index.
        let shifted = surface(
            vec![-0.15, -0.05, 0.05, 0.15],
            vec![0.3, 0.3, 0.3, 0.3],
            0.1,
        );
        assert!(shifted.lattice().is_some());
        let f = Folding::detect(&shifted, &[&winkler]).unwrap();
        assert_eq!((f.group(), f.len()), ("mirror x", 2));
        assert_eq!(f.orbit(1).collect::<Vec<_>>(), [1, 2]);
        assert_eq!((f.rep_of(3), f.stabilizer(0)), (0, 1.0));
        // Two points within the lattice tolerance of one cell: no image is
        // unique, nothing folds.
        let twins = surface(vec![-1.0, 0.0, 1e-14, 1.0], vec![0.0; 4], 1.0);
        assert!(twins.lattice().is_some());
        assert!(Folding::detect(&twins, &[&winkler]).is_none());
    }

    #[test]
    fn invariance_of_values() {
        let line = PointSet::line(-1.0, 1.0, 4).unwrap();
        let f = Folding::detect(&line, &[&Body::winkler(1.0)]).unwrap();
        assert!(f.is_invariant(&[1.0, 2.0, 2.0, 1.0], 0.0));
        assert!(!f.is_invariant(&[1.0, 2.0, 2.0, 1.5], 1e-12));
    }
}
