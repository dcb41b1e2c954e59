//! Several random inputs in one scenario: `[[input]]` tables, each an independent source (one process, or
//! a road of two parallel tracks with a coherence) and the model inputs it drives.
//!
//! # Format
//! ```toml
//! [[input]]                          # a road of two tracks
//! name = "road"                      # signal name in run files (default `input_<i>`)
//! road = { spectrum = "iso8608-c", track_width = "1.5 m", coherence = { kind = "dodds-robson" } }
//!                                    # track_width: the distance between the tracks; a vehicle model with its
//!                                    # own track width (full-vehicle) uses it when the key is left out and
//!                                    # refuses a different value
//! speed = "20 m/s"                   # every table that gives a speed must give the same one
//! mean = 0.0                         # mean of each track, in the spectrum's unit (default 0)
//! drives = [0, 1, 2, 3]              # model inputs (0-based; the mdof: base inputs first, then forces)
//! tracks = ["left", "right", "left", "right"]   # road only: the track under each driven input
//! positions = ["0 m", "0 m", "2.7 m", "2.7 m"]  # distance behind the first contact (delay = position/speed)
//! gains = [1, 1, 1, 1]               # u_j = gain · x(t − position/speed) + gain · mean
//!
//! [[input]]                          # one process (a force, a base motion, a road felt by one wheel line)
//! spectrum = "white-force"           # a catalogue name, a path or an inline table (as `[input] spectrum`)
//! drives = [4]
//! kurtosis = 6                       # optional, one process only: a non-Gaussian (Laplace moving average) source
//! band = ["0.011 cycles/m", "30 cycles/m"]   # optional, any table: the source's band (super::input_filters)
//! enveloping = { kind = "moving-average", length = "0.25 m" }   # optional, a road (either form): tyre enveloping
//! ```
//! * A road of two tracks alone may also be written as its own `[road]` section (`spectrum`, `coherence`,
//!   `track_width`, `speed`, and the table keys below): the same as one `[[input]]` table with
//!   `road = { spectrum, coherence, track_width }` (`road_section_as_input`); errors name `road.<key>`.
//! * `drives` may be left out only when there is one `[[input]]` table: it then drives every model input.
//! * `tracks`, `positions`, `gains` default to the model's own layout for the driven inputs (a catalogue
//!   vehicle knows its wheels; the generic `mdof` reads `tracks`, `positions`, `gains` in `[model]`), else
//!   to position 0 and gain 1. A road needs a track for every driven input.
//! * Coherence kinds (ρ the coherence amplitude, γ² = ρ² the squared coherence, [`crate::coherence`]):
//!   `dodds-robson` (`waviness`, default 2: the isotropic surface, ρ = 2^{1−ν}/Γ(ν) x^ν K_ν(x), x = 2πnB,
//!   ν = w/2); `ammon-bormann` (`preset` = `iso-a` … `iso-e`, `major-road-concrete`,
//!   `major-road-asphaltic-concrete`, `main-road-asphaltic-concrete-on-pavement`,
//!   `main-road-asphaltic-concrete`, `track-tiled-concrete-pavement`; or `omega_p` (rad/m), `w`, `p`, `a`
//!   (default 1) and `values` = `squared_coherence` (default) or `coherence_amplitude`: the quantity the
//!   formula [1 + (Ω B^a/Ω_p)^w]^{−p} gives); `tabulated` (`n` in cycles/m and `squared_coherence` or
//!   `coherence_amplitude`, linear interpolation); `constant` (`coherence_amplitude`).
//! * Every model input is driven by exactly one table; the sources are independent of each other.
//! * `kurtosis = κ` (κ ≥ 3) in a table of one process makes that source a Laplace moving average of marginal
//!   kurtosis κ with the same spectrum ([`LaplaceMovingAverage`](crate::simulate::LaplaceMovingAverage));
//!   Monte Carlo runs then draw every source the Laplace way (the others with κ = 3, Gaussian). A road of
//!   two tracks refuses it: mixing two Laplace moving averages to the prescribed coherence would not keep
//!   the prescribed kurtosis of each track.
//! * The keys of each table are declared in the key tables of [`super::input_keys`], which the scenario
//!   file reference shows: an `[[input]]` table's unknown-key check and its "known keys" list come from
//!   [`input_keys::INPUT`], and the key reference test checks every table against the keys read here.

