//! The contact's extent resolved within a cell.
//!
//! The cells in contact overstate the contact: the outermost points carry a
//! little force and their whole cells count. Near a smooth edge the
//! pressure falls like the square root of the distance to it (Hertz:
//! `p^2 = p0^2 (1 - r^2 / a^2)`, linear in r near r = a), so along each
//! grid direction that leaves the contact at point k, the straight line
//! through `p^2` at k and at the point behind it reaches zero at
//!
//! ```text
//!     t = h p_k^2 / (p_behind^2 - p_k^2)        beyond x_k,  clamped to [0, h]
//! ```
//!
//! and the contact's edge point on that side lies there. On a line the
//! contact's length is the sum of its cells', each side that leaves the
//! contact reaching t instead of h / 2. On a surface the edge points,
//! joined in order of their angle about the centre of pressure, make a
//! polygon whose area is the contact's (a star-shaped contact: Hertz's
//! ellipses, a roller's patch; a contact of another shape, whose polygon
//! would cross itself, keeps its cells' area).
//! On a Winkler foundation alone (no half-space body) the pressure is the
//! foundation's deflection, which crosses zero linearly: there p itself,
//! not p^2, is extrapolated. Where the pressure does not fall toward the
//! edge (a flat punch's rises to it) or no point lies behind, the cell
//! counts whole (t = h / 2), as it does for a problem built from a given S
//! (`ContactProblem::from_parts`), whose edge law is not known.

use std::cell::OnceCell;

use elcon_influence::{Body, Dimension, Lattice, LatticeIndex, Model, PointSet};

/// How the pressure falls to zero at a smooth edge of the contact.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum EdgeLaw {
    /// Like the square root of the distance (an elastic half-space body).
    SquareRoot,
    /// Linearly (foundations and beams only).
    Linear,
    /// Not known: whole cells.
    Cells,
}

impl EdgeLaw {
    /// The law of two bodies: a half-space model in either sets it.
    pub(crate) fn of(bodies: [&Body; 2]) -> Self {
        let half_space = bodies.iter().any(|b| {
            matches!(
                b.model(),
                Model::PointForce { .. }
                    | Model::UniformPatch { .. }
                    | Model::PlaneStrainStrip { .. }
            )
        });
        if half_space {
            Self::SquareRoot
        } else {
            Self::Linear
        }
    }

    /// The power q of the pressure that is linear in the distance.
    fn power(self) -> Option<i32> {
        match self {
            Self::SquareRoot => Some(2),
            Self::Linear => Some(1),
            Self::Cells => None,
        }
    }
}

/// The points of `points` on the bodies' own edges (`body_edges`: the
/// zone's extent along x, resp. y, is the bodies', see
/// `ContactProblem::with_body_edges`) where the pressure of an elastic
/// half-space (`law` [`EdgeLaw::SquareRoot`]) is singular if the contact
/// reaches them: a roller's ends, a punch's rim. None under any other law
/// (a foundation's or a beam's pressure is bounded at an edge).
pub(crate) fn singular_edge_points(
    points: &PointSet,
    (along_x, along_y): (bool, bool),
    law: EdgeLaw,
) -> Vec<usize> {
    if law != EdgeLaw::SquareRoot || !(along_x || along_y) {
        return Vec::new();
    }
    (0..points.len())
        .filter(|&k| {
            let (x, y) = points.open_sides(k);
            (x && along_x) || (y && along_y)
        })
        .collect()
}

/// A solution's pressures on its points, read for the contact's edge: the
/// lattice's index built once (the measure and every boundary point's
/// truncation test use it), and the outline found once.
pub(crate) struct Edge<'a> {
    points: &'a PointSet,
    pressures: &'a [f64],
    /// The lattice, its index and the power q of the law; `None` where the
    /// edge cannot be resolved (points not on a lattice, an unknown law).
    grid: Option<Grid<'a>>,
    /// [`Edge::outline`], once asked for.
    outline: OnceCell<Option<Vec<(f64, f64)>>>,
}

