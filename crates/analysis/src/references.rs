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
//!   concentrated load ([`HetenyiBeam`] of a [`BeamOnFoundation`]; Hetenyi,
//!   *Beams on Elastic Foundation*, 1946, §V; the foundation bilateral,
//!   i.e. every point in contact):
//!   `lambda = (k / (4 E I))^(1/4)`, `phi = lambda L / 2`, z the distance
//!   from the nearer free end,
//!   `y(z) = P lambda / (k (sinh lambda L + sin lambda L)) [2 cosh phi cos phi cosh lz cos lz
//!   + (cosh phi sin phi - sinh phi cos phi)(cosh lz sin lz + sinh lz cos lz)]`, `lz = lambda z`;
//!   at the centre `P lambda (cosh lambda L + cos lambda L + 2) / (2 k (sinh lambda L + sin lambda L))`.
//! - The flat punch under a load `P` and a moment with first moment
//!   `m = sum F x` about its centre, no lift-off while `|m| <= P a / 3`
//!   (Johnson §3.8): `p = (P + 3 m x / a^2) / (2 pi a sqrt(a^2 - r^2))`, the
//!   punch tilted by `3 m / (4 E* a^3)` toward the side of `m`.
//! - The same finite beam under a concentrated load anywhere on it
//!   ([`FiniteBeam`]): `E I w'''' + k w = P delta(x - e)` with free ends,
//!   solved exactly on the two spans either side of the load (four waves
//!   each; 8 conditions: free ends, continuity of `w`, `w'`, `w''` and the
//!   jump `P` of the shear at the load).
//! - Hertz, an elliptical contact ([`HertzEllipse`]; Johnson §4.2): two
//!   quadrics whose gap is `A u^2 + B v^2` touch on an ellipse of
//!   semi-axes a, b, `B/A = (a^2 E(e)/b^2 - K(e)) / (K(e) - E(e))`,
//!   `p = p0 sqrt(1 - u^2/a^2 - v^2/b^2)`, `p0 = 3 P / (2 pi a b)`,
//!   `delta = p0 b K(e) / E*`; the eccentricity e solved to rounding with
//!   the complete elliptic integrals in Carlson's symmetric forms.

use std::f64::consts::PI;

use crate::error::AnalysisError;

mod elliptic;
mod hertz_ellipse;

pub use hertz_ellipse::HertzEllipse;

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

    /// The largest first moment of the pressure about the centre, `P a / 3`,
    /// the punch carries without lifting its heel.
    pub fn lift_off_moment(&self, load: f64) -> f64 {
        load * self.radius / 3.0
    }

    /// The punch's tilt under a first moment `m = sum F x` of the pressure
    /// (no lift-off): `3 m / (4 E* a^3)` radians, pressing the side of `m`
    /// deeper.
    pub fn tilt(&self, first_moment: f64) -> f64 {
        3.0 * first_moment / (4.0 * self.combined_modulus * self.radius.powi(3))
    }

    /// Pressure at `(x, y)` inside the punch under load `P` and first
    /// moment `m = sum F x`: `(P + 3 m x / a^2) / (2 pi a sqrt(a^2 - r^2))`
    /// (no lift-off; infinite at the edge, 0 outside).
    pub fn pressure_with_moment(&self, load: f64, first_moment: f64, x: f64, y: f64) -> f64 {
        let a = self.radius;
        let r = x.hypot(y);
        if r >= a {
            return if r == a { f64::INFINITY } else { 0.0 };
        }
        (load + 3.0 * first_moment * x / (a * a)) / (2.0 * PI * a * (a * a - r * r).sqrt())
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

/// A finite Euler-Bernoulli beam with free ends on a Winkler foundation
/// under one concentrated load: the parameters of [`HetenyiBeam`] (the load
/// at the middle) and [`FiniteBeam`] (the load anywhere), each finite and
/// > 0.
///
/// Units: `E I` in force length^2, `k` in force per length per deflection
/// (force/length^2, the modulus per unit length of beam), `L` length, `P`
/// force.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BeamOnFoundation {
    /// Flexural rigidity `E I`.
    pub flexural_rigidity: f64,
    /// Foundation modulus `k` per unit length of beam.
    pub foundation_modulus: f64,
    /// Beam length `L`.
    pub length: f64,
    /// The load `P`.
    pub load: f64,
}

