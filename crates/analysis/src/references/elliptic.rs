//! Complete elliptic integrals to rounding, by Carlson's symmetric forms
//! (Carlson, "Numerical computation of real or complex elliptic
//! integrals", Numer. Algorithms 10, 1995; DLMF §19.25, §19.36):
//!
//! ```text
//!     R_F(x, y, z) = 1/2 ∫_0^∞ dt / sqrt((t + x)(t + y)(t + z))
//!     R_D(x, y, z) = 3/2 ∫_0^∞ dt / (sqrt((t + x)(t + y)) (t + z)^(3/2))
//!
//!     K(e) = R_F(0, 1 - e^2, 1)
//!     K(e) - E(e) = (e^2 / 3) R_D(0, 1 - e^2, 1)
//!     E(e) - (1 - e^2) K(e) = (e^2 (1 - e^2) / 3) R_D(0, 1, 1 - e^2)
//! ```
//!
//! (e the modulus, `K(e) = ∫_0^{pi/2} dθ / sqrt(1 - e^2 sin^2 θ)`). The
//! last two differences, which Hertz's elliptical contact is made of, come
//! out of R_D without the cancellation of subtracting K and E. Each
//! function is evaluated by the duplication theorem until the arguments
//! agree to a relative `ERRTOL` (0.0025 for R_F, 0.0015 for R_D), then by
//! the Taylor series of the mean to fifth order, whose truncation error is
//! about `ERRTOL^6 / (4 (1 - ERRTOL))`, below 1e-16 (the tolerances of
//! Numerical Recipes, 3rd ed., §6.12).

/// The duplication step's stopping tolerance for R_F.
const RF_TOLERANCE: f64 = 0.0025;

/// The duplication step's stopping tolerance for R_D.
const RD_TOLERANCE: f64 = 0.0015;

/// Carlson's `R_F(x, y, z)` for `x, y, z >= 0`, at most one of them zero
/// (the caller's arguments; NaN otherwise).
pub(crate) fn carlson_rf(x: f64, y: f64, z: f64) -> f64 {
    let valid = [x, y, z].iter().all(|v| v.is_finite() && *v >= 0.0)
        && [x, y, z].iter().filter(|v| **v == 0.0).count() <= 1;
    if !valid {
        return f64::NAN;
    }
    let (mut x, mut y, mut z) = (x, y, z);
    loop {
        let (sx, sy, sz) = (x.sqrt(), y.sqrt(), z.sqrt());
        let lambda = sx * (sy + sz) + sy * sz;
        x = 0.25 * (x + lambda);
        y = 0.25 * (y + lambda);
        z = 0.25 * (z + lambda);
        let mean = (x + y + z) / 3.0;
        let (dx, dy, dz) = ((mean - x) / mean, (mean - y) / mean, (mean - z) / mean);
        if dx.abs().max(dy.abs()).max(dz.abs()) <= RF_TOLERANCE {
            let e2 = dx * dy - dz * dz;
            let e3 = dx * dy * dz;
            return (1.0 + (e2 / 24.0 - 0.1 - 3.0 / 44.0 * e3) * e2 + e3 / 14.0) / mean.sqrt();
        }
    }
}

/// Carlson's `R_D(x, y, z)` for `x, y >= 0`, not both zero, and `z > 0`
/// (the caller's arguments; NaN otherwise).
pub(crate) fn carlson_rd(x: f64, y: f64, z: f64) -> f64 {
    let valid = [x, y, z].iter().all(|v| v.is_finite() && *v >= 0.0) && x + y > 0.0 && z > 0.0;
    if !valid {
        return f64::NAN;
    }
    const C1: f64 = 3.0 / 14.0;
    const C2: f64 = 1.0 / 6.0;
    const C3: f64 = 9.0 / 22.0;
    const C4: f64 = 3.0 / 26.0;
    const C5: f64 = 0.25 * C3;
    const C6: f64 = 1.5 * C4;
    let (mut x, mut y, mut z) = (x, y, z);
    let (mut sum, mut factor) = (0.0, 1.0);
    loop {
        let (sx, sy, sz) = (x.sqrt(), y.sqrt(), z.sqrt());
        let lambda = sx * (sy + sz) + sy * sz;
        sum += factor / (sz * (z + lambda));
        factor *= 0.25;
        x = 0.25 * (x + lambda);
        y = 0.25 * (y + lambda);
        z = 0.25 * (z + lambda);
        let mean = 0.2 * (x + y + 3.0 * z);
        let (dx, dy, dz) = ((mean - x) / mean, (mean - y) / mean, (mean - z) / mean);
        if dx.abs().max(dy.abs()).max(dz.abs()) <= RD_TOLERANCE {
            let ea = dx * dy;
            let eb = dz * dz;
            let ec = ea - eb;
            let ed = ea - 6.0 * eb;
            let ee = ed + ec + ec;
            let series = 1.0
                + ed * (-C1 + C5 * ed - C6 * dz * ee)
                + dz * (C2 * ee + dz * (-C3 * ec + dz * C4 * ea));
            return 3.0 * sum + factor * series / (mean * mean.sqrt());
        }
    }
}

