//! The two surfaces near the initial point of contact and the initial
//! separations they give, `eps_k = h1(x_k, y_k) + h2(x_k, y_k)` (the
//! paper's ε), plus any tabulated departures (height maps, axial
//! profiles, `crate::contact::tabulated`), or separations given one per
//! point.
//!
//! Each surface is a quadric near the first point of contact, its height
//! above the common tangent plane a quadratic form,
//!
//! ```text
//!     h(x, y) = (k_xx x^2 + 2 k_xy x y + k_yy y^2) / 2         (a Curvature)
//! ```
//!
//! with principal curvatures `1/R_x`, `1/R_y` along the directions at
//! `angle` and `angle + 90°` from the x axis:
//! `k_xx = c^2/R_x + s^2/R_y`, `k_yy = s^2/R_x + c^2/R_y`,
//! `k_xy = (1/R_x - 1/R_y) s c` (`c = cos angle`, `s = sin angle`). The
//! gap of two bodies is the sum of their heights, so its curvature is the
//! sum of theirs, and its principal curvatures and their directions are
//! the eigenvalues and eigenvectors of that 2 x 2 form: the relative
//! curvatures `2A`, `2B` of Hertz's elliptical contact
//! (`crate::references::HertzEllipse`).

use std::ops::Add;

use elcon_influence::{Dimension, PointSet};

use super::tabulated::Departure;
use crate::{AnalysisError, Num};

/// The shape of one surface near the initial point of contact, as its height
/// above the common tangent plane. Radii are positive for convex surfaces and
/// negative for concave ones (a ball in a groove).
#[derive(Debug, Clone, Copy, PartialEq)]
#[non_exhaustive]
pub enum Surface {
    /// A plane: height 0.
    Plane,
    /// A sphere of radius R: height `(x^2 + y^2) / (2R)` (Hertz's paraboloid).
    Sphere {
        /// Radius R (length; negative = concave).
        radius: f64,
    },
    /// A cylinder of radius R with its axis along y: height `x^2 / (2R)`.
    Cylinder {
        /// Radius R (length; negative = concave).
        radius: f64,
    },
    /// A quadric with principal radii `R_x` along the direction at `angle`
    /// from the x axis and `R_y` across it: height `(u^2 / R_x + v^2 / R_y)
    /// / 2`, `u = x cos angle + y sin angle`, `v = -x sin angle + y cos
    /// angle`. A sphere is `R_x = R_y`; a cylinder with its axis along y
    /// is `R_y` infinite (straight along y); a negative radius is concave
    /// (a bearing's groove).
    Quadric {
        /// Radius along the direction at `angle` (length; negative =
        /// concave, infinite = straight).
        radius_x: f64,
        /// Radius across it (length; negative = concave, infinite =
        /// straight).
        radius_y: f64,
        /// The direction of `radius_x` from the x axis (radians).
        angle: f64,
    },
}

impl Surface {
    /// The curvatures along x and along y (1 / length; negative where
    /// concave): `1/R` both ways for a sphere, `1/R` along x for a cylinder
    /// with its axis along y, none for a plane; a quadric's `k_xx`, `k_yy`
    /// ([`Curvature`]).
    pub fn curvatures(&self) -> (f64, f64) {
        match *self {
            Surface::Plane => (0.0, 0.0),
            Surface::Sphere { radius } => (1.0 / radius, 1.0 / radius),
            Surface::Cylinder { radius } => (1.0 / radius, 0.0),
            Surface::Quadric { .. } => {
                let c = Curvature::of(self);
                (c.xx, c.yy)
            }
        }
    }

    /// Its radius (length; negative = concave): a sphere's or a
    /// cylinder's; `None` for a plane and for a quadric, which has two
    /// ([`Surface::Quadric`]).
    pub fn radius(&self) -> Option<f64> {
        match *self {
            Surface::Plane | Surface::Quadric { .. } => None,
            Surface::Sphere { radius } | Surface::Cylinder { radius } => Some(radius),
        }
    }

    /// Whether it is curved somewhere (not a plane, nor a quadric with
    /// both radii infinite).
    pub fn is_curved(&self) -> bool {
        Curvature::of(self) != Curvature::default()
    }

    pub(crate) fn height(&self, x: f64, y: f64) -> f64 {
        match *self {
            Surface::Plane => 0.0,
            Surface::Sphere { radius } => (x * x + y * y) / (2.0 * radius),
            Surface::Cylinder { radius } => x * x / (2.0 * radius),
            Surface::Quadric {
                radius_x,
                radius_y,
                angle,
            } => {
                let (s, c) = angle.sin_cos();
                let (u, v) = (x * c + y * s, -x * s + y * c);
                0.5 * (u * u / radius_x + v * v / radius_y)
            }
        }
    }

