//! Conversions at the Python edge: Python values into the config's
//! `KEY=VALUE` assignments, and JSON (summaries, resolved configs) into
//! Python objects.

use pyo3::prelude::*;
use pyo3::types::{PyBool, PyDict, PyFloat, PyList, PyString};
use serde_json::Value as Json;

use crate::errors::key_error;
use crate::keys::{Bare, NORM_SUFFIX, doc_of, normalised_meaning};

/// A Python number as a float: an int (or anything with `__index__`,
/// such as numpy's integer types) stays an integer, anything else with
/// `__float__` (a numpy float) is a float; `None` for a value that is not
/// a number (bools are not numbers here).
/// numpy's `bool_` (named `bool` in numpy 2): a bool, not a number.
fn is_numpy_bool(value: &Bound<'_, PyAny>) -> PyResult<bool> {
    let name = value.get_type().name()?.to_string();
    Ok(!value.is_instance_of::<PyBool>() && (name == "bool" || name == "bool_"))
}

enum Number {
    Int(i64),
    Float(f64),
}

fn number(key: &str, value: &Bound<'_, PyAny>) -> PyResult<Option<Number>> {
    if value.is_instance_of::<PyBool>() || value.is_instance_of::<PyString>() {
        return Ok(None);
    }
    if is_numpy_bool(value)? {
        return Ok(None);
    }
    // __index__ of an array that is not an integer scalar raises: then it
    // is not an integer.
    if let Ok(index) = value.call_method0("__index__") {
        let n: i64 = index
            .extract()
            .map_err(|_| key_error(key, format!("{key}: integer {value} is out of range")))?;
        return Ok(Some(Number::Int(n)));
    }
    if value.is_instance_of::<PyFloat>() {
        return Ok(Some(Number::Float(value.extract()?)));
    }
    if let Ok(x) = value.call_method0("__float__").and_then(|f| f.extract::<f64>()) {
        return Ok(Some(Number::Float(x)));
    }
    Ok(None)
}

/// A number as a TOML literal. TOML spells these inf, -inf and nan; the
/// config then refuses a NaN naming the key, as it does for
/// `--set KEY=nan`.
fn number_literal(n: &Number) -> String {
    match *n {
        Number::Int(i) => i.to_string(),
        Number::Float(x) if x.is_nan() => "nan".to_string(),
        Number::Float(x) => format!("{x:?}"),
    }
}

/// The `KEY=TEXT` assignment (the CLI's `--set`) of a Python value to the
/// config key `section.name`, typed in Python as `typed` (a keyword or a
/// dict key; `norm` when it was the `_norm` spelling). The units rule of
/// the Python API ([`crate::keys`]) applies: a bare number where the
/// config would read it as a normalised value is refused unless the
/// `_norm` spelling was used, with a message saying how to write it.
pub fn assignment(typed: &str, section: &str, name: &str, norm: bool, value: &Bound<'_, PyAny>) -> PyResult<String> {
    let dotted = format!("{section}.{name}");
    let n = number(typed, value)?;
    let bare = doc_of(section, name).map(|d| d.bare);
    match (&n, norm) {
        (None, true) => {
            let type_name = value.get_type().name()?;
            return Err(key_error(
                &dotted,
                format!(
                    "{typed}: the {NORM_SUFFIX} spelling takes a number in normalised units, got {type_name}; a value with its unit is written {}=\"…\"",
                    typed.strip_suffix(NORM_SUFFIX).unwrap_or(typed)
                ),
            ));
        }
        (Some(n), false) if bare == Some(Bare::Normalised) => {
            let (unit, meaning) = normalised_meaning(section, name).unwrap_or(("", "normalised units"));
            let shown = number_literal(n);
            return Err(key_error(
                &dotted,
                format!(
                    "{typed}={shown}: a bare number is ambiguous here (the config reads it in {meaning}); give its unit, e.g. {typed}=\"{shown} {unit}\", or write the normalised value as {typed}{NORM_SUFFIX}={shown}"
                ),
            ));
        }
        _ => {}
    }
    Ok(format!("{dotted}={}", toml_literal(&dotted, value, n)?))
}

/// A Python value as the text of a TOML value, so that `KEY=TEXT` goes
/// through the CLI's own `--set` parser: a number or bool as its literal,
/// a string (a quantity with its unit, `"0.35 g"`, or a name) quoted. A
/// path-like value is its path as a string.
fn toml_literal(key: &str, value: &Bound<'_, PyAny>, n: Option<Number>) -> PyResult<String> {
    // bool before int: Python's bool is an int.
    if value.is_instance_of::<PyBool>() || is_numpy_bool(value)? {
        let b: bool = value.is_truthy()?;
        return Ok(b.to_string());
    }
    if let Some(n) = n {
        return Ok(number_literal(&n));
    }
    if value.is_instance_of::<PyString>() {
        let s: String = value.extract()?;
        return Ok(toml::Value::String(s).to_string());
    }
    if let Ok(path) = value.extract::<std::path::PathBuf>() {
        return Ok(toml::Value::String(path.display().to_string()).to_string());
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
