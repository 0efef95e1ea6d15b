//! The discretization error of a solution: the same problem (bodies,
//! geometry, loading, storage rule, method) solved on other grids of its
//! family, and each quantity's values put through the generalized
//! Richardson estimate of `crate::discretization`.
//!
//! The grids are the run's own h and its coarser `2h` and `4h`
//! (`crate::grid::GridFamily::coarser`: a quarter and a sixteenth of the
//! points on a surface, a half and a quarter on a line) while they resolve
//! the contact: the fine contact spans at least [`MIN_CELLS_ACROSS`] of
//! their cells along each axis, and their cells are no coarser than the
//! nodes of a table of the surface (a height map, a profile: coarser
//! cells would sample the data differently, and their changes would not
//! be the discretization's). Where the grid at 4h would not, a finer
//! grid `h/2` (`GridFamily::finer`) is solved instead, and the grids are
//! `h/2, h, 2h`; where 2h would not either, `h/4, h/2, h`. A finer grid is
//! solved only while its solve's memory ([`Plan`](super::builder::Plan))
//! stays within [`finer_allowance`] of the run's own; otherwise the
//! estimate says so. A solve that fails, or is not certified, ends the
//! sequence (the quantities are then estimated from fewer grids, or not
//! estimated, with the reason); it never fails the estimate. The other
//! problems are built and dropped one at a time after the fine solve.
//!
//! Where the run's own grid is the finest of h, 2h, 4h and those (with the
//! grids between them, `GridFamily::intermediate`) still leave a quantity
//! the input does not limit not resolved, the finer grid h/2 and the grid
//! between it and h are solved too, within the memory allowance and
//! [`refine_seconds_allowance`]: 2h and 4h may lie outside the range where
//! the error falls at a steady order. Quantities h, 2h, 4h resolved keep
//! their estimate.
//!
//! A surface interpolated with slope kinks (a height map read bilinearly,
//! a profile linearly) puts a pressure peak under each kink that every
//! finer grid resolves higher: the peak pressure is then not resolved
//! whatever its changes, the input named ([`InputLimit`]); so are the peak
//! and the contact's extent where the peak lies on the bodies' own edge
//! (a punch's rim, a roller's end), where the pressure is singular.

use std::time::Instant;

use elcon_influence::{Cell, PointSet};
use elcon_lcp::{Method, Options};

use super::builder::ProblemBuilder;
use super::geometry::Geometry;
use super::solution::ContactSolution;
use super::tabulated::{Departure, Interpolation, ProfileAxis};
use crate::AnalysisError;
use crate::discretization::{
    Discretization, ErrorEstimate, GridRun, InputLimit, MIN_CELLS_ACROSS, Quantity,
    REFINE_FLOOR_SECONDS, REFINE_TIMES, Verdict, changes, estimate, finer_allowance, fitted,
    refine_seconds_allowance,
};
use crate::edge::contact_spans;
use crate::grid::GridFamily;

/// The grids an estimate solves besides the run's own.
const OTHER_GRIDS: usize = 2;

impl ProblemBuilder<'_> {
    /// The discretization error of `fine`, this builder's problem solved on
    /// `family`'s points by `method` with `options`: the same problem
    /// solved on other grids of the family (see the module documentation),
    /// each quantity of [`Quantity::ALL`] estimated. A problem whose
    /// separations are given per point has no other grid: every quantity
    /// is then not estimated, with that reason.
    ///
    /// # Errors
    /// [`AnalysisError::Incompatible`] when `family` does not lay out this
    /// builder's number of points, [`AnalysisError::SizeMismatch`] when
    /// `fine` is not a solution on them; the other grids' failures are
    /// reported in the result, not as errors.
    pub fn discretization(
        &self,
        family: &GridFamily,
        fine: &ContactSolution,
        method: Method,
        options: &Options,
    ) -> Result<Discretization, AnalysisError> {
        let n = self.points().len();
        let laid_out = family.points()?.len();
        if laid_out != n {
            return Err(AnalysisError::Incompatible {
                field: "family",
                reason: format!("it lays out {laid_out} points, the problem has {n}"),
            });
        }
        if fine.forces.len() != n {
            return Err(AnalysisError::SizeMismatch {
                field: "fine.forces",
                expected: n,
                found: fine.forces.len(),
            });
        }
        let own = GridRun {
            points: n,
            spacing: family.spacing(),
            seconds: fine.assembly_seconds + fine.solve_seconds,
            failure: None,
        };
        if let Geometry::Separation(_) = self.geometry() {
            let reason = "the separations are given per point: another grid has none";
            return Ok(Discretization::not_estimated(
                vec![own],
                |q| value(fine, q),
                reason,
            ));
        }
        let run = Solver {
            builder: self,
            fine,
            method,
            options,
        };
        let mut sequence = run.sequence(family, own);
        // The tables first: a quantity limited by both is named by its data.
        let mut limits = input_limits(self.geometry(), sequence.coarsest);
        limits.extend(singular_edge(self, fine));
        if sequence.needs_fit(&limits) {
            run.intermediates(&mut sequence);
        }
        let mut estimates = sequence.estimates(&limits);
        if sequence.needs_finer(&estimates, &limits) {
            run.refine(family, &mut sequence);
            estimates = keep_resolved(estimates, sequence.estimates(&limits));
        }
        let (grids, own) = sequence.all_grids();
        Ok(Discretization {
            grids,
            estimates,
            note: sequence.stop.map(|stop| stop.to_string()),
            own,
            limits,
        })
    }
}

