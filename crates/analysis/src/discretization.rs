//! The discretization error of a solution, estimated from the same problem
//! solved on coarser grids of its family (`crate::grid::GridFamily`):
//! generalized Richardson extrapolation with the observed order, as in the
//! grid convergence index procedure of Celik et al. (2008, J. Fluids Eng.
//! 130, 078001), non-integer grid ratios allowed.
//!
//! With a quantity's values `f1, f2, f3` on grids of spacings
//! `h1 < h2 < h3` (fine first), `r21 = h2 / h1`, `r32 = h3 / h2`,
//! `e21 = f2 - f1`, `e32 = f3 - f2` and `s = sign(e32 / e21)`, the observed
//! order p is the fixed point of
//!
//! ```text
//!     p = (ln|e32 / e21| + q(p)) / ln r21,    q(p) = ln((r21^p - s) / (r32^p - s))
//! ```
//!
//! (Celik's equation without its absolute value, whose sign tells a
//! quantity whose changes shrink from one whose changes grow), started at
//! `q = 0`. It is the order of the model `f_i = f + C (s)^i h_i^p`:
//! monotone convergence for `s = 1`, errors of alternating sign for
//! `s = -1`. The model's limit and the fine grid's error are
//!
//! ```text
//!     f_ext = f1 - s e21 / (r21^p' - s),      error = |e21| / (r21^p' - s),
//! ```
//!
//! with `p' = min(p, 2)`: 2 is the formal order of elcon's discretization
//! (piecewise-constant pressure over cells, collocation at their centres),
//! and an observed order above it is a cancellation of errors, not a rate
//! to extrapolate with (the cap of Eça & Hoekstra's procedure, J. Comput.
//! Phys. 262, 2014). Only `s = 1` is extrapolated (see the verdicts).
//!
//! When the run's own grid is not the finest solved (a finer grid, h/2,
//! was added because the grid at 4h would not resolve the contact, or
//! because h, 2h and 4h left a quantity not resolved), the limit is the
//! same and the run's own value's error is `|f_ext - f_h|`.
//!
//! The verdict:
//!
//! - `exact`: the values agree on every grid to `1e-9` of the quantity's
//!   scale (a tilt that symmetry makes zero, a load under load control);
//! - `converging`, with the error above, only when the three grids show
//!   it: the changes have one sign (`s = 1`) and shrink at an observed
//!   order within the discretization's range with a margin of 2 each way,
//!   `LOWEST_ORDER = 1/2 <= p <= HIGHEST_ORDER = 4` (the contact's extent
//!   converges at order 1, smooth quantities at 2);
//! - `not resolved`, with the observed order and why: changes of
//!   alternating sign (the coarser grids put a feature, a punch's rounded
//!   rim, in one cell or the next), changes that do not shrink (`p < 1/2`:
//!   a singular edge's peak grows like `h^(-1/2)`, a kinked surface's like
//!   `ln h`), or changes that shrink faster than the method allows
//!   (`p > 4`: a cancellation of errors, not a rate). Where the input
//!   itself limits a quantity (a surface interpolated with slope kinks: a
//!   pressure peak under each kink that every finer grid resolves higher)
//!   the caller marks it not resolved whatever its changes, naming the
//!   input;
//! - `not estimated`: with the reason. Two grids give no observed order:
//!   rather than assume one, the quantity is not estimated (its values on
//!   both grids are reported).

/// Values agreeing to this fraction of the quantity's scale count as the
/// same (a million times the rounding of a certified solve, a thousand
/// times below the smallest discretization error elcon's grids show).
pub const EXACT: f64 = 1e-9;

/// The formal order of elcon's discretization: the cap on the order the
/// error is extrapolated with.
pub const FORMAL_ORDER: f64 = 2.0;

/// The lowest observed order taken as converging: the contact extent's
/// order 1 (its edge moves by a fraction of a cell), over the margin 2.
pub const LOWEST_ORDER: f64 = 0.5;

/// The highest observed order taken as converging: the formal order 2
/// times the margin 2. Changes falling faster are errors cancelling
/// between the grids (a value crossing its limit), not a rate.
pub const HIGHEST_ORDER: f64 = 4.0;

/// The fewest cells of a coarser grid the fine contact must span along
/// each axis for that grid to be solved (about nine points across it).
/// Coarser grids are outside the range where the error falls at a steady
/// order: Example 1's spheres at 21 points across, whose grid at 4h puts
/// 5 cells across the contact, show the peak pressure's changes growing
/// from 4h to h (an observed order of -0.2, where the finer grids show 2).
/// Where the grid at 4h would span fewer, a finer grid (h/2) is solved
/// instead.
pub const MIN_CELLS_ACROSS: f64 = 8.0;

/// The most bytes a finer grid's solve may hold: the run's own solve's, or
/// this floor (256 MiB) where that is less. The runner's estimate of a
/// scene's peak counts a finer grid within it.
pub const FINER_FLOOR_BYTES: f64 = 256.0 * 1024.0 * 1024.0;

/// The bytes a finer grid's solve may hold when the run's own holds
/// `own_bytes` (see [`FINER_FLOOR_BYTES`]).
pub fn finer_allowance(own_bytes: f64) -> f64 {
    own_bytes.max(FINER_FLOOR_BYTES)
}

/// The most seconds a finer grid added for a quantity the coarser grids
/// leave unresolved may take, as a multiple of the run's own planned
/// solve ([`refine_seconds_allowance`]): a grid at h/2 on a surface has four
/// times the points, matrix-free about four times the seconds and dense
/// up to 64 times (every point in contact).
pub const REFINE_TIMES: f64 = 16.0;

/// The floor of [`refine_seconds_allowance`], seconds: what a run of a few
/// thousand points may spend on its estimate whatever its own solve took.
pub const REFINE_FLOOR_SECONDS: f64 = 10.0;

