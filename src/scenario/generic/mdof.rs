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
/// tables, so base inputs and forces may be mixed (each table drives its own inputs, in its own unit). The
/// keys are those of the tables of [`super::mdof_keys`].
///
/// # Errors
/// [`Error::File`] naming the key, value and reason.
pub fn from_fields_in(f: &Fields, several_inputs: bool) -> Result<ModelInstance> {
    let matrix_form = f.get("mass_matrix").is_some();
    let (coords, masses) = coordinates(f, matrix_form)?;
    let n = coords.len();
    let n_base = base_inputs(f)?;
    let elements = elements(f, &coords, n_base)?;
    let forces: Vec<Vec<f64>> = match f.get("forces") {
        None => Vec::new(),
        Some(v) => {
            let arr = v
                .as_array()
                .ok_or_else(|| f.error("forces", v, "expected an array of points (coordinate weights)"))?;
            arr.iter()
                .enumerate()
                .map(|(i, p)| coordinate_weights(f, &format!("forces[{i}]"), p, n))
                .collect::<Result<_>>()?
        }
    };
    check_form(f, n_base, &forces, several_inputs, matrix_form && !elements.is_empty())?;
    let names: Vec<String> = elements.iter().map(|e| e.name.clone()).collect();
    let cref: Vec<(&str, &str)> = coords.iter().map(|(a, b)| (a.as_str(), b.as_str())).collect();
    let mut model = if matrix_form {
        matrix_model(f, &cref, n_base, &forces)?
    } else {
        Mdof::from_elements(&cref, &masses, elements, n_base, &forces).map_err(|e| f.wrap("coordinates", e))?
    };
    let ov = f.require("output")?;
    let oarr = ov
        .as_array()
        .ok_or_else(|| f.error("output", ov, "expected [[model.output]] tables"))?;
    let (mut out_names, mut quantities) = (Vec::with_capacity(oarr.len()), Vec::with_capacity(oarr.len()));
    for (i, o) in oarr.iter().enumerate() {
        let key = format!("output[{i}]");
        let t = o.as_table().ok_or_else(|| f.error(&key, o, "expected a table"))?;
        let of = Fields::new(f.file(), &f.path(&key), t);
        let name = of.string("name")?.to_string();
        let quantity = output_quantity(&of, n, n_base, &names)?;
        super::mdof_keys::OUTPUT.finish(&of, &[])?;
        out_names.push(name);
        quantities.push(quantity);
    }
    // all outputs at once: the state space is written once, not once per output (a scheduled model is
    // rebuilt at every time of a transient's exact route)
    let outputs = out_names.iter().map(String::as_str).zip(quantities).collect();
    model = model.with_outputs(outputs).map_err(|e| f.wrap("output", e))?;
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

/// The (name, unit) of each coordinate, and the masses of the element form (kg or kg m²; none with matrices).
type Coordinates = (Vec<(String, String)>, Vec<f64>);

/// `coordinates`: the (name, unit) of each coordinate and, in the element form, its mass (kg or kg m²).
fn coordinates(f: &Fields, matrix_form: bool) -> Result<Coordinates> {
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
        let (name, unit, mass) = coordinate(&cf, matrix_form)?;
        masses.extend(mass);
        coords.push((name, unit));
    }
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
    Ok((coords, masses))
}

/// One coordinate `{ name, unit, mass }`: its name, unit and (in the element form) mass.
fn coordinate(cf: &Fields, matrix_form: bool) -> Result<(String, String, Option<f64>)> {
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
    let mut mass = None;
    if !matrix_form {
        let m = cf.quantity("mass", mass_dim)?;
        if m <= 0.0 {
            return Err(cf.error(
                "mass",
                cf.get("mass").map_or("?".into(), |v| v.to_string()),
                "must be > 0",
            ));
        }
        mass = Some(m);
    }
    super::mdof_keys::COORDINATE.finish(cf, &[])?;
    Ok((name, unit, mass))
}

/// `base_inputs` (default 0).
fn base_inputs(f: &Fields) -> Result<usize> {
    let Some(v) = f.get("base_inputs") else {
        return Ok(0);
    };
    let n = v
        .as_integer()
        .filter(|k| (0..=MAX_BASE_INPUTS as i64).contains(k))
        .ok_or_else(|| {
            f.error(
                "base_inputs",
                v,
                format!("expected a count from 0 to {MAX_BASE_INPUTS}"),
            )
        })?;
    Ok(n as usize)
}

