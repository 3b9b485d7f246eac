//! The scene's settings as the user wrote them: the TOML table of explicit
//! keys (from a preset, a file, or edits in the panel) and where it came
//! from. Resolving goes through [`from_table`](crate::io::config::from_table), so the app accepts
//! exactly what the CLI accepts and refuses the rest with the same one-line
//! message. Keys left out keep their documented defaults (e.g. Ω_v follows
//! Ω_h), which a table of resolved values would lose. A slider drag
//! ([`Settings::dragged`]) reaches the same scene as a typed edit of the
//! scene shown, without resolving the table or reading a record again.

use std::path::Path;

use toml::Table;

use crate::io::config::{ConfigError, from_table_keeping, set_dotted};
use crate::io::config::{Source, parse_toml, preset_text, read_file};
use crate::sim::{Param, Scenario};

/// The explicit keys of a scene and their source.
#[derive(Clone, Debug, Default)]
pub struct Settings {
    /// Explicit keys, `section.key = value`.
    pub table: Table,
    /// Where relative record paths are resolved.
    pub source: Source,
    /// What the settings came from (a preset name or a file), for the title.
    pub origin: String,
}

impl Settings {
    /// The settings of preset `name`.
    pub fn preset(name: &str) -> Result<Self, String> {
        let text = preset_text(name).map_err(|e| e.to_string())?;
        let table = parse_toml(text, &format!("preset {name}")).map_err(|e| e.to_string())?;
        Ok(Self {
            table,
            source: Source::preset(),
            origin: format!("preset {name}"),
        })
    }

    /// The settings in a TOML (or summary.json) file, resolved and checked.
    pub fn open(path: &Path) -> Result<(Self, Scenario), String> {
        let (table, source) = read_file(path).map_err(|e| e.to_string())?;
        let s = Self {
            table,
            source,
            origin: path.display().to_string(),
        };
        let cfg = s.resolve()?;
        Ok((s, cfg))
    }

    /// The scene the command line names: `--config FILE` or `--preset NAME`
    /// (default `default`), then each `--set KEY=VALUE`, resolved and checked.
    pub fn from_cli(preset: Option<&str>, file: Option<&Path>, sets: &[String]) -> Result<(Self, Scenario), String> {
        let mut s = match (preset, file) {
            (Some(_), Some(_)) => return Err("give either --preset or --config, not both".into()),
            (_, Some(path)) => Self::open(path)?.0,
            (name, None) => Self::preset(name.unwrap_or("default"))?,
        };
        crate::io::config::apply_sets(&mut s.table, sets).map_err(|e| e.to_string())?;
        let cfg = s.resolve()?;
        Ok((s, cfg))
    }

    /// Settings whose every key is explicit, from a resolved config (used
    /// when the app is handed a `Scenario` rather than a table).
    pub fn from_config(cfg: &Scenario) -> Self {
        let mut table = Table::new();
        if let serde_json::Value::Object(sections) = crate::io::config::to_json(cfg) {
            for (section, keys) in sections {
                let serde_json::Value::Object(keys) = keys else {
                    continue;
                };
                let mut t = Table::new();
                for (k, v) in keys {
                    let tv = match v {
                        serde_json::Value::String(s) if s == "inf" => toml::Value::Float(f64::INFINITY),
                        serde_json::Value::String(s) => toml::Value::String(s),
                        serde_json::Value::Bool(b) => toml::Value::Boolean(b),
                        serde_json::Value::Number(n) => match n.as_i64() {
                            Some(i) if !is_float_key(&section, &k) => toml::Value::Integer(i),
                            _ => match n.as_f64() {
                                Some(f) => toml::Value::Float(f),
                                None => continue,
                            },
                        },
                        serde_json::Value::Null | serde_json::Value::Array(_) | serde_json::Value::Object(_) => {
                            continue;
                        }
                    };
                    t.insert(k, tv);
                }
                table.insert(section, toml::Value::Table(t));
            }
        }
        Self {
            table,
            source: Source::default(),
            origin: "config".to_string(),
        }
    }

    /// Resolves and validates.
    pub fn resolve(&self) -> Result<Scenario, String> {
        self.resolve_typed().map_err(|e| e.to_string())
    }

