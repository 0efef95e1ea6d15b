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
//! `J = {i : z_i > 0}`, `u = M z` and `g = u + q`:
//!
//! 1. `λ` is the least-squares fit of `g_J` by `B_J` (`k x k` normal
//!    equations); `w = g - B λ` is then orthogonal to `B_J`'s columns;
//! 2. the direction `t_J = w_J + δ (G / G_old) t_J` (`G = ‖w_J‖²`, `δ = 0`
//!    after the contact set grew, else 1), `t = 0` off `J`;
//! 3. the product `r = M t` (the iteration's one product of `M`), the step
//!    `τ = (w_J · t_J) / (r_J · t_J)`, `z_J -= τ t_J`, then `z = max(z, 0)`;
//!    points out of contact that interfere (`z_i = 0`, `w_i < 0`) enter with
//!    `z_i = -τ w_i`; and `u -= τ r`, which is `M z` again
//!    (`M (z - τ t) = u - τ r`) when no point was clipped or entered;
//! 4. the rows `B^T z = b` restored: for one row by scaling `z` and `u`
//!    (Polonsky & Keer's load balance; `M (c z) = c u`), for several by
//!    `z_i <- z_i exp(B_i ν)`, the nearest point on the rows that keeps the
//!    contact set (no clipping); where the step clipped points and the
//!    contact set left cannot carry the rows, the step is cut where the
//!    first point reaches 0 (`τ_b = min z_i / t_i` over `t_i > 0`: one point
//!    leaves and `B_J^T t_J = 0` keeps the rows), and failing that the
//!    rows are restored by adding `B_J ν` and clipping, repeated. Without
//!    clipping the step keeps several rows to rounding (`B_J^T t_J = 0`),
//!    and they are left as they are.
//!
//! Preconditioned (where the problem has a preconditioner `P ≈ M^{-1}`,
//! a [`Preconditioner`](crate::Preconditioner), and
//! `Options::preconditioner` is set; after Vollebregt 2014), step 2 is
//!
//! ```text
//!     r = w_J,  p = P r,  p_J -= B_J μ  (B_J^T B_J μ = B_J^T p_J),  ρ = r · p_J,
//!     t_J = p_J + δ (ρ / ρ_old) t_J
//! ```
//!
//! (the projection keeps `B_J^T t_J = 0`, so the step keeps the rows), and
//! steps 1, 3 and 4 are the same: one application of `P` an iteration
//! besides the product.
//!
//! Where a step clipped a point or let one enter, or several rows had to be
//! restored, `u` is no longer `M z`. With one row or none, and an operator
//! whose columns are cheap ([`Operator::add_columns`](crate::Operator::add_columns):
//! the lattice kernel shifted to a point), the step's departure from the
//! step along the direction, `d = z - (c z_old - τ t)` on the points clipped
//! or let in, is added by columns, `u += M d`, where they are at most a
//! product's worth ([`Operator::columns_per_product`](crate::Operator::columns_per_product)),
//! at most [`MAX_CORRECTIONS`] times between true products. Otherwise `u`
//! is recomputed from a true product `M z` (a second product in that
//! iteration: while the contact set settles, when thousands of points
//! leave a step). So the method costs about one product per iteration, as
//! Polonsky & Keer's, where computing `g` afresh would cost two.
//!
//! Points enter by Polonsky & Keer's rule, `z_i = -τ w_i` with the step `τ`
//! of the direction on `J`. Where that overshoots and the iteration makes
//! no progress (no new smallest residual for `GUARD_WINDOW` iterations),
//! the method turns guarded: steps on `J` let no point enter, and where the
//! interference off `J` outweighs the residual on `J` (`‖β‖² > ‖w_J‖²`,
//! `β_i = min(w_i, 0)` off `J`) a proportioning step enters the points
//! along `β` by the exact line search `τ = β · β / β · M β` (MPRGP, Dostál
//! & Schöberl 2005).
//!
//! It stops when the residuals the certificate measures (smallest `w`,
//! largest `|z_i w_i|`, the rows' residual, each relative to its terms'
//! scale) are below [`ITERATIVE_STOP`](crate::tolerance::ITERATIVE_STOP)
//! times the certificate's tolerance. Judged from a `u` kept by the
//! recurrence, they are confirmed from a true product (the recurrence
//! drifts from `M z` by rounding): accepted there up to
//! [`STALLED_STOP`](crate::tolerance::STALLED_STOP) times the tolerance
//! (what is left above the recurrence's residual is that drift, or the
//! rounding floor of sums of n terms), else the iteration goes on from the
//! true product. The strategy then certifies the answer from the original
//! operator and data. At the iteration cap
//! ([`Options::max_pivots`](crate::Options::max_pivots)) short of its
//! stopping rule it returns no answer
//! ([`LcpError::ConjugateGradientLimit`]). With `k = 0` it is the method under displacement
//! control (the approach inside `q`).
//!
//! Every pass over the vectors runs on the current rayon pool's threads,
//! with sums in a fixed order (the `passes` module): the iterates are the
//! same to the bit on one thread or many.

