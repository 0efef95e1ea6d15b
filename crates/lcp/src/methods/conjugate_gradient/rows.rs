//! The border's rows `B^T z = b` of the constrained conjugate gradient:
//! restored after a step (scaling for one row, else the nearest point on
//! the rows in the Kullback-Leibler sense, `z_i <- z_i exp(B_i ν)`, or an
//! additive correction `B_J ν` clipped at zero), and the least-squares fit
//! `B_J^T B_J ν = rhs` on an active set.

use faer::linalg::solvers::Solve;
use faer::{Col, ColRef, Mat, MatRef, Side};

use super::Form;
use crate::linalg;
use crate::statistics::Breakdown;
use crate::tolerance::{ARMIJO, EQUALITY_CORRECTIONS, RESTORE_STEPS, ROWS_RESTORED, ROWS_STALLED};

/// Restores `B^T z = b` (step 4 of the iteration in the parent module's
/// documentation): on the contact set ([`restore_on_support`]), or failing
/// that (the set's cone does not hold the resultants) by
/// [`shift_into_rows`].
pub(super) fn restore_rows(form: &Form<'_>, z: &mut [f64]) -> Result<(), Breakdown> {
    if restore_on_support(form, z) {
        return Ok(());
    }
    shift_into_rows(form, z)
}

/// Restores `B^T z = b` keeping the contact set: for one row by scaling,
/// else by [`tilt_into_rows`]. False, with `z` as it was, where the contact
/// set cannot carry the rows.
pub(super) fn restore_on_support(form: &Form<'_>, z: &mut [f64]) -> bool {
    let k = form.border.ncols();
    if k == 0 {
        return true;
    }
    if k == 1 {
        let col = form.border.col(0);
        let row = compensated_sum(z.iter().zip(col.iter()).map(|(zi, bi)| zi * bi));
        let ratio = form.resultant[0] / row;
        if ratio.is_finite() && ratio > 0.0 {
            z.iter_mut().for_each(|v| *v *= ratio);
            return true;
        }
    }
    tilt_into_rows(form, z).is_ok()
}

/// Adds the least-squares correction `B_J ν` on the contact set `J` (on
/// every point when `B_J` cannot carry the rows) and clips at zero,
/// repeated: the restoration when the contact set's cone does not hold the
/// resultants (points must enter or leave).
pub(super) fn shift_into_rows(form: &Form<'_>, z: &mut [f64]) -> Result<(), Breakdown> {
    let n = z.len();
    for _ in 0..EQUALITY_CORRECTIONS {
        let mut active: Vec<bool> = z.iter().map(|&v| v > 0.0).collect();
        let z_col = ColRef::from_slice(z);
        let deficit = form.resultant - linalg::matvec(form.border.transpose(), z_col);
        let nu = match fit(form.border, |i| active[i], deficit.as_ref()) {
            Some(nu) => nu,
            None => {
                active.iter_mut().for_each(|a| *a = true);
                fit(form.border, |_| true, deficit.as_ref()).ok_or(Breakdown::SingularBorder)?
            }
        };
        let add = linalg::matvec(form.border, nu.as_ref());
        let mut clipped = false;
        for i in (0..n).filter(|&i| active[i]) {
            let v = z[i] + add[i];
            clipped |= v < 0.0;
            z[i] = v.max(0.0);
        }
        if !clipped {
            break;
        }
    }
    Ok(())
}

