//! The error of every output writer: the run's files (`output`) and the
//! staging directory they go through (`staging`) both return it, so it sits
//! below both.

use std::path::Path;

/// Errors writing outputs.
#[derive(Debug, thiserror::Error)]
pub enum OutputError {
    /// A file system operation failed. The cause is in the message and
    /// deliberately not a `source`, so that a chain printed on one line
    /// says it once.
    #[error("{path}: {error}")]
    Io {
        /// The path involved.
        path: String,
        /// The error.
        error: std::io::Error,
    },
    /// The output path exists and is not a directory.
    #[error("{0}: exists and is not a directory")]
    NotADirectory(String),
    /// A value to be written was not finite.
    #[error("refusing to write a non-finite number to {0}")]
    NonFinite(String),
}

/// Wraps an I/O error on `path` (for `map_err`).
pub(crate) fn io_err(path: &Path) -> impl FnOnce(std::io::Error) -> OutputError + '_ {
    move |error| OutputError::Io {
        path: path.display().to_string(),
        error,
    }
}
