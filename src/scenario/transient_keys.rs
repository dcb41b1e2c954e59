//! The keys of a non-stationary scenario: `[input.speed_profile]`, `[input.envelope]`, `[transient]` (the
//! time window, the start, `[[transient.schedule]]`) and `[analysis.mission]` (`docs/transients.md`).
//!
//! # Format
//! ```toml
//! [input.speed_profile]            # a table v(t) ...
//! times = ["0 s", "10 s"]
//! speeds = ["5 m/s", "20 m/s"]
//! # ... or constant acceleration: from = "5 m/s", to = "20 m/s", acceleration = "1.5 m/s^2", start = "1 s"
//!
//! [input.envelope]                 # u(t) = a(t)·s(t)
//! times = ["0 s", "2 s"]
//! amplitude = [0.0, 1.0]           # or intensity = [...] (a², the factor on the variance)
//!
//! [transient]
//! duration = "20 s"                # the time window [0, duration]
//! step = "0.05 s"                  # spacing of the reported times (default duration/400)
//! start = "rest"                   # or "stationary" (default), or state = [x₀, …] (SI, the model's states)
//! max_error = 0.05                 # evolutionary route (non-rational inputs): largest error estimate δ(t)
//!
//! [[transient.schedule]]           # a model key as a piecewise-linear function of time
//! key = "model.element.0.stiffness"
//! times = ["0 s", "60 s"]
//! values = ["20 kN/m", "40 kN/m"]
//!
//! [analysis.mission]
//! duration = "20 s"                # default: [transient] duration, else [analysis] duration
//! levels = { travel = ["5 cm", "8 cm"] }   # clearances: P(max |y| > b within T)
//! ```

use crate::error::Result;
use crate::fields::Fields;
use crate::transient::{ConstantAcceleration, Envelope, PiecewiseLinear, RopeFormula, SpeedProfile, Start};
use crate::units::Dim;

/// The non-stationary part of a scenario (present when any of its keys is).
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct TransientSpec {
    /// `[input.speed_profile]`.
    pub speed_profile: Option<SpeedProfile>,
    /// `[input.envelope]` (a ≡ 1 when absent).
    pub envelope: Envelope,
    /// `[transient] start` / `state`.
    pub start: Start,
    /// `[transient] duration`, s.
    pub duration: Option<f64>,
    /// `[transient] step`, s.
    pub step: Option<f64>,
    /// `[transient] rel_tol`: the local relative error of the exact route's steps.
    pub rel_tol: Option<f64>,
    /// `[transient] max_error`: the evolutionary route's largest error estimate δ(t) of a reported value.
    pub max_error: Option<f64>,
    /// `[[transient.schedule]]`.
    pub schedules: Vec<ScheduledKey>,
}

/// One `[[transient.schedule]]` table: a `[model]` key whose value follows a piecewise-linear function of
/// time (values in SI).
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct ScheduledKey {
    /// The key inside `[model]` (`element.0.stiffness` for `model.element.0.stiffness`).
    pub key: String,
    /// The values (SI) over time; with `rope`, the rope length l(t) in m.
    pub profile: PiecewiseLinear,
    /// `rope = { formula = ..., ... }`: the key's value is this function of the rope length l(t).
    pub rope: Option<RopeFormula>,
}

/// `[analysis.mission]`.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct MissionSpec {
    /// T, s (None: the transient window, else `[analysis] duration`).
    pub duration: Option<f64>,
    /// (output index, clearances b in the output's SI unit).
    pub levels: Vec<(usize, Vec<f64>)>,
}

/// A time table of quantities: `key` is an array of numbers (SI) or strings with units of dimension `dim`.
fn quantities(f: &Fields, key: &str, dim: Dim) -> Result<Vec<f64>> {
    let v = f.require(key)?;
    let arr = v
        .as_array()
        .ok_or_else(|| f.error(key, v, format!("expected an array of quantities ({dim})")))?;
    arr.iter()
        .enumerate()
        .map(|(i, x)| crate::units::parse_value(x, dim).map_err(|r| f.error(&format!("{key}[{i}]"), x, r)))
        .collect()
}

