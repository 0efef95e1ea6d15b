//! The discretization error of a run (result.json's `discretization`):
//! the scene's problem solved again on the coarser grids of its layout's
//! family (`elcon_analysis::GridFamily`, `h -> 2h -> 4h`), each quantity's
//! error estimated by generalized Richardson extrapolation
//! (`elcon_analysis::discretization`). On by default; `[solver]
//! error_estimate = false` turns it off.

use elcon_analysis::discretization::{Discretization, GridRun};
use elcon_analysis::{ContactSolution, ProblemBuilder};
use elcon_report::DiscretizationJson;
use elcon_scene::Scene;

/// The estimate of a run: `builder` the run's problem, `solution` its
/// solution. Whatever stops it (a layout with no family, a bad family) is
/// the block's note, every quantity not estimated: never the run's failure.
pub(crate) fn discretization(
    scene: &Scene,
    builder: &ProblemBuilder<'_>,
    solution: &ContactSolution,
) -> DiscretizationJson {
    let fine = GridRun {
        points: solution.forces.len(),
        spacing: f64::NAN,
        seconds: solution.assembly_seconds + solution.solve_seconds,
        failure: None,
    };
    let family = scene.grid_family().map_err(|e| e.to_string());
    let result = family.and_then(|family| {
        builder
            .discretization(&family, solution, scene.method(), scene.options())
            .map_err(|e| e.to_string())
    });
    let d = result.unwrap_or_else(|reason| {
        Discretization::not_estimated(vec![fine], |q| solution.quantity(q), &reason)
    });
    DiscretizationJson::of(&d)
}