    pub(crate) fn validate(
        &self,
        field: &'static str,
        dimension: Dimension,
    ) -> Result<(), AnalysisError> {
        let radius = match *self {
            Surface::Plane => return Ok(()),
            Surface::Sphere { radius } | Surface::Cylinder { radius } => radius,
            Surface::Quadric {
                radius_x,
                radius_y,
                angle,
            } => return quadric_valid(field, dimension, radius_x, radius_y, angle),
        };
        if !(radius.is_finite() && radius != 0.0) {
            return Err(AnalysisError::InvalidInput {
                field,
                value: radius,
                reason: "a radius must be finite and non-zero (negative for a concave surface)",
            });
        }
        if matches!(self, Surface::Sphere { .. }) && dimension == Dimension::Line {
            return Err(AnalysisError::Incompatible {
                field,
                reason: "a sphere needs a surface point set; for a 2D line contact use a cylinder"
                    .into(),
            });
        }
        Ok(())
    }
}

/// A quadric's radii not NaN and non-zero (infinite: straight), its angle
/// finite, on a surface point set.
fn quadric_valid(
    field: &'static str,
    dimension: Dimension,
    radius_x: f64,
    radius_y: f64,
    angle: f64,
) -> Result<(), AnalysisError> {
    for radius in [radius_x, radius_y] {
        if radius.is_nan() || radius == 0.0 {
            return Err(AnalysisError::InvalidInput {
                field,
                value: radius,
                reason: "a quadric's radius must be non-zero (negative for a concave direction, \
                         infinite for a straight one)",
            });
        }
    }
    if !angle.is_finite() {
        return Err(AnalysisError::InvalidInput {
            field,
            value: angle,
            reason: "a quadric's angle must be finite",
        });
    }
    if dimension == Dimension::Line {
        return Err(AnalysisError::Incompatible {
            field,
            reason: "a quadric needs a surface point set; for a 2D line contact use a cylinder"
                .into(),
        });
    }
    Ok(())
}

/// The curvature of a surface, or of a gap (the sum of two surfaces'), as
/// the quadratic form of its height `h = (xx x^2 + 2 xy x y + yy y^2) / 2`
/// (each 1 / length; see the module documentation). Curvatures add:
/// `Curvature::of(&s1) + Curvature::of(&s2)` is the gap's.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Curvature {
    /// `d^2 h / dx^2`.
    pub xx: f64,
    /// `d^2 h / dx dy`.
    pub xy: f64,
    /// `d^2 h / dy^2`.
    pub yy: f64,
}

/// A curvature's principal values and directions: the smaller along the
/// direction at `angle` from the x axis, the larger across it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Principal {
    /// The smaller principal curvature (1 / length).
    pub smaller: f64,
    /// The larger principal curvature (1 / length).
    pub larger: f64,
    /// The direction of the smaller one from the x axis (radians, in
    /// (-pi/2, pi/2]; 0 when both are equal).
    pub angle: f64,
}

impl Curvature {
    /// The curvature of a surface (zero for a plane; a quadric's infinite
    /// radius is a zero curvature).
    pub fn of(surface: &Surface) -> Self {
        match *surface {
            Surface::Plane => Self::default(),
            Surface::Sphere { radius } => Self::principal(1.0 / radius, 1.0 / radius, 0.0),
            Surface::Cylinder { radius } => Self::principal(1.0 / radius, 0.0, 0.0),
            Surface::Quadric {
                radius_x,
                radius_y,
                angle,
            } => Self::principal(1.0 / radius_x, 1.0 / radius_y, angle),
        }
    }

    /// The curvature with principal values `along` in the direction at
    /// `angle` from the x axis (radians) and `across` perpendicular to it.
    pub fn principal(along: f64, across: f64, angle: f64) -> Self {
        if angle == 0.0 {
            return Self {
                xx: along,
                xy: 0.0,
                yy: across,
            };
        }
        let (s, c) = angle.sin_cos();
        Self {
            xx: along * c * c + across * s * s,
            xy: (along - across) * s * c,
            yy: along * s * s + across * c * c,
        }
    }