/// The other grids' problems of a run, solved as the fine one was.
struct Solver<'a, 'b> {
    builder: &'a ProblemBuilder<'b>,
    fine: &'a ContactSolution,
    method: Method,
    options: &'a Options,
}

/// The grids solved, the finest first, with the solutions of those that
/// did not fail, the run's own grid's index among them, and why the
/// sequence ended early, if it did.
struct Sequence {
    /// The cell of the coarsest grid solved.
    coarsest: Cell,
    grids: Vec<GridRun>,
    /// The families of `grids`.
    families: Vec<GridFamily>,
    solutions: Vec<ContactSolution>,
    own: usize,
    stop: Option<Stop>,
    /// The grids between the nested ones (about `sqrt 2` apart) solved for
    /// the least-squares fit, with their solutions if certified.
    between: Vec<(GridRun, Option<ContactSolution>)>,
}

/// Up to `levels` grids from `family`, each made from the last by `step`
/// (its level from 1), and why the walk stopped short, if it did.
fn walk(
    family: &GridFamily,
    levels: usize,
    step: impl Fn(&GridFamily, usize) -> Result<(GridFamily, PointSet), Stop>,
) -> (Vec<(GridFamily, PointSet)>, Option<Stop>) {
    let mut grids: Vec<(GridFamily, PointSet)> = Vec::new();
    for level in 1..=levels {
        let current = grids.last().map_or(*family, |(grid, _)| *grid);
        match step(&current, level) {
            Ok(next) => grids.push(next),
            Err(why) => return (grids, Some(why)),
        }
    }
    (grids, None)
}

impl Solver<'_, '_> {
    /// The run's own grid `own` of `family` with the others: 2h and 4h
    /// while they resolve the contact, finer grids in place of those that
    /// do not (see the module documentation).
    fn sequence(&self, family: &GridFamily, own: GridRun) -> Sequence {
        let (coarse, coarse_stop) =
            walk(family, OTHER_GRIDS, |grid, level| self.coarse(grid, level));
        let (finer, finer_stop) = walk(family, OTHER_GRIDS - coarse.len(), |grid, level| {
            self.finer(grid, level)
        });
        let mut stop = finer_stop.or(coarse_stop);
        if finer.len() + coarse.len() == OTHER_GRIDS {
            stop = None;
        }
        let coarsest = coarse
            .last()
            .map_or(self.builder.points().cell(), |(_, points)| points.cell());
        let mut sequence = Sequence {
            coarsest,
            grids: vec![own],
            families: vec![*family],
            solutions: vec![self.fine.clone()],
            own: 0,
            stop,
            between: Vec::new(),
        };
        for (level, (grid, points)) in finer.into_iter().enumerate() {
            let times = 0.5f64.powi(level as i32 + 1);
            if let Err(why) = sequence.push_finer(self.solve(&grid, points, times)) {
                sequence.stop = Some(why);
                break;
            }
        }
        for (level, (grid, points)) in coarse.into_iter().enumerate() {
            let times = 2.0f64.powi(level as i32 + 1);
            if let Err(why) = sequence.push_coarser(self.solve(&grid, points, times)) {
                sequence.stop = Some(why);
                break;
            }
        }
        sequence
    }

