//! Closed-form references: one copy, shared by tests, examples and reports.
//!
//! `E*` is the combined modulus, `1/E* = (1 - nu1^2)/E1 + (1 - nu2^2)/E2`;
//! `R` the combined radius, `1/R = 1/R1 + 1/R2`. Any consistent units.
//!
//! - Hertz, two spheres (Johnson, *Contact Mechanics*, 1985, §4.2):
//!   `a = (3 P R / 4 E*)^(1/3)`, approach `delta = a^2 / R`,
//!   `p0 = 3 P / (2 pi a^2)`, `p(r) = p0 sqrt(1 - r^2/a^2)`.
//! - Hertz, two cylinders with parallel axes, load `P'` per unit length
//!   (Johnson §4.3): `b = sqrt(4 P' R / (pi E*))`, `p0 = 2 P' / (pi b)`,
//!   `p(x) = p0 sqrt(1 - x^2/b^2)`. A 2D approach exists only relative to a
//!   datum; for surface displacements measured from points at distance `d0`
//!   along the surface (the plane-strain strip model of elcon-influence),
//!   `delta = (2 P' / (pi E*)) (ln(2 d0 / b) + 1/2)`.
//! - Rigid flat circular punch of radius `a` (Johnson §3.8, Boussinesq):
//!   `P = 2 a E* delta`, `p(r) = P / (2 pi a sqrt(a^2 - r^2))`.

use std::f64::consts::PI;

use crate::AnalysisError;

fn positive(field: &'static str, value: f64) -> Result<f64, AnalysisError> {
    if value.is_finite() && value > 0.0 {
        Ok(value)
    } else {
        Err(AnalysisError::InvalidInput {
            field,
            value,
            reason: "must be finite and > 0",
        })
    }
}

/// `1/R = 1/R1 + 1/R2` for two convex radii (`f64::INFINITY` for a plane).
pub fn combined_radius(r1: f64, r2: f64) -> f64 {
    1.0 / (1.0 / r1 + 1.0 / r2)
}

/// Hertz contact of two spheres (or a sphere on a plane).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct HertzSpheres {
    /// Combined modulus `E*`.
    pub combined_modulus: f64,
    /// Combined radius `R`.
    pub radius: f64,
    /// Normal load `P`.
    pub load: f64,
}

impl HertzSpheres {
    /// The reference for modulus `E*`, radius `R`, load `P` (all > 0).
    pub fn new(combined_modulus: f64, radius: f64, load: f64) -> Result<Self, AnalysisError> {
        Ok(Self {
            combined_modulus: positive("combined_modulus", combined_modulus)?,
            radius: positive("radius", radius)?,
            load: positive("load", load)?,
        })
    }

    /// Contact radius `a = (3 P R / 4 E*)^(1/3)`.
    pub fn contact_radius(&self) -> f64 {
        (3.0 * self.load * self.radius / (4.0 * self.combined_modulus)).cbrt()
    }

    /// Rigid-body approach `delta = a^2 / R` (the paper's alpha).
    pub fn approach(&self) -> f64 {
        self.contact_radius().powi(2) / self.radius
    }

    /// Peak pressure `p0 = 3 P / (2 pi a^2)`.
    pub fn peak_pressure(&self) -> f64 {
        3.0 * self.load / (2.0 * PI * self.contact_radius().powi(2))
    }

    /// Pressure at radius `r`: `p0 sqrt(1 - r^2/a^2)`, 0 outside the contact.
    pub fn pressure(&self, r: f64) -> f64 {
        let a = self.contact_radius();
        self.peak_pressure() * (1.0 - (r / a).powi(2)).max(0.0).sqrt()
    }
}

/// Hertz line contact of two cylinders with parallel axes (plane strain).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct HertzCylinders {
    /// Combined modulus `E*`.
    pub combined_modulus: f64,
    /// Combined radius `R`.
    pub radius: f64,
    /// Load per unit length `P'`.
    pub load_per_length: f64,
}

impl HertzCylinders {
    /// The reference for modulus `E*`, radius `R`, load per length `P'` (all > 0).
    pub fn new(
        combined_modulus: f64,
        radius: f64,
        load_per_length: f64,
    ) -> Result<Self, AnalysisError> {
        Ok(Self {
            combined_modulus: positive("combined_modulus", combined_modulus)?,
            radius: positive("radius", radius)?,
            load_per_length: positive("load_per_length", load_per_length)?,
        })
    }

    /// Half-width `b = sqrt(4 P' R / (pi E*))`.
    pub fn half_width(&self) -> f64 {
        (4.0 * self.load_per_length * self.radius / (PI * self.combined_modulus)).sqrt()
    }

    /// Peak pressure `p0 = 2 P' / (pi b)`.
    pub fn peak_pressure(&self) -> f64 {
        2.0 * self.load_per_length / (PI * self.half_width())
    }

    /// Pressure at `x`: `p0 sqrt(1 - x^2/b^2)`, 0 outside the contact.
    pub fn pressure(&self, x: f64) -> f64 {
        let b = self.half_width();
        self.peak_pressure() * (1.0 - (x / b).powi(2)).max(0.0).sqrt()
    }

    /// Approach relative to a datum at distance `d0` along the surface:
    /// `(2 P' / (pi E*)) (ln(2 d0 / b) + 1/2)`.
    pub fn approach(&self, reference_distance: f64) -> Result<f64, AnalysisError> {
        let d0 = positive("reference_distance", reference_distance)?;
        Ok(2.0 * self.load_per_length / (PI * self.combined_modulus)
            * ((2.0 * d0 / self.half_width()).ln() + 0.5))
    }
}

/// A rigid flat-ended circular punch on an elastic half-space.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FlatPunch {
    /// Combined modulus `E*` (the punch rigid: `E* = E / (1 - nu^2)` of the half-space).
    pub combined_modulus: f64,
    /// Punch radius `a`.
    pub radius: f64,
}

impl FlatPunch {
    /// The reference for modulus `E*` and radius `a` (both > 0).
    pub fn new(combined_modulus: f64, radius: f64) -> Result<Self, AnalysisError> {
        Ok(Self {
            combined_modulus: positive("combined_modulus", combined_modulus)?,
            radius: positive("radius", radius)?,
        })
    }

    /// Load for approach `delta`: `P = 2 a E* delta`.
    pub fn load(&self, approach: f64) -> f64 {
        2.0 * self.radius * self.combined_modulus * approach
    }

    /// Approach for load `P`: `delta = P / (2 a E*)`.
    pub fn approach(&self, load: f64) -> f64 {
        load / (2.0 * self.radius * self.combined_modulus)
    }

    /// Pressure at `r < a` under load `P`: `P / (2 pi a sqrt(a^2 - r^2))`
    /// (infinite at the edge; 0 outside).
    pub fn pressure(&self, load: f64, r: f64) -> f64 {
        let a = self.radius;
        if r >= a {
            return if r == a { f64::INFINITY } else { 0.0 };
        }
        load / (2.0 * PI * a * (a * a - r * r).sqrt())
    }
}