mod chunk;
mod iteration;
mod linear;
mod passes;
mod progress;
mod rows;

use faer::dyn_stack::{PodBuffer, PodStack};
use faer::linalg::solvers::Solve;
use faer::{Col, Side};

use iteration::{Data, FitSums, Measures, Update, UpdateSums};
use progress::{Progress, step_length};
use rows::{fit, restore_on_support, restore_rows, shift_into_rows};

pub(crate) use linear::attempt_linear;

use crate::LcpError;
use crate::linalg;
use crate::methods::{Answer, Attempted, Failure, NotApplicable};
use crate::operator::{MatrixFree, OperatorLcp, scratch};
use crate::options::Options;
use crate::problem::{Bordered, Problem};
use crate::statistics::{Breakdown, Work};
use crate::tolerance::ROWS_RESTORED;

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
        m: MatrixFree {
            operator: &problem.mixed.m,
            preconditioner: None,
        },
        q: problem.mixed.q,
        border: border.columns,
        resultant: border.resultant,
    })
}

/// The method's state: the iterate and what it has computed of it (four
/// vectors of n, five preconditioned, one more with several rows once a
/// step clipped: the memory of a large solve), and the scratch its
/// operator and preconditioner work in.
struct State {
    z: Vec<f64>,
    /// `u = M z`, from a true product or kept by the recurrence.
    u: Vec<f64>,
    /// The conjugate direction.
    t: Vec<f64>,
    /// `r = M t`; before the product, in a preconditioned step, `w_J`
    /// (written by the measure pass).
    r: Vec<f64>,
    /// The preconditioned residual `P w_J` (`None`: no preconditioner).
    p: Option<Vec<f64>>,
    lambda: Col<f64>,
    /// A factor of `z` and `u` not applied yet (the one-row restoration's):
    /// the iterate is `scale z`, with `M (scale z) = scale u` (while `u`
    /// is not stale: a step that changed the contact set leaves `u` to be
    /// recomputed). The passes that read them multiply in registers, the
    /// step stores its result at scale 1, and the answer applies what is
    /// left.
    scale: f64,
    /// The fit's sums over the contact set, at `scale` 1.
    fit: FitSums,
    /// `ρ` of the previous iteration: `‖w_J‖²`, preconditioned `w_J · P w_J`.
    g_old: f64,
    /// Whether the contact set grew in the last step (restart the direction).
    restart: bool,
    /// `u` is not `M z` (a point clipped or entered, several rows
    /// restored): a true product is due.
    stale: bool,
    /// `u` came from a true product since the last step.
    fresh: bool,
    /// With several rows, `z` before a step that clips points (allocated
    /// at the first such step).
    before: Option<Vec<f64>>,
    /// The step to the first boundary ([`iteration::boundary_pass`]) of
    /// the current step, where it clips points and `before` holds `z`.
    boundary: Option<f64>,
    /// Points enter only by proportioning steps (after the iteration made
    /// no progress: see [`Guard`]).
    guarded: bool,
    /// Steps whose `u` was kept by columns ([`correct`](Self::correct))
    /// since the last true product.
    corrected: usize,
    /// The scratch of the operator's products and the preconditioner's
    /// applications, which take turns in it.
    scratch: PodBuffer,
}

