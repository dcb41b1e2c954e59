//! Spectrum files: one named spectrum per TOML file in `spectra/`.
//!
//! # Format
//! ```toml
//! name = "book-8-45"                      # optional, defaults to the file stem
//! description = "..."                      # optional
//! source = "Sukharev (2012), eq. (8.45)"   # optional provenance
//! kind = "exponential"                     # see below
//! domain = "spatial"                       # "temporal" (default; ω in rad/s) or "spatial" (Ω in rad/m; the default of `iso8608` and `two-pole-road`)
//! unit = "m"                               # SI unit of the process itself (default "m")
//! variance = "2.25 cm^2"                   # numbers are SI; strings carry units
//! alpha = "0.035 1/cm"
//! ```
//!
//! | kind | keys |
//! |---|---|
//! | `exponential` (type 1), `gaussian` (type 2) | `variance`, `alpha` |
//! | `exp-cosine` (type 3), `gauss-cosine` (type 4) | `variance`, `alpha`, `beta` |
//! | `rational` | `numerator`, `denominator`: SI numbers, ascending powers of ω² (two-sided angular) |
//! | `band-white` | `convention`, `level` (number in that convention), `band = ["1 Hz", "10 Hz"]` |
//! | `tabulated` | `convention`, `frequency_unit` (`Hz`, `rad/s`, `cycles/m`, `rad/m`), `frequencies`, `values` |
//! | `power-law` | `g0` (one-sided cyclic density at n₀, number), `n0` (with unit), `waviness`, optional `band` |
//! | `iso8608` | `class` (A–H), optional `bound` (`lower`, `mean`, `upper`), optional `band` (default 0.011–2.83 cycles/m) or `unbounded = true` |
//! | `two-pole-road` | `form` (`as-printed`, `consistent`), `dq` or `sigma_q`, `alpha`, `beta` (1/m) |
//! | `measured-profile` | `file` (a profile CSV, relative to the file that names it; [`crate::road::Profile`]), optional `track` (column name, default the first), `segment` (Welch samples, default [`crate::road::default_segment`]), `detrend` (`linear` default, `mean`): the Welch estimate Ĝ_d(n) of the track as a tabulated spatial spectrum (log–log interpolation between bins, zero outside them); a Monte Carlo run records the CSV's size and CRC-32 as part of its identity |
//!
//! Frequencies (band edges, n₀, `frequency_unit`) must carry a unit: a bare number would be ambiguous
//! between cyclic and angular frequency. Density levels are plain numbers whose convention is named by
//! `convention` (never by a unit, which would apply the 2π twice).

use super::catalogue::SpectrumOrigin;
use crate::error::{Error, Result};
use crate::fields::Fields;
use crate::spectrum::{
    two_pole_road::Form, BandWhiteParameters, Convention, Domain, ExpCosine, Exponential, GaussCosineParameters,
    Gaussian, IsoBound, IsoClass, PowerLaw, PowerLawParameters, RationalSpectrum, Spectrum, Tabulated, TwoPoleRoad,
    ISO_BAND,
};
use crate::units::{self, Dim};
use std::f64::consts::PI;
use std::path::Path;
use std::sync::Arc;

/// A spectrum read from a file, with its metadata.
#[derive(Debug, Clone)]
pub struct SpectrumFile {
    /// Name (file stem unless given).
    pub name: String,
    /// Free text.
    pub description: String,
    /// Provenance of the parameter values.
    pub source: String,
    /// SI unit of the process.
    pub unit: String,
    /// The spectrum.
    pub spectrum: Arc<dyn Spectrum>,
    /// Where it came from ([`SpectrumOrigin::File`] for [`load_spectrum`]; the catalogue sets
    /// [`SpectrumOrigin::Catalogue`]).
    pub origin: SpectrumOrigin,
    /// The file's text, verbatim (what a run records to be tied to the exact spectrum it used).
    pub text: String,
}

/// Reads and validates a spectrum file.
///
/// # Errors
/// [`Error::Io`] if unreadable, [`Error::Parse`] if not TOML, [`Error::File`] naming the key, value and
/// reason for anything invalid (unknown kind or key, missing key, bad unit, negative variance, ...).
pub fn load_spectrum(path: &Path) -> Result<SpectrumFile> {
    let text = crate::fields::read_text_file(path)?;
    let mut sf = parse_spectrum(&text, path)?;
    sf.origin = SpectrumOrigin::File {
        path: path.to_path_buf(),
    };
    Ok(sf)
}

