//! The run configuration: TOML with dotted keys, `--set` overrides, presets
//! and `summary.json`, read into a typed [`Scenario`] with one-line errors,
//! and the scenario written back as JSON.
//!
//! This is the only layer that knows the config's string keys: it resolves
//! them to the scenario's typed fields (and a swept key to a [`Param`]);
//! the rules a value must obey are the scenario's own
//! ([`Scenario::validate`]), so a config file and a sweep point are checked
//! alike. Every key, its unit, default and allowed range is listed in
//! [`KNOWN_KEYS`] and documented on the fields of [`Scenario`]. A resolved
//! scenario round-trips: `rocking --batch --config out/summary.json`
//! repeats the run.

use std::path::{Path, PathBuf};

use serde_json::{Value as Json, json};
use toml::Table;

use super::table::{ConfigError, TableReader, line_of, set_dotted};
use crate::model::FlightPolicy;
use crate::model::excitation::record;
use crate::sim::scenario::{
    Analyses, Block, ExcitationKind, ExcitationSpec, Impact, LawKind, LyapunovChoice, Record, RunSpec, ShapeKind,
    SpectrumRange,
};
use crate::sim::{InitialState, Method, Param, Scenario};

/// Every section and key the config accepts.
pub const KNOWN_KEYS: &[(&str, &[&str])] = &[
    ("block", &["width", "height"]),
    ("friction", &["static", "kinetic"]),
    ("impact", &["law", "r", "e", "static", "kinetic"]),
    (
        "excitation",
        &[
            "kind", "a_h", "a_v", "omega_h", "omega_v", "phase_h", "phase_v", "shape", "cycles", "file_h", "file_v",
            "scale_h", "scale_v",
        ],
    ),
    ("initial", &["theta", "theta_dot", "x_dot"]),
    (
        "run",
        &[
            "tau_end",
            "method",
            "rtol",
            "atol",
            "step",
            "output_dt",
            "tumble_theta",
            "flight",
            "zeno_eps",
            "max_steps",
            "max_events",
        ],
    ),
    (
        "analysis",
        &["lyapunov", "lyapunov_method", "spectrum", "spectrum_window"],
    ),
];

/// Where a config came from, for resolving relative record paths.
#[derive(Clone, Debug, Default)]
pub struct Source {
    /// Directory that relative paths are relative to.
    pub base_dir: PathBuf,
}

/// Reads a preset shipped in `assets/presets/NAME.toml`.
pub fn preset_text(name: &str) -> Result<&'static str, ConfigError> {
    super::presets::get(name).ok_or_else(|| {
        ConfigError::Usage(format!(
            "--preset {name}: unknown preset (known: {})",
            super::presets::names().join(", ")
        ))
    })
}

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

/// Reads a config file: TOML, or a `summary.json` / JSON config (whose
/// `config` object is used if present).
pub fn read_file(path: &Path) -> Result<(Table, Source), ConfigError> {
    let name = path.display().to_string();
    if path.is_dir() {
        return Err(file_error(&name, "is a directory, expected a config file"));
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
            Json::Array(_) => return Err(format!("{k}: arrays are not config values")),
        };
        t.insert(k.clone(), tv);
    }
    Ok(t)
}

/// Applies `--set KEY=VALUE` assignments.
pub fn apply_sets(table: &mut Table, sets: &[String]) -> Result<(), ConfigError> {
    for s in sets {
        set_dotted(table, s)?;
    }
    Ok(())
}

fn file_error(file: &str, message: impl std::fmt::Display) -> ConfigError {
    ConfigError::File {
        file: file.to_string(),
        message: message.to_string(),
    }
}

/// `section.key` as a boolean, or `None` if absent (a non-table section is
/// reported by [`TableReader::reject_unknown`]).
fn boolean(table: &Table, section: &str, key: &str) -> Result<Option<bool>, ConfigError> {
    match table.get(section).and_then(|s| s.as_table()).and_then(|s| s.get(key)) {
        None => Ok(None),
        Some(toml::Value::Boolean(b)) => Ok(Some(*b)),
        Some(other) => Err(ConfigError::key(
            &format!("{section}.{key}"),
            format!("expected true or false, found {other}"),
        )),
    }
}

/// Reads the record file `path` names, naming `key` in errors.
fn read_record(key: &'static str, path: Option<&str>, source: &Source) -> Result<Option<Record>, ConfigError> {
    let Some(p) = path else {
        return Ok(None);
    };
    let p = PathBuf::from(p);
    let path = if p.is_absolute() { p } else { source.base_dir.join(p) };
    let series = record::read_record(&path).map_err(|e| ConfigError::Record {
        key,
        message: e.to_string(),
    })?;
    Ok(Some(Record { path, series }))
}

