//! What one start of a design method found: its parameters, objective,
//! last analyses and how its objective was measured.

use elcon_analysis::ContactSolution;

use crate::prepared::Solver;
use crate::subsurface::Criterion;

/// What one start of a method found: the parameters (the program's, or
/// the descent's, before the profile is shifted to a smallest drop of 0),
/// its worst intensities, and how.
pub(crate) struct Found {
    pub(crate) theta: Vec<f64>,
    /// The worst `p_max_l / r_l` of its own solutions.
    pub(crate) objective: f64,
    /// Their worst `max_k F_k / A_k`.
    pub(crate) max_intensity: f64,
    /// The descent's last analyses (warm starts of the re-analysis).
    pub(crate) solutions: Option<Vec<ContactSolution>>,
    pub(crate) solver: Solver,
    /// How its objective was measured (the re-analysis is measured alike).
    pub(crate) criterion: Criterion,
}
