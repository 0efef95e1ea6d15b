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

use elcon_influence::{Dimension, PointSet};
use elcon_lcp::{Method, Options};

use super::builder::ProblemBuilder;
use super::geometry::Geometry;
use super::solution::ContactSolution;
use crate::AnalysisError;
use crate::discretization::{Discretization, GridRun, MIN_CELLS_ACROSS, Quantity, estimate};
use crate::grid::GridFamily;

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
        let mut solutions = vec![fine.clone()];
        let mut note = None;
        let mut current = *family;
        for level in 1..=COARSER_GRIDS {
            match self.coarse(&current, fine, level) {
                Err(why) => {
                    note = Some(why);
                    break;
                }
                Ok((coarse, points)) => {
                    let start = Instant::now();
                    let solved = self
                        .on(points)
                        .build()
                        .and_then(|p| p.solve(method, options));
                    let seconds = start.elapsed().as_secs_f64();
                    let spacing = coarse.spacing();
                    let points = solved.as_ref().map_or(0, |s| s.forces.len());
                    let failure = match &solved {
                        Ok(s) if s.certificate.holds() => None,
                        Ok(s) => Some(format!("not certified ({})", s.certificate)),
                        Err(e) => Some(e.to_string()),
                    };
                    grids.push(GridRun {
                        points,
                        spacing,
                        seconds,
                        failure: failure.clone(),
                    });
                    if let Some(f) = failure {
                        note = Some(format!(
                            "the grid at {} times the spacing failed: {f}",
                            1 << level
                        ));
                        break;
                    }
                    solutions.extend(solved.ok());
                    current = coarse;
                }
            }
        }
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

    /// The grid coarser than `current` and its points, if it is made and
    /// resolves `fine`'s contact; else why not. `level` 1 is 2h, 2 is 4h.
    fn coarse(
        &self,
        current: &GridFamily,
        fine: &ContactSolution,
        level: usize,
    ) -> Result<(GridFamily, PointSet), String> {
        let times = 1 << level;
        let coarse = current.coarser().ok_or_else(|| {
            format!(
                "the grid at {times} times the spacing would have fewer than {} points along an \
                 axis",
                crate::grid::MIN_COARSE_COUNT
            )
        })?;
        let points = coarse
            .points()
            .map_err(|e| format!("the grid at {times} times the spacing: {e}"))?;
        let cells = cells_across(self.points(), fine, &points);
        if !(cells >= MIN_CELLS_ACROSS) {
            return Err(format!(
                "the contact spans {cells:.1} cells of the grid at {times} times the spacing, \
                 fewer than {MIN_CELLS_ACROSS}: too few points to resolve it"
            ));
        }
        Ok((coarse, points))
    }
}

/// The fewest cells of `coarse` the contact of `fine` (on `points`) spans
/// along an axis: its extent along x (and y on a surface), point to point
/// plus a cell of the fine grid, over the coarse cell. 0 without contact.
fn cells_across(points: &PointSet, fine: &ContactSolution, coarse: &PointSet) -> f64 {
    if fine.contact.is_empty() {
        return 0.0;
    }
    let span = |coordinate: &dyn Fn(usize) -> f64, cell: f64| {
        let (lo, hi) = fine
            .contact
            .iter()
            .map(|&k| coordinate(k))
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), v| {
                (lo.min(v), hi.max(v))
            });
        hi - lo + cell
    };
    let (fine_cell, coarse_cell) = (points.cell(), coarse.cell());
    let along_x = span(&|k| points.x(k), fine_cell.dx) / coarse_cell.dx;
    match points.dimension() {
        Dimension::Line => along_x,
        Dimension::Surface => along_x.min(span(&|k| points.y(k), fine_cell.dy) / coarse_cell.dy),
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