    /// The run's problem on other `points`, planned and held for the run's
    /// method (where the storage is left to the plan, a grid of more points
    /// would otherwise be held matrix-free, which a pivoting method cannot
    /// solve).
    fn on(&self, points: PointSet) -> ProblemBuilder<'_> {
        self.builder.on(points).method(self.method)
    }

    /// `grid`'s problem on `points` solved, logged as the grid at `times`
    /// the spacing; its solution if it is certified.
    fn solve(&self, grid: &GridFamily, points: PointSet, times: f64) -> Solved {
        let start = Instant::now();
        let solved = (self.on(points).build()).and_then(|p| p.solve(self.method, self.options));
        let seconds = start.elapsed().as_secs_f64();
        let failure = match &solved {
            Ok(s) if s.certificate.holds() => None,
            Ok(s) => Some(format!("not certified ({})", s.certificate)),
            Err(e) => Some(e.to_string()),
        };
        let run = GridRun {
            points: solved.as_ref().map_or(0, |s| s.forces.len()),
            spacing: grid.spacing(),
            seconds,
            failure: failure.clone(),
        };
        Solved {
            run,
            family: *grid,
            times,
            solution: solved.ok().filter(|_| failure.is_none()),
            failure,
        }
    }

    /// The grid coarser than `current` and its points, if it is made and
    /// resolves the fine contact; else why not. `level` 1 is 2h, 2 is 4h.
    fn coarse(&self, current: &GridFamily, level: usize) -> Result<(GridFamily, PointSet), Stop> {
        let times = 2.0f64.powi(level as i32);
        let coarse = current.coarser().ok_or(Stop::TooFewPoints { times })?;
        let points = coarse
            .points()
            .map_err(|error| Stop::NoPoints { times, error })?;
        let cells = cells_across(self.builder.points(), &self.fine.contact, &points);
        if !(cells >= MIN_CELLS_ACROSS) {
            return Err(Stop::Unresolved { times, cells });
        }
        if let Geometry::Tabulated { departures, .. } = self.builder.geometry()
            && let Some(limit) = departures
                .iter()
                .find_map(|d| InputLimit::coarser_than(d, points.cell()))
        {
            return Err(Stop::CoarserThanData { times, limit });
        }
        Ok((coarse, points))
    }

    /// The grid finer than `current` and its points, if its solve fits the
    /// allowance ([`finer_allowance`]); else why not. `level` 1 is h/2, 2
    /// is h/4.
    fn finer(&self, current: &GridFamily, level: usize) -> Result<(GridFamily, PointSet), Stop> {
        let times = 0.5f64.powi(level as i32);
        let finer = current.finer();
        let points = finer
            .points()
            .map_err(|error| Stop::NoPoints { times, error })?;
        self.within_allowance(&points, times)?;
        Ok((finer, points))
    }

    /// Whether a finer grid's solve on `points` (at `times` the run's
    /// spacing) fits the allowance ([`finer_allowance`]); why not if not.
    fn within_allowance(&self, points: &PointSet, times: f64) -> Result<(), Stop> {
        let own = self.builder.plan().map(|p| p.estimate.solve_bytes);
        let planned = self.on(points.clone()).plan();
        let (Ok(own), Ok(planned)) = (own, planned) else {
            return Err(Stop::TooBig {
                times,
                bytes: f64::INFINITY,
                allowance: f64::NAN,
            });
        };
        let allowance = finer_allowance(own);
        let bytes = planned.estimate.solve_bytes;
        if !(bytes <= allowance) {
            return Err(Stop::TooBig {
                times,
                bytes,
                allowance,
            });
        }
        Ok(())
    }

    /// The grids between `sequence`'s nested ones, each about `sqrt 2`
    /// coarser than the finer of a pair ([`GridFamily::intermediate`]),
    /// solved for the least-squares fit: those finer than the run's own
    /// only within [`finer_allowance`]. A grid that cannot be made or
    /// fails is logged (a failure) or noted, and the fit made on the
    /// others.
    fn intermediates(&self, sequence: &mut Sequence) {
        let own = self.builder.points().len();
        let h_own = sequence.grids[0..]
            .iter()
            .find(|g| g.points == own && g.failure.is_none());
        let h_own = h_own.map_or(f64::NAN, |g| g.spacing);
        let pairs: Vec<(GridFamily, f64)> = (sequence.grids.windows(2))
            .zip(&sequence.families)
            .filter(|(w, _)| w[0].failure.is_none() && w[1].failure.is_none())
            .map(|(w, f)| (*f, w[1].spacing))
            .collect();
        for (fine, coarse_spacing) in pairs {
            self.between(&fine, coarse_spacing, h_own, sequence);
        }
    }

    /// The grid between `fine` and the grid of `coarse_spacing` next
    /// coarser ([`GridFamily::intermediate`]), solved for the
    /// least-squares fit into `sequence` (`h_own` the run's own spacing): a
    /// grid finer than the run's own only within [`finer_allowance`]. A grid
    /// that cannot be made or fails is logged (a failure) or noted.
    fn between(&self, fine: &GridFamily, coarse_spacing: f64, h_own: f64, sequence: &mut Sequence) {
        let Some(grid) = fine.intermediate() else {
            return;
        };
        let h = grid.spacing();
        if !(h > fine.spacing() && h < coarse_spacing) {
            return;
        }
        let times = h / h_own;
        let points = match grid.points() {
            Ok(points) => points,
            Err(error) => {
                sequence.stop.get_or_insert(Stop::NoPoints { times, error });
                return;
            }
        };
        if h < h_own
            && let Err(why) = self.within_allowance(&points, times)
        {
            sequence.stop.get_or_insert(why);
            return;
        }
        let solved = self.solve(&grid, points, times);
        if let Some(failure) = &solved.failure {
            let failure = failure.clone();
            sequence.stop.get_or_insert(Stop::Failed { times, failure });
        }
        sequence.between.push((solved.run, solved.solution));
    }

    /// The finer grid h/2 and the grid between it and the run's own `family`,
    /// solved where the run's own grid is the finest and the coarser grids
    /// (with those between them) leave a quantity the input does not limit
    /// unresolved: the grids at 2h and 4h then lie outside the range where
    /// the error falls at a steady order (a contact edge in one cell or the
    /// next), and the finer ones may not. Only within the memory allowance
    /// ([`finer_allowance`]) and the time allowance
    /// ([`refine_seconds_allowance`]); whatever stops it is noted.
    fn refine(&self, family: &GridFamily, sequence: &mut Sequence) {
        let finer = self
            .finer(family, 1)
            .and_then(|(grid, points)| self.within_time(&points, 0.5).map(|()| (grid, points)));
        let (grid, points) = match finer {
            Ok(finer) => finer,
            Err(why) => {
                sequence.stop.get_or_insert(why);
                return;
            }
        };
        if let Err(why) = sequence.push_finer(self.solve(&grid, points, 0.5)) {
            sequence.stop.get_or_insert(why);
            return;
        }
        let h_own = family.spacing();
        if let Some(between) = grid.intermediate()
            && let Ok(points) = between.points()
            && let Err(why) = self.within_time(&points, between.spacing() / h_own)
        {
            sequence.stop.get_or_insert(why);
            return;
        }
        self.between(&grid, h_own, h_own, sequence);
    }

    /// Whether the solve of a finer grid added by [`Solver::refine`] on
    /// `points` (at `times` the run's spacing) fits the time allowance
    /// ([`refine_seconds_allowance`] of the run's own planned solve); why
    /// not if not.
    fn within_time(&self, points: &PointSet, times: f64) -> Result<(), Stop> {
        let own = self.builder.plan().map(|p| p.estimate.seconds);
        let planned = self.on(points.clone()).plan();
        let (Ok(own), Ok(planned)) = (own, planned) else {
            return Err(Stop::TooLong {
                times,
                seconds: f64::INFINITY,
                allowance: f64::NAN,
            });
        };
        let allowance = refine_seconds_allowance(own);
        let seconds = planned.estimate.seconds;
        if !(seconds <= allowance) {
            return Err(Stop::TooLong {
                times,
                seconds,
                allowance,
            });
        }
        Ok(())
    }
}

