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

/// Loading's builders that set one tilt each: `$name(self, $value)` sets
/// `$tilt` to `Tilt::$kind { $value }`.
macro_rules! tilt_builders {
    ($($(#[doc = $doc:literal])+ $name:ident: $tilt:ident = $kind:ident { $value:ident };)+) => {
        impl Loading {
            $(
                $(#[doc = $doc])+
                pub fn $name(self, $value: f64) -> Self {
                    Self {
                        $tilt: Tilt::$kind { $value },
                        ..self
                    }
                }
            )+
        }
    };
}

tilt_builders! {
    /// The same with the moment `M_x` about the x axis (free `θ_x`).
    with_moment_x: tilt_x = Free { moment };
    /// The same with the moment `M_y` about the y axis (free `θ_y`).
    with_moment_y: tilt_y = Free { moment };
    /// The same with the rotation `θ_x` prescribed (radians).
    with_tilt_x: tilt_x = Prescribed { angle };
    /// The same with the rotation `θ_y` prescribed (radians).
    with_tilt_y: tilt_y = Prescribed { angle };
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
        Self::pressed(Normal::Load(load))
    }

    /// Displacement control with the approach `alpha` (free tilts, zero
    /// moments).
    pub fn approach(approach: f64) -> Self {
        Self::pressed(Normal::Approach(approach))
    }

    /// `normal` with free tilts and zero moments.
    fn pressed(normal: Normal) -> Self {
        Self {
            normal,
            tilt_x: Tilt::default(),
            tilt_y: Tilt::default(),
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
        let normal = match self.normal {
            Normal::Load(p) => (
                p.is_finite() && p > 0.0,
                "load",
                p,
                "the normal load must be finite and > 0",
            ),
            Normal::Approach(a) => (a.is_finite(), "approach", a, "the approach must be finite"),
        };
        // A tilt's moment when it is free, its angle when prescribed.
        let tilt = |tilt: Tilt, moment, angle| {
            let (field, value) = match tilt {
                Tilt::Free { moment: m } => (moment, m),
                Tilt::Prescribed { angle: a } => (angle, a),
            };
            (value.is_finite(), field, value, "must be finite")
        };
        elcon_num::check([
            normal,
            tilt(self.tilt_x, "moment_x", "tilt_x"),
            tilt(self.tilt_y, "moment_y", "tilt_y"),
        ])?;
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