/// Parses spectrum-file text; `path` is used for the name and in error messages. The origin is
/// [`SpectrumOrigin::Inline`] (text not read from a file) until a loader sets it.
///
/// # Errors
/// As [`load_spectrum`].
pub fn parse_spectrum(text: &str, path: &Path) -> Result<SpectrumFile> {
    let table: toml::Table = crate::fields::parse_toml(text, path)?;
    let f = Fields::new(path, "", &table);
    let stem = path
        .file_stem()
        .map(|s| s.to_string_lossy().into_owned())
        .unwrap_or_default();
    let name = f.opt_string("name")?.map(str::to_string).unwrap_or(stem);
    let description = f.opt_string("description")?.unwrap_or("").to_string();
    let source = f.opt_string("source")?.unwrap_or("").to_string();
    let spectrum = spectrum_from_fields(&f)?;
    let unit = f.opt_string("unit")?.unwrap_or("m").to_string();
    f.finish()?;
    Ok(SpectrumFile {
        name,
        description,
        source,
        unit,
        spectrum,
        origin: SpectrumOrigin::Inline,
        text: text.to_string(),
    })
}

/// A decay rate (α of e^{−α|τ|} or e^{−ατ²}, the poles α, β of the (8.66) road): a quantity of `dim` whose
/// unit names no angle. `Hz`, `rad`, `cycles` and `deg` would scale it by 2π or π/180 (the SI value of a
/// frequency is angular), which a decay rate does not have: `"1 Hz"` is refused, `"1 1/s"` is the rate.
///
/// # Errors
/// [`Error::File`] naming the key: an angle in the unit, or as [`Fields::quantity`].
fn decay_rate(f: &Fields, key: &str, dim: Dim) -> Result<f64> {
    if let Some(toml::Value::String(text)) = f.get(key) {
        let angle = text
            .split(|c: char| !c.is_alphanumeric())
            .any(|t| t.ends_with("Hz") || t.ends_with("rad") || ["cycle", "cycles", "deg"].contains(&t));
        if angle {
            return Err(f.error(
                key,
                text,
                "a decay rate carries no angle or cycle (Hz, rad, cycles, deg would scale it by 2π or π/180): \
                 write it in 1/s, or 1/m for a spatial spectrum (1/s^2, 1/m^2 for a gaussian α)",
            ));
        }
    }
    f.quantity(key, dim)
}

/// Builds the spectrum described by the keys of `f` (also used for inline spectra in scenario files).
///
/// # Errors
/// [`Error::File`] naming the key.
pub fn spectrum_from_fields(f: &Fields) -> Result<Arc<dyn Spectrum>> {
    let kind = f.string("kind")?;
    let domain = match f.opt_string("domain")? {
        // the road kinds (ISO 8608, the (8.66) road) are spatial by definition; every other kind defaults to time
        None if kind == "iso8608" || kind == "two-pole-road" || kind == "measured-profile" => Domain::Spatial,
        None | Some("temporal") => Domain::Temporal,
        Some("spatial") => Domain::Spatial,
        Some(other) => return Err(f.error("domain", other, "expected \"temporal\" or \"spatial\"")),
    };
    let unit_text = f.opt_string("unit")?.unwrap_or("m");
    let unit_dim = process_dim(f, unit_text)?;
    let lag = match domain {
        Domain::Temporal => Dim::TIME,
        Domain::Spatial => Dim::LENGTH,
    };
    let var_dim = pow(unit_dim, 2);
    let inv_lag = pow(lag, -1);
    let dims = Dims {
        domain,
        unit: unit_dim,
        variance: var_dim,
        inv_lag,
    };
    let w = |key: &str, e: Error| f.wrap(key, e);
    let spectrum: Arc<dyn Spectrum> = match kind {
        "exponential" | "gaussian" | "exp-cosine" | "gauss-cosine" => decaying(f, &dims, kind)?,
        "rational" => {
            let n = f.numbers("numerator")?;
            let d = f.numbers("denominator")?;
            Arc::new(RationalSpectrum::new(n, d, domain).map_err(|e| w(param_key(&e), e))?)
        }
        "butterworth-band" => Arc::new(super::butterworth_keys::butterworth_from_fields(f, domain, inv_lag)?),
        "band-white" => band_white(f, &dims)?,
        "tabulated" => tabulated(f, &dims)?,
        "power-law" => power_law(f, &dims)?,
        "iso8608" => iso8608(f, &dims)?,
        "two-pole-road" => two_pole_road(f, &dims)?,
        "measured-profile" => measured_profile(f, &dims)?,
        other => {
            return Err(f.error(
                "kind",
                other,
                "unknown kind; expected exponential, gaussian, exp-cosine, gauss-cosine, rational, band-white, \
                 butterworth-band, tabulated, power-law, iso8608, two-pole-road, measured-profile",
            ))
        }
    };
    Ok(spectrum)
}