/// The planned seconds a finer grid added for an unresolved quantity may
/// take when the run's own planned solve takes `own_seconds`:
/// [`REFINE_TIMES`] times it, at least [`REFINE_FLOOR_SECONDS`]. The grids
/// at h/2 and h/4 solved where the grid at 4h would not resolve the contact
/// have only the memory allowance ([`finer_allowance`]): without them
/// there is no estimate at all.
pub fn refine_seconds_allowance(own_seconds: f64) -> f64 {
    (REFINE_TIMES * own_seconds).max(REFINE_FLOOR_SECONDS)
}

/// What the estimate of one quantity concluded.
#[derive(Debug, Clone, PartialEq)]
#[non_exhaustive]
pub enum Verdict {
    /// The changes have one sign and shrink at an order within the
    /// method's range: the error is Richardson's.
    Converging,
    /// The grids do not show convergence, or the input limits the
    /// quantity: why, with the observed order.
    NotResolved(String),
    /// The same value on every grid.
    Exact,
    /// No estimate, and why.
    NotEstimated(String),
}

impl Verdict {
    /// `converging`, `not resolved`, `exact` or `not estimated`.
    pub fn name(&self) -> &'static str {
        match self {
            Verdict::Converging => "converging",
            Verdict::NotResolved(_) => "not resolved",
            Verdict::Exact => "exact",
            Verdict::NotEstimated(_) => "not estimated",
        }
    }

    /// Why a quantity is not resolved or not estimated.
    pub fn reason(&self) -> Option<&str> {
        match self {
            Verdict::NotResolved(r) | Verdict::NotEstimated(r) => Some(r),
            _ => None,
        }
    }
}

/// The discretization error estimate of one quantity.
#[derive(Debug, Clone, PartialEq)]
pub struct ErrorEstimate {
    /// The value on each grid solved, the finest first.
    pub values: Vec<f64>,
    /// The index in `values` of the run's own grid (0, or 1 when a finer
    /// grid was solved).
    pub own: usize,
    /// The limit `f_ext` (converging, or exact: the value).
    pub extrapolated: Option<f64>,
    /// The run's own value's estimated error `|f_ext - f_h|` (the
    /// quantity's unit; 0 when exact).
    pub error: Option<f64>,
    /// The observed order p (three grids, the changes not zero), or the
    /// least-squares fit's.
    pub order: Option<f64>,
    /// The standard deviation of the least-squares fit the estimate is
    /// made with ([`fitted`]; the quantity's unit), if it is a fit.
    pub scatter: Option<f64>,
    /// What the estimate concluded.
    pub verdict: Verdict,
}

impl ErrorEstimate {
    /// The run's own grid's value (NaN when there is none).
    pub fn value(&self) -> f64 {
        self.values.get(self.own).copied().unwrap_or(f64::NAN)
    }

    /// The error over the value's magnitude, where both exist and the value
    /// is not 0.
    pub fn relative_error(&self) -> Option<f64> {
        let v = self.value().abs();
        self.error.filter(|_| v > 0.0).map(|e| e / v)
    }

    fn not_estimated(values: &[f64], reason: impl Into<String>) -> Self {
        Self {
            values: values.to_vec(),
            own: 0,
            extrapolated: None,
            error: None,
            order: None,
            scatter: None,
            verdict: Verdict::NotEstimated(reason.into()),
        }
    }
}

/// The estimate from a quantity's `values` on grids of `spacings` (the
/// finest first, spacings growing; the first three are used), `own` the
/// index of the run's own grid among them (0 or 1), `scale` the quantity's
/// magnitude the test of equal values is relative to (see the module
/// documentation).
///
/// ```
/// use elcon_analysis::discretization::{Verdict, estimate};
/// // f(h) = 1 + h^2 on h = 0.1, 0.2, 0.4.
/// let f = |h: f64| 1.0 + h * h;
/// let e = estimate(&[f(0.1), f(0.2), f(0.4)], &[0.1, 0.2, 0.4], 0, 1.0);
/// assert_eq!(e.verdict, Verdict::Converging);
/// assert!((e.order.unwrap() - 2.0).abs() < 1e-9);
/// assert!((e.error.unwrap() - 0.01).abs() < 1e-12);
/// ```
pub fn estimate(values: &[f64], spacings: &[f64], own: usize, scale: f64) -> ErrorEstimate {
    let mut estimate = ErrorEstimate::not_estimated(values, "");
    estimate.own = own.min(values.len().saturating_sub(1));
    match three_grids(values, spacings, scale) {
        Err(verdict) => {
            if verdict == Verdict::Exact {
                estimate.extrapolated = Some(estimate.value());
                estimate.error = Some(0.0);
            }
            estimate.verdict = verdict;
        }
        Ok(None) => {
            estimate.verdict =
                Verdict::NotEstimated("the observed order could not be computed".into())
        }
        Ok(Some(p)) => {
            estimate.order = Some(p);
            match unresolved(values, p) {
                Some(why) => estimate.verdict = Verdict::NotResolved(why),
                None => {
                    let (e21, r21) = (values[1] - values[0], spacings[1] / spacings[0]);
                    let limit = values[0] - e21 / (r21.powf(p.min(FORMAL_ORDER)) - 1.0);
                    estimate.extrapolated = Some(limit);
                    estimate.error = Some((limit - estimate.value()).abs());
                    estimate.verdict = Verdict::Converging;
                }
            }
        }
    }
    estimate
}

/// The observed order of three grids' `values` (`None` if it cannot be
/// computed), or the verdict that needs none: exact, or not estimated and
/// why (too few grids, a value not finite, two grids agreeing and the
/// third not).
fn three_grids(values: &[f64], spacings: &[f64], scale: f64) -> Result<Option<f64>, Verdict> {
    checked(values, spacings, scale)?;
    let not = |why: &str| Err(Verdict::NotEstimated(why.into()));
    let f1 = values[0];
    let magnitude = values.iter().fold(scale.abs(), |a, v| a.max(v.abs()));
    let tol = EXACT * magnitude;
    match values.len() {
        1 => return not("one grid: no other grid was solved"),
        2 => return not("two grids: no order observed (a third grid was not solved)"),
        _ => {}
    }
    let (e21, e32) = (values[1] - f1, values[2] - values[1]);
    if e21.abs() <= tol {
        return not(
            "the two finest grids agree to rounding and the coarsest does not: no order observed",
        );
    }
    if e32.abs() <= tol {
        return not(
            "the two coarser grids agree to rounding and the finest does not: no order observed",
        );
    }
    let (r21, r32) = (spacings[1] / spacings[0], spacings[2] / spacings[1]);
    Ok(observed_order(e21, e32, r21, r32, (e32 / e21).signum()))
}

