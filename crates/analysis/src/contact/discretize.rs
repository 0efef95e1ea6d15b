//! The discretization error of a solution: the same problem (bodies,
//! geometry, loading, storage rule, method) solved on the coarser grids of
//! its family, `h -> 2h` and `4h` (`crate::grid::GridFamily::coarser`: a
//! quarter and a sixteenth of the points on a surface, a half and a quarter
//! on a line), and each quantity's values put through the generalized
//! Richardson estimate of `crate::discretization`.
//!
//! A coarser grid is solved only while it resolves the contact: the fine
//! contact spans at least [`MIN_CELLS_ACROSS`] of its cells along each
//! axis. A coarse solve that fails, or is not certified, ends the sequence
//! there (the quantities are then estimated from fewer grids, or not
//! estimated, with the reason); it never fails the estimate. The coarse
//! problems are built and dropped one at a time after the fine solve: each
//! holds at most a quarter of the fine problem's S on a line and a
//! sixteenth on a surface.

use std::time::Instant;

use elcon_influence::PointSet;
use elcon_lcp::{Method, Options};

use super::builder::ProblemBuilder;
use super::geometry::Geometry;
use super::solution::ContactSolution;
use crate::AnalysisError;
use crate::discretization::{Discretization, GridRun, MIN_CELLS_ACROSS, Quantity, estimate};
use crate::grid::GridFamily;
use crate::subsurface::contact_spans;

/// The coarser grids solved beyond the fine one (2h and 4h).
const COARSER_GRIDS: usize = 2;

impl ProblemBuilder<'_> {
    /// The discretization error of `fine`, this builder's problem solved on
    /// `family`'s points by `method` with `options`: the same problem
    /// solved on the family's coarser grids (see the module
    /// documentation), each quantity of [`Quantity::ALL`] estimated. A
    /// problem whose separations are given per point has no coarser
    /// problem: every quantity is then not estimated, with that reason.
    ///
    /// # Errors
    /// [`AnalysisError::Incompatible`] when `family` does not lay out this
    /// builder's number of points, [`AnalysisError::SizeMismatch`] when
    /// `fine` is not a solution on them; the coarse grids' failures are
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
        let mut grids = vec![GridRun {
            points: n,
            spacing: family.spacing(),
            seconds: fine.assembly_seconds + fine.solve_seconds,
            failure: None,
        }];
        if let Geometry::Separation(_) = self.geometry() {
            let reason = "the separations are given per point: a coarser grid has none";
            return Ok(Discretization::not_estimated(
                grids,
                |q| value(fine, q),
                reason,
            ));
        }
        let (solutions, stop) = self.coarser_solutions(family, fine, method, options, &mut grids);
        let note = stop.map(|stop| stop.to_string());
        let spacings: Vec<f64> = grids
            .iter()
            .filter(|g| g.failure.is_none())
            .map(|g| g.spacing)
            .collect();
        let estimates = Quantity::ALL
            .iter()
            .map(|&q| {
                let values: Vec<f64> = solutions.iter().map(|s| value(s, q)).collect();
                let mut e = estimate(&values, &spacings, scale(&solutions, q));
                if let (Some(reason), Some(why)) = (e.verdict.reason(), &note) {
                    e.verdict = crate::discretization::Verdict::NotEstimated(format!(
                        "{}: {why}",
                        reason.split(':').next().unwrap_or(reason)
                    ));
                }
                (q, e)
            })
            .collect();
        Ok(Discretization {
            grids,
            estimates,
            note,
        })
    }

    /// `fine` and its problem solved on the coarser grids of `family`, each
    /// logged in `grids`, until one is not made, does not resolve the
    /// contact or fails ([`Stop`], why the sequence ended early).
    fn coarser_solutions(
        &self,
        family: &GridFamily,
        fine: &ContactSolution,
        method: Method,
        options: &Options,
        grids: &mut Vec<GridRun>,
    ) -> (Vec<ContactSolution>, Option<Stop>) {
        let mut solutions = vec![fine.clone()];
        let mut current = *family;
        for level in 1..=COARSER_GRIDS {
            let (coarse, points) = match self.coarse(&current, fine, level) {
                Ok(grid) => grid,
                Err(stop) => return (solutions, Some(stop)),
            };
            let start = Instant::now();
            let solved = self
                .on(points)
                .build()
                .and_then(|p| p.solve(method, options));
            let seconds = start.elapsed().as_secs_f64();
            let failure = match &solved {
                Ok(s) if s.certificate.holds() => None,
                Ok(s) => Some(format!("not certified ({})", s.certificate)),
                Err(e) => Some(e.to_string()),
            };
            grids.push(GridRun {
                points: solved.as_ref().map_or(0, |s| s.forces.len()),
                spacing: coarse.spacing(),
                seconds,
                failure: failure.clone(),
            });
            if let Some(failure) = failure {
                let times = 1 << level;
                return (solutions, Some(Stop::Failed { times, failure }));
            }
            solutions.extend(solved.ok());
            current = coarse;
        }
        (solutions, None)
    }

    /// The grid coarser than `current` and its points, if it is made and
    /// resolves `fine`'s contact; else why not. `level` 1 is 2h, 2 is 4h.
    fn coarse(
        &self,
        current: &GridFamily,
        fine: &ContactSolution,
        level: usize,
    ) -> Result<(GridFamily, PointSet), Stop> {
        let times = 1 << level;
        let coarse = current.coarser().ok_or(Stop::TooFewPoints { times })?;
        let points = coarse
            .points()
            .map_err(|error| Stop::NoPoints { times, error })?;
        let cells = cells_across(self.points(), &fine.contact, &points);
        if !(cells >= MIN_CELLS_ACROSS) {
            return Err(Stop::Unresolved { times, cells });
        }
        Ok((coarse, points))
    }
}