use super::catalogue::{Catalogue, SpectrumOrigin};
use super::input_keys;
use super::scenario_file::{quantity_in_unit, resolution_reason, ScenarioInput};
use super::spectrum_file::spectrum_from_fields;
use super::SpectrumFile;
use crate::coherence::{
    AmmonBormann, AmmonBormannParameters, AmmonBormannRoad, Coherence, CoherenceKind, ConstantCoherence,
    IsotropicCoherence, TabulatedCoherence, TwoTracks,
};
use crate::error::Result;
use crate::fields::Fields;
use crate::models::InputLayout;
use crate::response::{Excitation, InputMap, Source};
use crate::spectrum::{AtSpeed, Domain, Spectrum};
use crate::units::Dim;
use std::path::Path;
use std::sync::Arc;

/// `[road]`: a road of two tracks written as its own section,
/// ```toml
/// [road]
/// spectrum = "iso8608-c"
/// coherence = { kind = "dodds-robson", waviness = 2 }
/// track_width = "1.5 m"        # a vehicle with its own track width may leave it out
/// speed = "20 m/s"
/// ```
/// (and optionally `name`, `mean`, `drives`, `tracks`, `positions`, `gains` as in an `[[input]]` table), is the
/// one `[[input]]` table `{ name = "road", road = { spectrum, coherence, track_width }, speed, … }`: this
/// rewrites `root` so, and says whether it did. The scenario text is kept as written; errors are renamed
/// back to `road.<key>` by [`road_section_keys`].
///
/// # Errors
/// [`crate::Error::File`] at `road` when the scenario also has `[input]` or `[[input]]` tables, or when
/// `road` is not a table.
pub(crate) fn road_section_as_input(root: &mut toml::Table, path: &Path) -> Result<bool> {
    let Some(v) = root.get("road") else {
        return Ok(false);
    };
    let toml::Value::Table(t) = v else {
        return Err(crate::Error::in_file(
            path,
            "road",
            v,
            "expected a [road] section (spectrum, coherence, track_width, speed)",
        ));
    };
    if root.contains_key("input") {
        return Err(crate::Error::in_file(
            path,
            "road",
            "[road]",
            "the scenario also has [input] or [[input]] tables: give its inputs one way (a road of two \
             tracks as [road], or every input as an [[input]] table with road = { … })",
        ));
    }
    let mut road = toml::Table::new();
    let mut input = toml::Table::new();
    input.insert("name".into(), toml::Value::String("road".into()));
    for (k, v) in t {
        match k.as_str() {
            k if input_keys::ROAD.contains(k) => road.insert(k.to_string(), v.clone()),
            // every other key as in an [[input]] table (unknown ones refused there, named road.<key>)
            _ => input.insert(k.clone(), v.clone()),
        };
    }
    input.insert("road".into(), toml::Value::Table(road));
    root.remove("road");
    root.insert("input".into(), toml::Value::Array(vec![toml::Value::Table(input)]));
    Ok(true)
}

/// Renames the keys of an error of the `[[input]]` table that a `[road]` section stands for
/// ([`road_section_as_input`]) back to the section's own: `input[0].road.spectrum` → `road.spectrum`,
/// `input[0].speed` → `road.speed`, `input[0]`/`input` → `road`.
pub(crate) fn road_section_keys(e: crate::Error) -> crate::Error {
    match e {
        crate::Error::File {
            file,
            key,
            value,
            reason,
        } => {
            let key = if let Some(rest) = key.strip_prefix("input[0].road.") {
                format!("road.{rest}")
            } else if let Some(rest) = key.strip_prefix("input[0].") {
                format!("road.{rest}")
            } else if key == "input[0]" || key == "input" {
                "road".to_string()
            } else {
                key
            };
            crate::Error::File {
                file,
                key,
                value,
                reason: reason.replace("input[0].road.", "road.").replace("input[0].", "road."),
            }
        }
        e => e,
    }
}

/// The common `speed` of the `[[input]]` tables (m/s), if any gives one.
///
/// # Errors
/// A speed that is not a positive velocity, or two tables with different speeds.
pub(crate) fn common_speed(path: &Path, tables: &[toml::Value]) -> Result<Option<f64>> {
    let mut speed: Option<(usize, f64)> = None;
    for (i, v) in tables.iter().enumerate() {
        let Some(t) = v.as_table() else { continue };
        let inf = Fields::new(path, &format!("input[{i}]"), t);
        if let Some(v) = inf.opt_quantity("speed", Dim::VELOCITY)? {
            if v.is_nan() || v <= 0.0 {
                return Err(inf.error("speed", v, "must be > 0"));
            }
            match speed {
                Some((i0, v0)) if v0 != v => {
                    return Err(inf.error(
                        "speed",
                        v,
                        format!("input[{i0}].speed is {v0} m/s: one machine moves at one speed"),
                    ))
                }
                None => speed = Some((i, v)),
                _ => {}
            }
        }
    }
    Ok(speed.map(|s| s.1))
}