/// The verdict values need no order for: not estimated and why (no
/// grid, a value not finite, spacings not growing), or exact (every grid
/// agreeing to [`EXACT`] of `scale` or the values' magnitude).
fn checked(values: &[f64], spacings: &[f64], scale: f64) -> Result<(), Verdict> {
    let not = |why: &str| Err(Verdict::NotEstimated(why.into()));
    if values.len() != spacings.len() || values.is_empty() {
        return not("no grid with a value");
    }
    if let Some(v) = values.iter().find(|v| !v.is_finite()) {
        return Err(Verdict::NotEstimated(format!(
            "a value is not finite ({v})"
        )));
    }
    if !spacings.windows(2).all(|w| w[1] > w[0]) || !(spacings[0] > 0.0) {
        return not("the spacings do not grow from the fine grid");
    }
    let f1 = values[0];
    let magnitude = values.iter().fold(scale.abs(), |a, v| a.max(v.abs()));
    let tol = EXACT * magnitude;
    if values.len() > 1 && values.iter().all(|v| (v - f1).abs() <= tol) {
        return Err(Verdict::Exact);
    }
    Ok(())
}

/// Why three grids' `values` of observed order `p` do not show
/// convergence (see the module documentation), or `None` when they do.
fn unresolved(values: &[f64], p: f64) -> Option<String> {
    let (e21, e32) = (values[1] - values[0], values[2] - values[1]);
    let changes = changes(values)?;
    if e32 * e21 < 0.0 {
        return Some(format!(
            "the changes alternate in sign ({changes}): the coarser grids do not resolve a \
             feature of the contact, and no order holds"
        ));
    }
    if p < LOWEST_ORDER {
        return Some(format!(
            "the changes do not shrink as the method's do ({changes}, observed order {p:.2} \
             below {LOWEST_ORDER}): a peak that finer grids resolve higher, as at a singular \
             edge or a slope kink of the surface"
        ));
    }
    (p > HIGHEST_ORDER).then(|| {
        format!(
            "the changes shrink faster than the method's order allows ({changes}, observed \
             order {p:.2} above {HIGHEST_ORDER}): errors cancelling between the grids, not a \
             rate to extrapolate"
        )
    })
}

/// The changes of three grids' `values` (the finest first) as messages
/// give them: "changes +1.2e-3 then +3.0e-4 from the coarsest grid";
/// `None` with fewer than three.
pub fn changes(values: &[f64]) -> Option<String> {
    let [f1, f2, f3, ..] = values else {
        return None;
    };
    let (e21, e32) = (f2 - f1, f3 - f2);
    Some(format!(
        "changes {e32:+.2e} then {e21:+.2e} from the coarsest grid"
    ))
}

/// The fixed point of `p = (ln|e32 / e21| + q(p)) / ln r21` (see the
/// module documentation), started at `q = 0`; a p at or below 0 is
/// returned as it is (the changes do not shrink). `None` if the iteration
/// leaves the reals.
fn observed_order(e21: f64, e32: f64, r21: f64, r32: f64, s: f64) -> Option<f64> {
    let ratio = (e32 / e21).abs().ln();
    let ln_r = r21.ln();
    let mut p = ratio / ln_r;
    for _ in 0..100 {
        if !(p > 0.0) {
            return p.is_finite().then_some(p);
        }
        let q = ((r21.powf(p) - s) / (r32.powf(p) - s)).ln();
        let next = (ratio + q) / ln_r;
        if !next.is_finite() {
            return None;
        }
        let done = (next - p).abs() <= 1e-12 * p.max(1.0);
        p = next;
        if done {
            break;
        }
    }
    Some(p)
}

/// The fewest grids a least-squares fit is made on (three parameters and
/// at least one degree of freedom for its standard deviation).
pub const FIT_GRIDS: usize = 4;

/// The largest standard deviation of a least-squares fit, over the error
/// it estimates, for the fit to be credible: a fit scattering by more
/// than this fraction of the run's error does not tell the error from the
/// noise (see the module documentation for how it was set).
pub const FIT_SCATTER: f64 = 0.25;

/// The orders the free fit searches: a fit's best order at the lower end
/// is a quantity whose changes do not shrink.
const FIT_ORDERS: (f64, f64) = (0.05, 8.0);

/// The form of a least-squares fit `phi_i = phi_0 + ...` over the grids'
/// spacings `h_i` (Eça & Hoekstra 2014).
#[derive(Debug, Clone, Copy, PartialEq)]
#[non_exhaustive]
pub enum FitForm {
    /// `alpha h^p`, the order p fitted.
    Free,
    /// `alpha h^p`, the order fixed (1 or 2).
    Fixed(f64),
    /// `alpha h + beta h^2`.
    Mixed,
}

/// A least-squares fit of a quantity's values on four or more grids.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Fit {
    /// Its form.
    pub form: FitForm,
    /// The limit `phi_0` (the quantity's unit).
    pub limit: f64,
    /// The order p: fitted, fixed, or 1 for the mixed form.
    pub order: f64,
    /// The standard deviation `sqrt(S / (n - k))` of its `n` residuals,
    /// `k` its parameters (the quantity's unit).
    pub sigma: f64,
    /// Its coefficients of `h^p` (or `h` and `h^2`), `h` over the largest
    /// spacing.
    coefficients: [f64; 2],
    /// The largest spacing.
    h_max: f64,
}

impl Fit {
    /// The fit's value at the spacing `h`.
    pub fn at(&self, h: f64) -> f64 {
        let x = h / self.h_max;
        match self.form {
            FitForm::Mixed => self.limit + self.coefficients[0] * x + self.coefficients[1] * x * x,
            _ => self.limit + self.coefficients[0] * x.powf(self.order),
        }
    }
}

