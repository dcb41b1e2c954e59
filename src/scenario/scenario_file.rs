//! Scenario files (`data/*.toml`): a model, its random input and what to report.
//!
//! # Format
//! ```toml
//! title = "Quarter car on an ISO class C road"
//! source = "illustrative"
//!
//! [model]
//! kind = "mdof"                  # mdof | transfer-function | state-space | a catalogue model kind
//! ...                            # the model's keys (see below and the catalogue models' docs)
//!
//! [input]
//! spectrum = "iso8608-c"         # a catalogue name in spectra/, a path, or an inline table of spectrum keys
//! speed = "20 m/s"               # needed for spatial spectra and for delays between wheels
//! mean = 0.0                     # mean of the input process (default 0)
//!
//! [analysis]                     # optional
//! outputs = ["body", "travel"]   # default: every output
//! band = ["0.5 Hz", "80 Hz"]     # also report the band-limited σ
//! duration = "1 h"               # for exceedance probabilities and expected largest peaks (default 1 h)
//! [analysis.levels]              # optional levels per output for Rice crossing rates
//! travel = ["5 cm", "8 cm"]
//! ```
//!
//! Generic models:
//! * `kind = "mdof"` with full matrices: `coordinates = [{ name, unit }]`, `base_inputs = N`,
//!   `mass_matrix`, `damping_matrix`, `stiffness_matrix` (n × n), `base_stiffness`, `base_damping`
//!   (n × N) as SI numbers (M q̈ + B q̇ + C q = K_u u + B_u u̇); outputs `displacement`, `velocity`,
//!   `acceleration` of a point.
//! * `kind = "mdof"` from elements: `coordinates = [{ name, unit, mass }]`, `base_inputs = N`, `[[model.element]]` with
//!   `name`, `point` (weights of the coordinates), `to` (`"ground"`, `"base 0"`, … or a point array),
//!   `stiffness`, `damping`; `[[model.output]]` with `name`, `quantity` (`displacement`, `velocity`,
//!   `acceleration` with `point`; `deflection`, `spring-force`, `damper-force`, `element-force` with
//!   `element`); optional `positions` (wheel positions along the track, with units) and `gains`.
//! * `kind = "transfer-function"`: `numerator`, `denominator` (SI numbers, ascending powers of s),
//!   `output = { name, unit }`.
//! * `kind = "state-space"`: `a`, `b`, `c`, optional `d`, `e` (arrays of rows), `outputs = [{ name, unit }]`,
//!   optional `positions`/`gains` for several inputs on one track.

use super::fields::Fields;
use super::spectrum_file::{load_spectrum, spectrum_from_fields};
use crate::error::{Error, Result};
use crate::models::{InputLayout, ModelInstance};
use crate::response::Excitation;
use crate::spectrum::{AtSpeed, Domain, Spectrum};
use crate::system::{Attach, Element, Mdof, OutputInfo, Quantity, StateSpace, TransferFunction};
use crate::units::Dim;
use nalgebra::DMatrix;
use std::path::{Path, PathBuf};
use std::sync::Arc;

/// What to report besides the defaults.
#[derive(Debug, Clone, Default)]
pub struct AnalysisOptions {
    /// Indices of the outputs to report.
    pub outputs: Vec<usize>,
    /// Band [ω₁, ω₂] in rad/s for band-limited σ.
    pub band: Option<(f64, f64)>,
    /// Duration (s) for exceedance probabilities and expected largest peaks.
    pub duration: f64,
    /// (output index, levels in the output's SI unit).
    pub levels: Vec<(usize, Vec<f64>)>,
}

/// A loaded, validated scenario.
#[derive(Debug, Clone)]
pub struct Scenario {
    /// The file.
    pub path: PathBuf,
    /// The file's text (stored with Monte Carlo runs).
    pub text: String,
    /// Title.
    pub title: String,
    /// Provenance.
    pub source: String,
    /// The model kind.
    pub kind: String,
    /// Model and input layout.
    pub model: ModelInstance,
    /// The input process as given (before turning a road into time).
    pub input_spectrum: Arc<dyn Spectrum>,
    /// Name of the input spectrum (catalogue name, path or "inline").
    pub input_name: String,
    /// Speed in m/s, if given.
    pub speed: Option<f64>,
    /// The excitation of the system's inputs.
    pub excitation: Excitation,
    /// Report options.
    pub analysis: AnalysisOptions,
}

