//! The design crate's errors: bad input named by field, the failures of the
//! layers below passed through, and a design whose re-analysis disagrees
//! with it (never returned as a result).

use elcon_analysis::{AnalysisError, Num};
use elcon_lcp::LcpError;

/// Everything that can stop a design.
#[derive(Debug, Clone, thiserror::Error)]
#[non_exhaustive]
pub enum DesignError {
    /// A scalar parameter is out of its range.
    #[error("`{field}` = {}: {reason}", Num(*value))]
    InvalidInput {
        /// The parameter.
        field: &'static str,
        /// The value given.
        value: f64,
        /// Why it is rejected, and the admissible range.
        reason: &'static str,
    },
    /// Inputs that do not go together (no load case, a displacement-controlled
    /// case, a profile that cannot be evaluated where it is needed...).
    #[error("`{field}`: {reason}")]
    Incompatible {
        /// The field.
        field: &'static str,
        /// Why, and what to give instead.
        reason: String,
    },
    /// A contact analysis (of a start, a crown, a re-analysis) failed.
    #[error("analysis of {stage} failed: {source}")]
    Analysis {
        /// Which analysis: "load case 2 of the re-analysis", ...
        stage: String,
        /// The analysis error.
        source: AnalysisError,
    },
    /// A machine element's system (a bearing designed over its own
    /// elements' loads) could not be built or solved.
    #[error("the bearing's analysis failed: {0}")]
    Element(#[from] elcon_elements::ElementsError),
    /// The design program could not be built or solved by the engine.
    #[error(
        "the design program failed: {0}; the descent solves the same problem by analyses \
         alone (design.method = \"descent\")"
    )]
    Engine(#[from] LcpError),
    /// The design's objective (its worst p_max) and that of its re-analysis
    /// differ by more than the tolerance: the design is not returned.
    #[error(
        "the design's objective {design:.6e} and its re-analysis' {reanalysis:.6e} differ by {relative:.2e} relative \
         (tolerance {tolerance:.1e})"
    )]
    Disagreement {
        /// The objective of the design program.
        design: f64,
        /// The objective of the re-analysis.
        reanalysis: f64,
        /// Their relative difference.
        relative: f64,
        /// The tolerance it exceeded.
        tolerance: f64,
    },
    /// A design's stress objective (`design.objective` = "von-mises" or
    /// "max-shear") that cannot be met: no body has a field below its
    /// surface, or the method asked for cannot take it.
    #[error("`design.objective` = \"{objective}\": {reason}")]
    Objective {
        /// The objective's name.
        objective: &'static str,
        /// Why, and what to give instead.
        reason: String,
    },
    /// A design carried over finer and finer grids that did not converge
    /// (or whose verification on a finer grid disagreed) before a grid
    /// exceeded the points allowed: its objective still depends on the
    /// grid.
    #[error(
        "the design did not converge over the grids within {max_points} points a case: its worst \
         objective on successive grids was {} (tolerance {tolerance:.1e} relative); allow more \
         points (design.max_points), a looser design.grid_tolerance, or a coarser start grid",
        listed(objectives)
    )]
    NotConverged {
        /// The worst objective on each design grid, coarse to fine.
        objectives: Vec<f64>,
        /// The relative tolerance.
        tolerance: f64,
        /// The most points a case may have.
        max_points: usize,
    },
}

/// Objectives as a short list for a message: "1.242, 1.238, 1.241".
fn listed(values: &[f64]) -> String {
    let parts: Vec<String> = values.iter().map(|v| format!("{v:.4}")).collect();
    if parts.is_empty() {
        "none".into()
    } else {
        parts.join(", ")
    }
}

elcon_num::rejected_into_invalid_input!(DesignError);

impl DesignError {
    /// An [`DesignError::Analysis`] for `stage`.
    pub(crate) fn analysis(stage: impl Into<String>) -> impl FnOnce(AnalysisError) -> Self {
        let stage = stage.into();
        move |source| Self::Analysis { stage, source }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn an_invalid_input_shows_its_value_in_the_shortest_form() {
        let e = DesignError::InvalidInput {
            field: "log_crown.design_load",
            value: 1e300,
            reason: "must be finite and > 0",
        };
        assert_eq!(
            e.to_string(),
            "`log_crown.design_load` = 1e300: must be finite and > 0"
        );
    }
}