/// The least-squares fit of `values` on `spacings` in `form`: `None` when
/// there are no more values than parameters or the normal equations are
/// singular. For the free form, `order` is the fixed order tried.
fn fit_form(values: &[f64], spacings: &[f64], form: FitForm, order: f64) -> Option<Fit> {
    let n = values.len();
    let h_max = spacings.iter().fold(0.0, |a: f64, &h| a.max(h));
    let k = match form {
        FitForm::Mixed | FitForm::Free => 3,
        FitForm::Fixed(_) => 2,
    };
    if n <= k || !(h_max > 0.0) {
        return None;
    }
    let basis = |h: f64| -> [f64; 3] {
        let x = h / h_max;
        match form {
            FitForm::Mixed => [1.0, x, x * x],
            _ => [1.0, x.powf(order), 0.0],
        }
    };
    let m = if form == FitForm::Mixed { 3 } else { 2 };
    // Centred on the values' mean for the normal equations' conditioning.
    let mean = values.iter().sum::<f64>() / n as f64;
    let mut a = [[0.0; 4]; 3];
    for (&v, &h) in values.iter().zip(spacings) {
        let b = basis(h);
        for i in 0..m {
            for j in 0..m {
                a[i][j] += b[i] * b[j];
            }
            a[i][3] += b[i] * (v - mean);
        }
    }
    let c = solve_small(&mut a, m)?;
    let residual: f64 = (values.iter().zip(spacings))
        .map(|(&v, &h)| {
            let b = basis(h);
            let r = v - mean - (c[0] * b[0] + c[1] * b[1] + c[2] * b[2]);
            r * r
        })
        .sum();
    Some(Fit {
        form,
        limit: mean + c[0],
        order: if form == FitForm::Mixed { 1.0 } else { order },
        sigma: (residual / (n - k) as f64).sqrt(),
        coefficients: [c[1], c[2]],
        h_max,
    })
}

/// Gaussian elimination with partial pivoting of the `m x m` system in
/// `a` (its right-hand side the fourth column); `None` if singular.
fn solve_small(a: &mut [[f64; 4]; 3], m: usize) -> Option<[f64; 3]> {
    let scale = (0..m).fold(0.0, |s: f64, i| s.max(a[i][i].abs()));
    for col in 0..m {
        let pivot = (col..m).max_by(|&i, &j| a[i][col].abs().total_cmp(&a[j][col].abs()))?;
        a.swap(col, pivot);
        if !(a[col][col].abs() > 1e-13 * scale) {
            return None;
        }
        for row in col + 1..m {
            let f = a[row][col] / a[col][col];
            for k in col..4 {
                a[row][k] -= f * a[col][k];
            }
        }
    }
    let mut x = [0.0; 3];
    for row in (0..m).rev() {
        let tail: f64 = (row + 1..m).map(|k| a[row][k] * x[k]).sum();
        x[row] = (a[row][3] - tail) / a[row][row];
    }
    Some(x)
}

/// The free fit `phi_0 + alpha h^p` of least residual, p searched over
/// [`FIT_ORDERS`] (a scan, then golden sections around its best).
fn free_fit(values: &[f64], spacings: &[f64]) -> Option<Fit> {
    let at = |p: f64| fit_form(values, spacings, FitForm::Free, p);
    let sigma = |p: f64| at(p).map_or(f64::INFINITY, |f| f.sigma);
    let (lo, hi) = FIT_ORDERS;
    let steps = 200;
    let p_of = |i: usize| lo * (hi / lo).powf(i as f64 / steps as f64);
    let best = (0..=steps).min_by(|&i, &j| sigma(p_of(i)).total_cmp(&sigma(p_of(j))))?;
    let (mut a, mut b) = (p_of(best.saturating_sub(1)), p_of((best + 1).min(steps)));
    let g = 0.5 * (5f64.sqrt() - 1.0);
    for _ in 0..60 {
        let (c, d) = (b - g * (b - a), a + g * (b - a));
        if sigma(c) < sigma(d) {
            b = d;
        } else {
            a = c;
        }
    }
    at(0.5 * (a + b)).filter(|f| f.sigma.is_finite())
}

/// The least-squares estimate (Eça & Hoekstra, J. Comput. Phys. 262,
/// 2014) from a quantity's `values` on four or more grids of `spacings`
/// (the finest first, spacings growing), `own` the index of the run's own
/// grid, `scale` the quantity's magnitude: `phi_i = phi_0 + alpha h_i^p`
/// fitted with p free; where p falls outside [`LOWEST_ORDER`],
/// [`HIGHEST_ORDER`], the fit of least standard deviation among p fixed
/// at 1, at 2 and the mixed `alpha h + beta h^2`. The run's error is
/// `|phi_own - phi_0|`; the verdict is converging only when the fit's
/// standard deviation is at most [`FIT_SCATTER`] of that error (see the
/// module documentation).
///
/// ```
/// use elcon_analysis::discretization::{Verdict, fitted};
/// let h = [0.1, 0.141, 0.2, 0.283, 0.4];
/// let f: Vec<f64> = h.iter().map(|h| 1.0 + h * h).collect();
/// let e = fitted(&f, &h, 0, 1.0);
/// assert_eq!(e.verdict, Verdict::Converging);
/// assert!((e.error.unwrap() - 0.01).abs() < 1e-9);
/// ```
pub fn fitted(values: &[f64], spacings: &[f64], own: usize, scale: f64) -> ErrorEstimate {
    let mut estimate = ErrorEstimate::not_estimated(values, "");
    estimate.own = own.min(values.len().saturating_sub(1));
    if let Err(verdict) = checked(values, spacings, scale) {
        if verdict == Verdict::Exact {
            estimate.extrapolated = Some(estimate.value());
            estimate.error = Some(0.0);
        }
        estimate.verdict = verdict;
        return estimate;
    }
    if values.len() < FIT_GRIDS {
        estimate.verdict = Verdict::NotEstimated(format!(
            "{} grids: a least-squares fit needs {FIT_GRIDS}",
            values.len()
        ));
        return estimate;
    }
    // The finest m grids, m from all down to FIT_GRIDS: the coarsest
    // grids may lie outside the range where the error falls at a steady
    // order (a contact edge in one cell or the next). The first credible
    // fit with its order free is taken, else the first credible one with
    // the order fixed, else the verdict of the fit over all.
    let own_value = estimate.value();
    let mut first = None;
    for fixed in [false, true] {
        for m in (FIT_GRIDS..=values.len()).rev() {
            let own_spacing = spacings[estimate.own];
            let subset = (&values[..m], &spacings[..m]);
            match fit_verdict(subset, (own_value, own_spacing), fixed) {
                Ok((fit, error)) => {
                    estimate.order = Some(fit.order);
                    estimate.scatter = Some(fit.sigma);
                    estimate.extrapolated = Some(fit.limit);
                    estimate.error = Some(error);
                    estimate.verdict = Verdict::Converging;
                    return estimate;
                }
                Err(refusal) => {
                    first.get_or_insert(refusal);
                }
            }
        }
    }
    if let Some((verdict, order, scatter)) = first {
        estimate.verdict = verdict;
        estimate.order = order;
        estimate.scatter = scatter;
    }
    estimate
}