/// Why the sequence of coarser grids ended before [`COARSER_GRIDS`]: the
/// discretization's note, each grid named by its spacing's multiple
/// `times` of the fine one (2 or 4).
#[derive(Debug)]
enum Stop {
    /// The coarser grid would have fewer than
    /// [`MIN_COARSE_COUNT`](crate::grid::MIN_COARSE_COUNT) points along an
    /// axis.
    TooFewPoints { times: usize },
    /// Its points could not be laid out.
    NoPoints { times: usize, error: AnalysisError },
    /// The contact spans fewer than [`MIN_CELLS_ACROSS`] of its cells.
    Unresolved { times: usize, cells: f64 },
    /// Its solve failed or was not certified.
    Failed { times: usize, failure: String },
}

impl std::fmt::Display for Stop {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Stop::TooFewPoints { times } => write!(
                f,
                "the grid at {times} times the spacing would have fewer than {} points along an \
                 axis",
                crate::grid::MIN_COARSE_COUNT
            ),
            Stop::NoPoints { times, error } => {
                write!(f, "the grid at {times} times the spacing: {error}")
            }
            Stop::Unresolved { times, cells } => write!(
                f,
                "the contact spans {cells:.1} cells of the grid at {times} times the spacing, \
                 fewer than {MIN_CELLS_ACROSS}: too few points to resolve it"
            ),
            Stop::Failed { times, failure } => {
                write!(f, "the grid at {times} times the spacing failed: {failure}")
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
                Stop::TooFewPoints { times: 2 },
                "the grid at 2 times the spacing would have fewer than",
            ),
            (
                Stop::NoPoints {
                    times: 4,
                    error: AnalysisError::Incompatible {
                        field: "family",
                        reason: "no points".into(),
                    },
                },
                "the grid at 4 times the spacing: ",
            ),
            (
                Stop::Unresolved {
                    times: 2,
                    cells: 3.04,
                },
                "the contact spans 3.0 cells of the grid at 2 times the spacing, fewer than",
            ),
            (
                Stop::Failed {
                    times: 4,
                    failure: "not certified".into(),
                },
                "the grid at 4 times the spacing failed: not certified",
            ),
        ];
        for (stop, begins) in stops {
            let text = stop.to_string();
            assert!(text.starts_with(begins), "{text}");
        }
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
