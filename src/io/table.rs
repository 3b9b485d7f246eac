//! A checked reader over a two-level TOML table (`section.key = value`).
//!
//! Every accessor names the dotted key in its error and says what is allowed;
//! every key read is marked used, so that whatever is left at the end is an
//! unknown key and can be reported with the known ones.

use std::collections::BTreeSet;

use toml::{Table, Value};

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
        /// `excitation.file_h` or `excitation.file_v`.
        key: &'static str,
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

/// Reads typed values out of a table and remembers which keys were read.
pub struct TableReader<'a> {
    table: &'a Table,
    used: BTreeSet<String>,
}

fn describe(v: &Value) -> String {
    match v {
        Value::String(s) => format!("string \"{s}\""),
        Value::Integer(i) => format!("integer {i}"),
        Value::Float(f) => format!("number {f}"),
        Value::Boolean(b) => format!("boolean {b}"),
        Value::Datetime(d) => format!("datetime {d}"),
        Value::Array(_) => "an array".to_string(),
        Value::Table(_) => "a table".to_string(),
    }
}

impl<'a> TableReader<'a> {
    /// A reader over `table`.
    pub fn new(table: &'a Table) -> Self {
        Self {
            table,
            used: BTreeSet::new(),
        }
    }

    fn get(&mut self, section: &str, key: &str) -> Result<Option<&'a Value>, ConfigError> {
        let Some(sec) = self.table.get(section) else {
            return Ok(None);
        };
        let Value::Table(sec) = sec else {
            return Err(ConfigError::key(
                section,
                format!("expected a table [{section}], found {}", describe(sec)),
            ));
        };
        let v = sec.get(key);
        if v.is_some() {
            self.used.insert(format!("{section}.{key}"));
        }
        Ok(v)
    }

    /// A number, or `None` if absent. Accepts integers, floats and the
    /// strings `inf`/`infinity` (and their negatives) when `allow_inf`.
    pub fn number(&mut self, section: &str, key: &str, allow_inf: bool) -> Result<Option<f64>, ConfigError> {
        let name = format!("{section}.{key}");
        let Some(v) = self.get(section, key)? else {
            return Ok(None);
        };
        let x = match v {
            Value::Integer(i) => *i as f64,
            Value::Float(f) => *f,
            Value::String(s)
                if allow_inf && matches!(s.trim().to_ascii_lowercase().as_str(), "inf" | "infinity" | "+inf") =>
            {
                f64::INFINITY
            }
            other => {
                let inf = if allow_inf { " or \"inf\"" } else { "" };
                return Err(ConfigError::key(
                    &name,
                    format!("expected a number{inf}, found {}", describe(other)),
                ));
            }
        };
        if x.is_nan() {
            return Err(ConfigError::key(&name, "NaN is not allowed"));
        }
        if x.is_infinite() && !allow_inf {
            return Err(ConfigError::key(&name, "must be finite"));
        }
        Ok(Some(x))
    }

    /// A string, or `None` if absent.
    pub fn string(&mut self, section: &str, key: &str) -> Result<Option<&'a str>, ConfigError> {
        let name = format!("{section}.{key}");
        match self.get(section, key)? {
            None => Ok(None),
            Some(Value::String(s)) => Ok(Some(s.as_str())),
            Some(other) => Err(ConfigError::key(
                &name,
                format!("expected a string, found {}", describe(other)),
            )),
        }
    }

    /// A non-negative integer, or `None` if absent.
    pub fn count(&mut self, section: &str, key: &str) -> Result<Option<u64>, ConfigError> {
        let name = format!("{section}.{key}");
        match self.get(section, key)? {
            None => Ok(None),
            Some(Value::Integer(i)) if *i >= 0 => Ok(Some(*i as u64)),
            Some(other) => Err(ConfigError::key(
                &name,
                format!("expected a non-negative integer, found {}", describe(other)),
            )),
        }
    }

    /// One of `choices`, or `None` if absent.
    pub fn choice(&mut self, section: &str, key: &str, choices: &[&str]) -> Result<Option<&'a str>, ConfigError> {
        let name = format!("{section}.{key}");
        match self.string(section, key)? {
            None => Ok(None),
            Some(s) if choices.contains(&s) => Ok(Some(s)),
            Some(s) => Err(ConfigError::key(
                &name,
                format!("\"{s}\" is not one of {}", choices.join(", ")),
            )),
        }
    }

    /// The first key of the table that was never read, with the section's
    /// known keys, as an error.
    pub fn reject_unknown(&self, known: &[(&str, &[&str])]) -> Result<(), ConfigError> {
        for (section, value) in self.table {
            let Some((_, keys)) = known.iter().find(|(s, _)| s == section) else {
                let sections: Vec<&str> = known.iter().map(|(s, _)| *s).collect();
                return Err(ConfigError::key(
                    section,
                    format!("unknown section (known: {})", sections.join(", ")),
                ));
            };
            let Value::Table(sec) = value else {
                return Err(ConfigError::key(
                    section,
                    format!("expected a table [{section}], found {}", describe(value)),
                ));
            };
            for key in sec.keys() {
                let name = format!("{section}.{key}");
                if !self.used.contains(&name) && !keys.contains(&key.as_str()) {
                    return Err(ConfigError::key(
                        &name,
                        format!("unknown key (known in [{section}]: {})", keys.join(", ")),
                    ));
                }
            }
        }
        Ok(())
    }
}

/// Sets `section.key = value` in `table`, parsing `value` as a TOML value
/// (`1.5`, `inf`, `"text"`) and falling back to a bare string (`ratio`).
pub fn set_dotted(table: &mut Table, assignment: &str) -> Result<(), ConfigError> {
    let Some((key, raw)) = assignment.split_once('=') else {
        return Err(ConfigError::Usage(format!(
            "--set {assignment}: expected KEY=VALUE, e.g. excitation.a_v=2.5"
        )));
    };
    let key = key.trim();
    let raw = raw.trim();
    let Some((section, name)) = key.split_once('.') else {
        return Err(ConfigError::Usage(format!(
            "--set {assignment}: the key must be SECTION.KEY, e.g. excitation.a_v"
        )));
    };
    if section.is_empty() || name.is_empty() || name.contains('.') {
        return Err(ConfigError::Usage(format!(
            "--set {assignment}: the key must be SECTION.KEY, e.g. excitation.a_v"
        )));
    }
    let value = match format!("v = {raw}").parse::<Table>() {
        Ok(mut t) => t.remove("v").unwrap_or_else(|| Value::String(raw.to_string())),
        Err(_) => Value::String(raw.to_string()),
    };
    let sec = table
        .entry(section.to_string())
        .or_insert_with(|| Value::Table(Table::new()));
    let Value::Table(sec) = sec else {
        return Err(ConfigError::key(section, "is not a table"));
    };
    sec.insert(name.to_string(), value);
    Ok(())
}

/// The 1-based line of byte offset `pos` in `text`.
pub fn line_of(text: &str, pos: usize) -> usize {
    text.get(..pos.min(text.len()))
        .map_or(1, |s| s.matches('\n').count() + 1)
}
