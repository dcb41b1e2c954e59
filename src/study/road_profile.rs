//! What `stochvib road PROFILE.csv` reports, as computed: a measured (or synthetic) road profile's spatial
//! density with its χ² intervals, the ISO 8608 fit (w = 2 fixed and free) with its class, the International
//! Roughness Index, and the coherence of the first two tracks; [`crate::report::road_report`] prints it.

use crate::error::Result;
use crate::road::spatial_psd::check_density_input;
use crate::road::{
    default_segment, fit_iso8608, iri, spatial_cross_spectrum, spatial_psd, Detrend, Profile, Track, Waviness,
};
use serde::Serialize;
use std::path::Path;

/// The goodness-of-fit threshold of the reports ([`crate::road::POWER_LAW_REJECT_P`]).
pub use crate::road::POWER_LAW_REJECT_P;

/// Options of [`road_report`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RoadReportOptions {
    /// Welch segment length M (samples, even); `None`: [`default_segment`].
    pub segment_len: Option<usize>,
    /// Trend removed before the density and the coherence (the IRI uses the profile as read).
    pub detrend: Detrend,
    /// Confidence of the intervals (e.g. 0.95).
    pub confidence: f64,
}

impl Default for RoadReportOptions {
    fn default() -> Self {
        RoadReportOptions {
            segment_len: None,
            detrend: Detrend::Linear,
            confidence: 0.95,
        }
    }
}

/// One bin of a density with its interval.
#[derive(Debug, Clone, Serialize)]
pub struct DensityRow {
    /// n, cycles/m.
    pub n: f64,
    /// Ĝ_d(n), m³ (one-sided, per cycle/m).
    pub g_d: f64,
    /// χ² interval of G_d(n).
    pub lower: f64,
    /// χ² interval of G_d(n).
    pub upper: f64,
}

/// An ISO 8608 fit.
#[derive(Debug, Clone, Serialize)]
pub struct FitRow {
    /// `fixed w = 2` or `free w`.
    pub waviness_mode: String,
    /// G_d(n₀), m³, n₀ = 0.1 cycles/m, with its interval.
    pub g0_m3: f64,
    /// Interval of G_d(n₀).
    pub g0_interval: (f64, f64),
    /// w and its interval (the fixed value twice when fixed).
    pub waviness: f64,
    /// Interval of w.
    pub waviness_interval: (f64, f64),
    /// ISO 8608 class of G_d(n₀).
    pub class: String,
    /// Band fitted, cycles/m.
    pub band: (f64, f64),
    /// Reduced χ² of the fit (≈ 1 for a power-law road).
    pub reduced_chi2: f64,
    /// The probability of a fit this poor or worse for a road that follows the power law
    /// ([`crate::road::IsoFit::fit_p_value`]).
    pub fit_p_value: f64,
    /// Whether the power law describes the track over the band (p ≥ [`crate::road::POWER_LAW_REJECT_P`]);
    /// when not, the class is the level of G_d at n₀ only, not a road of that class.
    pub describes_the_road: bool,
}

/// One track's results.
#[derive(Debug, Clone, Serialize)]
pub struct TrackReport {
    /// Track name (CSV column).
    pub name: String,
    /// σ of the detrended elevation, m.
    pub sigma_m: f64,
    /// IRI, m/km (golden car at 80 km/h, ASTM E1926).
    pub iri_m_per_km: f64,
    /// ISO 8608 fits: w = 2 fixed, then w free.
    pub fits: Vec<FitRow>,
    /// The Welch density, every bin.
    pub density: Vec<DensityRow>,
}

/// One bin of the coherence of two tracks.
#[derive(Debug, Clone, Serialize)]
pub struct CoherenceRow {
    /// n, cycles/m.
    pub n: f64,
    /// γ̂²(n).
    pub squared_coherence: f64,
    /// Fisher-z interval of γ².
    pub lower: f64,
    /// Fisher-z interval of γ².
    pub upper: f64,
}

/// The report of `stochvib road`.
#[derive(Debug, Clone, Serialize)]
pub struct RoadReport {
    /// The file.
    pub file: String,
    /// Distance step, m.
    pub step_m: f64,
    /// Samples per track.
    pub samples: usize,
    /// Length, m.
    pub length_m: f64,
    /// Welch segment M, samples, and the number of segments K.
    pub segment_len: usize,
    /// K.
    pub segments: u64,
    /// Welch's equivalent degrees of freedom per bin.
    pub dof: f64,
    /// Trend removed.
    pub detrend: Detrend,
    /// Confidence of the intervals.
    pub confidence: f64,
    /// Per track.
    pub tracks: Vec<TrackReport>,
    /// Names of the two tracks of the coherence, and its bins (two tracks or more).
    pub coherence_tracks: Option<(String, String)>,
    /// γ̂² per bin.
    pub coherence: Vec<CoherenceRow>,
}

/// Reads `path` ([`Profile::read_csv`]) and computes the report (see the module docs).
///
/// # Formula
/// Ĝ_d by [`spatial_psd()`] on the detrended track, its interval ν Ĝ/χ²_ν; the fits by [`fit_iso8608`]
/// (normal-theory intervals); IRI by [`iri`](fn@iri); γ̂² by [`spatial_cross_spectrum`] with the Fisher-z
/// interval.
///
/// # Errors
/// Everything [`Profile::read_csv`] refuses (naming the file, line, value and reason); a segment longer
/// than the record or odd; a profile shorter than the IRI needs (11 m plus the moving-average base).
///
/// # Examples
/// ```
/// use stochvib::study::road_profile::{road_report, RoadReportOptions};
/// let p = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("data/measured-profile.csv");
/// let r = road_report(&p, &RoadReportOptions::default()).unwrap();
/// assert_eq!(r.tracks.len(), 2);
/// assert_eq!(r.tracks[0].fits[0].class, "C");
/// ```
pub fn road_report(path: &Path, opts: &RoadReportOptions) -> Result<RoadReport> {
    profile_report(&Profile::read_csv(path)?, path, opts)
}

