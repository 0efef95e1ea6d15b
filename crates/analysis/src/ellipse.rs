//! The contact ellipse from the pressure field's own moments.
//!
//! Under Hertz's elliptical pressure `p = p0 sqrt(1 - u^2/a^2 - v^2/b^2)`
//! the weight `w = p^4 = p0^4 (1 - u^2/a^2 - v^2/b^2)^2` is smooth inside
//! the contact and falls to zero at the outline with zero slope, and its
//! second moments about the centre are
//!
//! ```text
//!     ∫ u^2 w dA / ∫ w dA = a^2 / 8,      ∫ v^2 w dA / ∫ w dA = b^2 / 8,      ∫ u v w dA = 0
//! ```
//!
//! (on the unit disk `∫ r^3 (1 - r^2)^2 dr / ∫ r (1 - r^2)^2 dr = 1/4`,
//! and the mean of `cos^2` is 1/2). So the ellipse is read from the
//! covariance `C` of `w` over the contact: `a = sqrt(8 λ1)`,
//! `b = sqrt(8 λ2)` with `λ1 >= λ2` its eigenvalues, the major axis along
//! the first eigenvector. On a Winkler foundation the pressure is the
//! deflection, `p = p0 (1 - u^2/a^2 - v^2/b^2)` under a quadric
//! (`EdgeLaw::Linear`): there `w = p^2`, the same weight.
//!
//! Each point's weight is its cell's integral of `w`, `w_k A_k`, at the
//! cell's centre, and the cell adds its own spread, `dx^2 / 12` and
//! `dy^2 / 12`, to the covariance (the midpoint rule's second moment of a
//! cell). With the weight's slope zero at the outline the cells the
//! outline cuts add no error of lower order, so the semi-axes converge
//! steadily as `h^2`; the outline's own area moments, or those of `p^2`
//! (which meets the outline at a slope), change irregularly with where the
//! outline crosses the cells. For a contact that is not Hertzian (a
//! roller's patch, a truncated zone) it is the ellipse of Hertz's pressure
//! with the same second moments: a summary, compared with Hertz only
//! where Hertz holds.

use elcon_influence::{Dimension, PointSet};

use crate::edge::EdgeLaw;

/// The ellipse of a contact: its semi-axes and the direction of the major
/// one, from the pressure's moments (see the module documentation;
/// `crate::ContactSolution::contact_ellipse`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ContactEllipse {
    /// The major semi-axis a (length).
    pub semi_major: f64,
    /// The minor semi-axis b (length).
    pub semi_minor: f64,
    /// The direction of the major axis from the x axis (radians, in
    /// [-pi/2, pi/2]).
    pub angle: f64,
}

/// The ratio of a Hertz ellipse's squared semi-axis to the second moment of
/// its weight `w = p^4` along it (see the module documentation).
const MOMENT_RATIO: f64 = 8.0;

/// The fewest points in contact an ellipse is read from (its three
/// second moments and centre need more than a point or a row).
const MIN_POINTS: usize = 3;

/// The ellipse of the contact where `pressures > 0` on `points`, under
/// `law`; `None` on a line, for an unknown law ([`EdgeLaw::Cells`]), or
/// with fewer than [`MIN_POINTS`] points in contact.
pub(crate) fn pressure_ellipse(
    points: &PointSet,
    pressures: &[f64],
    law: EdgeLaw,
) -> Option<ContactEllipse> {
    let weight = match law {
        EdgeLaw::SquareRoot => |p: f64| (p * p).powi(2),
        EdgeLaw::Linear => |p: f64| p * p,
        EdgeLaw::Cells => return None,
    };
    if points.dimension() == Dimension::Line {
        return None;
    }
    let pressed: Vec<(f64, f64, f64)> = (0..points.len())
        .filter(|&k| pressures[k] > 0.0)
        .map(|k| {
            (
                points.x(k),
                points.y(k),
                weight(pressures[k]) * points.measure(k),
            )
        })
        .collect();
    let total: f64 = pressed.iter().map(|&(_, _, w)| w).sum();
    if pressed.len() < MIN_POINTS || !(total > 0.0) {
        return None;
    }
    let mean = |f: &dyn Fn(f64, f64) -> f64| {
        pressed.iter().map(|&(x, y, w)| w * f(x, y)).sum::<f64>() / total
    };
    let (cx, cy) = (mean(&|x, _| x), mean(&|_, y| y));
    let cell = points.cell();
    let sxx = mean(&|x, _| (x - cx).powi(2)) + cell.dx * cell.dx / 12.0;
    let syy = mean(&|_, y| (y - cy).powi(2)) + cell.dy * cell.dy / 12.0;
    let sxy = mean(&|x, y| (x - cx) * (y - cy));
    Some(of_covariance(sxx, syy, sxy))
}

