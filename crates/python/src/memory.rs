//! The memory ceiling the command line uses, and the check of a solve's
//! estimate against it before anything of size N x N is allocated.

use elcon_analysis::{Plan, Relief};
use elcon_process::{Ceiling, human};
use elcon_runner::BASELINE;
use pyo3::prelude::*;

use crate::errors::{SceneError, SolveError};

/// The memory ceiling of this process, as the command line computes it
/// (`ELCON_MEMORY_LIMIT` lowers it).
pub(crate) fn ceiling() -> PyResult<Ceiling> {
    Ceiling::of_this_process(None).map_err(|e| SceneError::new_err(e.to_string()))
}

/// Refuses a solve whose estimate (`plan`) does not fit under `ceiling`,
/// saying what would help.
pub(crate) fn admit(plan: &Plan, ceiling: &Ceiling) -> PyResult<()> {
    let e = &plan.estimate;
    let peak = (e.solve_bytes.max(0.0) as u64).saturating_add(BASELINE);
    if ceiling.admits(peak) {
        return Ok(());
    }
    let mut hints = Vec::new();
    for relief in e.reliefs() {
        match relief {
            Relief::MatrixFree => hints.push(
                "storage=\"lattice\" (matrix-free: points on a regular grid, no beam) with \
                 method=\"conjugate-gradient\"",
            ),
            Relief::FewerMatrices => hints.push("method=\"block-pivoting\" (fewer matrices)"),
            _ => {}
        }
    }
    hints.push("fewer points");
    Err(SolveError::new_err(format!(
        "too big for the memory available: N = {} points ({} unknowns) needs about {} ({}); \
         the ceiling is {}. What helps: {}",
        e.points,
        e.unknowns,
        human(peak),
        e.holding(),
        ceiling,
        hints.join("; ")
    )))
}