/// An error of a table constructor ([`PiecewiseLinear`], [`SpeedProfile`], [`Envelope`]) naming
/// `time[k]` / `speed[k]` / `envelope[k]`, as the file key `times[k]` / `<values>[k]`.
fn table_error(f: &Fields, e: crate::Error, values: &str) -> crate::Error {
    let key = match &e {
        crate::Error::InvalidParameter { name, .. } => {
            let (base, index) = name.split_once('[').unwrap_or((name.as_str(), ""));
            let file_key = match base {
                "time" => "times",
                _ => values,
            };
            if index.is_empty() {
                file_key.to_string()
            } else {
                format!("{file_key}[{index}")
            }
        }
        _ => values.to_string(),
    };
    f.wrap(&key, e)
}

/// `[input.speed_profile]`: `times` + `speeds`, or `from`, `to`, `acceleration` and optional `start`.
///
/// # Errors
/// An error naming the file, the key, the value and the reason: times that do not increase (not a function
/// of time), a negative speed, an acceleration that never reaches `to`, both forms or neither.
pub fn speed_profile(f: &Fields) -> Result<SpeedProfile> {
    if f.get("times").is_some() || f.get("speeds").is_some() {
        if let Some(k) = ["from", "to", "acceleration", "start"]
            .iter()
            .find(|k| f.get(k).is_some())
        {
            return Err(f.error(
                k,
                f.get(k).map_or(String::new(), |v| v.to_string()),
                "give the profile as a table (times, speeds) or as constant acceleration (from, to, acceleration, \
                 start), not both",
            ));
        }
        let times = quantities(f, "times", Dim::TIME)?;
        let speeds = quantities(f, "speeds", Dim::VELOCITY)?;
        if times.len() != speeds.len() {
            return Err(f.error(
                "speeds",
                f.get("speeds").map_or(String::new(), |v| v.to_string()),
                format!(
                    "{} speeds for {} times: give one speed per time",
                    speeds.len(),
                    times.len()
                ),
            ));
        }
        let v = SpeedProfile::table(times, speeds).map_err(|e| table_error(f, e, "speeds"))?;
        super::input_keys::SPEED_PROFILE.finish(f, &[])?;
        return Ok(v);
    }
    let v0 = f.quantity("from", Dim::VELOCITY)?;
    let v1 = f.quantity("to", Dim::VELOCITY)?;
    let a = f.quantity("acceleration", Dim::ACCELERATION)?;
    let t0 = f.opt_quantity("start", Dim::TIME)?.unwrap_or(0.0);
    for (k, x) in [("from", v0), ("to", v1)] {
        if x < 0.0 {
            return Err(f.error(k, x, "a speed is >= 0: the road is traversed in one direction"));
        }
    }
    // times that collapse in rounding (t0 + (v1 − v0)/a = t0) are the start's doing, else the acceleration's
    let blamed = if f.get("start").is_some() && t0 + (v1 - v0).abs() / a.abs() == t0 {
        "start"
    } else {
        "acceleration"
    };
    let v = ConstantAcceleration {
        from_m_s: v0,
        to_m_s: v1,
        acceleration_m_s2: a,
        start_s: t0,
    }
    .build()
    .map_err(|e| f.wrap_param(e, blamed))?;
    super::input_keys::SPEED_PROFILE.finish(f, &[])?;
    Ok(v)
}

/// `[input.envelope]`: `times` and `amplitude` (a) or `intensity` (a², the factor on the variance).
///
/// # Errors
/// Non-finite values, times that do not increase, a negative intensity, both value keys or neither (file,
/// key, value, reason).
pub fn envelope(f: &Fields) -> Result<Envelope> {
    let times = quantities(f, "times", Dim::TIME)?;
    let (key, intensity) = match (f.get("amplitude"), f.get("intensity")) {
        (Some(_), None) => ("amplitude", false),
        (None, Some(_)) => ("intensity", true),
        (a, i) => {
            return Err(f.error(
                "amplitude",
                a.or(i).map_or("<missing>".to_string(), |v| v.to_string()),
                "give exactly one of amplitude (a(t)) or intensity (a(t)², the factor on the variance)",
            ))
        }
    };
    let values = envelope_values(f, key)?;
    if values.len() != times.len() {
        return Err(f.error(
            key,
            f.get(key).map_or(String::new(), |v| v.to_string()),
            format!(
                "{} values for {} times: give one value per time",
                values.len(),
                times.len()
            ),
        ));
    }
    let e = if intensity {
        Envelope::intensity(times, values)
    } else {
        Envelope::table(times, values)
    };
    let e = e.map_err(|e| table_error(f, e, key))?;
    super::input_keys::ENVELOPE.finish(f, &[])?;
    Ok(e)
}

