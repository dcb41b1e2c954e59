//! The verdict sections of a scenario file: `[analysis.comfort]` (ISO 2631-1 weighted accelerations and
//! the daily exposure) and `[analysis.fatigue]` (a stress output, its S–N curve and the spectral methods).
//!
//! # Format
//! ```toml
//! [analysis.comfort]
//! purpose = "health"              # "health" (default; ISO 2631-1 clause 7, Directive 2002/44/EC) or "comfort"
//! exposure = "6 h"                # daily exposure duration T (A(8) = k·a_w·√(T/8 h), VDV = (3T)^(1/4)·k·a_w)
//! # a8_action = "0.5 m/s^2"       # optional: the Directive's values (a8_action, a8_limit in m/s²;
//! # vdv_action = 9.1              #   vdv_action, vdv_limit as plain numbers in m/s^1.75)
//! [[analysis.comfort.axis]]       # one table per measured axis
//! output = "seat_acc"             # an acceleration output of the model (m/s², rad/s² for rotations)
//! location = "seat-surface"       # seat-surface | seat-back | feet | standing-floor
//! axis = "z"                      # x | y | z | rx | ry | rz
//! # weighting = "Wk"              # default: the standard's weighting for purpose, location and axis
//! # k = 1.0                       # default: the standard's multiplying factor
//!
//! [analysis.fatigue]
//! output = "spring_force"         # the output whose stress is judged
//! stress_factor = "2.5e3 1/m^2"   # stress per unit of the output: a number (SI) or a quantity whose
//!                                 # dimension is stress/output (here Pa per N)
//! k = 5                           # S–N slope: N·S_a^k = C, S_a the stress amplitude in Pa
//! reference_amplitude = "60 MPa"  # either c (in Pa^k) or a point of the curve: amplitude and cycles
//! reference_cycles = 2e6
//! # endurance_limit = "30 MPa"    # optional: amplitudes below it do no damage
//! # methods = ["dirlik", "narrow-band", "wirsching-light", "tovo-benasciutti", "zhao-baker"]  (default: all)
//! design_life = "10000 h"         # optional: the life to compare with (or design_distance = "200000 km"
//!                                 # at the [input] speed)
//! # bins = 48                     # rainflow range histogram of a Monte Carlo run
//! ```
//! Durations and distances carry their unit (`"6 h"`, `"90 min"`, `"200000 km"`): a bare number is refused,
//! with the fix in the message, since people think of these in hours and kilometres and `exposure = 7` would
//! be 7 s. Implausible values are refused naming the key and the value in hours or kilometres: an exposure
//! under 1 min ([`MIN_EXPOSURE_S`]) or over 24 h, a design life under 1 h ([`MIN_DESIGN_LIFE_S`]), a design
//! distance under 1 km ([`MIN_DESIGN_DISTANCE_M`]).
//!
//! Every key is checked: a misspelled key, an unknown weighting, location, axis or method, a weighting on a
//! non-acceleration output, an exposure action value at or above its limit value (`a8_action` ≥ `a8_limit`,
//! `vdv_action` ≥ `vdv_limit`), k ≤ 0, C ≤ 0, a negative duration, and a fatigue output whose λ₄ diverges are
//! refused naming the file, the key, the value and the reason.

use crate::comfort::{axis_factor, Axis, DirectiveLimits, Location, Purpose, Weighting};
use crate::error::{Error, Result};
use crate::fatigue::{SnCurve, SnReferencePoint, SpectralMethodKind};
use crate::fields::{EverydayUnit, Fields};
use crate::models::ModelInstance;
use crate::units::Dim;

/// Shortest daily exposure accepted, s: 1 min ([`crate::comfort::MIN_DAILY_EXPOSURE_S`]).
pub const MIN_EXPOSURE_S: f64 = crate::comfort::MIN_DAILY_EXPOSURE_S;
/// Shortest design life accepted, s: 1 h (a fatigue design life is hours to tens of thousands of hours).
pub const MIN_DESIGN_LIFE_S: f64 = 3600.0;
/// Shortest design distance accepted, m: 1 km (a vehicle's design distance is thousands of kilometres).
pub const MIN_DESIGN_DISTANCE_M: f64 = 1000.0;

