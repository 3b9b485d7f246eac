//! The Python exceptions and the mapping of the core's errors onto them.
//!
//! Every exception carries the one-line message the CLI prints after
//! `error: `, formatted the same way (an `anyhow` chain printed with
//! `{:#}`), so a message can be searched for in the CLI's docs and tests.
//! Bad input (the CLI's exit 2) is a [`ConfigError`]; a run that fails
//! after its input was accepted (exit 1) is a [`RunError`].

use pyo3::exceptions::{PyRuntimeError, PyValueError};
use pyo3::prelude::*;
use rocking::io::ConfigError as CoreConfigError;

pyo3::create_exception!(
    rocking,
    ConfigError,
    PyValueError,
    "Bad input (the CLI's exit 2): a config key, value, file or argument. `key` names the config key at fault (or None), `file` and `line` the file and 1-based line where one applies."
);
pyo3::create_exception!(
    rocking,
    RecordError,
    ConfigError,
    "A ground-motion record that cannot be read: `key` is the config key that names it (excitation.file_h, or the unit_*/dt_* key when those are wrong), `file` the record file, `line` the 1-based line at fault (None for errors about the whole file)."
);
pyo3::create_exception!(
    rocking,
    RunError,
    PyRuntimeError,
    "A run that failed after its input was accepted (the CLI's exit 1), e.g. a step-size underflow."
);

/// Where an error points: a key, a file and a line, each if known.
#[derive(Default)]
pub struct Origin {
    /// `section.key`.
    pub key: Option<String>,
    /// A config or record file.
    pub file: Option<String>,
    /// 1-based line in `file`.
    pub line: Option<usize>,
}

/// The exception of type `E` with `message` and the attributes `key`,
/// `file` and `line` (None when unknown).
fn with_origin<E: pyo3::PyTypeInfo>(message: String, origin: Origin) -> PyErr {
    Python::attach(|py| {
        let err = PyErr::new::<E, _>(message);
        let value = err.value(py);
        // Setting attributes on a fresh exception instance cannot fail.
        let _ = value.setattr("key", origin.key);
        let _ = value.setattr("file", origin.file);
        let _ = value.setattr("line", origin.line);
        err
    })
}

/// Bad input with a message and where it points.
pub fn config_error(message: impl Into<String>, origin: Origin) -> PyErr {
    with_origin::<ConfigError>(message.into(), origin)
}

/// Bad input naming `key`.
pub fn key_error(key: &str, message: impl Into<String>) -> PyErr {
    config_error(
        message,
        Origin {
            key: Some(key.to_string()),
            ..Origin::default()
        },
    )
}

/// A failed run.
pub fn run_error(error: &anyhow::Error) -> PyErr {
    PyErr::new::<RunError, _>(format!("{error:#}"))
}

/// The 1-based line a record reader's message gives right after the file
/// name (`FILE:LINE: …`), if it gives one.
fn record_line(file: &str, message: &str) -> Option<usize> {
    let rest = message.strip_prefix(file)?.strip_prefix(':')?;
    let (digits, _) = rest.split_once(':')?;
    digits.parse().ok()
}

/// A record that cannot be read, outside a config (a fragility suite): the
/// reader's one-line message, naming the file and line.
pub fn record_error(path: &std::path::Path, e: &rocking::io::record::RecordError) -> PyErr {
    let file = path.display().to_string();
    let message = e.to_string();
    let line = record_line(&file, &message);
    with_origin::<RecordError>(
        message,
        Origin {
            key: None,
            file: Some(file),
            line,
        },
    )
}