/// The envelope's values: numbers, each finite (named by its index).
fn envelope_values(f: &Fields, key: &str) -> Result<Vec<f64>> {
    let v = f.require(key)?;
    let arr = v
        .as_array()
        .ok_or_else(|| f.error(key, v, "expected an array of numbers"))?;
    arr.iter()
        .enumerate()
        .map(
            |(i, x)| match x.as_float().or_else(|| x.as_integer().map(|n| n as f64)) {
                Some(y) if y.is_finite() => Ok(y),
                _ => Err(f.error(
                    &format!("{key}[{i}]"),
                    x,
                    "an envelope value is a finite number (dimensionless)",
                )),
            },
        )
        .collect()
}

/// `[transient]` (without the input's keys, which the caller adds).
///
/// # Errors
/// A duration or step that is not a positive time, a step longer than the duration, an unknown start,
/// `start` and `state` both given, a malformed schedule (file, key, value, reason).
pub fn transient_section(f: &Fields) -> Result<TransientSpec> {
    let duration = f.opt_quantity("duration", Dim::TIME)?;
    let step = f.opt_quantity("step", Dim::TIME)?;
    for (k, x) in [("duration", duration), ("step", step)] {
        if let Some(x) = x
            && (x.is_nan() || x <= 0.0)
        {
            return Err(f.error(k, x, "a time span > 0"));
        }
    }
    if let (Some(d), Some(s)) = (duration, step)
        && s > d
    {
        return Err(f.error("step", s, format!("longer than the duration {d} s")));
    }
    let rel_tol = bounded(f, "rel_tol", 1e-2)?;
    let max_error = bounded(f, "max_error", 1.0)?;
    let start = start(f)?;
    let schedules = schedules(f)?;
    super::transient_key_table::TRANSIENT.finish(f, &[])?;
    Ok(TransientSpec {
        speed_profile: None,
        envelope: Envelope::unit(),
        start,
        duration,
        step,
        rel_tol,
        max_error,
        schedules,
    })
}

/// An optional relative error `key` in (0, `upper`).
fn bounded(f: &Fields, key: &str, upper: f64) -> Result<Option<f64>> {
    match f.get(key) {
        None => Ok(None),
        Some(v) => f.number(key).and_then(|x| {
            if x > 0.0 && x < upper {
                Ok(Some(x))
            } else {
                Err(f.error(key, v, format!("a relative error in (0, {upper})")))
            }
        }),
    }
}

fn start(f: &Fields) -> Result<Start> {
    match (f.get("start"), f.get("state")) {
        (Some(s), Some(_)) => Err(f.error(
            "start",
            s,
            "give start (rest or stationary) or state (the initial state), not both",
        )),
        (None, Some(_)) => Ok(Start::State(f.numbers("state")?)),
        (Some(s), None) => match s.as_str() {
            Some("rest") => Ok(Start::Rest),
            Some("stationary") => Ok(Start::Stationary),
            _ => Err(f.error(
                "start",
                s,
                "expected \"rest\" (every state zero) or \"stationary\" (the stationary state at t = 0); a stated \
                 state is written state = [...]",
            )),
        },
        (None, None) => Ok(Start::Stationary),
    }
}

