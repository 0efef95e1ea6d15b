//! result.json's `reference` block: the closed form's values (Hertz,
//! the flat punch, Hetenyi's beam) and the relative errors
//! `computed / reference - 1` of the run against them.

use serde::{Deserialize, Serialize};

/// Relative errors against the closed form, signed (computed / reference - 1),
/// except `pressure_l2` (a norm ratio). Absent where not meaningful.
#[serde_with::skip_serializing_none]
#[derive(Debug, Clone, PartialEq, Default, Serialize, Deserialize)]
pub struct Errors {
    /// Approach.
    pub approach: Option<f64>,
    /// Largest pressure (intensity).
    pub max_pressure: Option<f64>,
    /// Contact radius or half-width.
    pub contact_extent: Option<f64>,
    /// Load (under displacement control).
    pub load: Option<f64>,
    /// `||p - p_ref||_2 / ||p_ref||_2` over the points.
    pub pressure_l2: Option<f64>,
    /// The rotation about x (where the reference's is not zero).
    pub tilt_x: Option<f64>,
    /// The rotation about y (where the reference's is not zero).
    pub tilt_y: Option<f64>,
    /// The major semi-axis of the contact's ellipse (an elliptical
    /// reference; `ContactSolution::contact_ellipse`).
    pub semi_major: Option<f64>,
    /// The minor semi-axis of the contact's ellipse.
    pub semi_minor: Option<f64>,
}

/// The closed form's values and the errors against it: gathered from the
/// closed form and the solution, not the copy of one type.
#[serde_with::skip_serializing_none]
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct ReferenceJson {
    /// "hertz-spheres", "hertz-cylinders", "flat-punch", "hetenyi-beam",
    /// "hertz-ellipse".
    pub kind: String,
    /// Reference approach (length).
    pub approach: Option<f64>,
    /// Reference peak pressure (intensity unit).
    pub max_pressure: Option<f64>,
    /// Reference contact radius or half-width (length); of an ellipse,
    /// the radius of the circle of its area, `sqrt(a b)`.
    pub contact_extent: Option<f64>,
    /// An elliptical reference's semi-axes `[a, b]`, a along the
    /// direction `angle` (length).
    pub semi_axes: Option<[f64; 2]>,
    /// The direction of an elliptical reference's major axis from x
    /// (degrees).
    pub angle: Option<f64>,
    /// Reference load (force).
    pub load: Option<f64>,
    /// Where the reference's contact is centred, when off the origin (a
    /// Hertz contact translated to the load centre; length).
    pub load_centre: Option<XY>,
    /// The reference's rotations, when not zero (radians).
    pub tilt: Option<XY>,
    /// Relative errors.
    pub errors: Errors,
    /// What limits the comparison, where something does (Hetenyi's bonded
    /// beam against a tensionless foundation that lifted off; a moment or
    /// a tilt the closed form does not have).
    pub note: Option<String>,
}

/// A pair of components about x and y.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct XY {
    /// About (or along) x.
    pub x: f64,
    /// About (or along) y.
    pub y: f64,
}
