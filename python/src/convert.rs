//! Values between Python and the library's data formats: serialisable reports to Python objects (through
//! JSON, so that every field the library adds to a report appears in Python without a change here), and
//! Python keyword arguments to a TOML table (so that the catalogue models are built by the library's own
//! file reader, with its units and its error messages).

use crate::errors::invalid_input;
use pyo3::prelude::*;
use pyo3::sync::PyOnceLock;
use pyo3::types::{PyBool, PyDict, PyFloat, PyInt, PyList, PyString, PyTuple};

static JSON_LOADS: PyOnceLock<Py<PyAny>> = PyOnceLock::new();

/// Any serialisable value as Python objects (dicts, lists, floats, ints, strings, None), via `json.loads`.
///
/// Non-finite floats become `NaN`/`Infinity` in the JSON text, which Python's `json` reads back as floats.
pub fn to_python<'py, T: serde::Serialize>(py: Python<'py>, value: &T) -> PyResult<Bound<'py, PyAny>> {
    let text = serde_json::to_string(value)
        .map_err(|e| pyo3::exceptions::PyRuntimeError::new_err(format!("serialising a report: {e}")))?;
    let loads = JSON_LOADS.get_or_try_init(py, || Ok::<_, PyErr>(py.import("json")?.getattr("loads")?.unbind()))?;
    loads.bind(py).call1((text,))
}

/// A Python value as a TOML value: bool, int, float, str, list/tuple, dict (nested tables), numpy scalars and
/// arrays (through `tolist()`).
///
/// # Errors
/// `InvalidInputError` naming `key` for anything else (None included: TOML has no null).
pub fn toml_value(py: Python<'_>, key: &str, v: &Bound<'_, PyAny>) -> PyResult<toml::Value> {
    if v.is_instance_of::<PyBool>() {
        return Ok(toml::Value::Boolean(v.extract()?));
    }
    if v.is_instance_of::<PyInt>() {
        return Ok(toml::Value::Integer(v.extract()?));
    }
    if v.is_instance_of::<PyFloat>() {
        return Ok(toml::Value::Float(v.extract()?));
    }
    if v.is_instance_of::<PyString>() {
        return Ok(toml::Value::String(v.extract()?));
    }
    if v.is_instance_of::<PyList>() || v.is_instance_of::<PyTuple>() {
        let mut arr = Vec::new();
        for (i, x) in v.try_iter()?.enumerate() {
            arr.push(toml_value(py, &format!("{key}[{i}]"), &x?)?);
        }
        return Ok(toml::Value::Array(arr));
    }
    if let Ok(d) = v.cast::<PyDict>() {
        return Ok(toml::Value::Table(toml_table(py, key, d)?));
    }
    if v.hasattr("tolist")? {
        // numpy scalars and arrays
        return toml_value(py, key, &v.call_method0("tolist")?);
    }
    Err(invalid_input(
        py,
        format!(
            "`{key}` = {}: expected a number, a string with a unit (\"70 kN/m\"), a bool, a list or a dict",
            v.repr()?
        ),
    ))
}

/// A dict of Python values as a TOML table (keys must be strings).
pub fn toml_table(py: Python<'_>, prefix: &str, d: &Bound<'_, PyDict>) -> PyResult<toml::Table> {
    let mut t = toml::Table::new();
    for (k, v) in d.iter() {
        let k: String = k
            .extract()
            .map_err(|_| invalid_input(py, format!("`{prefix}`: keys must be strings")))?;
        let full = if prefix.is_empty() {
            k.clone()
        } else {
            format!("{prefix}.{k}")
        };
        t.insert(k, toml_value(py, &full, &v)?);
    }
    Ok(t)
}
