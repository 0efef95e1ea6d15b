//! The analysis crate's errors: bad input named by field, and the failures
//! of the layers below, passed through.

use elcon_influence::InfluenceError;
use elcon_lcp::LcpError;
pub use elcon_num::Num;

/// Everything that can stop a contact analysis.
#[derive(Debug, Clone, thiserror::Error)]
#[non_exhaustive]
pub enum AnalysisError {
    /// A scalar input is out of its physical range.
    #[error("`{field}` = {}: {reason}", Num(*value))]
    InvalidInput {
        /// The field.
        field: &'static str,
        /// The given value.
        value: f64,
        /// Why it is rejected.
        reason: &'static str,
    },
    /// A vector or matrix does not match the number of points.
    #[error("`{field}` has {found} entries, expected {expected} (one per candidate point)")]
    SizeMismatch {
        /// The field.
        field: &'static str,
        /// The number of points.
        expected: usize,
        /// The size given.
        found: usize,
    },
    /// A vector holds NaN or an infinity.
    #[error("`{field}` has a non-finite value ({}) at point {index}", Num(*value))]
    NonFinite {
        /// The field.
        field: &'static str,
        /// The point.
        index: usize,
        /// The value.
        value: f64,
    },
    /// A matrix holds NaN or an infinity (an influence matrix given by
    /// [`ContactProblem::from_parts`](crate::ContactProblem::from_parts)).
    #[error("`{field}`[{row}, {column}] = {}: must be a finite number", Num(*value))]
    NonFiniteEntry {
        /// The field.
        field: &'static str,
        /// The entry's row.
        row: usize,
        /// The entry's column.
        column: usize,
        /// The value.
        value: f64,
    },
    /// Inputs that do not go together (a sphere on a line contact...).
    #[error("`{field}`: {reason}")]
    Incompatible {
        /// The field.
        field: &'static str,
        /// Why, and what to use instead.
        reason: String,
    },
    /// A method needs S's entries and the problem holds S without them
    /// (matrix-free).
    #[error(
        "{what} reads the entries of S, which this problem holds matrix-free (storage \
         \"{storage}\"): build it with the dense or folded storage"
    )]
    NeedsEntries {
        /// What needs them.
        what: &'static str,
        /// How the problem holds S.
        storage: crate::storage::Storage,
    },
    /// A tabulated surface (a height map, a profile) that is not valid, or
    /// does not cover a candidate point: `label` names it (its file).
    #[error("{label}: {reason}")]
    Table {
        /// What names the table: its file, or the key it was given under.
        label: String,
        /// What is wrong, and where (the row, the point).
        reason: String,
    },
    /// A system of contacts that is not valid: `field` names the body or
    /// zone (its index and name) and what of it.
    #[error("`{field}`: {reason}")]
    System {
        /// The body or zone, and its field.
        field: String,
        /// What is wrong.
        reason: String,
    },
    /// A body of a system whose motion no contact zone can restrain: it
    /// would move without bound under any load.
    #[error(
        "body `{body}`: its {motion} is restrained by no contact zone's candidate points; \
         fix or prescribe it, or add a zone that holds it"
    )]
    Unrestrained {
        /// The body's name.
        body: String,
        /// The motion (or the largest part of a combination) left free.
        motion: &'static str,
    },
    /// The Newton steps of a system's solve stopped short of equilibrium.
    #[error(
        "the system's bodies did not reach equilibrium after {iterations} steps (residual {}); \
         check that the loads can be carried by the zones' candidate points",
        Num(*residual)
    )]
    SystemNotConverged {
        /// The steps taken.
        iterations: usize,
        /// The largest relative equilibrium residual reached.
        residual: f64,
    },
    /// The influence models rejected the bodies or the points.
    #[error(transparent)]
    Influence(#[from] InfluenceError),
    /// The pivoting engine failed (no solution, pivot limit, inaccuracy...).
    #[error("the contact solve failed: {0}")]
    Engine(#[from] LcpError),
}

elcon_num::rejected_into_invalid_input!(AnalysisError);

impl AnalysisError {
    /// A [`AnalysisError::Table`] error of the table `label`.
    pub(crate) fn table(label: &str, reason: impl Into<String>) -> Self {
        Self::Table {
            label: label.to_string(),
            reason: reason.into(),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn an_invalid_input_shows_its_value_briefly() {
        let e = AnalysisError::InvalidInput {
            field: "load",
            value: 1e300,
            reason: "too large",
        };
        assert_eq!(e.to_string(), "`load` = 1e300: too large");
        let e = AnalysisError::NonFinite {
            field: "separation",
            index: 3,
            value: f64::NAN,
        };
        assert_eq!(
            e.to_string(),
            "`separation` has a non-finite value (NaN) at point 3"
        );
    }
}
