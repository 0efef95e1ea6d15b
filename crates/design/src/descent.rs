//! The case-decomposed design method: the min-max problem of a linear
//! family, solved as an outer problem over the profile parameters theta
//! with every load case an analysis.
//!
//! Once theta is fixed the problem decomposes by case: case l's forces
//! `F_l(theta)` are its contact solution with the separations
//! `eps_l + Phi_l theta`, unique because S is positive definite, and
//! piecewise linear in theta. The objective
//!
//! ```text
//!     f(theta) = max_l max_k F_lk(theta) / (r_l A_k)
//! ```
//!
//! is minimized by a trust-region sequential linear program (Madsen's
//! minimax method). At theta, each case's contact set J gives the exact
//! derivative of its forces while J holds: with the free rigid motions'
//! levers L_J (the approach, free tilts) and the profile's basis D_J = Phi
//! at the points of J,
//!
//! ```text
//!     S_JJ X - L_J Lambda = -D_J,     L_J^T X = 0       X = dF_J / dtheta, Lambda = d lambda / dtheta
//! ```
//!
//! (m + k right-hand sides of the case's restricted solve,
//! `ContactProblem::restricted_solve`: a Cholesky factor of S_JJ where S is
//! dense, conjugate gradients on its products where it is matrix-free).
//! The step d solves the
//! linear program
//!
//! ```text
//!     minimize t   subject to   (F_lk + X_lk d) / (r_l A_k) <= t   (every case l, k in J_l)
//!                               -Phi'_st (theta' + d') <= c_max    (every station: the normalized constant)
//!                               |d_i| <= Delta                     (the trust region)
//! ```
//!
//! by its dual on the engine (one row per parameter, one column per
//! constraint: a small tableau however many cases). Every case is
//! then re-analysed at theta + d, warm-started from its contact set; the
//! step is taken when f falls by a fraction of the model's prediction, and
//! Delta shrinks when the model was wrong (a contact set changed) and grows
//! when it was right up to its edge.
//!
//! Cost per iteration: one analysis and one restricted solve per case, S
//! shared: linear in the cases, where the paper's program over every case
//! at once grows with their square. Memory: S as its case holds it, one
//! contact block at a time (none matrix-free: a design on a large grid
//! never forms S). What is guaranteed: the objective never rises from the
//! start; the method stops at a point where the linear model of every
//! case's contact set predicts no decrease (a stationary point of the
//! piecewise-linear min-max problem), a local minimum as the program's is.
//! A uniform shift of the profile only moves the approach (every case is
//! under load control), so the drops are normalized (smallest 0) only at
//! the end, and `Phi theta >= 0` is never a constraint of the steps.
//!
//! A stress objective (`DesignOptions::objective`: the worst von Mises or
//! largest shear stress below the surface) measures each case by
//! `crate::subsurface` and takes its model rows from there, with the same X.

use crate::dense;
use elcon_analysis::{ContactProblem, ContactSolution};
use elcon_lcp::{Bound, LcpError, ProgramBuilder};
use faer::{Col, Mat};

use crate::DesignError;
use crate::DesignOptions;
use crate::basis::Basis;
use crate::constraint::Constraint;
use crate::evaluate::solve_corrected;
use crate::found::Found;
use crate::prepared::{Case, Solver, Stop};
use crate::subsurface::{Criterion, StressObjective};

/// Stationarity: the model's predicted decrease below this fraction of the
/// objective ends the descent. The forces are certified to about 1e-13 of
/// the load, so a prediction below 1e-12 of the peak is rounding.
const STATIONARY: f64 = 1e-12;
/// A step is taken when the objective falls by at least this fraction of
/// the predicted decrease (any true decrease, allowing for rounding).
const ACCEPT: f64 = 1e-4;
/// The largest violation of a step's constraint (relative to its terms'
/// size) accepted from the step's basis: rounding of an (m + 1)-square
/// solve, far above it, far below any model error that matters.
const STEP_FEASIBILITY: f64 = 1e-9;
/// Below this ratio of actual to predicted decrease the trust region
/// shrinks to a quarter of the step; above `EXPAND`, with the step at its
/// edge, it doubles.
const SHRINK: f64 = 0.25;
/// See [`SHRINK`].
const EXPAND: f64 = 0.75;
/// The descent ends when the trust region is below this fraction of the
/// cases' elastic deflection: the drops change by less than the rounding
/// of the separations they are added to.
const RESOLUTION: f64 = 1e-13;

