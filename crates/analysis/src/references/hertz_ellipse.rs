//! Hertz's elliptical contact (Johnson, *Contact Mechanics*, 1985, §4.2,
//! eqs. 4.36 to 4.41): two bodies whose gap is `h = A u^2 + B v^2` in its
//! principal axes (`A <= B`; `2A`, `2B` the principal curvatures of the
//! summed heights, [`Curvature::principal_values`]), pressed by a load P,
//! touch on an ellipse of semi-axes `a >= b` (a along u) under
//!
//! ```text
//!     p(u, v) = p0 sqrt(1 - u^2/a^2 - v^2/b^2),     P = (2/3) pi a b p0
//! ```
//!
//! whose surface displacements `delta - A u^2 - B v^2` inside the ellipse
//! close the gap when, with `e^2 = 1 - b^2/a^2` and the complete elliptic
//! integrals K(e), E(e) (`super::elliptic`),
//!
//! ```text
//!     B / A = (a^2 E/b^2 - K) / (K - E) = R_D(0, 1, q) / R_D(0, q, 1),   q = b^2/a^2
//!     a^3   = 3 P (K - E) / (2 pi E* A e^2) = P R_D(0, q, 1) / (2 pi E* A)
//!     delta = p0 b K / E*
//! ```
//!
//! The ratio of Carlson's integrals falls from 1 at q = 1 (a circle) to
//! infinity as q -> 0 (a line): q is found by bisection on the bit
//! patterns of the positive doubles, which ends at two adjacent doubles
//! (at most 64 steps), so the eccentricity is exact to rounding. The
//! limits: `A = B` is Hertz's spheres with `R = 1 / (2A)`; as `A / B -> 0`
//! the ellipse's minor semi-axis tends to the line contact's half-width
//! under the load per length `(pi/2) p0 b` of its middle section.

use std::f64::consts::PI;

use super::elliptic::{carlson_rd, complete_e, complete_k};
use crate::AnalysisError;
use crate::contact::Curvature;

/// The smallest `q = (b/a)^2` solved for: a contact more slender than
/// `b/a = 1e-12` (a principal curvature ratio above about 1e22) is a line
/// contact to rounding.
const MIN_RATIO_SQUARED: f64 = 1e-24;

/// Hertz's elliptical contact of two bodies under a load: see the module
/// documentation. Built by [`HertzEllipse::new`], which solves for the
/// eccentricity once.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct HertzEllipse {
    combined_modulus: f64,
    curvature: Curvature,
    load: f64,
    /// The smaller and the larger principal curvature of the gap, `2A`, `2B`.
    principal: (f64, f64),
    /// The direction of the major axis from x (radians).
    angle: f64,
    /// `q = (b / a)^2`.
    ratio_squared: f64,
    /// The major semi-axis a.
    semi_major: f64,
}

impl HertzEllipse {
    /// The contact of two bodies of combined modulus `E*` whose gap has
    /// the curvature `curvature` (the sum of the two surfaces', as
    /// [`Curvature::of`] gives them), under the load `P`.
    ///
    /// # Errors
    /// [`AnalysisError::InvalidInput`] naming `combined_modulus` or `load`
    /// when not finite and > 0, and `curvature` when a principal curvature
    /// of the gap is not finite and > 0 (a line contact, or surfaces that
    /// part) or their ratio exceeds what a double resolves (about 1e22: a
    /// line contact to rounding).
    pub fn new(
        combined_modulus: f64,
        curvature: Curvature,
        load: f64,
    ) -> Result<Self, AnalysisError> {
        let combined_modulus = super::positive("combined_modulus", combined_modulus)?;
        let load = super::positive("load", load)?;
        let p = curvature.principal_values();
        // A circular gap's smaller value, `det / larger`, can round a unit
        // in the last place above the larger (equal radii, crossed equal
        // cylinders): it is a circle, Hertz's spheres, not a refusal.
        let (smaller, larger) = (p.smaller.min(p.larger), p.larger.max(p.smaller));
        if !(smaller.is_finite() && larger.is_finite() && smaller > 0.0) {
            return Err(AnalysisError::InvalidInput {
                field: "curvature",
                value: smaller,
                reason: "both principal curvatures of the gap must be finite and > 0: a line \
                         contact (one of them zero) or surfaces that part have no elliptical \
                         Hertz contact",
            });
        }
        let ratio_squared = eccentricity(larger / smaller).ok_or(AnalysisError::InvalidInput {
            field: "curvature",
            value: larger / smaller,
            reason: "the principal curvatures' ratio is beyond what a double resolves: a \
                         line contact to rounding",
        })?;
        // a^3 = P R_D(0, q, 1) / (2 pi E* A), A = k_smaller / 2.
        let semi_major =
            (load * carlson_rd(0.0, ratio_squared, 1.0) / (PI * combined_modulus * smaller)).cbrt();
        Ok(Self {
            combined_modulus,
            curvature,
            load,
            principal: (smaller, larger),
            angle: p.angle,
            ratio_squared,
            semi_major,
        })
    }

