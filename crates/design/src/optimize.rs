//! The paper's design problem: the profile correction of a linear family
//! that minimizes the maximum load intensity (Conry & Seireg 1971, eq. 16),
//! over several load cases at once,
//!
//! ```text
//!     minimize over theta:   max_l max_k F_lk(theta) / (r_l A_k)
//! ```
//!
//! where `F_l(theta)` is case l's contact solution with the separations
//! `eps_l + Phi_l theta` (`y(s) = sum_i theta_i phi_i(s)`), `A_k` the
//! points' measures and `r_l` reference intensities (default 1).
//!
//! [`design`] routes one strategy: the starts (the uncorrected geometry, as
//! in the paper; for line contacts the least-squares fit of the
//! uniform-pressure separation, the paper's own comparison; and any profiles
//! the caller gives), each solved by the method [`DesignMethod`] names (the
//! paper's program, `crate::lpcc`, or the case-decomposed descent,
//! `crate::descent`), the best kept. Both end at a local minimum of a
//! non-convex problem (the paper says so too): on a flexible beam over a
//! stiff foundation the uncorrected start ends with the load on the few
//! points under it, which is why there are several starts. Neither ends
//! worse than its start. Every design is re-analysed with elcon-analysis;
//! its objective and the re-analysis' agree to [`DesignOptions::agreement`]
//! or the design is an error. The constant c has an upper bound (the
//! paper's c_max): a uniform separation only shifts the approach, and the
//! bound keeps the profile's depth finite.

use elcon_analysis::{ContactProblem, RigidMode};
use elcon_influence::Dimension;

use crate::basis::Basis;
use crate::evaluate::{Analysis, Evaluation, evaluate};
use crate::found::Found;
use crate::prepared::{
    Case, Solver, axial_stations, deflection_scale, prepare, reference_intensities,
};
use crate::subsurface::{Criterion, StressObjective};
use crate::target::uniform_target;
use crate::{
    Axis, DesignError, DesignMethod, DesignOptions, Family, ITERATIVE_AGREEMENT, Objective, Profile,
};
use crate::{descent, lpcc};

/// How one start ended.
#[derive(Debug, Clone)]
pub struct StartOutcome {
    /// "uncorrected", "fitted uniform-pressure separation", or "given start i".
    pub label: String,
    /// The objective it reached (the worst p_max_l / r_l), or why it failed.
    pub result: Result<f64, DesignError>,
    /// Engine pivots of its solve (the program's; the descent's analyses'
    /// and linear programs' together).
    pub pivots: usize,
}

/// A certified design.
#[derive(Debug, Clone)]
pub struct Design {
    /// The correction, shifted so that its smallest drop over the stations is 0.
    pub profile: Profile,
    /// The axial stations (distinct axial positions of the points; length).
    pub stations: Vec<f64>,
    /// The method's objective: the worst `p_max_l / r_l` over the cases
    /// (the worst p_max when every r_l = 1), from its own solutions; for a
    /// stress objective ([`Design::criterion`]) the worst stress over r_l.
    pub objective: f64,
    /// The method's worst load intensity over the cases, max_k F_k / A_k.
    pub max_intensity: f64,
    /// The re-analysis with elcon-analysis: each case's certified solution.
    pub evaluation: Evaluation,
    /// Every start and where it ended.
    pub starts: Vec<StartOutcome>,
    /// How the chosen start was solved: the program's certificate and
    /// statistics, or the descent's iterations.
    pub solver: Solver,
    /// The bound c_max used (polynomial families).
    pub max_constant: Option<f64>,
    /// What it minimized ([`DesignOptions::objective`]); `objective` is
    /// the worst stress over r_l for a stress objective.
    pub criterion: Objective,
    /// For a stress objective, the worst stress measure over the cases
    /// (stress) of the re-analysis, on each case's grid of depths.
    pub worst_stress: Option<f64>,
    /// Whether the normalized constant (smallest drop 0) needs the whole of
    /// c_max: the bound then limits the design; raise it.
    pub constant_at_bound: bool,
}

/// What every start shares.
struct Setup<'a> {
    cases: &'a [ContactProblem],
    prepared: Vec<Case<'a>>,
    basis: Basis,
    family: Family,
    axis: Axis,
    stations: Vec<f64>,
    c_max: Option<f64>,
    /// The cases' largest elastic deflection under a uniform pressure
    /// (length).
    scale: f64,
    /// Whether every case leaves the rotation about the axis across the
    /// profile free: a straight line added to the profile then changes no
    /// force (the rotation and the approach absorb it), and the design's
    /// profile is given without one.
    line_free: bool,
    method: DesignMethod,
    /// The stress objective, if the design minimizes one.
    stress: Option<StressObjective>,
    /// The agreement the re-analysis is held to: the options', or
    /// [`ITERATIVE_AGREEMENT`] if larger when the cases are solved by the
    /// conjugate gradient (matrix-free, or `options.reanalysis`).
    agreement: f64,
}