impl State {
    fn new(
        z: Vec<f64>,
        k: usize,
        preconditioned: bool,
        scratch: PodBuffer,
    ) -> Result<Self, LcpError> {
        let n = z.len();
        let vector = |what| linalg::try_zeros(n, what).map_err(LcpError::from);
        Ok(Self {
            p: match preconditioned {
                true => Some(vector("the conjugate gradient's preconditioned residual")?),
                false => None,
            },
            u: vector("the conjugate gradient's product M z")?,
            t: vector("the conjugate gradient's direction")?,
            r: vector("the conjugate gradient's product M t")?,
            z,
            lambda: Col::zeros(k),
            scale: 1.0,
            fit: FitSums {
                bu: vec![0.0; k],
                bq: vec![0.0; k],
                gram: faer::Mat::zeros(k, k),
            },
            g_old: 0.0,
            restart: true,
            stale: true,
            fresh: false,
            before: None,
            boundary: None,
            guarded: false,
            corrected: 0,
            scratch,
        })
    }

    /// `u = M z` from a true product and the fit's sums, at scale 1: a
    /// pending scale stays pending (`M (c z) = c M z`).
    fn refresh(&mut self, form: &Form<'_>, data: &Data<'_>, work: &mut Work) {
        let stack = PodStack::new(&mut self.scratch);
        form.m.operator.apply(&self.z, &mut self.u, stack);
        work.products += 1;
        self.fit = iteration::fit_pass(data, &self.z, &self.u);
        self.stale = false;
        self.fresh = true;
        self.corrected = 0;
    }

    /// The most points a step may clip or let in and keep `u = M z` by
    /// columns ([`correct`](Self::correct)), a product's worth
    /// ([`Operator::columns_per_product`](crate::Operator::columns_per_product));
    /// `None` where it may not: an operator without cheap columns, several
    /// rows (whose restoration after a changed contact set moves every
    /// point), or [`MAX_CORRECTIONS`] corrections since the last true
    /// product (the rounding of the recurrence and of the columns then
    /// starts afresh from one).
    fn collect_limit(&self, form: &Form<'_>) -> Option<usize> {
        let per_product = form.m.operator.columns_per_product();
        let allowed =
            per_product > 0 && form.border.ncols() <= 1 && self.corrected < MAX_CORRECTIONS;
        allowed.then_some(per_product)
    }

    /// After a step that changed the contact set at the few points of its
    /// [`Changes`](iteration::Changes): `u += M d` by their columns, which
    /// makes `u` `M z` again without a product, and the fit's sums of the
    /// new contact set; the update then reads as one that kept the set.
    fn correct(
        &mut self,
        form: &Form<'_>,
        data: &Data<'_>,
        mut update: Update,
        work: &mut Work,
    ) -> Update {
        let Some(changes) = update.changes.take() else {
            return update;
        };
        if !form.m.operator.add_columns(&changes.columns, &mut self.u) {
            return update;
        }
        work.corrections += 1;
        work.columns += changes.columns.len();
        self.corrected += 1;
        self.fit = iteration::fit_pass(data, &self.z, &self.u);
        update.sums = Some(UpdateSums {
            rows_terms: changes.rows_terms,
            bu: self.fit.bu.clone(),
        });
        update
    }

    /// `λ` fitted on the contact set, then the measure pass.
    fn measure(&mut self, data: &Data<'_>) -> Result<Measures, Breakdown> {
        let k = self.lambda.nrows();
        let rhs = Col::from_fn(k, |j| self.scale * self.fit.bu[j] + self.fit.bq[j]);
        self.lambda = solve_fit(&self.fit, rhs)?;
        let lambda: Vec<f64> = self.lambda.iter().copied().collect();
        // A preconditioned step's residual `w_J`, written while the pass
        // has the chunk in cache.
        let residual = match self.p {
            Some(_) => Some(&mut self.r[..]),
            None => None,
        };
        let m = iteration::measure_pass(data, (&self.z, &self.u), residual, self.scale, &lambda);
        if !m.finite {
            return Err(Breakdown::NonFinite);
        }
        Ok(m)
    }