/// The largest error at the spacing `own` that a trend `alpha h^p` of the
/// lowest order ([`LOWEST_ORDER`]) spanning the range of `values` over
/// `spacings` gives: `range (own / h_min)^p / ((h_max / h_min)^p - 1)`. A
/// fit whose limit lies further extrapolates beyond what the grids show.
fn reach(values: &[f64], spacings: &[f64], own: f64) -> f64 {
    let (lo, hi) = values
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &v| {
            (a.min(v), b.max(v))
        });
    let h_min = spacings[0];
    let h_max = spacings[spacings.len() - 1];
    let p = LOWEST_ORDER;
    (hi - lo) * (own / h_min).powf(p) / ((h_max / h_min).powf(p) - 1.0)
}

/// Why a fit was not taken: the verdict, the fit's order and standard
/// deviation where there is one.
type Refusal = (Verdict, Option<f64>, Option<f64>);

/// The credible fit of `values` on `spacings` (see [`fitted`]) and the
/// error `|own_value - phi_0|` it gives: with the order free, or, if
/// `fixed`, the form of least standard deviation of p = 1, p = 2 and the
/// mixed one. Else the verdict why not, with the fit's order and standard
/// deviation where there is one.
fn fit_verdict(
    (values, spacings): (&[f64], &[f64]),
    (own_value, own_spacing): (f64, f64),
    fixed: bool,
) -> Result<(Fit, f64), Refusal> {
    let n = values.len();
    let Some(free) = free_fit(values, spacings) else {
        let why = "the least-squares fit is singular".to_string();
        return Err((Verdict::NotEstimated(why), None, None));
    };
    if free.order < LOWEST_ORDER {
        return Err((
            Verdict::NotResolved(format!(
                "the changes do not shrink as the method's do (a least-squares fit over {n} \
                 grids has order {:.2}, below {LOWEST_ORDER}): a peak that finer grids resolve \
                 higher, as at a singular edge or a slope kink of the surface",
                free.order
            )),
            Some(free.order),
            None,
        ));
    }
    let fit = if !fixed {
        free
    } else if free.order <= HIGHEST_ORDER {
        // The fixed orders stand in only for a free order above the
        // method's range, not for a free fit that scatters.
        return Err((
            Verdict::NotResolved(String::new()),
            Some(free.order),
            Some(free.sigma),
        ));
    } else {
        [FitForm::Fixed(1.0), FitForm::Fixed(2.0), FitForm::Mixed]
            .into_iter()
            .filter_map(|form| {
                let p = if let FitForm::Fixed(p) = form { p } else { 1.0 };
                fit_form(values, spacings, form, p)
            })
            .min_by(|a, b| a.sigma.total_cmp(&b.sigma))
            .unwrap_or(free)
    };
    let error = (own_value - fit.limit).abs();
    let reach = reach(values, spacings, own_spacing);
    if error > reach {
        return Err((
            Verdict::NotResolved(format!(
                "a least-squares fit over {n} grids ({}) puts the limit {error:.2e} from the \
                 run's value, further than a trend of order {LOWEST_ORDER} through the grids' \
                 values reaches ({reach:.2e}): an extrapolation the grids do not support",
                fit.form
            )),
            Some(fit.order),
            Some(fit.sigma),
        ));
    }
    let finest = (values[1] - values[0]).abs();
    let signal = error.min(finest);
    if fit.sigma <= FIT_SCATTER * signal && (fixed || free.order <= HIGHEST_ORDER) {
        return Ok((fit, error));
    }
    let why = if fit.sigma <= FIT_SCATTER * signal {
        format!(
            "a least-squares fit over {n} grids has order {:.2}, above {HIGHEST_ORDER}: \
             errors cancelling between the grids, not a rate to extrapolate",
            fit.order
        )
    } else {
        format!(
            "a least-squares fit over {n} grids ({}) scatters by {:.2e}, more than \
             {FIT_SCATTER} of the smaller of the error it estimates ({error:.2e}) and the \
             finest grids' change ({finest:.2e}): the grids' noise (a feature the coarser \
             grids put in one cell or the next) is as large as the discretization's trend",
            fit.form, fit.sigma
        )
    };
    Err((Verdict::NotResolved(why), Some(fit.order), Some(fit.sigma)))
}

impl std::fmt::Display for FitForm {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            FitForm::Free => write!(f, "order fitted"),
            FitForm::Fixed(p) => write!(f, "order fixed at {p}"),
            FitForm::Mixed => write!(f, "orders 1 and 2"),
        }
    }
}

/// A quantity of a solution whose discretization error is estimated.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[non_exhaustive]
pub enum Quantity {
    /// The approach alpha.
    Approach,
    /// The peak pressure `max F_k / A_k`.
    MaxPressure,
    /// The contact radius or half-width (`ContactSolution::contact_extent`).
    ContactExtent,
    /// The contact area or length (`ContactSolution::contact_measure`).
    ContactMeasure,
    /// The load `e^T F` (given under load control).
    Load,
    /// The load centre's x.
    LoadCentreX,
    /// The load centre's y.
    LoadCentreY,
    /// The rotation about the x axis.
    TiltX,
    /// The rotation about the y axis.
    TiltY,
}

