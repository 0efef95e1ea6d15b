//! How the bodies are pressed together: the normal load or approach, and
//! the two rotations of body 1 about the point where the load acts, each
//! free (its moment given) or prescribed (a misalignment).
//!
//! With the normal z pointing from body 1 toward body 2 and right-handed
//! rotations `θ = (θ_x, θ_y)` about axes through the load point `(x0, y0)`,
//! the rigid-body displacement of body 1 toward body 2 at `(x, y)` is
//!
//! ```text
//!     alpha + θ_x (y - y0) - θ_y (x - x0)
//! ```
//!
//! and the gaps are `Y = S F + eps - alpha - θ_x (y - y0) + θ_y (x - x0)`.
//! Each of `alpha`, `θ_x`, `θ_y` is prescribed, or free with its resultant
//! given: the load and the moments of the contact forces about the load
//! point,
//!
//! ```text
//!     sum F = P,     sum F (y - y0) = M_x,     sum F (x - x0) = -M_y
//! ```
//!
//! (the moments `M_x`, `M_y` applied to body 1 about the load point, which
//! the contact forces balance). A load applied at a point and nothing else
//! is free tilts with zero moments: the default. On a line (plane strain, a
//! beam along x) there is one rotation, `θ_y`.

use crate::AnalysisError;

/// The normal loading: a load or an approach.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Normal {
    /// Load control: the normal load P (force; force per unit length for a
    /// line contact), > 0; the approach follows.
    Load(f64),
    /// Displacement control: the approach alpha (length); the load follows.
    Approach(f64),
}

/// One rotation of body 1 about an axis through the load point.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Tilt {
    /// Free, the moment about the axis given (force length; force length
    /// per unit length for a line contact).
    Free {
        /// The moment `M` applied to body 1 about the axis.
        moment: f64,
    },
    /// Prescribed: a misalignment of `angle` radians.
    Prescribed {
        /// The rotation `θ` (radians).
        angle: f64,
    },
}

impl Default for Tilt {
    /// Free with zero moment: a load applied at a point.
    fn default() -> Self {
        Tilt::Free { moment: 0.0 }
    }
}

impl Tilt {
    /// Whether the rotation is free with zero moment (the default).
    pub fn is_free_without_moment(&self) -> bool {
        *self == Tilt::Free { moment: 0.0 }
    }

    /// The prescribed rotation `θ` (radians), 0 where the rotation is free.
    pub fn prescribed_angle(&self) -> f64 {
        match *self {
            Tilt::Prescribed { angle } => angle,
            Tilt::Free { .. } => 0.0,
        }
    }
}

/// How the bodies are pressed together (see the module documentation).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Loading {
    /// The load or the approach.
    pub normal: Normal,
    /// The rotation about the x axis (`θ_x`; lever `y - y0`).
    pub tilt_x: Tilt,
    /// The rotation about the y axis (`θ_y`; lever `-(x - x0)`).
    pub tilt_y: Tilt,
}

impl Loading {
    /// Load control with the load `P` applied at the load point (free tilts,
    /// zero moments).
    pub fn load(load: f64) -> Self {
        Self {
            normal: Normal::Load(load),
            tilt_x: Tilt::default(),
            tilt_y: Tilt::default(),
        }
    }

    /// Displacement control with the approach `alpha` (free tilts, zero
    /// moments).
    pub fn approach(approach: f64) -> Self {
        Self {
            normal: Normal::Approach(approach),
            tilt_x: Tilt::default(),
            tilt_y: Tilt::default(),
        }
    }

    /// The same with the moment `M_x` about the x axis (free `θ_x`).
    pub fn with_moment_x(self, moment: f64) -> Self {
        Self {
            tilt_x: Tilt::Free { moment },
            ..self
        }
    }

    /// The same with the moment `M_y` about the y axis (free `θ_y`).
    pub fn with_moment_y(self, moment: f64) -> Self {
        Self {
            tilt_y: Tilt::Free { moment },
            ..self
        }
    }

    /// The same with the rotation `θ_x` prescribed (radians).
    pub fn with_tilt_x(self, angle: f64) -> Self {
        Self {
            tilt_x: Tilt::Prescribed { angle },
            ..self
        }
    }

    /// The same with the rotation `θ_y` prescribed (radians).
    pub fn with_tilt_y(self, angle: f64) -> Self {
        Self {
            tilt_y: Tilt::Prescribed { angle },
            ..self
        }
    }

    /// The same with both rotations prescribed at zero: the bodies held
    /// aligned, only the approach (or load) free (Conry & Seireg's problem).
    pub fn aligned(self) -> Self {
        self.with_tilt_x(0.0).with_tilt_y(0.0)
    }

    /// The load of load control.
    pub fn load_value(&self) -> Option<f64> {
        match self.normal {
            Normal::Load(p) => Some(p),
            Normal::Approach(_) => None,
        }
    }

    /// Checks the numbers: a finite positive load or a finite approach,
    /// finite moments and angles.
    pub(crate) fn validate(&self) -> Result<(), AnalysisError> {
        match self.normal {
            Normal::Load(p) if !(p.is_finite() && p > 0.0) => {
                return Err(AnalysisError::InvalidInput {
                    field: "load",
                    value: p,
                    reason: "the normal load must be finite and > 0",
                });
            }
            Normal::Approach(a) if !a.is_finite() => {
                return Err(AnalysisError::InvalidInput {
                    field: "approach",
                    value: a,
                    reason: "the approach must be finite",
                });
            }
            _ => {}
        }
        for (tilt, moment, angle) in [
            (self.tilt_x, "moment_x", "tilt_x"),
            (self.tilt_y, "moment_y", "tilt_y"),
        ] {
            let (field, value) = match tilt {
                Tilt::Free { moment: m } => (moment, m),
                Tilt::Prescribed { angle: a } => (angle, a),
            };
            if !value.is_finite() {
                return Err(AnalysisError::InvalidInput {
                    field,
                    value,
                    reason: "must be finite",
                });
            }
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_default_is_a_load_at_a_point() {
        let l = Loading::load(10.0);
        assert!(l.tilt_x.is_free_without_moment() && l.tilt_y.is_free_without_moment());
        let l = l.with_moment_y(2.0).with_tilt_x(1e-3);
        assert_eq!(l.tilt_y, Tilt::Free { moment: 2.0 });
        assert_eq!(l.tilt_x, Tilt::Prescribed { angle: 1e-3 });
        assert_eq!(
            Loading::approach(1.0).aligned().tilt_y,
            Tilt::Prescribed { angle: 0.0 }
        );
        let e = Loading::load(1.0)
            .with_moment_x(f64::NAN)
            .validate()
            .unwrap_err();
        assert!(e.to_string().contains("moment_x"), "{e}");
    }
}
