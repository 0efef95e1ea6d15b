//! The constrained conjugate gradient of Polonsky & Keer (1999),
//! generalized to a border of `k` rows: an iterative method that needs only
//! products `M x`, for the bordered LCP
//!
//! ```text
//!     w = M z - B λ + q,   B^T z = b,   z >= 0, w >= 0, z^T w = 0
//! ```
//!
//! with `M` symmetric positive definite (the minimization of
//! `1/2 z^T M z + q^T z` over `z >= 0`, `B^T z = b`). An iteration, with
//! `J = {i : z_i > 0}` and `g = M z + q`:
//!
//! 1. `λ` is the least-squares fit of `g_J` by `B_J` (`k x k` normal
//!    equations); `w = g - B λ` is then orthogonal to `B_J`'s columns;
//! 2. the direction `t_J = w_J + δ (G / G_old) t_J` (`G = ‖w_J‖²`, `δ = 0`
//!    after the contact set grew, else 1), `t = 0` off `J`;
//! 3. the step `τ = (w_J · t_J) / ((M t)_J · t_J)`, `z_J -= τ t_J`, then
//!    `z = max(z, 0)`; points out of contact that interfere (`z_i = 0`,
//!    `w_i < 0`) enter with `z_i = -τ w_i`;
//! 4. the rows `B^T z = b` restored: for one row by scaling `z` (Polonsky
//!    & Keer's load balance), for several by `z_i <- z_i exp(B_i ν)`, the
//!    nearest point on the rows that keeps the contact set (no clipping),
//!    or where the contact set cannot carry the rows by adding `B_J ν` and
//!    clipping, repeated.
//!
//! It stops when the residuals the certificate measures (smallest `w`,
//! largest `|z_i w_i|`, the rows' residual, each relative to its terms'
//! scale) are below [`ITERATIVE_STOP`](crate::tolerance::ITERATIVE_STOP)
//! times the certificate's tolerance; the strategy then certifies the
//! answer from the original operator and data. With `k = 0` it is the
//! method under displacement control (the approach inside `q`).

use faer::linalg::solvers::Solve;
use faer::{Col, ColMut, ColRef, Mat, MatRef, Side};

use crate::LcpError;
use crate::linalg;
use crate::methods::{Answer, Attempted, Failure, LinearAnswer, LinearAttempted, NotApplicable};
use crate::operator::{Operator, OperatorLcp};
use crate::options::Options;
use crate::problem::{Bordered, Problem};
use crate::statistics::{Breakdown, Work};
use crate::tolerance::{
    ARMIJO, EQUALITY_CORRECTIONS, ITERATIVE_STOP, RESTORE_STEPS, RIDGE, ROUNDING_FLOOR,
    ROWS_RESTORED, ROWS_STALLED, STALL_WINDOW, STALLED_STOP,
};

/// A bordered LCP as the method reads it: `M` by its products (a dense
/// problem's `M` as the operator of its products).
type Form<'a> = OperatorLcp<'a>;

/// The method applies to a dense problem with a border (or none) and a
/// symmetric `M` with a positive diagonal.
pub(crate) fn applies<'a>(problem: &'a Problem<'a>) -> Result<Form<'a>, NotApplicable> {
    let Some(border) = problem.border else {
        return Err(NotApplicable::new(
            "a mixed form with general equality rows; write it as a bordered LCP",
        ));
    };
    if !problem.symmetric() || !problem.positive_diagonal() {
        return Err(NotApplicable::new(
            "M must be symmetric with a positive diagonal (positive definite); use Lemke's method",
        ));
    }
    Ok(Bordered {
        m: &problem.mixed.m,
        q: problem.mixed.q,
        border: border.columns,
        resultant: border.resultant,
    })
}

/// The method's state: the iterate and what it has computed of it (three
/// vectors of n: the memory of a large solve).
struct State {
    z: Vec<f64>,
    /// `w = M z + q - B λ` (`g = M z + q` is not kept: `w + B λ`); during
    /// a [`step`], once its last read is done, the product `M t` (the next
    /// [`residual`] computes `w` again).
    w: Vec<f64>,
    lambda: Col<f64>,
    /// The conjugate direction.
    t: Vec<f64>,
    /// `‖w_J‖²` of the previous iteration.
    g_old: f64,
    /// Whether the contact set grew in the last step (restart the direction).
    restart: bool,
}

