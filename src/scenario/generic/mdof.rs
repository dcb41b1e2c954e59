//! `kind = "mdof"`: a multi-degree-of-freedom model written in the scenario file, from elements (springs and
//! dampers between coordinates, the ground and base inputs) or from full matrices.
//!
//! # Format
//! * From elements: `coordinates = [{ name, unit, mass }]` (unit `m` with a mass in kg, or `rad` with an
//!   inertia in kg m²), `base_inputs = N`, `[[model.element]]` with `name`, `point` (weights of the
//!   coordinates), `to` (`"ground"`, `"base 0"`, … or a point array), `stiffness`, `damping`. An element
//!   whose point weights any length coordinate deflects a length (z + aφ: a is a lever arm in m/rad) and
//!   takes N/m and N s/m; one on angles alone takes N m/rad and N m s/rad.
//! * From matrices: `coordinates = [{ name, unit }]`, `base_inputs = N`, `mass_matrix`, `damping_matrix`,
//!   `stiffness_matrix` (n × n), `base_stiffness`, `base_damping` (n × N) as SI numbers:
//!   M q̈ + B q̇ + C q = K_u u + B_u u̇.
//! * Optional `forces = [[w₁, …, w_n], …]`: force inputs, each applied at a point (a force in N where the
//!   point weights a length, a torque in N m on angles alone), in either form: M q̈ + … = … + F f with the
//!   points as the columns of F. With one `[input]` process a model has base inputs or force inputs, not
//!   both (their spectra would need different units); with `[[input]]` tables
//!   ([`crate::scenario::inputs`]) it may have both, each table driving its own inputs.
//! * Outputs `[[model.output]]` with `name`, `quantity` (`displacement`, `velocity`, `acceleration` with
//!   `point`; `relative-displacement`, `relative-velocity` with `point` and `base` (the index of a base
//!   input): gᵀq − u_j, the matrix form's suspension travel; `deflection`, `spring-force`, `damper-force`,
//!   `element-force` with `element`).
//! * Optional `positions` (wheel positions along the track, with units) and `gains` of the inputs (base
//!   inputs first, then forces). Optional `tracks` (`"left"` or `"right"` per input) for a machine on two
//!   tracks: each wheel names its track and its position along it, and the scenario's `[[input]]` road
//!   drives them (any number of axles).

use super::io::track_layout;
use crate::error::{Error, Result};
use crate::fields::Fields;
use crate::models::ModelInstance;
use crate::system::mdof::MAX_MASS_CONDITION;
use crate::system::{Attach, Element, Mdof, Quantity};
use crate::units::Dim;
use nalgebra::DMatrix;
use std::sync::Arc;

/// Largest `base_inputs` accepted.
pub const MAX_BASE_INPUTS: usize = 10_000;

/// Indices of the smallest and largest mass, if any.
fn mass_range(masses: &[f64]) -> Option<(usize, usize)> {
    let lo = (0..masses.len()).min_by(|&a, &b| masses[a].total_cmp(&masses[b]))?;
    let hi = (0..masses.len()).max_by(|&a, &b| masses[a].total_cmp(&masses[b]))?;
    Some((lo, hi))
}

/// Builds the model of a `kind = "mdof"` `[model]` table (see the module docs) for a scenario with one
/// `[input]`.
///
/// # Errors
/// [`Error::File`] naming the key, value and reason.
pub fn from_fields(f: &Fields) -> Result<ModelInstance> {
    from_fields_in(f, false)
}