impl Quantity {
    /// Every quantity, in the order result.json writes them.
    pub const ALL: [Quantity; 9] = [
        Quantity::Approach,
        Quantity::MaxPressure,
        Quantity::ContactExtent,
        Quantity::ContactMeasure,
        Quantity::Load,
        Quantity::LoadCentreX,
        Quantity::LoadCentreY,
        Quantity::TiltX,
        Quantity::TiltY,
    ];

    /// The name result.json writes: `approach`, `max_pressure`,
    /// `contact_extent`, `contact_measure`, `load`, `load_centre_x`,
    /// `load_centre_y`, `tilt_x`, `tilt_y`.
    pub fn name(self) -> &'static str {
        match self {
            Quantity::Approach => "approach",
            Quantity::MaxPressure => "max_pressure",
            Quantity::ContactExtent => "contact_extent",
            Quantity::ContactMeasure => "contact_measure",
            Quantity::Load => "load",
            Quantity::LoadCentreX => "load_centre_x",
            Quantity::LoadCentreY => "load_centre_y",
            Quantity::TiltX => "tilt_x",
            Quantity::TiltY => "tilt_y",
        }
    }
}

/// One grid of a discretization estimate.
#[derive(Debug, Clone, PartialEq)]
pub struct GridRun {
    /// Its points N.
    pub points: usize,
    /// Its spacing h (`GridFamily::spacing`; length).
    pub spacing: f64,
    /// Seconds to build and solve its problem (the fine grid's: its
    /// assembly and solve).
    pub seconds: f64,
    /// Why its solve failed, if it did (its values are then not used).
    pub failure: Option<String>,
}

/// What in a scene's input limits a quantity whatever the grid: the
/// quantity is then not a converged property of the scene.
#[derive(Debug, Clone, PartialEq)]
#[non_exhaustive]
pub enum InputLimit {
    /// A height map interpolated bilinearly: its slope kinks at every
    /// node line.
    KinkedMap {
        /// The map's file (or key).
        label: String,
    },
    /// An axial profile interpolated linearly: its slope kinks at every
    /// row.
    KinkedProfile {
        /// The profile's file (or key).
        label: String,
    },
    /// The contact reaches the bodies' own edge (a punch's rim, a roller's
    /// end) where an elastic half-space's pressure is singular, and its
    /// peak pressure is there: it grows without bound as the grid refines.
    SingularEdge {
        /// The run's points in contact on that edge.
        points: usize,
    },
    /// A table whose nodes lie closer than the cells of the coarsest grid
    /// solved: the grids sample different parts of the data, and their
    /// changes are not the discretization's.
    CoarserThanData {
        /// The table's file (or key).
        label: String,
        /// Its nodes' spacing (length).
        nodes: f64,
        /// The coarsest grid's cell along the table's axes (length).
        cell: f64,
    },
}

impl InputLimit {
    /// Whether it limits `quantity`: a kinked surface the peak pressure, a
    /// singular edge the peak and the contact's extent and measure (its
    /// outline there is the bodies' edge, as the grid lays it out), a table
    /// finer than the grids every quantity.
    pub fn limits(&self, quantity: Quantity) -> bool {
        match self {
            InputLimit::KinkedMap { .. } | InputLimit::KinkedProfile { .. } => {
                quantity == Quantity::MaxPressure
            }
            InputLimit::SingularEdge { .. } => matches!(
                quantity,
                Quantity::MaxPressure | Quantity::ContactExtent | Quantity::ContactMeasure
            ),
            InputLimit::CoarserThanData { .. } => true,
        }
    }
}

impl std::fmt::Display for InputLimit {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let (what, label, read) = match self {
            InputLimit::KinkedMap { label } => ("height map", label, "bilinearly"),
            InputLimit::KinkedProfile { label } => ("profile", label, "linearly"),
            InputLimit::SingularEdge { points } => {
                return write!(
                    f,
                    "the contact reaches the bodies' own edge (a punch's rim, a roller's end) \
                     at {points} point(s) and its peak pressure is there, where an elastic \
                     half-space's pressure is singular: the peak grows without bound as the \
                     grid refines, and the \
                     contact's outline there is the edge as the grid's cells lay it out, so \
                     neither the peak nor the contact's extent is a converged property of the \
                     scene (a rounded rim or a crowned end keeps the contact off the edge and \
                     the peak finite)"
                );
            }
            InputLimit::CoarserThanData { label, nodes, cell } => {
                return write!(
                    f,
                    "the table {label}'s nodes are {} apart, closer than the {} cells of the \
                     coarsest grid the error estimate solved: its grids sample the data \
                     differently, so their changes do not measure the discretization error \
                     (a finer grid, at most the nodes' spacing, resolves the data)",
                    crate::Num(*nodes),
                    crate::Num(*cell)
                );
            }
        };
        write!(
            f,
            "the {what} {label} is interpolated {read}: its slope kinks at the nodes put a \
             pressure peak under each that every finer grid resolves higher, so the peak \
             pressure is not a converged property of the scene (interpolation = \"cubic\" \
             gives a surface with a continuous slope)"
        )
    }
}

/// A solution's discretization error: the grids solved (the finest
/// first) and each quantity's estimate.
#[derive(Debug, Clone, PartialEq)]
pub struct Discretization {
    /// The grids, the finest first; the values come from those without a
    /// failure.
    pub grids: Vec<GridRun>,
    /// The index in `grids` of the run's own grid (0, or 1 or 2 where
    /// finer grids were solved).
    pub own: usize,
    /// What in the input limits the quantities whatever the grid.
    pub limits: Vec<InputLimit>,
    /// Each quantity's estimate, in the order of [`Quantity::ALL`].
    pub estimates: Vec<(Quantity, ErrorEstimate)>,
    /// What limited the estimate (a coarser grid not made, not resolving
    /// the contact, or failing), if anything did.
    pub note: Option<String>,
}

