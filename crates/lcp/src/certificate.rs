//! The certificate of a solution, as data: its residuals relative to the
//! scale of the terms each is made of, and the tolerance they are judged
//! against. A solution is certified when
//!
//! ```text
//!     max(-min_z, -min_w, -min_u, complementarity, equality) <= tolerance
//! ```
//!
//! and every entry of the solution is finite. How each residual is computed
//! from the ORIGINAL data of a problem is the `certify` module's business;
//! this module depends on nothing else of the crate, so that every other
//! module (the errors among them) may name a certificate.

use std::fmt;

/// Relative residuals of a solution, computed from the original data.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Certificate {
    /// Smallest complementary unknown `z_i`, over `‖z‖∞` (negative = infeasible).
    pub min_z: f64,
    /// Smallest complementary slack `w_i`, over the scale of `w`'s terms (negative = infeasible).
    pub min_w: f64,
    /// Smallest non-negative extra unknown `u_j`, over `‖u‖∞` (0 when there is none).
    pub min_u: f64,
    /// Largest `|z_i w_i|`, over `z_scale * w_scale`.
    pub complementarity: f64,
    /// Largest equality-row residual, over the scale of its terms (0 when there is no equality row).
    pub equality: f64,
    /// The scale of `z` used above: `‖z‖∞`, floored by the `z` that alone
    /// would move a `w` by `w_scale` (see the `certify` module).
    pub z_scale: f64,
    /// The scale of `w` used above: the largest `(|M| |z| + |B| |u| + |q|)_i`.
    pub w_scale: f64,
    /// The tolerance the certificate is judged against.
    pub tolerance: f64,
    /// Whether every entry of z, u and w is finite (a NaN or an overflow
    /// never certifies, whatever the ratios above say).
    pub finite: bool,
}

impl Certificate {
    /// The worst relative residual: the largest of `-min_z`, `-min_w`,
    /// `-min_u`, `complementarity`, `equality` (and 0).
    pub fn worst(&self) -> f64 {
        let parts = [
            -self.min_z,
            -self.min_w,
            -self.min_u,
            self.complementarity,
            self.equality,
            self.z_scale,
            self.w_scale,
        ];
        // A non-finite solution, residual or scale never certifies: f64::max
        // would silently drop a NaN.
        if !self.finite || parts.iter().any(|v| !v.is_finite()) {
            return f64::INFINITY;
        }
        parts[..5].iter().copied().fold(0.0, f64::max)
    }

    /// Whether every residual is within the tolerance.
    pub fn holds(&self) -> bool {
        self.worst() <= self.tolerance
    }
}

impl fmt::Display for Certificate {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "min_z {:.2e}, min_w {:.2e}, min_u {:.2e}, complementarity {:.2e}, equality {:.2e}",
            self.min_z, self.min_w, self.min_u, self.complementarity, self.equality
        )
    }
}