/// Resolves `table` into a scenario and validates it. Record paths are
/// relative to `source.base_dir`; the records are read here, so a scenario
/// never refers to a file it has not read.
pub fn from_table(table: &Table, source: &Source) -> Result<Scenario, ConfigError> {
    let d = Scenario::default();
    let mut r = TableReader::new(table);
    let block = Block {
        width: r.number("block", "width", false)?.unwrap_or(d.block.width),
        height: r.number("block", "height", false)?.unwrap_or(d.block.height),
        mu_s: r.number("friction", "static", true)?.unwrap_or(d.block.mu_s),
        mu_k: r.number("friction", "kinetic", true)?,
    };
    let impact = Impact {
        law: match r.choice("impact", "law", &["housner", "ratio", "impulse"])? {
            None | Some("housner") => LawKind::Housner,
            Some("ratio") => LawKind::Ratio,
            Some(_) => LawKind::Impulse,
        },
        r: r.number("impact", "r", false)?,
        e: r.number("impact", "e", false)?.unwrap_or(d.impact.e),
        mu_s: r.number("impact", "static", true)?,
        mu_k: r.number("impact", "kinetic", true)?,
    };
    let kind = match r.choice("excitation", "kind", &["harmonic", "pulse", "record", "none"])? {
        None | Some("harmonic") => ExcitationKind::Harmonic,
        Some("pulse") => ExcitationKind::Pulse,
        Some("record") => ExcitationKind::Record,
        Some(_) => ExcitationKind::None,
    };
    let dx = &d.excitation;
    let shape = match r.choice("excitation", "shape", &["one-sine", "one-cosine", "type-c"])? {
        None | Some("one-sine") => ShapeKind::OneSine,
        Some("one-cosine") => ShapeKind::OneCosine,
        Some(_) => ShapeKind::TypeC,
    };
    let cycles = r.count("excitation", "cycles")?.map_or(Ok(dx.cycles), |n| {
        u32::try_from(n).map_err(|_| {
            ConfigError::key(
                "excitation.cycles",
                format!(
                    "{n} is out of range: must be in 1..={}",
                    crate::model::excitation::pulse::MAX_TYPE_C_CYCLES
                ),
            )
        })
    })?;
    let file_h = r.string("excitation", "file_h")?;
    let file_v = r.string("excitation", "file_v")?;
    let mut excitation = ExcitationSpec {
        kind,
        a_h: r.number("excitation", "a_h", false)?.unwrap_or(dx.a_h),
        a_v: r.number("excitation", "a_v", false)?.unwrap_or(dx.a_v),
        omega_h: r.number("excitation", "omega_h", false)?.unwrap_or(dx.omega_h),
        omega_v: r.number("excitation", "omega_v", false)?,
        phase_h: r.number("excitation", "phase_h", false)?.unwrap_or(dx.phase_h),
        phase_v: r.number("excitation", "phase_v", false)?.unwrap_or(dx.phase_v),
        shape,
        cycles,
        record_h: None,
        record_v: None,
        scale_h: r.number("excitation", "scale_h", false)?.unwrap_or(dx.scale_h),
        scale_v: r.number("excitation", "scale_v", false)?.unwrap_or(dx.scale_v),
    };
    let dr = &d.run;
    let run = RunSpec {
        tau_end: r.number("run", "tau_end", false)?.unwrap_or(dr.tau_end),
        method: match r.choice("run", "method", &["dop853", "dopri5", "ralston", "taylor"])? {
            None => None,
            Some("dop853") => Some(Method::Dop853),
            Some("dopri5") => Some(Method::Dopri5),
            Some("taylor") => Some(Method::Taylor),
            Some(_) => Some(Method::Ralston),
        },
        rtol: r.number("run", "rtol", false)?.unwrap_or(dr.rtol),
        atol: r.number("run", "atol", false)?.unwrap_or(dr.atol),
        step: r.number("run", "step", false)?.unwrap_or(dr.step),
        output_dt: r.number("run", "output_dt", false)?.unwrap_or(dr.output_dt),
        tumble_theta: r.number("run", "tumble_theta", false)?.unwrap_or(dr.tumble_theta),
        flight: match r.choice("run", "flight", &["stop", "ignore"])? {
            None | Some("stop") => FlightPolicy::Stop,
            Some(_) => FlightPolicy::Ignore,
        },
        zeno_eps: r.number("run", "zeno_eps", false)?.unwrap_or(dr.zeno_eps),
        max_steps: r.count("run", "max_steps")?.unwrap_or(dr.max_steps),
        max_events: r.count("run", "max_events")?.unwrap_or(dr.max_events),
    };
    let initial = InitialState {
        theta: r.number("initial", "theta", false)?.unwrap_or(0.0),
        theta_dot: r.number("initial", "theta_dot", false)?.unwrap_or(0.0),
        x_dot: r.number("initial", "x_dot", false)?,
    };
    let analyses = Analyses {
        lyapunov: boolean(table, "analysis", "lyapunov")?.unwrap_or(false),
        lyapunov_method: match r.choice("analysis", "lyapunov_method", &["tangent", "benettin", "both"])? {
            None | Some("tangent") => LyapunovChoice::Tangent,
            Some("benettin") => LyapunovChoice::Benettin,
            Some(_) => LyapunovChoice::Both,
        },
        spectrum: boolean(table, "analysis", "spectrum")?.unwrap_or(false),
        spectrum_window: match r.choice("analysis", "spectrum_window", &["all", "paper"])? {
            None | Some("all") => SpectrumRange::All,
            Some(_) => SpectrumRange::Paper,
        },
    };
    r.reject_unknown(KNOWN_KEYS)?;

    excitation.record_h = read_record("excitation.file_h", file_h, source)?;
    excitation.record_v = read_record("excitation.file_v", file_v, source)?;
    let scenario = Scenario {
        block,
        impact,
        excitation,
        initial,
        run,
        analyses,
    };
    scenario.validate()?;
    Ok(scenario)
}