    /// The same bodies under the load that gives the approach `delta`
    /// (> 0): `delta` grows as `P^(2/3)` at a fixed shape, so the load is
    /// `P (delta / delta_P)^(3/2)`.
    ///
    /// # Errors
    /// [`AnalysisError::InvalidInput`] naming `approach` when not finite
    /// and > 0, or `load` when the load is outside floating-point range.
    pub fn at_approach(&self, approach: f64) -> Result<Self, AnalysisError> {
        let delta = super::positive("approach", approach)?;
        let load = self.load * (delta / self.approach()).powf(1.5);
        Self::new(self.combined_modulus, self.curvature, load)
    }

    /// The combined modulus `E*`.
    pub fn combined_modulus(&self) -> f64 {
        self.combined_modulus
    }

    /// The gap's curvature.
    pub fn curvature(&self) -> Curvature {
        self.curvature
    }

    /// The load P.
    pub fn load(&self) -> f64 {
        self.load
    }

    /// The gap's principal curvatures, the smaller (along the major axis)
    /// first: `(2A, 2B)`.
    pub fn principal_curvatures(&self) -> (f64, f64) {
        self.principal
    }

    /// The direction of the major axis from the x axis (radians, in
    /// (-pi/2, pi/2]; 0 for a circle).
    pub fn angle(&self) -> f64 {
        self.angle
    }

    /// The major semi-axis a.
    pub fn semi_major(&self) -> f64 {
        self.semi_major
    }

    /// The minor semi-axis `b = a sqrt(q)`.
    pub fn semi_minor(&self) -> f64 {
        self.semi_major * self.ratio_squared.sqrt()
    }

    /// The eccentricity `e = sqrt(1 - b^2/a^2)`.
    pub fn eccentricity(&self) -> f64 {
        (1.0 - self.ratio_squared).sqrt()
    }

    /// The complete elliptic integrals `(K(e), E(e))`.
    pub fn elliptic_integrals(&self) -> (f64, f64) {
        (
            complete_k(self.ratio_squared),
            complete_e(self.ratio_squared),
        )
    }

    /// The radius of the circle of the same area, `sqrt(a b)` (what a
    /// solution's `contact_extent` measures).
    pub fn equivalent_radius(&self) -> f64 {
        (self.semi_major * self.semi_minor()).sqrt()
    }

    /// The ellipse's half-extents along x and along y:
    /// `(sqrt(a^2 c^2 + b^2 s^2), sqrt(a^2 s^2 + b^2 c^2))`, c and s the
    /// cosine and sine of [`HertzEllipse::angle`] (what
    /// `crate::grid::hertz_ellipse_family` sizes a grid from).
    pub fn half_extents(&self) -> (f64, f64) {
        let (s, c) = self.angle.sin_cos();
        let (a, b) = (self.semi_major, self.semi_minor());
        ((a * c).hypot(b * s), (a * s).hypot(b * c))
    }

    /// The peak pressure `p0 = 3 P / (2 pi a b)`.
    pub fn peak_pressure(&self) -> f64 {
        3.0 * self.load / (2.0 * PI * self.semi_major * self.semi_minor())
    }

    /// The approach `delta = p0 b K(e) / E*`.
    pub fn approach(&self) -> f64 {
        self.peak_pressure() * self.semi_minor() * complete_k(self.ratio_squared)
            / self.combined_modulus
    }

    /// The pressure at `(x, y)`: `p0 sqrt(1 - u^2/a^2 - v^2/b^2)` in the
    /// ellipse's axes (rotated by [`HertzEllipse::angle`]), 0 outside.
    pub fn pressure(&self, x: f64, y: f64) -> f64 {
        let (s, c) = self.angle.sin_cos();
        let (u, v) = (x * c + y * s, -x * s + y * c);
        let (a, b) = (self.semi_major, self.semi_minor());
        self.peak_pressure() * (1.0 - (u / a).powi(2) - (v / b).powi(2)).max(0.0).sqrt()
    }
}