    /// One step from the measures `m`: a conjugate-gradient step (steps 2
    /// to 4 of the module documentation), or, guarded, a proportioning
    /// step where the points that interfere off `J` outweigh the residual
    /// on `J` (`‖β‖² > ‖w_J‖²`).
    fn step(
        &mut self,
        form: &Form<'_>,
        data: &Data<'_>,
        m: &Measures,
        work: &mut Work,
    ) -> Result<(), Breakdown> {
        let lambda: Vec<f64> = self.lambda.iter().copied().collect();
        if self.guarded && m.chopped > m.g {
            return self.proportion(form, data, &lambda, work);
        }
        let g_now = m.g;
        let num = if self.p.is_some() {
            self.preconditioned_direction(form, data, work)?
        } else {
            let beta = self.beta(g_now);
            self.g_old = g_now;
            let iterate = (&self.z[..], &self.u[..], self.scale);
            iteration::direction_pass(data, iterate, &mut self.t, &lambda, beta)
        };
        let enter = !self.guarded;
        self.advance(form, data, (&lambda, num), enter, work)
    }

    /// Steps along the direction `t` from `w · t = num`: the product `r =
    /// M t`, the step `τ = num / (t · r)`, the update (points off `J` that
    /// interfere enter where `enter` is set), then the rows restored; the
    /// direction restarts where points entered.
    fn advance(
        &mut self,
        form: &Form<'_>,
        data: &Data<'_>,
        (lambda, num): (&[f64], f64),
        enter: bool,
        work: &mut Work,
    ) -> Result<(), Breakdown> {
        let stack = PodStack::new(&mut self.scratch);
        form.m.operator.apply(&self.t, &mut self.r, stack);
        work.products += 1;
        let den = iteration::curvature_pass(&self.t, &self.r);
        let tau = step_length(num, den)?;
        self.keep_before_clipping(form.border.ncols(), tau)?;
        let collect = self.collect_limit(form);
        let update = iteration::update_pass(
            data,
            (&mut self.z, &mut self.u, self.scale),
            &self.t,
            &self.r,
            lambda,
            tau,
            (enter, collect),
        );
        // The step stored `z` (and `u`, where it kept the contact set) at
        // scale 1.
        self.scale = 1.0;
        self.restart = update.entered > 0;
        self.fresh = false;
        let update = self.correct(form, data, update, work);
        self.rows_after(form, update)
    }

    /// A proportioning step (Dostál 2005): the points that interfere off
    /// `J` enter along `β` (`t = β`, [`iteration::chopped_pass`]) by the
    /// exact line search `τ = β · β / β · M β`, a decrease of the objective
    /// whatever the units, where Polonsky & Keer's entry `z_i = -τ w_i`
    /// takes the step length of the direction on `J`; then the rows are
    /// restored and the direction restarts.
    fn proportion(
        &mut self,
        form: &Form<'_>,
        data: &Data<'_>,
        lambda: &[f64],
        work: &mut Work,
    ) -> Result<(), Breakdown> {
        let iterate = (&self.z[..], &self.u[..], self.scale);
        let num = iteration::chopped_pass(data, iterate, &mut self.t, lambda);
        // `t` is 0 on `J`: no point leaves, and every point along `β` enters.
        self.advance(form, data, (lambda, num), true, work)
    }

    /// With several rows, keeps `z` where the step `τ` will clip points
    /// (it reaches the boundary `τ_b <= τ`): should the clipped contact set
    /// not carry the rows, the step is cut at `τ_b` instead
    /// ([`rows_after`](Self::rows_after)).
    fn keep_before_clipping(&mut self, k: usize, tau: f64) -> Result<(), Breakdown> {
        self.boundary = None;
        if k < 2 || !(tau > 0.0) {
            return Ok(());
        }
        // Several rows: no pending scale (only one row is restored by it).
        debug_assert!(self.scale == 1.0);
        let boundary = iteration::boundary_pass(&self.z, &self.t);
        if boundary > tau {
            return Ok(());
        }
        if self.before.is_none() {
            let what = "the conjugate gradient's iterate before a step";
            let v = linalg::try_zeros(self.z.len(), what)
                .map_err(|e| Breakdown::Error(Box::new(e.into())))?;
            self.before = Some(v);
        }
        let before = self.before.as_mut().expect("allocated above");
        before.copy_from_slice(&self.z);
        self.boundary = Some(boundary);
        Ok(())
    }

    /// `β = ρ / ρ_old` (0 after a restart).
    fn beta(&self, rho: f64) -> f64 {
        if self.restart || self.g_old == 0.0 {
            0.0
        } else {
            rho / self.g_old
        }
    }