/// The report of a profile already in memory (e.g. arrays from the Python package); `path` names its
/// source in the report and in errors about a track.
///
/// # Errors
/// As [`road_report`], less the reading.
pub fn profile_report(p: &Profile, path: &Path, opts: &RoadReportOptions) -> Result<RoadReport> {
    let n = p.len();
    let detrended = p.detrended(opts.detrend);
    for (t, d) in p.tracks.iter().zip(&detrended.tracks) {
        check_density_input(path, &t.name, &t.elevation_m, &d.elevation_m)?;
    }
    let m = match opts.segment_len {
        None => default_segment(n),
        Some(m) if m >= 4 && m % 2 == 0 && m <= n => m,
        Some(m) => {
            return Err(crate::Error::invalid(
                "--segment",
                m,
                format!("expected an even number of samples from 4 to the profile's {n} samples"),
            ))
        }
    };
    let mut tracks = Vec::new();
    let mut meta = None;
    for (t, d) in p.tracks.iter().zip(&detrended.tracks) {
        let (track, psd) = track_report(t, d, p.step_m, m, opts).map_err(|e| in_track(path, &t.name, e))?;
        tracks.push(track);
        meta = Some((psd.segments, psd.dof));
    }
    let (segments, dof) = meta.unwrap_or((0, 0.0));
    let (coherence_tracks, coherence) = if detrended.tracks.len() >= 2 {
        let (l, r) = (&detrended.tracks[0], &detrended.tracks[1]);
        let cs = spatial_cross_spectrum(&l.elevation_m, &r.elevation_m, p.step_m, m)
            .map_err(|e| in_track(path, &format!("{} and {}", l.name, r.name), e))?;
        let rows = (0..cs.n.len())
            .map(|i| {
                cs.squared_coherence_interval(i, opts.confidence)
                    .map(|iv| CoherenceRow {
                        n: cs.n[i],
                        squared_coherence: iv.estimate,
                        lower: iv.lower,
                        upper: iv.upper,
                    })
            })
            .collect::<Result<Vec<_>>>()?;
        (Some((l.name.clone(), r.name.clone())), rows)
    } else {
        (None, Vec::new())
    };
    Ok(RoadReport {
        file: path.display().to_string(),
        step_m: p.step_m,
        samples: n,
        length_m: p.length_m(),
        segment_len: m,
        segments,
        dof,
        detrend: opts.detrend,
        confidence: opts.confidence,
        tracks,
        coherence_tracks,
        coherence,
    })
}

/// One track's density, ISO 8608 fits and IRI (`t` as read, `d` detrended), and its Welch estimate.
fn track_report(
    t: &Track,
    d: &Track,
    step_m: f64,
    m: usize,
    opts: &RoadReportOptions,
) -> Result<(TrackReport, crate::road::SpatialPsd)> {
    let psd = spatial_psd(&d.elevation_m, step_m, m)?;
    let density = (0..psd.n.len())
        .map(|i| {
            psd.interval(i, opts.confidence).map(|iv| DensityRow {
                n: psd.n[i],
                g_d: psd.g_d[i],
                lower: iv.lower,
                upper: iv.upper,
            })
        })
        .collect::<Result<Vec<_>>>()?;
    let mut fits = Vec::new();
    for (mode, w) in [("fixed w = 2", Waviness::Fixed(2.0)), ("free w", Waviness::Free)] {
        let fit = fit_iso8608(&psd, w, None)?;
        let g = fit.g0_interval(opts.confidence)?;
        let wi = if matches!(w, Waviness::Free) {
            let i = fit.waviness_interval(opts.confidence)?;
            (i.lower, i.upper)
        } else {
            (fit.waviness, fit.waviness)
        };
        fits.push(FitRow {
            waviness_mode: mode.into(),
            g0_m3: fit.g0_m3,
            g0_interval: (g.lower, g.upper),
            waviness: fit.waviness,
            waviness_interval: wi,
            class: format!("{:?}", fit.class),
            band: fit.band,
            reduced_chi2: fit.reduced_chi2,
            fit_p_value: fit.fit_p_value,
            describes_the_road: fit.describes_the_road(),
        });
    }
    let sigma = (d.elevation_m.iter().map(|y| y * y).sum::<f64>() / d.elevation_m.len() as f64).sqrt();
    let track = TrackReport {
        name: t.name.clone(),
        sigma_m: sigma,
        iri_m_per_km: iri(&t.elevation_m, step_m)?.m_per_km,
        fits,
        density,
    };
    Ok((track, psd))
}

/// An error about one track of the profile `path`, naming the file and the column: a fit or an estimate
/// the track is too short (or too coarse) for is a property of the file, not of a library parameter.
fn in_track(path: &Path, track: &str, e: crate::Error) -> crate::Error {
    use crate::Error;
    match e {
        Error::File { .. } | Error::Io { .. } | Error::Parse { .. } => e,
        Error::InvalidParameter { name, value, reason } => Error::in_file(
            path,
            format!("column {track}"),
            value,
            format!("{name}: {reason} (the profile is too short or too coarse for it)"),
        ),
        other => Error::in_file(path, format!("column {track}"), "…", other.to_string()),
    }
}