/// The one `speed_profile` of the `[[input]]` tables (v(t) for `stochvib transient`) with its stationary
/// speed, if a table gives one.
///
/// # Errors
/// A malformed profile; two tables that give one ("one machine moves along one speed profile").
pub(crate) fn common_speed_profile(
    path: &Path,
    tables: &[toml::Value],
) -> Result<Option<(crate::transient::SpeedProfile, f64)>> {
    let mut found: Option<(usize, (crate::transient::SpeedProfile, f64))> = None;
    for (i, v) in tables.iter().enumerate() {
        let Some(t) = v.as_table() else { continue };
        let inf = Fields::new(path, &format!("input[{i}]"), t);
        let Some(p) = super::transient_keys::input_speed_profile(&inf)? else {
            continue;
        };
        if let Some((i0, _)) = found {
            return Err(inf.error(
                "speed_profile",
                "[table]",
                format!("input[{i0}].speed_profile is given: one machine moves along one speed profile, give it once"),
            ));
        }
        found = Some((i, p));
    }
    Ok(found.map(|f| f.1))
}

/// Resolves `key` of `inf` (a catalogue name, a path or an inline table of spectrum keys) into the
/// reference as written and the spectrum file.
///
/// # Errors
/// An unknown name or path, a bad inline table, a value of another type.
pub(crate) fn resolve_spectrum(
    inf: &Fields,
    key: &str,
    catalogue: &Catalogue,
    base: Option<&Path>,
) -> Result<(String, SpectrumFile)> {
    match inf.require(key)? {
        toml::Value::String(name) => {
            let sf = catalogue
                .resolve(name, base)
                .map_err(|e| inf.error(key, name, resolution_reason(e)))?;
            Ok((name.clone(), sf))
        }
        toml::Value::Table(t) => {
            let sf = Fields::new(inf.file(), &inf.path(key), t);
            let spectrum = spectrum_from_fields(&sf)?;
            let unit = sf.opt_string("unit")?.unwrap_or("m").to_string();
            // metadata keys allowed inline
            let name = sf.opt_string("name")?.unwrap_or("inline").to_string();
            let description = sf.opt_string("description")?.unwrap_or("").to_string();
            let src = sf.opt_string("source")?.unwrap_or("").to_string();
            sf.finish()?;
            let file = SpectrumFile {
                name,
                description,
                source: src,
                unit,
                spectrum,
                origin: SpectrumOrigin::Inline,
                text: toml::to_string(t).unwrap_or_default(),
            };
            Ok(("inline".to_string(), file))
        }
        other => Err(inf.error(key, other, "expected a catalogue name, a path or an inline table")),
    }
}

/// (track, position in m, gain) of model input j in the model's own layout.
fn layout_of(layout: &InputLayout, j: usize) -> (Option<usize>, f64, f64) {
    match layout {
        InputLayout::Single => (None, 0.0, 1.0),
        InputLayout::Track { positions, gains } => (
            None,
            positions.get(j).copied().unwrap_or(0.0),
            gains.get(j).copied().unwrap_or(1.0),
        ),
        InputLayout::TwoTracks {
            tracks,
            positions,
            gains,
            ..
        } => (
            tracks.get(j).copied(),
            positions.get(j).copied().unwrap_or(0.0),
            gains.get(j).copied().unwrap_or(1.0),
        ),
    }
}

/// `left` → 0, `right` → 1.
pub(crate) fn track_index(f: &Fields, key: &str, v: &toml::Value) -> Result<usize> {
    match v.as_str() {
        Some("left") => Ok(0),
        Some("right") => Ok(1),
        _ => Err(f.error(key, v, "expected \"left\" or \"right\"")),
    }
}

