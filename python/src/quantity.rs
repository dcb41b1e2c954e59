//! Quantities as Python arguments: a number (SI, in the parameter's unit) or a string with a unit
//! ("10.8 km/h", "70 kN/m"), checked against the parameter's dimension by the library's unit parser.
//! A bad unit raises `UnitError` naming the parameter; anything else that is not a quantity raises
//! `InvalidInputError`.

use crate::errors::{invalid_input, unit_error};
use pyo3::prelude::*;
use pyo3::types::{PyBool, PyString};
use std::f64::consts::PI;
use stochvib::units::{parse_as, parse_quantity, parse_sample_rate, unit_dim, Dim};
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

/// The value of `obj` as a quantity of dimension `dim` (SI): a number as it is, a string parsed with its unit
/// and checked against `dim`.
///
/// # Errors
/// As [`quantity`]; the message names the expected dimension.
pub fn of_dim(py: Python<'_>, obj: &Bound<'_, PyAny>, name: &str, dim: Dim) -> PyResult<f64> {
    read(py, obj, name, &dim_text(dim), |text| parse_as(text, dim))
}

/// A quantity of dimension `dim` whose unit may name no angle: a decay rate (α of e^{−α|τ|}), a density
/// level (per Hz or per rad/s is said by a `convention`, never by a unit). `Hz`, `rad`, `cycles` and `deg`
/// would scale the value by 2π or π/180 (a frequency's SI value is angular), so a string naming one is
/// refused with `why` (what to write instead).
///
/// # Errors
/// As [`of_dim`], and `UnitError` naming `name` for a unit with an angle.
pub fn without_angle(py: Python<'_>, obj: &Bound<'_, PyAny>, name: &str, dim: Dim, why: &str) -> PyResult<f64> {
    read(py, obj, name, &dim_text(dim), |text| {
        let angle = text
            .split(|c: char| !c.is_alphanumeric())
            .any(|t| t.ends_with("Hz") || t.ends_with("rad") || ["cycle", "cycles", "deg"].contains(&t));
        if angle {
            return Err(Error::Unit {
                text: text.to_string(),
                reason: format!("{why}; expected dimension {}", dim_text(dim)),
            });
        }
        parse_as(text, dim)
    })
}

/// A frequency of dimension `inv_lag` (s⁻¹ or m⁻¹): a number as it is (Hz or cycles/m when `cyclic`, rad/s
/// or rad/m otherwise), a string parsed angularly ("1 Hz" is 2π rad/s, "1 1/s" is 1 rad/s) and divided by 2π
/// when `cyclic`.
///
/// # Errors
/// As [`of_dim`].
pub fn frequency(py: Python<'_>, obj: &Bound<'_, PyAny>, name: &str, inv_lag: Dim, cyclic: bool) -> PyResult<f64> {
    let unit = match (cyclic, inv_lag == Dim::FREQUENCY) {
        (true, true) => "Hz",
        (true, false) => "cycles/m",
        (false, true) => "rad/s",
        (false, false) => "rad/m",
    };
    let scale = if cyclic { 2.0 * PI } else { 1.0 };
    read(py, obj, name, unit, |text| parse_as(text, inv_lag).map(|w| w / scale))
}

/// A pair of [`frequency`] values (a band), named `name[0]`, `name[1]`.
///
/// # Errors
/// As [`frequency`], and `InvalidInputError` for anything but two elements.
pub fn frequency_pair(
    py: Python<'_>,
    obj: &Bound<'_, PyAny>,
    name: &str,
    inv_lag: Dim,
    cyclic: bool,
) -> PyResult<(f64, f64)> {
    let items: Vec<Bound<'_, PyAny>> = if obj.is_instance_of::<PyString>() {
        Vec::new()
    } else {
        obj.try_iter()
            .map_or_else(|_| Ok(Vec::new()), |it| it.collect::<PyResult<_>>())?
    };
    let [lo, hi] = items.as_slice() else {
        return Err(invalid_input(
            py,
            format!("`{name}`: expected a pair (low, high) of frequencies"),
        ));
    };
    let at = |x: &Bound<'_, PyAny>, i: usize| frequency(py, x, &format!("{name}[{i}]"), inv_lag, cyclic);
    Ok((at(lo, 0)?, at(hi, 1)?))
}

/// A stress-like quantity in the (possibly non-SI) unit `unit` raised to `power` (`"MPa"`, 3 for the C of
/// N·S^3 = C in MPa³): a number as it is, a string converted into that unit. `power` must be an integer for
/// a string (a unit's power is).
///
/// # Errors
/// `UnitError` naming `name` for a bad string, a `unit` that is no unit, or a non-integer `power`.
pub fn in_unit_power(py: Python<'_>, obj: &Bound<'_, PyAny>, name: &str, unit: &str, power: f64) -> PyResult<f64> {
    let shown = if power == 1.0 {
        unit.to_string()
    } else {
        format!("{unit}^{power}")
    };
    read(py, obj, name, &shown, |text| {
        let refuse = |reason: String| Error::Unit {
            text: text.to_string(),
            reason,
        };
        let (scale, dim) = parse_quantity(&format!("1 {unit}"))
            .map_err(|e| refuse(format!("the unit `{unit}` of the values is no unit: {e}")))?;
        if power.fract() != 0.0 || power.abs() > 16.0 {
            return Err(refuse(format!(
                "a string needs an integer exponent k (here {power}): give the number in {unit}^k"
            )));
        }
        let k = power as i32;
        let exp = |e: i8| i8::try_from(i32::from(e) * k).map_err(|_| refuse(format!("{unit}^{k} is out of range")));
        let want = Dim::new(exp(dim.m)?, exp(dim.kg)?, exp(dim.s)?);
        parse_as(text, want).map(|v| v / scale.powi(k))
    })
}

/// A dimension as a unit text: `m^2`, `s^-1`, `1` for a pure number.
pub fn dim_text(dim: Dim) -> String {
    if dim == Dim::DIMENSIONLESS {
        "1".to_string()
    } else {
        dim.to_string()
    }
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
    sequence_with(py, obj, name, |x, at| quantity(py, x, at, unit))
}

/// As [`sequence`], each element a quantity of dimension `dim` ([`of_dim`]).
///
/// # Errors
/// As [`of_dim`], naming the element.
pub fn sequence_of_dim(py: Python<'_>, obj: &Bound<'_, PyAny>, name: &str, dim: Dim) -> PyResult<Vec<f64>> {
    sequence_with(py, obj, name, |x, at| of_dim(py, x, at, dim))
}

/// The elements of the sequence `obj` read by `one(element, "name[i]")`.
fn sequence_with(
    py: Python<'_>,
    obj: &Bound<'_, PyAny>,
    name: &str,
    one: impl Fn(&Bound<'_, PyAny>, &str) -> PyResult<f64>,
) -> PyResult<Vec<f64>> {
    if obj.is_instance_of::<PyString>() {
        return Err(invalid_input(
            py,
            format!("`{name}`: expected a sequence of quantities, got one string"),
        ));
    }
    let it = obj
        .try_iter()
        .map_err(|_| invalid_input(py, format!("`{name}`: expected a sequence of quantities")))?;
    it.enumerate().map(|(i, x)| one(&x?, &format!("{name}[{i}]"))).collect()
}