/// The complete elliptic integral of the first kind `K(e)` of modulus e,
/// given `q = 1 - e^2` in (0, 1]: `R_F(0, q, 1)`.
pub(crate) fn complete_k(q: f64) -> f64 {
    carlson_rf(0.0, q, 1.0)
}

/// The complete elliptic integral of the second kind `E(e)`, given
/// `q = 1 - e^2` in (0, 1]: `K - (e^2 / 3) R_D(0, q, 1)`.
pub(crate) fn complete_e(q: f64) -> f64 {
    complete_k(q) - (1.0 - q) / 3.0 * carlson_rd(0.0, q, 1.0)
}

#[cfg(test)]
mod tests {
    use std::f64::consts::PI;

    use super::*;

    /// `K` by the arithmetic-geometric mean, `pi / (2 AGM(1, sqrt(q)))`:
    /// an independent check of R_F.
    fn agm_k(q: f64) -> f64 {
        let (mut a, mut b) = (1.0f64, q.sqrt());
        // Quadratic convergence: once within a few roundings, one step
        // more settles it (a fixed cap: the two may alternate between
        // adjacent doubles).
        for _ in 0..64 {
            let done = (a - b).abs() <= 4.0 * f64::EPSILON * a;
            (a, b) = (0.5 * (a + b), (a * b).sqrt());
            if done {
                break;
            }
        }
        PI / (2.0 * a)
    }

    /// Simpson's rule on `f` over [0, pi/2] with n (even) intervals.
    fn simpson(f: impl Fn(f64) -> f64, n: usize) -> f64 {
        let h = 0.5 * PI / n as f64;
        let w = |i: usize| match i {
            0 => 1.0,
            i if i == n => 1.0,
            i if i % 2 == 1 => 4.0,
            _ => 2.0,
        };
        (0..=n).map(|i| w(i) * f(i as f64 * h)).sum::<f64>() * h / 3.0
    }

    #[test]
    fn the_integrals_at_zero_eccentricity_are_a_quarter_circle() {
        assert!((complete_k(1.0) / (0.5 * PI) - 1.0).abs() < 4.0 * f64::EPSILON);
        assert!((complete_e(1.0) / (0.5 * PI) - 1.0).abs() < 4.0 * f64::EPSILON);
        // R_D(0, 1, 1) = 3 pi / 4.
        assert!((carlson_rd(0.0, 1.0, 1.0) / (0.75 * PI) - 1.0).abs() < 4.0 * f64::EPSILON);
    }

    #[test]
    fn k_agrees_with_the_arithmetic_geometric_mean_to_rounding() {
        for q in [1.0, 0.9, 0.5, 0.1, 1e-3, 1e-6, 1e-12] {
            let (k, agm) = (complete_k(q), agm_k(q));
            assert!(
                (k / agm - 1.0).abs() < 8.0 * f64::EPSILON,
                "q = {q}: {k} {agm}"
            );
        }
    }

    #[test]
    fn legendre_s_relation_holds_to_rounding() {
        // E K' + E' K - K K' = pi / 2 for complementary moduli (q and 1 - q).
        for q in [0.9, 0.7, 0.5, 0.3, 0.01] {
            let (k, e) = (complete_k(q), complete_e(q));
            let (kc, ec) = (complete_k(1.0 - q), complete_e(1.0 - q));
            let lhs = e * kc + ec * k - k * kc;
            assert!((lhs / (0.5 * PI) - 1.0).abs() < 1e-15, "q = {q}: {lhs}");
        }
    }

    #[test]
    fn e_and_the_differences_agree_with_quadrature() {
        // Simpson's rule on 2000 intervals of a smooth periodic integrand
        // is exact to rounding at these moduli (q >= 0.1).
        for q in [0.9, 0.5, 0.1] {
            let m = 1.0 - q;
            let e = simpson(|t| (1.0 - m * t.sin().powi(2)).sqrt(), 2000);
            let k = simpson(|t| 1.0 / (1.0 - m * t.sin().powi(2)).sqrt(), 2000);
            assert!((complete_e(q) / e - 1.0).abs() < 1e-14, "q = {q}");
            // The cancellation-free differences of the module documentation.
            let d = m / 3.0 * carlson_rd(0.0, q, 1.0);
            assert!((d / (k - e) - 1.0).abs() < 1e-13, "q = {q}: K - E");
            let b = m * q / 3.0 * carlson_rd(0.0, 1.0, q);
            assert!((b / (e - q * k) - 1.0).abs() < 1e-13, "q = {q}: E - q K");
        }
    }

    #[test]
    fn invalid_arguments_are_nan_not_a_panic() {
        assert!(carlson_rf(0.0, 0.0, 1.0).is_nan());
        assert!(carlson_rf(-1.0, 1.0, 1.0).is_nan());
        assert!(carlson_rd(0.0, 0.0, 1.0).is_nan());
        assert!(carlson_rd(1.0, 1.0, 0.0).is_nan());
        assert!(carlson_rd(f64::NAN, 1.0, 1.0).is_nan());
    }
}
