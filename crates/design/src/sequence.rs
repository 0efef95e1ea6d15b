//! A design carried to convergence over a sequence of grids, and verified
//! on a finer one.
//!
//! A design found on one grid fits that grid: a coarse grid averages a
//! roller's edge peak over its last cell, and a profile designed there can
//! peak far higher on a finer grid. So the correction is a function of
//! position (a linear family's closed form, a crown's, or a free profile's
//! drops at the stations of its grid, linear between them and carried out
//! to the zone's ends along its end slopes: `Profile::extended`) and the
//! design runs on grids
//! of growing fineness `f_0 = 1 < f_1 < ...` (the caller's grid family at
//! spacing `h / f`), each design started from the last, until the worst
//! objective changes by less than the tolerance between two successive
//! grids:
//!
//! ```text
//!     |t_k - t_(k-1)| <= tol t_k,     t_k = max_l p_max_l / r_l of the design on grid k
//! ```
//!
//! The converged profile is then evaluated on the next finer grid, and kept
//! only when that verification agrees with `t_k` to the same tolerance;
//! otherwise the design goes on from that grid. A grid whose cases exceed
//! [`GridSequence::max_points`] ends the sequence without a design:
//! [`DesignError::NotConverged`].

use std::time::Instant;

use elcon_analysis::ContactProblem;

use crate::evaluate::{Analysis, evaluate};
use crate::request::{DesignRequest, Outcome};
use crate::{Axis, DesignError};

/// How a design is carried over grids (see the [module documentation](self)).
#[derive(Debug, Clone, PartialEq)]
pub struct GridSequence {
    /// The grids' fineness, in order: the caller's grid at spacing `h / f`
    /// (default 1, 2, 3, 4, 6, 8, 12, 16).
    pub fineness: Vec<f64>,
    /// The relative change of the worst objective between two successive
    /// grids at which the design has converged, and the verification's
    /// agreement (default 0.01).
    pub tolerance: f64,
    /// The most points a load case may have on a grid of the sequence
    /// (default 20,000).
    pub max_points: usize,
}

impl Default for GridSequence {
    fn default() -> Self {
        Self {
            fineness: vec![1.0, 2.0, 3.0, 4.0, 6.0, 8.0, 12.0, 16.0],
            tolerance: 0.01,
            max_points: 20_000,
        }
    }
}

/// One grid of the sequence.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Level {
    /// Its fineness f (spacing h / f).
    pub fineness: f64,
    /// The points of its largest load case.
    pub points: usize,
    /// The worst `p_max_l / r_l` over the cases on it.
    pub objective: f64,
    /// Seconds spent on it (building, designing or evaluating).
    pub seconds: f64,
}

/// A design that converged over a sequence of grids.
#[derive(Debug, Clone)]
pub struct Converged {
    /// The design on the last design grid.
    pub outcome: Outcome,
    /// The design grids, coarse to fine, with the objective on each.
    pub levels: Vec<Level>,
    /// The converged profile evaluated on the next finer grid.
    pub verification: Level,
}

impl GridSequence {
    fn check(&self) -> Result<(), DesignError> {
        if !(self.tolerance.is_finite() && self.tolerance > 0.0 && self.tolerance < 1.0) {
            return Err(DesignError::InvalidInput {
                field: "grid_tolerance",
                value: self.tolerance,
                reason: "must be in (0, 1)",
            });
        }
        let increasing = self.fineness.windows(2).all(|w| w[1] > w[0]);
        if self.fineness.len() < 2 || !increasing || !self.fineness.iter().all(|f| *f > 0.0) {
            return Err(DesignError::Incompatible {
                field: "fineness",
                reason: "at least two grids, their fineness positive and increasing".into(),
            });
        }
        Ok(())
    }
}

/// The points of the largest case.
fn largest(cases: &[ContactProblem]) -> usize {
    cases.iter().map(|c| c.points().len()).max().unwrap_or(0)
}

/// The zone's ends along the profile's axis: the outermost stations of the
/// cases' points, their cells included.
fn zone_ends(cases: &[ContactProblem], axis: Axis) -> (f64, f64) {
    let mut ends = (f64::INFINITY, f64::NEG_INFINITY);
    for case in cases {
        let points = case.points();
        let half = 0.5
            * match axis {
                Axis::X => points.cell().dx,
                Axis::Y => points.cell().dy,
            };
        for s in axis.positions(points) {
            ends = (ends.0.min(s - half), ends.1.max(s + half));
        }
    }
    ends
}

impl DesignRequest {
    /// The design over the load cases `cases(f)` builds on the grid of
    /// fineness f, carried to convergence over `sequence` and verified (see
    /// the [module documentation](crate::sequence)). The reference
    /// intensities, if any, are per case and the same on every grid.
    /// `report` is told of every grid as it is done (designed, or
    /// evaluated to verify), for progress.
    ///
    /// # Errors
    /// [`DesignError::NotConverged`] when a grid would exceed
    /// [`GridSequence::max_points`] before the design converged and was
    /// verified; the errors of `cases` and of [`DesignRequest::run`].
    pub fn run_converged(
        &self,
        sequence: &GridSequence,
        mut cases: impl FnMut(f64) -> Result<Vec<ContactProblem>, DesignError>,
        mut report: impl FnMut(&Level),
    ) -> Result<Converged, DesignError> {
        sequence.check()?;
        let mut request = self.clone();
        let mut levels: Vec<Level> = Vec::new();
        let mut current: Option<Outcome> = None;
        let mut converged = false;
        for &fineness in &sequence.fineness {
            let start = Instant::now();
            let grid = cases(fineness)?;
            let points = largest(&grid);
            if points > sequence.max_points {
                break;
            }
            let references = request
                .reference_intensities
                .clone()
                .unwrap_or_else(|| vec![1.0; grid.len()]);
            if let (Some(outcome), true) = (&current, converged) {
                let analysis = Analysis::new(request.reanalysis, &request.reanalysis_options);
                let e = evaluate(&grid, request.axis, &outcome.profile, &analysis)?;
                let objective = e.relative_worst(&references);
                let verification = Level {
                    fineness,
                    points,
                    objective,
                    seconds: start.elapsed().as_secs_f64(),
                };
                report(&verification);
                let designed = levels.last().map_or(objective, |l| l.objective);
                if (objective - designed).abs() <= sequence.tolerance * designed {
                    return Ok(Converged {
                        outcome: current.expect("a design"),
                        levels,
                        verification,
                    });
                }
            }
            let mut outcome = request.run(&grid)?;
            let (lo, hi) = zone_ends(&grid, request.axis);
            outcome.profile = outcome.profile.extended(lo, hi);
            let objective = outcome.evaluation.relative_worst(&references);
            converged = levels
                .last()
                .is_some_and(|l| (objective - l.objective).abs() <= sequence.tolerance * objective);
            let level = Level {
                fineness,
                points,
                objective,
                seconds: start.elapsed().as_secs_f64(),
            };
            report(&level);
            levels.push(level);
            // The next grid starts from this design alone.
            request.starts = vec![outcome.profile.clone()];
            request.own_starts = false;
            current = Some(outcome);
        }
        Err(DesignError::NotConverged {
            objectives: levels.iter().map(|l| l.objective).collect(),
            tolerance: sequence.tolerance,
            max_points: sequence.max_points,
        })
    }
}