impl BeamOnFoundation {
    /// The parameters, each checked finite and > 0 (an error names the
    /// first that is not).
    fn validated(self) -> Result<Self, AnalysisError> {
        Ok(Self {
            flexural_rigidity: positive("flexural_rigidity", self.flexural_rigidity)?,
            foundation_modulus: positive("foundation_modulus", self.foundation_modulus)?,
            length: positive("length", self.length)?,
            load: positive("load", self.load)?,
        })
    }

    /// The characteristic `lambda = (k / (4 E I))^(1/4)` (1/length).
    pub fn lambda(&self) -> f64 {
        (self.foundation_modulus / (4.0 * self.flexural_rigidity)).powf(0.25)
    }
}

/// A finite Euler-Bernoulli beam with free ends on a Winkler foundation,
/// loaded by a concentrated force at its middle (Hetenyi 1946), the
/// foundation bilateral: the closed form holds while the deflection stays
/// positive everywhere (every point in contact), i.e. for `lambda L < pi`
/// (beyond it the ends would lift off a tensionless foundation).
///
/// Units as [`BeamOnFoundation`]; deflections in length, foundation
/// reaction `k y` in force per length.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct HetenyiBeam {
    /// `E I`, `k`, `L` and the central load `P`, validated.
    beam: BeamOnFoundation,
}

impl HetenyiBeam {
    /// The reference for `E I`, `k`, `L` and `P`.
    ///
    /// # Errors
    /// [`AnalysisError::InvalidInput`] naming the first parameter that is
    /// not finite and > 0.
    pub fn new(beam: BeamOnFoundation) -> Result<Self, AnalysisError> {
        Ok(Self {
            beam: beam.validated()?,
        })
    }

    /// The beam's parameters.
    pub fn parameters(&self) -> &BeamOnFoundation {
        &self.beam
    }

    /// The characteristic `lambda = (k / (4 E I))^(1/4)` (1/length).
    pub fn lambda(&self) -> f64 {
        self.beam.lambda()
    }

    /// Deflection (into the foundation) at `x`, measured from the beam's
    /// middle (`|x| <= L/2`; outside the beam: 0).
    pub fn deflection(&self, x: f64) -> f64 {
        let half = 0.5 * self.beam.length;
        if x.abs() > half {
            return 0.0;
        }
        let lam = self.lambda();
        let ll = lam * self.beam.length;
        let phi = 0.5 * ll;
        let lz = lam * (half - x.abs());
        let factor = self.beam.load * lam / (self.beam.foundation_modulus * (ll.sinh() + ll.sin()));
        factor
            * (2.0 * phi.cosh() * phi.cos() * lz.cosh() * lz.cos()
                + (phi.cosh() * phi.sin() - phi.sinh() * phi.cos())
                    * (lz.cosh() * lz.sin() + lz.sinh() * lz.cos()))
    }

    /// Deflection at the load point: `P lambda (cosh lambda L + cos lambda L
    /// + 2) / (2 k (sinh lambda L + sin lambda L))`, the approach alpha.
    pub fn centre_deflection(&self) -> f64 {
        let lam = self.lambda();
        let ll = lam * self.beam.length;
        self.beam.load * lam * (ll.cosh() + ll.cos() + 2.0)
            / (2.0 * self.beam.foundation_modulus * (ll.sinh() + ll.sin()))
    }

    /// Foundation reaction per unit length at `x`: `k y(x)` (force/length).
    pub fn load_intensity(&self, x: f64) -> f64 {
        self.beam.foundation_modulus * self.deflection(x)
    }
}

/// A finite Euler-Bernoulli beam with free ends on a Winkler foundation
/// under a concentrated load anywhere on it, the foundation bilateral
/// (every point in contact; the solution holds for a tensionless one while
/// the deflection stays positive: [`FiniteBeam::lifts_off`]).
///
/// `E I w'''' + k w = P delta(x - e)` on `|x| <= L/2` (x from the beam's
/// middle), `w'' = w''' = 0` at both ends. On each span between an end and
/// the load the solution is a sum of the four waves `exp(-lambda t)
/// (cos, sin)(lambda t)` decaying from either end of the span (bounded by 1,
/// so long beams do not overflow); the 8 coefficients solve the 8
/// conditions (free ends; `w`, `w'`, `w''` continuous and `E I` times the
/// jump of `w'''` equal to `P` at the load) by a faer LU. Units as
/// [`HetenyiBeam`]; `w` is the deflection into the foundation, and the
/// beam's rotation is `w'` (the tilt of elcon's loading about the load
/// point is `-w'(e)`).
#[derive(Debug, Clone, PartialEq)]
pub struct FiniteBeam {
    /// `E I`, `k`, `L` and the load `P`, validated.
    beam: BeamOnFoundation,
    /// Where the load acts, `e`, from the beam's middle.
    position: f64,
    /// The span coefficients (see [`FiniteBeam::deflection`]), cached: they
    /// follow from the parameters, which are therefore not public fields.
    coefficients: [f64; 8],
}

