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
//! Phys. 262, 2014). For `s = -1` the error is at most `|e21| / 2` (the two
//! grids' errors of opposite sign, the fine one the smaller).
//!
//! The verdict:
//!
//! - `exact`: the values agree on every grid to `1e-9` of the quantity's
//!   scale (a tilt that symmetry makes zero, a load under load control);
//! - `not converging`: the changes do not shrink under refinement, an
//!   observed order below 1/2 for monotone changes (a singular edge's peak
//!   pressure grows like `h^(-1/2)`, p = -1/2; at p = 1/2 Richardson's
//!   error is already 2.4 times the last change at r = 2) or at most 0 for
//!   alternating ones, and not below -1 (changes growing faster than any
//!   contact singularity makes them, `STEEPEST_GROWTH`, say the coarser
//!   grids are outside the range where the error follows a power of h: not
//!   estimated);
//! - `converging`: the error above;
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

/// The smallest observed order of monotone changes taken as converging.
pub const SLOWEST_ORDER: f64 = 0.5;

/// The lowest observed order taken for a quantity that grows without
/// bound: a contact pressure in linear elasticity is at most singular like
/// `r^(-1/2)` (a rigid punch's rim), so a cell's mean grows at most like
/// `h^(-1/2)`; changes growing faster (an order below twice that rate)
/// come from coarse grids outside the range where the error follows a
/// power of h, and are not estimated.
pub const STEEPEST_GROWTH: f64 = -1.0;

/// The fewest cells of a coarser grid the fine contact must span along
/// each axis for that grid to be solved (about nine points across it).
/// Coarser grids are outside the range where the error falls at a steady
/// order: Example 1's spheres at 21 points across, whose grid at 4h puts
/// 5 cells across the contact, show the peak pressure's changes growing
/// from 4h to h (an observed order of -0.2, where the finer grids show 2).
pub const MIN_CELLS_ACROSS: f64 = 8.0;

/// What the estimate of one quantity concluded.
#[derive(Debug, Clone, PartialEq)]
#[non_exhaustive]
pub enum Verdict {
    /// The changes shrink with the grid at the observed order: the error
    /// is Richardson's.
    Converging,
    /// The changes do not shrink (a singular edge's peak pressure).
    NotConverging,
    /// The same value on every grid.
    Exact,
    /// No estimate, and why.
    NotEstimated(String),
}

impl Verdict {
    /// `converging`, `not converging`, `exact` or `not estimated`.
    pub fn name(&self) -> &'static str {
        match self {
            Verdict::Converging => "converging",
            Verdict::NotConverging => "not converging",
            Verdict::Exact => "exact",
            Verdict::NotEstimated(_) => "not estimated",
        }
    }

    /// Why a quantity is not estimated.
    pub fn reason(&self) -> Option<&str> {
        match self {
            Verdict::NotEstimated(r) => Some(r),
            _ => None,
        }
    }
}

/// The discretization error estimate of one quantity.
#[derive(Debug, Clone, PartialEq)]
pub struct ErrorEstimate {
    /// The value on each grid solved, the fine one first.
    pub values: Vec<f64>,
    /// The limit `f_ext` (converging, or exact: the value).
    pub extrapolated: Option<f64>,
    /// The fine value's estimated error `|f_ext - f1|` (the quantity's
    /// unit; 0 when exact).
    pub error: Option<f64>,
    /// The observed order p (three grids, the changes not zero).
    pub order: Option<f64>,
    /// What the estimate concluded.
    pub verdict: Verdict,
}

impl ErrorEstimate {
    /// The fine grid's value (NaN when there is none).
    pub fn value(&self) -> f64 {
        self.values.first().copied().unwrap_or(f64::NAN)
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
            extrapolated: None,
            error: None,
            order: None,
            verdict: Verdict::NotEstimated(reason.into()),
        }
    }
}

