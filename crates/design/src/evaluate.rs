//! Analysis of a profile correction: every load case solved with the
//! correction added to its initial separations,
//!
//! ```text
//!     eps_k  ->  eps_k + y(s_k),     p_max = max_k F_k / A_k
//! ```
//!
//! each solution certified by elcon-analysis. Used for the re-analysis of
//! every design, for crowns, and for comparing profiles.

use elcon_analysis::{ContactProblem, ContactSolution, Method, Normal, Options};

use crate::{Axis, DesignError, Profile};

/// The certified analysis of one profile under every load case.
#[derive(Debug, Clone)]
pub struct Evaluation {
    /// The profile's drops at each case's points (length).
    pub corrections: Vec<Vec<f64>>,
    /// The contact solution of each load case, with its certificate.
    pub solutions: Vec<ContactSolution>,
    /// p_max = max_k F_k / A_k of each load case (force per length on a
    /// line, per area on a surface).
    pub max_intensities: Vec<f64>,
    /// The worst p_max over the load cases.
    pub worst: f64,
}

impl Evaluation {
    /// The worst `p_max_l / r_l` over the cases (`references` one per case).
    pub fn relative_worst(&self, references: &[f64]) -> f64 {
        self.max_intensities
            .iter()
            .zip(references)
            .map(|(p, r)| p / r)
            .fold(0.0f64, f64::max)
    }
}

/// The load of a case, or an error naming it when the case is displacement
/// controlled (a design evens the pressure under a given load) or folded (a
/// design needs every point's influence coefficients).
pub(crate) fn load_of(case: &ContactProblem, index: usize) -> Result<f64, DesignError> {
    if let Some(f) = case.folding() {
        return Err(DesignError::Incompatible {
            field: "cases",
            reason: format!(
                "load case {index} is folded by its symmetry ({}); a design may break the symmetry and \
                 needs the full problem: build it with ContactProblem::new",
                f.group()
            ),
        });
    }
    match case.loading().normal {
        Normal::Load(p) => Ok(p),
        Normal::Approach(_) => Err(DesignError::Incompatible {
            field: "cases",
            reason: format!(
                "load case {index} is displacement controlled; a design needs every case under a load (Loading::Load)"
            ),
        }),
    }
}

/// How [`evaluate`] analyses the cases: the method and its options, and
/// optionally solutions already known or warm starts, one per case.
#[derive(Debug, Clone, Copy)]
pub struct Analysis<'a> {
    /// The method every case is solved by.
    pub method: Method,
    /// Its options.
    pub options: &'a Options,
    /// Solutions already known: `known[l]`, when given, is case l's
    /// solution with the profile added (solved with `method` and `options`,
    /// e.g. the scene's own analysis as the uncorrected case), taken as it
    /// is instead of being solved again.
    pub known: Option<&'a [Option<&'a ContactSolution>]>,
    /// Warm starts, one per case (the solutions of a neighbouring profile:
    /// a crown search's previous sample, a design's last iterate). Block
    /// principal pivoting then starts from that contact set
    /// ([`ContactProblem::solve_from`]); the answer does not depend on the
    /// start.
    pub starts: Option<&'a [ContactSolution]>,
}

impl<'a> Analysis<'a> {
    /// Every case solved by `method` with `options`, from its own start.
    pub fn new(method: Method, options: &'a Options) -> Self {
        Self {
            method,
            options,
            known: None,
            starts: None,
        }
    }

    /// With solutions already known (see [`Analysis::known`]).
    pub fn with_known(self, known: &'a [Option<&'a ContactSolution>]) -> Self {
        Self {
            known: Some(known),
            ..self
        }
    }

    /// With warm starts (see [`Analysis::starts`]).
    pub fn starting_from(self, starts: &'a [ContactSolution]) -> Self {
        Self {
            starts: Some(starts),
            ..self
        }
    }
}

