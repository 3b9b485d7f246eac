//! `rocking.Scene`: a resolved, validated scenario built through the
//! config layer, so its keys, units, defaults and error messages are the
//! CLI's (`--preset`, `--config`, `--set`).

use std::path::{Path, PathBuf};

use pyo3::prelude::*;
use pyo3::types::{PyDict, PyTuple};
use rocking::io::config::{self, KNOWN_KEYS, Source};
use rocking::sim::Scenario;
use toml::Table;

use crate::convert::{assignment, json_to_py};
use crate::errors::{from_config, key_error};
use crate::keys::strip_norm;
use crate::memory::{Memory, RecordArgs};

/// A block, its excitation, initial state and run settings, resolved and
/// validated exactly as the CLI resolves `--preset`/`--config` and `--set`.
///
/// `Scene(preset=None, *, file=None, config=None, **keys)`: the preset (or
/// the file; with neither, keys build on the literature's base of
/// `Scene.defaults()`: Housner impact, no sliding, no vertical motion; no
/// key at all is the app's `default` preset), then the assignments of
/// `config` (a dict of `"section.key": value` or `"section": {key: value}`),
/// then the keyword arguments: `a_h="0.35 g"` (a key unique to one section),
/// `friction={"static": 0.7}` (a section). Quantities take the CLI's unit
/// strings; a bare number only where it is SI, dimensionless or under a
/// normalised name (`tau_end`, `a_h_norm`): the key list below.
///
/// Ground motion from memory: `record_h=values` with `dt=` (s) or
/// `record_h=(times, values)`, and `unit=` ("g", "m/s2", "cm/s2"); the same
/// for `record_v`. The scene pickles with its samples.
#[pyclass(frozen, module = "rocking._rocking", name = "Scene")]
pub struct Scene {
    /// The unresolved config: what `with_` modifies.
    table: Table,
    /// Where relative record paths are resolved from.
    source: Source,
    /// The resolved scenario.
    scenario: Scenario,
    /// What the scene was made from, for `repr`.
    origin: String,
    /// Records given as samples.
    memory: Memory,
}

impl Scene {
    /// The resolved scenario.
    pub fn scenario(&self) -> &Scenario {
        &self.scenario
    }

    fn resolve(table: Table, source: Source, origin: String, memory: Memory) -> PyResult<Self> {
        let scenario = config::from_table_with(&table, &source, memory.records()).map_err(from_config)?;
        Ok(Self {
            table,
            source,
            scenario,
            origin,
            memory,
        })
    }
}

/// The section of an undotted keyword: the one section that has the key
/// (`_norm` spellings stripped). `width` and `height` are the block's, as
/// they always were; a rocking frame's columns are `frame={"width": …}` or
/// `"frame.width"`, and a stack's blocks are its tables' keys
/// (`config={"stack[2].height": "0.6 m"}`).
fn section_of(typed: &str) -> PyResult<&'static str> {
    let (name, _) = strip_norm(None, typed);
    let mut sections: Vec<&'static str> = KNOWN_KEYS
        .iter()
        .filter(|(_, keys)| keys.contains(&name))
        .map(|(s, _)| *s)
        .collect();
    if sections.contains(&"block") {
        sections.retain(|s| *s != "frame");
    }
    // A stack's keys are in its tables: an undotted key shared with
    // another section is that section's.
    if sections.len() > 1 {
        sections.retain(|s| *s != "stack");
    }
    match sections.as_slice() {
        [one] => Ok(one),
        [] => {
            let names: Vec<&str> = KNOWN_KEYS.iter().map(|(s, _)| *s).collect();
            Err(key_error(
                typed,
                format!(
                    "{typed}: unknown key (a keyword is a key of one section, e.g. a_h=\"0.35 g\", or a section with a dict, e.g. friction={{\"static\": 0.7}}; sections: {})",
                    names.join(", ")
                ),
            ))
        }
        several => Err(key_error(
            typed,
            format!(
                "{typed}: the key is in several sections ({}); give the section, e.g. {}={{\"{typed}\": …}}",
                several.join(", "),
                several[0]
            ),
        )),
    }
}

/// The assignment of `value` to `name` of `section`, typed as `typed`
/// (a `_norm` spelling is the normalised value of its key).
fn section_assignment(typed: &str, section: &str, name: &str, value: &Bound<'_, PyAny>) -> PyResult<String> {
    let (key, norm) = strip_norm(Some(section), name);
    assignment(typed, section, key, norm, value)
}