/// Builds the model of a `kind = "mdof"` `[model]` table; `several_inputs`: the scenario has `[[input]]`
/// tables, so base inputs and forces may be mixed (each table drives its own inputs, in its own unit).
///
/// # Errors
/// [`Error::File`] naming the key, value and reason.
pub fn from_fields_in(f: &Fields, several_inputs: bool) -> Result<ModelInstance> {
    let matrix_form = f.get("mass_matrix").is_some();
    let cv = f.require("coordinates")?;
    let carr = cv
        .as_array()
        .ok_or_else(|| f.error("coordinates", cv, "expected an array of { name, unit, mass }"))?;
    let mut coords = Vec::new();
    let mut masses = Vec::new();
    for (i, c) in carr.iter().enumerate() {
        let key = format!("coordinates[{i}]");
        let t = c
            .as_table()
            .ok_or_else(|| f.error(&key, c, "expected { name, unit, mass }"))?;
        let cf = Fields::new(f.file(), &f.path(&key), t);
        let name = cf.string("name")?.to_string();
        let unit = cf.opt_string("unit")?.unwrap_or("m").to_string();
        let mass_dim = match unit.as_str() {
            "m" => Dim::MASS,
            "rad" => Dim::INERTIA,
            other => {
                return Err(cf.error(
                    "unit",
                    other,
                    "coordinate units are \"m\" (mass in kg) or \"rad\" (inertia in kg m^2)",
                ))
            }
        };
        // with full matrices (`mass_matrix` …) the coordinates carry no mass of their own
        if !matrix_form {
            let m = cf.quantity("mass", mass_dim)?;
            if m <= 0.0 {
                return Err(cf.error(
                    "mass",
                    cf.get("mass").map_or("?".into(), |v| v.to_string()),
                    "must be > 0",
                ));
            }
            masses.push(m);
        }
        cf.finish()?;
        coords.push((name, unit));
    }
    let n = coords.len();
    if let Some((lo, hi)) = mass_range(&masses)
        && masses[hi] / masses[lo] > MAX_MASS_CONDITION
    {
        return Err(f.error(
                &format!("coordinates[{hi}].mass"),
                crate::numbers::num(masses[hi]),
                format!(
                    "{:.1e} times the mass of `{}`: double precision cannot resolve masses more than {MAX_MASS_CONDITION:.0e} \
                     apart (check the units)",
                    masses[hi] / masses[lo],
                    coords[lo].0
                ),
            ));
    }
    let n_base = match f.get("base_inputs") {
        None => 0,
        Some(v) => v
            .as_integer()
            .filter(|k| (0..=MAX_BASE_INPUTS as i64).contains(k))
            .ok_or_else(|| {
                f.error(
                    "base_inputs",
                    v,
                    format!("expected a count from 0 to {MAX_BASE_INPUTS}"),
                )
            })? as usize,
    };
    let point = |key: &str, v: &toml::Value, ff: &Fields| coordinate_weights(ff, key, v, n);
    let mut elements = Vec::new();
    if let Some(ev) = f.get("element") {
        let earr = ev
            .as_array()
            .ok_or_else(|| f.error("element", ev, "expected [[model.element]] tables"))?;
        for (i, e) in earr.iter().enumerate() {
            let key = format!("element[{i}]");
            let t = e.as_table().ok_or_else(|| f.error(&key, e, "expected a table"))?;
            let ef = Fields::new(f.file(), &f.path(&key), t);
            let name = ef.string("name")?.to_string();
            let p = point("point", ef.require("point")?, &ef)?;
            // the same rule as the output units (Mdof::with_output): a point weighting a length is a length
            // (an angle's weight is then a lever arm in m/rad), a point of angles alone is an angle
            let rot = p.iter().any(|w| *w != 0.0) && p.iter().zip(&coords).all(|(w, c)| *w == 0.0 || c.1 == "rad");
            let (kd, bd) = if rot {
                (Dim::TORQUE, Dim::new(2, 1, -1))
            } else {
                (Dim::STIFFNESS, Dim::DAMPING)
            };
            let to = attachment(&ef, n, n_base)?;
            let stiffness = ef.opt_quantity("stiffness", kd)?.unwrap_or(0.0);
            let damping = ef.opt_quantity("damping", bd)?.unwrap_or(0.0);
            for (k, v) in [("stiffness", stiffness), ("damping", damping)] {
                if v < 0.0 {
                    return Err(ef.error(k, ef.get(k).map_or("?".into(), |x| x.to_string()), "must be >= 0"));
                }
            }
            ef.finish()?;
            elements.push(Element {
                name,
                point: p,
                to,
                stiffness,
                damping,
            });
        }
    }
    let forces: Vec<Vec<f64>> = match f.get("forces") {
        None => Vec::new(),
        Some(v) => {
            let arr = v
                .as_array()
                .ok_or_else(|| f.error("forces", v, "expected an array of points (coordinate weights)"))?;
            arr.iter()
                .enumerate()
                .map(|(i, p)| point(&format!("forces[{i}]"), p, f))
                .collect::<Result<_>>()?
        }
    };
    if n_base > 0 && !forces.is_empty() && !several_inputs {
        return Err(f.error(
            "forces",
            forces.len(),
            format!(
                "the model has {n_base} base inputs as well: one [input] process cannot drive both base \
                 displacements (m) and forces (N); write [[input]] tables, one per source, each naming the \
                 inputs it drives"
            ),
        ));
    }
    if matrix_form && !elements.is_empty() {
        return Err(f.error(
            "element",
            "[[model.element]]",
            "give either elements with coordinate masses, or full matrices (mass_matrix, …), not both",
        ));
    }
    let names: Vec<String> = elements.iter().map(|e| e.name.clone()).collect();
    let cref: Vec<(&str, &str)> = coords.iter().map(|(a, b)| (a.as_str(), b.as_str())).collect();
    let mut model = if matrix_form {
        // M q̈ + B q̇ + C q = K_u u + B_u u̇, SI numbers, n × n and n × base_inputs
        let sq = |key: &str, cols: usize| -> Result<DMatrix<f64>> {
            let m = match f.get(key) {
                Some(_) => f.matrix(key)?,
                None => DMatrix::zeros(n, cols),
            };
            if m.nrows() != n || m.ncols() != cols {
                return Err(f.error(
                    key,
                    format!("{}x{}", m.nrows(), m.ncols()),
                    format!("must be {n}x{cols}"),
                ));
            }
            Ok(m)
        };
        Mdof::new(
            &cref,
            sq("mass_matrix", n)?,
            sq("damping_matrix", n)?,
            sq("stiffness_matrix", n)?,
            sq("base_stiffness", n_base)?,
            sq("base_damping", n_base)?,
            DMatrix::from_fn(n, forces.len(), |i, j| forces[j][i]),
        )
        .map_err(|e| {
            let key = match &e {
                Error::InvalidParameter { name, .. } => match name.as_str() {
                    "B" => "damping_matrix",
                    "C" => "stiffness_matrix",
                    "K_u" => "base_stiffness",
                    "F" => "forces",
                    "B_u" => "base_damping",
                    _ => "mass_matrix",
                },
                _ => "mass_matrix",
            };
            f.wrap(key, e)
        })?
    } else {
        Mdof::from_elements(&cref, &masses, elements, n_base, &forces).map_err(|e| f.wrap("coordinates", e))?
    };
    let ov = f.require("output")?;
    let oarr = ov
        .as_array()
        .ok_or_else(|| f.error("output", ov, "expected [[model.output]] tables"))?;
    for (i, o) in oarr.iter().enumerate() {
        let key = format!("output[{i}]");
        let t = o.as_table().ok_or_else(|| f.error(&key, o, "expected a table"))?;
        let of = Fields::new(f.file(), &f.path(&key), t);
        let name = of.string("name")?.to_string();
        let q = of.string("quantity")?;
        let element = |of: &Fields| -> Result<usize> {
            let e = of.string("element")?;
            names
                .iter()
                .position(|x| x == e)
                .ok_or_else(|| of.error("element", e, format!("no such element; known: {}", names.join(", "))))
        };
        let quantity = match q {
            "displacement" => Quantity::Displacement(point("point", of.require("point")?, &of)?),
            "velocity" => Quantity::Velocity(point("point", of.require("point")?, &of)?),
            "acceleration" => Quantity::Acceleration(point("point", of.require("point")?, &of)?),
            "relative-displacement" | "relative-velocity" => {
                let point = point("point", of.require("point")?, &of)?;
                let bv = of.require("base")?;
                let base = bv
                    .as_integer()
                    .filter(|j| (0..n_base as i64).contains(j))
                    .ok_or_else(|| of.error("base", bv, format!("expected the index of a base input (0 to {})", n_base as i64 - 1)))?
                    as usize;
                if q == "relative-displacement" {
                    Quantity::RelativeDisplacement { point, base }
                } else {
                    Quantity::RelativeVelocity { point, base }
                }
            }
            "deflection" => Quantity::Deflection(element(&of)?),
            "spring-force" => Quantity::SpringForce(element(&of)?),
            "damper-force" => Quantity::DamperForce(element(&of)?),
            "element-force" => Quantity::ElementForce(element(&of)?),
            other => return Err(of.error("quantity", other, "expected displacement, velocity, acceleration, relative-displacement, relative-velocity, deflection, spring-force, damper-force or element-force")),
        };
        of.finish()?;
        model = model.with_output(&name, quantity).map_err(|e| f.wrap("output", e))?;
    }
    if n_base + forces.len() == 0 {
        // the count as written, or `<missing>` when the file has no `base_inputs` (its default is 0)
        let written = f.get("base_inputs").map_or("<missing>".to_string(), |v| v.to_string());
        return Err(f.error(
            "base_inputs",
            written,
            "a generic mdof scenario needs at least one input: base_inputs > 0 or forces",
        ));
    }
    let layout = track_layout(f, n_base + forces.len())?;
    Ok(ModelInstance {
        system: Arc::new(model),
        layout,
        description: format!("MDOF model, {n} coordinates"),
    })
}