/// The estimate from a quantity's `values` on grids of `spacings` (the
/// fine grid first, spacings growing; the first three are used), `scale`
/// the quantity's magnitude the test of equal values is relative to (see
/// the module documentation).
///
/// ```
/// use elcon_analysis::discretization::{Verdict, estimate};
/// // f(h) = 1 + h^2 on h = 0.1, 0.2, 0.4.
/// let f = |h: f64| 1.0 + h * h;
/// let e = estimate(&[f(0.1), f(0.2), f(0.4)], &[0.1, 0.2, 0.4], 1.0);
/// assert_eq!(e.verdict, Verdict::Converging);
/// assert!((e.order.unwrap() - 2.0).abs() < 1e-9);
/// assert!((e.error.unwrap() - 0.01).abs() < 1e-12);
/// ```
pub fn estimate(values: &[f64], spacings: &[f64], scale: f64) -> ErrorEstimate {
    if values.len() != spacings.len() || values.is_empty() {
        return ErrorEstimate::not_estimated(values, "no grid with a value");
    }
    if let Some(v) = values.iter().find(|v| !v.is_finite()) {
        return ErrorEstimate::not_estimated(values, format!("a value is not finite ({v})"));
    }
    if !spacings.windows(2).all(|w| w[1] > w[0]) || !(spacings[0] > 0.0) {
        return ErrorEstimate::not_estimated(values, "the spacings do not grow from the fine grid");
    }
    let f1 = values[0];
    let magnitude = values.iter().fold(scale.abs(), |a, v| a.max(v.abs()));
    let tol = EXACT * magnitude;
    let mut estimate = ErrorEstimate::not_estimated(values, "");
    if values.len() > 1 && values.iter().all(|v| (v - f1).abs() <= tol) {
        estimate.extrapolated = Some(f1);
        estimate.error = Some(0.0);
        estimate.verdict = Verdict::Exact;
        return estimate;
    }
    match values.len() {
        1 => {
            estimate.verdict = Verdict::NotEstimated("one grid: no coarser grid was solved".into());
            return estimate;
        }
        2 => {
            estimate.verdict = Verdict::NotEstimated(
                "two grids: no order observed (the grid at four times the spacing was not solved)"
                    .into(),
            );
            return estimate;
        }
        _ => {}
    }
    let (e21, e32) = (values[1] - f1, values[2] - values[1]);
    let (r21, r32) = (spacings[1] / spacings[0], spacings[2] / spacings[1]);
    if e21.abs() <= tol {
        estimate.verdict = Verdict::NotEstimated(
            "the two finest grids agree to rounding and the coarsest does not: no order observed"
                .into(),
        );
        return estimate;
    }
    if e32.abs() <= tol {
        estimate.verdict = Verdict::NotEstimated(
            "the two coarser grids agree to rounding and the finest does not: no order observed"
                .into(),
        );
        return estimate;
    }
    let s = (e32 / e21).signum();
    let Some(p) = observed_order(e21, e32, r21, r32, s) else {
        estimate.verdict = Verdict::NotEstimated("the observed order could not be computed".into());
        return estimate;
    };
    estimate.order = Some(p);
    if p < STEEPEST_GROWTH {
        estimate.verdict = Verdict::NotEstimated(format!(
            "the changes grow faster than a contact singularity makes them (observed order \
             {p:.2} below {STEEPEST_GROWTH}): the coarser grids are outside the range where the \
             error follows a power of the spacing"
        ));
        return estimate;
    }
    let slowest = if s > 0.0 { SLOWEST_ORDER } else { 0.0 };
    if !(p > slowest) {
        estimate.verdict = Verdict::NotConverging;
        return estimate;
    }
    let denominator = r21.powf(p.min(FORMAL_ORDER)) - s;
    estimate.extrapolated = Some(f1 - s * e21 / denominator);
    estimate.error = Some(e21.abs() / denominator);
    estimate.verdict = Verdict::Converging;
    estimate
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

/// A solution's discretization error: the grids solved (the fine one
/// first) and each quantity's estimate.
#[derive(Debug, Clone, PartialEq)]
pub struct Discretization {
    /// The grids, the fine one first; the values come from those without a
    /// failure.
    pub grids: Vec<GridRun>,
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

    /// Seconds spent on the coarser grids (the estimate's cost).
    pub fn coarse_seconds(&self) -> f64 {
        self.grids.iter().skip(1).map(|g| g.seconds).sum()
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
        let e = estimate(&[f(h[0]), f(h[1]), f(h[2])], &h, 3.0);
        assert_eq!(e.verdict, Verdict::Converging);
        assert!((e.order.unwrap() - 1.5).abs() < 1e-9, "{e:?}");
        assert!((e.extrapolated.unwrap() - 3.0).abs() < 1e-12, "{e:?}");
        assert!((e.error.unwrap() - 0.7 * 0.1f64.powf(1.5)).abs() < 1e-12);
        assert!((e.relative_error().unwrap() - e.error.unwrap() / f(0.1)).abs() < 1e-15);
    }

    #[test]
    fn alternating_errors_follow_the_alternating_model() {
        // f_i = 1 + (-1)^i 0.01 h_i^1 : signs alternate, |error| halves.
        let h = [0.1, 0.2, 0.4];
        let f = [1.0 + 0.01 * 0.1, 1.0 - 0.01 * 0.2, 1.0 + 0.01 * 0.4];
        let e = estimate(&f, &h, 1.0);
        assert_eq!(e.verdict, Verdict::Converging);
        assert!((e.order.unwrap() - 1.0).abs() < 1e-9, "{e:?}");
        assert!((e.extrapolated.unwrap() - 1.0).abs() < 1e-12, "{e:?}");
        assert!((e.error.unwrap() - 0.001).abs() < 1e-12, "{e:?}");
    }

    #[test]
    fn an_order_above_the_formal_one_extrapolates_at_the_formal_one() {
        let f = |h: f64| 1.0 + h.powi(3);
        let h = [0.1, 0.2, 0.4];
        let e = estimate(&[f(0.1), f(0.2), f(0.4)], &h, 1.0);
        assert!((e.order.unwrap() - 3.0).abs() < 1e-9);
        // |e21| / (2^2 - 1) = 0.007 / 3.
        assert!((e.error.unwrap() - 0.007 / 3.0).abs() < 1e-12, "{e:?}");
    }

    #[test]
    fn a_value_growing_without_bound_is_not_converging() {
        // A singular edge's peak: f = h^(-1/2), and a logarithm.
        let h = [0.05, 0.1, 0.2];
        for f in [|h: f64| h.powf(-0.5), |h: f64| (1.0 / h).ln()] {
            let e = estimate(&[f(h[0]), f(h[1]), f(h[2])], &h, 1.0);
            assert_eq!(e.verdict, Verdict::NotConverging, "{e:?}");
            assert_eq!(e.error, None);
        }
        // Alternating changes that grow.
        let e = estimate(&[1.0, 1.1, 1.04], &h, 1.0);
        assert_eq!(e.verdict, Verdict::NotConverging, "{e:?}");
        // Changes growing faster than h^-1: erratic coarse grids.
        let e = estimate(&[1.0, 1.1, 1.12], &h, 1.0);
        assert!(e.verdict.reason().unwrap().contains("faster"), "{e:?}");
    }

    #[test]
    fn equal_values_are_exact_and_too_few_grids_are_said() {
        let h = [0.1, 0.2, 0.4];
        let e = estimate(&[0.0, 1e-20, -1e-20], &h, 1e-3);
        assert_eq!(e.verdict, Verdict::Exact);
        assert_eq!(e.error, Some(0.0));
        let e = estimate(&[1.0, 1.01], &h[..2], 1.0);
        assert!(e.verdict.reason().unwrap().contains("two grids"), "{e:?}");
        assert_eq!(e.values, vec![1.0, 1.01]);
        let e = estimate(&[1.0], &h[..1], 1.0);
        assert_eq!(e.verdict.name(), "not estimated");
        let e = estimate(&[1.0, f64::NAN, 1.0], &h, 1.0);
        assert!(e.verdict.reason().unwrap().contains("not finite"));
        let e = estimate(&[1.0, 1.1, 1.2], &[0.2, 0.1, 0.4], 1.0);
        assert!(e.verdict.reason().unwrap().contains("spacings"));
    }
}
