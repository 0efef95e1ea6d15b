//! What can stop a report: a file that cannot be written or read back, a
//! plot that cannot be drawn.

use std::path::{Path, PathBuf};

use elcon_process::ProcessError;

/// Everything writing or reading a report can fail with.
#[derive(Debug, Clone, thiserror::Error)]
#[non_exhaustive]
pub enum ReportError {
    /// A file or directory that could not be written whole.
    #[error(transparent)]
    Write(#[from] ProcessError),
    /// A plot that could not be drawn into its file.
    #[error("{}: {reason}", path.display())]
    Plot {
        /// The plot's file.
        path: PathBuf,
        /// plotters' reason.
        reason: String,
    },
    /// A plot that could not be drawn (before it has a file).
    #[error("the plot cannot be drawn: {reason}")]
    Draw {
        /// plotters' reason.
        reason: String,
    },
    /// A result or table that could not be serialized, or read back.
    #[error("{}: {reason}", path.display())]
    Json {
        /// The file.
        path: PathBuf,
        /// serde_json's reason.
        reason: String,
    },
}

impl ReportError {
    /// A [`ReportError::Json`] for `path`.
    pub(crate) fn json(path: &Path, e: impl std::fmt::Display) -> Self {
        Self::Json {
            path: path.to_path_buf(),
            reason: e.to_string(),
        }
    }
}