/// The ellipse whose Hertz weight has the covariance `[[sxx, sxy], [sxy,
/// syy]]`: its eigenvalues times [`MOMENT_RATIO`] are the squared
/// semi-axes.
fn of_covariance(sxx: f64, syy: f64, sxy: f64) -> ContactEllipse {
    let mean = 0.5 * (sxx + syy);
    let d = (0.5 * (sxx - syy)).hypot(sxy);
    let angle = if d == 0.0 {
        0.0
    } else {
        0.5 * (2.0 * sxy).atan2(sxx - syy)
    };
    ContactEllipse {
        semi_major: (MOMENT_RATIO * (mean + d)).sqrt(),
        semi_minor: (MOMENT_RATIO * (mean - d).max(0.0)).sqrt(),
        angle,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Hertz's pressure of semi-axes (1, 0.3) turned by `angle`, on a
    /// square grid of `n x n` cells over [-1.2, 1.2]^2.
    fn hertz(n: usize, angle: f64) -> (PointSet, Vec<f64>) {
        let points = PointSet::grid_rectangle(1.2, 1.2, n, n).unwrap();
        let (s, c) = angle.sin_cos();
        let p = (0..points.len())
            .map(|k| {
                let (x, y) = (points.x(k), points.y(k));
                let (u, v) = (x * c + y * s, -x * s + y * c);
                (1.0 - u * u - (v / 0.3).powi(2)).max(0.0).sqrt()
            })
            .collect();
        (points, p)
    }

    #[test]
    fn a_hertz_pressure_gives_its_semi_axes_converging_as_h_squared() {
        // The semi-axes' errors on 60, 120 and 240 cells a side, aligned
        // and turned by 0.4 rad: within (h / b)^2 on the finest (h = 0.01,
        // (h / b)^2 = 1.1e-3; measured 3.3e-5 and 3.7e-4), and falling by
        // at least 3 (h^2: 4; measured 3.7 to 4.1) from one grid to the
        // next where they are above rounding.
        for angle in [0.0f64, 0.4] {
            let errors: Vec<(f64, f64, f64)> = [60, 120, 240]
                .iter()
                .map(|&n| {
                    let (points, p) = hertz(n, angle);
                    let e = pressure_ellipse(&points, &p, EdgeLaw::SquareRoot).unwrap();
                    (
                        (e.semi_major - 1.0).abs(),
                        (e.semi_minor / 0.3 - 1.0).abs(),
                        (e.angle - angle).abs(),
                    )
                })
                .collect();
            let (a, b, t) = errors[2];
            let bound = (0.01f64 / 0.3).powi(2);
            assert!(a < bound && b < bound && t < bound, "{angle}: {errors:?}");
            for w in errors.windows(2) {
                assert!(
                    w[1].0 < w[0].0 / 3.0 || w[1].0 < 1e-6,
                    "{angle}: {errors:?}"
                );
                assert!(
                    w[1].1 < w[0].1 / 3.0 || w[1].1 < 1e-6,
                    "{angle}: {errors:?}"
                );
            }
        }
    }

    #[test]
    fn a_winkler_deflection_weighs_by_the_pressure_itself() {
        // p = 1 - u^2 - (v / 0.3)^2, the deflection of a foundation under
        // an elliptical paraboloid: its square is the weight.
        let (points, p) = hertz(240, 0.0);
        let q: Vec<f64> = p.iter().map(|p| p * p).collect();
        let e = pressure_ellipse(&points, &q, EdgeLaw::Linear).unwrap();
        assert!((e.semi_major - 1.0).abs() < 2e-3, "{e:?}");
        assert!((e.semi_minor / 0.3 - 1.0).abs() < 2e-3, "{e:?}");
    }

    #[test]
    fn no_ellipse_on_a_line_for_an_unknown_law_or_a_point() {
        let line = PointSet::line(-1.0, 1.0, 20).unwrap();
        assert!(pressure_ellipse(&line, &[1.0; 20], EdgeLaw::SquareRoot).is_none());
        let (points, p) = hertz(60, 0.0);
        assert!(pressure_ellipse(&points, &p, EdgeLaw::Cells).is_none());
        let mut one = vec![0.0; points.len()];
        one[points.len() / 2] = 1.0;
        assert!(pressure_ellipse(&points, &one, EdgeLaw::SquareRoot).is_none());
    }
}