/// Loads a scenario file; spectra named by catalogue name are looked up in `spectra_dir`.
///
/// # Errors
/// [`Error::Io`], [`Error::Parse`], or [`Error::File`] naming the key, value and reason.
pub fn load_scenario(path: &Path, spectra_dir: &Path) -> Result<Scenario> {
    let text = std::fs::read_to_string(path).map_err(|source| Error::Io {
        path: path.to_path_buf(),
        source,
    })?;
    parse_scenario(&text, path, spectra_dir)
}

/// Parses scenario text (see [`load_scenario`]).
///
/// # Errors
/// As [`load_scenario`].
pub fn parse_scenario(text: &str, path: &Path, spectra_dir: &Path) -> Result<Scenario> {
    let root: toml::Table = toml::from_str(text).map_err(|e| Error::Parse {
        file: path.to_path_buf(),
        reason: e.to_string(),
    })?;
    let f = Fields::new(path, "", &root);
    let title = f.opt_string("title")?.unwrap_or("").to_string();
    let source = f.opt_string("source")?.unwrap_or("").to_string();
    let input_t = table(&f, "input")?;
    let inf = Fields::new(path, "input", input_t);
    let speed = inf.opt_quantity("speed", Dim::VELOCITY)?;
    if let Some(v) = speed {
        if !(v > 0.0) {
            return Err(inf.error("speed", v, "must be > 0"));
        }
    }
    let model_t = table(&f, "model")?;
    let mf = Fields::new(path, "model", model_t);
    let kind = mf.string("kind")?.to_string();
    let model = build_model(&kind, &mf, crate::models::ModelContext { speed })?;
    mf.finish()?;

    let (input_spectrum, input_name) = match inf.require("spectrum")? {
        toml::Value::String(name) => {
            let p = Path::new(name.as_str());
            let candidate = if p.is_file() {
                p.to_path_buf()
            } else {
                spectra_dir.join(format!("{name}.toml"))
            };
            if !candidate.is_file() {
                return Err(inf.error(
                    "spectrum",
                    name,
                    format!(
                        "no spectrum file `{}` (catalogue {})",
                        candidate.display(),
                        spectra_dir.display()
                    ),
                ));
            }
            let sf = load_spectrum(&candidate)?;
            (sf.spectrum, name.clone())
        }
        toml::Value::Table(t) => {
            let sf = Fields::new(path, "input.spectrum", t);
            let s = spectrum_from_fields(&sf)?;
            // metadata keys allowed inline
            let _ = (
                sf.opt_string("name")?,
                sf.opt_string("description")?,
                sf.opt_string("source")?,
            );
            sf.finish()?;
            (s, "inline".to_string())
        }
        other => {
            return Err(inf.error(
                "spectrum",
                other,
                "expected a catalogue name, a path or an inline table",
            ))
        }
    };
    // the mean is in the input process's own unit: a number (SI) or a quantity string of any dimension
    let mean = match inf.get("mean") {
        None => 0.0,
        Some(v @ toml::Value::String(s)) => crate::units::parse_quantity(s)
            .map(|q| q.0)
            .map_err(|e| inf.error("mean", v, e.to_string()))?,
        Some(_) => inf.number("mean")?,
    };
    inf.finish()?;

    let excitation = build_excitation(&inf, &model.layout, input_spectrum.clone(), speed, mean)?;

    let analysis = match root.get("analysis") {
        None => {
            f.get("analysis");
            AnalysisOptions {
                outputs: (0..model.system.outputs().len()).collect(),
                duration: 3600.0,
                ..Default::default()
            }
        }
        Some(_) => {
            let at = table(&f, "analysis")?;
            let af = Fields::new(path, "analysis", at);
            let opts = analysis_options(&af, &model)?;
            af.finish()?;
            opts
        }
    };
    f.finish()?;
    Ok(Scenario {
        path: path.to_path_buf(),
        text: text.to_string(),
        title,
        source,
        kind,
        model,
        input_spectrum,
        input_name,
        speed,
        excitation,
        analysis,
    })
}

fn table<'a>(f: &Fields<'a>, key: &str) -> Result<&'a toml::Table> {
    let v = f.require(key)?;
    v.as_table().ok_or_else(|| f.error(key, v, "expected a table"))
}