const WHY_EXPOSURE: &str = "a daily exposure is minutes to hours: ISO 2631-1 Annex B guides 10 min to 24 h; \
                            write e.g. exposure = \"7 h\"";

/// One weighted axis of `[analysis.comfort]`.
#[derive(Debug, Clone, PartialEq)]
pub struct ComfortAxisSpec {
    /// Index of the acceleration output.
    pub output: usize,
    /// Output name.
    pub output_name: String,
    /// Where the acceleration enters the body.
    pub location: Location,
    /// Which axis.
    pub axis: Axis,
    /// The frequency weighting.
    pub weighting: Weighting,
    /// The multiplying factor k.
    pub k: f64,
}

/// `[analysis.comfort]`.
#[derive(Debug, Clone, PartialEq)]
pub struct ComfortSpec {
    /// Health or comfort.
    pub purpose: Purpose,
    /// Daily exposure duration, s.
    pub exposure_s: f64,
    /// Action and limit values.
    pub limits: DirectiveLimits,
    /// The axes.
    pub axes: Vec<ComfortAxisSpec>,
}

/// `[analysis.fatigue]`.
#[derive(Debug, Clone, PartialEq)]
pub struct FatigueSpec {
    /// Index of the output.
    pub output: usize,
    /// Output name.
    pub output_name: String,
    /// Stress per unit of the output (Pa per SI unit of the output).
    pub stress_factor: f64,
    /// The S–N curve in Pa amplitudes.
    pub sn: SnCurve,
    /// The spectral methods to report.
    pub methods: Vec<SpectralMethodKind>,
    /// Design life to compare with, s.
    pub design_life_s: Option<f64>,
    /// How the design life was given (e.g. `200000 km at 5 m/s`).
    pub design_life_text: Option<String>,
    /// Bins of the rainflow range histogram of a Monte Carlo run.
    pub bins: usize,
}

/// The verdict sections of a scenario (both optional).
#[derive(Debug, Clone, PartialEq, Default)]
pub struct VerdictSpec {
    /// `[analysis.comfort]`, if present.
    pub comfort: Option<ComfortSpec>,
    /// `[analysis.fatigue]`, if present.
    pub fatigue: Option<FatigueSpec>,
    /// `[analysis.seat_factor]`, if present.
    pub seat_factor: Option<super::seat_factor::SeatFactorSpec>,
}

impl VerdictSpec {
    /// True when the scenario asks for no verdict.
    pub fn is_empty(&self) -> bool {
        self.comfort.is_none() && self.fatigue.is_none() && self.seat_factor.is_none()
    }
}

/// Reads `[analysis.comfort]` and `[analysis.fatigue]` from the `[analysis]` table `f`.
///
/// # Formula
/// See the module docs.
///
/// # Errors
/// [`Error::File`] naming the key, the value and the reason.
pub fn parse_verdicts(f: &Fields, model: &ModelInstance, speed: Option<f64>) -> Result<VerdictSpec> {
    let comfort = match f.get("comfort") {
        None => None,
        Some(_) => {
            let c = f.sub("comfort")?;
            let spec = parse_comfort(&c, model)?;
            super::analysis_keys::COMFORT.finish(&c, &[])?;
            Some(spec)
        }
    };
    let fatigue = match f.get("fatigue") {
        None => None,
        Some(_) => {
            let c = f.sub("fatigue")?;
            let spec = parse_fatigue(&c, model, speed)?;
            super::analysis_keys::FATIGUE.finish(&c, &[])?;
            Some(spec)
        }
    };
    let seat_factor = match f.get("seat_factor") {
        None => None,
        Some(_) => {
            let c = f.sub("seat_factor")?;
            let spec = super::seat_factor::parse_seat_factor(&c, model)?;
            super::analysis_keys::SEAT_FACTOR.finish(&c, &[])?;
            Some(spec)
        }
    };
    Ok(VerdictSpec {
        comfort,
        fatigue,
        seat_factor,
    })
}