/// The lattice coordinates of the points, their index, and q.
struct Grid<'a> {
    lattice: Lattice<'a>,
    index: LatticeIndex,
    q: i32,
}

impl<'a> Edge<'a> {
    /// The edge of the contact where `pressures > 0`, under `law`.
    pub(crate) fn new(points: &'a PointSet, pressures: &'a [f64], law: EdgeLaw) -> Self {
        let grid = law.power().and_then(|q| {
            Some(Grid {
                lattice: points.lattice()?,
                index: points.lattice_index()?,
                q,
            })
        });
        Self {
            points,
            pressures,
            grid,
            outline: OnceCell::new(),
        }
    }

    /// The cells' measure of the contact: the sum of the measures of the
    /// points where the pressure is positive.
    fn cells(&self) -> f64 {
        (0..self.points.len())
            .filter(|&k| self.pressures[k] > 0.0)
            .map(|k| self.points.measure(k))
            .sum()
    }

    /// [`Edge::outline`] of the contact's cells, found on the first call.
    fn outline_once(&self) -> Option<&[(f64, f64)]> {
        self.outline
            .get_or_init(|| self.outline(self.cells()))
            .as_deref()
    }

    /// The point at lattice coordinates `ij`, if it is in contact.
    fn pressed(&self, g: &Grid<'_>, ij: (i64, i64)) -> Option<usize> {
        g.index.get(ij).filter(|&k| self.pressures[k] > 0.0)
    }

    /// How far beyond point k, toward `(di, dj)` (spacing h), `p^q`
    /// extrapolated from k and the point behind it reaches zero; `None`
    /// where it cannot be told (no point behind, a pressure that does not
    /// fall toward the side).
    fn beyond(&self, g: &Grid<'_>, k: usize, (di, dj): (i64, i64), h: f64) -> Option<f64> {
        let (i, j) = g.lattice.get(k);
        let b = self.pressed(g, (i - di, j - dj))?;
        let (pk, pb) = (self.pressures[k], self.pressures[b]);
        (pb > pk && pk > 0.0).then(|| {
            // h pk^q / (pb^q - pk^q), on the ratio: powers of pressures
            // near the bottom (or top) of the doubles would underflow (or
            // overflow) to 0 / 0.
            let r = (pk / pb).powi(g.q);
            h * r / (1.0 - r)
        })
    }

    /// Where the contact of point k reaches toward `(di, dj)`: h / 2 when
    /// the neighbour is in contact, else the extrapolated edge within
    /// `[0, h]` (h / 2 where it cannot be told).
    fn reach(&self, g: &Grid<'_>, k: usize, (di, dj): (i64, i64), h: f64) -> f64 {
        let (i, j) = g.lattice.get(k);
        if self.pressed(g, (i + di, j + dj)).is_some() {
            return 0.5 * h;
        }
        self.open_reach(g, k, (di, dj), h)
    }

    /// [`Edge::reach`] toward a neighbour known not to be in contact: the
    /// extrapolated edge within `[0, h]` (h / 2 where it cannot be told).
    fn open_reach(&self, g: &Grid<'_>, k: usize, toward: (i64, i64), h: f64) -> f64 {
        self.beyond(g, k, toward, h)
            .map_or(0.5 * h, |t| t.clamp(0.0, h))
    }

    /// Whether the contact at point k, on the candidate zone's boundary,
    /// may go on beyond it: along some open side (`open_x`, `open_y`: a
    /// side whose neighbour cell is missing), the extrapolated edge does
    /// not end inside k's cell, or that cannot be told. A contact that
    /// ends within its outermost cells is not cut off by the zone.
    pub(crate) fn may_be_truncated(&self, k: usize, (open_x, open_y): (bool, bool)) -> bool {
        let Some(g) = &self.grid else {
            return true;
        };
        let cell = self.points.cell();
        let (i, j) = g.lattice.get(k);
        let mut sides = Vec::new();
        if open_x {
            sides.extend([(1, 0, cell.dx), (-1, 0, cell.dx)]);
        }
        if open_y && self.points.dimension() == Dimension::Surface {
            sides.extend([(0, 1, cell.dy), (0, -1, cell.dy)]);
        }
        sides
            .into_iter()
            .filter(|&(di, dj, _)| g.index.get((i + di, j + dj)).is_none())
            .any(|(di, dj, h)| self.beyond(g, k, (di, dj), h).is_none_or(|t| t >= 0.5 * h))
    }

