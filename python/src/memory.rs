//! Ground motion from memory: `Scene(record_h=values, dt=0.01, unit="g")`
//! or `record_h=(times, values)`, read into the core's
//! [`Record::in_memory`], and pickled with its samples.

use pyo3::prelude::*;
use pyo3::types::{PyString, PyTuple};
use rocking::model::excitation::record::Series;
use rocking::model::units::AccelUnit;
use rocking::sim::scenario::Record;

use crate::errors::key_error;

/// The shortest and longest time step accepted, s: outside, the samples
/// are almost certainly not in seconds (the bounds of a record file's
/// `excitation.dt_h`).
const DT_RANGE_S: (f64, f64) = (1e-5, 10.0);

/// Records given as samples, horizontal and vertical.
#[derive(Clone, Default)]
pub struct Memory {
    pub h: Option<Record>,
    pub v: Option<Record>,
}

impl Memory {
    /// The records, for [`rocking::io::config::from_table_with`].
    pub fn records(&self) -> [Option<&Record>; 2] {
        [self.h.as_ref(), self.v.as_ref()]
    }

    /// The samples, for pickling: per record `None` or
    /// `(times_s, accel_g, unit, dt)`.
    pub fn state<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        let one = |r: &Option<Record>| {
            r.as_ref().map(|r| {
                (
                    r.series.times_s().to_vec(),
                    r.series.accel_g().to_vec(),
                    r.unit.name(),
                    r.dt,
                )
            })
        };
        Ok((one(&self.h), one(&self.v)).into_pyobject(py)?.into_any())
    }

    /// The records of a pickled [`Memory::state`].
    pub fn from_state(state: &Bound<'_, PyAny>) -> PyResult<Self> {
        type One = Option<(Vec<f64>, Vec<f64>, String, Option<f64>)>;
        let (h, v): (One, One) = state.extract()?;
        let one = |name: &str, r: One| -> PyResult<Option<Record>> {
            r.map(|(times, accel, unit, dt)| {
                let unit =
                    AccelUnit::parse(&unit).ok_or_else(|| key_error(name, format!("{name}: unknown unit {unit}")))?;
                let series = Series::new(times, accel).map_err(|e| key_error(name, format!("{name}: {e}")))?;
                Ok(Record::in_memory(series, unit, dt))
            })
            .transpose()
        };
        Ok(Self {
            h: one("record_h", h)?,
            v: one("record_v", v)?,
        })
    }
}

/// The record arguments of `Scene(...)` and `Scene.with_(...)`.
pub struct RecordArgs<'a, 'py> {
    pub h: Option<&'a Bound<'py, PyAny>>,
    pub v: Option<&'a Bound<'py, PyAny>>,
    /// Time step of samples given without times, s.
    pub dt: Option<&'a Bound<'py, PyAny>>,
    /// Unit of the accelerations.
    pub unit: Option<&'a str>,
}

/// Whether `value` is a number (not a sequence of them).
fn is_number(value: &Bound<'_, PyAny>) -> bool {
    value.extract::<f64>().is_ok() && !value.hasattr("__len__").unwrap_or(false)
}

impl RecordArgs<'_, '_> {
    /// The records these arguments give, over `base` (a `with_`'s scene),
    /// and the assignment that makes the scene a record scene, added to
    /// `sets`. A `kind` other than "record" with a record in memory is an
    /// error rather than a record silently ignored.
    pub fn read(&self, base: &Memory, sets: &mut Vec<String>) -> PyResult<Memory> {
        if self.h.is_none() && self.v.is_none() {
            for (name, given) in [("dt", self.dt.is_some()), ("unit", self.unit.is_some())] {
                if given {
                    return Err(key_error(
                        name,
                        format!(
                            "{name}: describes samples given as record_h= or record_v=; a record file takes file_h= with unit_h= and dt_h="
                        ),
                    ));
                }
            }
            return Ok(base.clone());
        }
        let unit_text = self.unit.ok_or_else(|| {
            key_error(
                "unit",
                "unit: needed with record_h/record_v, the unit of the accelerations: \"g\", \"m/s2\" or \"cm/s2\"",
            )
        })?;
        let unit = AccelUnit::parse(unit_text).ok_or_else(|| {
            key_error(
                "unit",
                format!("unit={unit_text:?}: unknown unit (known: \"g\", \"m/s2\", \"cm/s2\")"),
            )
        })?;
        let dt = self.dt.map(|d| self.dt_s(d)).transpose()?;
        let mut out = base.clone();
        if let Some(h) = self.h {
            out.h = Some(record("record_h", h, unit, dt)?);
        }
        if let Some(v) = self.v {
            out.v = Some(record("record_v", v, unit, dt)?);
        }
        if self.h.is_some() {
            if let Some(other) = sets
                .iter()
                .find(|s| s.starts_with("excitation.kind=") && s.as_str() != "excitation.kind=\"record\"")
            {
                return Err(key_error(
                    "excitation.kind",
                    format!("{other}: record_h gives a record, so kind must be \"record\" (or leave kind out)"),
                ));
            }
            sets.insert(0, "excitation.kind=\"record\"".to_string());
        }
        Ok(out)
    }

