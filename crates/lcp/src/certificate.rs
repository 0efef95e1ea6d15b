//! The certificate of a solution: its residuals, recomputed from the ORIGINAL
//! data (never from the tableau), each relative to the scale of the terms it
//! is made of.
//!
//! For the mixed form `w = M z + B u + q`, `0 = C z + D u + r`:
//!
//! ```text
//!     z_scale  = ‖z‖∞
//!     w_scale  = max_i ( |M| |z| + |B| |u| + |q| )_i      (size of the terms summing to w)
//!     eq_scale = max_i ( |C| |z| + |D| |u| + |r| )_i
//!     min_z = min_i z_i / z_scale          min_w = min_i w_i / w_scale
//!     complementarity = max_i |z_i w_i| / (z_scale w_scale)
//!     equality = ‖C z + D u + r‖∞ / eq_scale
//! ```
//!
//! A solution is certified when `-min_z`, `-min_w`, `-min_u`,
//! `complementarity` and `equality` are all at most the tolerance.

use std::fmt;

use faer::{Col, ColRef, MatRef};

use crate::linalg::{abs_matvec, matvec, norm_inf};

/// The data of a mixed form `w = M z + B u + q`, `0 = C z + D u + r`, as
/// the certificate reads it.
#[derive(Debug, Clone, Copy)]
pub(crate) struct MixedData<'a> {
    pub m: MatRef<'a, f64>,
    pub b: MatRef<'a, f64>,
    pub q: ColRef<'a, f64>,
    pub c: MatRef<'a, f64>,
    pub d: MatRef<'a, f64>,
    pub r: ColRef<'a, f64>,
}

/// The residual vectors a certificate is made of: `w` and the magnitude
/// of its terms, the equality rows' residual and the magnitude of theirs.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Residuals<'a> {
    pub z: ColRef<'a, f64>,
    pub u: ColRef<'a, f64>,
    pub nonneg_u: &'a [bool],
    pub w: ColRef<'a, f64>,
    pub w_terms: ColRef<'a, f64>,
    pub equality: ColRef<'a, f64>,
    pub equality_terms: ColRef<'a, f64>,
}

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
    /// The scale of `z` used above, `‖z‖∞`.
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

    /// Certificate of `(z, u)` for the mixed form `data`; also returns
    /// `w = M z + B u + q`.
    pub(crate) fn mixed(
        data: &MixedData<'_>,
        nonneg_u: &[bool],
        z: ColRef<'_, f64>,
        u: ColRef<'_, f64>,
        tolerance: f64,
    ) -> (Self, Col<f64>) {
        let MixedData { m, b, q, c, d, r } = *data;
        let n = z.nrows();
        let mut w = matvec(m, z);
        let mut w_terms = abs_matvec(m, z);
        if u.nrows() > 0 {
            w += matvec(b, u);
            w_terms += abs_matvec(b, u);
        }
        for i in 0..n {
            w[i] += q[i];
            w_terms[i] += q[i].abs();
        }
        let (e, e_terms) = if c.nrows() > 0 {
            let mut e = matvec(c, z);
            let mut e_terms = abs_matvec(c, z);
            if u.nrows() > 0 {
                e += matvec(d, u);
                e_terms += abs_matvec(d, u);
            }
            for i in 0..c.nrows() {
                e[i] += r[i];
                e_terms[i] += r[i].abs();
            }
            (e, e_terms)
        } else {
            (Col::zeros(0), Col::zeros(0))
        };
        let cert = Self::from_residuals(
            &Residuals {
                z,
                u,
                nonneg_u,
                w: w.as_ref(),
                w_terms: w_terms.as_ref(),
                equality: e.as_ref(),
                equality_terms: e_terms.as_ref(),
            },
            tolerance,
        );
        (cert, w)
    }

    /// The certificate of residuals computed elsewhere (the mixed form's
    /// above, or a matrix-free problem's from its operator).
    pub(crate) fn from_residuals(res: &Residuals<'_>, tolerance: f64) -> Self {
        let Residuals {
            z,
            u,
            nonneg_u,
            w,
            w_terms,
            equality,
            equality_terms,
        } = *res;
        let n = z.nrows();
        let z_scale = norm_inf(z);
        let w_scale = norm_inf(w_terms);
        let rel = |v: f64, s: f64| if s > 0.0 { v / s } else { 0.0 };
        let min_z = rel(
            z.iter()
                .cloned()
                .fold(f64::INFINITY, f64::min)
                .min(f64::MAX),
            z_scale,
        );
        let min_w = rel(
            w.iter()
                .cloned()
                .fold(f64::INFINITY, f64::min)
                .min(f64::MAX),
            w_scale,
        );
        let comp = (0..n).fold(0.0f64, |a, i| a.max((z[i] * w[i]).abs()));
        let complementarity = rel(comp, z_scale * w_scale);
        let u_scale = norm_inf(u);
        let min_u = (0..u.nrows())
            .filter(|&j| nonneg_u[j])
            .fold(0.0f64, |a, j| a.min(rel(u[j], u_scale)));
        let equality = rel(norm_inf(equality), norm_inf(equality_terms));
        Self {
            min_z: if n == 0 { 0.0 } else { min_z },
            min_w: if n == 0 { 0.0 } else { min_w },
            min_u,
            complementarity,
            equality,
            z_scale,
            w_scale,
            tolerance,
            finite: z
                .iter()
                .chain(u.iter())
                .chain(w.iter())
                .all(|v| v.is_finite()),
        }
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