    /// Step 2 preconditioned: `r = w_J` (from the measure pass), `p = P r`, projected on the rows'
    /// null space on `J` (`p_J - B_J μ`, `B_J^T B_J μ = B_J^T p_J`), `ρ =
    /// r_J · p_J`, `t_J = p_J + (ρ / ρ_old) t_J`; returns `w_J · t_J`.
    fn preconditioned_direction(
        &mut self,
        form: &Form<'_>,
        data: &Data<'_>,
        work: &mut Work,
    ) -> Result<f64, Breakdown> {
        let p = self.p.as_mut().expect("a preconditioned state");
        let preconditioner = form.m.preconditioner.expect("a preconditioned state");
        preconditioner.precondition(&self.r, p, PodStack::new(&mut self.scratch));
        work.preconditionings += 1;
        let sums = iteration::projection_pass(data, &self.z, &self.r, p);
        let k = sums.bp.len();
        let mu = solve_fit(&self.fit, Col::from_fn(k, |j| sums.bp[j]))?;
        let mu: Vec<f64> = mu.iter().copied().collect();
        let rho = sums.rp - (0..k).map(|j| mu[j] * sums.br[j]).sum::<f64>();
        if !rho.is_finite() {
            return Err(Breakdown::NonFinite);
        }
        let beta = self.beta(rho);
        self.g_old = rho;
        let p = self.p.as_ref().expect("a preconditioned state");
        Ok(iteration::preconditioned_direction_pass(
            data,
            &self.z,
            &self.r,
            p,
            &mut self.t,
            &mu,
            beta,
        ))
    }

    /// Step 4: the rows restored after a step, and whether `u` still is
    /// `M z` (no point left or entered: the update's sums are there). Where the step clipped points and the contact set left
    /// cannot carry several rows, the step is cut at the first boundary
    /// (one point leaves; the rows hold as `B_J^T t_J = 0`): restoring the
    /// rows from the clipped iterate by an additive correction could
    /// return it to where the step started, and the iteration would cycle
    /// (a step overshooting by its full length on a contact set of the
    /// rows' size).
    fn rows_after(&mut self, form: &Form<'_>, update: Update) -> Result<(), Breakdown> {
        let k = form.border.ncols();
        // One row is restored by scaling `z` (and `u`, where it is still
        // `M z`): the scale waits for the next pass that reads them.
        let one_row = (k == 1)
            .then(|| form.resultant[0] / update.rows[0])
            .filter(|ratio| ratio.is_finite() && *ratio > 0.0);
        // The same contact set: its Gram matrix and `Σ_J B q` hold, `Σ_J B
        // u` is new. A changed one: `u` is recomputed from `M z` (it may
        // hold the recurrence in part only), and the scale applies to both.
        self.stale = update.sums.is_none();
        let restored = update.sums.is_some_and(|sums| {
            self.fit.bu = sums.bu;
            (0..k).all(|j| {
                let (sum, terms) = (update.rows[j] - form.resultant[j], sums.rows_terms[j]);
                let terms = terms + form.resultant[j].abs();
                terms == 0.0 || sum.abs() <= ROWS_RESTORED * terms
            })
        });
        if let Some(ratio) = one_row {
            self.scale = ratio;
            return Ok(());
        }
        if restored {
            return Ok(());
        }
        self.stale = true;
        if restore_on_support(form, &mut self.z) {
            return Ok(());
        }
        if let (Some(boundary), Some(before)) = (self.boundary.take(), &self.before) {
            iteration::boundary_step(&mut self.z, before, &self.t, boundary);
            self.restart = true;
            if restore_on_support(form, &mut self.z) {
                return Ok(());
            }
        }
        shift_into_rows(form, &mut self.z)
    }
}