fn schedules(f: &Fields) -> Result<Vec<ScheduledKey>> {
    let Some(v) = f.get("schedule") else {
        return Ok(Vec::new());
    };
    let tables = v
        .as_array()
        .ok_or_else(|| f.error("schedule", v, "expected [[transient.schedule]] tables"))?;
    let mut out: Vec<ScheduledKey> = Vec::new();
    for (i, t) in tables.iter().enumerate() {
        let t = t
            .as_table()
            .ok_or_else(|| f.error(&format!("schedule[{i}]"), t, "expected a table { key, times, values }"))?;
        let sf = Fields::new(f.file(), &f.path(&format!("schedule[{i}]")), t);
        let key = sf.string("key")?;
        let Some(inner) = key.strip_prefix("model.").filter(|k| !k.is_empty() && *k != "kind") else {
            return Err(sf.error(
                "key",
                key,
                "a schedule varies a key of [model] (e.g. model.element.0.stiffness); the input varies by \
                 [input.speed_profile] and [input.envelope]",
            ));
        };
        if out.iter().any(|s| s.key == inner) {
            return Err(sf.error("key", key, "scheduled twice"));
        }
        let times = quantities(&sf, "times", Dim::TIME)?;
        let rope = rope_formula(&sf)?;
        let values = match rope {
            Some(_) => quantities(&sf, "values", Dim::LENGTH)?,
            None => schedule_values(&sf)?,
        };
        if rope.is_some()
            && let Some((i, l)) = values.iter().enumerate().find(|(_, l)| !(l.is_finite() && **l > 0.0))
        {
            return Err(sf.error(&format!("values[{i}]"), l, "a rope length is finite and > 0 m"));
        }
        if values.len() != times.len() {
            return Err(sf.error(
                "values",
                sf.get("values").map_or(String::new(), |v| v.to_string()),
                format!(
                    "{} values for {} times: give one value per time",
                    values.len(),
                    times.len()
                ),
            ));
        }
        let profile = PiecewiseLinear::new(times, values).map_err(|e| table_error(&sf, e, "values"))?;
        super::transient_key_table::SCHEDULE.finish(&sf, &[])?;
        out.push(ScheduledKey {
            key: inner.to_string(),
            profile,
            rope,
        });
    }
    Ok(out)
}

/// `rope = { formula = "stiffness", axial_rigidity = ... }` (EF/l), `{ formula = "rayleigh-mass" | "lumped-mass",
/// end_mass = ..., mass_per_metre = ... }` (m + γl/3, m + γl/4) of a schedule table, if any.
fn rope_formula(sf: &Fields) -> Result<Option<RopeFormula>> {
    if sf.get("rope").is_none() {
        return Ok(None);
    }
    let rf = sf.sub("rope")?;
    let positive = |key: &str, dim: Dim| -> Result<f64> {
        let v = rf.quantity(key, dim)?;
        if !(v.is_finite() && v > 0.0) {
            return Err(rf.error(key, v, "must be finite and > 0"));
        }
        Ok(v)
    };
    let formula = rf.string("formula")?;
    let f = match formula {
        "stiffness" => RopeFormula::Stiffness {
            axial_rigidity: positive("axial_rigidity", Dim::FORCE)?,
        },
        "rayleigh-mass" | "lumped-mass" => {
            let (end_mass, mass_per_metre) = (
                positive("end_mass", Dim::MASS)?,
                positive("mass_per_metre", Dim::new(-1, 1, 0))?,
            );
            if formula == "rayleigh-mass" {
                RopeFormula::RayleighMass {
                    end_mass,
                    mass_per_metre,
                }
            } else {
                RopeFormula::LumpedMass {
                    end_mass,
                    mass_per_metre,
                }
            }
        }
        other => {
            return Err(rf.error(
                "formula",
                other,
                "one of \"stiffness\" (EF/l), \"rayleigh-mass\" (m + γl/3), \"lumped-mass\" (m + γl/4)",
            ));
        }
    };
    super::transient_key_table::ROPE.finish(&rf, &[])?;
    Ok(Some(f))
}

/// The values of a schedule in SI: numbers, or quantities of one dimension (that of the first value).
fn schedule_values(sf: &Fields) -> Result<Vec<f64>> {
    let v = sf.require("values")?;
    let arr = v
        .as_array()
        .ok_or_else(|| sf.error("values", v, "expected an array of values as the key takes them"))?;
    let mut dim: Option<Dim> = None;
    arr.iter()
        .enumerate()
        .map(|(i, x)| {
            let key = format!("values[{i}]");
            let (y, d) = match x.as_str() {
                Some(s) => crate::units::parse_quantity(s).map_err(|e| sf.wrap(&key, e))?,
                None => (
                    crate::units::parse_value(x, Dim::DIMENSIONLESS).map_err(|r| sf.error(&key, x, r))?,
                    Dim::DIMENSIONLESS,
                ),
            };
            if *dim.get_or_insert(d) != d {
                return Err(sf.error(&key, x, "all values of a schedule have the dimension of the first"));
            }
            Ok(y)
        })
        .collect()
}