impl Discretization {
    /// The estimate of `quantity`.
    pub fn get(&self, quantity: Quantity) -> Option<&ErrorEstimate> {
        self.estimates
            .iter()
            .find(|(q, _)| *q == quantity)
            .map(|(_, e)| e)
    }

    /// Seconds spent on the grids other than the run's own (the
    /// estimate's cost).
    pub fn extra_seconds(&self) -> f64 {
        let own = self.own;
        (self.grids.iter().enumerate())
            .filter(|&(i, _)| i != own)
            .fold(0.0, |sum, (_, g)| sum + g.seconds)
    }

    /// Every quantity not estimated for `reason`, with its fine value from
    /// `value`.
    pub fn not_estimated(
        grids: Vec<GridRun>,
        value: impl Fn(Quantity) -> f64,
        reason: &str,
    ) -> Self {
        Self {
            grids,
            estimates: Quantity::ALL
                .iter()
                .map(|&q| (q, ErrorEstimate::not_estimated(&[value(q)], reason)))
                .collect(),
            note: Some(reason.to_string()),
            own: 0,
            limits: Vec::new(),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_power_law_is_recovered_on_non_integer_ratios() {
        // f(h) = 3 - 0.7 h^1.5 on spacings in ratios 2.08 and 1.86.
        let f = |h: f64| 3.0 - 0.7 * h.powf(1.5);
        let h = [0.1, 0.208, 0.38688];
        let e = estimate(&[f(h[0]), f(h[1]), f(h[2])], &h, 0, 3.0);
        assert_eq!(e.verdict, Verdict::Converging);
        assert!((e.order.unwrap() - 1.5).abs() < 1e-9, "{e:?}");
        assert!((e.extrapolated.unwrap() - 3.0).abs() < 1e-12, "{e:?}");
        assert!((e.error.unwrap() - 0.7 * 0.1f64.powf(1.5)).abs() < 1e-12);
        assert!((e.relative_error().unwrap() - e.error.unwrap() / f(0.1)).abs() < 1e-15);
    }

    #[test]
    fn alternating_changes_are_not_resolved() {
        // f_i = 1 + (-1)^i 0.01 h_i : the grids straddle the limit by turns.
        let h = [0.1, 0.2, 0.4];
        let f = [1.0 + 0.01 * 0.1, 1.0 - 0.01 * 0.2, 1.0 + 0.01 * 0.4];
        let e = estimate(&f, &h, 0, 1.0);
        assert_eq!(e.verdict.name(), "not resolved");
        assert!(e.verdict.reason().unwrap().contains("alternate"), "{e:?}");
        assert_eq!(e.error, None);
    }

    #[test]
    fn a_finer_grid_estimates_the_run_s_own_value() {
        // f(h) = 1 + h^2 on h/2 = 0.05, h = 0.1, 2h = 0.2, the run's own
        // grid the second: its error is h^2 = 0.01.
        let f = |h: f64| 1.0 + h * h;
        let e = estimate(&[f(0.05), f(0.1), f(0.2)], &[0.05, 0.1, 0.2], 1, 1.0);
        assert_eq!(e.verdict, Verdict::Converging);
        assert_eq!(e.value(), f(0.1));
        assert!((e.error.unwrap() - 0.01).abs() < 1e-12, "{e:?}");
        assert!((e.extrapolated.unwrap() - 1.0).abs() < 1e-12, "{e:?}");
    }

    #[test]
    fn an_order_above_the_formal_one_extrapolates_at_the_formal_one() {
        let f = |h: f64| 1.0 + h.powi(3);
        let h = [0.1, 0.2, 0.4];
        let e = estimate(&[f(0.1), f(0.2), f(0.4)], &h, 0, 1.0);
        assert!((e.order.unwrap() - 3.0).abs() < 1e-9);
        // |e21| / (2^2 - 1) = 0.007 / 3.
        assert!((e.error.unwrap() - 0.007 / 3.0).abs() < 1e-12, "{e:?}");
    }

    #[test]
    fn changes_that_do_not_shrink_or_shrink_too_fast_are_not_resolved() {
        // A singular edge's peak: f = h^(-1/2), and a kink's logarithm.
        let h = [0.05, 0.1, 0.2];
        for f in [|h: f64| h.powf(-0.5), |h: f64| (1.0 / h).ln()] {
            let e = estimate(&[f(h[0]), f(h[1]), f(h[2])], &h, 0, 1.0);
            assert!(
                e.verdict.reason().unwrap().contains("do not shrink"),
                "{e:?}"
            );
            assert_eq!(e.error, None);
        }
        // Order 0.4, just below the lowest, and 4.5, above the highest.
        for (p, says) in [(0.4, "do not shrink"), (4.5, "faster")] {
            let f = |h: f64| 1.0 + h.powf(p);
            let e = estimate(&[f(h[0]), f(h[1]), f(h[2])], &h, 0, 1.0);
            assert!((e.order.unwrap() - p).abs() < 1e-9, "{e:?}");
            assert!(e.verdict.reason().unwrap().contains(says), "{e:?}");
        }
        // Order 0.6 and 3.9, within the range with the margin, converge.
        for p in [0.6, 3.9] {
            let f = |h: f64| 1.0 + h.powf(p);
            let e = estimate(&[f(h[0]), f(h[1]), f(h[2])], &h, 0, 1.0);
            assert_eq!(e.verdict, Verdict::Converging, "{p}: {e:?}");
        }
    }

    #[test]
    fn a_kinked_table_limits_the_peak_and_a_fine_table_every_quantity() {
        let kinked = InputLimit::KinkedProfile {
            label: "crown.csv".into(),
        };
        let fine = InputLimit::CoarserThanData {
            label: "map.npy".into(),
            nodes: 0.005,
            cell: 0.008,
        };
        for q in Quantity::ALL {
            assert_eq!(kinked.limits(q), q == Quantity::MaxPressure, "{q:?}");
            assert!(fine.limits(q), "{q:?}");
        }
        let text = kinked.to_string();
        assert!(
            text.contains("crown.csv") && text.contains("linearly"),
            "{text}"
        );
        let text = fine.to_string();
        assert!(text.contains("map.npy") && text.contains("0.005"), "{text}");
        let map = InputLimit::KinkedMap {
            label: "rough.npy".into(),
        };
        assert!(map.to_string().contains("bilinearly"));
    }

    #[test]
    fn a_singular_edge_limits_the_peak_and_the_extent_and_says_why() {
        let edge = InputLimit::SingularEdge { points: 112 };
        for q in Quantity::ALL {
            let limited = matches!(
                q,
                Quantity::MaxPressure | Quantity::ContactExtent | Quantity::ContactMeasure
            );
            assert_eq!(edge.limits(q), limited, "{q:?}");
        }
        let text = edge.to_string();
        for says in ["112 point(s)", "singular", "is a converged property"] {
            assert!(text.contains(says), "{says}: {text}");
        }
    }

    #[test]
    fn a_finer_grid_for_an_unresolved_quantity_may_take_16_times_the_run_or_10_s() {
        assert_eq!(refine_seconds_allowance(0.001), REFINE_FLOOR_SECONDS);
        assert_eq!(refine_seconds_allowance(2.0), 32.0);
        assert!(!(refine_seconds_allowance(f64::NAN) < 10.0));
    }

    #[test]
    fn three_grids_changes_are_written_from_the_coarsest() {
        let text = changes(&[1.0, 1.5, 3.5]).unwrap();
        assert_eq!(text, "changes +2.00e0 then +5.00e-1 from the coarsest grid");
        assert_eq!(changes(&[1.0, 2.0]), None);
    }

    /// Spacings in ratios of about sqrt 2, as the fit's grids are.
    const FIT_H: [f64; 5] = [0.1, 0.1414, 0.2, 0.2829, 0.4];

    #[test]
    fn a_fit_recovers_the_limit_of_a_noisy_second_order_sequence() {
        // phi_0 = 3, a h^2 with a = 5, noise of 1 % of the trend's
        // change at h, alternating.
        let noise = [1.0, -1.0, 1.0, -1.0, 1.0];
        let f: Vec<f64> = (FIT_H.iter().zip(noise))
            .map(|(h, s)| 3.0 + 5.0 * h * h + s * 0.01 * 5.0 * 0.01)
            .collect();
        let e = fitted(&f, &FIT_H, 0, 3.0);
        assert_eq!(e.verdict, Verdict::Converging, "{e:?}");
        assert!((e.extrapolated.unwrap() - 3.0).abs() < 0.02 * 0.05, "{e:?}");
        let truth = f[0] - 3.0;
        assert!((e.error.unwrap() / truth - 1.0).abs() < 0.05, "{e:?}");
        assert!((e.order.unwrap() - 2.0).abs() < 0.2, "{e:?}");
        assert!(e.scatter.unwrap() < 0.02 * truth, "{e:?}");
        // The run's own grid the second: its error is against the same limit.
        let e = fitted(&f, &FIT_H, 1, 3.0);
        assert!(
            (e.error.unwrap() / (f[1] - 3.0) - 1.0).abs() < 0.05,
            "{e:?}"
        );
    }

    #[test]
    fn a_fit_of_an_order_above_the_highest_is_not_resolved() {
        // Changes falling as h^6: no fixed order fits them within the
        // scatter allowed, and the free order is a cancellation.
        let f: Vec<f64> = FIT_H.iter().map(|h| 1.0 + h.powi(6)).collect();
        let e = fitted(&f, &FIT_H, 0, 1.0);
        assert_eq!(e.verdict.name(), "not resolved", "{e:?}");
        assert!(e.verdict.reason().unwrap().contains("above 4"), "{e:?}");
    }

    #[test]
    fn noise_larger_than_the_trend_is_not_resolved_by_the_fit() {
        // A trend of 1e-4 h^2 under alternating noise of 1e-5.
        let f: Vec<f64> = (FIT_H.iter().enumerate())
            .map(|(i, h)| 1.0 + 1e-4 * h * h + if i % 2 == 0 { 1e-5 } else { -1e-5 })
            .collect();
        let e = fitted(&f, &FIT_H, 0, 1.0);
        assert_eq!(e.verdict.name(), "not resolved", "{e:?}");
        assert!(e.verdict.reason().unwrap().contains("scatters"), "{e:?}");
        assert_eq!(e.error, None);
    }

    #[test]
    fn a_fit_of_changes_that_do_not_shrink_is_not_resolved() {
        for f in [|h: f64| h.powf(-0.5), |h: f64| (1.0 / h).ln()] {
            let v: Vec<f64> = FIT_H.iter().map(|&h| f(h)).collect();
            let e = fitted(&v, &FIT_H, 0, 1.0);
            assert!(
                e.verdict.reason().unwrap().contains("do not shrink"),
                "{e:?}"
            );
        }
        let e = fitted(&[1.0; 5], &FIT_H, 0, 1.0);
        assert_eq!(e.verdict, Verdict::Exact);
        let e = fitted(&[1.0, 1.1, 1.2], &FIT_H[..3], 0, 1.0);
        assert_eq!(e.verdict.name(), "not estimated");
    }

    #[test]
    fn equal_values_are_exact_and_too_few_grids_are_said() {
        let h = [0.1, 0.2, 0.4];
        let e = estimate(&[0.0, 1e-20, -1e-20], &h, 0, 1e-3);
        assert_eq!(e.verdict, Verdict::Exact);
        assert_eq!(e.error, Some(0.0));
        let e = estimate(&[1.0, 1.01], &h[..2], 0, 1.0);
        assert!(e.verdict.reason().unwrap().contains("two grids"), "{e:?}");
        assert_eq!(e.values, vec![1.0, 1.01]);
        let e = estimate(&[1.0], &h[..1], 0, 1.0);
        assert_eq!(e.verdict.name(), "not estimated");
        let e = estimate(&[1.0, f64::NAN, 1.0], &h, 0, 1.0);
        assert!(e.verdict.reason().unwrap().contains("not finite"));
        let e = estimate(&[1.0, 1.1, 1.2], &[0.2, 0.1, 0.4], 0, 1.0);
        assert!(e.verdict.reason().unwrap().contains("spacings"));
    }
}