    /// Resolves and validates, keeping the config layer's error as it is
    /// (so the caller can tell which key is at fault).
    pub(crate) fn resolve_typed(&self) -> Result<Scenario, ConfigError> {
        crate::io::config::from_table(&self.table, &self.source)
    }

    /// These settings with each `(key, value)` (`section.key`) set, or
    /// removed for `None`; not resolved.
    pub(crate) fn with_values(&self, values: &[(&str, Option<toml::Value>)]) -> Self {
        let mut next = self.clone();
        for (key, value) in values {
            let Some((section, name)) = key.split_once('.') else {
                continue;
            };
            let entry = next
                .table
                .entry(section.to_string())
                .or_insert_with(|| toml::Value::Table(Table::new()));
            let toml::Value::Table(t) = entry else {
                continue;
            };
            match value {
                Some(v) => {
                    t.insert(name.to_string(), v.clone());
                }
                None => {
                    t.remove(name);
                }
            }
        }
        next
    }

    /// The explicit value of `key` (`section.key`), as TOML text.
    pub fn explicit(&self, key: &str) -> Option<String> {
        self.value(key).map(value_text)
    }

    /// These settings with `key` set to `raw` (TOML value text; empty
    /// removes the key, restoring its default), resolved and checked.
    /// Nothing changes on error.
    pub fn with(&self, key: &str, raw: &str) -> Result<(Self, Scenario), String> {
        let next = self.edited(key, raw)?;
        let cfg = next.resolve()?;
        Ok((next, cfg))
    }

    /// [`Settings::with`] as a slider drag applies it, once a frame:
    /// `current` is the scene these settings resolve to, and the result is
    /// the one [`Settings::with`] gives, without reading a record file
    /// again and, for most keys, without resolving the table.
    ///
    /// - A number for a key with a [`Param`] is set typed on a copy of
    ///   `current` ([`Param::apply`]: the one value set, the scene
    ///   re-validated), with the refusal [`Settings::with`] gives. The
    ///   table gets the same text written in, so that a later typed edit,
    ///   a save or a share link keeps it.
    /// - The block's width and height are the exception: they move ψ and p,
    ///   through which every value given with a unit (`output_dt = "0.01
    ///   s"`, `a_h = "0.3 g"`) converts, so they re-resolve the table.
    ///   That, and any other key but a record's own, takes the records
    ///   `current` holds ([`from_table_keeping`]).
    /// - A record's own keys (file, unit, time step, checksum, channel)
    ///   name what to read: they are resolved as [`Settings::with`] does.
    pub fn dragged(&self, key: &str, raw: &str, current: &Scenario) -> Result<(Self, Scenario), String> {
        let next = self.edited(key, raw)?;
        if names_the_record(key) {
            let cfg = next.resolve()?;
            return Ok((next, cfg));
        }
        // The number as the table now holds it: what resolving would read.
        let value = match next.value(key) {
            Some(toml::Value::Float(v)) => Some(*v),
            Some(toml::Value::Integer(i)) => Some(*i as f64),
            _ => None,
        };
        let typed = crate::io::config::param(key)
            .ok()
            .filter(|p| !matches!(p, Param::Width | Param::Height));
        let cfg = match (typed, value) {
            (Some(p), Some(v)) if v.is_finite() => Param::apply(current, &[(p, v)]).map_err(|e| e.to_string())?,
            _ => from_table_keeping(&next.table, &next.source, current).map_err(|e| e.to_string())?,
        };
        Ok((next, cfg))
    }

    /// These settings with `key` set to `raw` as [`Settings::with`] sets
    /// it; not resolved.
    fn edited(&self, key: &str, raw: &str) -> Result<Self, String> {
        let mut next = self.clone();
        let raw = raw.trim();
        if raw.is_empty() {
            if let Some((section, name)) = key.split_once('.')
                && let Some(toml::Value::Table(t)) = next.table.get_mut(section)
            {
                t.remove(name);
            }
        } else {
            set_dotted(&mut next.table, &format!("{key}={raw}")).map_err(|e| e.to_string())?;
        }
        Ok(next)
    }

