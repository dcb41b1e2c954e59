//! Two keys of an input table (`[input]`, an `[[input]]` table, a `[road]` section) that change the input
//! process before it reaches the model: an explicit band, and a tyre's enveloping.
//!
//! # Format
//! ```toml
//! [input]
//! spectrum = "iso8608-d"                                  # any spectrum: a catalogue name, a path, inline
//! band = ["0.011 cycles/m", "30 cycles/m"]                # optional: the band of the process
//! enveloping = { kind = "moving-average", length = "0.25 m" }   # optional, a road only
//! speed = "3 m/s"
//! ```
//! * `band = [low, high]`: frequencies with units of the spectrum's own variable — `cycles/m` or `rad/m`
//!   for a road, `Hz` or `rad/s` for a process in time. A bare `1/m` or `1/s` is refused: it would be read
//!   as rad/m (2π times less than cycles/m), the trap of writing ISO 8608's n with the wrong unit. For a
//!   spectrum that has a band of its own (`iso8608`, `power-law`, `band-white`, including the catalogue's
//!   `iso8608-a` … `-h`) the key replaces that band: the law is continued (or cut) to the new edges. Any
//!   other spectrum is restricted to the band ([`BandLimited`]); a tabulated or measured spectrum cannot
//!   be extended beyond its data, and a band reaching past them is refused.
//! * `enveloping = { kind = "moving-average", length = L }`: the road profile seen through the contact patch
//!   of a pneumatic tyre, a moving average of length L ([`MovingAverage`]:
//!   |H(n)|² = (sin(πnL)/(πnL))², n in cycles/m). Applied after the band, to a spatial spectrum only. The
//!   250 mm average is the smoothing of the golden-car quarter car of the International Roughness Index
//!   (Sayers & Karamihas, *The Little Book of Profiling*, 1998; ASTM E1926).
//!
//! The density is then not rational: the Lyapunov route of the analysis says it does not apply and the
//! variance comes from quadrature; Monte Carlo runs take the spectral route (the exact route needs a
//! rational input). Both keys are part of the scenario's text and of the excitation's description, so a
//! run resumed with other values is refused.

use super::SpectrumFile;
use crate::error::Result;
use crate::fields::Fields;
use crate::spectrum::{BandLimited, Domain, MovingAverage, Spectrum};
use crate::units::Dim;
use std::f64::consts::PI;
use std::sync::Arc;

/// Kinds of spectrum file whose own `band` key the scenario's `band` replaces.
const BANDED_KINDS: [&str; 3] = ["iso8608", "power-law", "band-white"];

/// The spectrum of `sf` with the input table's `band` and `enveloping` keys applied (see the module docs);
/// `reference` is the spectrum as written (for messages).
///
/// # Errors
/// [`crate::Error::File`] naming `band`, `band[k]`, `enveloping` or `enveloping.<key>` of the table: a band
/// that is not two frequencies of the spectrum's variable with units, not 0 ≤ low < high, or past the data of
/// a tabulated spectrum; a band the spectrum's own law rejects (a power law down to 0); an enveloping of a
/// process in time, an unknown kind, a length that is not a length > 0.
pub(crate) fn apply_input_keys(inf: &Fields, sf: &SpectrumFile, reference: &str) -> Result<Arc<dyn Spectrum>> {
    let mut spectrum = sf.spectrum.clone();
    if let Some((lo, hi)) = band(inf, spectrum.domain())? {
        spectrum = with_band(inf, sf, reference, lo, hi)?;
    }
    if inf.get("enveloping").is_some() {
        spectrum = enveloped(inf, spectrum, reference)?;
    }
    Ok(spectrum)
}