impl FiniteBeam {
    /// The reference for `E I`, `k`, `L`, `P` and the load's position `e`
    /// from the beam's middle (strictly inside the beam).
    ///
    /// # Errors
    /// [`AnalysisError::InvalidInput`] naming the first parameter that is
    /// not finite and > 0, or `position` when `|e| >= L / 2`.
    pub fn new(beam: BeamOnFoundation, position: f64) -> Result<Self, AnalysisError> {
        let beam = beam.validated()?;
        let length = beam.length;
        let mut beam = Self {
            beam,
            position,
            coefficients: [0.0; 8],
        };
        if !(position.is_finite() && position.abs() < 0.5 * length) {
            return Err(AnalysisError::InvalidInput {
                field: "position",
                value: position,
                reason: "the load must act strictly inside the beam, |e| < L / 2",
            });
        }
        beam.coefficients = beam.solve();
        Ok(beam)
    }

    /// The beam's parameters.
    pub fn parameters(&self) -> &BeamOnFoundation {
        &self.beam
    }

    /// Where the load acts, `e`, from the beam's middle.
    pub fn position(&self) -> f64 {
        self.position
    }

    /// The characteristic `lambda = (k / (4 E I))^(1/4)` (1/length).
    pub fn lambda(&self) -> f64 {
        self.beam.lambda()
    }

    /// The spans: `[start, end]` of the left span and of the right one.
    fn spans(&self) -> [(f64, f64); 2] {
        let h = 0.5 * self.beam.length;
        [(-h, self.position), (self.position, h)]
    }

    /// The four waves of a span `[start, end]` and their first three
    /// derivatives in x at `x`: `waves[d][j]`, d the order; j = 0, 1 are
    /// `exp(-lt) cos lt`, `exp(-lt) sin lt` with `t = x - start`, j = 2, 3
    /// the same with `t = end - x`.
    fn waves(&self, (start, end): (f64, f64), x: f64) -> [[f64; 4]; 4] {
        let l = self.lambda();
        let mut w = [[0.0; 4]; 4];
        for (side, t, sign) in [(0, x - start, 1.0), (1, end - x, -1.0)] {
            let (c, s, d) = ((l * t).cos(), (l * t).sin(), (-l * t).exp());
            let (mut f, mut g) = (d * c, d * s);
            let mut factor = 1.0;
            for order in w.iter_mut() {
                order[2 * side] = factor * f;
                order[2 * side + 1] = factor * g;
                // d/dt (f, g) = (-f - g, f - g); d/dx = sign * l * d/dt.
                (f, g) = (-f - g, f - g);
                factor *= sign * l;
            }
        }
        w
    }

    /// The 8 coefficients from the 8 conditions.
    fn solve(&self) -> [f64; 8] {
        use faer::linalg::solvers::Solve;
        let [left, right] = self.spans();
        let mut a = faer::Mat::<f64>::zeros(8, 8);
        let mut b = faer::Col::<f64>::zeros(8);
        // Free ends: w'' = w''' = 0.
        for (row0, span, x, offset) in [(0, left, left.0, 0), (2, right, right.1, 4)] {
            let w = self.waves(span, x);
            for d in 0..2 {
                for j in 0..4 {
                    a[(row0 + d, offset + j)] = w[2 + d][j];
                }
            }
        }
        // At the load: w, w', w'' continuous; E I (w'''(e+) - w'''(e-)) = P.
        let (l, r) = (
            self.waves(left, self.position),
            self.waves(right, self.position),
        );
        for d in 0..4 {
            for j in 0..4 {
                a[(4 + d, j)] = -l[d][j];
                a[(4 + d, 4 + j)] = r[d][j];
            }
        }
        b[7] = self.beam.load / self.beam.flexural_rigidity;
        let x = a.partial_piv_lu().solve(&b);
        std::array::from_fn(|i| x[i])
    }

