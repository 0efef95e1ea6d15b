//! The candidate zone's outline, for moments: contact forces `F_k >= 0` at
//! the points `(x_k, y_k)` have their resultant at
//! `(sum F_k x_k, sum F_k y_k) / sum F_k`, a convex combination of the
//! points, so a load centre `(-M_y / P, M_x / P)` can be balanced only
//! inside the points' convex hull. The hull (Andrew's monotone chain) says
//! whether a load centre lies inside and how far from the outline, for
//! `check`'s refusal and for the message of a moment-loaded solve that
//! failed.

use elcon_influence::PointSet;

use crate::ctx::rounded;

/// The convex hull of the candidate points, counter-clockwise (two points
/// for points on one line, one for a single point).
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Zone {
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
    pub(crate) fn of(points: &PointSet) -> Self {
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
    pub(crate) fn depth(&self, c: (f64, f64)) -> f64 {
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

    /// The largest `t >= 0` for which a convex shape centred at `t shift`
    /// lies inside the outline grown by `margin(n)` along each outward
    /// unit normal `n` of its edges, `support(n)` the shape's reach from
    /// its centre along `n`: on every edge of normal `n` and offset `c`,
    /// `t (n . shift) + support(n) <= c + margin(n)`. Edges the shift does
    /// not move the shape towards bound nothing; infinite for points on
    /// one line (no edges).
    pub(crate) fn largest_shift(
        &self,
        shift: (f64, f64),
        support: impl Fn((f64, f64)) -> f64,
        margin: impl Fn((f64, f64)) -> f64,
    ) -> f64 {
        let h = &self.hull;
        if h.len() < 3 {
            return f64::INFINITY;
        }
        (0..h.len())
            .filter_map(|i| {
                let (a, b) = (h[i], h[(i + 1) % h.len()]);
                let (dx, dy) = (b.0 - a.0, b.1 - a.1);
                let length = dx.hypot(dy);
                // Counter-clockwise: the outward normal is on the right.
                let n = (dy / length, -dx / length);
                let towards = n.0 * shift.0 + n.1 * shift.1;
                (towards > 0.0).then(|| {
                    let room = n.0 * a.0 + n.1 * a.1 + margin(n) - support(n);
                    (room / towards).max(0.0)
                })
            })
            .fold(f64::INFINITY, f64::min)
    }

    /// Whether `c` lies inside the outline or on it (to a billionth of the
    /// zone's size, for points on one line).
    pub(crate) fn holds(&self, c: (f64, f64)) -> bool {
        self.depth(c) >= -1e-9 * self.size()
    }

    /// The zone in words: its points' extent along x and y.
    pub(crate) fn describe(&self) -> String {
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

#[cfg(test)]
mod tests {
    use super::*;

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
    fn a_shape_shifted_to_the_outline_of_a_rectangle_stops_at_its_edge() {
        // Points at -1, 0, 1 both ways; a disk of radius 0.5 moved along
        // x fits until its edge reaches x = 1 + margin 0.25: t = 0.75 / 2.
        let square = PointSet::grid_rectangle(1.5, 1.5, 3, 3).unwrap();
        let zone = Zone::of(&square);
        let t = zone.largest_shift((2.0, 0.0), |_| 0.5, |_| 0.25);
        assert!((t - 0.375).abs() < 1e-12, "{t}");
        // Along the diagonal the corner edges bind x and y alike.
        let t = zone.largest_shift((1.0, 1.0), |_| 0.5, |_| 0.0);
        assert!((t - 0.5).abs() < 1e-12, "{t}");
        // No shift: nothing binds.
        assert_eq!(
            zone.largest_shift((0.0, 0.0), |_| 0.5, |_| 0.0),
            f64::INFINITY
        );
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