/// `q = (b/a)^2` of the ellipse whose `R_D(0, 1, q) / R_D(0, q, 1)` is
/// `ratio = B / A >= 1`, to adjacent doubles; `None` beyond
/// [`MIN_RATIO_SQUARED`].
fn eccentricity(ratio: f64) -> Option<f64> {
    let f = |q: f64| carlson_rd(0.0, 1.0, q) / carlson_rd(0.0, q, 1.0);
    if !(ratio.is_finite() && ratio >= 1.0) {
        return None;
    }
    if ratio == 1.0 {
        return Some(1.0);
    }
    let (mut lo, mut hi) = (MIN_RATIO_SQUARED, 1.0f64);
    if !(f(lo) >= ratio) {
        return None;
    }
    // f falls with q: f(lo) >= ratio > f(hi). Bisect the bit patterns
    // (monotone in the value for positive doubles).
    loop {
        let mid =
            f64::from_bits(lo.to_bits() / 2 + hi.to_bits() / 2 + (lo.to_bits() & hi.to_bits() & 1));
        if mid <= lo || mid >= hi {
            break;
        }
        if f(mid) >= ratio {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    Some(if (f(lo) - ratio).abs() <= (f(hi) - ratio).abs() {
        lo
    } else {
        hi
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::references::{HertzCylinders, HertzSpheres};

    /// The displacement `u1 + u2` of the two half-spaces at `(x, y)` under
    /// the Hertz pressure, from Boussinesq's kernel `1 / (pi E* r)` in
    /// polar coordinates about the point: `u = (1 / (pi E*)) ∫_0^{2 pi}
    /// ∫_0^{rho(θ)} p dr dθ`. Along a ray the pressure is `p0 sqrt(Q(r))`,
    /// Q quadratic, whose integral to its root is closed:
    /// `sqrt(γ)/2 [R^2 (pi/2 - asin(c/R)) - c sqrt(R^2 - c^2)]` with
    /// `Q = γ (R^2 - (r + c)^2)`. The θ integrand is smooth and periodic,
    /// so the trapezoidal rule on 2000 angles is exact to rounding: an
    /// independent check of a, b, delta and the eccentricity.
    fn boussinesq(h: &HertzEllipse, x: f64, y: f64) -> f64 {
        let (s, c) = h.angle().sin_cos();
        let (u0, v0) = (x * c + y * s, -x * s + y * c);
        let (a, b) = (h.semi_major(), h.semi_minor());
        let n = 2000;
        let sum: f64 = (0..n)
            .map(|i| {
                let t = 2.0 * PI * i as f64 / n as f64;
                let (du, dv) = (t.cos(), t.sin());
                // Q(r) = alpha - 2 beta r - gamma r^2.
                let alpha = 1.0 - (u0 / a).powi(2) - (v0 / b).powi(2);
                let beta = u0 * du / (a * a) + v0 * dv / (b * b);
                let gamma = (du / a).powi(2) + (dv / b).powi(2);
                let cc = beta / gamma;
                let r2 = (alpha * gamma + beta * beta) / (gamma * gamma);
                let r = r2.sqrt();
                0.5 * gamma.sqrt()
                    * (r2 * (0.5 * PI - (cc / r).asin()) - cc * (r2 - cc * cc).max(0.0).sqrt())
            })
            .sum();
        h.peak_pressure() * sum * (2.0 * PI / n as f64) / (PI * h.combined_modulus())
    }

    #[test]
    fn the_displacements_of_the_pressure_close_the_gap_inside_the_ellipse() {
        // A ball in a bearing's groove (curvature ratio about 33) and a
        // crossed pair at 30 degrees: u(x, y) = delta - h(x, y) inside.
        let ball = Curvature::principal(1.0 / 3.969 + 1.0 / 15.5, 1.0 / 3.969 - 1.0 / 4.128, 0.0);
        let crossed = Curvature::of(&crate::Surface::Quadric {
            radius_x: 10.0,
            radius_y: 40.0,
            angle: 0.3,
        }) + Curvature::of(&crate::Surface::Cylinder { radius: 25.0 });
        for (curvature, load) in [(ball, 1000.0), (crossed, 500.0)] {
            let h = HertzEllipse::new(230_769.2, curvature, load).unwrap();
            let (a, b) = (h.semi_major(), h.semi_minor());
            assert!(a > b, "{a} {b}");
            let (s, c) = h.angle().sin_cos();
            for (fu, fv) in [(0.0, 0.0), (0.5, 0.0), (0.0, 0.7), (0.4, -0.5), (-0.9, 0.1)] {
                let (u, v) = (fu * a, fv * b);
                let (x, y) = (u * c - v * s, u * s + v * c);
                let expected = h.approach() - curvature.height(x, y);
                let got = boussinesq(&h, x, y);
                assert!(
                    (got / expected - 1.0).abs() < 1e-12,
                    "({fu}, {fv}): {got} against {expected}"
                );
            }
        }
    }

    /// `h`'s semi-axes, approach and peak are `s`'s radius, approach and
    /// peak to 1e-14.
    fn assert_is_spheres(h: &HertzEllipse, s: &HertzSpheres) {
        let close = |a: f64, b: f64| (a / b - 1.0).abs() < 1e-14;
        assert!(close(h.semi_major(), s.contact_radius()));
        assert!(close(h.semi_minor(), s.contact_radius()));
        assert!(close(h.approach(), s.approach()));
        assert!(close(h.peak_pressure(), s.peak_pressure()));
    }

    #[test]
    fn equal_curvatures_are_hertz_s_spheres_to_rounding() {
        let (e, r1, r2, p) = (32.967e6, 1.0, 10.0, 100.0);
        let k = 1.0 / r1 + 1.0 / r2;
        let h = HertzEllipse::new(e, Curvature::principal(k, k, 0.0), p).unwrap();
        let s = HertzSpheres::new(e, 1.0 / k, p).unwrap();
        assert_is_spheres(&h, &s);
        assert_eq!(h.eccentricity(), 0.0);
        // Nearly circular: the ellipse moves continuously from the circle
        // (a relative change of 1e-9 in the curvature moves a by about
        // that much).
        let near = HertzEllipse::new(e, Curvature::principal(k, k * (1.0 + 1e-9), 0.0), p).unwrap();
        assert!((near.semi_major() / s.contact_radius() - 1.0).abs() < 1e-9);
        assert!((near.approach() / s.approach() - 1.0).abs() < 1e-9);
    }

    #[test]
    fn a_circular_gap_whose_smaller_value_rounds_above_the_larger_is_a_circle() {
        // Two quadrics of radii 10 both ways: k = 0.2 both ways, and
        // det / larger = 0.04 / 0.2 rounds to 0.20000000000000004.
        let (e, p) = (115.38e3, 1000.0);
        let k = 1.0 / 10.0 + 1.0 / 10.0;
        let form = Curvature::principal(k, k, 0.0);
        let v = form.principal_values();
        assert!(v.smaller > v.larger, "{v:?}");
        let h = HertzEllipse::new(e, form, p).unwrap();
        let s = HertzSpheres::new(e, 1.0 / k, p).unwrap();
        assert_is_spheres(&h, &s);
        let (smaller, larger) = h.principal_curvatures();
        assert!(smaller <= larger, "{smaller} {larger}");
        // A ratio a unit above 1: q = 1 - 1.1e-16, e = sqrt(1 - q) ~ 1e-8.
        assert!(h.eccentricity() < 1e-7, "{}", h.eccentricity());
    }

    #[test]
    fn a_slender_ellipse_tends_to_the_line_contact_of_its_middle_section() {
        // The minor semi-axis against the line contact's half-width under
        // the load per length (pi/2) p0 b of the middle section; the
        // difference falls as b/a does (about (b/a)^2 ln(a/b)).
        let (e, r) = (230_769.2, 5.0);
        let mut last = f64::INFINITY;
        for ratio in [1e2, 1e4, 1e6, 1e8] {
            let h = HertzEllipse::new(
                e,
                Curvature::principal(1.0 / (r * ratio), 1.0 / r, 0.0),
                1e3,
            )
            .unwrap();
            let per_length = 0.5 * PI * h.peak_pressure() * h.semi_minor();
            let line = HertzCylinders::new(e, r, per_length).unwrap();
            let error = (h.semi_minor() / line.half_width() - 1.0).abs();
            assert!(error < last, "{ratio}: {error}");
            last = error;
        }
        assert!(last < 1e-4, "{last}");
    }

    #[test]
    fn the_approach_gives_back_its_load() {
        let c = Curvature::principal(0.01, 0.3, 0.2);
        let h = HertzEllipse::new(2e5, c, 750.0).unwrap();
        let again = h.at_approach(h.approach()).unwrap();
        assert!((again.load() / 750.0 - 1.0).abs() < 1e-14);
        let doubled = h.at_approach(2.0 * h.approach()).unwrap();
        assert!((doubled.load() / (750.0 * 2f64.powf(1.5)) - 1.0).abs() < 1e-14);
        assert!((doubled.approach() / (2.0 * h.approach()) - 1.0).abs() < 1e-14);
    }

    #[test]
    fn a_line_contact_or_parting_surfaces_are_refused_by_field() {
        let field = |r: Result<HertzEllipse, AnalysisError>| match r {
            Err(AnalysisError::InvalidInput { field, .. }) => field,
            other => panic!("{other:?}"),
        };
        let c = Curvature::principal(0.1, 0.2, 0.0);
        assert_eq!(field(HertzEllipse::new(-1.0, c, 1.0)), "combined_modulus");
        assert_eq!(field(HertzEllipse::new(1.0, c, f64::NAN)), "load");
        let line = Curvature::principal(0.0, 0.2, 0.0);
        assert_eq!(field(HertzEllipse::new(1.0, line, 1.0)), "curvature");
        let saddle = Curvature::principal(-0.1, 0.2, 0.0);
        assert_eq!(field(HertzEllipse::new(1.0, saddle, 1.0)), "curvature");
        let slender = Curvature::principal(1e-30, 1.0, 0.0);
        assert_eq!(field(HertzEllipse::new(1.0, slender, 1.0)), "curvature");
    }
}