/// The kinds of a variance and decay rates: `exponential`, `gaussian`, `exp-cosine`, `gauss-cosine`.
///
/// # Errors
/// [`Error::File`] naming the key.
fn decaying(f: &Fields, dims: &Dims, kind: &str) -> Result<Arc<dyn Spectrum>> {
    let w = |key: &str, e: Error| f.wrap(key, e);
    let domain = dims.domain;
    let d = f.quantity("variance", dims.variance)?;
    let gauss = kind == "gaussian" || kind == "gauss-cosine";
    let a = decay_rate(f, "alpha", if gauss { pow(dims.inv_lag, 2) } else { dims.inv_lag })?;
    if kind == "gaussian" || kind == "exponential" {
        return Ok(if gauss {
            Arc::new(Gaussian::new(d, a, domain).map_err(|e| w(param_key(&e), e))?)
        } else {
            Arc::new(Exponential::new(d, a, domain).map_err(|e| w(param_key(&e), e))?)
        });
    }
    let b = f.quantity("beta", dims.inv_lag)?;
    Ok(if gauss {
        Arc::new(
            GaussCosineParameters {
                variance: d,
                alpha: a,
                beta: b,
                domain,
            }
            .build()
            .map_err(|e| w(param_key(&e), e))?,
        )
    } else {
        Arc::new(
            ExpCosine {
                variance: d,
                alpha: a,
                beta: b,
                domain,
            }
            .build()
            .map_err(|e| w(param_key(&e), e))?,
        )
    })
}

/// `kind = "power-law"`: G₀ at n₀, the waviness, an optional band.
///
/// # Errors
/// [`Error::File`] naming the key.
fn power_law(f: &Fields, d: &Dims) -> Result<Arc<dyn Spectrum>> {
    let g0 = f.number("g0")?;
    let n0v = f.require("n0")?;
    let n0 = f.angular_frequency(n0v, "n0", d.inv_lag)? / (2.0 * PI);
    let wav = f.number("waviness")?;
    let b = band(f, "band", d.inv_lag)?.map(|(a, b)| (a / (2.0 * PI), b / (2.0 * PI)));
    Ok(Arc::new(
        PowerLawParameters {
            g0,
            n0,
            waviness: wav,
            band: b,
            domain: d.domain,
        }
        .build()
        .map_err(|e| f.wrap(param_key(&e), e))?,
    ))
}

/// The dimensions of a spectrum file's quantities: its domain, the process's unit, the variance's, and the
/// inverse lag (1/s or 1/m).
struct Dims {
    domain: Domain,
    unit: Dim,
    variance: Dim,
    inv_lag: Dim,
}

/// Refuses a temporal `domain` for a kind that is spatial by definition (`what`: "… are spatial").
fn require_spatial(f: &Fields, domain: Domain, what: &str) -> Result<()> {
    if domain == Domain::Spatial {
        return Ok(());
    }
    Err(f.error("domain", "temporal", format!("{what}: set domain = \"spatial\"")))
}

/// `kind = "band-white"`: a level on a band.
///
/// # Errors
/// [`Error::File`] naming the key.
fn band_white(f: &Fields, d: &Dims) -> Result<Arc<dyn Spectrum>> {
    let c = convention(f)?;
    let level = f.number("level")?;
    let (lo, hi) = band(f, "band", d.inv_lag)?.ok_or_else(|| f.error("band", "<missing>", "required"))?;
    let (_, s0) = c.to_canonical(1.0, level);
    if level.is_nan() || level < 0.0 {
        return Err(f.error(
            "level",
            f.get("level").map_or("?".into(), |v| v.to_string()),
            "must be >= 0",
        ));
    }
    Ok(Arc::new(
        BandWhiteParameters {
            convention: Convention::TwoSidedAngular,
            level: s0,
            lo,
            hi,
            domain: d.domain,
        }
        .build()
        .map_err(|e| f.wrap("band", e))?,
    ))
}

