//! The certificate of an answer: its residuals, recomputed from the
//! ORIGINAL data (never from a tableau or an iterate), each relative to the
//! scale of the terms it is made of ([`Certificate`] holds them).
//!
//! For the mixed form `w = M z + B u + q`, `0 = C z + D u + r`:
//!
//! ```text
//!     w_scale  = max_i ( |M| |z| + |B| |u| + |q| )_i      (size of the terms summing to w)
//!     z_floor  = w_scale / max_ij |M_ij|                  (the z that alone moves a w by w_scale)
//!     z_scale  = max( ‖z‖∞, z_floor )
//!     eq_scale = max( max_i ( |C| |z| + |D| |u| + |r| )_i,  ‖C‖∞ z_floor )
//!     min_z = min_i z_i / z_scale          min_w = min_i w_i / w_scale
//!     complementarity = max_i |z_i w_i| / (z_scale w_scale)
//!     equality = ‖C z + D u + r‖∞ / eq_scale
//! ```
//!
//! A bordered problem is the mixed form with `B -> -B`, `C = B^T`, `D = 0`,
//! `r = -b`; a problem whose `M` is an operator computes the same residuals
//! from products of the original operator (`M z` and `|M| |z|`). A linear
//! system `M X = R` has only equality rows: its residual is the worst
//! column's `‖R_c - M X_c‖∞ / ‖|M| |X_c| + |R_c|‖∞`. A solution
//! is certified when `-min_z`, `-min_w`, `-min_u`, `complementarity` and
//! `equality` are all at most the tolerance.
//!
//! The floor `z_floor` makes the scale of `z` the problem's own when every
//! `z_i` is at rounding level: a contact whose bodies separate has `z = 0`,
//! and a pivoting method returns it as the difference of two pivots'
//! values, `1e-11` where the natural forces are `1e4`. Judged against
//! `‖z‖∞` alone, that rounding would be a relative residual of 1. A problem
//! given by its products, whose largest entry is not at hand, keeps
//! `z_scale = ‖z‖∞`.

use faer::dyn_stack::{PodBuffer, PodStack};
use faer::{Col, ColRef, Mat, MatRef};

use crate::certificate::Certificate;
use crate::linalg::{self, abs_matvec, matvec, norm_inf};
use crate::linear::{LinearSystem, Matrix};
use crate::operator::OperatorLcp;
use crate::problem::{BorderedLcpRef, Bound, MixedBorder, MixedLcp, MixedRef};

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
    /// `max_ij |M_ij|` (0 where it is not at hand: no floor on `z_scale`).
    pub m_largest: f64,
    /// `‖C‖∞`, the equality rows' largest absolute row sum.
    pub c_norm: f64,
}

impl MixedRef<'_> {
    /// The certificate of `(z, u)` and `w = M z + B u + q`.
    pub(crate) fn certify(
        &self,
        z: ColRef<'_, f64>,
        u: ColRef<'_, f64>,
        tolerance: f64,
    ) -> (Certificate, Col<f64>) {
        let MixedRef {
            m,
            b,
            q,
            c,
            d,
            r,
            bounds,
        } = *self;
        let nonneg_u: Vec<bool> = bounds.iter().map(|b| *b == Bound::NonNegative).collect();
        let (w, w_terms) = with_terms((m, z), (b, u), q);
        let (e, e_terms) = with_terms((c, z), (d, u), r);
        let cert = from_residuals(
            &Residuals {
                z,
                u,
                nonneg_u: &nonneg_u,
                w: w.as_ref(),
                w_terms: w_terms.as_ref(),
                equality: e.as_ref(),
                equality_terms: e_terms.as_ref(),
                m_largest: m.norm_max(),
                c_norm: row_sums_max(c),
            },
            tolerance,
        );
        (cert, w)
    }
}