    /// The measure (area on a surface, length on a line) of the contact,
    /// its edge resolved within the cells (see the module documentation);
    /// the cells' own measure where the edge cannot be resolved.
    pub(crate) fn measure(&self) -> f64 {
        let (points, pressures) = (self.points, self.pressures);
        let cells = self.cells();
        let Some(g) = &self.grid else {
            return cells;
        };
        let cell = points.cell();
        if points.dimension() == Dimension::Line {
            return (0..points.len())
                .filter(|&k| pressures[k] > 0.0)
                .map(|k| self.reach(g, k, (1, 0), cell.dx) + self.reach(g, k, (-1, 0), cell.dx))
                .sum();
        }
        self.outline_once().map_or(cells, polygon_area)
    }

    /// On a surface: the edge points along every face that leaves the
    /// contact, in order of their angle about the contact's centre of
    /// pressure (a star-shaped contact: Hertz's ellipses, a roller's
    /// patch); `None` when fewer than 3, or when their polygon's area
    /// differs from the cells' `cells` by more than the edge faces can move
    /// it (a contact that is not star-shaped about its centre, two patches,
    /// a ring, makes a polygon that crosses itself).
    fn outline(&self, cells: f64) -> Option<Vec<(f64, f64)>> {
        let (points, pressures) = (self.points, self.pressures);
        let g = self.grid.as_ref()?;
        let cell = points.cell();
        // The centre of pressure, the points walked in order (a grid's by
        // its runs, not point by point).
        let total: f64 = pressures.iter().filter(|&&p| p > 0.0).sum();
        let centre =
            points.positions().enumerate().fold(
                (0.0, 0.0),
                |(x, y), (k, (xk, yk))| match pressures[k] > 0.0 {
                    true => (x + pressures[k] * xk, y + pressures[k] * yk),
                    false => (x, y),
                },
            );
        let (cx, cy) = (centre.0 / total, centre.1 / total);
        // Whether the neighbour at `ij` is pressed: a mask of the pressed
        // cells where it is small, else the index.
        let mask = PressedCells::new(g.lattice, pressures);
        let pressed = |ij| match &mask {
            Some(m) => m.has(ij),
            None => self.pressed(g, ij).is_some(),
        };
        let mut edge: Vec<(f64, f64, f64)> = Vec::new();
        g.lattice.iter().enumerate().for_each(|(k, (i, j))| {
            if !(pressures[k] > 0.0) {
                return;
            }
            for (di, dj, h) in [
                (1, 0, cell.dx),
                (-1, 0, cell.dx),
                (0, 1, cell.dy),
                (0, -1, cell.dy),
            ] {
                if pressed((i + di, j + dj)) {
                    continue;
                }
                // A point on the contact's edge (a few in a thousand):
                // its coordinates looked up.
                let (xk, yk) = (points.x(k), points.y(k));
                let t = self.open_reach(g, k, (di, dj), h);
                let (x, y) = (xk + di as f64 * t, yk + dj as f64 * t);
                edge.push(((y - cy).atan2(x - cx), x, y));
            }
        });
        if edge.len() < 3 {
            return None;
        }
        edge.sort_by(|a, b| a.0.total_cmp(&b.0));
        let edge: Vec<(f64, f64)> = edge.into_iter().map(|(_, x, y)| (x, y)).collect();
        let polygon = polygon_area(&edge);
        (!((polygon - cells).abs() > edge.len() as f64 * cell.dx * cell.dy)).then_some(edge)
    }
}