/// Designs the correction of `family` that minimizes the worst load
/// intensity over `cases` (each under load control, [`elcon_analysis::Normal::Load`]);
/// see the [module documentation](self) for the method and what it guarantees.
///
/// # Errors
/// [`DesignError::Incompatible`] for no case, a displacement-controlled
/// or folded case, a `reanalysis` method a case cannot be solved by (a
/// pivoting method on a matrix-free S), or a degree the stations cannot
/// carry; [`DesignError::Analysis`] for [`DesignMethod::Program`] on a case
/// that holds S without its entries (matrix-free);
/// [`DesignError::InvalidInput`] for a bad `max_constant`, `agreement` or
/// `max_iterations`; [`DesignError::Engine`] or [`DesignError::Analysis`]
/// when every start failed (the first start's error);
/// [`DesignError::Disagreement`] when the best design's re-analysis does
/// not reproduce its objective.
pub fn design(
    cases: &[ContactProblem],
    axis: Axis,
    family: Family,
    options: &DesignOptions,
) -> Result<Design, DesignError> {
    let mut setup = setup(cases, axis, family, options)?;
    let starts = starts(&setup, options)?;
    setup.c_max = max_constant(&setup, &starts, options.max_constant);
    let mut outcomes = Vec::new();
    let mut best: Option<Design> = None;
    let mut first_error = None;
    for (label, theta0) in &starts {
        match run_start(&setup, theta0, options) {
            Ok(d) => {
                let pivots = match &d.solver {
                    Solver::Program { statistics, .. } => statistics.pivots(),
                    Solver::Descent { pivots, .. } => *pivots,
                };
                outcomes.push(StartOutcome {
                    label: label.clone(),
                    result: Ok(d.objective),
                    pivots,
                });
                if best.as_ref().is_none_or(|b| d.objective < b.objective) {
                    best = Some(d);
                }
            }
            Err(e) => {
                outcomes.push(StartOutcome {
                    label: label.clone(),
                    result: Err(e.clone()),
                    pivots: 0,
                });
                first_error.get_or_insert(e);
            }
        }
    }
    match (best, first_error) {
        (Some(mut d), _) => {
            d.starts = outcomes;
            Ok(d)
        }
        // The program chosen by `Auto` ended without its certificate (its
        // tableau mixes forces, lengths and intensities, and a problem
        // whose scales lie decades apart, a stiff beam on a soft
        // foundation, can leave it short of the engine's tolerance): the
        // descent, which solves the same problem by analyses alone, takes
        // over.
        (None, Some(DesignError::Engine(elcon_lcp::LcpError::Inaccurate { .. })))
            if options.method == DesignMethod::Auto && setup.method == DesignMethod::Program =>
        {
            let descent = DesignOptions {
                method: DesignMethod::Descent,
                ..options.clone()
            };
            design(cases, axis, family, &descent)
        }
        (None, Some(e)) => Err(e),
        (None, None) => Err(DesignError::Incompatible {
            field: "starts",
            reason: "no start to design from".into(),
        }),
    }
}

/// The options checked, the cases prepared, the basis, c_max and the method.
fn setup<'a>(
    cases: &'a [ContactProblem],
    axis: Axis,
    family: Family,
    options: &DesignOptions,
) -> Result<Setup<'a>, DesignError> {
    if cases.is_empty() {
        return Err(DesignError::Incompatible {
            field: "cases",
            reason: "no load case given".into(),
        });
    }
    let agreement = options.agreement;
    let max_constant = options.max_constant;
    elcon_num::check([
        (
            agreement.is_finite() && agreement > 0.0 && agreement < 1.0,
            "agreement",
            agreement,
            "must be in (0, 1)",
        ),
        (
            max_constant.is_none_or(|c| c.is_finite() && c > 0.0),
            "max_constant",
            max_constant.unwrap_or_default(),
            "must be finite and > 0",
        ),
        (
            options.max_iterations > 0,
            "max_iterations",
            0.0,
            "the descent needs at least one iteration",
        ),
    ])?;
    let references = reference_intensities(options.reference_intensities.as_deref(), cases.len())?;
    let (stations, index) = axial_stations(cases.iter().map(ContactProblem::points), axis);
    let basis = Basis::new(family, &stations, options.knots.as_deref())?;
    let prepared = prepare(cases, index, &references, (options.edge_clearance, axis))?;
    let mut scale = 0.0f64;
    for case in &prepared {
        scale = scale.max(deflection_scale(case)?);
    }
    let points: usize = prepared.iter().map(|c| c.station.len()).sum();
    for case in cases {
        case.check_method(options.reanalysis)
            .map_err(|e| DesignError::Incompatible {
                field: "reanalysis",
                reason: e.to_string(),
            })?;
    }
    let entries = cases
        .iter()
        .all(|c| c.entries("the design program").is_ok());
    let across = match axis {
        Axis::X => RigidMode::TiltY,
        Axis::Y => RigidMode::TiltX,
    };
    let line_free = cases
        .iter()
        .all(|c| c.rigid().prescribed.iter().all(|&(mode, _)| mode != across));
    let stress = StressObjective::new(options.objective, &options.bodies)?;
    let method = match (stress.is_some(), options.method) {
        (false, method) => method.admits(entries)?.resolve(points, entries),
        (true, DesignMethod::Program) => {
            return Err(DesignError::Objective {
                objective: options.objective.name(),
                reason:
                    "the design program's objective is linear in the forces; a stress below the \
                         surface is minimized by method = \"descent\" (or \"auto\")"
                        .into(),
            });
        }
        (true, _) => DesignMethod::Descent,
    };
    // The cases are solved iteratively (a matrix-free case can be solved no
    // other way: `check_method`).
    let agreement = if options.reanalysis == elcon_analysis::Method::ConjugateGradient {
        options.agreement.max(ITERATIVE_AGREEMENT)
    } else {
        options.agreement
    };
    Ok(Setup {
        cases,
        prepared,
        basis,
        family,
        axis,
        stations,
        c_max: None,
        scale,
        line_free,
        method,
        stress,
        agreement,
    })
}