    /// The explicit value of `key` (`section.key`).
    fn value(&self, key: &str) -> Option<&toml::Value> {
        let (section, name) = key.split_once('.')?;
        self.table.get(section)?.as_table()?.get(name)
    }

    /// The scene as TOML text, with a header naming its origin.
    pub(crate) fn to_toml(&self) -> Result<String, String> {
        let body = toml::to_string(&self.table).map_err(|e| format!("cannot write the scene as TOML: {e}"))?;
        Ok(format!("# rocking scene (from {})\n\n{body}", self.origin))
    }
}

/// Whether `key` says which record to read and how (its file, unit, time
/// step, checksum or channel), rather than what to do with it.
fn names_the_record(key: &str) -> bool {
    let Some(("excitation", name)) = key.split_once('.') else {
        return false;
    };
    ["file", "unit", "dt", "crc32", "channel"]
        .iter()
        .any(|k| name.strip_prefix(k).is_some_and(|side| matches!(side, "_h" | "_v")))
}

/// Keys whose values are real numbers even when they print as integers.
fn is_float_key(section: &str, key: &str) -> bool {
    !matches!(
        (section, key),
        ("excitation", "cycles") | ("run", "max_steps") | ("run", "max_events")
    )
}

/// A TOML value as the user would type it (`inf`, `0.4`, `ratio`).
pub(crate) fn value_text(v: &toml::Value) -> String {
    match v {
        toml::Value::String(s) => s.clone(),
        toml::Value::Float(f) if f.is_infinite() && *f > 0.0 => "inf".to_string(),
        toml::Value::Float(f) => format_number(*f),
        toml::Value::Integer(i) => i.to_string(),
        toml::Value::Boolean(b) => b.to_string(),
        toml::Value::Datetime(d) => d.to_string(),
        toml::Value::Array(_) | toml::Value::Table(_) => v.to_string(),
    }
}

/// A number in the shortest form that reads back to the same value.
pub(crate) fn format_number(x: f64) -> String {
    if x.is_infinite() {
        if x > 0.0 { "inf".into() } else { "-inf".into() }
    } else {
        // Rust's Display is the shortest round-tripping representation.
        format!("{x}")
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn an_edit_keeps_defaults_that_follow_other_keys() {
        let s = Settings::preset("fig3").expect("preset");
        let (s2, cfg) = s.with("excitation.omega_h", "5").expect("valid");
        assert_eq!(cfg.excitation.omega_v(), 5.0, "Ω_v defaults to Ω_h");
        assert_eq!(s2.explicit("excitation.omega_h").as_deref(), Some("5"));
    }

    #[test]
    fn an_invalid_edit_is_refused_with_the_key_named() {
        let s = Settings::preset("default").expect("preset");
        let err = s.with("block.width", "-1").expect_err("refused");
        assert!(err.starts_with("block.width"), "{err}");
        let err = s.with("friction.kinetic", "0.9").expect_err("refused");
        assert!(err.contains("friction.kinetic"), "{err}");
    }

    #[test]
    fn an_empty_value_restores_the_default() {
        let s = Settings::preset("default").expect("preset");
        let (_, cfg) = s.with("excitation.a_h", "").expect("valid");
        assert_eq!(cfg.excitation.a_h, 0.0);
    }

    #[test]
    fn the_scene_round_trips_through_toml() {
        let s = Settings::preset("fig16").expect("preset");
        let text = s.to_toml().expect("toml");
        let table = parse_toml(&text, "saved").expect("parses");
        let back = crate::io::config::from_table(&table, &Source::default()).expect("valid");
        assert_eq!(back, s.resolve().expect("valid"));
    }

    #[test]
    fn settings_from_a_resolved_config_resolve_to_it() {
        let cfg = Settings::preset("fig12").and_then(|s| s.resolve()).expect("valid");
        let back = Settings::from_config(&cfg).resolve().expect("valid");
        // The resolved values are equal; `back` has every default written
        // out (Ω_v, the impact friction, the method), so it no longer
        // follows the values they default to, and the structs differ there.
        use crate::io::config::to_json;
        assert_eq!(to_json(&back), to_json(&cfg));
    }
}