/// A dotted key as typed (`"excitation.a_h"`), split at its first dot.
fn dotted_assignment(typed: &str, value: &Bound<'_, PyAny>) -> PyResult<String> {
    match typed.split_once('.') {
        Some((section, name)) => section_assignment(typed, section, name, value),
        None => Err(key_error(
            typed,
            format!(
                "{typed}: expected \"section.key\" or a section with a dict, e.g. \"friction\": {{\"static\": 0.7}}"
            ),
        )),
    }
}

/// `KEY=VALUE` assignments (the CLI's `--set`) from a dict of dotted keys
/// or sections.
fn dict_assignments(dict: &Bound<'_, PyDict>, out: &mut Vec<String>) -> PyResult<()> {
    for (k, v) in dict.iter() {
        let key: String = k.extract()?;
        if let Ok(inner) = v.cast::<PyDict>() {
            for (ik, iv) in inner.iter() {
                let name: String = ik.extract()?;
                out.push(section_assignment(&format!("{key}.{name}"), &key, &name, &iv)?);
            }
        } else {
            out.push(dotted_assignment(&key, &v)?);
        }
    }
    Ok(())
}

/// Assignments from keyword arguments: a section name with a dict, or a
/// key unique to one section.
fn keyword_assignments(kwargs: &Bound<'_, PyDict>, out: &mut Vec<String>) -> PyResult<()> {
    for (k, v) in kwargs.iter() {
        let name: String = k.extract()?;
        if KNOWN_KEYS.iter().any(|(s, _)| *s == name)
            && let Ok(inner) = v.cast::<PyDict>()
        {
            for (ik, iv) in inner.iter() {
                let key: String = ik.extract()?;
                out.push(section_assignment(&format!("{name}.{key}"), &name, &key, &iv)?);
            }
            continue;
        }
        let section = section_of(&name)?;
        out.push(section_assignment(&name, section, &name, &v)?);
    }
    Ok(())
}

/// All assignments of a `config` dict and keyword arguments, in that order.
fn assignments(config: Option<&Bound<'_, PyDict>>, kwargs: Option<&Bound<'_, PyDict>>) -> PyResult<Vec<String>> {
    let mut sets = Vec::new();
    if let Some(c) = config {
        dict_assignments(c, &mut sets)?;
    }
    if let Some(k) = kwargs {
        keyword_assignments(k, &mut sets)?;
    }
    Ok(sets)
}

#[pymethods]
impl Scene {
    #[new]
    #[pyo3(signature = (preset=None, *, file=None, config=None, record_h=None, record_v=None, dt=None, unit=None, **keys))]
    #[allow(clippy::too_many_arguments)]
    fn new(
        preset: Option<&str>,
        file: Option<PathBuf>,
        config: Option<&Bound<'_, PyDict>>,
        record_h: Option<&Bound<'_, PyAny>>,
        record_v: Option<&Bound<'_, PyAny>>,
        dt: Option<&Bound<'_, PyAny>>,
        unit: Option<&str>,
        keys: Option<&Bound<'_, PyDict>>,
    ) -> PyResult<Self> {
        let records = RecordArgs {
            h: record_h,
            v: record_v,
            dt,
            unit,
        };
        let mut sets = assignments(config, keys)?;
        let memory = records.read(&Memory::default(), &mut sets)?;
        let (table, source) = config::load_table(preset, file.as_deref(), &sets).map_err(from_config)?;
        let mut origin = match (&file, preset) {
            (Some(f), _) => format!("file {}", f.display()),
            (None, Some(p)) => format!("preset {p}"),
            (None, None) if !sets.is_empty() => "defaults".to_string(),
            (None, None) => "preset default".to_string(),
        };
        if !sets.is_empty() {
            origin = format!("{origin}, {}", sets.join(", "));
        }
        origin.push_str(&records.describe());
        Self::resolve(table, source, origin, memory)
    }

    /// The scenario's own defaults with `config` and keyword assignments,
    /// from no preset: the base scene of `rocking fragility`, `spectrum`
    /// and `pulse-map` without `--preset`/`--config` (Housner impact, no
    /// sliding, rtol 1e-10).
    #[staticmethod]
    #[pyo3(signature = (config=None, **keys))]
    fn defaults(config: Option<&Bound<'_, PyDict>>, keys: Option<&Bound<'_, PyDict>>) -> PyResult<Self> {
        let sets = assignments(config, keys)?;
        let (table, source) = config::base_table(&sets).map_err(from_config)?;
        let mut origin = "defaults".to_string();
        if !sets.is_empty() {
            origin = format!("{origin}, {}", sets.join(", "));
        }
        Self::resolve(table, source, origin, Memory::default())
    }