fn build_excitation(
    f: &Fields,
    layout: &InputLayout,
    spectrum: Arc<dyn Spectrum>,
    speed: Option<f64>,
    mean: f64,
) -> Result<Excitation> {
    let temporal = |s: Arc<dyn Spectrum>| -> Result<Arc<dyn Spectrum>> {
        match (s.domain(), speed) {
            (Domain::Temporal, _) => Ok(s),
            (Domain::Spatial, Some(v)) => Ok(Arc::new(AtSpeed::new(s, v).map_err(|e| f.wrap("speed", e))?)),
            (Domain::Spatial, None) => Err(f.error(
                "speed",
                "<missing>",
                "the input spectrum is spatial (a road): give the speed to turn it into time",
            )),
        }
    };
    match layout {
        InputLayout::Single => Excitation::single(temporal(spectrum)?, mean).map_err(|e| f.wrap("spectrum", e)),
        InputLayout::Track { positions, gains } => {
            let delays = if positions.iter().all(|p| *p == 0.0) {
                vec![0.0; positions.len()]
            } else {
                let v = speed.ok_or_else(|| {
                    f.error(
                        "speed",
                        "<missing>",
                        "the wheels are at different positions: the delays need a speed",
                    )
                })?;
                positions.iter().map(|p| p / v).collect()
            };
            Excitation::track(temporal(spectrum)?, delays, gains.clone(), mean).map_err(|e| f.wrap("spectrum", e))
        }
    }
}

fn analysis_options(f: &Fields, model: &ModelInstance) -> Result<AnalysisOptions> {
    let names: Vec<String> = model.system.outputs().iter().map(|o| o.name.clone()).collect();
    let find = |key: &str, n: &str| -> Result<usize> {
        names
            .iter()
            .position(|x| x == n)
            .ok_or_else(|| f.error(key, n, format!("no such output; the model has: {}", names.join(", "))))
    };
    let outputs = match f.get("outputs") {
        None => (0..names.len()).collect(),
        Some(v) => {
            let arr = v
                .as_array()
                .ok_or_else(|| f.error("outputs", v, "expected an array of output names"))?;
            arr.iter()
                .map(|x| {
                    x.as_str()
                        .ok_or_else(|| f.error("outputs", x, "expected a string"))
                        .and_then(|n| find("outputs", n))
                })
                .collect::<Result<Vec<_>>>()?
        }
    };
    let band = match f.get("band") {
        None => None,
        Some(v) => {
            let arr = v
                .as_array()
                .filter(|a| a.len() == 2)
                .ok_or_else(|| f.error("band", v, "expected two frequencies"))?;
            let lo = f.angular_frequency(&arr[0], "band[0]", Dim::FREQUENCY)?;
            let hi = f.angular_frequency(&arr[1], "band[1]", Dim::FREQUENCY)?;
            if !(lo >= 0.0 && hi > lo) {
                return Err(f.error("band", v, "need 0 <= low < high"));
            }
            Some((lo, hi))
        }
    };
    let duration = f.opt_quantity("duration", Dim::TIME)?.unwrap_or(3600.0);
    if !(duration > 0.0) {
        return Err(f.error("duration", duration, "must be > 0"));
    }
    let mut levels = Vec::new();
    if let Some(v) = f.get("levels") {
        let t = v
            .as_table()
            .ok_or_else(|| f.error("levels", v, "expected a table: output name = [levels]"))?;
        for (name, lv) in t {
            let i = find(&format!("levels.{name}"), name)?;
            let arr = lv
                .as_array()
                .ok_or_else(|| f.error(&format!("levels.{name}"), lv, "expected an array"))?;
            let mut vals = Vec::new();
            for x in arr {
                let val = match x {
                    toml::Value::String(s) => crate::units::parse_quantity(s)
                        .map(|q| q.0)
                        .map_err(|e| f.error(&format!("levels.{name}"), x, e.to_string()))?,
                    _ => x
                        .as_float()
                        .or_else(|| x.as_integer().map(|n| n as f64))
                        .ok_or_else(|| f.error(&format!("levels.{name}"), x, "expected a number or a quantity"))?,
                };
                vals.push(val);
            }
            levels.push((i, vals));
        }
    }
    Ok(AnalysisOptions {
        outputs,
        band,
        duration,
        levels,
    })
}

