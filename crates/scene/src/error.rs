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

/// Everything that can be wrong with a scene or batch file as read.
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
    /// A valid scene whose problem cannot be laid out or planned (the
    /// points of a design load, the storage and method of its solve).
    #[error("scene `{scene}`: {reason}")]
    Layout {
        /// The scene's name.
        scene: String,
        /// Why, from the solver crates.
        reason: String,
    },
    /// Candidate points that cannot be laid out: a layout relative to a
    /// Hertz contact that does not apply, sizes the grids refuse, more
    /// points than elcon lays out. The reason alone: where it is met names
    /// the scene or the field.
    #[error("{reason}")]
    Points {
        /// Why, from the layout or the solver crates.
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
    pub fn io(path: &Path, e: impl std::fmt::Display) -> Self {
        Self::Io {
            path: path.to_path_buf(),
            reason: e.to_string(),
        }
    }

    /// A [`SceneError::Points`] saying `reason`.
    pub fn points(reason: impl std::fmt::Display) -> Self {
        Self::Points {
            reason: reason.to_string(),
        }
    }

    /// Whether the error is in the file (syntax, schema or value) rather
    /// than in a solve or an output.
    pub fn is_input_error(&self) -> bool {
        matches!(self, Self::Syntax { .. } | Self::Invalid { .. })
    }
}
