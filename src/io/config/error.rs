//! The config layer's one error type: one line, naming the key, or the
//! file and line.

use crate::sim::ScenarioError;

/// A configuration error: one line, naming the key, or the file and line.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
pub enum ConfigError {
    /// A key with a value of the wrong type, or a key or section that does
    /// not exist.
    #[error("{key}: {message}")]
    Key {
        /// `section.key` (or the section).
        key: String,
        /// What is wrong and what is allowed.
        message: String,
    },
    /// A value that breaks a rule of the scenario (out of range, or in
    /// conflict with another).
    #[error(transparent)]
    Scenario(#[from] ScenarioError),
    /// A file that cannot be parsed, at a line.
    #[error("{file}:{line}: {message}")]
    Syntax {
        /// The file (or `preset NAME`).
        file: String,
        /// 1-based line.
        line: usize,
        /// The parser's message.
        message: String,
    },
    /// A file that cannot be read at all.
    #[error("{file}: {message}")]
    File {
        /// The file.
        file: String,
        /// Why.
        message: String,
    },
    /// A record file named by a key that cannot be read; the message names
    /// the file and, where one applies, its line.
    #[error("{key}: {message}")]
    Record {
        /// The key at fault: `excitation.file_h`, or the `unit_*` or `dt_*`
        /// key when the unit or time step is what is wrong.
        key: String,
        /// The record file as read (the path the message starts with).
        file: String,
        /// The reader's one-line error.
        message: String,
    },
    /// A command-line option used wrongly (`--set` without `=`, an unknown
    /// preset, both `--preset` and `--config`).
    #[error("{0}")]
    Usage(String),
}

impl ConfigError {
    /// An error about `key`.
    pub fn key(key: &str, msg: impl std::fmt::Display) -> Self {
        Self::Key {
            key: key.to_string(),
            message: msg.to_string(),
        }
    }
}
