//! The elements crate's errors: engineering data named by field, and the
//! analysis' failures passed through.

use elcon_analysis::AnalysisError;
use elcon_analysis::Num;

/// Everything that can stop building or solving a machine element.
#[derive(Debug, Clone, thiserror::Error)]
#[non_exhaustive]
pub enum ElementsError {
    /// A value of the element's data out of its range.
    #[error("`{field}` = {}: {reason}", Num(*value))]
    InvalidInput {
        /// The field.
        field: &'static str,
        /// The given value.
        value: f64,
        /// Why it is rejected, in the user's terms.
        reason: String,
    },
    /// Under this load and clearance no element carries load (the rings
    /// part), or the reference model found no equilibrium.
    #[error("{0}")]
    NoEquilibrium(String),
    /// The system's analysis failed.
    #[error(transparent)]
    Analysis(#[from] AnalysisError),
}

impl ElementsError {
    /// An [`ElementsError::InvalidInput`].
    pub(crate) fn invalid(field: &'static str, value: f64, reason: impl Into<String>) -> Self {
        Self::InvalidInput {
            field,
            value,
            reason: reason.into(),
        }
    }
}