/// A coherence model written as a TOML inline table, e.g. `{ kind = "dodds-robson", waviness = 2 }` (the
/// `coherence` table of a scenario's road, same kinds and keys), for tracks `width_m` apart.
///
/// # Errors
/// [`crate::Error::File`] naming `--model` and the key, value and reason; text that is not a TOML inline table;
/// [`crate::Error::InvalidParameter`] naming `--track-width` for a width that is not finite and > 0 (it read
/// "key `coherence.waviness` = 2: invalid parameter `track_width`").
///
/// # Examples
/// ```
/// let c = stochvib::scenario::coherence_from_toml(r#"{ kind = "constant", coherence_amplitude = 0.5 }"#, 1.5).unwrap();
/// assert_eq!(c.squared_coherence(0.3), 0.25);
/// let e = stochvib::scenario::coherence_from_toml(r#"{ kind = "dodds-robson", waviness = 2 }"#, 0.0).unwrap_err();
/// assert!(e.to_string().contains("--track-width"), "{e}");
/// ```
pub fn coherence_from_toml(text: &str, width_m: f64) -> Result<Arc<dyn Coherence>> {
    if !(width_m.is_finite() && width_m > 0.0) {
        return Err(crate::Error::invalid(
            "--track-width",
            format!("{} m", crate::numbers::num(width_m)),
            "a track width must be finite and > 0 m",
        ));
    }
    let file = Path::new("--model");
    let doc: toml::Table = toml::from_str(&format!("coherence = {text}")).map_err(|e| {
        crate::Error::in_file(
            file,
            "coherence",
            crate::io_rules::excerpt(text),
            format!("not a TOML inline table: {}", e.message()),
        )
    })?;
    let Some(toml::Value::Table(t)) = doc.get("coherence") else {
        return Err(crate::Error::in_file(
            file,
            "coherence",
            crate::io_rules::excerpt(text),
            "expected an inline table { kind = … }",
        ));
    };
    let f = Fields::new(file, "coherence", t);
    let c = coherence_from_fields(&f, width_m)?;
    coherence_finish(&f)?;
    Ok(c)
}

/// The unknown-key check of a `road.coherence` table `cf`: `kind` ([`input_keys::COHERENCE`]) and the keys of
/// the table of its kind.
///
/// # Errors
/// The first key that the coherence's kind does not take.
fn coherence_finish(cf: &Fields) -> Result<()> {
    let kind = cf.get("kind").and_then(|v| v.as_str());
    let table = super::key_table::KEY_TABLES
        .iter()
        .find(|t| t.prefix == input_keys::COHERENCE.prefix && t.kind.is_some() && t.kind == kind);
    match table {
        Some(t) => t.finish(cf, &input_keys::COHERENCE.names()),
        None => input_keys::COHERENCE.finish(cf, &[]),
    }
}

/// The coherence of a `road.coherence` table for tracks `width_m` apart (the keys of the tables
/// [`input_keys::COHERENCE`] and of each kind).
fn coherence_from_fields(cf: &Fields, width_m: f64) -> Result<Arc<dyn Coherence>> {
    let kind = cf.string("kind")?;
    let w = |key: &str, e| cf.wrap(key, e);
    let c: Arc<dyn Coherence> = match kind {
        "dodds-robson" => {
            let waviness = match cf.get("waviness") {
                None => 2.0,
                Some(_) => cf.number("waviness")?,
            };
            Arc::new(IsotropicCoherence::new(width_m, waviness).map_err(|e| w("waviness", e))?)
        }
        "ammon-bormann" => ammon_bormann(cf, width_m)?,
        "tabulated" => {
            let n = cf.numbers("n")?;
            let (key, values) = match (cf.get("squared_coherence"), cf.get("coherence_amplitude")) {
                (Some(_), None) => ("squared_coherence", CoherenceKind::SquaredCoherence),
                (None, Some(_)) => ("coherence_amplitude", CoherenceKind::CoherenceAmplitude),
                _ => {
                    return Err(cf.error(
                        "squared_coherence",
                        "<missing>",
                        "give exactly one of squared_coherence (γ²) or coherence_amplitude (ρ), one value per n",
                    ))
                }
            };
            let v = cf.numbers(key)?;
            Arc::new(TabulatedCoherence::new(n, v, values).map_err(|e| w(key, e))?)
        }
        "constant" => {
            let rho = cf.number("coherence_amplitude")?;
            Arc::new(ConstantCoherence::new(rho).map_err(|e| w("coherence_amplitude", e))?)
        }
        other => {
            return Err(cf.error(
                "kind",
                other,
                "expected dodds-robson, ammon-bormann, tabulated or constant",
            ))
        }
    };
    Ok(c)
}

