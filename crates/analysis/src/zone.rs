//! The candidate zone's outline, for moments: contact forces `F_k >= 0` at
//! the points `(x_k, y_k)` have their resultant at
//! `(sum F_k x_k, sum F_k y_k) / sum F_k`, a convex combination of the
//! points, so a load centre `(-M_y / P, M_x / P)` can be balanced only
//! inside the points' convex hull. The hull (Andrew's monotone chain) says
//! whether a load centre lies inside and how far from the outline, for
//! a scene's check (elcon-scene) and for the message of a moment-loaded solve that
//! failed.
//!
//! The zone's open edge ([`OpenEdge`]) is where the run finds a contact
//! cut off by the zone: a boundary point in contact whose contact goes on
//! at least half a cell past it on an open side. `check` tests a tilted
//! Hertz contact against it the same way.

use elcon_influence::PointSet;

use elcon_num::rounded;

/// The convex hull of the candidate points, counter-clockwise (two points
/// for points on one line, one for a single point).
#[derive(Debug, Clone, PartialEq)]
pub struct Zone {
    hull: Vec<(f64, f64)>,
    /// The points' extent along x and y: (lo, hi) each.
    span: [(f64, f64); 2],
}

/// The z-component of `(a - o) x (b - o)`.
fn cross(o: (f64, f64), a: (f64, f64), b: (f64, f64)) -> f64 {
    (a.0 - o.0) * (b.1 - o.1) - (a.1 - o.1) * (b.0 - o.0)
}

/// The distance from `p` to the segment `a b`.
fn to_segment(p: (f64, f64), a: (f64, f64), b: (f64, f64)) -> f64 {
    let (dx, dy) = (b.0 - a.0, b.1 - a.1);
    let length2 = dx * dx + dy * dy;
    let t = if length2 > 0.0 {
        (((p.0 - a.0) * dx + (p.1 - a.1) * dy) / length2).clamp(0.0, 1.0)
    } else {
        0.0
    };
    (p.0 - a.0 - t * dx).hypot(p.1 - a.1 - t * dy)
}

impl Zone {
    /// The outline of `points`.
    pub fn of(points: &PointSet) -> Self {
        let mut p: Vec<(f64, f64)> = (0..points.len())
            .map(|k| (points.x(k), points.y(k)))
            .collect();
        let span = p.iter().fold(
            [(f64::INFINITY, f64::NEG_INFINITY); 2],
            |[x, y], &(px, py)| [(x.0.min(px), x.1.max(px)), (y.0.min(py), y.1.max(py))],
        );
        p.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.total_cmp(&b.1)));
        p.dedup();
        if p.len() < 3 {
            return Self { hull: p, span };
        }
        // Andrew's monotone chain: the lower hull left to right, then the
        // upper right to left, dropping turns that are not left turns.
        let mut hull: Vec<(f64, f64)> = Vec::with_capacity(2 * p.len());
        for pass in [&p[..], &p.iter().rev().copied().collect::<Vec<_>>()[..]] {
            let start = hull.len();
            for &q in pass {
                while hull.len() >= start + 2
                    && cross(hull[hull.len() - 2], hull[hull.len() - 1], q) <= 0.0
                {
                    hull.pop();
                }
                hull.push(q);
            }
            hull.pop();
        }
        if hull.len() < 3 {
            // All points on one line: its two ends.
            hull = vec![p[0], p[p.len() - 1]];
        }
        Self { hull, span }
    }

    /// The zone's size: the larger of its extents along x and y.
    fn size(&self) -> f64 {
        let [x, y] = self.span;
        (x.1 - x.0).max(y.1 - y.0)
    }

    /// How far `c` lies inside the outline (positive) or outside it
    /// (negative), as a distance.
    pub fn depth(&self, c: (f64, f64)) -> f64 {
        let h = &self.hull;
        match h.len() {
            0 => f64::NEG_INFINITY,
            1 => -(c.0 - h[0].0).hypot(c.1 - h[0].1),
            2 => -to_segment(c, h[0], h[1]),
            n => {
                let inside = (0..n).all(|i| cross(h[i], h[(i + 1) % n], c) >= 0.0);
                let edge = (0..n)
                    .map(|i| to_segment(c, h[i], h[(i + 1) % n]))
                    .fold(f64::INFINITY, f64::min);
                if inside { edge } else { -edge }
            }
        }
    }

    /// Whether `c` lies inside the outline or on it (to a billionth of the
    /// zone's size, for points on one line).
    pub fn holds(&self, c: (f64, f64)) -> bool {
        self.depth(c) >= -1e-9 * self.size()
    }

    /// The zone in words: its points' extent along x and y.
    pub fn describe(&self) -> String {
        let [x, y] = self.span;
        if y.0 == y.1 {
            format!("x from {} to {}", rounded(x.0), rounded(x.1))
        } else {
            format!(
                "x from {} to {}, y from {} to {}",
                rounded(x.0),
                rounded(x.1),
                rounded(y.0),
                rounded(y.1)
            )
        }
    }
}

/// The candidate zone's open edge as the run tests a contact against it:
/// each point on the zone's boundary paired with the point half a cell
/// beyond it on each open side (the adjacent cell holds no point). A
/// contact that holds both goes on past the point's cell: the zone, not
/// the bodies, ends it (the run's truncation test extrapolates the
/// pressure's edge there and refuses an edge half a cell out or more).
#[derive(Debug, Clone, PartialEq)]
pub struct OpenEdge {
    /// (boundary point, half a cell beyond it on an open side).
    probes: Vec<((f64, f64), (f64, f64))>,
    /// The zone's outline: a contact whose centre leaves it has crossed
    /// the edge.
    zone: Zone,
    /// The smaller side of a cell.
    cell: f64,
}

