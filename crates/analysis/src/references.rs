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
//! - A finite beam with free ends on a Winkler foundation under a central
//!   concentrated load (Hetenyi, *Beams on Elastic Foundation*, 1946, §V;
//!   the foundation bilateral, i.e. every point in contact):
//!   `lambda = (k / (4 E I))^(1/4)`, `phi = lambda L / 2`, z the distance
//!   from the nearer free end,
//!   `y(z) = P lambda / (k (sinh lambda L + sin lambda L)) [2 cosh phi cos phi cosh lz cos lz
//!   + (cosh phi sin phi - sinh phi cos phi)(cosh lz sin lz + sinh lz cos lz)]`, `lz = lambda z`;
//!   at the centre `P lambda (cosh lambda L + cos lambda L + 2) / (2 k (sinh lambda L + sin lambda L))`.

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

/// A finite Euler-Bernoulli beam with free ends on a Winkler foundation,
/// loaded by a concentrated force at its middle (Hetenyi 1946), the
/// foundation bilateral: the closed form holds while the deflection stays
/// positive everywhere (every point in contact), i.e. for `lambda L < pi`
/// (beyond it the ends would lift off a tensionless foundation).
///
/// Units: `E I` in force length^2, `k` in force per length per deflection
/// (force/length^2, the modulus per unit length of beam), `L` length, `P`
/// force; deflections in length, foundation reaction `k y` in force per length.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct HetenyiBeam {
    /// Flexural rigidity `E I`.
    pub flexural_rigidity: f64,
    /// Foundation modulus `k` per unit length of beam.
    pub foundation_modulus: f64,
    /// Beam length `L`.
    pub length: f64,
    /// Central load `P`.
    pub load: f64,
}

impl HetenyiBeam {
    /// The reference for `E I`, `k`, `L` and `P` (all finite and > 0).
    pub fn new(
        flexural_rigidity: f64,
        foundation_modulus: f64,
        length: f64,
        load: f64,
    ) -> Result<Self, AnalysisError> {
        Ok(Self {
            flexural_rigidity: positive("flexural_rigidity", flexural_rigidity)?,
            foundation_modulus: positive("foundation_modulus", foundation_modulus)?,
            length: positive("length", length)?,
            load: positive("load", load)?,
        })
    }

    /// The characteristic `lambda = (k / (4 E I))^(1/4)` (1/length).
    pub fn lambda(&self) -> f64 {
        (self.foundation_modulus / (4.0 * self.flexural_rigidity)).powf(0.25)
    }

    /// Deflection (into the foundation) at `x`, measured from the beam's
    /// middle (`|x| <= L/2`; outside the beam: 0).
    pub fn deflection(&self, x: f64) -> f64 {
        let half = 0.5 * self.length;
        if x.abs() > half {
            return 0.0;
        }
        let lam = self.lambda();
        let ll = lam * self.length;
        let phi = 0.5 * ll;
        let lz = lam * (half - x.abs());
        let factor = self.load * lam / (self.foundation_modulus * (ll.sinh() + ll.sin()));
        factor
            * (2.0 * phi.cosh() * phi.cos() * lz.cosh() * lz.cos()
                + (phi.cosh() * phi.sin() - phi.sinh() * phi.cos())
                    * (lz.cosh() * lz.sin() + lz.sinh() * lz.cos()))
    }

    /// Deflection at the load point: `P lambda (cosh lambda L + cos lambda L
    /// + 2) / (2 k (sinh lambda L + sin lambda L))`, the approach alpha.
    pub fn centre_deflection(&self) -> f64 {
        let lam = self.lambda();
        let ll = lam * self.length;
        self.load * lam * (ll.cosh() + ll.cos() + 2.0)
            / (2.0 * self.foundation_modulus * (ll.sinh() + ll.sin()))
    }

    /// Foundation reaction per unit length at `x`: `k y(x)` (force/length).
    pub fn load_intensity(&self, x: f64) -> f64 {
        self.foundation_modulus * self.deflection(x)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn hetenyi_general_form_meets_the_centre_and_end_formulas() {
        let beam = HetenyiBeam::new(1.6e8, 1e7, 8.9, 5e4).unwrap();
        let lam = beam.lambda();
        let ll = lam * beam.length;
        assert!((beam.deflection(0.0) / beam.centre_deflection() - 1.0).abs() < 1e-14);
        // End: 2 P lambda cosh(lL/2) cos(lL/2) / (k (sinh lL + sin lL)) (Roark, Table 8.6).
        let end = 2.0 * beam.load * lam * (0.5 * ll).cosh() * (0.5 * ll).cos()
            / (beam.foundation_modulus * (ll.sinh() + ll.sin()));
        assert!((beam.deflection(4.45) - end).abs() < 1e-14 * beam.centre_deflection());
        assert_eq!(beam.deflection(-1.3), beam.deflection(1.3));
        assert_eq!(beam.deflection(4.5), 0.0);
    }

    #[test]
    fn hetenyi_satisfies_equilibrium_and_the_rigid_limit() {
        // The reaction integrates to P (Simpson's rule on 2000 intervals).
        let beam = HetenyiBeam::new(2.0e5, 3.0e3, 6.0, 7.0).unwrap();
        let n = 2000;
        let h = beam.length / n as f64;
        let f = |i: usize| beam.load_intensity(-0.5 * beam.length + i as f64 * h);
        let simpson: f64 = (0..=n)
            .map(|i| {
                let w = if i == 0 || i == n {
                    1.0
                } else if i % 2 == 1 {
                    4.0
                } else {
                    2.0
                };
                w * f(i)
            })
            .sum::<f64>()
            * h
            / 3.0;
        assert!((simpson / beam.load - 1.0).abs() < 1e-10, "{simpson}");
        // A very stiff beam sinks uniformly: y = P / (k L).
        let rigid = HetenyiBeam::new(1e12, 3.0e3, 6.0, 7.0).unwrap();
        let uniform = 7.0 / (3.0e3 * 6.0);
        for x in [0.0, 1.0, 2.9] {
            assert!((rigid.deflection(x) / uniform - 1.0).abs() < 1e-6);
        }
    }
}