/// The Ammon–Bormann presets by their `preset` names.
const AMMON_BORMANN_PRESETS: [(&str, AmmonBormannRoad); 10] = [
    ("iso-a", AmmonBormannRoad::IsoA),
    ("iso-b", AmmonBormannRoad::IsoB),
    ("iso-c", AmmonBormannRoad::IsoC),
    ("iso-d", AmmonBormannRoad::IsoD),
    ("iso-e", AmmonBormannRoad::IsoE),
    ("major-road-concrete", AmmonBormannRoad::MajorRoadConcrete),
    (
        "major-road-asphaltic-concrete",
        AmmonBormannRoad::MajorRoadAsphalticConcrete,
    ),
    (
        "main-road-asphaltic-concrete-on-pavement",
        AmmonBormannRoad::MainRoadAsphalticConcreteOnPavement,
    ),
    (
        "main-road-asphaltic-concrete",
        AmmonBormannRoad::MainRoadAsphalticConcrete,
    ),
    (
        "track-tiled-concrete-pavement",
        AmmonBormannRoad::TrackTiledConcretePavement,
    ),
];

/// `kind = "ammon-bormann"`: a `preset`, or `omega_p`, `w`, `p`, `a` and `values`.
fn ammon_bormann(cf: &Fields, width_m: f64) -> Result<Arc<dyn Coherence>> {
    if let Some(v) = cf.get("preset") {
        let Some((_, preset)) = AMMON_BORMANN_PRESETS.iter().find(|(name, _)| v.as_str() == Some(*name)) else {
            return Err(cf.error(
                "preset",
                v,
                "expected iso-a … iso-e, major-road-concrete, major-road-asphaltic-concrete, \
                 main-road-asphaltic-concrete-on-pavement, main-road-asphaltic-concrete or \
                 track-tiled-concrete-pavement",
            ));
        };
        return Ok(Arc::new(
            AmmonBormann::preset(*preset, width_m).map_err(|e| cf.wrap("preset", e))?,
        ));
    }
    let values = match cf.opt_string("values")? {
        None => CoherenceKind::SquaredCoherence,
        Some(s) => s.parse().map_err(|e| cf.wrap("values", e))?,
    };
    let a = match cf.get("a") {
        None => 1.0,
        Some(_) => cf.number("a")?,
    };
    // Ω_p's unit (rad/m)·m^a depends on the exponent a: a plain number in SI
    let omega_p = cf.number_in("omega_p", "(rad/m)·m^a (SI, with a the exponent `a`)")?;
    let (wv, p) = (cf.number("w")?, cf.number("p")?);
    Ok(Arc::new(
        AmmonBormannParameters {
            track_width_m: width_m,
            omega_p,
            w: wv,
            p,
            a,
            kind: values,
        }
        .build()
        .map_err(|e| cf.wrap_param(e, "omega_p"))?,
    ))
}

/// An optional array `key` of `len` values read by `item`.
fn opt_array<T>(
    f: &Fields,
    key: &str,
    len: usize,
    item: impl Fn(&str, &toml::Value) -> Result<T>,
) -> Result<Option<Vec<T>>> {
    let Some(v) = f.get(key) else { return Ok(None) };
    let arr = v.as_array().ok_or_else(|| {
        f.error(
            key,
            v,
            format!("expected an array of {len} values, one per driven input"),
        )
    })?;
    if arr.len() != len {
        return Err(f.error(
            key,
            v,
            format!(
                "{} values for {len} driven inputs (`drives`): need one per driven input",
                arr.len()
            ),
        ));
    }
    arr.iter()
        .enumerate()
        .map(|(k, x)| item(&format!("{key}[{k}]"), x))
        .collect::<Result<Vec<T>>>()
        .map(Some)
}

/// Parses the `[[input]]` tables `tables` of the scenario `f` for a model of `n_inputs` inputs with layout
/// `layout`: the scenario inputs as written and the excitation (one [`Source`] per table, in order).
///
/// # Errors
/// [`crate::Error::File`] naming `input[i].<key>`, the value and the reason: unknown keys, a spectrum that
/// cannot be resolved, a road whose spectrum is not spatial, a missing speed, a model input driven twice
/// or not at all, bad tracks, positions or gains, a cross-spectral matrix that fails its check.
pub(crate) fn parse_inputs(
    f: &Fields,
    tables: &[toml::Value],
    n_inputs: usize,
    layout: &InputLayout,
    speed: Option<f64>,
    catalogue: &Catalogue,
) -> Result<(Vec<ScenarioInput>, Excitation)> {
    if tables.is_empty() {
        return Err(f.error("input", "[]", "no [[input]] table: give at least one"));
    }
    let reader = InputReader {
        f,
        n_tables: tables.len(),
        n_inputs,
        layout,
        speed,
        catalogue,
    };
    let mut inputs = Vec::new();
    let mut sources = Vec::new();
    let mut maps: Vec<Option<(usize, InputMap)>> = vec![None; n_inputs];
    for (i, v) in tables.iter().enumerate() {
        let (input, source) = reader.table(i, v, &inputs, sources.len(), &mut maps)?;
        sources.push(source);
        inputs.push(input);
    }
    let maps = maps
        .into_iter()
        .enumerate()
        .map(|(j, m)| {
            m.map(|(_, x)| x).ok_or_else(|| {
                f.error(
                    "input",
                    format!("model input {j}"),
                    format!("model input {j} is driven by no [[input]] table: add it to some table's drives"),
                )
            })
        })
        .collect::<Result<Vec<_>>>()?;
    let excitation = Excitation::sources(sources, maps).map_err(|e| f.wrap("input", e))?;
    Ok((inputs, excitation))
}