/// Solves `form` from `options.initial_z` (clipped to `z >= 0`) or from a
/// start of its own.
pub(crate) fn attempt(form: &Form<'_>, options: &Options) -> Attempted {
    let n = form.q.nrows();
    let mut work = Work::default();
    let z = match start(form, options) {
        Ok(Some(z)) => z,
        Ok(None) => return Ok(answer(vec![0.0; n], Col::zeros(form.border.ncols()), work)),
        Err(breakdown) => return Err(Failure::new(breakdown, work)),
    };
    let mut state = State {
        w: vec![0.0; n],
        lambda: Col::zeros(form.border.ncols()),
        t: vec![0.0; n],
        g_old: 0.0,
        restart: true,
        z,
    };
    let cap = options.iteration_cap();
    let mut progress = Progress::new(options.tolerances.certificate, n);
    loop {
        crate::cancel::check().map_err(|c| Failure::new(c.into(), work))?;
        if let Err(b) = residual(form, &mut state) {
            return Err(Failure::new(b, work));
        }
        let c = converged(form, &state);
        if progress.done(work.iterations, c) || work.iterations >= cap {
            // The answer copies z: free the other vectors first.
            let State {
                z, lambda, w, t, ..
            } = state;
            drop((w, t));
            return Ok(answer(z, lambda, work));
        }
        work.iterations += 1;
        if let Err(b) = step(form, &mut state) {
            return Err(Failure::new(b, work));
        }
        if let Err(b) = restore_rows(form, &mut state.z) {
            return Err(Failure::new(b, work));
        }
    }
}

fn answer(z: Vec<f64>, lambda: Col<f64>, work: Work) -> Answer {
    let basic = z.iter().map(|&v| v > 0.0).collect();
    Answer {
        z: Col::from_fn(z.len(), |i| z[i]),
        u: lambda,
        basic,
        work,
    }
}

/// The start: `options.initial_z`, or `B ν` with `B^T B ν = b` (a load
/// spread over every point), restored to the rows; with no border, the
/// interference `max(-q, 0)` over the diagonal. `None`: `z = 0` solves.
fn start(form: &Form<'_>, options: &Options) -> Result<Option<Vec<f64>>, Breakdown> {
    let n = form.q.nrows();
    let k = form.border.ncols();
    let mut z: Vec<f64> = match &options.initial_z {
        Some(z0) if z0.len() != n => {
            return Err(Breakdown::Error(Box::new(LcpError::DimensionMismatch {
                field: "initial_z",
                expected: n,
                found: z0.len(),
                unit: "entries",
            })));
        }
        Some(z0) => z0.iter().map(|&v| v.max(0.0)).collect(),
        None if k == 0 => {
            let (j, worst) = (0..n)
                .map(|i| (i, form.q[i]))
                .fold((0, f64::INFINITY), |a, b| if b.1 < a.1 { b } else { a });
            if worst >= 0.0 {
                return Ok(None);
            }
            let mut e = vec![0.0; n];
            let mut column = vec![0.0; n];
            e[j] = 1.0;
            form.m.apply(&e, &mut column);
            let d = column[j];
            if !(d > 0.0 && d.is_finite()) {
                return Err(Breakdown::NotPositiveDefinite);
            }
            (0..n).map(|i| (-form.q[i]).max(0.0) / d).collect()
        }
        None => {
            let nu = fit(form.border, |_| true, form.resultant).ok_or(Breakdown::SingularBorder)?;
            let spread = linalg::matvec(form.border, nu.as_ref());
            spread.iter().map(|&v| v.max(0.0)).collect()
        }
    };
    if k > 0 && z.iter().all(|&v| v == 0.0) {
        z.iter_mut().for_each(|v| *v = 1.0);
    }
    restore_rows(form, &mut z)?;
    Ok(Some(z))
}