/// Every case analysed at one theta.
struct Iterate {
    theta: Vec<f64>,
    /// The cases with the drops added (their rigid unknowns as the
    /// analysis used them).
    problems: Vec<ContactProblem>,
    solutions: Vec<ContactSolution>,
    /// `f(theta)`, the worst `w_k p_k / r_l` (the worst `p_max_l / r_l`
    /// when no weight is set, or the edges are out of contact).
    objective: f64,
}

/// Analyses every case at `theta`, warm-started from `previous`, each
/// measured by `criterion`.
fn analyse(
    cases: &[Case<'_>],
    basis: &Basis,
    theta: Vec<f64>,
    previous: Option<&[ContactSolution]>,
    (options, criterion): (&DesignOptions, &Criterion),
) -> Result<Iterate, DesignError> {
    let drops = basis.drops(&theta);
    let mut problems = Vec::with_capacity(cases.len());
    let mut solutions = Vec::with_capacity(cases.len());
    let mut objective = 0.0f64;
    for (l, case) in cases.iter().enumerate() {
        let (problem, solution) = solve_corrected(
            case.problem,
            case.station.iter().map(|&st| drops[st]),
            previous.map(|p| &p[l]),
            options.reanalysis,
            &options.reanalysis_options,
            &format!("load case {l} in the design's descent"),
        )?;
        objective = objective.max(criterion.merit(l, case, &solution)?.0);
        problems.push(problem);
        solutions.push(solution);
    }
    Ok(Iterate {
        theta,
        problems,
        solutions,
        objective,
    })
}

/// Case l's model rows at its solution: for each point in contact its
/// intensity over r_l and the derivative of that with respect to theta
/// (or, for a stress criterion, its rows: `crate::subsurface`).
fn model_rows(
    (l, case): (usize, &Case<'_>),
    problem: &ContactProblem,
    solution: &ContactSolution,
    basis: &Basis,
    (reanalysis, criterion): (&elcon_lcp::Options, &Criterion),
) -> Result<Vec<Constraint>, DesignError> {
    let contact = &solution.contact;
    if contact.is_empty() {
        return Ok(Vec::new());
    }
    let x = sensitivities(case, problem, solution, basis, reanalysis)?;
    if let Criterion::Stress(stress) = criterion {
        return stress.rows(l, case, solution, x.as_ref());
    }
    let m = basis.params();
    Ok((0..contact.len())
        .map(|a| {
            let k = contact[a];
            let scale = case.reference * case.measures[k] / case.weights[k];
            Constraint {
                a: (0..m).map(|i| x[(a, i)] / scale).collect(),
                t_coefficient: -1.0,
                b: -solution.forces[k] / scale,
            }
        })
        .collect())
}

/// `X = dF_J / dtheta` of case l's contact set J at its solution (|J| x m).
pub(crate) fn sensitivities(
    case: &Case<'_>,
    problem: &ContactProblem,
    solution: &ContactSolution,
    basis: &Basis,
    reanalysis: &elcon_lcp::Options,
) -> Result<Mat<f64>, DesignError> {
    let contact = &solution.contact;
    let (nj, m) = (contact.len(), basis.params());
    let rigid = problem.rigid();
    let points = problem.points();
    let levers = Mat::from_fn(nj, rigid.free.len(), |a, j| {
        let k = contact[a];
        rigid.free[j]
            .0
            .lever((points.x(k), points.y(k)), rigid.load_point)
    });
    // X = -V + U Lambda with U = S^-1 L, V = S^-1 D and (L^T U) Lambda = L^T V:
    // both from one factor (or one set of CG solves), the right-hand side
    // [L | D].
    let k = levers.ncols();
    let rhs = Mat::from_fn(nj, k + m, |a, c| {
        if c < k {
            levers[(a, c)]
        } else {
            basis.phi[(case.station[contact[a]], c - k)]
        }
    });
    let solved = problem
        .restricted_solve(contact, rhs.as_ref(), reanalysis)
        .map_err(DesignError::analysis("a design sensitivity"))?
        .x;
    let (u, v) = (solved.subcols(0, k), solved.subcols(k, m));
    let x = if k == 0 {
        -v
    } else {
        let reduced = dense::product(levers.transpose(), u);
        let lambda = dense::lu_solve(
            reduced.as_ref(),
            dense::product(levers.transpose(), v).as_ref(),
        );
        dense::product(u, lambda.as_ref()) - v
    };
    Ok(x)
}

/// The bounds on the normalized constant of a polynomial family at every
/// station: `-sum_{i != c} Phi[st, i] (theta_i + d_i) <= c_max`.
fn constant_rows(basis: &Basis, theta: &[f64], c_max: Option<f64>) -> Vec<Constraint> {
    let (Some(ci), Some(c_max)) = (basis.constant, c_max) else {
        return Vec::new();
    };
    (0..basis.phi.nrows())
        .map(|st| {
            let row = |i: usize| if i == ci { 0.0 } else { basis.phi[(st, i)] };
            Constraint {
                a: (0..theta.len()).map(|i| -row(i)).collect(),
                t_coefficient: 0.0,
                b: c_max + (0..theta.len()).map(|i| row(i) * theta[i]).sum::<f64>(),
            }
        })
        .collect()
}

/// The step of least model objective within the trust region: the step,
/// the model's objective there, and the engine's pivots.
///
/// Solved as the dual of the step's program, which has one row per
/// parameter and one for t, and one column per constraint (the model rows
/// of every case, the bounds, the trust region `|d_i| <= radius`):
///
/// ```text
///     minimize b . y   subject to   sum_r y_r a_r = 0,   sum_(model rows) y_r = 1,   y >= 0
/// ```
///
/// Its optimum is `-t`, and the step is read from the final basis B
/// (the simplex multipliers pi of `B^T pi = b_B`: `d = pi_(1..m)`,
/// `t = -pi_(m+1)`). The trust region's `d_i <= radius` is a unit column in
/// row i and the lower bound `t >= floor` (implied: no intensity can fall
/// below its lowest reach) one in the last row, so the start is a feasible
/// basis of unit columns and no artificial is ever basic.
fn step(
    pool: &[Constraint],
    m: usize,
    radius: f64,
    engine: &elcon_lcp::Options,
) -> Result<(Vec<f64>, f64, usize), DesignError> {
    // The model's objective is at least the largest lower reach of any
    // intensity; a constraint that cannot reach it never binds.
    let floor = pool
        .iter()
        .filter(|c| c.t_coefficient != 0.0)
        .map(|c| -c.b - c.a.iter().map(|v| v.abs()).sum::<f64>() * radius)
        .fold(f64::NEG_INFINITY, f64::max);
    // The unit columns first (the start basis): d_i <= radius in row i,
    // t >= floor in the last row; then d_i >= -radius and the live
    // constraints.
    let bound = |i: usize, sign: f64| Constraint {
        a: (0..m).map(|j| if j == i { sign } else { 0.0 }).collect(),
        t_coefficient: 0.0,
        b: radius,
    };
    let mut own: Vec<Constraint> = (0..m).map(|i| bound(i, 1.0)).collect();
    own.push(Constraint {
        a: vec![0.0; m],
        t_coefficient: -1.0,
        b: -floor,
    });
    own.extend((0..m).map(|i| bound(i, -1.0)));
    let live = pool.iter().filter(|c| {
        let reach = c.reach(radius);
        if c.t_coefficient != 0.0 {
            reach >= floor
        } else {
            reach > 0.0
        }
    });
    let columns: Vec<&Constraint> = own.iter().chain(live).collect();
    let rows = m + 1;
    let entry = |r: usize, c: &Constraint| if r < m { c.a[r] } else { -c.t_coefficient };
    let block = Mat::from_fn(rows, columns.len() - rows, |r, j| {
        entry(r, columns[rows + j])
    });
    let mut program = ProgramBuilder::new(rows);
    let units = program.unit_columns("unit", 0..rows, 1.0, Bound::NonNegative)?;
    let dense = program.dense_columns("y", block.as_ref(), Bound::NonNegative)?;
    for (j, c) in units.chain(dense).zip(&columns) {
        program.cost(j, c.b)?;
    }
    let rhs = Col::from_fn(rows, |r| f64::from(r == m));
    program.rhs(rhs.as_ref())?;
    let program = program.build()?;
    // The step is only as good as the basis it is read from, and that is
    // checked to STEP_FEASIBILITY (`read_step`): the engine's certificate is
    // held to the same (a model's rows weighted to keep edges clear span a
    // wider range than its data's rounding).
    let mut engine = engine.clone();
    engine.tolerances.certificate = engine.tolerances.certificate.max(STEP_FEASIBILITY);
    // The engine's equilibration can end phase 2 at a basis whose
    // multipliers are not a feasible step (rows of parameters whose model
    // columns nearly depend on one another over the grid: a polynomial of
    // degree 4 on a disk); the same program unscaled is the fallback, its
    // step checked alike.
    let mut pivots = 0;
    let mut failure = None;
    for equilibrate in [engine.equilibrate, !engine.equilibrate] {
        engine.equilibrate = equilibrate;
        match program.solve(&engine) {
            Ok(solution) => {
                pivots += solution.statistics.pivots();
                if let Some((d, t)) = read_step(&solution.basis, &columns, own.len(), m, radius) {
                    return Ok((d, t, pivots));
                }
            }
            Err(LcpError::Cancelled) => return Err(LcpError::Cancelled.into()),
            Err(e) => failure = Some(e),
        }
    }
    Err(DesignError::Incompatible {
        field: "cases",
        reason: match failure {
            Some(e) => format!("the descent's step program failed: {e}"),
            None => "the descent's step program (with and without equilibration) ended at no \
                     basis whose multipliers are a feasible step"
                .into(),
        },
    })
}

/// The step `(d, t)` read from the dual program's final basis (indices into
/// `columns`, whose first `own` are the trust region's and the floor's), or
/// `None` when that basis is not one of the program's own columns or its
/// multipliers are not a feasible step to [`STEP_FEASIBILITY`].
fn read_step(
    basic: &[usize],
    columns: &[&Constraint],
    own: usize,
    m: usize,
    radius: f64,
) -> Option<(Vec<f64>, f64)> {
    let rows = m + 1;
    if basic.len() != rows || basic.iter().any(|&v| v >= columns.len()) {
        return None;
    }
    let entry = |r: usize, c: &Constraint| if r < m { c.a[r] } else { -c.t_coefficient };
    let basis = Mat::from_fn(rows, rows, |r, i| entry(r, columns[basic[i]]));
    let costs = Col::from_fn(rows, |i| columns[basic[i]].b);
    let pi = dense::lu_solve(basis.transpose(), costs.as_mat());
    let pi = pi.col(0);
    // The trust region's bounds are exact: the solve's rounding, relative
    // to the model rows' terms (intensities), can put d_i beyond a radius
    // that has shrunk to rounding's size of them. d is clamped to them, if
    // what the clamp moves in every other constraint is rounding too.
    let raw: Vec<f64> = (0..m).map(|i| pi[i]).collect();
    let d: Vec<f64> = raw.iter().map(|v| v.clamp(-radius, radius)).collect();
    let t = -pi[m];
    let clamped = columns[own..]
        .iter()
        .map(|c| {
            let moved: f64 =
                c.a.iter()
                    .zip(raw.iter().zip(&d))
                    .map(|(a, (r, d))| (a * (r - d)).abs())
                    .sum();
            moved / c.size(&d, t)
        })
        .fold(0.0f64, f64::max);
    // The multipliers of an optimal basis are a feasible step: checked,
    // since the step is only as good as the basis it is read from.
    let worst = columns
        .iter()
        .map(|c| c.violation(&d, t))
        .fold(0.0f64, f64::max);
    let finite = t.is_finite() && d.iter().all(|v| v.is_finite());
    (finite && worst <= STEP_FEASIBILITY && clamped <= STEP_FEASIBILITY).then_some((d, t))
}

/// The descent from `theta0`; `scale` is the cases' elastic deflection
/// (length), the first trust radius; `stress` the stress objective, if
/// any (its depths fixed from the start's solutions).
pub(crate) fn solve(
    cases: &[Case<'_>],
    basis: &Basis,
    (c_max, stress): (Option<f64>, Option<&StressObjective>),
    theta0: &[f64],
    scale: f64,
    options: &DesignOptions,
) -> Result<Found, DesignError> {
    let m = basis.params();
    let mut current = analyse(
        cases,
        basis,
        theta0.to_vec(),
        None,
        (options, &Criterion::Pressure),
    )?;
    let criterion = match stress {
        None => Criterion::Pressure,
        Some(stress) => {
            let criterion = Criterion::Stress(stress.at(cases, &current.solutions));
            current.objective = objective_of(cases, &current.solutions, &criterion)?;
            criterion
        }
    };
    let mut radius = scale;
    let (mut iterations, mut accepted) = (0, 0);
    let mut analyses = cases.len();
    let mut pivots = pivots_of(&current.solutions);
    // The model at `current`: rebuilt only when a step is accepted (a
    // rejected one changes the radius alone).
    let mut model_at_current: Option<Vec<Constraint>> = None;
    let stop = loop {
        if iterations >= options.max_iterations {
            break Stop::IterationLimit;
        }
        if radius < RESOLUTION * scale {
            break Stop::TrustRegion;
        }
        iterations += 1;
        let pool = match &mut model_at_current {
            Some(pool) => pool,
            None => model_at_current.insert(model_of(
                cases,
                basis,
                c_max,
                &current,
                (&options.reanalysis_options, &criterion),
            )?),
        };
        let (d, model, p) = step(pool, m, radius, &options.engine)?;
        pivots += p;
        let predicted = current.objective - model;
        if predicted <= STATIONARY * current.objective {
            break Stop::Stationary;
        }
        let theta: Vec<f64> = current.theta.iter().zip(&d).map(|(t, d)| t + d).collect();
        let trial = analyse(
            cases,
            basis,
            theta,
            Some(&current.solutions),
            (options, &criterion),
        )?;
        analyses += cases.len();
        pivots += pivots_of(&trial.solutions);
        let ratio = (current.objective - trial.objective) / predicted;
        let length = d.iter().fold(0.0f64, |a, v| a.max(v.abs()));
        if ratio < SHRINK {
            radius = 0.25 * length;
        } else if ratio > EXPAND && length >= 0.99 * radius {
            radius *= 2.0;
        }
        if ratio >= ACCEPT {
            accepted += 1;
            current = trial;
            model_at_current = None;
        }
    };
    let max_intensity = current
        .solutions
        .iter()
        .fold(0.0f64, |a, s| a.max(s.max_pressure));
    Ok(Found {
        theta: current.theta,
        objective: current.objective,
        max_intensity,
        solutions: Some(current.solutions),
        solver: Solver::Descent {
            iterations,
            accepted,
            analyses,
            pivots,
            stop,
        },
        criterion,
    })
}

/// The worst merit of `solutions` under `criterion`.
fn objective_of(
    cases: &[Case<'_>],
    solutions: &[ContactSolution],
    criterion: &Criterion,
) -> Result<f64, DesignError> {
    let mut worst = 0.0f64;
    for (l, (case, solution)) in cases.iter().zip(solutions).enumerate() {
        worst = worst.max(criterion.merit(l, case, solution)?.0);
    }
    Ok(worst)
}

/// The step's constraints at `current`: the constant's bounds and every
/// case's model rows.
fn model_of(
    cases: &[Case<'_>],
    basis: &Basis,
    c_max: Option<f64>,
    current: &Iterate,
    model: (&elcon_lcp::Options, &Criterion),
) -> Result<Vec<Constraint>, DesignError> {
    let mut pool = constant_rows(basis, &current.theta, c_max);
    for (l, ((case, problem), solution)) in cases
        .iter()
        .zip(&current.problems)
        .zip(&current.solutions)
        .enumerate()
    {
        pool.extend(model_rows((l, case), problem, solution, basis, model)?);
    }
    Ok(pool)
}

fn pivots_of(solutions: &[ContactSolution]) -> usize {
    solutions.iter().map(|s| s.statistics.pivots()).sum()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Model rows of intensities near 1.6e5 whose sensitivities are near
    /// 1e9 per unit of the parameters (psi and inches in a crowned
    /// contact), the trust region down to rounding's size.
    #[test]
    fn a_step_at_a_radius_near_rounding_stays_in_its_trust_region() {
        let row = |a: [f64; 3], p: f64| Constraint {
            a: a.to_vec(),
            t_coefficient: -1.0,
            b: -p,
        };
        let pool = vec![
            row([3.1e9, -1.2e9, 2.3e9], 1.640_658e5),
            row([-2.2e9, 1.05e9, -2.7e9], 1.640_657e5),
            row([0.4e9, 2.9e9, -0.8e9], 1.640_651e5),
            row([-1.3e9, -2.1e9, 1.9e9], 1.640_655e5),
        ];
        let engine = elcon_lcp::Options::default();
        for exponent in 3..=16 {
            let radius = 5.771_143_672e-1 * 10f64.powi(-exponent);
            let (d, t, _) = step(&pool, 3, radius, &engine)
                .unwrap_or_else(|e| panic!("radius {radius:e}: {e}"));
            assert!(d.iter().all(|v| v.abs() <= radius), "{d:?} {radius:e}");
            assert!(t <= 1.640_658e5, "{t}");
        }
    }

    /// A step is read from a basis only when its multipliers are a
    /// feasible step: the optimal basis of a one-parameter program gives
    /// one, a basis whose multipliers violate the program's rows (the
    /// fallback's trigger) none.
    #[test]
    fn a_step_is_read_only_from_a_basis_whose_multipliers_are_feasible() {
        // minimize t subject to t >= 2 + d, t >= 2 - 3 d, |d| <= 1:
        // d = 0, t = 2.
        let radius = 1.0;
        let own = [
            Constraint {
                a: vec![1.0],
                t_coefficient: 0.0,
                b: radius,
            },
            Constraint {
                a: vec![0.0],
                t_coefficient: -1.0,
                b: 10.0,
            },
            Constraint {
                a: vec![-1.0],
                t_coefficient: 0.0,
                b: radius,
            },
        ];
        let model = [
            Constraint {
                a: vec![1.0],
                t_coefficient: -1.0,
                b: -2.0,
            },
            Constraint {
                a: vec![-3.0],
                t_coefficient: -1.0,
                b: -2.0,
            },
        ];
        let columns: Vec<&Constraint> = own.iter().chain(&model).collect();
        let (d, t) = read_step(&[3, 4], &columns, own.len(), 1, radius).unwrap();
        assert!(d[0].abs() < 1e-12 && (t - 2.0).abs() < 1e-12, "{d:?} {t}");
        // A feasible basis that is not optimal still gives a feasible step
        // (d = 1, t = 3: the descent's acceptance test judges it).
        let (d, t) = read_step(&[0, 3], &columns, own.len(), 1, radius).unwrap();
        assert!(
            (d[0] - 1.0).abs() < 1e-12 && (t - 3.0).abs() < 1e-12,
            "{d:?} {t}"
        );
        // The floor's row and the second model row: d = 4, beyond the
        // trust region, t = -10 below both model rows.
        assert!(read_step(&[1, 4], &columns, own.len(), 1, radius).is_none());
        // A basis of the wrong size, or naming no column of the program.
        assert!(read_step(&[3], &columns, own.len(), 1, radius).is_none());
        assert!(read_step(&[3, 9], &columns, own.len(), 1, radius).is_none());
    }
}
