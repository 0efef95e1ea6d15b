//! The best parameter of a one-parameter crown: the crown radius of a
//! circular crown, the design load of a logarithmic crown, or any family
//! given as a function of one positive parameter q.
//!
//! ```text
//!     minimize over q in [q_lo, q_hi]:   max_l p_max_l(q) / r_l      (every load case re-analysed)
//! ```
//!
//! (`r_l` reference intensities, all 1 unless given, as in the design program).
//!
//! A direct search: `samples` values of q spaced evenly in log q, then a
//! golden-section refinement (in log q) between the neighbours of the best
//! sample. Every evaluation is a certified contact analysis. The result is
//! the best of the samples, refined: global over the bracket to the
//! sampling's resolution when the worst p_max is unimodal near its minimum,
//! which the samples make visible ([`CrownSearch::samples`]).

use elcon_analysis::{ContactProblem, Method, Options};

use crate::evaluate::{Analysis, Evaluation, evaluate};
use crate::prepared::reference_intensities;
use crate::{Axis, DesignError, Profile};

/// Golden-section steps of the refinement: the bracket shrinks by 0.618 per
/// step, 40 steps to 4e-9 of its log-width.
const GOLDEN_STEPS: usize = 40;

/// Settings of a crown search.
#[derive(Debug, Clone)]
pub struct SearchOptions {
    /// Samples spaced evenly in log q before the refinement (default 15, at least 3).
    pub samples: usize,
    /// The analysis method (default block principal pivoting).
    pub method: Method,
    /// The analysis options.
    pub options: Options,
    /// Reference intensities r_l, one per case (default: all 1).
    pub reference_intensities: Option<Vec<f64>>,
}

impl Default for SearchOptions {
    fn default() -> Self {
        Self {
            samples: 15,
            method: Method::BlockPivoting,
            options: Options::default(),
            reference_intensities: None,
        }
    }
}

/// The result of a crown search.
#[derive(Debug, Clone)]
pub struct CrownSearch {
    /// The best parameter found.
    pub parameter: f64,
    /// The profile at that parameter.
    pub profile: Profile,
    /// Its certified analysis under every load case.
    pub evaluation: Evaluation,
    /// Every parameter tried with its objective (the worst p_max_l / r_l), in the order tried.
    pub samples: Vec<(f64, f64)>,
}

/// Searches `q` in `[low, high]` (both finite, `0 < low < high`) for the
/// crown `make(q)` with the least worst-case `p_max_l / r_l` over `cases`.
///
/// # Errors
/// [`DesignError::InvalidInput`] for a bad bracket, `samples < 3` or a
/// reference intensity that is not finite and > 0,
/// [`DesignError::Incompatible`] for references that do not match the
/// cases in number; the errors of `make` and of the analyses.
pub fn crown_search(
    cases: &[ContactProblem],
    axis: Axis,
    make: impl Fn(f64) -> Result<Profile, DesignError>,
    low: f64,
    high: f64,
    search: &SearchOptions,
) -> Result<CrownSearch, DesignError> {
    let (samples, method, options) = (search.samples, search.method, &search.options);
    let references = reference_intensities(search.reference_intensities.as_deref(), cases.len())?;
    check_bracket(low, high, samples)?;
    let mut tried = Vec::new();
    // The best so far (the first of equal objectives): parameter, objective,
    // profile, and its evaluation, kept rather than recomputed.
    let mut found: Option<(f64, f64, Profile, Evaluation)> = None;
    let mut worst_at = |log_q: f64| -> Result<f64, DesignError> {
        let q = log_q.exp();
        let profile = make(q)?;
        // Warm-started from the best evaluation so far: the samples close in
        // on it, so its contact sets are the nearest at hand.
        let e = match &found {
            Some((.., best)) => evaluate(
                cases,
                axis,
                &profile,
                &Analysis::new(method, options).starting_from(&best.solutions),
            )?,
            None => evaluate(cases, axis, &profile, &Analysis::new(method, options))?,
        };
        let objective = e.relative_worst(&references);
        tried.push((q, objective));
        if found
            .as_ref()
            .is_none_or(|b| objective.total_cmp(&b.1).is_lt())
        {
            found = Some((q, objective, profile, e));
        }
        Ok(objective)
    };
    let (a, b) = (low.ln(), high.ln());
    let grid: Vec<f64> = (0..samples)
        .map(|i| a + (b - a) * i as f64 / (samples - 1) as f64)
        .collect();
    let values: Vec<f64> = grid
        .iter()
        .map(|&g| worst_at(g))
        .collect::<Result<_, _>>()?;
    let best = (0..samples)
        .min_by(|&i, &j| values[i].total_cmp(&values[j]))
        .unwrap_or(0);
    let bracket = (
        grid[best.saturating_sub(1)],
        grid[(best + 1).min(samples - 1)],
    );
    golden_section(bracket, &mut worst_at)?;
    let (parameter, _, profile, evaluation) = found.expect("samples were tried");
    Ok(CrownSearch {
        parameter,
        profile,
        evaluation,
        samples: tried,
    })
}

/// Checks the bracket `[low, high]` (finite, `0 < low < high`) and the
/// samples (at least 3).
fn check_bracket(low: f64, high: f64, samples: usize) -> Result<(), DesignError> {
    elcon_num::check([
        (
            low.is_finite() && low > 0.0,
            "low",
            low,
            "must be finite and > 0",
        ),
        (
            high.is_finite() && high > low,
            "high",
            high,
            "must be finite and > low",
        ),
        (
            samples >= 3,
            "samples",
            samples as f64,
            "at least 3 samples",
        ),
    ])?;
    Ok(())
}

/// The golden-section refinement of `f`'s minimum in `(lo, hi)`,
/// [`GOLDEN_STEPS`] steps (`f` keeps what it finds).
fn golden_section(
    (mut lo, mut hi): (f64, f64),
    f: &mut impl FnMut(f64) -> Result<f64, DesignError>,
) -> Result<(), DesignError> {
    let ratio = 0.5 * (5f64.sqrt() - 1.0);
    let mut x1 = hi - ratio * (hi - lo);
    let mut x2 = lo + ratio * (hi - lo);
    let mut f1 = f(x1)?;
    let mut f2 = f(x2)?;
    for _ in 0..GOLDEN_STEPS {
        if f1 <= f2 {
            hi = x2;
            x2 = x1;
            f2 = f1;
            x1 = hi - ratio * (hi - lo);
            f1 = f(x1)?;
        } else {
            lo = x1;
            x1 = x2;
            f1 = f2;
            x2 = lo + ratio * (hi - lo);
            f2 = f(x2)?;
        }
    }
    Ok(())
}