fn output_index(f: &Fields, key: &str, model: &ModelInstance) -> Result<(usize, String)> {
    let name = f.string(key)?;
    let outs = model.system.outputs();
    outs.iter()
        .position(|o| o.name == name)
        .map(|i| (i, name.to_string()))
        .ok_or_else(|| {
            let names: Vec<&str> = outs.iter().map(|o| o.name.as_str()).collect();
            f.error(
                key,
                name,
                format!("no such output; the model has: {}", names.join(", ")),
            )
        })
}

fn parse_comfort(f: &Fields, model: &ModelInstance) -> Result<ComfortSpec> {
    let purpose = match f.opt_string("purpose")? {
        None | Some("health") => Purpose::Health,
        Some("comfort") => Purpose::Comfort,
        Some(p) => return Err(f.error("purpose", p, "expected \"health\" or \"comfort\"")),
    };
    let exposure_s = f.everyday_quantity("exposure", EverydayUnit::HOUR)?;
    f.at_least("exposure", exposure_s, MIN_EXPOSURE_S, EverydayUnit::HOUR, WHY_EXPOSURE)?;
    if exposure_s > crate::comfort::MAX_DAILY_EXPOSURE_S {
        return Err(f.error(
            "exposure",
            EverydayUnit::HOUR.show(exposure_s),
            "a daily exposure is at most 24 h",
        ));
    }
    let limits = directive_limits(f)?;
    let arr = match f.require("axis")? {
        toml::Value::Array(a) if !a.is_empty() => a,
        v => return Err(f.error("axis", v, "expected one or more [[analysis.comfort.axis]] tables")),
    };
    let mut axes: Vec<ComfortAxisSpec> = Vec::new();
    for (j, v) in arr.iter().enumerate() {
        let key = format!("axis[{j}]");
        let t = v.as_table().ok_or_else(|| f.error(&key, v, "expected a table"))?;
        let a = comfort_axis(&Fields::new(f.file(), &f.path(&key), t), model, purpose)?;
        if axes.iter().any(|b| {
            b.location == a.location
                && b.axis == a.axis
                && (b.weighting == Weighting::Wf) == (a.weighting == Weighting::Wf)
        }) {
            return Err(f.error(
                &key,
                format!("{} {}", a.location.label(), a.axis.label()),
                "each location and axis may appear once (and once more with Wf, for motion sickness)",
            ));
        }
        axes.push(a);
    }
    Ok(ComfortSpec {
        purpose,
        exposure_s,
        limits,
        axes,
    })
}