/// `z_i <- z_i exp(B_i ν)` with `ν` minimizing the convex
/// `φ(ν) = Σ z_i exp(B_i ν) - b^T ν`, whose gradient is `B^T z' - b`: the
/// nearest `z' >= 0` on the rows in the Kullback-Leibler sense, with the
/// support of `z` (no clipping, so a point that entered stays). Newton's
/// method with backtracking on `φ`; for one row of ones it is Polonsky &
/// Keer's scaling. Fails when `b` is not inside the cone of the supported
/// points' `B_i` (the contact set cannot carry the rows), leaving `z` as
/// it was.
fn tilt_into_rows(form: &Form<'_>, z: &mut [f64]) -> Result<(), Breakdown> {
    let (border, b) = (form.border, form.resultant);
    let (n, k) = (z.len(), border.ncols());
    let start = z.to_vec();
    let scaled = |nu: &Col<f64>| -> Option<Col<f64>> {
        let exponent = linalg::matvec(border, nu.as_ref());
        let s = Col::from_fn(n, |i| {
            if start[i] > 0.0 {
                start[i] * exponent[i].exp()
            } else {
                0.0
            }
        });
        let finite = s.iter().all(|v| v.is_finite());
        finite.then_some(s)
    };
    let phi = |s: &Col<f64>, nu: &Col<f64>| s.sum() - (b.transpose() * nu);
    let mut nu = Col::<f64>::zeros(k);
    let mut s = scaled(&nu).ok_or(Breakdown::NonFinite)?;
    let residual = |s: &Col<f64>| -> (Col<f64>, f64) {
        let gradient = linalg::matvec(border.transpose(), s.as_ref()) - b;
        let terms = linalg::abs_matvec(border.transpose(), s.as_ref()) + b.map(|v| v.abs());
        let scale = terms.iter().fold(0.0f64, |a, &v| a.max(v));
        let worst = gradient.iter().fold(0.0f64, |a, &v| a.max(v.abs()));
        (gradient, if scale > 0.0 { worst / scale } else { 0.0 })
    };
    for _ in 0..RESTORE_STEPS {
        let (gradient, worst) = residual(&s);
        if worst <= ROWS_RESTORED {
            break;
        }
        let weighted = Mat::from_fn(n, k, |i, j| s[i].sqrt() * border[(i, j)]);
        let hessian = linalg::gram(weighted.as_ref());
        let Ok(llt) = hessian.llt(Side::Lower) else {
            break;
        };
        let step = llt.solve(&gradient);
        let slope = gradient.transpose() * &step;
        let current = phi(&s, &nu);
        let mut length = 1.0;
        while length >= f64::EPSILON {
            let trial = &nu - &step * faer::Scale(length);
            if let Some(t) = scaled(&trial)
                && phi(&t, &trial) <= current - ARMIJO * length * slope
            {
                nu = trial;
                s = t;
                break;
            }
            length *= 0.5;
        }
        if length < f64::EPSILON {
            // No decrease left: at the rounding floor, or no minimizer.
            break;
        }
    }
    if residual(&s).1 > ROWS_STALLED {
        return Err(Breakdown::SingularBorder);
    }
    z.iter_mut().zip(s.iter()).for_each(|(zi, si)| *zi = *si);
    Ok(())
}

/// Neumaier's compensated sum: accurate to a few units of rounding of the
/// result whatever the number of terms. `λ` is fitted from sums of 10^5 to
/// 10^6 nearly equal `g_i`, and a plain running sum's error (n eps) shifts
/// every `w_J` by as much, which the iteration then cannot remove.
fn compensated_sum(terms: impl Iterator<Item = f64>) -> f64 {
    let (mut sum, mut carry) = (0.0f64, 0.0f64);
    for t in terms {
        let next = sum + t;
        carry += if sum.abs() >= t.abs() {
            (sum - next) + t
        } else {
            (t - next) + sum
        };
        sum = next;
    }
    sum + carry
}

/// The normal equations' matrix `B_J^T B_J` (k x k) of the rows in the
/// active set `J`, summed row by row (no masked copy of `B`: n k values
/// at a million points).
fn masked_gram(border: MatRef<'_, f64>, active: impl Fn(usize) -> bool) -> Mat<f64> {
    let k = border.ncols();
    let mut gram = Mat::<f64>::zeros(k, k);
    for i in (0..border.nrows()).filter(|&i| active(i)) {
        for a in 0..k {
            let ba = border[(i, a)];
            for b in 0..=a {
                gram[(a, b)] += ba * border[(i, b)];
            }
        }
    }
    for a in 0..k {
        for b in 0..a {
            gram[(b, a)] = gram[(a, b)];
        }
    }
    gram
}

/// Solves the normal equations `B_J^T B_J ν = rhs` (`k x k`, by faer's
/// Cholesky); `None` when `B_J` is rank deficient.
pub(super) fn fit(
    border: MatRef<'_, f64>,
    active: impl Fn(usize) -> bool,
    rhs: ColRef<'_, f64>,
) -> Option<Col<f64>> {
    let k = border.ncols();
    if k == 0 {
        return Some(Col::zeros(0));
    }
    let gram = masked_gram(border, active);
    let llt = gram.llt(Side::Lower).ok()?;
    let nu = llt.solve(rhs.to_owned());
    let finite = nu.iter().all(|v| v.is_finite());
    finite.then_some(nu)
}