/// `kind = "tabulated"`: values over frequencies.
///
/// # Errors
/// [`Error::File`] naming the key.
fn tabulated(f: &Fields, d: &Dims) -> Result<Arc<dyn Spectrum>> {
    let c = convention(f)?;
    let fu = f.string("frequency_unit")?;
    let scale = frequency_scale(f, fu, d.inv_lag)?;
    let x = f.numbers("frequencies")?;
    let v = f.numbers("values")?;
    // Abscissae → the convention's own abscissa unit (cyclic or angular), exactly.
    let to_conv = if c.is_cyclic() { scale / (2.0 * PI) } else { scale };
    let x: Vec<f64> = x.iter().map(|xi| xi * to_conv).collect();
    Ok(Arc::new(
        Tabulated::new(c, x, v, d.domain).map_err(|e| f.wrap(param_key(&e), e))?,
    ))
}

/// `kind = "iso8608"`: the ISO 8608 road of a class and bound.
///
/// # Errors
/// [`Error::File`] naming the key.
fn iso8608(f: &Fields, d: &Dims) -> Result<Arc<dyn Spectrum>> {
    require_spatial(f, d.domain, "ISO 8608 spectra are spatial")?;
    let class: IsoClass = f.string("class")?.parse().map_err(|e| f.wrap("class", e))?;
    let bound: IsoBound = match f.opt_string("bound")? {
        None => IsoBound::GeometricMean,
        Some(b) => b.parse().map_err(|e| f.wrap("bound", e))?,
    };
    let unbounded = match f.get("unbounded") {
        None => false,
        Some(v) => v
            .as_bool()
            .ok_or_else(|| f.error("unbounded", v, "expected true or false"))?,
    };
    let b = band(f, "band", d.inv_lag)?.map(|(a, b)| (a / (2.0 * PI), b / (2.0 * PI)));
    if unbounded && b.is_some() {
        return Err(f.error("unbounded", "true", "contradicts the `band` key: give one of them"));
    }
    let b = if unbounded { None } else { Some(b.unwrap_or(ISO_BAND)) };
    Ok(Arc::new(
        PowerLaw::iso8608(class, bound, b).map_err(|e| f.wrap_param(e, "band"))?,
    ))
}

/// `kind = "two-pole-road"`: the road of Sukharev (2012) (8.66).
///
/// # Errors
/// [`Error::File`] naming the key.
fn two_pole_road(f: &Fields, d: &Dims) -> Result<Arc<dyn Spectrum>> {
    require_spatial(f, d.domain, "the (8.66) road is spatial")?;
    let form = match f.string("form")? {
        "as-printed" => Form::AsPrinted,
        "consistent" => Form::Consistent,
        other => return Err(f.error("form", other, "expected \"as-printed\" or \"consistent\"")),
    };
    let dq = match (f.opt_quantity("dq", d.variance)?, f.opt_quantity("sigma_q", d.unit)?) {
        (Some(v), None) => v,
        (None, Some(s)) => {
            if s < 0.0 {
                return Err(f.error("sigma_q", s, "must be >= 0"));
            }
            s * s
        }
        (Some(_), Some(_)) => return Err(f.error("sigma_q", "both", "give `dq` or `sigma_q`, not both")),
        (None, None) => return Err(f.error("dq", "<missing>", "give `dq` (variance) or `sigma_q`")),
    };
    let a = decay_rate(f, "alpha", d.inv_lag)?;
    let b = decay_rate(f, "beta", d.inv_lag)?;
    Ok(Arc::new(
        TwoPoleRoad {
            dq,
            alpha: a,
            beta: b,
            form,
        }
        .build()
        .map_err(|e| f.wrap(param_key(&e), e))?,
    ))
}