/// Solves every case with `profile` added to its separations, as
/// `analysis` says.
///
/// # Errors
/// [`DesignError::Incompatible`] for no case, a displacement-controlled
/// case, or known solutions or starts that do not have one entry per case
/// with one value per point; the profile's own errors;
/// [`DesignError::Analysis`] naming the case whose analysis failed.
pub fn evaluate(
    cases: &[ContactProblem],
    axis: Axis,
    profile: &Profile,
    analysis: &Analysis<'_>,
) -> Result<Evaluation, DesignError> {
    let none = vec![None; cases.len()];
    let known = analysis.known.unwrap_or(&none);
    let starts: Vec<Option<&ContactSolution>> = match analysis.starts {
        Some(starts) => starts.iter().map(Some).collect(),
        None => none.clone(),
    };
    evaluate_cases(cases, axis, profile, analysis, known, &starts)
}

/// Solutions given per case (`known`, or warm starts): one entry per case,
/// each with one value per point, or a [`DesignError::Incompatible`] naming
/// `field`.
fn check_given(
    field: &'static str,
    given: &[Option<&ContactSolution>],
    cases: &[ContactProblem],
) -> Result<(), DesignError> {
    if given.len() != cases.len() {
        return Err(DesignError::Incompatible {
            field,
            reason: format!(
                "has {} entries, expected {} (one per load case)",
                given.len(),
                cases.len()
            ),
        });
    }
    for (l, (case, solution)) in cases.iter().zip(given).enumerate() {
        if let Some(solution) = solution
            && solution.pressures.len() != case.points().len()
        {
            return Err(DesignError::Incompatible {
                field,
                reason: format!(
                    "the solution of load case {l} has {} values, the case {} points",
                    solution.pressures.len(),
                    case.points().len()
                ),
            });
        }
    }
    Ok(())
}

/// `case` with `drops` (one per point, length) added to its separations,
/// solved from `start` when one is given: the corrected problem and its
/// solution; `stage` names the analysis in an error.
pub(crate) fn solve_corrected(
    case: &ContactProblem,
    drops: impl Iterator<Item = f64>,
    start: Option<&ContactSolution>,
    method: Method,
    options: &Options,
    stage: &str,
) -> Result<(ContactProblem, ContactSolution), DesignError> {
    let eps: Vec<f64> = case
        .separation()
        .iter()
        .zip(drops)
        .map(|(e, d)| e + d)
        .collect();
    let corrected = case
        .with_separation(eps)
        .map_err(DesignError::analysis(stage))?;
    let solution = match start {
        Some(start) => corrected.solve_from(start, method, options),
        None => corrected.solve(method, options),
    }
    .map_err(DesignError::analysis(stage))?;
    Ok((corrected, solution))
}

/// [`evaluate`] with its known solutions and starts per case: a known
/// solution is taken as it is, a start begins the solve.
fn evaluate_cases(
    cases: &[ContactProblem],
    axis: Axis,
    profile: &Profile,
    analysis: &Analysis<'_>,
    known: &[Option<&ContactSolution>],
    starts: &[Option<&ContactSolution>],
) -> Result<Evaluation, DesignError> {
    if cases.is_empty() {
        return Err(DesignError::Incompatible {
            field: "cases",
            reason: "no load case given".into(),
        });
    }
    check_given("known", known, cases)?;
    check_given("start", starts, cases)?;
    let mut corrections = Vec::with_capacity(cases.len());
    let mut solutions = Vec::with_capacity(cases.len());
    let mut max_intensities = Vec::with_capacity(cases.len());
    for (l, ((case, known), start)) in cases.iter().zip(known).zip(starts).enumerate() {
        load_of(case, l)?;
        let y = profile.separations(&axis.positions(case.points()))?;
        let solution = match known {
            Some(solution) => (*solution).clone(),
            None => {
                let stage = format!("load case {l} with the {} profile", profile.family());
                let drops = y.iter().copied();
                let (method, options) = (analysis.method, analysis.options);
                solve_corrected(case, drops, *start, method, options, &stage)?.1
            }
        };
        max_intensities.push(solution.max_pressure);
        solutions.push(solution);
        corrections.push(y);
    }
    let worst = max_intensities.iter().fold(0.0f64, |a, p| a.max(*p));
    Ok(Evaluation {
        corrections,
        solutions,
        max_intensities,
        worst,
    })
}