    /// The `order`-th derivative of the deflection at `x` (0 outside the beam).
    fn derivative(&self, x: f64, order: usize) -> f64 {
        if x.abs() > 0.5 * self.beam.length {
            return 0.0;
        }
        let [left, right] = self.spans();
        let (span, offset) = if x <= self.position {
            (left, 0)
        } else {
            (right, 4)
        };
        let w = self.waves(span, x);
        (0..4)
            .map(|j| self.coefficients[offset + j] * w[order][j])
            .sum()
    }

    /// Deflection into the foundation at `x` (from the beam's middle).
    pub fn deflection(&self, x: f64) -> f64 {
        self.derivative(x, 0)
    }

    /// The beam's slope `w'(x)`.
    pub fn slope(&self, x: f64) -> f64 {
        self.derivative(x, 1)
    }

    /// Foundation reaction per unit length at `x`: `k w(x)` (force/length).
    pub fn load_intensity(&self, x: f64) -> f64 {
        self.beam.foundation_modulus * self.deflection(x)
    }

    /// Whether the bilateral solution pulls on the foundation somewhere
    /// (some deflection negative, sampled at 2001 points along the beam):
    /// then a tensionless foundation lifts off and this is no reference.
    pub fn lifts_off(&self) -> bool {
        let h = 0.5 * self.beam.length;
        (0..=2000).any(|i| self.deflection(-h + self.beam.length * i as f64 / 2000.0) < 0.0)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Example 2's beam: E I = 1.6e8 lb in^2 on a foundation of 1e7
    /// lb/in/in, 8.9 in long, under 50,000 lb.
    const EXAMPLE: BeamOnFoundation = BeamOnFoundation {
        flexural_rigidity: 1.6e8,
        foundation_modulus: 1e7,
        length: 8.9,
        load: 5e4,
    };

    /// The weight of node i of Simpson's rule on n intervals (n even):
    /// 1, 4, 2, 4, ..., 2, 4, 1 (times h / 3).
    fn simpson_weight(i: usize, n: usize) -> f64 {
        if i == 0 || i == n {
            1.0
        } else if i % 2 == 1 {
            4.0
        } else {
            2.0
        }
    }

    #[test]
    fn the_finite_beam_is_hetenyi_s_with_a_central_load_and_in_equilibrium_off_centre() {
        let central = HetenyiBeam::new(EXAMPLE).unwrap();
        let beam = FiniteBeam::new(EXAMPLE, 0.0).unwrap();
        for i in 0..=20 {
            let x = -4.45 + 8.9 * i as f64 / 20.0;
            let (a, b) = (beam.deflection(x), central.deflection(x));
            assert!(
                (a - b).abs() <= 1e-12 * central.centre_deflection(),
                "{x}: {a} {b}"
            );
        }
        // Off centre: the foundation's reaction balances the load and its
        // moment about the load (Simpson's rule on a fine grid).
        let e = 1.3;
        let beam = FiniteBeam::new(EXAMPLE, e).unwrap();
        let n = 20_000;
        let h = 8.9 / n as f64;
        let (mut force, mut moment) = (0.0, 0.0);
        for i in 0..=n {
            let x = -4.45 + h * i as f64;
            let weight = simpson_weight(i, n);
            let q = beam.load_intensity(x);
            force += weight * q * h / 3.0;
            moment += weight * q * (x - e) * h / 3.0;
        }
        assert!((force / 5e4 - 1.0).abs() < 1e-9, "{force}");
        assert!(moment.abs() < 1e-9 * 5e4 * 8.9, "{moment}");
        // Past the kern of a nearly rigid beam (e > L / 6) the far end pulls;
        // well inside it (L = 6, e = 0.5) it does not.
        assert!(beam.lifts_off());
        assert!(
            !FiniteBeam::new(
                BeamOnFoundation {
                    length: 6.0,
                    ..EXAMPLE
                },
                0.5
            )
            .unwrap()
            .lifts_off()
        );
        // A soft beam loaded near its end lifts the far end.
        let soft = FiniteBeam::new(
            BeamOnFoundation {
                flexural_rigidity: 1e6,
                ..EXAMPLE
            },
            3.5,
        )
        .unwrap();
        assert!(soft.lifts_off());
        // A load off the beam is refused.
        assert!(
            FiniteBeam::new(
                BeamOnFoundation {
                    flexural_rigidity: 1.0,
                    foundation_modulus: 1.0,
                    length: 2.0,
                    load: 1.0
                },
                1.0
            )
            .is_err()
        );
    }

    #[test]
    fn hetenyi_general_form_meets_the_centre_and_end_formulas() {
        let beam = HetenyiBeam::new(EXAMPLE).unwrap();
        let lam = beam.lambda();
        let ll = lam * beam.parameters().length;
        assert!((beam.deflection(0.0) / beam.centre_deflection() - 1.0).abs() < 1e-14);
        // End: 2 P lambda cosh(lL/2) cos(lL/2) / (k (sinh lL + sin lL)) (Roark, Table 8.6).
        let end = 2.0 * beam.parameters().load * lam * (0.5 * ll).cosh() * (0.5 * ll).cos()
            / (beam.parameters().foundation_modulus * (ll.sinh() + ll.sin()));
        assert!((beam.deflection(4.45) - end).abs() < 1e-14 * beam.centre_deflection());
        assert_eq!(beam.deflection(-1.3), beam.deflection(1.3));
        assert_eq!(beam.deflection(4.5), 0.0);
    }

    #[test]
    fn hetenyi_satisfies_equilibrium_and_the_rigid_limit() {
        // The reaction integrates to P (Simpson's rule on 2000 intervals).
        let beam = HetenyiBeam::new(BeamOnFoundation {
            flexural_rigidity: 2.0e5,
            foundation_modulus: 3.0e3,
            length: 6.0,
            load: 7.0,
        })
        .unwrap();
        let n = 2000;
        let h = beam.parameters().length / n as f64;
        let f = |i: usize| beam.load_intensity(-0.5 * beam.parameters().length + i as f64 * h);
        let simpson: f64 = (0..=n).map(|i| simpson_weight(i, n) * f(i)).sum::<f64>() * h / 3.0;
        assert!(
            (simpson / beam.parameters().load - 1.0).abs() < 1e-10,
            "{simpson}"
        );
        // A very stiff beam sinks uniformly: y = P / (k L).
        let rigid = HetenyiBeam::new(BeamOnFoundation {
            flexural_rigidity: 1e12,
            ..*beam.parameters()
        })
        .unwrap();
        let uniform = 7.0 / (3.0e3 * 6.0);
        for x in [0.0, 1.0, 2.9] {
            assert!((rigid.deflection(x) / uniform - 1.0).abs() < 1e-6);
        }
    }

    #[test]
    fn the_beams_name_each_parameter_out_of_range() {
        let field = |e: AnalysisError| match e {
            AnalysisError::InvalidInput { field, .. } => field,
            other => panic!("expected InvalidInput, got {other:?}"),
        };
        for (beam, name) in [
            (
                BeamOnFoundation {
                    flexural_rigidity: -1.0,
                    ..EXAMPLE
                },
                "flexural_rigidity",
            ),
            (
                BeamOnFoundation {
                    foundation_modulus: f64::NAN,
                    ..EXAMPLE
                },
                "foundation_modulus",
            ),
            (
                BeamOnFoundation {
                    length: 0.0,
                    ..EXAMPLE
                },
                "length",
            ),
            (
                BeamOnFoundation {
                    load: f64::INFINITY,
                    ..EXAMPLE
                },
                "load",
            ),
        ] {
            assert_eq!(field(HetenyiBeam::new(beam).unwrap_err()), name);
            assert_eq!(field(FiniteBeam::new(beam, 0.0).unwrap_err()), name);
        }
        for position in [4.45, -5.0, f64::NAN] {
            let e = FiniteBeam::new(EXAMPLE, position).unwrap_err();
            assert_eq!(field(e), "position", "e = {position}");
        }
        let beam = FiniteBeam::new(EXAMPLE, 1.3).unwrap();
        assert_eq!((*beam.parameters(), beam.position()), (EXAMPLE, 1.3));
        assert_eq!(*HetenyiBeam::new(EXAMPLE).unwrap().parameters(), EXAMPLE);
    }
}