    /// A copy with more assignments (a `config` dict, records given as
    /// samples and/or keywords, as for `Scene(...)`); the scene itself is
    /// unchanged.
    #[pyo3(signature = (config=None, *, record_h=None, record_v=None, dt=None, unit=None, **keys))]
    fn with_(
        &self,
        config: Option<&Bound<'_, PyDict>>,
        record_h: Option<&Bound<'_, PyAny>>,
        record_v: Option<&Bound<'_, PyAny>>,
        dt: Option<&Bound<'_, PyAny>>,
        unit: Option<&str>,
        keys: Option<&Bound<'_, PyDict>>,
    ) -> PyResult<Self> {
        let records = RecordArgs {
            h: record_h,
            v: record_v,
            dt,
            unit,
        };
        let mut sets = assignments(config, keys)?;
        let memory = records.read(&self.memory, &mut sets)?;
        let mut table = self.table.clone();
        config::apply_sets(&mut table, &sets).map_err(from_config)?;
        let mut origin = if sets.is_empty() {
            self.origin.clone()
        } else {
            format!("{}, {}", self.origin, sets.join(", "))
        };
        origin.push_str(&records.describe());
        Self::resolve(table, self.source.clone(), origin, memory)
    }

    /// The resolved configuration as a dict in the config's sections and
    /// keys (summary.json's `config`): block sizes in m, the rest in the
    /// model's normalised units, infinite friction as `"inf"`.
    fn to_dict<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        json_to_py(py, &config::to_json(&self.scenario))
    }

    /// Every resolved input in normalised and physical units (summary.json's
    /// `resolved`).
    fn resolved<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        json_to_py(py, &rocking::io::output::resolved_json(&self.scenario))
    }

    /// Warnings about the scene (a record whose peak suggests a wrong
    /// unit): the lines the CLI prints before a run, less `warning: `.
    #[getter]
    fn warnings(&self) -> Vec<String> {
        self.scenario
            .warnings()
            .into_iter()
            .map(|w| w.strip_prefix("warning: ").map_or(w.clone(), str::to_string))
            .collect()
    }

    /// Block slenderness ψ = atan(B/H), rad.
    #[getter]
    fn psi_rad(&self) -> f64 {
        self.scenario.geometry().psi
    }

    /// Frequency parameter p = √(3g/(4R)), rad/s (τ = p·t).
    #[getter]
    fn p_per_s(&self) -> f64 {
        self.scenario.geometry().p
    }

    /// Half-diagonal R, m.
    #[getter]
    fn r_m(&self) -> f64 {
        self.scenario.geometry().r
    }

    fn __repr__(&self) -> String {
        format!("rocking.Scene({})", self.origin)
    }

    /// Pickles as the unresolved config, its folder and the samples of
    /// records given in memory, re-resolved where it is unpickled: a Dask
    /// worker needs record files at the same paths, but no file for a
    /// record given as samples.
    fn __reduce__<'py>(&self, py: Python<'py>) -> PyResult<(Bound<'py, PyAny>, Bound<'py, PyTuple>)> {
        let text =
            toml::to_string(&self.table).map_err(|e| key_error("", format!("cannot serialise the scene: {e}")))?;
        let rebuild = py.import("rocking._rocking")?.getattr("_scene_from_state")?;
        let args = (
            text,
            self.source.base_dir.display().to_string(),
            self.origin.clone(),
            self.memory.state(py)?,
        )
            .into_pyobject(py)?;
        Ok((rebuild, args))
    }
}

/// Rebuilds a pickled [`Scene`].
#[pyfunction]
#[pyo3(signature = (text, base_dir, origin, memory=None))]
pub fn _scene_from_state(
    text: &str,
    base_dir: &str,
    origin: String,
    memory: Option<&Bound<'_, PyAny>>,
) -> PyResult<Scene> {
    let table = config::parse_toml(text, "pickled scene").map_err(from_config)?;
    let source = Source {
        base_dir: Path::new(base_dir).to_path_buf(),
    };
    let memory = match memory {
        Some(m) if !m.is_none() => Memory::from_state(m)?,
        _ => Memory::default(),
    };
    Scene::resolve(table, source, origin, memory)
}

/// The text of `help(rocking.Scene)`'s key list (every key with its units).
#[pyfunction]
pub fn _keys_help() -> String {
    crate::keys::keys_help()
}

/// The config keys [`crate::keys::KEY_DOCS`] does not document (none).
#[pyfunction]
pub fn _undocumented_keys() -> Vec<String> {
    crate::keys::undocumented()
}

/// The names of the presets shipped with the CLI.
#[pyfunction]
pub fn presets() -> Vec<&'static str> {
    rocking::io::presets::names()
}