/// `band = [low, high]` in rad/s or rad/m (the spectrum's variable), if given.
fn band(inf: &Fields, domain: Domain) -> Result<Option<(f64, f64)>> {
    let Some(v) = inf.get("band") else {
        return Ok(None);
    };
    let (dim, units) = match domain {
        Domain::Spatial => (Dim::WAVENUMBER, "cycles/m or rad/m"),
        Domain::Temporal => (Dim::FREQUENCY, "Hz or rad/s"),
    };
    let arr = v.as_array().filter(|a| a.len() == 2).ok_or_else(|| {
        inf.error(
            "band",
            v,
            format!("expected two frequencies in {units}, e.g. [\"0.011 cycles/m\", \"30 cycles/m\"]"),
        )
    })?;
    let mut edges = [0.0; 2];
    for (k, x) in arr.iter().enumerate() {
        let key = format!("band[{k}]");
        if let Some(s) = x.as_str()
            && !(s.contains("cycle") || s.contains("rad") || s.contains("Hz"))
        {
            return Err(inf.error(
                &key,
                x,
                format!(
                    "write the unit as {units}: a bare 1/m or 1/s is read as rad/m or rad/s, 2π times less than \
                     cycles/m or Hz (ISO 8608's n is in cycles/m)"
                ),
            ));
        }
        edges[k] = inf.angular_frequency(x, &key, dim)?;
    }
    let [lo, hi] = edges;
    if !(lo.is_finite() && hi.is_finite() && lo >= 0.0 && hi > lo) {
        return Err(inf.error("band", v, "need finite edges with 0 <= low < high"));
    }
    Ok(Some((lo, hi)))
}

/// The spectrum of `sf` on the band [lo, hi] (rad/s or rad/m): its own band replaced for a banded kind, a
/// restriction otherwise.
fn with_band(inf: &Fields, sf: &SpectrumFile, reference: &str, lo: f64, hi: f64) -> Result<Arc<dyn Spectrum>> {
    let v = inf.get("band").map_or(String::new(), |v| v.to_string());
    let table: Option<toml::Table> = sf.text.parse().ok();
    let kind = table.as_ref().and_then(|t| t.get("kind")).and_then(|k| k.as_str());
    if let (Some(mut t), Some(kind)) = (table.clone(), kind)
        && BANDED_KINDS.contains(&kind)
    {
        t.insert(
            "band".into(),
            inf.get("band").cloned().unwrap_or(toml::Value::Array(Vec::new())),
        );
        t.remove("unbounded");
        let f = Fields::new(inf.file(), &inf.path("spectrum"), &t);
        return super::spectrum_file::spectrum_from_fields(&f).map_err(|e| {
            let reason = match e {
                crate::Error::File { reason, .. } => reason,
                other => other.to_string(),
            };
            inf.error(
                "band",
                &v,
                format!("the spectrum `{reference}` ({kind}) on this band: {reason}"),
            )
        });
    }
    let (a, b) = sf.spectrum.support();
    let c = |w: f64| w / (2.0 * PI);
    if b.is_finite() && (hi > b * (1.0 + 1e-12) || lo < a * (1.0 - 1e-12)) {
        let unit = sf.spectrum.domain().cyclic_unit();
        return Err(inf.error(
            "band",
            &v,
            format!(
                "the spectrum `{reference}` has data only from {:.6} to {:.6} {unit}: a band can restrict it, not \
                 extend it (give a band within its data, or a power-law spectrum for the wavelengths it lacks)",
                c(a),
                c(b)
            ),
        ));
    }
    Ok(Arc::new(
        BandLimited::new(sf.spectrum.clone(), lo, hi).map_err(|e| inf.wrap("band", e))?,
    ))
}

/// `enveloping = { kind = "moving-average", length = L }` applied to a spatial spectrum.
fn enveloped(inf: &Fields, spectrum: Arc<dyn Spectrum>, reference: &str) -> Result<Arc<dyn Spectrum>> {
    let ef = inf.sub("enveloping")?;
    match ef.string("kind")? {
        "moving-average" => {}
        other => {
            return Err(ef.error(
                "kind",
                other,
                "expected \"moving-average\" (the contact patch averaging the profile over its length)",
            ))
        }
    }
    let length = ef.quantity("length", Dim::LENGTH)?;
    if !(length.is_finite() && length > 0.0) {
        return Err(ef.error(
            "length",
            length,
            "must be a finite length > 0 (a tyre's contact patch: 0.1–0.3 m)",
        ));
    }
    super::input_keys::ENVELOPING.finish(&ef, &[])?;
    if spectrum.domain() != Domain::Spatial {
        return Err(inf.error(
            "enveloping",
            "{ … }",
            format!(
                "a tyre envelops a road profile: the spectrum `{reference}` is a process in time (give enveloping to \
                 a spatial spectrum, in cycles/m or rad/m)"
            ),
        ));
    }
    Ok(Arc::new(
        MovingAverage::new(spectrum, length).map_err(|e| ef.wrap("length", e))?,
    ))
}