/// `g = M z + q`, `λ` fitted on the contact set, `w = g - B λ` (`g` held
/// in `w` until `λ` is known).
fn residual(form: &Form<'_>, s: &mut State) -> Result<(), Breakdown> {
    form.m.apply(&s.z, &mut s.w);
    for (g, q) in s.w.iter_mut().zip(form.q.iter()) {
        *g += q;
    }
    let z = &s.z;
    let active = |i: usize| z[i] > 0.0;
    let rhs = masked_transpose_product(form.border, active, &s.w);
    // Fewer contact points than independent rows (an early iterate): the
    // least-norm fit of a slightly regularized system.
    s.lambda = fit(form.border, active, rhs.as_ref())
        .or_else(|| fit_regularized(form.border, active, rhs.as_ref()))
        .ok_or(Breakdown::SingularBorder)?;
    linalg::sub_matvec(
        ColMut::from_slice_mut(&mut s.w),
        form.border,
        s.lambda.as_ref(),
    );
    if s.w.iter().any(|v| !v.is_finite()) {
        return Err(Breakdown::NonFinite);
    }
    Ok(())
}

/// The worst of the residuals the certificate measures, from the state
/// (`M |z|` read as `M z = w + B λ - q`: exact for an operator with
/// non-negative entries, a stricter scale otherwise).
fn converged(form: &Form<'_>, s: &State) -> f64 {
    let n = s.z.len();
    let k = form.border.ncols();
    let mut w_scale = 0.0f64;
    for i in 0..n {
        let (mut shift, mut shift_terms) = (0.0, 0.0);
        for j in 0..k {
            let b = form.border[(i, j)] * s.lambda[j];
            shift += b;
            shift_terms += b.abs();
        }
        let q = form.q[i];
        let product = s.w[i] + shift - q;
        w_scale = w_scale.max(product.abs() + q.abs() + shift_terms);
    }
    let z_scale = s.z.iter().fold(0.0f64, |a, &v| a.max(v));
    let rel = |v: f64, scale: f64| if scale > 0.0 { v / scale } else { 0.0 };
    let min_w = s.w.iter().fold(0.0f64, |a, &v| a.min(v));
    let comp = (0..n).fold(0.0f64, |a, i| a.max((s.z[i] * s.w[i]).abs()));
    let mut worst = rel(-min_w, w_scale).max(rel(comp, z_scale * w_scale));
    for j in 0..k {
        let col = form.border.col(j);
        let (mut sum, mut terms) = (-form.resultant[j], form.resultant[j].abs());
        for i in 0..n {
            sum += col[i] * s.z[i];
            terms += (col[i] * s.z[i]).abs();
        }
        worst = worst.max(rel(sum.abs(), terms));
    }
    worst
}

/// One conjugate-gradient step on the contact set (steps 2 and 3 of the
/// module documentation). `M t` is written over `w`, which is read before
/// it: on `J` for the direction and the numerator, off `J` for the points
/// that enter, which are marked by `z_i = w_i < 0` until the step length is
/// known (J = {z_i > 0} is unchanged by the marks). Three vectors of n, not
/// four.
fn step(form: &Form<'_>, s: &mut State) -> Result<(), Breakdown> {
    let n = s.z.len();
    // The contact set J = {z_i > 0}: read from z, which the loops below
    // change only at the entry they are visiting.
    let g_now = dot_on(|i| s.z[i] > 0.0, &s.w, &s.w);
    let beta = if s.restart || s.g_old == 0.0 {
        0.0
    } else {
        g_now / s.g_old
    };
    let mut num = 0.0;
    for i in 0..n {
        if s.z[i] > 0.0 {
            s.t[i] = s.w[i] + beta * s.t[i];
            num += s.w[i] * s.t[i];
        } else {
            s.t[i] = 0.0;
            if s.w[i] < 0.0 {
                // Interference out of contact: the point will enter.
                s.z[i] = s.w[i];
            }
        }
    }
    form.m.apply(&s.t, &mut s.w);
    let den = dot_on(|i| s.z[i] > 0.0, &s.w, &s.t);
    let tau = step_length(num, den)?;
    s.g_old = g_now;
    let mut entered = false;
    for i in 0..n {
        let z = s.z[i];
        if z > 0.0 {
            s.z[i] = (z - tau * s.t[i]).max(0.0);
        } else if z < 0.0 {
            // A marked point (z_i = w_i) enters with -τ w_i. With τ = 0
            // (no step on the contact set) the diagonal-free scale of the
            // overlap itself starts it.
            s.z[i] = if tau > 0.0 { -tau * z } else { -z };
            entered = true;
        }
    }
    s.restart = entered;
    Ok(())
}