/// `kind = "measured-profile"`: the density of a road profile (CSV) by Welch's method.
///
/// # Errors
/// [`Error::File`] naming the key.
fn measured_profile(f: &Fields, d: &Dims) -> Result<Arc<dyn Spectrum>> {
    require_spatial(f, d.domain, "a road profile is spatial")?;
    let file = f.string("file")?;
    let path = match f.file().parent() {
        Some(dir) => dir.join(file),
        None => Path::new(file).to_path_buf(),
    };
    let profile = crate::road::Profile::read_csv(&path).map_err(|e| f.wrap("file", e))?;
    let track = match f.opt_string("track")? {
        None => profile
            .tracks
            .first()
            .ok_or_else(|| f.error("file", file, "the profile has no track column"))?,
        Some(name) => profile.track(name).map_err(|e| f.wrap("track", e))?,
    };
    let detrend = match f.opt_string("detrend")? {
        None | Some("linear") => crate::road::Detrend::Linear,
        Some("mean") => crate::road::Detrend::Mean,
        Some(other) => return Err(f.error("detrend", other, "expected \"linear\" or \"mean\"")),
    };
    let m = match f.get("segment") {
        None => crate::road::default_segment(profile.len()),
        Some(v) => v
            .as_integer()
            .filter(|m| *m >= 4 && m % 2 == 0 && *m as usize <= profile.len())
            .ok_or_else(|| {
                f.error(
                    "segment",
                    v,
                    format!(
                        "expected an even number of samples from 4 to the record's {}",
                        profile.len()
                    ),
                )
            })? as usize,
    };
    let detrended = detrend.apply(&track.elevation_m);
    crate::road::spatial_psd::check_density_input(&path, &track.name, &track.elevation_m, &detrended)?;
    let psd = crate::road::spatial_psd(&detrended, profile.step_m, m).map_err(|e| f.wrap("file", e))?;
    Ok(Arc::new(
        Tabulated::new(Convention::OneSidedCyclic, psd.n, psd.g_d, Domain::Spatial).map_err(|e| f.wrap("file", e))?,
    ))
}

/// Maps a constructor's parameter name onto the file key it came from.
fn param_key(e: &Error) -> &'static str {
    match e {
        Error::InvalidParameter { name, .. } => match name.as_str() {
            "variance" => "variance",
            "alpha" => "alpha",
            "beta" => "beta",
            "dq" => "dq",
            "g0" => "g0",
            "n0" => "n0",
            "waviness" => "waviness",
            "numerator" => "numerator",
            "denominator" => "denominator",
            n if n.starts_with("band") => "band",
            n if n.starts_with("values") => "values",
            _ => "frequencies",
        },
        _ => "kind",
    }
}

fn convention(f: &Fields) -> Result<Convention> {
    let c = f.string("convention")?;
    c.parse().map_err(|e| f.wrap("convention", e))
}

fn process_dim(f: &Fields, unit: &str) -> Result<Dim> {
    let text = format!("1 {unit}");
    let (scale, dim) = if unit == "1" {
        (1.0, Dim::DIMENSIONLESS)
    } else {
        units::parse_quantity(&text).map_err(|e| f.error("unit", unit, e.to_string()))?
    };
    if (scale - 1.0).abs() > 1e-12 {
        return Err(f.error(
            "unit",
            unit,
            "the process unit must be a coherent SI unit (m, N, rad, m/s, N m, 1); values may still be written in \
             other units",
        ));
    }
    Ok(dim)
}

/// Angular-frequency scale of a frequency unit name: `Hz` → 2π, `rad/s` → 1, `cycles/m` → 2π, `rad/m` → 1.
fn frequency_scale(f: &Fields, unit: &str, dim: Dim) -> Result<f64> {
    let v = toml::Value::String(format!("1 {unit}"));
    f.angular_frequency(&v, "frequency_unit", dim)
}

fn band(f: &Fields, key: &str, dim: Dim) -> Result<Option<(f64, f64)>> {
    let Some(v) = f.get(key) else { return Ok(None) };
    let arr = v.as_array().filter(|a| a.len() == 2).ok_or_else(|| {
        f.error(
            key,
            v,
            "expected two frequencies with units, e.g. [\"0.011 cycles/m\", \"2.83 cycles/m\"]",
        )
    })?;
    let lo = f.angular_frequency(&arr[0], &format!("{key}[0]"), dim)?;
    let hi = f.angular_frequency(&arr[1], &format!("{key}[1]"), dim)?;
    if !(lo >= 0.0 && hi > lo) {
        return Err(f.error(key, v, "need 0 <= low < high"));
    }
    Ok(Some((lo, hi)))
}

fn pow(d: Dim, k: i8) -> Dim {
    Dim::new(d.m * k, d.kg * k, d.s * k)
}