/// `‖A‖∞`: the largest absolute row sum (0 for no rows).
fn row_sums_max(a: MatRef<'_, f64>) -> f64 {
    (0..a.nrows()).fold(0.0f64, |m, i| {
        m.max(a.row(i).iter().map(|v| v.abs()).sum::<f64>())
    })
}

/// `A x + E y + c` and the magnitude of its terms, `|A| |x| + |E| |y| + |c|`
/// (no `E y` when `y` is empty): `w` of the mixed form, or its equality
/// rows.
fn with_terms(
    (a, x): (MatRef<'_, f64>, ColRef<'_, f64>),
    (e, y): (MatRef<'_, f64>, ColRef<'_, f64>),
    c: ColRef<'_, f64>,
) -> (Col<f64>, Col<f64>) {
    let mut sum = matvec(a, x);
    let mut terms = abs_matvec(a, x);
    if y.nrows() > 0 {
        sum += matvec(e, y);
        terms += abs_matvec(e, y);
    }
    for i in 0..c.nrows() {
        sum[i] += c[i];
        terms[i] += c[i].abs();
    }
    (sum, terms)
}

/// The public `certify` of each problem type, through its mixed form
/// (`$mixed`, from the problem `$p`).
macro_rules! certify_by_mixed_form {
    ($($(#[doc = $doc:literal])+ $ty:ty, $u:ident => |$p:ident| $mixed:expr;)+) => {$(
        impl $ty {
            $(#[doc = $doc])+
            pub fn certify(
                &self,
                z: ColRef<'_, f64>,
                $u: ColRef<'_, f64>,
                tolerance: f64,
            ) -> (Certificate, Col<f64>) {
                let $p = self;
                $mixed.certify(z, $u, tolerance)
            }
        }
    )+};
}

certify_by_mixed_form! {
    /// The certificate of a candidate `(z, λ)` against this problem's data,
    /// with `w = M z - B λ + q`.
    BorderedLcpRef<'_>, lambda => |p| MixedBorder::of(p).view(p);
    /// The certificate of a candidate `(z, u)` against this problem's data,
    /// with `w = M z + B u + q`.
    MixedLcp, u => |p| p.view();
}

impl OperatorLcp<'_> {
    /// The certificate of `(z, λ)` from products of the original operator:
    /// `w = M z - B λ + q` and `|M| |z| + |B| |λ| + |q|`, `B^T z - b` and
    /// `|B|^T |z| + |b|`; also returns `w` and the number of products it
    /// took (one where `M`'s entries are non-negative and `z >= 0`).
    pub(crate) fn certify(
        &self,
        z: &Col<f64>,
        lambda: &Col<f64>,
        tolerance: f64,
    ) -> (Certificate, Col<f64>, usize) {
        let n = z.nrows();
        // Two vectors of n, computed in place: at 10^6 points each is 8 MB.
        let z_slice = z
            .try_as_col_major()
            .expect("an owned column is contiguous")
            .as_slice();
        let mut w = Col::<f64>::zeros(n);
        let mut w_terms = Col::<f64>::zeros(n);
        let w_out = w.try_as_col_major_mut().expect("contiguous").as_slice_mut();
        let operator = self.m.operator;
        let mut scratch = PodBuffer::new(operator.apply_scratch());
        let stack = PodStack::new(&mut scratch);
        operator.apply(z_slice, w_out, stack);
        let terms_out = w_terms
            .try_as_col_major_mut()
            .expect("contiguous")
            .as_slice_mut();
        let mut products = 2;
        if z_slice.iter().all(|&v| v >= 0.0) {
            if operator.entries_nonnegative() {
                terms_out.copy_from_slice(w_out);
                products = 1;
            } else {
                operator.apply_abs(z_slice, terms_out, stack);
            }
        } else {
            let z_abs: Vec<f64> = z_slice.iter().map(|v| v.abs()).collect();
            operator.apply_abs(&z_abs, terms_out, stack);
        }
        // w = M z - B λ + q and its terms |M| |z| + |B| |λ| + |q|.
        linalg::sub_matvec(w.as_mut(), self.border, lambda.as_ref());
        linalg::add_abs_matvec(w_terms.as_mut(), self.border, lambda.as_ref());
        for i in 0..n {
            w[i] += self.q[i];
            w_terms[i] += self.q[i].abs();
        }
        let equality = linalg::matvec(self.border.transpose(), z.as_ref()) - self.resultant;
        let mut equality_terms = self.resultant.map(|v| v.abs());
        linalg::add_abs_matvec(equality_terms.as_mut(), self.border.transpose(), z.as_ref());
        let nonneg = vec![false; lambda.nrows()];
        let certificate = from_residuals(
            &Residuals {
                z: z.as_ref(),
                u: lambda.as_ref(),
                nonneg_u: &nonneg,
                w: w.as_ref(),
                w_terms: w_terms.as_ref(),
                equality: equality.as_ref(),
                equality_terms: equality_terms.as_ref(),
                m_largest: 0.0,
                c_norm: 0.0,
            },
            tolerance,
        );
        (certificate, w, products)
    }
}

impl LinearSystem<'_> {
    /// The certificate of `X`: every column's residual `R_c - M X_c`
    /// relative to its terms `|M| |X_c| + |R_c|`, from products of the
    /// original `M` (dense, or by its products), the worst as the
    /// certificate's equality residual (no complementarity: its other
    /// residuals are 0).
    pub(crate) fn certify(&self, x: MatRef<'_, f64>, tolerance: f64) -> Certificate {
        let (products, terms) = self.products(x);
        let (mut worst, mut finite) = (0.0f64, true);
        for c in 0..self.columns() {
            let (r, product, terms) = (self.rhs.col(c), products.col(c), terms.col(c));
            let (mut residual, mut scale) = (0.0f64, 0.0f64);
            for i in 0..self.size() {
                residual = residual.max((r[i] - product[i]).abs());
                scale = scale.max(terms[i] + r[i].abs());
            }
            // A NaN is left out by max: the finite flag keeps it.
            finite &= x
                .col(c)
                .iter()
                .chain(product.iter())
                .chain(terms.iter())
                .all(|v| v.is_finite());
            worst = worst.max(if scale > 0.0 { residual / scale } else { 0.0 });
        }
        Certificate {
            min_z: 0.0,
            min_w: 0.0,
            min_u: 0.0,
            complementarity: 0.0,
            equality: worst,
            z_scale: 0.0,
            w_scale: 0.0,
            tolerance,
            finite,
        }
    }

    /// `M X` and `|M| |X|`, column by column. A dense `M` takes them as
    /// two matrix products (each reads `M` once for all the columns, where
    /// products column by column read it once a column), `|M|` read from
    /// `M` itself where its entries are non-negative, else from a copy of
    /// their magnitudes; an operator by two products a column.
    fn products(&self, x: MatRef<'_, f64>) -> (Mat<f64>, Mat<f64>) {
        let (n, columns) = (self.size(), self.columns());
        let magnitude = Mat::from_fn(n, columns, |i, c| x[(i, c)].abs());
        if let Matrix::Dense(m) = self.matrix {
            let product = linalg::matmul_seq(m, x);
            let nonnegative = (0..n).all(|j| m.col(j).iter().all(|v| *v >= 0.0));
            let terms = if nonnegative {
                linalg::matmul_seq(m, magnitude.as_ref())
            } else {
                let abs = Mat::from_fn(n, n, |i, j| m[(i, j)].abs());
                linalg::matmul_seq(abs.as_ref(), magnitude.as_ref())
            };
            return (product, terms);
        }
        let operator = self.matrix.operator();
        let (mut product, mut terms) = (Mat::zeros(n, columns), Mat::zeros(n, columns));
        let (mut x_c, mut magnitude_c) = (vec![0.0; n], vec![0.0; n]);
        let (mut product_c, mut terms_c) = (vec![0.0; n], vec![0.0; n]);
        let mut scratch = PodBuffer::new(operator.apply_scratch());
        let stack = PodStack::new(&mut scratch);
        for c in 0..columns {
            for i in 0..n {
                (x_c[i], magnitude_c[i]) = (x[(i, c)], magnitude[(i, c)]);
            }
            operator.apply(&x_c, &mut product_c, stack);
            operator.apply_abs(&magnitude_c, &mut terms_c, stack);
            for i in 0..n {
                (product[(i, c)], terms[(i, c)]) = (product_c[i], terms_c[i]);
            }
        }
        (product, terms)
    }
}

