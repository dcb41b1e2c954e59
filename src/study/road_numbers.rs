//! Road building blocks as numbers, as computed: `stochvib coherence` (the coherence of a model and/or a
//! measured two-track profile, per frequency) and `stochvib iri` (the expected IRI of a road spectrum beside
//! the IRI of a measured profile); [`crate::report::road_numbers`] prints them.

use crate::coherence::Coherence;
use crate::error::{Error, Result};
use crate::road::{default_segment, expected_iri, iri, spatial_cross_spectrum, Detrend, ExpectedIri, Profile};
use crate::scenario::SpectrumFile;
use serde::Serialize;
use std::path::Path;
use std::sync::Arc;

/// One frequency of a [`CoherenceReport`].
#[derive(Debug, Clone, Copy, Serialize)]
pub struct CoherenceRow {
    /// n, cycles/m.
    pub n: f64,
    /// The model's coherence amplitude ρ(n).
    pub model_coherence_amplitude: Option<f64>,
    /// The model's squared coherence γ²(n) = ρ².
    pub model_squared_coherence: Option<f64>,
    /// The profile's estimate γ̂²(n).
    pub measured_squared_coherence: Option<f64>,
    /// Its Fisher-z interval.
    pub lower: Option<f64>,
    /// Its Fisher-z interval.
    pub upper: Option<f64>,
}

/// The report of `stochvib coherence`.
#[derive(Debug, Clone, Serialize)]
pub struct CoherenceReport {
    /// The model, described.
    pub model: Option<String>,
    /// The profile file.
    pub profile: Option<String>,
    /// The tracks of the estimate.
    pub tracks: Option<(String, String)>,
    /// Confidence of the intervals.
    pub confidence: f64,
    /// Welch segments of the estimate and ν.
    pub segments: Option<(u64, f64)>,
    /// The rows.
    pub rows: Vec<CoherenceRow>,
}

/// The coherence of `model` at `frequencies` (default 0.01–10 cycles/m, four per decade), or at the bins of
/// the measured `profile`'s first two tracks with the model beside.
///
/// # Formula
/// Model: ρ(n) and γ² = ρ² ([`Coherence`]). Profile: γ̂² = |Ĝ_LR|²/(Ĝ_LL Ĝ_RR) of the linearly detrended
/// tracks by Welch ([`spatial_cross_spectrum`]), with the Fisher-z interval.
///
/// # Errors
/// Neither a model nor a profile; a frequency not finite and ≥ 0; a profile of one track; the errors of
/// [`Profile::read_csv`] and of the estimate.
pub fn coherence_report(
    model: Option<Arc<dyn Coherence>>,
    profile: Option<&Path>,
    frequencies: &[f64],
    segment: Option<usize>,
    confidence: f64,
) -> Result<CoherenceReport> {
    if !(confidence > 0.0 && confidence < 1.0) {
        return Err(Error::invalid(
            "--confidence",
            confidence,
            "the confidence of the intervals must lie in (0, 1)",
        ));
    }
    if let Some(f) = frequencies.iter().find(|f| !(f.is_finite() && **f >= 0.0)) {
        return Err(Error::invalid(
            "--frequency",
            f,
            "spatial frequencies must be finite and >= 0 cycles/m",
        ));
    }
    let at = |n: f64| {
        let rho = model.as_ref().map(|m| m.coherence_amplitude(n));
        (rho, rho.map(|r| r * r))
    };
    let mut report = CoherenceReport {
        model: model.as_ref().map(|m| m.describe()),
        profile: profile.map(|p| p.display().to_string()),
        tracks: None,
        confidence,
        segments: None,
        rows: Vec::new(),
    };
    let Some(path) = profile else {
        if model.is_none() {
            return Err(Error::invalid(
                "--model",
                "<none>",
                "give a coherence model (--model) or a profile (--profile)",
            ));
        }
        let ns: Vec<f64> = if frequencies.is_empty() {
            (0..=12).map(|k| 0.01 * 10f64.powf(k as f64 / 4.0)).collect()
        } else {
            frequencies.to_vec()
        };
        report.rows = ns
            .into_iter()
            .map(|n| {
                let (r, g) = at(n);
                CoherenceRow {
                    n,
                    model_coherence_amplitude: r,
                    model_squared_coherence: g,
                    measured_squared_coherence: None,
                    lower: None,
                    upper: None,
                }
            })
            .collect();
        return Ok(report);
    };
    let p = Profile::read_csv(path)?.detrended(Detrend::Linear);
    if p.tracks.len() < 2 {
        return Err(Error::in_file(
            path,
            "header",
            p.tracks.len(),
            "the coherence needs a profile of two tracks",
        ));
    }
    let m = segment.unwrap_or_else(|| default_segment(p.len()));
    let cs = spatial_cross_spectrum(&p.tracks[0].elevation_m, &p.tracks[1].elevation_m, p.step_m, m)
        .map_err(|e| segment_error(e, path, &p, segment))?;
    for i in 0..cs.n.len() {
        let iv = cs
            .squared_coherence_interval(i, confidence)
            .map_err(|e| segment_error(e, path, &p, segment))?;
        let (r, g) = at(cs.n[i]);
        report.rows.push(CoherenceRow {
            n: cs.n[i],
            model_coherence_amplitude: r,
            model_squared_coherence: g,
            measured_squared_coherence: Some(iv.estimate),
            lower: Some(iv.lower),
            upper: Some(iv.upper),
        });
    }
    report.tracks = Some((p.tracks[0].name.clone(), p.tracks[1].name.clone()));
    report.segments = Some((cs.segments, cs.dof));
    Ok(report)
}

