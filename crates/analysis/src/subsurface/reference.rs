//! Closed-form stresses below Hertz contacts (Johnson 1985, §3.4 and §4.2),
//! in units of the peak pressure p0, tension positive, z the depth.
//!
//! Point contact (radius a), along the axis:
//!
//! ```text
//!     sigma_r / p0 = sigma_theta / p0 = -(1 + nu) (1 - (z / a) atan(a / z)) + 1 / (2 (1 + z^2 / a^2))
//!     sigma_z / p0 = -1 / (1 + z^2 / a^2)
//! ```
//!
//! its largest shear `(sigma_r - sigma_z) / 2` 0.31 p0 at z = 0.48 a for
//! nu = 0.3. Line contact (half-width b), everywhere (McEwen 1949), with
//! `m^2 = (sqrt(s^2 + 4 x^2 z^2) + s) / 2`, `n^2 = (sqrt(s^2 + 4 x^2 z^2) -
//! s) / 2`, `s = b^2 - x^2 + z^2`, n of the sign of x:
//!
//! ```text
//!     sigma_x = -(p0 / b) [m (1 + (z^2 + n^2) / (m^2 + n^2)) - 2 z]
//!     sigma_z = -(p0 / b) m (1 - (z^2 + n^2) / (m^2 + n^2))
//!     tau_xz  = -(p0 / b) n (m^2 - z^2) / (m^2 + n^2)          sigma_y = nu (sigma_x + sigma_z)
//! ```
//!
//! its largest shear 0.30 p0 at z = 0.78 b on the axis and its largest
//! orthogonal shear 0.25 p0 at z = 0.50 b, x = +-0.87 b.

use elcon_influence::Stress;

/// The stresses along the axis of a Hertz point contact of radius `a` at
/// depth `z` > 0, over p0 (Poisson's ratio `nu` of the body).
pub fn hertz_point_axis(z: f64, a: f64, nu: f64) -> Stress {
    let t = z / a;
    let radial = -(1.0 + nu) * (1.0 - t * (1.0 / t).atan()) + 0.5 / (1.0 + t * t);
    Stress {
        xx: radial,
        yy: radial,
        zz: -1.0 / (1.0 + t * t),
        ..Stress::default()
    }
}

/// The stresses at `(x, z)`, z > 0, below a Hertz line contact of
/// half-width `b`, over p0 (plane strain, Poisson's ratio `nu`; McEwen).
pub fn hertz_line(x: f64, z: f64, b: f64, nu: f64) -> Stress {
    let s = b * b - x * x + z * z;
    let root = (s * s + 4.0 * x * x * z * z).sqrt();
    let m = (0.5 * (root + s)).max(0.0).sqrt();
    let n = (0.5 * (root - s)).max(0.0).sqrt().copysign(x);
    let (mn, zn) = (m * m + n * n, z * z + n * n);
    let xx = -(m * (1.0 + zn / mn) - 2.0 * z) / b;
    let zz = -(m * (1.0 - zn / mn)) / b;
    let xz = -(n * (m * m - z * z) / mn) / b;
    Stress {
        xx,
        yy: nu * (xx + zz),
        zz,
        xz,
        ..Stress::default()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The largest of `f` over (0, span] by a fine scan then a golden
    /// refinement: (value, argument).
    fn largest(f: impl Fn(f64) -> f64, span: f64) -> (f64, f64) {
        let n = 2000;
        let (mut at, mut best) = (0.0, f64::NEG_INFINITY);
        for i in 1..=n {
            let t = span * i as f64 / n as f64;
            if f(t) > best {
                (at, best) = (t, f(t));
            }
        }
        (best, at)
    }

    #[test]
    fn a_point_contacts_largest_shear_is_031_p0_at_048_a() {
        let (tau, z) = largest(|z| hertz_point_axis(z, 1.0, 0.3).tresca(), 2.0);
        assert!((tau - 0.31).abs() < 0.005, "{tau}");
        assert!((z - 0.48).abs() < 0.01, "{z}");
        // At the surface, sigma_z = -p0 and sigma_r = -(1 + 2 nu) p0 / 2.
        let s = hertz_point_axis(1e-9, 1.0, 0.3);
        assert!(
            (s.zz + 1.0).abs() < 1e-8 && (s.xx + 0.8).abs() < 1e-8,
            "{s:?}"
        );
    }

    #[test]
    fn a_line_contacts_shears_are_johnsons() {
        let (tau, z) = largest(|z| hertz_line(0.0, z, 1.0, 0.3).tresca(), 2.0);
        assert!((tau - 0.30).abs() < 0.005, "{tau}");
        assert!((z - 0.78).abs() < 0.01, "{z}");
        // The orthogonal shear's largest, off the axis.
        let mut best = (0.0f64, 0.0, 0.0);
        for i in 1..=200 {
            for j in 0..=200 {
                let (x, z) = (2.0 * j as f64 / 200.0, i as f64 / 200.0);
                let t = hertz_line(x, z, 1.0, 0.3).xz.abs();
                if t > best.0 {
                    best = (t, x, z);
                }
            }
        }
        assert!((best.0 - 0.25).abs() < 0.003, "{best:?}");
        assert!(
            (best.1 - 0.87).abs() < 0.02 && (best.2 - 0.50).abs() < 0.02,
            "{best:?}"
        );
        // On the axis it is the surface pressure below: sigma_z = -p0 at the
        // surface's middle, sigma_x too.
        let s = hertz_line(0.0, 1e-9, 1.0, 0.3);
        assert!(
            (s.zz + 1.0).abs() < 1e-8 && (s.xx + 1.0).abs() < 1e-8,
            "{s:?}"
        );
        assert!(hertz_line(0.0, 0.5, 1.0, 0.3).xz.abs() < 1e-15);
    }
}