/// The starts: the uncorrected geometry; for line contacts, the fit of the
/// uniform-pressure separation of the heaviest case; the given profiles.
fn starts(
    setup: &Setup<'_>,
    options: &DesignOptions,
) -> Result<Vec<(String, Vec<f64>)>, DesignError> {
    let basis = &setup.basis;
    let mut starts: Vec<(String, Vec<f64>)> = Vec::new();
    if options.uncorrected_start {
        starts.push(("uncorrected".into(), vec![0.0; basis.params()]));
    }
    let prepared = &setup.prepared;
    let heaviest = (0..prepared.len())
        .max_by(|&a, &b| prepared[a].load.total_cmp(&prepared[b].load))
        .unwrap_or(0);
    let line = setup
        .cases
        .iter()
        .all(|c| c.points().dimension() == Dimension::Line);
    if options.fitted_start && line {
        let target = uniform_target(&setup.cases[heaviest])?;
        let mut y = vec![0.0; setup.stations.len()];
        for (k, &st) in prepared[heaviest].station.iter().enumerate() {
            y[st] = target.correction[k];
        }
        starts.push(("fitted uniform-pressure separation".into(), basis.fit(&y)));
    }
    for (i, profile) in options.starts.iter().enumerate() {
        let y = profile.separations(&setup.stations)?;
        starts.push((
            format!("given start {i} ({})", profile.family()),
            basis.fit(&y),
        ));
    }
    Ok(starts)
}

/// The bound c_max: given, or ten times the elastic deflection scale and at
/// least twice the largest constant of a start.
fn max_constant(
    setup: &Setup<'_>,
    starts: &[(String, Vec<f64>)],
    given: Option<f64>,
) -> Option<f64> {
    setup.basis.constant.map(|ci| {
        given.unwrap_or_else(|| {
            let fitted = starts.iter().map(|(_, th)| th[ci]).fold(0.0f64, f64::max);
            (10.0 * setup.scale).max(2.0 * fitted)
        })
    })
}

/// The design's objective and its re-analysis' must agree to `tolerance`
/// (relative), or the design is refused.
fn agree(design: f64, reanalysis: f64, tolerance: f64) -> Result<(), DesignError> {
    let relative = (reanalysis - design).abs() / design;
    if relative <= tolerance {
        Ok(())
    } else {
        Err(DesignError::Disagreement {
            design,
            reanalysis,
            relative,
            tolerance,
        })
    }
}

/// One start solved by the setup's method, then re-analysed.
fn run_start(
    setup: &Setup<'_>,
    theta0: &[f64],
    options: &DesignOptions,
) -> Result<Design, DesignError> {
    let found = match setup.method {
        DesignMethod::Descent => descent::solve(
            &setup.prepared,
            &setup.basis,
            (setup.c_max, setup.stress.as_ref()),
            theta0,
            setup.scale,
            options,
        )?,
        _ => program(setup, theta0, options)?,
    };
    finish(setup, found, options)
}