/// Builds the model of `kind` from the `[model]` table.
///
/// # Errors
/// [`Error::File`] for an unknown kind or bad keys.
pub fn build_model(kind: &str, f: &Fields, ctx: crate::models::ModelContext) -> Result<ModelInstance> {
    match kind {
        "mdof" => mdof_from_fields(f),
        "transfer-function" => {
            let num = f.numbers("numerator")?;
            let den = f.numbers("denominator")?;
            let out = output_info(f, "output")?;
            let tf = TransferFunction::new(num, den, out).map_err(|e| f.wrap("denominator", e))?;
            Ok(ModelInstance {
                system: Arc::new(tf),
                layout: InputLayout::Single,
                description: "rational transfer function".into(),
            })
        }
        "state-space" => {
            let a = matrix(f, "a")?;
            let b = matrix(f, "b")?;
            let c = matrix(f, "c")?;
            let d = f.get("d").map(|_| matrix(f, "d")).transpose()?;
            let e = f.get("e").map(|_| matrix(f, "e")).transpose()?;
            let outs = output_list(f, "outputs")?;
            let m = b.ncols();
            let ss = StateSpace::new(a, b, c, d, e, outs).map_err(|e| f.wrap("a", e))?;
            let layout = track_layout(f, m)?;
            Ok(ModelInstance {
                system: Arc::new(ss),
                layout,
                description: "state-space system".into(),
            })
        }
        other => crate::models::from_fields(other, f, ctx).unwrap_or_else(|| {
            Err(f.error(
                "kind",
                other,
                format!(
                    "unknown model kind; known kinds: mdof, transfer-function, state-space, {}",
                    crate::models::KINDS.join(", ")
                ),
            ))
        }),
    }
}

fn output_info(f: &Fields, key: &str) -> Result<OutputInfo> {
    let v = f.require(key)?;
    let t = v
        .as_table()
        .ok_or_else(|| f.error(key, v, "expected { name = \"..\", unit = \"..\" }"))?;
    let of = Fields::new(f.file(), &f.path(key), t);
    let info = OutputInfo::new(of.string("name")?, of.opt_string("unit")?.unwrap_or("m"));
    of.finish()?;
    Ok(info)
}

fn output_list(f: &Fields, key: &str) -> Result<Vec<OutputInfo>> {
    let v = f.require(key)?;
    let arr = v
        .as_array()
        .ok_or_else(|| f.error(key, v, "expected an array of { name, unit }"))?;
    arr.iter()
        .enumerate()
        .map(|(i, x)| {
            let t = x
                .as_table()
                .ok_or_else(|| f.error(&format!("{key}[{i}]"), x, "expected { name, unit }"))?;
            let of = Fields::new(f.file(), &f.path(&format!("{key}[{i}]")), t);
            let info = OutputInfo::new(of.string("name")?, of.opt_string("unit")?.unwrap_or("m"));
            of.finish()?;
            Ok(info)
        })
        .collect()
}

fn matrix(f: &Fields, key: &str) -> Result<DMatrix<f64>> {
    let v = f.require(key)?;
    let rows = v
        .as_array()
        .ok_or_else(|| f.error(key, v, "expected an array of rows"))?;
    let mut data = Vec::new();
    let mut ncols = None;
    for (i, r) in rows.iter().enumerate() {
        let r = r
            .as_array()
            .ok_or_else(|| f.error(&format!("{key}[{i}]"), r, "expected a row (array of numbers)"))?;
        if *ncols.get_or_insert(r.len()) != r.len() {
            return Err(f.error(&format!("{key}[{i}]"), r.len(), "rows must all have the same length"));
        }
        for (j, x) in r.iter().enumerate() {
            let val = x
                .as_float()
                .or_else(|| x.as_integer().map(|n| n as f64))
                .filter(|v| v.is_finite())
                .ok_or_else(|| f.error(&format!("{key}[{i}][{j}]"), x, "expected a finite number"))?;
            data.push(val);
        }
    }
    Ok(DMatrix::from_row_slice(rows.len(), ncols.unwrap_or(0), &data))
}