/// The lattice cells that hold a pressed point, a flag a cell over the
/// pressed points' bounding box, for the outline's neighbour tests (four
/// a pressed point): a byte read where the index would search its runs.
struct PressedCells {
    i0: i64,
    j0: i64,
    ni: i64,
    nj: i64,
    cells: Vec<bool>,
}

/// The mask is built where its box holds at most this many cells a
/// pressed point (a contact on a grid: about 1.3; a sparse listed set
/// asks the index instead).
const MASK_CELLS_PER_POINT: usize = 16;

impl PressedCells {
    /// The mask of the points of `lattice` where `pressures > 0`; `None`
    /// when none is pressed or the box is too large for them.
    fn new(lattice: Lattice<'_>, pressures: &[f64]) -> Option<Self> {
        let (mut lo, mut hi, mut count) = ((i64::MAX, i64::MAX), (i64::MIN, i64::MIN), 0usize);
        lattice.iter().enumerate().for_each(|(k, (i, j))| {
            if pressures[k] > 0.0 {
                (lo, hi) = ((lo.0.min(i), lo.1.min(j)), (hi.0.max(i), hi.1.max(j)));
                count += 1;
            }
        });
        let side = |lo: i64, hi: i64| hi.checked_sub(lo)?.checked_add(1);
        let (ni, nj) = (side(lo.0, hi.0)?, side(lo.1, hi.1)?);
        let size = usize::try_from(ni)
            .ok()?
            .checked_mul(usize::try_from(nj).ok()?)?;
        // (Nothing pressed leaves an empty box: `side` gave `None` above.)
        if size > MASK_CELLS_PER_POINT.saturating_mul(count) {
            return None;
        }
        let mut mask = Self {
            i0: lo.0,
            j0: lo.1,
            ni,
            nj,
            cells: vec![false; size],
        };
        lattice.iter().enumerate().for_each(|(k, ij)| {
            if pressures[k] > 0.0 {
                let at = mask.at(ij).expect("a pressed point is in its own box");
                mask.cells[at] = true;
            }
        });
        Some(mask)
    }

    /// The flag's position of cell `(i, j)`, if in the box.
    fn at(&self, (i, j): (i64, i64)) -> Option<usize> {
        let (r, c) = (i.checked_sub(self.i0)?, j.checked_sub(self.j0)?);
        ((0..self.ni).contains(&r) && (0..self.nj).contains(&c)).then(|| (r * self.nj + c) as usize)
    }

    /// Whether cell `(i, j)` holds a pressed point.
    fn has(&self, ij: (i64, i64)) -> bool {
        self.at(ij).is_some_and(|at| self.cells[at])
    }
}

/// The area of the polygon of `vertices` (in order, either sense), by the
/// shoelace sum: with `c_i = x_i y_{i+1} - x_{i+1} y_i`, `A = |sum c_i| / 2`.
fn polygon_area(vertices: &[(f64, f64)]) -> f64 {
    let m = vertices.len();
    let twice: f64 = (0..m)
        .map(|i| {
            let (x0, y0) = vertices[i];
            let (x1, y1) = vertices[(i + 1) % m];
            x0 * y1 - x1 * y0
        })
        .sum();
    0.5 * twice.abs()
}