    /// The principal curvatures and the direction of the smaller: the
    /// eigenvalues `m -+ d` of the form, `m = (xx + yy) / 2`,
    /// `d = hypot((xx - yy) / 2, xy)`, the smaller taken as `det / larger`
    /// when both are positive (no cancellation for a slender contact), its
    /// direction `atan2(2 xy, xx - yy) / 2 + pi/2`.
    pub fn principal_values(&self) -> Principal {
        let m = 0.5 * (self.xx + self.yy);
        let d = (0.5 * (self.xx - self.yy)).hypot(self.xy);
        let larger = m + d;
        let det = self.xx * self.yy - self.xy * self.xy;
        let smaller = if larger > 0.0 && det >= 0.0 {
            det / larger
        } else {
            m - d
        };
        let angle = if d == 0.0 {
            0.0
        } else {
            let of_larger = 0.5 * (2.0 * self.xy).atan2(self.xx - self.yy);
            let a = of_larger + std::f64::consts::FRAC_PI_2;
            if a > std::f64::consts::FRAC_PI_2 {
                a - std::f64::consts::PI
            } else {
                a
            }
        };
        Principal {
            smaller,
            larger,
            angle,
        }
    }

    /// The height `(xx x^2 + 2 xy x y + yy y^2) / 2` of the form at `(x, y)`.
    pub fn height(&self, x: f64, y: f64) -> f64 {
        0.5 * (self.xx * x * x + 2.0 * self.xy * x * y + self.yy * y * y)
    }
}

impl Add for Curvature {
    type Output = Curvature;

    /// The curvature of the summed heights.
    fn add(self, other: Curvature) -> Curvature {
        Curvature {
            xx: self.xx + other.xx,
            xy: self.xy + other.xy,
            yy: self.yy + other.yy,
        }
    }
}

/// Where the initial separations come from.
#[derive(Debug, Clone, PartialEq)]
#[non_exhaustive]
pub enum Geometry {
    /// Two surfaces: `eps_k = h1(x_k, y_k) + h2(x_k, y_k)`.
    Surfaces(Surface, Surface),
    /// Given separations, one per point (length).
    Separation(Vec<f64>),
    /// Two surfaces with tabulated departures added (height maps, axial
    /// profiles): `eps_k = h1 + h2 + sum_l d_l(x_k, y_k)`, each departure
    /// interpolated at the point (`crate::contact::tabulated`). Unlike
    /// given separations, it has a value at any point, so coarser and finer
    /// grids of the same zone have their problems.
    Tabulated {
        /// The two surfaces' quadrics.
        surfaces: (Surface, Surface),
        /// The departures, each added to the sum of the surfaces' heights.
        departures: Vec<Departure>,
    },
}

impl Geometry {
    /// The two surfaces' quadrics: of [`Geometry::Surfaces`] and of
    /// [`Geometry::Tabulated`] (its departures left out); `None` for given
    /// separations.
    pub fn surfaces(&self) -> Option<(Surface, Surface)> {
        match self {
            Geometry::Surfaces(a, b) => Some((*a, *b)),
            Geometry::Tabulated { surfaces, .. } => Some(*surfaces),
            Geometry::Separation(_) => None,
        }
    }

    /// The tabulated departures added to the quadrics (height maps, axial
    /// profiles), in the order they are added: those of
    /// [`Geometry::Tabulated`], none for the other geometries.
    pub fn departures(&self) -> Vec<&Departure> {
        match self {
            Geometry::Tabulated { departures, .. } => departures.iter().collect(),
            Geometry::Surfaces(..) | Geometry::Separation(_) => Vec::new(),
        }
    }

    /// The curvature of the gap of the two quadrics (departures left out),
    /// `None` for given separations.
    pub fn curvature(&self) -> Option<Curvature> {
        self.surfaces()
            .map(|(a, b)| Curvature::of(&a) + Curvature::of(&b))
    }
}

/// Initial separations of a geometry on a point set.
pub fn separations(points: &PointSet, geometry: &Geometry) -> Result<Vec<f64>, AnalysisError> {
    let n = points.len();
    match geometry {
        Geometry::Surfaces(s1, s2) => {
            s1.validate("surface1.radius", points.dimension())?;
            s2.validate("surface2.radius", points.dimension())?;
            Ok(points.map_positions(|(x, y)| s1.height(x, y) + s2.height(x, y)))
        }
        Geometry::Tabulated {
            surfaces: (s1, s2),
            departures,
        } => {
            s1.validate("surface1.radius", points.dimension())?;
            s2.validate("surface2.radius", points.dimension())?;
            points
                .positions()
                .enumerate()
                .map(|(k, (x, y))| {
                    departures
                        .iter()
                        .try_fold(s1.height(x, y) + s2.height(x, y), |eps, d| {
                            d.at(x, y)
                                .map(|v| eps + v)
                                .ok_or_else(|| not_covered(d, k, x, y))
                        })
                })
                .collect()
        }
        Geometry::Separation(eps) => {
            if eps.len() != n {
                return Err(AnalysisError::SizeMismatch {
                    field: "separation",
                    expected: n,
                    found: eps.len(),
                });
            }
            Ok(eps.clone())
        }
    }
}