/// Reads optional `positions` (with units) and `gains` for `m` inputs on one track.
fn track_layout(f: &Fields, m: usize) -> Result<InputLayout> {
    let positions = match f.get("positions") {
        None => vec![0.0; m],
        Some(v) => {
            let arr = v
                .as_array()
                .ok_or_else(|| f.error("positions", v, "expected an array of lengths"))?;
            arr.iter()
                .enumerate()
                .map(|(i, x)| {
                    crate::units::parse_value(x, Dim::LENGTH).map_err(|r| f.error(&format!("positions[{i}]"), x, r))
                })
                .collect::<Result<Vec<_>>>()?
        }
    };
    let gains = match f.get("gains") {
        None => vec![1.0; m],
        Some(_) => f.numbers("gains")?,
    };
    if positions.len() != m || gains.len() != m {
        return Err(f.error(
            "positions",
            positions.len(),
            format!("need one position and one gain per input ({m})"),
        ));
    }
    if let Some((i, p)) = positions.iter().enumerate().find(|(_, p)| **p < 0.0) {
        return Err(f.error(
            &format!("positions[{i}]"),
            p,
            "must be >= 0 (distance behind the first contact)",
        ));
    }
    Ok(InputLayout::Track { positions, gains })
}

fn mdof_from_fields(f: &Fields) -> Result<ModelInstance> {
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
            masses.push(cf.quantity("mass", mass_dim)?);
        }
        cf.finish()?;
        coords.push((name, unit));
    }
    let n = coords.len();
    let n_base = match f.get("base_inputs") {
        None => 0,
        Some(v) => v
            .as_integer()
            .filter(|k| *k >= 0)
            .ok_or_else(|| f.error("base_inputs", v, "expected a count >= 0"))? as usize,
    };
    let point = |key: &str, v: &toml::Value, ff: &Fields| -> Result<Vec<f64>> {
        let arr = v
            .as_array()
            .ok_or_else(|| ff.error(key, v, format!("expected {n} weights of the coordinates")))?;
        if arr.len() != n {
            return Err(ff.error(key, v, format!("expected {n} weights (one per coordinate)")));
        }
        arr.iter()
            .map(|x| {
                x.as_float()
                    .or_else(|| x.as_integer().map(|k| k as f64))
                    .ok_or_else(|| ff.error(key, x, "expected a number"))
            })
            .collect()
    };
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
            let rot = p.iter().zip(&coords).any(|(w, c)| *w != 0.0 && c.1 == "rad");
            let (kd, bd) = if rot {
                (Dim::TORQUE, Dim::new(2, 1, -1))
            } else {
                (Dim::STIFFNESS, Dim::DAMPING)
            };
            let to = match ef.require("to")? {
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
                v @ toml::Value::Array(_) => Attach::Point(point("to", v, &ef)?),
                v => return Err(ef.error("to", v, "expected \"ground\", \"base <j>\" or a point array")),
            };
            let stiffness = ef.opt_quantity("stiffness", kd)?.unwrap_or(0.0);
            let damping = ef.opt_quantity("damping", bd)?.unwrap_or(0.0);
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
                Some(_) => matrix(f, key)?,
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
            DMatrix::zeros(n, 0),
        )
        .map_err(|e| {
            let key = match &e {
                Error::InvalidParameter { name, .. } => match name.as_str() {
                    "B" => "damping_matrix",
                    "C" => "stiffness_matrix",
                    "K_u" => "base_stiffness",
                    "B_u" => "base_damping",
                    _ => "mass_matrix",
                },
                _ => "mass_matrix",
            };
            f.wrap(key, e)
        })?
    } else {
        Mdof::from_elements(&cref, &masses, elements, n_base, &[]).map_err(|e| f.wrap("coordinates", e))?
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
            "deflection" => Quantity::Deflection(element(&of)?),
            "spring-force" => Quantity::SpringForce(element(&of)?),
            "damper-force" => Quantity::DamperForce(element(&of)?),
            "element-force" => Quantity::ElementForce(element(&of)?),
            other => return Err(of.error("quantity", other, "expected displacement, velocity, acceleration, deflection, spring-force, damper-force or element-force")),
        };
        of.finish()?;
        model = model.with_output(&name, quantity).map_err(|e| f.wrap("output", e))?;
    }
    if n_base == 0 {
        return Err(f.error(
            "base_inputs",
            0,
            "a generic mdof scenario needs at least one base input (force inputs: use a catalogue model or state-space)",
        ));
    }
    let layout = track_layout(f, n_base)?;
    Ok(ModelInstance {
        system: Arc::new(model),
        layout,
        description: format!("MDOF model, {n} coordinates"),
    })
}
