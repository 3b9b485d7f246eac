//! `--set KEY=VALUE` overrides and line numbers for errors.

use toml::{Table, Value};

use super::ConfigError;

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
    // A later assignment replaces the keys it is an alternative to, so
    // `--set run.t_end=30s` overrides a preset's `run.tau_end` (a file
    // that gives both is refused instead: nothing says which it meant).
    for other in alternatives(section, name) {
        sec.remove(*other);
    }
    sec.insert(name.to_string(), value);
    Ok(())
}

/// The keys that `section.name` replaces when set.
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