/// The error of a departure that does not cover point k at `(x, y)`.
fn not_covered(departure: &Departure, k: usize, x: f64, y: f64) -> AnalysisError {
    AnalysisError::table(
        departure.label(),
        format!(
            "does not cover candidate point {k} at ({}, {}): {}; give a table over the whole \
             candidate zone",
            Num(x),
            Num(y),
            departure.describe_extent()
        ),
    )
}

#[cfg(test)]
mod tests {
    use std::sync::Arc;

    use super::*;
    use crate::contact::tabulated::{AxialProfile, ProfileAxis};

    #[test]
    fn a_quadric_s_special_cases_and_its_turned_form() {
        let points = PointSet::grid_rectangle(1.0, 1.0, 5, 5).unwrap();
        let same = |a: Surface, b: Surface| {
            let ea = separations(&points, &Geometry::Surfaces(a, Surface::Plane)).unwrap();
            let eb = separations(&points, &Geometry::Surfaces(b, Surface::Plane)).unwrap();
            ea.iter()
                .zip(&eb)
                .all(|(x, y)| (x - y).abs() <= 1e-15 * x.abs().max(1.0))
        };
        let quadric = |radius_x, radius_y, angle| Surface::Quadric {
            radius_x,
            radius_y,
            angle,
        };
        assert!(same(
            quadric(2.0, 2.0, 0.7),
            Surface::Sphere { radius: 2.0 }
        ));
        assert!(same(
            quadric(3.0, f64::INFINITY, 0.0),
            Surface::Cylinder { radius: 3.0 }
        ));
        // Turned by 90 degrees, R_x lies along y.
        assert!(same(
            quadric(3.0, -8.0, std::f64::consts::FRAC_PI_2),
            quadric(-8.0, 3.0, 0.0)
        ));
        // The form's principal values give back the radii and the angle.
        let c = Curvature::of(&quadric(10.0, 2.0, 0.3));
        let p = c.principal_values();
        assert!((p.smaller - 0.1).abs() < 1e-15 && (p.larger - 0.5).abs() < 1e-15);
        assert!((p.angle - 0.3).abs() < 1e-14, "{p:?}");
        assert!(!Surface::Plane.is_curved() && quadric(1.0, 1.0, 0.0).is_curved());
    }

    #[test]
    fn a_departure_adds_to_the_quadrics_and_refuses_a_point_it_does_not_cover() {
        let points = PointSet::line(-1.0, 1.0, 4).unwrap();
        let profile =
            AxialProfile::new("crown.csv", ProfileAxis::X, vec![-1.0, 1.0], vec![0.5, 0.5])
                .unwrap();
        let geometry = Geometry::Tabulated {
            surfaces: (Surface::Cylinder { radius: 2.0 }, Surface::Plane),
            departures: vec![Departure::Profile(Arc::new(profile))],
        };
        assert_eq!(geometry.departures().len(), 1);
        assert_eq!(geometry.departures()[0].label(), "crown.csv");
        let plain = Geometry::Surfaces(Surface::Plane, Surface::Plane);
        assert!(plain.departures().is_empty());
        let eps = separations(&points, &geometry).unwrap();
        for (k, e) in eps.iter().enumerate() {
            let x = points.x(k);
            assert!((e - (x * x / 4.0 + 0.5)).abs() < 1e-15);
        }
        let wider = PointSet::line(-2.0, 2.0, 4).unwrap();
        let e = separations(&wider, &geometry).unwrap_err();
        assert!(
            matches!(&e, AnalysisError::Table { label, .. } if label == "crown.csv"),
            "{e}"
        );
        assert!(e.to_string().contains("candidate point 0"), "{e}");
        let quadric = Surface::Quadric {
            radius_x: 1.0,
            radius_y: 0.0,
            angle: 0.0,
        };
        let e = separations(&points, &Geometry::Surfaces(quadric, Surface::Plane)).unwrap_err();
        assert!(matches!(e, AnalysisError::InvalidInput { .. }), "{e}");
    }
}
