//! A design carried over a sequence of grids until it holds on a finer one.
//!
//! A design found on one grid fits that grid: a coarse grid averages a
//! roller's edge peak over its last cell, and a profile designed there can
//! peak far higher on a finer grid. So the correction is a function of
//! position (a linear family's closed form, a crown's, or a free profile's
//! drops at the first grid's stations, kept as knots, with the natural
//! cubic spline through them: `Profile::Spline`), and the design runs on
//! grids of growing fineness `f_0 = 1 < f_1 < ...` (the caller's grid
//! family at spacing `h / f`). After the design on grid k its profile is
//! evaluated on grid k + 1, and the design is kept when that worst
//! objective agrees with its own to the tolerance:
//!
//! ```text
//!     |v_(k+1) - t_k| <= tol t_k,     t_k = max_l p_max_l / r_l of the design on grid k,
//!                                     v_(k+1) the same profile's on grid k + 1
//! ```
//!
//! Otherwise the design goes on from grid k + 1, started from the last
//! one. A grid whose cases exceed [`GridSequence::max_points`] ends the
//! sequence without a design: [`DesignError::NotConverged`].

use std::time::Instant;

use elcon_analysis::ContactProblem;

use crate::evaluate::{Analysis, evaluate};
use crate::request::{DesignFamily, DesignRequest, Outcome};
use crate::{DesignError, Family};

/// How a design is carried over grids (see the [module documentation](self)).
#[derive(Debug, Clone, PartialEq)]
pub struct GridSequence {
    /// The grids' fineness, in order: the caller's grid at spacing `h / f`
    /// (default 1, 2, 3, 4, 6, 8, 12, 16).
    pub fineness: Vec<f64>,
    /// The relative agreement a design's worst objective on a finer grid
    /// must have with its own for the design to hold (default 0.01).
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
    /// Whether a design was made on it (else a design's profile was
    /// evaluated on it, to see whether it holds there).
    pub designed: bool,
}

/// A design that held on a finer grid than its own.
#[derive(Debug, Clone)]
pub struct Converged {
    /// The design on the last design grid.
    pub outcome: Outcome,
    /// The load cases on that grid.
    pub cases: Vec<ContactProblem>,
    /// The design grids, coarse to fine, with the objective on each.
    pub levels: Vec<Level>,
    /// The last design's profile (`outcome.profile`, exactly as it is
    /// returned) evaluated on the next finer grid, within the tolerance of
    /// its objective (`None` for a design made on one grid and not
    /// verified).
    pub verification: Option<Level>,
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

impl DesignRequest {
    /// The design over the load cases `cases(f)` builds on the grid of
    /// fineness f (`None` when that grid is beyond what may be built),
    /// carried over `sequence` until it holds on a finer grid (see the
    /// [module documentation](crate::sequence)). The reference
    /// intensities, if any, are per case and the same on every grid.
    /// `report` is told of every grid as it is done (designed, or
    /// evaluated to verify), for progress.
    ///
    /// # Errors
    /// [`DesignError::NotConverged`] when the grids run out (or exceed
    /// [`GridSequence::max_points`]) before a design held; the errors of
    /// `cases` and of [`DesignRequest::run`].
    pub fn run_converged(
        &self,
        sequence: &GridSequence,
        mut cases: impl FnMut(f64) -> Result<Option<Vec<ContactProblem>>, DesignError>,
        mut report: impl FnMut(&Level),
    ) -> Result<Converged, DesignError> {
        sequence.check()?;
        let mut request = self.clone();
        let mut levels: Vec<Level> = Vec::new();
        // The last design, with the cases of its grid.
        let mut current: Option<(Outcome, Vec<ContactProblem>)> = None;
        for &fineness in &sequence.fineness {
            let start = Instant::now();
            let Some(grid) = cases(fineness)? else {
                break;
            };
            let points = largest(&grid);
            if points > sequence.max_points {
                break;
            }
            if let Some((outcome, _)) = &current {
                let verification =
                    request.verify(&grid, &outcome.profile, fineness, points, start)?;
                report(&verification);
                let designed = levels.last().map_or(f64::NAN, |l| l.objective);
                if (verification.objective - designed).abs() <= sequence.tolerance * designed {
                    let (outcome, cases) = current.expect("a design");
                    return Ok(Converged {
                        outcome,
                        cases,
                        levels,
                        verification: Some(verification),
                    });
                }
            }
            if current.is_none()
                && request.knots.is_none()
                && request.family == DesignFamily::Linear(Family::Free)
            {
                // A free profile keeps the first grid's stations as its
                // knots: finer grids refine the analysis, not the profile,
                // which could otherwise fit each grid's points.
                let (stations, _) =
                    crate::axial_stations(grid.iter().map(ContactProblem::points), request.axis);
                request.knots = Some(stations);
            }
            let outcome = request.run(&grid)?;
            let level = Level {
                fineness,
                points,
                objective: outcome
                    .evaluation
                    .relative_worst(&request.references(grid.len())),
                seconds: start.elapsed().as_secs_f64(),
                designed: true,
            };
            report(&level);
            levels.push(level);
            // The next grid starts from this design alone.
            request.starts = vec![outcome.profile.clone()];
            request.own_starts = false;
            current = Some((outcome, grid));
        }
        Err(DesignError::NotConverged {
            objectives: levels.iter().map(|l| l.objective).collect(),
            tolerance: sequence.tolerance,
            max_points: sequence.max_points,
        })
    }

    /// The reference intensities of `n` cases (all 1 unless given).
    fn references(&self, n: usize) -> Vec<f64> {
        self.reference_intensities
            .clone()
            .unwrap_or_else(|| vec![1.0; n])
    }

    /// `profile` evaluated on `grid`: a verification [`Level`].
    ///
    /// `profile` is the design's own [`Profile`](crate::Profile), the one
    /// the user is given (result.json's `design.profile`, Python's
    /// `Design.profile`, sampled into profile.csv): a free profile's natural
    /// cubic spline through its knots, evaluated at each point of the finer
    /// grid by [`Profile::separations`](crate::Profile::separations), not
    /// a table of its values at the design grid's stations read linearly
    /// (a kink at every station, which a finer grid resolves into peaks).
    fn verify(
        &self,
        grid: &[ContactProblem],
        profile: &crate::Profile,
        fineness: f64,
        points: usize,
        start: Instant,
    ) -> Result<Level, DesignError> {
        let method = self.method_for(grid);
        let analysis = Analysis::new(method, &self.reanalysis_options);
        let e = evaluate(grid, self.axis, profile, &analysis)?;
        Ok(Level {
            fineness,
            points,
            objective: e.relative_worst(&self.references(grid.len())),
            seconds: start.elapsed().as_secs_f64(),
            designed: false,
        })
    }
}
