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

use toml::Table;

mod echo;
mod error;
mod file;
mod floor;
mod quantity;
mod raw;
mod records;
mod set;
mod stack;

pub use echo::to_json;
pub use error::ConfigError;
pub use file::parse_toml;
pub(crate) use file::read_file;
pub use set::{apply_sets, line_of, set_dotted, set_dotted_from};

use crate::model::{FlightPolicy, Frame, Geometry};
use crate::sim::scenario::{Analyses, Block, ExcitationSpec, Impact, LyapunovChoice, Record, RunSpec};
use crate::sim::{InitialState, Param, Scenario, catalogue};
use quantity::{Dimension, Quantity};
use raw::{Coefficient, Count, Finite, RawConfig};
use records::{RecordFrom, RecordKeys, given_or_read, record_scale};

/// Every section and its keys, in the config file's order: the
/// catalogue's ([`crate::sim::catalogue`]), where each key is declared.
pub static KNOWN_KEYS: std::sync::LazyLock<Vec<(&'static str, Vec<&'static str>)>> = std::sync::LazyLock::new(|| {
    catalogue::sections()
        .into_iter()
        .map(|s| (s, catalogue::keys_of(s)))
        .collect()
});

/// Where a config came from, for resolving relative record paths.
#[derive(Clone, Debug, Default)]
pub struct Source {
    /// Directory that relative paths written in the config are relative
    /// to: the config file's folder (empty: the current folder). Paths
    /// given with `--set` are made absolute when set ([`set_dotted`]), so
    /// this never applies to them.
    pub base_dir: PathBuf,
}

impl Source {
    /// The source of a shipped preset. A preset names its records as
    /// shipped ones (`shipped:kobe-1995.dat`, compiled into the program),
    /// so it needs no folder: it runs the same from a copied binary, after
    /// `cargo install` or from any folder (tested for every preset).
    pub fn preset() -> Self {
        Self::default()
    }
}

/// Reads a preset shipped in `assets/presets/NAME.toml`. The message for
/// an unknown name keeps the CLI's `--preset` wording: the Python package's
/// `Scene(name)` is tested to raise the CLI's very message.
pub fn preset_text(name: &str) -> Result<&'static str, ConfigError> {
    super::presets::get(name).ok_or_else(|| {
        ConfigError::Usage(format!(
            "--preset {name}: unknown preset (known: {})",
            super::presets::names().join(", ")
        ))
    })
}

/// The first key or section of `table` that the config does not know, as
/// an error listing the known ones (serde's `deny_unknown_fields` would
/// refuse it too, but without the list).
fn reject_unknown(table: &Table) -> Result<(), ConfigError> {
    for (section, value) in table {
        let Some((_, keys)) = KNOWN_KEYS.iter().find(|(s, _)| s == section) else {
            let sections: Vec<&str> = KNOWN_KEYS.iter().map(|(s, _)| *s).collect();
            return Err(ConfigError::key(
                section,
                format!("unknown section (known: {})", sections.join(", ")),
            ));
        };
        if let toml::Value::Table(sec) = value
            && let Some(key) = sec.keys().find(|k| !keys.contains(&k.as_str()))
        {
            return Err(ConfigError::key(
                &format!("{section}.{key}"),
                format!("unknown key (known in [{section}]: {})", keys.join(", ")),
            ));
        }
    }
    Ok(())
}

/// With `[frame]`, the sections that describe a single block are errors:
/// a config describes one structure, and a frame's columns do not slide.
fn frame_alone(table: &Table) -> Result<(), ConfigError> {
    if table.contains_key("block") {
        return Err(ConfigError::key(
            "block",
            "a config has one of [block] and [frame], not both (a frame's columns are frame.width × frame.height)",
        ));
    }
    if table.contains_key("friction") {
        return Err(ConfigError::key(
            "friction",
            "a [frame]'s columns rock on stuck corners; sliding of a frame is not modelled: remove [friction] (docs/model.md §16)",
        ));
    }
    Ok(())
}

/// Deserialises `table` into the config's shape; a value of the wrong type
/// is an error naming its key.
fn raw(table: &Table) -> Result<RawConfig, ConfigError> {
    reject_unknown(table)?;
    serde_path_to_error::deserialize(toml::Value::Table(table.clone())).map_err(|e| {
        let key = e.path().to_string();
        let message = e.into_inner().message().to_string();
        if key == "." {
            ConfigError::Usage(message)
        } else {
            ConfigError::Key { key, message }
        }
    })
}