/// The `[[model.element]]` tables, between points of the coordinates `coords` and their far ends.
fn elements(f: &Fields, coords: &[(String, String)], n_base: usize) -> Result<Vec<Element>> {
    let Some(ev) = f.get("element") else {
        return Ok(Vec::new());
    };
    let earr = ev
        .as_array()
        .ok_or_else(|| f.error("element", ev, "expected [[model.element]] tables"))?;
    let mut elements = Vec::new();
    for (i, e) in earr.iter().enumerate() {
        let key = format!("element[{i}]");
        let t = e.as_table().ok_or_else(|| f.error(&key, e, "expected a table"))?;
        let ef = Fields::new(f.file(), &f.path(&key), t);
        elements.push(element(&ef, coords, n_base)?);
    }
    Ok(elements)
}

/// One `[[model.element]]` table.
fn element(ef: &Fields, coords: &[(String, String)], n_base: usize) -> Result<Element> {
    let n = coords.len();
    let name = ef.string("name")?.to_string();
    let p = coordinate_weights(ef, "point", ef.require("point")?, n)?;
    // the same rule as the output units (Mdof::with_output): a point weighting a length is a length
    // (an angle's weight is then a lever arm in m/rad), a point of angles alone is an angle
    let rot = p.iter().any(|w| *w != 0.0) && p.iter().zip(coords).all(|(w, c)| *w == 0.0 || c.1 == "rad");
    let (kd, bd) = if rot {
        (Dim::TORQUE, Dim::new(2, 1, -1))
    } else {
        (Dim::STIFFNESS, Dim::DAMPING)
    };
    let to = attachment(ef, n, n_base)?;
    let stiffness = ef.opt_quantity("stiffness", kd)?.unwrap_or(0.0);
    let damping = ef.opt_quantity("damping", bd)?.unwrap_or(0.0);
    for (k, v) in [("stiffness", stiffness), ("damping", damping)] {
        if v < 0.0 {
            return Err(ef.error(k, ef.get(k).map_or("?".into(), |x| x.to_string()), "must be >= 0"));
        }
    }
    super::mdof_keys::ELEMENT.finish(ef, &[])?;
    Ok(Element {
        name,
        point: p,
        to,
        stiffness,
        damping,
    })
}

/// Refuses base inputs with forces under one `[input]` process (not `several_inputs`), and elements in the
/// matrix form (`elements_with_matrices`).
fn check_form(
    f: &Fields,
    n_base: usize,
    forces: &[Vec<f64>],
    several_inputs: bool,
    elements_with_matrices: bool,
) -> Result<()> {
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
    if elements_with_matrices {
        return Err(f.error(
            "element",
            "[[model.element]]",
            "give either elements with coordinate masses, or full matrices (mass_matrix, …), not both",
        ));
    }
    Ok(())
}

/// The matrix form M q̈ + B q̇ + C q = K_u u + B_u u̇ + F f: SI numbers, n × n and n × base_inputs.
fn matrix_model(f: &Fields, cref: &[(&str, &str)], n_base: usize, forces: &[Vec<f64>]) -> Result<Mdof> {
    let n = cref.len();
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
        cref,
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
    })
}

/// The `quantity` of one `[[model.output]]` table and the keys it takes (`point`, `base`, `element`) for a
/// model of `n` coordinates, `n_base` base inputs and the elements `names`.
fn output_quantity(of: &Fields, n: usize, n_base: usize, names: &[String]) -> Result<Quantity> {
    let q = of.string("quantity")?;
    let point = || coordinate_weights(of, "point", of.require("point")?, n);
    let element = || -> Result<usize> {
        let e = of.string("element")?;
        names
            .iter()
            .position(|x| x == e)
            .ok_or_else(|| of.error("element", e, format!("no such element; known: {}", names.join(", "))))
    };
    Ok(match q {
        "displacement" => Quantity::Displacement(point()?),
        "velocity" => Quantity::Velocity(point()?),
        "acceleration" => Quantity::Acceleration(point()?),
        "relative-displacement" | "relative-velocity" => {
            let point = point()?;
            let bv = of.require("base")?;
            let last = n_base as i64 - 1;
            let base = bv
                .as_integer()
                .filter(|j| (0..n_base as i64).contains(j))
                .ok_or_else(|| of.error("base", bv, format!("expected the index of a base input (0 to {last})")))?
                as usize;
            if q == "relative-displacement" {
                Quantity::RelativeDisplacement { point, base }
            } else {
                Quantity::RelativeVelocity { point, base }
            }
        }
        "deflection" => Quantity::Deflection(element()?),
        "spring-force" => Quantity::SpringForce(element()?),
        "damper-force" => Quantity::DamperForce(element()?),
        "element-force" => Quantity::ElementForce(element()?),
        other => return Err(of.error("quantity", other, OUTPUT_QUANTITIES)),
    })
}

/// The error of an unknown output `quantity`.
const OUTPUT_QUANTITIES: &str = "expected displacement, velocity, acceleration, relative-displacement, \
                                 relative-velocity, deflection, spring-force, damper-force or element-force";

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