/// Solves the linear system `M X = R` for an `M` given by its products:
/// the plain conjugate gradient, one right-hand side after the other (the
/// iteration of the module documentation with every index in `J`, no
/// clipping and no rows). The same checks as the constrained method's:
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
/// `r`, the direction `p` and the product `q = M p`.
struct Vectors {
    b: Vec<f64>,
    r: Vec<f64>,
    p: Vec<f64>,
    q: Vec<f64>,
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
    let Vectors { b, r, p, q } = v;
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
            operator.apply(x, q);
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
        operator.apply(p, q);
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
/// stricter scale than the certificate's `|M| |x| + |b|`, as
/// [`converged`]'s); 0 when both are 0.
fn relative(b: &[f64], r: &[f64]) -> f64 {
    let (mut worst, mut scale) = (0.0f64, 0.0f64);
    for (&b, &r) in b.iter().zip(r) {
        worst = worst.max(r.abs());
        scale = scale.max((b - r).abs() + b.abs());
    }
    if scale > 0.0 { worst / scale } else { 0.0 }
}

/// When a conjugate gradient stops: its residual `c` (relative to the
/// data's scale) at most [`ITERATIVE_STOP`] times the certificate's
/// tolerance, or stalled: at most [`STALLED_STOP`] times the tolerance,
/// below the rounding floor of sums of n terms, and not halved over the
/// last [`STALL_WINDOW`] iterations (at the rounding floor of very large
/// sums the residuals creep down for hundreds of iterations: the iterate
/// is then as good as the arithmetic allows).
struct Progress {
    target: f64,
    stalled_target: f64,
    /// `ROUNDING_FLOOR eps sqrt(n)`: only there is a stall the
    /// arithmetic's, not a slow convergence.
    floor: f64,
    /// The residual at the start of the current window.
    checkpoint: f64,
    stalled: bool,
}

impl Progress {
    fn new(tolerance: f64, n: usize) -> Self {
        Self {
            target: ITERATIVE_STOP * tolerance,
            stalled_target: STALLED_STOP * tolerance,
            floor: ROUNDING_FLOOR * f64::EPSILON * (n as f64).sqrt(),
            checkpoint: f64::INFINITY,
            stalled: false,
        }
    }

    /// Whether the iterate of `iteration` (counted from 0), of residual
    /// `c`, is done: converged, or stalled (judged every window).
    fn done(&mut self, iteration: usize, c: f64) -> bool {
        if iteration.is_multiple_of(STALL_WINDOW) {
            self.stalled = c <= self.stalled_target && c <= self.floor && c > 0.5 * self.checkpoint;
            self.checkpoint = c;
        }
        c <= self.target || self.stalled
    }

    /// Whether a done iterate's residual `c`, recomputed from a true
    /// product, is accepted: at the target, or after a stall at the
    /// stalled target.
    fn accepts(&self, c: f64) -> bool {
        c <= self.target || (self.stalled && c <= self.stalled_target)
    }