/// Resolves `table` into a scenario and validates it. Record paths are
/// relative to `source.base_dir`; the records are read here, so a scenario
/// never refers to a file it has not read.
pub fn from_table(table: &Table, source: &Source) -> Result<Scenario, ConfigError> {
    from_table_with(table, source, [None, None])
}

/// [`from_table`] with records given as samples ([`Record::in_memory`]),
/// horizontal and vertical, for a caller that holds them (the Python
/// package): each takes the place of a file the table does not name
/// (naming one as well is an error naming `excitation.file_*`).
pub fn from_table_with(table: &Table, source: &Source, memory: [Option<&Record>; 2]) -> Result<Scenario, ConfigError> {
    let [h, v] = memory;
    resolve(table, source, [RecordFrom::given(h), RecordFrom::given(v)])
}

/// [`from_table`] for a table whose record keys (`excitation.file_*`,
/// `unit_*`, `dt_*`, `crc32_*`, `channel_*`) are those `kept` resolved
/// from: each record the table names is taken from `kept` (sharing its
/// samples) instead of being read again. For an edit of another key, such
/// as a slider drag, which must not read a file every frame; the caller
/// vouches for the record keys. A record `kept` lacks is read.
pub fn from_table_keeping(table: &Table, source: &Source, kept: &Scenario) -> Result<Scenario, ConfigError> {
    let x = &kept.excitation;
    let from = [
        RecordFrom::kept(x.record_h.as_ref()),
        RecordFrom::kept(x.record_v.as_ref()),
    ];
    resolve(table, source, from)
}