/// What every `[[input]]` table is read against: the scenario, the model's inputs and layout, the common speed.
struct InputReader<'a> {
    f: &'a Fields<'a>,
    n_tables: usize,
    n_inputs: usize,
    layout: &'a InputLayout,
    speed: Option<f64>,
    catalogue: &'a Catalogue,
}

/// The source of one `[[input]]` table: the reference as written, the spectrum file, the source, and the
/// coherence described (a road of two tracks).
type TableSource = (String, SpectrumFile, Source, Option<String>);

/// Where the driven inputs of one table sit: `positions`, `gains` and `tracks` as written (one per driven
/// input), and whether the table is a road of two tracks.
struct Wiring {
    positions: Option<Vec<f64>>,
    gains: Option<Vec<f64>>,
    tracks: Option<Vec<usize>>,
    is_road: bool,
}

impl InputReader<'_> {
    /// Reads table `i` (`v`), after the tables `earlier`, as source number `s`; records the model inputs it
    /// drives in `maps`.
    fn table(
        &self,
        i: usize,
        v: &toml::Value,
        earlier: &[ScenarioInput],
        s: usize,
        maps: &mut [Option<(usize, InputMap)>],
    ) -> Result<(ScenarioInput, Source)> {
        let key = format!("input[{i}]");
        let t = v
            .as_table()
            .ok_or_else(|| self.f.error(&key, v, "expected an [[input]] table"))?;
        let inf = Fields::new(self.f.file(), &key, t);
        // a misspelt key is named before a key it may have meant is reported missing
        if let Some((k, v)) = t.iter().find(|(k, _)| !input_keys::INPUT.contains(k)) {
            let known = input_keys::INPUT.names().join(", ");
            return Err(inf.error(k, v, format!("unknown key (known keys here: {known})")));
        }
        let _ = inf.get("speed"); // read by common_speed
        let _ = inf.get("speed_profile"); // read by common_speed_profile
        let (reference, sf, source, coherence) = self.source(&inf)?;
        let mean = match inf.get("mean") {
            None => 0.0,
            Some(v) => quantity_in_unit(&inf, "mean", v, &sf.unit, &format!("the input process `{reference}`"))?,
        };
        let name = input_name(&inf, i, earlier)?;
        let drives = self.drives(&inf)?;
        let wiring = wiring(&inf, drives.len(), matches!(source, Source::Matrix(_)))?;
        self.map_drives(&inf, i, s, &drives, &wiring, mean, maps)?;
        let kurtosis = super::scenario_file::input_kurtosis(&inf)?;
        if let (Some(_), Source::Matrix(_)) = (kurtosis, &source) {
            return Err(road_kurtosis(&inf));
        }
        inf.finish()?;
        let input = ScenarioInput {
            reference,
            spectrum: sf.spectrum,
            unit: sf.unit,
            origin: sf.origin,
            spectrum_text: sf.text,
            speed: self.speed,
            mean,
            name,
            coherence,
            kurtosis,
        };
        Ok((input, source))
    }

    /// The common speed, or an error at `speed` saying `what` needs it.
    fn need_speed(&self, inf: &Fields, what: &str) -> Result<f64> {
        self.speed.ok_or_else(|| {
            inf.error(
                "speed",
                "<missing>",
                format!("{what}: give the speed (e.g. speed = \"20 m/s\")"),
            )
        })
    }

    /// The source of a table: `spectrum` (one process) or `road` (two tracks).
    fn source(&self, inf: &Fields) -> Result<TableSource> {
        match (inf.get("spectrum"), inf.get("road")) {
            (Some(_), None) => self.process(inf),
            (None, Some(_)) => self.road(inf),
            (Some(_), Some(_)) => Err(inf.error(
                "road",
                "{ … }",
                "give either spectrum (one process) or road (two tracks), not both",
            )),
            (None, None) => Err(inf.error(
                "spectrum",
                "<missing>",
                "give spectrum = … (one process) or road = { spectrum, coherence, track_width } (two tracks)",
            )),
        }
    }

    /// `spectrum = …`: one process (a spatial one at the common speed).
    fn process(&self, inf: &Fields) -> Result<TableSource> {
        let (reference, mut sf) = resolve_spectrum(inf, "spectrum", self.catalogue, self.f.file().parent())?;
        sf.spectrum = super::input_filters::apply_input_keys(inf, &sf, &reference)?;
        let temporal: Arc<dyn Spectrum> = match sf.spectrum.domain() {
            Domain::Temporal => sf.spectrum.clone(),
            Domain::Spatial => {
                let v = self.need_speed(inf, "the spectrum is spatial (a road)")?;
                Arc::new(AtSpeed::new(sf.spectrum.clone(), v).map_err(|e| inf.wrap("speed", e))?)
            }
        };
        Ok((reference, sf, Source::Process(temporal), None))
    }

    /// `road = { spectrum, track_width, coherence }`: a road of two tracks.
    fn road(&self, inf: &Fields) -> Result<TableSource> {
        let rf = inf.sub("road")?;
        let (reference, mut sf) = resolve_spectrum(&rf, "spectrum", self.catalogue, self.f.file().parent())?;
        if sf.spectrum.domain() != Domain::Spatial {
            return Err(rf.error(
                "spectrum",
                &reference,
                "a road of two tracks needs a spatial spectrum (a profile in cycles/m or rad/m)",
            ));
        }
        let width = track_width(&rf, self.layout)?;
        sf.spectrum = super::input_filters::apply_input_keys(inf, &sf, &reference)?;
        let cf = rf.sub("coherence")?;
        let coh = coherence_from_fields(&cf, width)?;
        coherence_finish(&cf)?;
        input_keys::ROAD.finish(&rf, &[])?;
        let v = self.need_speed(inf, "a road is a spatial process")?;
        let desc = coh.describe();
        let tracks = TwoTracks::new(sf.spectrum.clone(), coh, v).map_err(|e| rf.wrap("spectrum", e))?;
        Ok((reference, sf, Source::Matrix(Arc::new(tracks)), Some(desc)))
    }

    /// `drives`: the model inputs the table drives (every one when there is one table and no `drives`).
    fn drives(&self, inf: &Fields) -> Result<Vec<usize>> {
        let last = self.n_inputs as i64 - 1;
        let Some(v) = inf.get("drives") else {
            if self.n_tables == 1 {
                return Ok((0..self.n_inputs).collect());
            }
            return Err(inf.error(
                "drives",
                "<missing>",
                format!("with several [[input]] tables each names the model inputs it drives (0 to {last})"),
            ));
        };
        let arr = v
            .as_array()
            .filter(|a| !a.is_empty())
            .ok_or_else(|| inf.error("drives", v, "expected a non-empty array of model input indices"))?;
        arr.iter()
            .enumerate()
            .map(|(k, x)| {
                x.as_integer()
                    .filter(|j| (0..self.n_inputs as i64).contains(j))
                    .map(|j| j as usize)
                    .ok_or_else(|| {
                        let reason = format!("expected a model input index from 0 to {last}");
                        inf.error(&format!("drives[{k}]"), x, reason)
                    })
            })
            .collect()
    }

    /// Records in `maps` how table `i` (source `s`, of mean `mean`) drives each of `drives`: its track,
    /// delay and gain, as written in `wiring` or else the model's own layout.
    #[allow(clippy::too_many_arguments)]
    fn map_drives(
        &self,
        inf: &Fields,
        i: usize,
        s: usize,
        drives: &[usize],
        wiring: &Wiring,
        mean: f64,
        maps: &mut [Option<(usize, InputMap)>],
    ) -> Result<()> {
        for (k, &j) in drives.iter().enumerate() {
            let (own_track, own_pos, own_gain) = layout_of(self.layout, j);
            let position = wiring.positions.as_ref().map_or(own_pos, |p| p[k]);
            let gain = wiring.gains.as_ref().map_or(own_gain, |g| g[k]);
            let component = match (wiring.is_road, wiring.tracks.as_ref().map(|t| t[k]).or(own_track)) {
                (false, _) => 0,
                (true, Some(c)) => c,
                (true, None) => return Err(no_track(inf, j)),
            };
            let delay = if position == 0.0 {
                0.0
            } else {
                position
                    / self.need_speed(
                        inf,
                        &format!("model input {j} is {position} m behind the first contact"),
                    )?
            };
            if let Some((other, _)) = maps[j] {
                return Err(inf.error(
                    &format!("drives[{k}]"),
                    j,
                    format!("model input {j} is driven by input[{other}] already: each model input by one table"),
                ));
            }
            let map = InputMap {
                source: s,
                component,
                delay,
                gain,
                mean: gain * mean,
            };
            maps[j] = Some((i, map));
        }
        Ok(())
    }
}