/// The design program from `theta0`, every case's rotations free (a
/// correction may break a case's symmetry, and its re-analysis then frees
/// them); when the engine finds no complementary start so, again with the
/// rotations a symmetric case's analysis holds at zero.
fn program(
    setup: &Setup<'_>,
    theta0: &[f64],
    options: &DesignOptions,
) -> Result<Found, DesignError> {
    let solve =
        |cases: &[Case<'_>]| lpcc::solve(cases, &setup.basis, setup.c_max, theta0, &options.engine);
    match solve(&setup.prepared) {
        Err(DesignError::Engine(elcon_lcp::LcpError::Infeasible { .. }))
            if setup.prepared.iter().any(Case::holds_rotations) =>
        {
            let held: Vec<Case<'_>> = setup.prepared.iter().map(Case::held).collect();
            solve(&held)
        }
        found => found,
    }
}

/// The profile of what a start found (smallest drop 0), re-analysed and
/// checked against the method's objective.
fn finish(setup: &Setup<'_>, found: Found, options: &DesignOptions) -> Result<Design, DesignError> {
    let Found {
        theta,
        objective,
        max_intensity,
        solutions,
        solver,
        criterion,
    } = found;
    let theta = if setup.line_free {
        setup.basis.without_line(&theta)
    } else {
        theta
    };
    let profile = setup.basis.profile(setup.family, &setup.stations, &theta);
    let (method, reanalysis) = (options.reanalysis, &options.reanalysis_options);
    let evaluation = match solutions {
        Some(previous) => evaluate(
            setup.cases,
            setup.axis,
            &profile,
            &Analysis::new(method, reanalysis).starting_from(&previous),
        )?,
        None => evaluate(
            setup.cases,
            setup.axis,
            &profile,
            &Analysis::new(method, reanalysis),
        )?,
    };
    // The re-analysis measured as the method measured its own solutions
    // (the worst p_max_l / r_l, edges weighted when they are kept clear).
    let mut reanalysed = 0.0f64;
    let mut worst_stress = None;
    for (l, (c, s)) in setup.prepared.iter().zip(&evaluation.solutions).enumerate() {
        let (merit, largest) = criterion.merit(l, c, s)?;
        reanalysed = reanalysed.max(merit);
        if let Some(largest) = largest {
            worst_stress = Some(worst_stress.map_or(largest, |w: f64| w.max(largest)));
        }
    }
    agree(objective, reanalysed, setup.agreement)?;
    // A uniform shift of the profile only moves the approach, so the bound
    // constrains the design only if the normalized profile (smallest drop 0)
    // still needs the whole of it.
    let constant_at_bound = match (&profile, setup.c_max) {
        (Profile::Quadratic { c, .. }, Some(c_max)) => *c >= (1.0 - 1e-9) * c_max,
        (Profile::Polynomial { coefficients }, Some(c_max)) => {
            coefficients[0] >= (1.0 - 1e-9) * c_max
        }
        _ => false,
    };
    Ok(Design {
        profile,
        stations: setup.stations.clone(),
        objective,
        max_intensity,
        evaluation,
        starts: Vec::new(),
        solver,
        max_constant: setup.c_max,
        constant_at_bound,
        criterion: match &criterion {
            Criterion::Pressure => Objective::Pressure,
            Criterion::Stress(s) => s.objective(),
        },
        worst_stress,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_reanalysis_that_disagrees_refuses_the_design() {
        assert!(agree(100.0, 100.0 * (1.0 + 1e-12), 1e-9).is_ok());
        let e = agree(100.0, 101.0, 1e-9).unwrap_err();
        assert!(matches!(e, DesignError::Disagreement { .. }));
        assert_eq!(
            e.to_string(),
            "the design's objective 1.000000e2 and its re-analysis' 1.010000e2 differ by 1.00e-2 relative \
             (tolerance 1.0e-9)"
        );
        // NaN never agrees.
        assert!(agree(100.0, f64::NAN, 1e-9).is_err());
    }

    #[test]
    fn a_case_solved_by_the_conjugate_gradient_is_held_to_the_iterative_agreement() {
        use elcon_analysis::Storage;
        use elcon_fixtures::design_cases::aligned_roller;
        let roller = |storage| aligned_roller(5e3, (5, 12), storage).unwrap().0;
        let (dense, lattice) = (roller(Storage::Dense), roller(Storage::Lattice));
        let options = DesignOptions {
            reanalysis: elcon_analysis::Method::ConjugateGradient,
            ..DesignOptions::default()
        };
        let agreement = |case: &ContactProblem, options: &DesignOptions| {
            setup(
                std::slice::from_ref(case),
                Axis::Y,
                Family::Quadratic,
                options,
            )
            .unwrap()
            .agreement
        };
        assert_eq!(agreement(&dense, &DesignOptions::default()), 1e-9);
        assert_eq!(agreement(&lattice, &options), ITERATIVE_AGREEMENT);
        // A dense case re-analysed by the conjugate gradient as well.
        assert_eq!(agreement(&dense, &options), ITERATIVE_AGREEMENT);
        // A looser agreement asked for is kept.
        let loose = DesignOptions {
            agreement: 1e-3,
            ..options
        };
        assert_eq!(agreement(&lattice, &loose), 1e-3);
    }
}