/// `λ` from the fit's normal equations, regularized where the contact set
/// has fewer points than independent rows (an early iterate).
fn solve_fit(fit: &FitSums, rhs: Col<f64>) -> Result<Col<f64>, Breakdown> {
    let k = rhs.nrows();
    if k == 0 {
        return Ok(Col::zeros(0));
    }
    let finite = |nu: Col<f64>| {
        let ok = nu.iter().all(|v| v.is_finite());
        ok.then_some(nu)
    };
    if let Ok(llt) = fit.gram.llt(Side::Lower)
        && let Some(nu) = finite(llt.solve(&rhs))
    {
        return Ok(nu);
    }
    let mut gram = fit.gram.clone();
    let largest = (0..k).fold(0.0f64, |a, j| a.max(gram[(j, j)]));
    let ridge = if largest > 0.0 {
        crate::tolerance::RIDGE * largest
    } else {
        1.0
    };
    for j in 0..k {
        gram[(j, j)] += ridge;
    }
    let llt = gram
        .llt(Side::Lower)
        .map_err(|_| Breakdown::SingularBorder)?;
    finite(llt.solve(&rhs)).ok_or(Breakdown::SingularBorder)
}

/// The worst of the residuals the certificate measures, from the measure
/// pass (`M |z|` read as `u`: exact for an operator with non-negative
/// entries, a stricter scale otherwise).
fn worst(form: &Form<'_>, m: &Measures) -> f64 {
    let rel = |v: f64, scale: f64| if scale > 0.0 { v / scale } else { 0.0 };
    let mut worst = rel(-m.min_w, m.w_scale).max(rel(m.complementarity, m.z_scale * m.w_scale));
    for j in 0..m.rows.len() {
        let b = form.resultant[j];
        worst = worst.max(rel((m.rows[j] - b).abs(), m.rows_terms[j] + b.abs()));
    }
    worst
}

/// Solves `form` from `options.initial_z` (clipped to `z >= 0`) or from a
/// start of its own.
pub(crate) fn attempt(form: &Form<'_>, options: &Options) -> Attempted {
    solve(form, options, Guard::default())
}

/// [`attempt`] under `guard` (guarded from the start where it is tripped).
fn solve(form: &Form<'_>, options: &Options, mut guard: Guard) -> Attempted {
    let n = form.q.nrows();
    let mut work = Work::default();
    let preconditioned = options.preconditioner && form.m.preconditioner.is_some();
    let what = "the conjugate gradient's scratch (of its products)";
    let mut scratch = scratch(form.m.scratch(preconditioned), what)
        .map_err(|e| Failure::error(e.into(), work))?;
    let z = match start(form, options, &mut work, &mut scratch) {
        Ok(Some(z)) => z,
        Ok(None) => return Ok(answer(vec![0.0; n], Col::zeros(form.border.ncols()), work)),
        Err(breakdown) => return Err(Failure::new(breakdown, work)),
    };
    let k = form.border.ncols();
    let mut state =
        State::new(z, k, preconditioned, scratch).map_err(|e| Failure::error(e, work))?;
    state.guarded = guard.tripped;
    let data = Data::new(form.q, form.border);
    let cap = options.iteration_cap();
    let mut progress = Progress::new(options.tolerances.certificate, n);
    let mut confirming = false;
    loop {
        crate::cancel::check().map_err(|c| Failure::new(c.into(), work))?;
        if state.stale {
            state.refresh(form, &data, &mut work);
        }
        let m = state.measure(&data).map_err(|b| Failure::new(b, work))?;
        let c = worst(form, &m);
        let done = if confirming {
            // A true product judges what the recurrence found converged.
            confirming = false;
            let confirmed = progress.confirms(c);
            if !confirmed {
                progress.restart();
                state.restart = true;
            }
            confirmed
        } else if progress.done(work.iterations, c) {
            if !state.fresh {
                state.stale = true;
                confirming = true;
                continue;
            }
            true
        } else {
            false
        };
        if !done && work.iterations >= cap {
            let error = LcpError::ConjugateGradientLimit {
                size: n,
                limit: cap,
                residual: c,
                tolerance: options.tolerances.certificate,
            };
            return Err(Failure::error(error, work));
        }
        if done {
            // The answer copies z: free the other vectors first.
            let State {
                mut z,
                lambda,
                u,
                t,
                r,
                p,
                scale,
                scratch,
                ..
            } = state;
            drop((u, t, r, p, scratch));
            if scale != 1.0 {
                z.iter_mut().for_each(|v| *v *= scale);
            }
            return Ok(answer(z, lambda, work));
        }
        if guard.stuck(c) {
            state.guarded = true;
            state.restart = true;
        }
        work.iterations += 1;
        state
            .step(form, &data, &m, &mut work)
            .map_err(|b| Failure::new(b, work))?;
    }
}