impl OpenEdge {
    /// The open edge of `points` (sides told apart by the lattice's
    /// neighbours; without a lattice both sides of an open direction).
    pub fn of(points: &PointSet) -> Self {
        let cell = points.cell();
        let lattice = points.lattice();
        let index = points.lattice_index();
        let mut probes = Vec::new();
        for k in (0..points.len()).filter(|&k| points.is_on_boundary(k)) {
            let p = (points.x(k), points.y(k));
            let (open_x, open_y) = points.open_sides(k);
            let sides = [
                (1, 0, open_x),
                (-1, 0, open_x),
                (0, 1, open_y),
                (0, -1, open_y),
            ];
            for (di, dj, open) in sides {
                let missing = match (&lattice, &index) {
                    (Some(l), Some(index)) => {
                        let (i, j) = l.get(k);
                        index.get((i + di, j + dj)).is_none()
                    }
                    _ => open,
                };
                if open && missing {
                    let out = (
                        p.0 + 0.5 * di as f64 * cell.dx,
                        p.1 + 0.5 * dj as f64 * cell.dy,
                    );
                    probes.push((p, out));
                }
            }
        }
        Self {
            probes,
            zone: Zone::of(points),
            cell: cell.dx.min(cell.dy),
        }
    }

    /// The zone in words ([`Zone::describe`]).
    pub fn describe(&self) -> String {
        self.zone.describe()
    }

    /// Whether a contact centred at `c` (`inside(d)`: the point at `d`
    /// from its centre lies in it) reaches past the open edge.
    pub fn reached(&self, c: (f64, f64), inside: &impl Fn((f64, f64)) -> bool) -> bool {
        let at = |p: (f64, f64)| inside((p.0 - c.0, p.1 - c.1));
        self.probes.iter().any(|&(p, out)| at(p) && at(out))
    }

    /// The largest `t` in `[0, 1]` for which a contact centred at `t'
    /// shift` stays clear of the open edge for every `t' <= t` (1 where
    /// the whole shift does; a contact that crossed the edge and left the
    /// zone is not clear again): stepped by a quarter of a cell, then
    /// bisected to a millionth of the shift.
    pub fn largest_shift(&self, shift: (f64, f64), inside: impl Fn((f64, f64)) -> bool) -> f64 {
        let at = |t: f64| (t * shift.0, t * shift.1);
        let clear = |t: f64| self.zone.holds(at(t)) && !self.reached(at(t), &inside);
        let length = shift.0.hypot(shift.1);
        if !clear(0.0) {
            return 0.0;
        }
        if !(length > 0.0) {
            return 1.0;
        }
        let step = (0.25 * self.cell / length).max(1e-6);
        let mut lo = 0.0f64;
        loop {
            let hi = (lo + step).min(1.0);
            if !clear(hi) {
                let mut hi = hi;
                while hi - lo > 1e-6 {
                    let mid = 0.5 * (lo + hi);
                    if clear(mid) { lo = mid } else { hi = mid }
                }
                return lo;
            }
            if hi >= 1.0 {
                return 1.0;
            }
            lo = hi;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_contact_past_a_boundary_point_by_half_a_cell_reaches_the_open_edge() {
        // Points at -1, 0, 1 both ways (cells of 1): a circle of radius
        // 0.5 moved along x holds (1, 0) and (1.5, 0) once its centre
        // passes 1.
        let square = PointSet::grid_rectangle(1.5, 1.5, 3, 3).unwrap();
        let edge = OpenEdge::of(&square);
        let circle = |r: f64| move |d: (f64, f64)| d.0.hypot(d.1) < r;
        assert!(!edge.reached((0.99, 0.0), &circle(0.5)));
        assert!(edge.reached((1.01, 0.0), &circle(0.5)));
        // The centre itself is no boundary point: a circle around it of
        // radius 1 holds every boundary point but no point half a cell out.
        assert!(!edge.reached((0.0, 0.0), &circle(1.0)));
        let t = edge.largest_shift((2.0, 0.0), circle(0.5));
        assert!((t - 0.5).abs() < 1e-6, "{t}");
        assert_eq!(edge.largest_shift((0.5, 0.0), circle(0.5)), 1.0);
        assert_eq!(edge.largest_shift((0.5, 0.0), circle(2.0)), 0.0);
        // A shift far past the zone crosses the edge on its way out.
        let t = edge.largest_shift((100.0, 0.0), circle(0.5));
        assert!((t - 0.01).abs() < 1e-6, "{t}");
    }

    #[test]
    fn a_disk_holds_its_centre_and_not_a_corner_of_its_box() {
        let disk = PointSet::grid_disk(0.1, 1.0).unwrap();
        let zone = Zone::of(&disk);
        assert!(zone.holds((0.0, 0.0)));
        assert!((zone.depth((0.0, 0.0)) - 1.0).abs() < 0.05);
        // Inside the extent along each axis, outside the disk.
        assert!(!zone.holds((0.8, 0.8)));
        assert!(zone.depth((0.8, 0.8)) < -0.1);
        assert!(zone.describe().starts_with("x from -1 to 1, y from"));
    }

    #[test]
    fn a_line_holds_its_segment_alone() {
        let line = PointSet::line(-2.0, 2.0, 41).unwrap();
        let zone = Zone::of(&line);
        assert!(zone.holds((1.5, 0.0)));
        assert!(!zone.holds((2.5, 0.0)) && !zone.holds((0.0, 0.5)));
        assert!(
            zone.describe().starts_with("x from "),
            "{}",
            zone.describe()
        );
    }
}