/// `road.track_width`, or the model's own; it must be a finite length > 0 equal to the model's.
fn track_width(rf: &Fields, layout: &InputLayout) -> Result<f64> {
    let model_width = match layout {
        InputLayout::TwoTracks { track_width, .. } => *track_width,
        _ => None,
    };
    let width = match (rf.opt_quantity("track_width", Dim::LENGTH)?, model_width) {
        (Some(w), _) => w,
        (None, Some(b)) => b,
        (None, None) => return Err(rf.error("track_width", "<missing>", "required (a length, e.g. \"1.5 m\")")),
    };
    if !(width.is_finite() && width > 0.0) {
        return Err(rf.error("track_width", width, "must be a finite length > 0"));
    }
    if let Some(b) = model_width
        && (width - b).abs() > 1e-9 * b
    {
        return Err(rf.error(
            "track_width",
            rf.get("track_width").map_or(width.to_string(), |v| v.to_string()),
            format!(
                "the model's track width is {b} m (model.track_width): the coherence between the \
                                 tracks is that of tracks {width} m apart, but the wheels run {b} m apart; give \
                                 the model's width (or leave track_width out to use it)"
            ),
        ));
    }
    Ok(width)
}

/// `name` of table `i` (default `input_<i>`): a signal name no earlier table has.
fn input_name(inf: &Fields, i: usize, earlier: &[ScenarioInput]) -> Result<String> {
    let name = inf
        .opt_string("name")?
        .map(str::to_string)
        .unwrap_or_else(|| format!("input_{i}"));
    if name.is_empty() || name.contains(['/', ' ']) {
        return Err(inf.error("name", &name, "a signal name: not empty, without spaces or '/'"));
    }
    if let Some(k) = earlier.iter().position(|x| x.name == name) {
        return Err(inf.error("name", &name, format!("input[{k}] has this name already")));
    }
    Ok(name)
}

