//! Conversions at the Python edge: Python values into the config's
//! `KEY=VALUE` assignments, and JSON (summaries, resolved configs) into
//! Python objects.

use pyo3::prelude::*;
use pyo3::types::{PyBool, PyDict, PyFloat, PyInt, PyList, PyString};
use serde_json::Value as Json;

use crate::errors::key_error;

/// A Python value as the text of a TOML value, so that `KEY=TEXT` goes
/// through the CLI's own `--set` parser: a number or bool as its literal,
/// a string (a quantity with its unit, `"0.35 g"`, or a name) quoted. A
/// path-like value is its path as a string.
pub fn toml_literal(key: &str, value: &Bound<'_, PyAny>) -> PyResult<String> {
    // bool before int: Python's bool is an int.
    if value.is_instance_of::<PyBool>() {
        let b: bool = value.extract()?;
        return Ok(b.to_string());
    }
    if value.is_instance_of::<PyInt>() {
        let n: i64 = value
            .extract()
            .map_err(|_| key_error(key, format!("{key}: integer {value} is out of range")))?;
        return Ok(n.to_string());
    }
    if value.is_instance_of::<PyFloat>() {
        let x: f64 = value.extract()?;
        // TOML spells these inf, -inf and nan; the config then refuses a
        // NaN naming the key, as it does for `--set KEY=nan`.
        return Ok(if x.is_nan() {
            "nan".to_string()
        } else {
            format!("{x:?}")
        });
    }
    if value.is_instance_of::<PyString>() {
        let s: String = value.extract()?;
        return Ok(toml::Value::String(s).to_string());
    }
    if let Ok(path) = value.extract::<std::path::PathBuf>() {
        return Ok(toml::Value::String(path.display().to_string()).to_string());
    }
    // numpy scalars and other numbers: through float().
    if let Ok(x) = value.call_method0("__float__").and_then(|f| f.extract::<f64>()) {
        return Ok(if x.is_nan() {
            "nan".to_string()
        } else {
            format!("{x:?}")
        });
    }
    let type_name = value.get_type().name()?;
    Err(key_error(
        key,
        format!(
            "{key}: expected a number, a string (a quantity with its unit, e.g. \"0.35 g\") or a bool, got {type_name}"
        ),
    ))
}

/// A JSON value as the Python object `json.loads` would give.
pub fn json_to_py<'py>(py: Python<'py>, v: &Json) -> PyResult<Bound<'py, PyAny>> {
    Ok(match v {
        Json::Null => py.None().into_bound(py),
        Json::Bool(b) => PyBool::new(py, *b).to_owned().into_any(),
        Json::Number(n) => match (n.as_u64(), n.as_i64()) {
            (Some(u), _) => u.into_pyobject(py)?.into_any(),
            (None, Some(i)) => i.into_pyobject(py)?.into_any(),
            (None, None) => PyFloat::new(py, n.as_f64().unwrap_or(0.0)).into_any(),
        },
        Json::String(s) => PyString::new(py, s).into_any(),
        Json::Array(items) => {
            let list = PyList::empty(py);
            for item in items {
                list.append(json_to_py(py, item)?)?;
            }
            list.into_any()
        }
        Json::Object(map) => {
            let dict = PyDict::new(py);
            for (k, item) in map {
                dict.set_item(k, json_to_py(py, item)?)?;
            }
            dict.into_any()
        }
    })
}
