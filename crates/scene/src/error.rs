//! The scene crate's errors. Every message about a file names the file, the
//! line and column, and the field; every failure of a run names the scene.

use std::path::{Path, PathBuf};

/// A place in a scene file: 1-based line and column.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Location {
    /// Line, from 1.
    pub line: usize,
    /// Column, from 1 (in characters).
    pub column: usize,
}

impl Location {
    /// The line and column of byte `offset` in `text`.
    pub fn of(text: &str, offset: usize) -> Self {
        // Offsets from the parser fall on character boundaries; any other
        // offset counts the whole text.
        let before = text.get(..offset.min(text.len())).unwrap_or(text);
        let line = before.matches('\n').count() + 1;
        let column = before
            .rsplit_once('\n')
            .map_or(before, |(_, tail)| tail)
            .chars()
            .count()
            + 1;
        Self { line, column }
    }
}

/// Everything that can stop a scene, a batch or an output.
#[derive(Debug, Clone, thiserror::Error)]
#[non_exhaustive]
pub enum SceneError {
    /// A file could not be read or written.
    #[error("{}: {reason}", path.display())]
    Io {
        /// The file.
        path: PathBuf,
        /// The operating system's reason.
        reason: String,
    },
    /// The file is not valid TOML, or does not fit the schema (an unknown
    /// key, a missing one, a value of the wrong type).
    #[error("{}:{}:{}: {message}", file.display(), at.line, at.column)]
    Syntax {
        /// The file.
        file: PathBuf,
        /// Where.
        at: Location,
        /// The parser's message (it names the key).
        message: String,
    },
    /// A value is out of its physical range, or values do not go together.
    #[error("{}:{}:{}: `{field}`{}: {reason}", file.display(), at.line, at.column, shown(value))]
    Invalid {
        /// The file.
        file: PathBuf,
        /// Where the value is.
        at: Location,
        /// The field, as a dotted path (`body1.poissons_ratio`).
        field: String,
        /// The value, printed.
        value: String,
        /// Why it is rejected and what is admissible.
        reason: String,
    },
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
    /// `elcon merge` was given directories that are not every shard of one
    /// batch, each once, or rows that conflict.
    #[error("merge: {reason}")]
    Merge {
        /// What is wrong, naming the directories.
        reason: String,
    },
    /// A run stopped by an interrupt (Ctrl-C, SIGINT, SIGTERM, Python's
    /// KeyboardInterrupt) before it finished: nothing of it was written.
    #[error("scene `{scene}`: interrupted before it finished; nothing of it was written")]
    Interrupted {
        /// The scene's name.
        scene: String,
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
}

/// ` = value` for a message, or nothing for an empty value (a field that
/// is missing, or a section as a whole).
fn shown(value: &str) -> String {
    if value.is_empty() {
        String::new()
    } else {
        format!(" = {value}")
    }
}

impl SceneError {
    /// An [`SceneError::Io`] for `path`.
    pub(crate) fn io(path: &Path, e: impl std::fmt::Display) -> Self {
        Self::Io {
            path: path.to_path_buf(),
            reason: e.to_string(),
        }
    }

    /// Whether the error is in the file (syntax, schema or value) rather
    /// than in a solve or an output.
    pub fn is_input_error(&self) -> bool {
        matches!(self, Self::Syntax { .. } | Self::Invalid { .. })
    }
}