/// A grid solved: its log, its spacing's multiple of the run's, and its
/// solution or why it failed.
struct Solved {
    run: GridRun,
    family: GridFamily,
    times: f64,
    solution: Option<ContactSolution>,
    failure: Option<String>,
}

impl Sequence {
    /// A finer grid, ahead of the others; why the sequence stops if it
    /// failed.
    fn push_finer(&mut self, solved: Solved) -> Result<(), Stop> {
        self.grids.insert(0, solved.run);
        self.families.insert(0, solved.family);
        match (solved.solution, solved.failure) {
            (Some(s), _) => {
                self.solutions.insert(0, s);
                self.own += 1;
                Ok(())
            }
            (None, failure) => Err(Stop::Failed {
                times: solved.times,
                failure: failure.unwrap_or_default(),
            }),
        }
    }

    /// A coarser grid, after the others; why the sequence stops if it
    /// failed.
    fn push_coarser(&mut self, solved: Solved) -> Result<(), Stop> {
        self.grids.push(solved.run);
        self.families.push(solved.family);
        match (solved.solution, solved.failure) {
            (Some(s), _) => {
                self.solutions.push(s);
                Ok(())
            }
            (None, failure) => Err(Stop::Failed {
                times: solved.times,
                failure: failure.unwrap_or_default(),
            }),
        }
    }

