//! The separation that makes the contact forces exactly a target
//! distribution (the seed's Fig. 6 comparison curve).
//!
//! With every point in contact (`Y = 0`) and the target forces `F`, the
//! compatibility condition `Y = S F + eps + y - alpha e = 0` gives the
//! correction
//!
//! ```text
//!     y_k = alpha - (S F)_k - eps_k,     alpha = max_k ((S F)_k + eps_k)
//! ```
//!
//! alpha chosen so that the smallest correction is 0. The target is given as
//! non-negative weights `w`, scaled to the case's load: `F = P w / sum w`;
//! uniform pressure (the default) is `w_k = A_k`, `F_k / A_k = P / sum A`.
//! Re-analysed with `eps + y`, the contact solution is the target itself
//! (every `Y_k = 0`, `F_k >= 0`: complementary, and unique for S positive
//! definite).

use elcon_analysis::ContactProblem;

use crate::DesignError;
use crate::evaluate::load_of;

/// A correction that produces a target force distribution.
#[derive(Debug, Clone, PartialEq)]
pub struct TargetSeparation {
    /// The correction y_k at each point, smallest 0 (length).
    pub correction: Vec<f64>,
    /// The target forces F_k (force; per unit width on a 2D line).
    pub forces: Vec<f64>,
    /// The approach alpha at which every point touches (length).
    pub approach: f64,
}

/// The correction that gives a uniform pressure: `F_k = P A_k / sum A`.
///
/// # Errors
/// As [`target_separation`].
pub fn uniform_target(case: &ContactProblem) -> Result<TargetSeparation, DesignError> {
    let points = case.points();
    target_separation(case, &points.measures())
}

/// The correction that gives the forces `F = P w / sum w`.
///
/// # Errors
/// [`DesignError::Incompatible`] when `weights` does not have one entry per
/// point or the case is displacement controlled; [`DesignError::InvalidInput`]
/// for a weight that is negative or not finite, or weights that sum to 0.
pub fn target_separation(
    case: &ContactProblem,
    weights: &[f64],
) -> Result<TargetSeparation, DesignError> {
    let n = case.points().len();
    let load = load_of(case, 0)?;
    if weights.len() != n {
        return Err(DesignError::Incompatible {
            field: "weights",
            reason: format!(
                "has {} entries, expected {n} (one per point)",
                weights.len()
            ),
        });
    }
    if let Some(&w) = weights.iter().find(|w| !(w.is_finite() && **w >= 0.0)) {
        return Err(DesignError::InvalidInput {
            field: "weights",
            value: w,
            reason: "every weight must be finite and >= 0",
        });
    }
    let total: f64 = weights.iter().sum();
    if !(total > 0.0) {
        return Err(DesignError::InvalidInput {
            field: "weights",
            value: total,
            reason: "the weights must not all be 0",
        });
    }
    let forces: Vec<f64> = (0..n).map(|k| load * weights[k] / total).collect();
    // The elastic deflection under the target forces, S F.
    let deflection = case
        .deflection(&forces)
        .map_err(DesignError::analysis("the uniform target's deflection"))?;
    let eps = case.separation();
    let approach = (0..n)
        .map(|k| deflection[k] + eps[k])
        .fold(f64::NEG_INFINITY, f64::max);
    let correction = (0..n).map(|k| approach - deflection[k] - eps[k]).collect();
    Ok(TargetSeparation {
        correction,
        forces,
        approach,
    })
}