/// The Python exception of a config error, with the CLI's message.
pub fn from_config(e: CoreConfigError) -> PyErr {
    // As the CLI prints it: through anyhow, with the chain on one line.
    let message = format!("{:#}", anyhow::Error::new(e.clone()));
    match e {
        CoreConfigError::Key { key, .. } => key_error(&key, message),
        CoreConfigError::Scenario(s) => key_error(&s.key, message),
        CoreConfigError::Syntax { file, line, .. } => config_error(
            message,
            Origin {
                key: None,
                file: Some(file),
                line: Some(line),
            },
        ),
        CoreConfigError::File { file, .. } => config_error(
            message,
            Origin {
                file: Some(file),
                ..Origin::default()
            },
        ),
        CoreConfigError::Record {
            key,
            file,
            message: reader,
        } => {
            let line = record_line(&file, &reader);
            with_origin::<RecordError>(
                message,
                Origin {
                    key: Some(key),
                    file: Some(file),
                    line,
                },
            )
        }
        CoreConfigError::Usage(_) => config_error(message, Origin::default()),
    }
}

/// The Python arguments of `rocking.sweep`, by the CLI flag that
/// `rocking sweep` checks the same value under.
pub const SWEEP_ARGS: &[(&str, &str)] = &[
    ("--param", "param"),
    ("--from", "start"),
    ("--to", "stop"),
    ("--step", "step"),
    ("--transient", "transient"),
    ("--tau-end", "tau_end"),
    ("--continuation", "continuation"),
    ("--shard", "shard"),
    ("--threads", "threads"),
];

/// The Python arguments of `rocking.outcome_map`, by CLI flag.
pub const MAP_ARGS: &[(&str, &str)] = &[
    ("--x", "x"),
    ("--y", "y"),
    ("--transient", "transient"),
    ("--tau-end", "tau_end"),
    ("--coarse", "coarse"),
    ("--threads", "threads"),
];

/// `message` with each CLI flag of `args` written as the Python argument
/// that gave the value: `--threads 0: …` → `threads=0: …`, a flag not
/// followed by its value (`… below --from 3`, `--levels and --block: …`)
/// → the argument's name.
pub fn python_args(message: &str, args: &[(&str, &str)]) -> String {
    let mut out = String::with_capacity(message.len());
    let mut rest = message;
    'scan: while let Some(at) = rest.find("--") {
        out.push_str(&rest[..at]);
        let tail = &rest[at..];
        for (flag, name) in args {
            let Some(after) = tail.strip_prefix(flag) else { continue };
            // The whole flag, not a prefix of a longer one (--record of --records).
            if after.starts_with(|c: char| c.is_ascii_alphanumeric() || c == '-') {
                continue;
            }
            // A value: a number, or a word that ends in a colon (`--param
            // excitation.a_q: …`), not prose (`--shard cannot be …`).
            let word = after.strip_prefix(' ').map(|w| w.split(' ').next().unwrap_or(""));
            let valued = word.is_some_and(|w| {
                w.starts_with(|c: char| c.is_ascii_digit() || c == '-' || c == '.') || (w.len() > 1 && w.ends_with(':'))
            });
            if valued {
                out.push_str(name);
                out.push('=');
                rest = &after[1..];
            } else {
                out.push_str(name);
                rest = after;
            }
            continue 'scan;
        }
        out.push_str("--");
        rest = &tail[2..];
    }
    out.push_str(rest);
    out
}

/// `e` with its message's CLI flags written as Python arguments
/// ([`python_args`]); other exceptions (KeyboardInterrupt) unchanged.
pub fn with_python_args(e: PyErr, args: &[(&str, &str)]) -> PyErr {
    Python::attach(|py| {
        let value = e.value(py);
        if let Ok(message) = value.str().and_then(|s| s.extract::<String>()) {
            let renamed = python_args(&message, args);
            if renamed != message {
                let _ = value.setattr("args", (renamed,));
            }
        }
    });
    e
}

/// Why a run of a scene failed: bad input, or the run itself.
pub enum Failure {
    /// The CLI's exit 2, with the key at fault.
    Input { key: String, message: String },
    /// The CLI's exit 1.
    Run(anyhow::Error),
}

impl Failure {
    /// The Python exception.
    pub fn into_py(self) -> PyErr {
        match self {
            Failure::Input { key, message } => key_error(&key, message),
            Failure::Run(e) => run_error(&e),
        }
    }
}