    /// Judges afresh: the iteration restarted from a true residual.
    fn restart(&mut self) {
        self.checkpoint = f64::INFINITY;
        self.stalled = false;
    }
}

/// `Σ_{i in J} a_i b_i` over the indices `J` that `on` selects (the
/// contact set, or every index), summed in order.
fn dot_on(on: impl Fn(usize) -> bool, a: &[f64], b: &[f64]) -> f64 {
    (0..a.len()).filter(|&i| on(i)).map(|i| a[i] * b[i]).sum()
}

/// The step `num / den` along a direction `p` with `den = p · M p` (on the
/// contact set): a breakdown where `den` is not positive (`M` is not
/// positive definite along `p`) or not finite, unless there is nothing to
/// step (`num = 0`).
fn step_length(num: f64, den: f64) -> Result<f64, Breakdown> {
    if !(den > 0.0) && num != 0.0 {
        return Err(if den.is_finite() {
            Breakdown::NotPositiveDefinite
        } else {
            Breakdown::NonFinite
        });
    }
    Ok(if num == 0.0 { 0.0 } else { num / den })
}

/// Restores `B^T z = b` (step 4 of the module documentation): for one row
/// by scaling, else by [`tilt_into_rows`] on the contact set, or failing
/// that (the set's cone does not hold the resultants) by
/// [`shift_into_rows`].
fn restore_rows(form: &Form<'_>, z: &mut [f64]) -> Result<(), Breakdown> {
    let k = form.border.ncols();
    if k == 0 {
        return Ok(());
    }
    if k == 1 {
        let col = form.border.col(0);
        let row = compensated_sum(z.iter().zip(col.iter()).map(|(zi, bi)| zi * bi));
        let ratio = form.resultant[0] / row;
        if ratio.is_finite() && ratio > 0.0 {
            z.iter_mut().for_each(|v| *v *= ratio);
            return Ok(());
        }
    }
    let kept = z.to_vec();
    if tilt_into_rows(form, z).is_ok() {
        return Ok(());
    }
    z.copy_from_slice(&kept);
    shift_into_rows(form, z)
}

/// Adds the least-squares correction `B_J ν` on the contact set `J` (on
/// every point when `B_J` cannot carry the rows) and clips at zero,
/// repeated: the restoration when the contact set's cone does not hold the
/// resultants (points must enter or leave).
fn shift_into_rows(form: &Form<'_>, z: &mut [f64]) -> Result<(), Breakdown> {
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
/// points' `B_i` (the contact set cannot carry the rows).
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

/// `B_J^T v` (the rows of `B` outside the active set `J` left out).
fn masked_transpose_product(
    border: MatRef<'_, f64>,
    active: impl Fn(usize) -> bool,
    v: &[f64],
) -> Col<f64> {
    Col::from_fn(border.ncols(), |j| {
        let column = border.col(j);
        compensated_sum(
            (0..v.len())
                .filter(|&i| active(i))
                .map(|i| column[i] * v[i]),
        )
    })
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
fn fit(
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

/// [`fit`] with `RIDGE` times the largest diagonal entry added to the
/// normal equations' diagonal: the least-norm fit, nearly, when `B_J` has
/// fewer rows than columns.
fn fit_regularized(
    border: MatRef<'_, f64>,
    active: impl Fn(usize) -> bool,
    rhs: ColRef<'_, f64>,
) -> Option<Col<f64>> {
    let k = border.ncols();
    let mut gram = masked_gram(border, active);
    let largest = (0..k).fold(0.0f64, |a, j| a.max(gram[(j, j)]));
    let ridge = if largest > 0.0 { RIDGE * largest } else { 1.0 };
    for j in 0..k {
        gram[(j, j)] += ridge;
    }
    let nu = gram.llt(Side::Lower).ok()?.solve(rhs.to_owned());
    let finite = nu.iter().all(|v| v.is_finite());
    finite.then_some(nu)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_step_needs_a_positive_curvature() {
        assert_eq!(step_length(2.0, 4.0), Ok(0.5));
        assert_eq!(step_length(0.0, -1.0), Ok(0.0));
        assert_eq!(step_length(1.0, 0.0), Err(Breakdown::NotPositiveDefinite));
        assert_eq!(step_length(1.0, -3.0), Err(Breakdown::NotPositiveDefinite));
        assert_eq!(step_length(1.0, f64::NAN), Err(Breakdown::NonFinite));
    }

    #[test]
    fn progress_stops_at_the_target_or_at_a_stall_on_the_rounding_floor() {
        let mut p = Progress::new(1e-12, 100);
        assert!(!p.done(0, 1e-3));
        assert!(p.done(1, 0.25e-12));
        // A million terms: a rounding floor (8 eps sqrt(n) = 1.8e-12) above
        // the stalled target (7.5e-13). Below that and not halved over a
        // window: a stall, whose residual is accepted up to the stalled
        // target.
        let mut p = Progress::new(1e-12, 1_000_000);
        assert!(!p.done(0, 6e-13));
        assert!(!p.accepts(5e-13));
        assert!(p.done(STALL_WINDOW, 5e-13));
        assert!(p.accepts(7e-13) && !p.accepts(8e-13));
        p.restart();
        assert!(!p.accepts(7e-13));
    }
}
