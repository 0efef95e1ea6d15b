//! The two surfaces near the initial point of contact and the initial
//! separations they give, `eps_k = h1(x_k, y_k) + h2(x_k, y_k)` (the
//! paper's ε), or separations given one per point.

use elcon_influence::{Dimension, PointSet};

use crate::AnalysisError;

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
}

impl Surface {
    /// The curvatures along x and along y (1 / length; negative where
    /// concave): `1/R` both ways for a sphere, `1/R` along x for a cylinder
    /// with its axis along y, none for a plane.
    pub fn curvatures(&self) -> (f64, f64) {
        match *self {
            Surface::Plane => (0.0, 0.0),
            Surface::Sphere { radius } => (1.0 / radius, 1.0 / radius),
            Surface::Cylinder { radius } => (1.0 / radius, 0.0),
        }
    }

    /// Its radius (length; negative = concave), `None` for a plane.
    pub fn radius(&self) -> Option<f64> {
        match *self {
            Surface::Plane => None,
            Surface::Sphere { radius } | Surface::Cylinder { radius } => Some(radius),
        }
    }

    pub(crate) fn height(&self, x: f64, y: f64) -> f64 {
        match *self {
            Surface::Plane => 0.0,
            Surface::Sphere { radius } => (x * x + y * y) / (2.0 * radius),
            Surface::Cylinder { radius } => x * x / (2.0 * radius),
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

/// Where the initial separations come from.
#[derive(Debug, Clone, PartialEq)]
#[non_exhaustive]
pub enum Geometry {
    /// Two surfaces: `eps_k = h1(x_k, y_k) + h2(x_k, y_k)`.
    Surfaces(Surface, Surface),
    /// Given separations, one per point (length).
    Separation(Vec<f64>),
}

/// Initial separations of a geometry on a point set.
pub fn separations(points: &PointSet, geometry: &Geometry) -> Result<Vec<f64>, AnalysisError> {
    let n = points.len();
    match geometry {
        Geometry::Surfaces(s1, s2) => {
            s1.validate("surface1.radius", points.dimension())?;
            s2.validate("surface2.radius", points.dimension())?;
            Ok((0..n)
                .map(|k| {
                    let (x, y) = (points.x(k), points.y(k));
                    s1.height(x, y) + s2.height(x, y)
                })
                .collect())
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