/// The action and limit values of `[analysis.comfort]` (`f`), the Directive's where a key is absent.
///
/// # Errors
/// A value that is not > 0, a limit not above its action value.
fn directive_limits(f: &Fields) -> Result<DirectiveLimits> {
    let d = DirectiveLimits::WHOLE_BODY;
    let positive = |key: &str, v: Option<f64>, default: f64| -> Result<f64> {
        match v {
            None => Ok(default),
            Some(x) if x > 0.0 && x.is_finite() => Ok(x),
            Some(x) => Err(f.error(key, x, "must be > 0")),
        }
    };
    let plain = |key: &str| -> Result<Option<f64>> {
        match f.get(key) {
            None => Ok(None),
            Some(_) => f.number(key).map(Some),
        }
    };
    let limits = DirectiveLimits {
        a8_action: positive(
            "a8_action",
            f.opt_quantity("a8_action", Dim::ACCELERATION)?,
            d.a8_action,
        )?,
        a8_limit: positive("a8_limit", f.opt_quantity("a8_limit", Dim::ACCELERATION)?, d.a8_limit)?,
        vdv_action: positive("vdv_action", plain("vdv_action")?, d.vdv_action)?,
        vdv_limit: positive("vdv_limit", plain("vdv_limit")?, d.vdv_limit)?,
    };
    for (action, limit, a, l) in [
        ("a8_action", "a8_limit", limits.a8_action, limits.a8_limit),
        ("vdv_action", "vdv_limit", limits.vdv_action, limits.vdv_limit),
    ] {
        if l <= a {
            // the key the file gives (the other is the Directive's value)
            let (key, value) = match f.get(limit) {
                Some(v) => (limit, v.to_string()),
                None => (action, f.get(action).map_or(a.to_string(), |v| v.to_string())),
            };
            return Err(f.error(
                key,
                value,
                format!(
                    "the exposure limit value must be above the exposure action value ({action} = {a}, {limit} = \
                     {l}): the Directive's verdicts are `below action`, `above action` and `above limit`, in that \
                     order"
                ),
            ));
        }
    }
    Ok(limits)
}

/// The `location` and `axis` of a `[[analysis.comfort.axis]]` table.
///
/// # Errors
/// An unknown location or axis.
fn location_and_axis(af: &Fields) -> Result<(Location, Axis)> {
    let location = match af.string("location")? {
        "seat-surface" | "seat" => Location::SeatSurface,
        "seat-back" | "back" => Location::SeatBack,
        "feet" => Location::Feet,
        "standing-floor" | "floor" => Location::StandingFloor,
        s => {
            return Err(af.error(
                "location",
                s,
                "expected seat-surface, seat-back, feet or standing-floor",
            ))
        }
    };
    let axis = match af.string("axis")? {
        "x" => Axis::X,
        "y" => Axis::Y,
        "z" => Axis::Z,
        "rx" => Axis::Rx,
        "ry" => Axis::Ry,
        "rz" => Axis::Rz,
        s => return Err(af.error("axis", s, "expected x, y, z, rx, ry or rz")),
    };
    Ok((location, axis))
}

/// One `[[analysis.comfort.axis]]` table (`af`) for `purpose`.
///
/// # Errors
/// An unknown output, location, axis or weighting; a factor that is not > 0; an output that is not an
/// acceleration; an unknown key.
fn comfort_axis(af: &Fields, model: &ModelInstance, purpose: Purpose) -> Result<ComfortAxisSpec> {
    let (output, output_name) = output_index(af, "output", model)?;
    let (location, axis) = location_and_axis(af)?;
    let standard = axis_factor(purpose, location, axis);
    let weighting = match af.opt_string("weighting")? {
        Some(w) => Weighting::parse(w).map_err(|e| af.wrap("weighting", e))?,
        None => standard
            .as_ref()
            .map(|s| s.weighting)
            .map_err(|e| af.error("axis", axis.label(), e.to_string()))?,
    };
    let k = match af.get("k") {
        Some(_) => {
            let k = af.number("k")?;
            if k.is_nan() || k <= 0.0 {
                return Err(af.error("k", k, "a multiplying factor must be > 0"));
            }
            k
        }
        None => standard
            .map(|s| s.k)
            .map_err(|e| af.error("axis", axis.label(), e.to_string()))?,
    };
    // the weighting applies to an acceleration: refuse any other output here, naming the key
    if let Some(ss) = model.system.state_space() {
        crate::comfort::check_weightable(ss, output, &weighting).map_err(|e| {
            let reason = match e {
                Error::InvalidParameter { reason, value, .. } => format!("its unit is {value}: {reason}"),
                other => other.to_string(),
            };
            af.error("output", &output_name, reason)
        })?;
    } else {
        return Err(af.error("output", &output_name, "the model has no state-space form to weight"));
    }
    super::analysis_keys::COMFORT_AXIS.finish(af, &[])?;
    Ok(ComfortAxisSpec {
        output,
        output_name,
        location,
        axis,
        weighting,
        k,
    })
}