/// Resolves a swept or mapped key (`excitation.a_v`) to its [`Param`]; an
/// unknown or non-numeric key is an error naming it.
pub fn param(key: &str) -> Result<Param, ConfigError> {
    let Some((section, name)) = key.split_once('.') else {
        return Err(ConfigError::Usage(format!(
            "{key}: a parameter must be SECTION.KEY, e.g. excitation.a_v"
        )));
    };
    let Some((_, keys)) = KNOWN_KEYS.iter().find(|(s, _)| *s == section) else {
        let sections: Vec<&str> = KNOWN_KEYS.iter().map(|(s, _)| *s).collect();
        return Err(ConfigError::key(
            key,
            format!("unknown section (known: {})", sections.join(", ")),
        ));
    };
    if !keys.contains(&name) {
        return Err(ConfigError::key(
            key,
            format!("unknown key (known in [{section}]: {})", keys.join(", ")),
        ));
    }
    Param::ALL.into_iter().find(|p| p.key() == key).ok_or_else(|| {
        ConfigError::key(
            key,
            "is not a numeric parameter (a sweep or map varies a number: amplitudes, frequencies, phases, friction, impact coefficients, block size, initial state, tolerances)",
        )
    })
}

/// The resolved scenario as JSON, in the same sections and keys as the
/// TOML (infinite friction as the string `"inf"`, an unset
/// `initial.x_dot` as `null`): `summary.json`'s `config`, which repeats the
/// run.
pub fn to_json(s: &Scenario) -> Json {
    let num = |x: f64| if x.is_finite() { json!(x) } else { json!("inf") };
    let path = |r: &Option<Record>| r.as_ref().map(|r| r.path.display().to_string());
    let x = &s.excitation;
    json!({
        "block": { "width": s.block.width, "height": s.block.height },
        "friction": { "static": num(s.block.mu_s), "kinetic": num(s.block.kinetic()) },
        "impact": {
            "law": s.impact.law.name(), "r": s.impact_r(), "e": s.impact.e,
            "static": num(s.impact_mu_s()), "kinetic": num(s.impact_mu_k()),
        },
        "excitation": {
            "kind": x.kind.name(),
            "a_h": x.a_h, "a_v": x.a_v,
            "omega_h": x.omega_h, "omega_v": x.omega_v(),
            "phase_h": x.phase_h, "phase_v": x.phase_v,
            "shape": x.shape.name(), "cycles": x.cycles,
            "file_h": path(&x.record_h), "file_v": path(&x.record_v),
            "scale_h": x.scale_h, "scale_v": x.scale_v,
        },
        "initial": { "theta": s.initial.theta, "theta_dot": s.initial.theta_dot, "x_dot": s.initial.x_dot },
        "run": {
            "tau_end": s.run.tau_end, "method": s.run.method().name(),
            "rtol": s.run.rtol, "atol": s.run.atol, "step": s.run.step,
            "output_dt": s.run.output_dt, "tumble_theta": s.run.tumble_theta,
            "flight": match s.run.flight { FlightPolicy::Stop => "stop", FlightPolicy::Ignore => "ignore" },
            "zeno_eps": s.run.zeno_eps, "max_steps": s.run.max_steps, "max_events": s.run.max_events,
        },
        "analysis": {
            "lyapunov": s.analyses.lyapunov, "lyapunov_method": s.analyses.lyapunov_method.name(),
            "spectrum": s.analyses.spectrum, "spectrum_window": s.analyses.spectrum_window.name(),
        },
    })
}

/// Reads a preset or a config file (or the `default` preset) and applies
/// `--set` overrides, as the CLI does, into a table not yet resolved.
pub fn load_table(preset: Option<&str>, file: Option<&Path>, sets: &[String]) -> Result<(Table, Source), ConfigError> {
    let (mut table, source) = match (preset, file) {
        (Some(_), Some(_)) => {
            return Err(ConfigError::Usage("give either --preset or --config, not both".into()));
        }
        (_, Some(path)) => read_file(path)?,
        (name, None) => {
            let name = name.unwrap_or("default");
            let text = preset_text(name)?;
            (parse_toml(text, &format!("preset {name}"))?, Source::default())
        }
    };
    apply_sets(&mut table, sets)?;
    Ok((table, source))
}

/// Loads a scenario the way the CLI does: a preset or a file (or the
/// `default` preset), then `--set` overrides, then validation.
pub fn load(preset: Option<&str>, file: Option<&Path>, sets: &[String]) -> Result<Scenario, ConfigError> {
    let (table, source) = load_table(preset, file, sets)?;
    from_table(&table, &source)
}
