//! The plain conjugate gradient of a linear system `M X = R` whose `M` is
//! given by its products (symmetric positive definite), one right-hand side
//! after the other:
//!
//! ```text
//!     α = (r · r) / (p · M p),   x += α p,   r -= α M p,   p = r + ((r · r)_new / (r · r)) p
//! ```
//!
//! the residual kept by the recurrence and confirmed from a true product
//! `b - M x` before a column is accepted.

use faer::MatRef;
use faer::dyn_stack::{PodBuffer, PodStack};

use super::progress::{Progress, dot_on, step_length};
use crate::LcpError;
use crate::linalg;
use crate::methods::{Failure, LinearAnswer, LinearAttempted};
use crate::operator::{Operator, scratch};
use crate::options::Options;
use crate::statistics::{Breakdown, Work};

/// Solves the linear system `M X = R` for an `M` given by its products:
/// the plain conjugate gradient, one right-hand side after the other (the
/// constrained iteration with every index in `J`, no clipping and no rows). The same checks as the constrained method's:
/// `p · M p <= 0` breaks down ([`Breakdown::NotPositiveDefinite`]), as
/// does a value that is not finite; a column stops by [`Progress`] on its
/// residual relative to the data's scale, confirmed from a true product
/// (the recursion's residual drifts from it: where it has, the iteration
/// restarts from the true one). The iteration cap is
/// [`LcpError::IterationLimit`], never an unconverged answer.
pub(crate) fn attempt_linear(
    operator: &dyn Operator,
    rhs: MatRef<'_, f64>,
    options: &Options,
) -> LinearAttempted {
    let (n, columns) = (rhs.nrows(), rhs.ncols());
    let mut work = Work::default();
    let allocated =
        |what| linalg::try_zeros(n, what).map_err(|e| Failure::error(e.into(), Work::default()));
    let mut vectors = Vectors {
        b: allocated("the conjugate gradient's right-hand side")?,
        r: allocated("the conjugate gradient's residual")?,
        p: allocated("the conjugate gradient's direction")?,
        q: allocated("the conjugate gradient's product")?,
        scratch: scratch(operator.apply_scratch(), "the conjugate gradient's scratch")
            .map_err(|e| Failure::error(e.into(), Work::default()))?,
    };
    let mut x = linalg::try_mat(n, columns, "the solution", |_, _| 0.0)
        .map_err(|e| Failure::error(e.into(), work))?;
    for c in 0..columns {
        vectors
            .b
            .iter_mut()
            .zip(rhs.col(c).iter())
            .for_each(|(b, &v)| *b = v);
        let x_c = x
            .col_mut(c)
            .try_as_col_major_mut()
            .expect("an owned matrix's column is contiguous")
            .as_slice_mut();
        solve_column(operator, c, &mut vectors, x_c, options, &mut work)
            .map_err(|b| Failure::new(b, work))?;
    }
    Ok(LinearAnswer { x, work })
}

/// The vectors of a linear system's conjugate gradient (four of n, used
/// again for every right-hand side): the right-hand side `b`, the residual
/// `r`, the direction `p` and the product `q = M p`; and the scratch of
/// the products.
struct Vectors {
    b: Vec<f64>,
    r: Vec<f64>,
    p: Vec<f64>,
    q: Vec<f64>,
    scratch: PodBuffer,
}

/// Solves `M x = b` for the right-hand side `column` (`x` zero at the
/// start) by the conjugate gradient (see [`attempt_linear`]).
fn solve_column(
    operator: &dyn Operator,
    column: usize,
    v: &mut Vectors,
    x: &mut [f64],
    options: &Options,
    work: &mut Work,
) -> Result<(), Breakdown> {
    let Vectors {
        b,
        r,
        p,
        q,
        scratch,
    } = v;
    let n = x.len();
    let every = |_: usize| true;
    r.copy_from_slice(b);
    p.copy_from_slice(r);
    let mut rr = dot_on(every, r, r);
    let (cap, mut iterations) = (options.iteration_cap(), 0);
    let mut progress = Progress::new(options.tolerances.certificate, n);
    loop {
        crate::cancel::check()?;
        let mut c = relative(b, r);
        if progress.done(iterations, c) {
            // The true residual r = b - M x decides.
            operator.apply(x, q, PodStack::new(scratch));
            work.products += 1;
            r.iter_mut()
                .zip(b.iter().zip(q.iter()))
                .for_each(|(r, (b, product))| *r = b - product);
            if r.iter().any(|v| !v.is_finite()) {
                return Err(Breakdown::NonFinite);
            }
            c = relative(b, r);
            if progress.accepts(c) {
                return Ok(());
            }
            rr = dot_on(every, r, r);
            p.copy_from_slice(r);
            progress.restart();
        }
        if iterations >= cap {
            let error = LcpError::IterationLimit {
                size: n,
                column,
                limit: cap,
                residual: c,
            };
            return Err(Breakdown::Error(Box::new(error)));
        }
        iterations += 1;
        work.iterations += 1;
        operator.apply(p, q, PodStack::new(scratch));
        work.products += 1;
        let alpha = step_length(rr, dot_on(every, p, q))?;
        for i in 0..n {
            x[i] += alpha * p[i];
            r[i] -= alpha * q[i];
        }
        let next = dot_on(every, r, r);
        if !next.is_finite() {
            return Err(Breakdown::NonFinite);
        }
        let beta = next / rr;
        p.iter_mut()
            .zip(r.iter())
            .for_each(|(p, r)| *p = r + beta * *p);
        rr = next;
    }
}

/// The residual `r` of `M x = b` relative to its terms' scale,
/// `‖r‖∞ / max_i (|(M x)_i| + |b_i|)`, with `M x` read as `b - r` (a
/// stricter scale than the certificate's `|M| |x| + |b|`); 0 when both
/// are 0.
fn relative(b: &[f64], r: &[f64]) -> f64 {
    let (mut worst, mut scale) = (0.0f64, 0.0f64);
    for (&b, &r) in b.iter().zip(r) {
        worst = worst.max(r.abs());
        scale = scale.max((b - r).abs() + b.abs());
    }
    if scale > 0.0 { worst / scale } else { 0.0 }
}