    /// Each quantity's estimate from the nested solutions (Richardson),
    /// or, where their grids do not resolve it and the grids between them
    /// were solved, the least-squares fit over all; the stop's reason on
    /// those not estimated, and `limits` making the quantities they limit
    /// not resolved. Each estimate's values are those of every grid
    /// solved ([`Sequence::all_grids`]).
    fn estimates(&self, limits: &[InputLimit]) -> Vec<(Quantity, ErrorEstimate)> {
        let spacings: Vec<f64> = self
            .grids
            .iter()
            .filter(|g| g.failure.is_none())
            .map(|g| g.spacing)
            .collect();
        let all = self.all_solutions();
        let all_spacings: Vec<f64> = all.iter().map(|(h, _)| *h).collect();
        let own_value = self.own_value(&all);
        let note = self.stop.as_ref().map(Stop::to_string);
        Quantity::ALL
            .iter()
            .map(|&q| {
                let values: Vec<f64> = self.solutions.iter().map(|s| value(s, q)).collect();
                let scale = scale(&self.solutions, q);
                let mut e = estimate(&values, &spacings, self.own, scale);
                let limited = limits.iter().find(|l| l.limits(q));
                let all_values: Vec<f64> = all.iter().map(|(_, s)| value(s, q)).collect();
                if let Verdict::NotResolved(why) = &e.verdict
                    && limited.is_none()
                    && all.len() > values.len()
                {
                    let fit = fitted(&all_values, &all_spacings, own_value, scale);
                    e = match fit.verdict {
                        // The nested grids' order and reason, with the fit's.
                        Verdict::NotResolved(fit_why) => ErrorEstimate {
                            verdict: Verdict::NotResolved(format!(
                                "{why}; over {} grids: {fit_why}",
                                all.len()
                            )),
                            scatter: fit.scatter,
                            ..e
                        },
                        Verdict::NotEstimated(_) => e,
                        _ => fit,
                    };
                }
                e.values = all_values;
                e.own = own_value;
                if let (Verdict::NotEstimated(reason), Some(why)) = (&e.verdict, &note) {
                    let first = reason.split(':').next().unwrap_or(reason);
                    e.verdict = Verdict::NotEstimated(format!("{first}: {why}"));
                }
                if let Some(limit) = limited
                    && e.verdict != Verdict::Exact
                {
                    // The cause, then what the nested grids showed.
                    let observed = match (changes(&values), e.order) {
                        (Some(c), Some(p)) => format!(" (the grids show {c}, order {p:.2})"),
                        (Some(c), None) => format!(" (the grids show {c})"),
                        _ => String::new(),
                    };
                    e.verdict = Verdict::NotResolved(format!("{limit}{observed}"));
                    e.error = None;
                    e.extrapolated = None;
                }
                (q, e)
            })
            .collect()
    }

    /// Whether a quantity the input does not limit is not resolved by the
    /// nested grids (three of them solved): the grids between them are
    /// then worth solving for the least-squares fit.
    fn needs_fit(&self, limits: &[InputLimit]) -> bool {
        self.solutions.len() == 3 && unresolved(&self.estimates(limits), limits)
    }

    /// Whether the run's own grid is the finest of three nested grids
    /// solved and a quantity the input does not limit is still not
    /// resolved in `estimates` (the grids between them included): a finer
    /// grid is then worth solving ([`Solver::refine`]).
    fn needs_finer(&self, estimates: &[(Quantity, ErrorEstimate)], limits: &[InputLimit]) -> bool {
        self.own == 0 && self.solutions.len() == 3 && unresolved(estimates, limits)
    }

    /// The spacing and solution of every grid solved without failure,
    /// nested and between, the finest first.
    fn all_solutions(&self) -> Vec<(f64, &ContactSolution)> {
        let nested = (self.grids.iter().filter(|g| g.failure.is_none()))
            .map(|g| g.spacing)
            .zip(&self.solutions);
        let between = (self.between.iter()).filter_map(|(g, s)| s.as_ref().map(|s| (g.spacing, s)));
        let mut all: Vec<(f64, &ContactSolution)> = nested.chain(between).collect();
        all.sort_by(|a, b| a.0.total_cmp(&b.0));
        all
    }

    /// The index among `all` of the run's own solution.
    fn own_value(&self, all: &[(f64, &ContactSolution)]) -> usize {
        let own = &self.solutions[self.own];
        all.iter()
            .position(|(_, s)| std::ptr::eq(*s, own))
            .unwrap_or(0)
    }

    /// Every grid solved, nested and between, the finest first, and the
    /// index of the run's own among them.
    fn all_grids(&self) -> (Vec<GridRun>, usize) {
        let own = self
            .grids
            .iter()
            .filter(|g| g.failure.is_none())
            .nth(self.own);
        let own_spacing = own.map_or(f64::NAN, |g| g.spacing);
        let mut grids: Vec<GridRun> = (self.grids.iter())
            .chain(self.between.iter().map(|(g, _)| g))
            .cloned()
            .collect();
        grids.sort_by(|a, b| a.spacing.total_cmp(&b.spacing));
        let own = grids
            .iter()
            .position(|g| g.spacing == own_spacing && g.failure.is_none())
            .unwrap_or(0);
        (grids, own)
    }
}

/// Whether a quantity the input does not limit is not resolved in
/// `estimates`.
fn unresolved(estimates: &[(Quantity, ErrorEstimate)], limits: &[InputLimit]) -> bool {
    estimates.iter().any(|(q, e)| {
        matches!(e.verdict, Verdict::NotResolved(_)) && !limits.iter().any(|l| l.limits(*q))
    })
}