/// `positions`, `gains` and `tracks` of a table driving `m` inputs (`is_road`: a road of two tracks).
fn wiring(inf: &Fields, m: usize, is_road: bool) -> Result<Wiring> {
    let positions = opt_array(inf, "positions", m, |k, x| {
        let p = crate::units::parse_value(x, Dim::LENGTH).map_err(|r| inf.error(k, x, r))?;
        if !(p.is_finite() && p >= 0.0) {
            return Err(inf.error(k, x, "must be a finite distance >= 0 behind the first contact"));
        }
        Ok(p)
    })?;
    let gains = opt_array(inf, "gains", m, |k, x| {
        x.as_float()
            .or_else(|| x.as_integer().map(|g| g as f64))
            .filter(|g| g.is_finite())
            .ok_or_else(|| inf.error(k, x, "expected a finite number"))
    })?;
    let tracks = opt_array(inf, "tracks", m, |k, x| track_index(inf, k, x))?;
    if tracks.is_some() && !is_road {
        return Err(inf.error(
            "tracks",
            inf.get("tracks").map_or(String::new(), |v| v.to_string()),
            "only a road of two tracks (road = { … }) has tracks; this input is one process",
        ));
    }
    Ok(Wiring {
        positions,
        gains,
        tracks,
        is_road,
    })
}

/// The error of a road's model input `j` that no track is given for.
fn no_track(inf: &Fields, j: usize) -> crate::Error {
    inf.error(
        "tracks",
        "<missing>",
        format!(
            "model input {j} has no track: name the track of each driven input, \
                                 tracks = [\"left\", \"right\", …]"
        ),
    )
}

/// The error of `kurtosis` in a road of two tracks.
fn road_kurtosis(inf: &Fields) -> crate::Error {
    inf.error(
        "kurtosis",
        inf.get("kurtosis").map_or(String::new(), |v| v.to_string()),
        "a non-Gaussian road of two tracks with a coherence is not available: a Laplace moving average per \
                 track mixed to the prescribed cross-spectrum would not keep the prescribed kurtosis, and no sound \
                 construction of a non-Gaussian pair with a given coherence is implemented; give `kurtosis` to an \
                 [[input]] of one process (spectrum = …), or use a Gaussian road",
    )
}
