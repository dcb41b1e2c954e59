//! Quantities as Python arguments: a number (SI, in the parameter's unit) or a string with a unit
//! ("10.8 km/h", "70 kN/m"), checked against the parameter's dimension by the library's unit parser.
//! A bad unit raises `UnitError` naming the parameter; anything else that is not a quantity raises
//! `InvalidInputError`.

use crate::errors::{invalid_input, unit_error};
use pyo3::prelude::*;
use pyo3::types::{PyBool, PyString};
use stochvib::units::{parse_as, parse_sample_rate, unit_dim};
use stochvib::Error;

/// The value of `obj` in the SI unit `unit` (e.g. "m/s"): a real number as it is, a string parsed with
/// its unit.
///
/// # Errors
/// `UnitError` naming `name` for a string whose unit is unknown or of another dimension;
/// `InvalidInputError` for anything that is neither a number nor a string (booleans included).
pub fn quantity(py: Python<'_>, obj: &Bound<'_, PyAny>, name: &str, unit: &str) -> PyResult<f64> {
    read(py, obj, name, unit, |text| {
        let dim = unit_dim(unit).ok_or_else(|| Error::invalid(name, unit, "not a coherent SI unit"))?;
        parse_as(text, dim)
    })
}

/// A sample rate (samples per second): a real number as it is (Hz), a string parsed by the library's
/// sample-rate reading ("200 Hz", "200 1/s", "200 S/s" are 200; [`parse_sample_rate`]).
///
/// # Errors
/// As [`quantity`].
pub fn sample_rate(py: Python<'_>, obj: &Bound<'_, PyAny>, name: &str) -> PyResult<f64> {
    read(py, obj, name, "Hz", parse_sample_rate)
}

/// A number as it is, a string through `parse`; `UnitError` naming `name` for a bad string.
fn read(
    py: Python<'_>,
    obj: &Bound<'_, PyAny>,
    name: &str,
    unit: &str,
    parse: impl FnOnce(&str) -> stochvib::Result<f64>,
) -> PyResult<f64> {
    if obj.is_instance_of::<PyString>() {
        let text: String = obj.extract()?;
        return parse(&text).map_err(|e| match e {
            Error::Unit { reason, .. } => unit_error(py, name, &text, &format!("{reason} ({name} is in {unit})")),
            other => crate::errors::lib_error(py, &other),
        });
    }
    if !obj.is_instance_of::<PyBool>() {
        if let Ok(x) = obj.extract::<f64>() {
            return Ok(x);
        }
    }
    Err(invalid_input(
        py,
        format!(
            "`{name}` = {}: expected a number (SI, in {unit}) or a string with a unit, e.g. \"10 {unit}\"",
            obj.repr()?
        ),
    ))
}

/// As [`quantity`] for an optional argument (None stays None).
pub fn optional(py: Python<'_>, obj: Option<&Bound<'_, PyAny>>, name: &str, unit: &str) -> PyResult<Option<f64>> {
    match obj {
        Some(o) if !o.is_none() => quantity(py, o, name, unit).map(Some),
        _ => Ok(None),
    }
}

/// A sequence of quantities (a list, a tuple or a 1-D array), each a number or a string with a unit.
///
/// # Errors
/// As [`quantity`], naming the element (`positions[2]`).
pub fn sequence(py: Python<'_>, obj: &Bound<'_, PyAny>, name: &str, unit: &str) -> PyResult<Vec<f64>> {
    if obj.is_instance_of::<PyString>() {
        return Err(invalid_input(
            py,
            format!("`{name}`: expected a sequence of quantities, got one string"),
        ));
    }
    let it = obj
        .try_iter()
        .map_err(|_| invalid_input(py, format!("`{name}`: expected a sequence of quantities")))?;
    it.enumerate()
        .map(|(i, x)| quantity(py, &x?, &format!("{name}[{i}]"), unit))
        .collect()
}