/// The estimates after a finer grid was added ([`Solver::refine`]):
/// `refined`'s, except where the coarser grids already resolved a quantity
/// (`coarse` converging or exact), whose estimate stands, with every grid's
/// values. The finer grids are solved for the quantities the coarser ones
/// leave unresolved; a quantity they resolved keeps the estimate its own
/// grids showed.
fn keep_resolved(
    coarse: Vec<(Quantity, ErrorEstimate)>,
    refined: Vec<(Quantity, ErrorEstimate)>,
) -> Vec<(Quantity, ErrorEstimate)> {
    (coarse.into_iter().zip(refined))
        .map(|((q, before), (_, after))| match before.verdict {
            Verdict::Converging | Verdict::Exact => (
                q,
                ErrorEstimate {
                    values: after.values,
                    own: after.own,
                    ..before
                },
            ),
            _ => (q, after),
        })
        .collect()
}

/// The limit a singular edge sets where `fine`, the solution of
/// `builder`'s problem, has its peak pressure on the bodies' own edges
/// ([`ProblemBuilder::singular_edge_points`]; to [`PEAK_MATCH`] of it). A
/// contact that only touches the edge with a lower pressure there (a
/// crowned roller's ends) leaves the peak where the grids resolve it.
fn singular_edge(builder: &ProblemBuilder<'_>, fine: &ContactSolution) -> Option<InputLimit> {
    let edge = builder.singular_edge_points();
    let pressure = |k: usize| fine.pressures.get(k).copied().unwrap_or(0.0);
    let peak = edge.iter().map(|&k| pressure(k)).fold(0.0, f64::max);
    if !(peak > 0.0 && peak >= fine.max_pressure * (1.0 - PEAK_MATCH)) {
        return None;
    }
    let points = edge.iter().filter(|&&k| pressure(k) > 0.0).count();
    Some(InputLimit::SingularEdge { points })
}

/// A pressure within this fraction of the peak is the peak (the same
/// value on mirror-image points, to rounding).
const PEAK_MATCH: f64 = 1e-9;

/// What in `geometry` limits the quantities whatever the grid, the
/// coarsest grid solved of cell `coarsest`: each departure interpolated
/// with slope kinks, each whose nodes lie closer than that grid's cells.
fn input_limits(geometry: &Geometry, coarsest: Cell) -> Vec<InputLimit> {
    let Geometry::Tabulated { departures, .. } = geometry else {
        return Vec::new();
    };
    let kinked = departures.iter().filter_map(InputLimit::kinked);
    let sampled = departures
        .iter()
        .filter_map(|d| InputLimit::coarser_than(d, coarsest));
    kinked.chain(sampled).collect()
}

impl InputLimit {
    /// The limit a departure sets if it has slope kinks (interpolated
    /// linearly; a cubic table has a continuous slope).
    fn kinked(d: &Departure) -> Option<Self> {
        if d.interpolation() == Interpolation::Cubic {
            return None;
        }
        Some(match d {
            Departure::HeightMap(m) => InputLimit::KinkedMap {
                label: m.label().to_string(),
            },
            Departure::Profile(p) => InputLimit::KinkedProfile {
                label: p.label().to_string(),
            },
        })
    }

    /// The limit a departure sets if its nodes lie closer than `cell`
    /// along its axes (a profile's axis; a map's larger side of the cell,
    /// against its nodes' smaller spacing).
    fn coarser_than(d: &Departure, cell: Cell) -> Option<Self> {
        let along = match d {
            Departure::Profile(p) => match p.axis() {
                ProfileAxis::X => cell.dx,
                ProfileAxis::Y => cell.dy,
            },
            Departure::HeightMap(_) => cell.dx.max(cell.dy),
        };
        let nodes = d.node_spacing();
        (along > nodes * (1.0 + MATCH)).then(|| InputLimit::CoarserThanData {
            label: d.label().to_string(),
            nodes,
            cell: along,
        })
    }
}

/// A cell within this fraction of a table's node spacing counts as equal
/// to it (the rounding of spacings computed two ways).
const MATCH: f64 = 1e-9;

