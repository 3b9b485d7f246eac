//! A config's text read into a table: TOML parsed with its line in errors, or a config file (TOML, or a `summary.json` / JSON config) read within its size bound.

use std::path::Path;

use serde_json::Value as Json;
use toml::Table;

use super::{ConfigError, Source, line_of};

/// Parses TOML text, naming `file` and the line in errors.
pub fn parse_toml(text: &str, file: &str) -> Result<Table, ConfigError> {
    text.parse::<Table>().map_err(|e| {
        let line = e.span().map_or(1, |s| line_of(text, s.start));
        let msg = e.message().lines().next().unwrap_or("invalid TOML").to_string();
        ConfigError::Syntax {
            file: file.to_string(),
            line,
            message: msg,
        }
    })
}

/// Largest config file read, bytes: a config is a page of text; anything
/// near this is not one.
pub(crate) const MAX_CONFIG_BYTES: u64 = 1 << 20;

/// Reads a config file: TOML, or a `summary.json` / JSON config (whose
/// `config` object is used if present).
pub(crate) fn read_file(path: &Path) -> Result<(Table, Source), ConfigError> {
    let name = path.display().to_string();
    if path.is_dir() {
        return Err(file_error(&name, "is a directory, expected a config file"));
    }
    // Only a regular file of bounded size: `/dev/zero` would be read
    // without end and a FIFO would block forever.
    let meta = std::fs::metadata(path).map_err(|e| file_error(&name, e))?;
    if !meta.is_file() {
        return Err(file_error(&name, "not a regular file (a config is read from a file)"));
    }
    if meta.len() > MAX_CONFIG_BYTES {
        return Err(file_error(
            &name,
            format!("{} bytes; a config file is at most 1 MB", meta.len()),
        ));
    }
    let text = std::fs::read_to_string(path).map_err(|e| file_error(&name, e))?;
    if text.trim().is_empty() {
        return Err(file_error(&name, "empty file"));
    }
    let base_dir = path.parent().map(Path::to_path_buf).unwrap_or_default();
    let is_json = path.extension().is_some_and(|e| e.eq_ignore_ascii_case("json"));
    let table = if is_json {
        let v: Json = serde_json::from_str(&text).map_err(|e| ConfigError::Syntax {
            file: name.clone(),
            line: e.line(),
            message: e.to_string(),
        })?;
        let v = v.get("config").cloned().unwrap_or(v);
        json_to_table(&v).map_err(|m| file_error(&name, m))?
    } else {
        parse_toml(&text, &name)?
    };
    Ok((table, Source { base_dir }))
}

fn json_to_table(v: &Json) -> Result<Table, String> {
    let Json::Object(map) = v else {
        return Err("expected a JSON object".into());
    };
    let mut t = Table::new();
    for (k, v) in map {
        let tv = match v {
            Json::Object(_) => toml::Value::Table(json_to_table(v)?),
            Json::String(s) => toml::Value::String(s.clone()),
            Json::Bool(b) => toml::Value::Boolean(*b),
            Json::Number(n) => match n.as_i64() {
                Some(i) => toml::Value::Integer(i),
                None => toml::Value::Float(n.as_f64().unwrap_or(f64::NAN)),
            },
            // `null` means "absent / default".
            Json::Null => continue,
            // A list of tables (`[[stack]]`, `[[floor.mode]]`).
            Json::Array(items) => toml::Value::Array(
                items
                    .iter()
                    .map(|item| match item {
                        Json::Object(_) => json_to_table(item).map(toml::Value::Table),
                        _ => Err(format!("{k}: a list here must hold tables")),
                    })
                    .collect::<Result<_, _>>()?,
            ),
        };
        t.insert(k.clone(), tv);
    }
    Ok(t)
}

fn file_error(file: &str, message: impl std::fmt::Display) -> ConfigError {
    ConfigError::File {
        file: file.to_string(),
        message: message.to_string(),
    }
}
