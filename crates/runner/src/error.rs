//! What can stop a run, a batch or a merge: the scene's own errors, the
//! process's (a file, a panic, an interrupt), the report's, and the
//! runner's: a scene too big for the memory, a solve or design that failed,
//! shards that do not make one batch.

use elcon_process::ProcessError;
use elcon_report::ReportError;
use elcon_scene::{Scene, SceneError};

/// Everything that can stop a scene's run, a batch or a merge.
#[derive(Debug, Clone, thiserror::Error)]
#[non_exhaustive]
pub enum RunError {
    /// The scene or batch file is not valid, or cannot be read.
    #[error(transparent)]
    Scene(#[from] SceneError),
    /// A file that could not be written, a panic caught at the scene's
    /// boundary, an interrupt.
    #[error(transparent)]
    Process(#[from] ProcessError),
    /// An output that could not be written or read back.
    #[error(transparent)]
    Report(#[from] ReportError),
    /// A scene whose estimated peak memory exceeds what this process may
    /// use: refused before anything large is allocated.
    #[error(
        "scene `{scene}`: too big for the memory available: {needed}; the ceiling is {ceiling}. \
         What helps: {hints}"
    )]
    TooBig {
        /// The scene's name.
        scene: String,
        /// N, the estimate and what it is made of.
        needed: String,
        /// The ceiling and what set it.
        ceiling: String,
        /// What would make it fit.
        hints: String,
    },
    /// A valid scene whose solve failed (no solution, pivot limit, a design
    /// that could not be certified...).
    #[error("scene `{scene}`: {reason}")]
    Run {
        /// The scene's name.
        scene: String,
        /// The failure, from the solver crates.
        reason: String,
    },
    /// `elcon merge` was given directories that are not every shard of one
    /// batch, each once, or rows that conflict.
    #[error("merge: {reason}")]
    Merge {
        /// What is wrong, naming the directories.
        reason: String,
    },
}

impl RunError {
    /// Whether the error is in the file (syntax, schema or value) rather
    /// than in a solve or an output.
    pub fn is_input_error(&self) -> bool {
        matches!(self, Self::Scene(e) if e.is_input_error())
    }

    /// Whether the run was stopped by an interrupt before it finished.
    pub fn is_interrupted(&self) -> bool {
        matches!(self, Self::Process(ProcessError::Interrupted { .. }))
    }

    /// A [`ProcessError::Io`] for `path`.
    pub(crate) fn io(path: &std::path::Path, e: impl std::fmt::Display) -> Self {
        ProcessError::io(path, e).into()
    }
}

/// A failure of the run of `scene` (its assembly, solve or design stage),
/// named by the scene.
pub(crate) fn run_error(scene: &Scene, e: impl std::fmt::Display) -> RunError {
    // A scene has no tableau key (elcon chooses it): the engine's advice
    // about one becomes the scene's key that helps.
    let reason = e.to_string().replace(
        elcon_lcp::TABLEAU_ADVICE,
        "use another method (`solver.method`: a pivoting method takes what the conjugate \
         gradient cannot)",
    );
    RunError::Run {
        scene: scene.name().to_string(),
        reason,
    }
}