/// Watches for an iteration that makes no progress: Polonsky & Keer's
/// entries (`z_i = -τ w_i`, `τ` the step on `J`) can overshoot where the
/// direction on `J` has little curvature, and the contact set then
/// alternates between too many points and too few (a rubber ball in a
/// turned groove at 1 mN, 20,915 points: the residual settled near 5e-2
/// for 10,000 iterations). After [`GUARD_WINDOW`] iterations without a new
/// smallest residual the method turns guarded for good: points enter only
/// by proportioning steps, an exact line search along the interference
/// (MPRGP, Dostál & Schöberl 2005), which decreases the objective.
#[derive(Default)]
struct Guard {
    best: Option<f64>,
    since: usize,
    tripped: bool,
}

/// Steps whose `M z` is kept by columns before a true product is taken
/// again where the contact set changes: the recurrence and the columns add
/// their rounding step after step, and a product starts it afresh (the
/// stopping rule confirms from a true product besides).
const MAX_CORRECTIONS: usize = 8;

/// Iterations without a new smallest residual before the method turns
/// guarded.
const GUARD_WINDOW: usize = 2 * crate::tolerance::STALL_WINDOW;

impl Guard {
    /// Whether the iteration, at residual `c`, has just been found stuck.
    fn stuck(&mut self, c: f64) -> bool {
        if self.tripped {
            return false;
        }
        if self.best.is_none_or(|b| c < b) {
            self.best = Some(c);
            self.since = 0;
            return false;
        }
        self.since += 1;
        self.tripped = self.since >= GUARD_WINDOW;
        self.tripped
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
fn start(
    form: &Form<'_>,
    options: &Options,
    work: &mut Work,
    scratch: &mut PodBuffer,
) -> Result<Option<Vec<f64>>, Breakdown> {
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
            form.m
                .operator
                .apply(&e, &mut column, PodStack::new(scratch));
            work.products += 1;
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

#[cfg(test)]
mod tests {
    use super::*;
    use faer::Mat;
    use proptest::prelude::*;

    /// A bordered problem around a known solution `z*` (as the border
    /// proptests build theirs): `M = A A^T / n + I / 4`, a border of ones
    /// and lever arms, `z* > 0` on an active set of at least `k` points,
    /// `w* > 0` off it, `q = w* - M z* + B λ*`, `b = B^T z*`.
    struct Known {
        m: Mat<f64>,
        q: Col<f64>,
        border: Mat<f64>,
        resultant: Col<f64>,
        z: Col<f64>,
    }

    fn known(n: usize, k: usize, a: &[f64], v: &[f64], on: &[bool], arms: &[f64]) -> Known {
        let a = Mat::from_fn(n, n, |i, j| a[i * n + j]);
        let mut m = &a * a.transpose() * (1.0 / n as f64);
        for i in 0..n {
            m[(i, i)] += 0.25;
        }
        let border = Mat::from_fn(n, k, |i, l| if l == 0 { 1.0 } else { arms[l * n + i] });
        let active = |i: usize| i < k || on[i];
        let z = Col::from_fn(n, |i| if active(i) { 0.1 + v[i] } else { 0.0 });
        let w = Col::from_fn(n, |i| if active(i) { 0.0 } else { 0.1 + v[i] });
        let lambda = Col::from_fn(k, |l| 0.3 - 0.2 * l as f64);
        let q = &w - &m * &z + &border * &lambda;
        let resultant = border.transpose() * &z;
        Known {
            m,
            q,
            border,
            resultant,
            z,
        }
    }

    /// A dense `M` without columns: every changed contact set is met by a
    /// true product.
    struct NoColumns<'a>(faer::MatRef<'a, f64>);

    impl crate::Operator for NoColumns<'_> {
        fn size(&self) -> usize {
            self.0.nrows()
        }
        fn apply_scratch(&self) -> faer::dyn_stack::StackReq {
            faer::dyn_stack::StackReq::EMPTY
        }
        fn apply(&self, x: &[f64], y: &mut [f64], stack: &mut PodStack) {
            self.0.apply(x, y, stack);
        }
        fn apply_abs(&self, x: &[f64], y: &mut [f64], stack: &mut PodStack) {
            self.0.apply_abs(x, y, stack);
        }
    }

    fn solved(p: &Known, guard: Guard) -> Col<f64> {
        solved_by(p, &p.m.as_ref(), guard).0
    }

    /// The solution by `operator` (of `p.m`) and the work it took.
    fn solved_by(p: &Known, operator: &dyn crate::Operator, guard: Guard) -> (Col<f64>, Work) {
        let form: Form<'_> = Bordered {
            m: MatrixFree {
                operator,
                preconditioner: None,
            },
            q: p.q.as_ref(),
            border: p.border.as_ref(),
            resultant: p.resultant.as_ref(),
        };
        match solve(&form, &Options::default(), guard) {
            Ok(answer) => (answer.z, answer.work),
            Err(f) => panic!("the conjugate gradient failed: {:?}", f.breakdown),
        }
    }