/// `[analysis.mission]`: `duration` and `levels` (output name = array of clearances).
///
/// # Errors
/// An unknown output, a level that is not a finite value of the output's dimension, a duration that is
/// not a positive time (file, key, value, reason).
pub fn mission(f: &Fields, outputs: &[crate::system::OutputInfo]) -> Result<MissionSpec> {
    let duration = f.opt_everyday_quantity("duration", crate::fields::EverydayUnit::HOUR)?;
    if let Some(d) = duration
        && (d.is_nan() || d <= 0.0)
    {
        return Err(f.error("duration", d, "must be > 0"));
    }
    let lv = f.require("levels")?;
    let table = lv
        .as_table()
        .ok_or_else(|| f.error("levels", lv, "expected a table: output name = [clearances]"))?;
    let mut levels = Vec::new();
    for (name, v) in table {
        let key = format!("levels.{name}");
        let i = outputs.iter().position(|o| &o.name == name).ok_or_else(|| {
            let names: Vec<&str> = outputs.iter().map(|o| o.name.as_str()).collect();
            f.error(
                &key,
                name,
                format!("no such output; the model has: {}", names.join(", ")),
            )
        })?;
        let arr = v
            .as_array()
            .filter(|a| !a.is_empty())
            .ok_or_else(|| f.error(&key, v, "expected a non-empty array of levels"))?;
        let unit = &outputs[i].unit;
        let vals = arr
            .iter()
            .map(|x| {
                let b = super::scenario_file::quantity_in_unit(f, &key, x, unit, &format!("output `{name}`"))?;
                if b > 0.0 {
                    Ok(b)
                } else {
                    Err(f.error(&key, x, "a clearance b > 0 (the barrier of max |y| is ±b)"))
                }
            })
            .collect::<Result<Vec<_>>>()?;
        levels.push((i, vals));
    }
    super::analysis_keys::MISSION.finish(f, &[])?;
    Ok(MissionSpec { duration, levels })
}

/// `[input.speed_profile]` of the single `[input]` table, if present, with the speed of the stationary
/// analyses (`analyze`, `simulate`) when `[input] speed` is absent: the final speed of the profile, or its
/// largest speed if it ends at rest.
///
/// # Errors
/// The profile's errors; a profile that never moves.
pub fn input_speed_profile(inf: &Fields) -> Result<Option<(SpeedProfile, f64)>> {
    if inf.get("speed_profile").is_none() {
        return Ok(None);
    }
    let pf = inf.sub("speed_profile")?;
    let v = speed_profile(&pf)?;
    let values = v.table_points().values();
    let end = *values.last().expect("a table has a point");
    let stationary = if end > 0.0 { end } else { v.table_points().range().1 };
    if stationary.is_nan() || stationary <= 0.0 {
        return Err(pf.error(
            "speeds",
            pf.get("speeds").map_or(String::new(), |x| x.to_string()),
            "the vehicle never moves (every speed is 0): a road needs a speed to become a time signal",
        ));
    }
    Ok(Some((v, stationary)))
}

/// The scenario's [`TransientSpec`] from `[transient]` (read from the root `f`) and the input's profile and
/// envelope; `None` when none of them is given.
///
/// # Errors
/// The errors of [`transient_section`].
pub fn assemble(
    f: &Fields,
    speed_profile: Option<SpeedProfile>,
    envelope: Option<Envelope>,
) -> Result<Option<Box<TransientSpec>>> {
    let section = match f.get("transient") {
        None => None,
        Some(_) => Some(transient_section(&f.sub("transient")?)?),
    };
    if section.is_none() && speed_profile.is_none() && envelope.is_none() {
        return Ok(None);
    }
    let mut spec = section.unwrap_or(TransientSpec {
        speed_profile: None,
        envelope: Envelope::unit(),
        start: Start::Stationary,
        duration: None,
        step: None,
        rel_tol: None,
        max_error: None,
        schedules: Vec::new(),
    });
    spec.speed_profile = speed_profile;
    if let Some(e) = envelope {
        spec.envelope = e;
    }
    Ok(Some(Box::new(spec)))
}