/// Why the sequence of other grids ended early: the discretization's
/// note, each grid named by its spacing's multiple `times` of the run's
/// (1/4, 1/2, 2 or 4).
#[derive(Debug)]
enum Stop {
    /// The coarser grid would have fewer than
    /// [`MIN_COARSE_COUNT`](crate::grid::MIN_COARSE_COUNT) points along an
    /// axis.
    TooFewPoints { times: f64 },
    /// Its points could not be laid out.
    NoPoints { times: f64, error: AnalysisError },
    /// The contact spans fewer than [`MIN_CELLS_ACROSS`] of its cells.
    Unresolved { times: f64, cells: f64 },
    /// Its cells are coarser than a table's nodes.
    CoarserThanData { times: f64, limit: InputLimit },
    /// A finer grid's solve would hold more than its allowance.
    TooBig {
        times: f64,
        bytes: f64,
        allowance: f64,
    },
    /// A finer grid added for an unresolved quantity would take longer
    /// than its allowance.
    TooLong {
        times: f64,
        seconds: f64,
        allowance: f64,
    },
    /// Its solve failed or was not certified.
    Failed { times: f64, failure: String },
}

/// "the grid at 4 times the spacing", "the grid at half the spacing".
fn grid_at(times: f64) -> String {
    if times == 0.5 {
        "the grid at half the spacing".into()
    } else if times == 0.25 {
        "the grid at a quarter of the spacing".into()
    } else if times.fract() == 0.0 {
        format!("the grid at {times} times the spacing")
    } else {
        format!("the grid at {times:.2} times the spacing")
    }
}

impl std::fmt::Display for Stop {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Stop::TooFewPoints { times } => write!(
                f,
                "{} would have fewer than {} points along an axis",
                grid_at(*times),
                crate::grid::MIN_COARSE_COUNT
            ),
            Stop::NoPoints { times, error } => write!(f, "{}: {error}", grid_at(*times)),
            Stop::Unresolved { times, cells } => write!(
                f,
                "the contact spans {cells:.1} cells of {}, fewer than {MIN_CELLS_ACROSS}: too \
                 few points to resolve it",
                grid_at(*times)
            ),
            Stop::TooBig {
                times,
                bytes,
                allowance,
            } => write!(
                f,
                "{}'s solve would hold {:.0} MiB, more than the {:.0} MiB a finer grid may \
                 (the run's own solve's, at least 256 MiB)",
                grid_at(*times),
                bytes / 1048576.0,
                allowance / 1048576.0
            ),
            Stop::TooLong {
                times,
                seconds,
                allowance,
            } => write!(
                f,
                "{}'s solve would take about {seconds:.2e} s, more than the {allowance:.2e} s a \
                 finer grid added for an unresolved quantity may ({REFINE_TIMES} times the \
                 run's own solve, at least {REFINE_FLOOR_SECONDS} s)",
                grid_at(*times)
            ),
            Stop::Failed { times, failure } => {
                write!(f, "{} failed: {failure}", grid_at(*times))
            }
            Stop::CoarserThanData { times, limit } => {
                let InputLimit::CoarserThanData { label, nodes, .. } = limit else {
                    return write!(f, "{}: {limit}", grid_at(*times));
                };
                write!(
                    f,
                    "{}'s cells are coarser than the nodes of {label} ({} apart): it would \
                     sample the data differently",
                    grid_at(*times),
                    crate::Num(*nodes)
                )
            }
        }
    }
}

/// The fewest cells of `coarse` the contact `contact` (indices into
/// `points`, the fine grid's) spans along an axis: its extent along x (and
/// y on a surface), point to point plus a cell of the fine grid
/// ([`contact_spans`]), over the coarse cell. 0 without contact.
fn cells_across(points: &PointSet, contact: &[usize], coarse: &PointSet) -> f64 {
    let cell = coarse.cell();
    match contact_spans(points, contact.iter().copied()) {
        None => 0.0,
        Some((x, None)) => x / cell.dx,
        Some((x, Some(y))) => (x / cell.dx).min(y / cell.dy),
    }
}

impl ContactSolution {
    /// The value of `quantity` in this solution (the field it names).
    pub fn quantity(&self, quantity: Quantity) -> f64 {
        match quantity {
            Quantity::Approach => self.approach,
            Quantity::MaxPressure => self.max_pressure,
            Quantity::ContactExtent => self.contact_extent,
            Quantity::ContactMeasure => self.contact_measure,
            Quantity::Load => self.load,
            Quantity::LoadCentreX => self.load_centre.0,
            Quantity::LoadCentreY => self.load_centre.1,
            Quantity::TiltX => self.tilt_x,
            Quantity::TiltY => self.tilt_y,
        }
    }
}

/// The value of `quantity` in `solution`.
fn value(solution: &ContactSolution, quantity: Quantity) -> f64 {
    solution.quantity(quantity)
}