fn parse_fatigue(f: &Fields, model: &ModelInstance, speed: Option<f64>) -> Result<FatigueSpec> {
    let (output, output_name) = output_index(f, "output", model)?;
    let unit = model.system.outputs()[output].unit.clone();
    let stress_factor = stress_factor(f, &unit, &output_name)?;
    let sn = sn_curve(f)?;
    let methods = fatigue_methods(f)?;
    let (design_life_s, design_life_text) = design_life(f, speed)?;
    let bins = histogram_bins(f)?;
    Ok(FatigueSpec {
        output,
        output_name,
        stress_factor,
        sn,
        methods,
        design_life_s,
        design_life_text,
        bins,
    })
}

/// The dimension of a stress, Pa.
const STRESS_DIM: Dim = Dim::new(-1, 1, -2);

/// `stress_factor`: stress per unit of the output (`unit`, of the output `output_name`), a plain number (SI)
/// or a quantity of dimension Pa/(output unit); finite and non-zero.
///
/// # Errors
/// A value of the wrong dimension, or zero or non-finite.
fn stress_factor(f: &Fields, unit: &str, output_name: &str) -> Result<f64> {
    let stress_dim = STRESS_DIM;
    let stress_factor = match f.require("stress_factor")? {
        v @ toml::Value::String(_) => {
            let out_dim = crate::units::unit_dim(unit).ok_or_else(|| {
                f.error(
                    "stress_factor",
                    v,
                    format!(
                        "the output is in `{unit}`, which has no dimension to check against: give a plain SI number"
                    ),
                )
            })?;
            let want = Dim::new(
                stress_dim.m - out_dim.m,
                stress_dim.kg - out_dim.kg,
                stress_dim.s - out_dim.s,
            );
            crate::units::parse_value(v, want).map_err(|r| {
                f.error(
                    "stress_factor",
                    v,
                    format!("{r} (stress in Pa per {unit} of `{output_name}`)"),
                )
            })?
        }
        _ => f.number("stress_factor")?,
    };
    if !(stress_factor.is_finite() && stress_factor != 0.0) {
        return Err(f.error("stress_factor", stress_factor, "must be finite and non-zero"));
    }
    Ok(stress_factor)
}

/// The S–N curve of `[analysis.fatigue]`: `k` with `c`, or `k` with `reference_amplitude` and
/// `reference_cycles`; `endurance_limit` optional. An error of the curve names the key it came from.
///
/// # Errors
/// Neither or both forms, or values the curve refuses.
fn sn_curve(f: &Fields) -> Result<SnCurve> {
    let stress_dim = STRESS_DIM;
    let k = f.number("k")?;
    let endurance = f.opt_quantity("endurance_limit", stress_dim)?;
    match (f.get("c"), f.get("reference_amplitude")) {
        (Some(_), None) => {
            let c = f.number("c")?;
            SnCurve {
                k,
                c,
                endurance_limit: endurance,
            }
            .build()
        }
        (None, Some(_)) => {
            let a = f.quantity("reference_amplitude", stress_dim)?;
            let n = f.number("reference_cycles")?;
            SnReferencePoint {
                k,
                amplitude: a,
                cycles: n,
                endurance_limit: endurance,
            }
            .build()
        }
        _ => {
            return Err(f.error(
                "c",
                "<missing>",
                "give either c (in Pa^k) or reference_amplitude with reference_cycles",
            ))
        }
    }
    .map_err(|e| {
        let key = match &e {
            Error::InvalidParameter { name, .. } if name == "amplitude" => "reference_amplitude".to_string(),
            Error::InvalidParameter { name, .. } if name == "cycles" => "reference_cycles".to_string(),
            // C is the file's `c`, or derived from the reference point as N·S_a^k (its exponent k overflows it)
            Error::InvalidParameter { name, .. } if name == "C" && f.get("c").is_some() => "c".to_string(),
            Error::InvalidParameter { name, .. } if name == "C" => "k".to_string(),
            Error::InvalidParameter { name, .. } => name.clone(),
            _ => "k".to_string(),
        };
        f.wrap(&key, e)
    })
}