/// [`from_table`], with the horizontal and vertical records taken as
/// `records` say.
fn resolve(table: &Table, source: &Source, records: [RecordFrom<'_>; 2]) -> Result<Scenario, ConfigError> {
    let raw = raw(table)?;
    let d = Scenario::default();
    let num = |x: Option<Finite>| x.map(|v| v.0);
    let coef = |x: Option<Coefficient>| x.map(|v| v.0);
    // Sizes first: every other quantity with a unit converts with the
    // block's ψ, p and R.
    let metres = |key: &str, q: Option<Quantity>, default: f64| -> Result<f64, ConfigError> {
        q.map_or(Ok(default), |q| {
            q.resolve(key, Dimension::Length, &Geometry::new(1.0, 1.0))
        })
    };
    let (block, frame, stack) = match (&raw.frame, &raw.stack) {
        (_, Some(tables)) => {
            let (block, stack) = stack::resolve(table, tables)?;
            (block, None, stack)
        }
        (None, None) => (
            Block {
                width: metres("block.width", raw.block.width, d.block.width)?,
                height: metres("block.height", raw.block.height, d.block.height)?,
                mu_s: coef(raw.friction.mu_s).unwrap_or(d.block.mu_s),
                mu_k: coef(raw.friction.mu_k),
            },
            None,
            None,
        ),
        (Some(f), None) => {
            frame_alone(table)?;
            let required = |key: &str, what: &str| ConfigError::key(key, format!("is required with [frame] ({what})"));
            let size = |key: &str, q: Option<Quantity>, what: &str| -> Result<f64, ConfigError> {
                let q = q.ok_or_else(|| required(key, what))?;
                q.resolve(key, Dimension::Length, &Geometry::new(1.0, 1.0))
            };
            let block = Block {
                width: size("frame.width", f.width, "each column's width, e.g. 1.2 or \"120 cm\"")?,
                height: size("frame.height", f.height, "each column's height, e.g. 6 or \"6 m\"")?,
                mu_s: f64::INFINITY,
                mu_k: None,
            };
            let beam = f.beam_mass_ratio.ok_or_else(|| {
                required(
                    "frame.beam_mass_ratio",
                    "the cap beam's mass over the columns' total mass, e.g. 0.5",
                )
            })?;
            let frame = Frame {
                // Past u32, the scenario's range check could not see it.
                columns: f.columns.map_or(2, |Count(n)| u32::try_from(n).unwrap_or(u32::MAX)),
                beam_mass_ratio: beam.0,
            };
            (block, Some(frame), None)
        }
    };
    // The block is checked before any conversion uses its geometry.
    Scenario {
        block: block.clone(),
        frame,
        stack: stack.clone(),
        ..Scenario::default()
    }
    .validate()?;
    let geo = block.geometry();
    // A parameter's key and dimension are the catalogue's.
    let q = |p: Param, x: Option<Quantity>| {
        let spec = catalogue::spec_of(p);
        let dim = spec
            .dimension()
            .expect("a quantity key's entry has a dimension (tested)");
        x.map(|x| x.resolve(spec.key, dim, &geo)).transpose()
    };
    let impact = Impact {
        law: raw.impact.law.unwrap_or(d.impact.law),
        r: num(raw.impact.r),
        e: num(raw.impact.e).unwrap_or(d.impact.e),
        mu_s: coef(raw.impact.mu_s),
        mu_k: coef(raw.impact.mu_k),
    };
    let (x, dx) = (&raw.excitation, &d.excitation);
    let cycles = match x.cycles {
        None => dx.cycles,
        // Past u32, the scenario's range check could not see the value.
        Some(Count(n)) => u32::try_from(n).unwrap_or(u32::MAX),
    };
    let keys_h = RecordKeys {
        suffix: "_h",
        file: x.file_h.as_deref(),
        unit: x.unit_h.as_deref(),
        dt: x.dt_h,
        crc32: x.crc32_h.as_deref(),
        channel: x.channel_h.map(|Count(n)| n),
    };
    let keys_v = RecordKeys {
        suffix: "_v",
        file: x.file_v.as_deref(),
        unit: x.unit_v.as_deref(),
        dt: x.dt_v,
        crc32: x.crc32_v.as_deref(),
        channel: x.channel_v.map(|Count(n)| n),
    };
    let [from_h, from_v] = records;
    let record_h = given_or_read(&keys_h, source, from_h)?;
    let record_v = given_or_read(&keys_v, source, from_v)?;
    let scale_h = record_scale(&keys_h, record_h.as_ref(), x.scale_h, x.pga_h, &geo, dx.scale_h)?;
    let scale_v = record_scale(&keys_v, record_v.as_ref(), x.scale_v, x.pga_v, &geo, dx.scale_v)?;
    let excitation = ExcitationSpec {
        kind: x.kind.unwrap_or(dx.kind),
        a_h: q(Param::Ah, x.a_h)?.unwrap_or(dx.a_h),
        a_v: q(Param::Av, x.a_v)?.unwrap_or(dx.a_v),
        omega_h: q(Param::OmegaH, x.omega_h)?.unwrap_or(dx.omega_h),
        omega_v: q(Param::OmegaV, x.omega_v)?,
        phase_h: q(Param::PhaseH, x.phase_h)?.unwrap_or(dx.phase_h),
        phase_v: q(Param::PhaseV, x.phase_v)?.unwrap_or(dx.phase_v),
        shape: x.shape.unwrap_or(dx.shape),
        cycles,
        record_h,
        record_v,
        scale_h,
        scale_v,
    };
    let (r, dr) = (&raw.run, &d.run);
    let count = |c: Option<Count>| c.map(|c| c.0);
    let tau_end = match (r.tau_end, r.t_end) {
        (Some(_), Some(_)) => {
            return Err(ConfigError::key(
                "run.t_end",
                "give either run.tau_end or run.t_end, not both",
            ));
        }
        (Some(t), None) => Some(t.resolve("run.tau_end", Dimension::Tau, &geo)?),
        (None, Some(t)) => {
            let tau = t.resolve("run.t_end", Dimension::Seconds, &geo)? * geo.p;
            // Out of τ's range, the key the user wrote is named, not τ.
            if !(tau > 0.0 && tau <= 1e9) {
                return Err(ConfigError::key(
                    "run.t_end",
                    format!("is τ = p t = {tau:?}, out of range: τ must be in (0, 1e9]"),
                ));
            }
            Some(tau)
        }
        (None, None) => None,
    };
    let tail_s = r
        .tail_s
        .map(|t| t.resolve("run.tail_s", Dimension::Seconds, &geo))
        .transpose()?;
    if tail_s.is_some() && tau_end.is_some() {
        return Err(ConfigError::key(
            "run.tail_s",
            "a run with run.tau_end or run.t_end ends there; run.tail_s is for runs whose record decides the length",
        ));
    }
    let run = RunSpec {
        tau_end: tau_end.unwrap_or(dr.tau_end),
        method: r.method,
        rtol: num(r.rtol).unwrap_or(dr.rtol),
        atol: num(r.atol).unwrap_or(dr.atol),
        step: q(Param::Step, r.step)?.unwrap_or(dr.step),
        output_dt: q(Param::OutputDt, r.output_dt)?.unwrap_or(dr.output_dt),
        tumble_theta: q(Param::TumbleTheta, r.tumble_theta)?.unwrap_or(dr.tumble_theta),
        flight: r.flight.map_or(dr.flight, FlightPolicy::from),
        zeno_eps: num(r.zeno_eps).unwrap_or(dr.zeno_eps),
        max_steps: count(r.max_steps).unwrap_or(dr.max_steps),
        max_events: count(r.max_events).unwrap_or(dr.max_events),
        record_tail_s: match tau_end {
            Some(_) => None,
            None => Some(tail_s.unwrap_or(crate::sim::scenario::RECORD_TAIL_S)),
        },
    };
    let initial = InitialState {
        theta: q(Param::Theta0, raw.initial.theta)?.unwrap_or(d.initial.theta),
        theta_dot: q(Param::ThetaDot0, raw.initial.theta_dot)?.unwrap_or(d.initial.theta_dot),
        x_dot: q(Param::XDot0, raw.initial.x_dot)?,
    };
    let (a, da) = (&raw.analysis, &d.analyses);
    let analyses = Analyses {
        lyapunov: a.lyapunov.unwrap_or(da.lyapunov),
        // A stack's tangent equations are not written: its default is the
        // method it has.
        lyapunov_method: a.lyapunov_method.unwrap_or(if stack.is_some() {
            LyapunovChoice::Benettin
        } else {
            da.lyapunov_method
        }),
        spectrum: a.spectrum.unwrap_or(da.spectrum),
        spectrum_window: a.spectrum_window.unwrap_or(da.spectrum_window),
    };
    let floor = floor::resolve(&raw.floor, &geo)?;
    let scenario = Scenario {
        block,
        impact,
        excitation,
        initial,
        run,
        analyses,
        floor,
        frame,
        stack,
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

/// The literature's base scene with `sets` applied: every key not given
/// takes the scenario's own default ([`Scenario::default`]: Housner's
/// impact law, no sliding, no vertical motion, a record run as long as the
/// record plus `run.tail_s`). A scene built from keys alone starts here,
/// and so do the engineering commands without `--preset`/`--config`: one
/// definition, so that an engineer's cabinet never inherits the app's demo
/// (whose ratio law and friction answer another question). Relative paths
/// are relative to the current folder.
pub fn base_table(sets: &[String]) -> Result<(Table, Source), ConfigError> {
    let mut table = Table::new();
    apply_sets(&mut table, sets)?;
    Ok((table, Source::default()))
}

/// Reads a preset or a config file and applies `--set` overrides, as the
/// CLI does, into a table not yet resolved. With neither, keys alone build
/// on the literature's base ([`base_table`]); no keys at all is the app's
/// scene, the `default` preset.
pub fn load_table(preset: Option<&str>, file: Option<&Path>, sets: &[String]) -> Result<(Table, Source), ConfigError> {
    let (mut table, source) = match (preset, file) {
        (Some(_), Some(_)) => {
            return Err(ConfigError::Usage(
                "give either a preset or a config file, not both".into(),
            ));
        }
        (_, Some(path)) => read_file(path)?,
        (None, None) if !sets.is_empty() => return base_table(sets),
        (name, None) => {
            let name = name.unwrap_or("default");
            let text = preset_text(name)?;
            (parse_toml(text, &format!("preset {name}"))?, Source::preset())
        }
    };
    apply_sets(&mut table, sets)?;
    Ok((table, source))
}

/// Loads a scenario the way the CLI does: a preset or a file, then `--set`
/// overrides, then validation ([`load_table`] says which base).
pub fn load(preset: Option<&str>, file: Option<&Path>, sets: &[String]) -> Result<Scenario, ConfigError> {
    let (table, source) = load_table(preset, file, sets)?;
    from_table(&table, &source)
}
