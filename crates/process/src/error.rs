//! What can go wrong in the process plumbing: a file that cannot be
//! written, a panic caught at a scene's boundary, an interrupt, a memory
//! limit or a count of threads or jobs that is not admissible.

use std::path::{Path, PathBuf};

/// A count the process policy bounds ([`crate::threads`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Counted {
    /// The threads of a solve (`--threads`, `ELCON_THREADS`, Python's
    /// `threads=`).
    Threads,
    /// The runs of a batch in parallel (`--jobs`, Python's `jobs=`).
    Jobs,
}

/// Everything the process plumbing reports.
#[derive(Debug, Clone, thiserror::Error)]
#[non_exhaustive]
pub enum ProcessError {
    /// A file could not be read or written.
    #[error("{}: {reason}", path.display())]
    Io {
        /// The file.
        path: PathBuf,
        /// The operating system's reason.
        reason: String,
    },
    /// A failure that is not an answer to the input: a panic caught at the
    /// scene's boundary (the other scenes still run and are written).
    #[error(
        "scene `{scene}`: internal error (this is a bug; please report it with the scene): {message}"
    )]
    Bug {
        /// The scene's name.
        scene: String,
        /// The panic's message and place.
        message: String,
    },
    /// A run stopped by an interrupt (Ctrl-C, SIGINT, SIGTERM, Python's
    /// KeyboardInterrupt) before it finished: nothing of it was written.
    #[error("scene `{scene}`: interrupted before it finished; nothing of it was written")]
    Interrupted {
        /// The scene's name.
        scene: String,
    },
    /// A memory limit that is not a size ([`crate::parse_size`]).
    #[error("`{text}`: a memory limit must be {reason}")]
    Size {
        /// The text given.
        text: String,
        /// What a size must be.
        reason: &'static str,
    },
    /// An environment variable whose value is not what it must be.
    #[error("{name}={value}: {reason}")]
    Variable {
        /// The variable.
        name: &'static str,
        /// Its value.
        value: String,
        /// Why it is refused.
        reason: String,
    },
    /// A count of threads or jobs outside what the process policy admits
    /// (at least 1, at most a few per core).
    #[error("{}", counted_message(*what, given_by, *given, *per_core, *cores))]
    Count {
        /// Threads or jobs.
        what: Counted,
        /// Where the count was given (`--threads / ELCON_THREADS`, `jobs`).
        given_by: String,
        /// The count.
        given: usize,
        /// The most per core.
        per_core: usize,
        /// The cores of this machine.
        cores: usize,
    },
    /// The thread pool could not be built.
    #[error("the thread pool: {reason}")]
    Pool {
        /// rayon's reason.
        reason: String,
    },
}

/// A [`ProcessError::Count`]'s message: zero, or more than the cores admit.
fn counted_message(
    what: Counted,
    source: &str,
    given: usize,
    per_core: usize,
    cores: usize,
) -> String {
    let most = per_core * cores;
    match (what, given) {
        (Counted::Threads, 0) => format!("{source} = 0: the threads must be at least 1"),
        (Counted::Jobs, 0) => {
            format!("{source} = 0: give at least 1 run in parallel (leave it out for one per core)")
        }
        (Counted::Threads, _) => format!(
            "{source} = {given}: at most {per_core} threads per core, {most} on this machine's \
             {cores} (more only switch between themselves)"
        ),
        (Counted::Jobs, _) => format!(
            "{source} = {given}: at most {per_core} runs per core, {most} on this machine's \
             {cores} cores (more only add memory and contention)"
        ),
    }
}

impl ProcessError {
    /// An [`ProcessError::Io`] for `path`.
    pub fn io(path: &Path, e: impl std::fmt::Display) -> Self {
        Self::Io {
            path: path.to_path_buf(),
            reason: e.to_string(),
        }
    }
}