/// The scale equal values are judged against: the quantity's own
/// magnitude, the contact's extent for the load centre, the approach over
/// the extent for a tilt (the largest over the grids).
fn scale(solutions: &[ContactSolution], quantity: Quantity) -> f64 {
    let largest = |f: &dyn Fn(&ContactSolution) -> f64| {
        solutions.iter().map(|s| f(s).abs()).fold(0.0, f64::max)
    };
    match quantity {
        Quantity::LoadCentreX | Quantity::LoadCentreY => largest(&|s| s.contact_extent),
        Quantity::TiltX | Quantity::TiltY => {
            largest(&|s| s.approach) / largest(&|s| s.contact_extent).max(f64::MIN_POSITIVE)
        }
        q => largest(&|s| value(s, q)),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn each_stop_says_which_grid_and_why() {
        let stops = [
            (
                Stop::TooFewPoints { times: 2.0 },
                "the grid at 2 times the spacing would have fewer than",
            ),
            (
                Stop::NoPoints {
                    times: 4.0,
                    error: AnalysisError::Incompatible {
                        field: "family",
                        reason: "no points".into(),
                    },
                },
                "the grid at 4 times the spacing: ",
            ),
            (
                Stop::Unresolved {
                    times: 2.0,
                    cells: 3.04,
                },
                "the contact spans 3.0 cells of the grid at 2 times the spacing, fewer than",
            ),
            (
                Stop::Failed {
                    times: 4.0,
                    failure: "not certified".into(),
                },
                "the grid at 4 times the spacing failed: not certified",
            ),
            (
                Stop::CoarserThanData {
                    times: 2.0,
                    limit: InputLimit::CoarserThanData {
                        label: "map.npy".into(),
                        nodes: 0.005,
                        cell: 0.008,
                    },
                },
                "the grid at 2 times the spacing's cells are coarser than the nodes of map.npy \
                 (0.005 apart)",
            ),
            (
                Stop::TooLong {
                    times: 0.5,
                    seconds: 40.0,
                    allowance: 10.0,
                },
                "the grid at half the spacing's solve would take about 4.00e1 s, more than the \
                 1.00e1 s",
            ),
            (
                Stop::TooBig {
                    times: 0.5,
                    bytes: 512.0 * 1048576.0,
                    allowance: 256.0 * 1048576.0,
                },
                "the grid at half the spacing's solve would hold 512 MiB, more than the 256 MiB",
            ),
        ];
        for (stop, begins) in stops {
            let text = stop.to_string();
            assert!(text.starts_with(begins), "{text}");
        }
    }

    fn estimated(verdict: Verdict, values: &[f64], own: usize) -> ErrorEstimate {
        ErrorEstimate {
            values: values.to_vec(),
            own,
            extrapolated: Some(1.0),
            error: Some(0.1),
            order: Some(2.0),
            scatter: None,
            verdict,
        }
    }

    #[test]
    fn a_finer_grid_leaves_the_estimates_the_coarser_ones_resolved() {
        let coarse = vec![
            (
                Quantity::Approach,
                estimated(
                    Verdict::NotResolved("alternate".into()),
                    &[1.1, 1.2, 1.0],
                    0,
                ),
            ),
            (
                Quantity::MaxPressure,
                estimated(Verdict::Converging, &[2.1, 2.4, 3.6], 0),
            ),
        ];
        let mut refined_approach = estimated(Verdict::Converging, &[1.05, 1.1, 1.2, 1.0], 1);
        refined_approach.error = Some(0.05);
        let refined = vec![
            (Quantity::Approach, refined_approach.clone()),
            (
                Quantity::MaxPressure,
                estimated(
                    Verdict::NotResolved("faster".into()),
                    &[2.0, 2.1, 2.4, 3.6],
                    1,
                ),
            ),
        ];
        let kept = keep_resolved(coarse, refined);
        // The approach, unresolved by the coarser grids, takes the finer
        // ones' estimate; the peak keeps its own, with every grid's values.
        assert_eq!(kept[0].1, refined_approach);
        let peak = &kept[1].1;
        assert_eq!(peak.verdict, Verdict::Converging);
        assert_eq!(peak.values, vec![2.0, 2.1, 2.4, 3.6]);
        assert_eq!(peak.value(), 2.1);
        assert_eq!(peak.error, Some(0.1));
    }

    #[test]
    fn the_cells_across_a_contact_are_the_fewest_along_an_axis() {
        // Fine cells 1 x 0.5, coarse 2 x 1: a block of 3 x 8 fine cells.
        let fine = PointSet::grid_rectangle(4.0, 2.0, 8, 8).unwrap();
        let coarse = PointSet::grid_rectangle(4.0, 2.0, 4, 4).unwrap();
        assert_eq!(cells_across(&fine, &[], &coarse), 0.0);
        let block: Vec<usize> = (8..32).collect();
        assert_eq!(cells_across(&fine, &block, &coarse), 1.5);
        let line = PointSet::line(-1.0, 1.0, 10).unwrap();
        let coarse = PointSet::line(-1.0, 1.0, 5).unwrap();
        let across = cells_across(&line, &[2, 3, 4], &coarse);
        assert!((across - 1.5).abs() < 1e-15, "{across}");
    }
}