    #[test]
    fn the_guard_trips_after_a_window_without_a_new_smallest_residual() {
        let mut guard = Guard::default();
        assert!(!guard.stuck(1.0));
        assert!(!guard.stuck(0.5));
        for _ in 1..GUARD_WINDOW {
            assert!(!guard.stuck(0.7));
        }
        assert!(
            !guard.stuck(0.4),
            "a new smallest residual restarts the window"
        );
        for _ in 1..GUARD_WINDOW {
            assert!(!guard.stuck(0.4));
        }
        assert!(guard.stuck(0.4));
        assert!(guard.tripped && !guard.stuck(1e-3), "trips once");
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(200))]
        /// Guarded from the start (points enter only by proportioning
        /// steps), the method finds the same unique solution.
        #[test]
        fn the_guarded_iteration_finds_the_known_solution(
            n in 4usize..16,
            k in 1usize..4,
            a in prop::collection::vec(-1.0f64..1.0, 256),
            v in prop::collection::vec(0.0f64..1.0, 16),
            on in prop::collection::vec(any::<bool>(), 16),
            arms in prop::collection::vec(-1.0f64..1.0, 48),
        ) {
            let p = known(n, k, &a, &v, &on, &arms);
            let guarded = Guard { tripped: true, ..Guard::default() };
            for z in [solved(&p, guarded), solved(&p, Guard::default())] {
                let scale = p.z.iter().fold(0.0f64, |s, v| s.max(v.abs()));
                for i in 0..n {
                    prop_assert!((z[i] - p.z[i]).abs() <= 1e-7 * scale, "z[{}] {} vs {}", i, z[i], p.z[i]);
                }
            }
        }

        /// With one row or none, the iteration that keeps `M z` by columns
        /// where the contact set changed finds the solution that the one
        /// which takes a true product finds, with no more products.
        #[test]
        fn columns_in_place_of_products_find_the_known_solution(
            n in 4usize..16,
            k in 0usize..2,
            a in prop::collection::vec(-1.0f64..1.0, 256),
            v in prop::collection::vec(0.0f64..1.0, 16),
            on in prop::collection::vec(any::<bool>(), 16),
            arms in prop::collection::vec(-1.0f64..1.0, 48),
        ) {
            let p = known(n, k.max(1), &a, &v, &on, &arms);
            let p = if k == 0 {
                // No row: the load's multiplier moves into q.
                let q = &p.q - &p.border * Col::from_fn(1, |_| 0.3);
                Known { q, border: Mat::zeros(n, 0), resultant: Col::zeros(0), ..p }
            } else {
                p
            };
            let (with, columns) = solved_by(&p, &p.m.as_ref(), Guard::default());
            let (without, products) = solved_by(&p, &NoColumns(p.m.as_ref()), Guard::default());
            prop_assert_eq!(products.corrections, 0);
            prop_assert!(columns.products <= products.products + 1);
            let scale = p.z.iter().fold(0.0f64, |s, v| s.max(v.abs()));
            for i in 0..n {
                prop_assert!((with[i] - p.z[i]).abs() <= 1e-7 * scale, "z[{}] {} vs {}", i, with[i], p.z[i]);
                prop_assert!((without[i] - p.z[i]).abs() <= 1e-7 * scale);
            }
        }
    }
}
