//! `--set KEY=VALUE` overrides and line numbers for errors.

use std::path::{Path, PathBuf};

use toml::{Table, Value};

use super::ConfigError;
use crate::sim::scenario::SHIPPED_PREFIX;

/// Applies `--set KEY=VALUE` assignments in order. One of a pair of
/// exclusive keys (`run.t_end`/`run.tau_end`, `scale_h`/`pga_h`, …)
/// replaces its twin from the file or preset underneath: that is an
/// override of the same quantity. Two assignments of one pair are refused
/// (nothing says which was meant), and so is a table that already holds
/// both before any assignment (the file's conflict is not hidden by a
/// `--set` that happens to remove one of them).
pub fn apply_sets(table: &mut Table, sets: &[String]) -> Result<(), ConfigError> {
    if !sets.is_empty() {
        refuse_both_in_table(table)?;
    }
    let mut given: Vec<(String, String, &str)> = Vec::with_capacity(sets.len());
    for assignment in sets {
        let (section, name) = set_dotted_key(table, assignment, cwd(assignment))?;
        if let Some((_, other, earlier)) = given
            .iter()
            .find(|(s, n, _)| *s == section && alternatives(&section, &name).contains(&n.as_str()))
        {
            return Err(ConfigError::Usage(format!(
                "--set {} and --set {}: {section}.{other} and {section}.{name} are alternatives; give one",
                earlier.trim(),
                assignment.trim()
            )));
        }
        given.push((section, name, assignment));
    }
    Ok(())
}

/// The first pair of exclusive keys that `table` holds both of, as the
/// error the config gives for a file with both.
fn refuse_both_in_table(table: &Table) -> Result<(), ConfigError> {
    for (section, value) in table {
        let Value::Table(sec) = value else { continue };
        for name in sec.keys() {
            if let Some(other) = alternatives(section, name).iter().find(|o| sec.contains_key(**o)) {
                return Err(ConfigError::key(
                    &format!("{section}.{name}"),
                    format!("give either {section}.{other} or {section}.{name}, not both"),
                ));
            }
        }
    }
    Ok(())
}

/// Sets `section.key = value` in `table`, parsing `value` as a TOML value
/// (`1.5`, `inf`, `"text"`) and falling back to a bare string (`ratio`).
///
/// A record path (`excitation.file_h`, `file_v`) typed here is relative to
/// the current folder, as any path typed on a command line or passed from
/// Python is: it is made absolute now, so that the folder of a preset or
/// config the table came from (against which the paths written inside
/// that file resolve) never applies to it.
/// The keys it is an alternative to are removed (see [`apply_sets`]).
pub fn set_dotted(table: &mut Table, assignment: &str) -> Result<(), ConfigError> {
    set_dotted_key(table, assignment, cwd(assignment)).map(|_| ())
}

/// The current folder, asked for only when a relative path needs it.
fn cwd(assignment: &str) -> impl FnOnce() -> Result<PathBuf, ConfigError> + '_ {
    move || {
        std::env::current_dir().map_err(|e| {
            ConfigError::Usage(format!(
                "--set {assignment}: the current folder cannot be read ({e}), so a relative path cannot be resolved; give an absolute path"
            ))
        })
    }
}

/// [`set_dotted`] with relative record paths resolved against the folder
/// `base` returns (asked only for such a path).
pub fn set_dotted_from(
    table: &mut Table,
    assignment: &str,
    base: impl FnOnce() -> Result<PathBuf, ConfigError>,
) -> Result<(), ConfigError> {
    set_dotted_key(table, assignment, base).map(|_| ())
}

/// [`set_dotted_from`], returning the section and key it set.
fn set_dotted_key(
    table: &mut Table,
    assignment: &str,
    base: impl FnOnce() -> Result<PathBuf, ConfigError>,
) -> Result<(String, String), ConfigError> {
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
    let mut value = match format!("v = {raw}").parse::<Table>() {
        Ok(mut t) => t.remove("v").unwrap_or_else(|| Value::String(raw.to_string())),
        Err(_) => Value::String(raw.to_string()),
    };
    if let Value::String(path) = &value
        && section == "excitation"
        && matches!(name, "file_h" | "file_v")
        && !path.is_empty()
        && !path.starts_with(SHIPPED_PREFIX)
        && Path::new(path).is_relative()
    {
        let joined = base()?.join(path);
        let Some(text) = joined.to_str() else {
            return Err(ConfigError::Usage(format!(
                "--set {assignment}: the path {} is not UTF-8, which a config cannot hold",
                joined.display()
            )));
        };
        value = Value::String(text.to_string());
    }
    // One table of a list, as errors name it: `stack[2].height`.
    if let Some((list, index)) = indexed(section) {
        let Some(Value::Array(tables)) = table.get_mut(list) else {
            return Err(ConfigError::key(
                section,
                format!("there is no [[{list}]] list to set a table of (the scene has none)"),
            ));
        };
        let count = tables.len();
        let Some(Value::Table(t)) = tables.get_mut(index) else {
            return Err(ConfigError::key(
                section,
                format!("no such table: the [[{list}]] list has {count}, numbered from 0"),
            ));
        };
        t.insert(name.to_string(), value);
        return Ok((section.to_string(), name.to_string()));
    }
    let sec = table
        .entry(section.to_string())
        .or_insert_with(|| Value::Table(Table::new()));
    let Value::Table(sec) = sec else {
        return Err(ConfigError::key(section, "is not a table"));
    };
    // A later assignment replaces the keys it is an alternative to, so
    // `--set run.t_end=30s` overrides a preset's `run.tau_end` (a file
    // that gives both is refused instead: nothing says which it meant).
    for other in alternatives(section, name) {
        sec.remove(*other);
    }
    sec.insert(name.to_string(), value);
    Ok((section.to_string(), name.to_string()))
}

/// `("stack", 2)` for `stack[2]`; `None` for a plain section name.
fn indexed(section: &str) -> Option<(&str, usize)> {
    let (list, rest) = section.split_once('[')?;
    let index = rest.strip_suffix(']')?.parse().ok()?;
    Some((list, index))
}

/// The keys that `section.name` replaces when set: the pairs a config
/// refuses together (`run.tail_s` only applies to a run whose record decides
/// its length, so it is exclusive with both ends).
fn alternatives(section: &str, name: &str) -> &'static [&'static str] {
    match (section, name) {
        ("run", "t_end") => &["tau_end", "tail_s"],
        ("run", "tau_end") => &["t_end", "tail_s"],
        ("run", "tail_s") => &["t_end", "tau_end"],
        ("excitation", "pga_h") => &["scale_h"],
        ("excitation", "scale_h") => &["pga_h"],
        ("excitation", "pga_v") => &["scale_v"],
        ("excitation", "scale_v") => &["pga_v"],
        _ => &[],
    }
}

/// The 1-based line of byte offset `pos` in `text`.
pub fn line_of(text: &str, pos: usize) -> usize {
    text.get(..pos.min(text.len()))
        .map_or(1, |s| s.matches('\n').count() + 1)
}