/// `methods`: the spectral methods to compare (all five by default).
///
/// # Errors
/// Not a non-empty array of method names.
fn fatigue_methods(f: &Fields) -> Result<Vec<SpectralMethodKind>> {
    Ok(match f.get("methods") {
        None => SpectralMethodKind::ALL.to_vec(),
        Some(v) => {
            let arr = v
                .as_array()
                .filter(|a| !a.is_empty())
                .ok_or_else(|| f.error("methods", v, "expected a non-empty array of method names"))?;
            arr.iter()
                .map(|m| match m.as_str() {
                    Some("narrow-band") => Ok(SpectralMethodKind::NarrowBand),
                    Some("wirsching-light") => Ok(SpectralMethodKind::WirschingLight),
                    Some("dirlik") => Ok(SpectralMethodKind::Dirlik),
                    Some("tovo-benasciutti") => Ok(SpectralMethodKind::TovoBenasciutti),
                    Some("zhao-baker") => Ok(SpectralMethodKind::ZhaoBaker),
                    _ => Err(f.error(
                        "methods",
                        m,
                        "expected narrow-band, wirsching-light, dirlik, tovo-benasciutti or zhao-baker",
                    )),
                })
                .collect::<Result<Vec<_>>>()?
        }
    })
}

/// `bins`: the rainflow histogram's bin count (48 by default, 1 to 100000).
///
/// # Errors
/// Not a count in that range.
fn histogram_bins(f: &Fields) -> Result<usize> {
    Ok(match f.get("bins") {
        None => 48,
        Some(v) => v
            .as_integer()
            .filter(|b| (1..=100_000).contains(b))
            .map(|b| b as usize)
            .ok_or_else(|| f.error("bins", v, "expected a count from 1 to 100000"))?,
    })
}

/// `design_life` (a duration) or `design_distance` (a distance at the `[input]` speed): the life in s and the
/// text as written (`10000 h`, `200000 km at 5 m/s`).
fn design_life(f: &Fields, speed: Option<f64>) -> Result<(Option<f64>, Option<String>)> {
    let written = |key: &str| f.get(key).map(|v| v.as_str().unwrap_or_default().to_string());
    let life = f.opt_everyday_quantity("design_life", EverydayUnit::HOUR)?;
    let distance = f.opt_everyday_quantity("design_distance", EverydayUnit::KILOMETRE)?;
    match (life, distance) {
        (Some(_), Some(x)) => Err(f.error(
            "design_distance",
            EverydayUnit::KILOMETRE.show(x),
            "give design_life or design_distance, not both",
        )),
        (Some(t), None) => {
            let why = "a design life is hours to years of service; write e.g. design_life = \"10000 h\"";
            f.at_least("design_life", t, MIN_DESIGN_LIFE_S, EverydayUnit::HOUR, why)?;
            Ok((Some(t), written("design_life")))
        }
        (None, Some(x)) => {
            let why = "a design distance is thousands of kilometres; write e.g. design_distance = \"200000 km\"";
            f.at_least(
                "design_distance",
                x,
                MIN_DESIGN_DISTANCE_M,
                EverydayUnit::KILOMETRE,
                why,
            )?;
            let v = speed.ok_or_else(|| {
                f.error(
                    "design_distance",
                    EverydayUnit::KILOMETRE.show(x),
                    "a distance needs the [input] speed to become a time",
                )
            })?;
            let text = written("design_distance").unwrap_or_default();
            Ok((Some(x / v), Some(format!("{text} at {} m/s", crate::numbers::num(v)))))
        }
        (None, None) => Ok((None, None)),
    }
}