/// The weights of the `n` coordinates under `key` (a point, or an element's far end).
///
/// # Errors
/// [`Error::File`](crate::Error::File) naming the key and value: not an array of `n` finite numbers.
pub(crate) fn coordinate_weights(ff: &Fields, key: &str, v: &toml::Value, n: usize) -> Result<Vec<f64>> {
    let arr = v
        .as_array()
        .ok_or_else(|| ff.error(key, v, format!("expected {n} weights of the coordinates")))?;
    if arr.len() != n {
        return Err(ff.error(key, v, format!("expected {n} weights (one per coordinate)")));
    }
    arr.iter()
        .enumerate()
        .map(|(j, x)| {
            x.as_float()
                .or_else(|| x.as_integer().map(|k| k as f64))
                .filter(|w| w.is_finite())
                .ok_or_else(|| ff.error(&format!("{key}[{j}]"), x, "expected a finite number"))
        })
        .collect()
}

/// The far end of an element, key `to`: `"ground"`, `"base <j>"` or a point (weights of the `n` coordinates).
///
/// # Errors
/// [`Error::File`](crate::Error::File) naming `to` and its value: missing, malformed, or a base input the
/// model does not have.
pub(crate) fn attachment(ef: &Fields, n: usize, n_base: usize) -> Result<Attach> {
    Ok(match ef.require("to")? {
        toml::Value::String(s) if s == "ground" => Attach::Ground,
        toml::Value::String(s) if s.starts_with("base") => {
            let j: usize = s[4..]
                .trim()
                .parse()
                .map_err(|_| ef.error("to", s, "expected \"base <index>\""))?;
            if j >= n_base {
                return Err(ef.error("to", s, format!("only {n_base} base inputs (set model.base_inputs)")));
            }
            Attach::Base(j)
        }
        v @ toml::Value::Array(_) => Attach::Point(coordinate_weights(ef, "to", v, n)?),
        v => return Err(ef.error("to", v, "expected \"ground\", \"base <j>\" or a point array")),
    })
}