/// The certificate of residuals computed elsewhere (the mixed form's
/// above, or a matrix-free problem's from its operator).
pub(crate) fn from_residuals(res: &Residuals<'_>, tolerance: f64) -> Certificate {
    let Residuals {
        z,
        u,
        nonneg_u,
        w,
        w_terms,
        equality,
        equality_terms,
        m_largest,
        c_norm,
    } = *res;
    let n = z.nrows();
    let w_scale = norm_inf(w_terms);
    let z_floor = if m_largest > 0.0 && m_largest.is_finite() {
        w_scale / m_largest
    } else {
        0.0
    };
    let z_scale = norm_inf(z).max(z_floor);
    let rel = |v: f64, s: f64| if s > 0.0 { v / s } else { 0.0 };
    // The least entry relative to its scale (an infinite least kept finite).
    let least = |v: ColRef<'_, f64>, s: f64| {
        rel(
            v.iter()
                .cloned()
                .fold(f64::INFINITY, f64::min)
                .min(f64::MAX),
            s,
        )
    };
    let (min_z, min_w) = (least(z, z_scale), least(w, w_scale));
    let comp = (0..n).fold(0.0f64, |a, i| a.max((z[i] * w[i]).abs()));
    let complementarity = rel(comp, z_scale * w_scale);
    let u_scale = norm_inf(u);
    let min_u = (0..u.nrows())
        .filter(|&j| nonneg_u[j])
        .fold(0.0f64, |a, j| a.min(rel(u[j], u_scale)));
    let eq_scale = norm_inf(equality_terms).max(c_norm * z_floor);
    let equality = rel(norm_inf(equality), eq_scale);
    Certificate {
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

#[cfg(test)]
mod tests {
    use faer::{Col, Mat, col, mat};

    use crate::problem::{MixedLcp, MixedLcpParts};

    /// Two bodies that separate (`q > 0`, answer `z = 0`) with a lever row
    /// `sum x_i z_i = 0`, as a free tilt gives.
    fn separated() -> MixedLcp {
        MixedLcp::new(MixedLcpParts {
            m: mat![[3e-10, 1e-10], [1e-10, 3e-10]],
            b: Mat::zeros(2, 0),
            q: col![1e-3, 2e-3],
            c: mat![[-1.0, 1.0]],
            d: Mat::zeros(1, 0),
            r: Col::zeros(1),
            bounds: vec![],
        })
        .unwrap()
    }

    #[test]
    fn rounding_level_forces_are_judged_on_the_natural_force_scale() {
        let lcp = separated();
        let u = Col::<f64>::zeros(0);
        // z = 0 returned as the difference of two pivots' values near the
        // natural force scale w_scale / max|M| ~ 3e6 (one rounding unit of 1e5).
        let (c, _) = lcp.certify(col![-1.5e-11, 0.0].as_ref(), u.as_ref(), 1e-12);
        assert!(c.holds(), "{c}");
        assert!(c.z_scale >= 1e-3 / 3e-10 * (1.0 - 1e-12), "{}", c.z_scale);
        // A force that is wrong on that scale still fails: negative, and
        // out of balance on the lever row.
        let (c, _) = lcp.certify(col![-1.0, 0.0].as_ref(), u.as_ref(), 1e-12);
        assert!(!c.holds(), "{c}");
        assert!(c.min_z < -1e-7 && c.equality > 1e-8, "{c}");
    }
}