/// An error of the coherence estimate named by what the user wrote: the `--segment` flag when it gave the
/// segment (with the profile's length), else the profile itself, whose tracks are too short for the default
/// segment.
fn segment_error(e: Error, path: &Path, p: &Profile, segment: Option<usize>) -> Error {
    let why = match e {
        Error::InvalidParameter { name, value, reason } => format!("{name} = {value}: {reason}"),
        other => return other,
    };
    match segment {
        Some(m) => Error::invalid("--segment", m, format!("{why} (the profile has {} samples)", p.len())),
        None => Error::in_file(
            path,
            format!("column {} and {}", p.tracks[0].name, p.tracks[1].name),
            format!("{} rows", p.len()),
            format!("{why}: the profile is too short for a coherence estimate"),
        ),
    }
}

/// One measured track's IRI.
#[derive(Debug, Clone, Serialize)]
pub struct TrackIri {
    /// Track name.
    pub track: String,
    /// IRI, m/km.
    pub m_per_km: f64,
}

/// The report of `stochvib iri`.
#[derive(Debug, Clone, Serialize)]
pub struct IriReport {
    /// The spectrum's name and description.
    pub spectrum: String,
    /// The expectation from the spectrum.
    pub expected: ExpectedIri,
    /// The profile file and its tracks' IRI.
    pub profile: Option<String>,
    /// Per track.
    pub measured: Vec<TrackIri>,
}

/// The expected IRI of `spectrum` ([`expected_iri`]) beside the IRI of each track of `profile` ([`iri()`]).
///
/// # Errors
/// The errors of [`expected_iri`], [`Profile::read_csv`] and [`iri()`].
pub fn iri_report(spectrum: &SpectrumFile, profile: Option<&Path>) -> Result<IriReport> {
    // a spectrum the IRI does not apply to is named as the user wrote it (the command's SPECTRUM)
    let expected = expected_iri(spectrum.spectrum.as_ref()).map_err(|e| match e {
        Error::NotApplicable { method, reason } => {
            Error::invalid("spectrum", &spectrum.name, format!("{method} does not apply: {reason}"))
        }
        other => other,
    })?;
    let mut measured = Vec::new();
    if let Some(path) = profile {
        let p = Profile::read_csv(path)?;
        for t in &p.tracks {
            measured.push(TrackIri {
                track: t.name.clone(),
                m_per_km: track_iri(path, t, p.step_m)?,
            });
        }
    }
    Ok(IriReport {
        spectrum: format!("{} ({})", spectrum.name, spectrum.description),
        expected,
        profile: profile.map(|p| p.display().to_string()),
        measured,
    })
}

/// The IRI of one track of the profile `path`, m/km; what the IRI refuses (a step longer than 11 m, a
/// track too short) and a non-finite IRI (elevations beyond what f64 sums can hold) name the file and the
/// column.
fn track_iri(path: &Path, t: &crate::road::Track, step_m: f64) -> Result<f64> {
    let key = format!("column {}", t.name);
    let m_per_km = iri(&t.elevation_m, step_m)
        .map_err(|e| match e {
            Error::InvalidParameter { name, value, reason } => Error::in_file(
                path,
                &key,
                &value,
                format!("{name} = {value}: {reason} (the profile is too short or too coarse for the IRI)"),
            ),
            other => other,
        })?
        .m_per_km;
    if !m_per_km.is_finite() {
        let peak = t.elevation_m.iter().fold(0.0f64, |a, z| a.max(z.abs()));
        return Err(Error::in_file(
            path,
            &key,
            format!("largest |elevation| {peak:e} m"),
            "the IRI of this track is not a finite number: its elevations are beyond what the golden car's \
             sums can hold in f64; check the column's values and unit",
        ));
    }
    Ok(m_per_km)
}