    /// `dt` in seconds: a number (s), checked.
    fn dt_s(&self, d: &Bound<'_, PyAny>) -> PyResult<f64> {
        if d.is_instance_of::<PyString>() || !is_number(d) {
            return Err(key_error(
                "dt",
                format!("dt={d}: expected the time step in seconds as a number, e.g. dt=0.01"),
            ));
        }
        let dt: f64 = d.extract()?;
        let (lo, hi) = DT_RANGE_S;
        if !(dt.is_finite() && (lo..=hi).contains(&dt)) {
            return Err(key_error(
                "dt",
                format!("dt={dt}: must be a time step in [{lo}, {hi}] s"),
            ));
        }
        Ok(dt)
    }

    /// How the records were given, for `repr` (empty when none were).
    pub fn describe(&self) -> String {
        let mut out = String::new();
        for (name, given) in [("record_h", self.h), ("record_v", self.v)] {
            if let Some(g) = given {
                let n = g.len().unwrap_or(0);
                let form = if g.is_instance_of::<PyTuple>() {
                    "(times, values)"
                } else {
                    "values"
                };
                out.push_str(&format!(", {name}=<{form} in memory, {n}>"));
            }
        }
        out
    }
}

/// A record from `values` (with `dt`) or `(times, values)`.
fn record(name: &str, given: &Bound<'_, PyAny>, unit: AccelUnit, dt: Option<f64>) -> PyResult<Record> {
    let pair = given
        .cast::<PyTuple>()
        .ok()
        .filter(|t| t.len() == 2 && t.iter().all(|x| !is_number(&x)));
    let (times, values): (Vec<f64>, Vec<f64>) = match (pair, dt) {
        (Some(_), Some(_)) => {
            return Err(key_error(
                "dt",
                format!("dt: {name} was given as (times, values); give dt only for values without times"),
            ));
        }
        (Some(t), None) => {
            let times: Vec<f64> = floats(name, &t.get_item(0)?)?;
            let values: Vec<f64> = floats(name, &t.get_item(1)?)?;
            (times, values)
        }
        (None, Some(dt)) => {
            let values = floats(name, given)?;
            let times = (0..values.len()).map(|i| i as f64 * dt).collect();
            (times, values)
        }
        (None, None) => {
            return Err(key_error(
                "dt",
                format!(
                    "dt: needed for {name} given as values alone (the time step in s), or give {name}=(times, values)"
                ),
            ));
        }
    };
    let accel_g: Vec<f64> = values.iter().map(|&a| unit.to_g(a)).collect();
    let series = Series::new(times, accel_g).map_err(|e| key_error(name, format!("{name}: {e}")))?;
    Ok(Record::in_memory(series, unit, dt))
}

/// A sequence of numbers (a list, a numpy array) as floats.
fn floats(name: &str, value: &Bound<'_, PyAny>) -> PyResult<Vec<f64>> {
    if value.is_instance_of::<PyString>() {
        return Err(key_error(name, format!("{name}: expected numbers, got a string")));
    }
    // numpy arrays convert element by element; tolist() is much faster.
    let list = if value.hasattr("tolist")? {
        value.call_method0("tolist")?
    } else {
        value.clone()
    };
    list.extract::<Vec<f64>>().map_err(|_| {
        key_error(
            name,
            format!("{name}: expected a 1-D sequence of numbers (a list or a numpy array)"),
        )
    })
}