/// The extent of the points `contact` (indices into `points`) along x
/// and, on a surface, along y: point to point plus a cell,
/// `max x - min x + dx` (and the same in y). `None` for an empty contact.
pub(crate) fn contact_spans(
    points: &PointSet,
    contact: impl Iterator<Item = usize> + Clone,
) -> Option<(f64, Option<f64>)> {
    let cell = points.cell();
    let span = |of: &dyn Fn(usize) -> f64, size: f64| {
        let (lo, hi) = contact
            .clone()
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), k| {
                (lo.min(of(k)), hi.max(of(k)))
            });
        (lo <= hi).then_some(hi - lo + size)
    };
    let along_x = span(&|k| points.x(k), cell.dx)?;
    Some(match points.dimension() {
        Dimension::Line => (along_x, None),
        Dimension::Surface => (along_x, span(&|k| points.y(k), cell.dy)),
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_pressed_cells_mask_answers_as_the_index() {
        // A ring of pressure on a disk grid (a hole inside, cells outside):
        // every point's four neighbours, pressed or not, read the same from
        // the mask as from the index.
        let points = PointSet::grid_disk(0.1, 1.0).unwrap();
        let p: Vec<f64> = (0..points.len())
            .map(|k| {
                let r = points.radius(k);
                if (0.3..0.8).contains(&r) {
                    1.0 - r
                } else {
                    0.0
                }
            })
            .collect();
        let edge = Edge::new(&points, &p, EdgeLaw::SquareRoot);
        let g = edge.grid.as_ref().unwrap();
        let mask = PressedCells::new(g.lattice, &p).expect("a compact contact");
        for (i, j) in g.lattice.iter() {
            for ij in [(i, j), (i + 1, j), (i - 1, j), (i, j + 1), (i, j - 1)] {
                assert_eq!(mask.has(ij), edge.pressed(g, ij).is_some(), "{ij:?}");
            }
        }
        // Nothing pressed, or two pressed points far apart on a fine
        // lattice (a box of 10^6 cells for 2 points): no mask, the index.
        assert!(PressedCells::new(g.lattice, &vec![0.0; p.len()]).is_none());
        let cell = elcon_influence::Cell::square(1e-3);
        let far = PointSet::from_points(Dimension::Surface, vec![0.0, 1.0], vec![0.0, 1.0], cell)
            .unwrap();
        assert!(PressedCells::new(far.lattice().unwrap(), &[1.0, 1.0]).is_none());
    }

    #[test]
    fn an_exact_square_root_profile_gives_its_edge() {
        // p^2 = 1 - x on a line of unit cells: the edge at x = 1 exactly,
        // whatever the grid; the contact [-1, 1] has length 2.
        let points = PointSet::line(-2.05, 2.05, 41).unwrap();
        let p: Vec<f64> = points
            .xs()
            .iter()
            .map(|&x| (1.0 - x.abs()).max(0.0).sqrt())
            .collect();
        let length = Edge::new(&points, &p, EdgeLaw::SquareRoot).measure();
        assert!((length - 2.0).abs() < 1e-12, "{length}");
        // Pressures near the smallest doubles (a huge contact's): the
        // same edge, their squares underflowing notwithstanding.
        let tiny: Vec<f64> = p.iter().map(|q| q * 1e-200).collect();
        let length = Edge::new(&points, &tiny, EdgeLaw::SquareRoot).measure();
        assert!((length - 2.0).abs() < 1e-12, "{length}");
        // A linear fall under the linear law, likewise.
        let linear: Vec<f64> = p.iter().map(|v| v * v).collect();
        let length = Edge::new(&points, &linear, EdgeLaw::Linear).measure();
        assert!((length - 2.0).abs() < 1e-12, "{length}");
        // An unknown law keeps whole cells, 0.1 each.
        let pressed = p.iter().filter(|&&v| v > 0.0).count() as f64;
        let cells = Edge::new(&points, &p, EdgeLaw::Cells).measure();
        assert!((cells - 0.1 * pressed).abs() < 1e-12, "{cells}");
        // A pressure that rises to its edge (a punch) keeps whole cells.
        let q: Vec<f64> = points
            .xs()
            .iter()
            .map(|&x| if x.abs() < 1.0 { 1.0 + x.abs() } else { 0.0 })
            .collect();
        let cells = points.xs().iter().filter(|x| x.abs() < 1.0).count() as f64 * 0.1;
        assert!((Edge::new(&points, &q, EdgeLaw::SquareRoot).measure() - cells).abs() < 1e-12);
    }
}
