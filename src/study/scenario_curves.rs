//! The curves of a scenario's pictures as plain data: input densities, cross-spectra and coherence of a road
//! of two tracks, |H(iω)|², output densities with their cumulative variance, the weighted density of a
//! comfort axis, the natural-frequency markers and the model correlation of a stored output. Every x value
//! is already in the frequency of the chosen [`Convention`] (f in Hz or n in cycles/m when cyclic, ω or Ω
//! otherwise) and every density in that convention; [`crate::plot`] only draws them.

use crate::coherence::SpectralMatrix;
use crate::comfort::{band_rms, bands_covering, weighted_output, BandFraction};
use crate::error::{Error, Result};
use crate::response::{cumulative_variance, output_density, variance_quadrature, Excitation, Source};
use crate::scenario::Scenario;
use crate::spectrum::{Convention, Domain, Spectrum};
use crate::system::{FrequencyResponse, OutputInfo};
use std::f64::consts::PI;

/// Points (x, y) of one curve.
pub type Points = Vec<(f64, f64)>;

/// A named curve.
#[derive(Debug, Clone, PartialEq)]
pub struct Curve {
    /// Legend text.
    pub name: String,
    /// Its points.
    pub points: Points,
}

/// Fewest points per curve.
const MIN_POINTS: usize = 20;

fn check_points(points: usize) -> Result<()> {
    if points < MIN_POINTS {
        return Err(Error::invalid("points", points, "need at least 20 points per curve"));
    }
    Ok(())
}

/// Densities of one or more spectra of one domain on one log grid covering every spectrum's support and
/// breakpoints, each in `convention` and restricted to its own support; returns the domain and the curves
/// (named as given).
///
/// # Errors
/// [`Error::InvalidParameter`] for no spectra, fewer than 20 points or mixed domains.
pub fn spectra_curves(
    spectra: &[(&str, &dyn Spectrum)],
    convention: Convention,
    points: usize,
) -> Result<(Domain, Vec<Curve>)> {
    if spectra.is_empty() {
        return Err(Error::invalid("spectra", 0, "need at least one spectrum"));
    }
    check_points(points)?;
    let domain = spectra[0].1.domain();
    if spectra.iter().any(|s| s.1.domain() != domain) {
        return Err(Error::invalid(
            "spectra",
            "mixed domains",
            "temporal and spatial spectra need different axes",
        ));
    }
    let (mut lo, mut hi) = (f64::INFINITY, 0.0f64);
    for (_, s) in spectra {
        let (a, b) = spectrum_range(*s, &[]);
        lo = lo.min(a);
        hi = hi.max(b);
    }
    let grid = log_grid(lo, hi, points, &[]);
    let curves = spectra
        .iter()
        .map(|(name, s)| {
            let (slo, shi) = s.support();
            let points = grid
                .iter()
                .filter(|w| **w >= slo && **w <= shi)
                .map(|&w| convention.from_canonical(w, s.density(w)))
                .collect();
            Curve {
                name: name.to_string(),
                points,
            }
        })
        .collect();
    Ok((domain, curves))
}

/// The cross-spectral curves of one road of two tracks, in space (see [`cross_spectra`]).
#[derive(Debug, Clone, PartialEq)]
pub struct CrossSpectrum {
    /// Name of the `[[input]]` source.
    pub input: String,
    /// Its unit as the scenario gives it.
    pub unit: String,
    /// Names of the two tracks (components 0 and 1).
    pub tracks: (String, String),
    /// Density of each track, G_00 = G_11.
    pub auto: Points,
    /// Co-spectrum C = Re G_01.
    pub co: Points,
    /// Quad-spectrum Q = −Im G_01.
    pub quad: Points,
    /// Squared coherence γ² = |G_01|²/(G_00 G_11) (dimensionless y).
    pub coherence: Points,
}

impl CrossSpectrum {
    /// Whether the quad-spectrum is zero everywhere (a real coherence).
    pub fn is_real(&self) -> bool {
        self.quad.iter().all(|p| p.1 == 0.0)
    }
}

/// The cross-spectra of every road of two tracks (`[[input]] road = { … }`) of the scenario against the
/// spatial frequency in `convention`; empty when the scenario has none or no speed.
///
/// # Formula
/// The source is the pair at the speed v (temporal, [`crate::coherence::TwoTracks`]); back in space,
/// S_x(Ω) = v·S_t(vΩ) for every entry of the matrix, then [`Convention::from_canonical`]. The Ω grid is that
/// of the input density of the road's spectrum ([`spectra_curves`]).
///
/// # Errors
/// [`Error::InvalidParameter`] for fewer than 20 points.
pub fn cross_spectra(sc: &Scenario, convention: Convention, points: usize) -> Result<Vec<CrossSpectrum>> {
    let Some((sources, v)) = sources_at_speed(sc) else {
        return Ok(Vec::new());
    };
    check_points(points)?;
    let mut out = Vec::new();
    for (s, m) in multi_component(sources) {
        let Some(inp) = sc.inputs.get(s) else { continue };
        let (lo, hi) = spectrum_range(inp.spectrum.as_ref(), &[]);
        let grid = log_grid(lo, hi, points, &[]);
        let (mut auto, mut co, mut quad, mut coherence) = (Vec::new(), Vec::new(), Vec::new(), Vec::new());
        for &om in &grid {
            let sm = m.matrix(om * v);
            let x = |z: f64| convention.from_canonical(om, v * z);
            auto.push(x(sm[(0, 0)].re));
            co.push(x(sm[(0, 1)].re));
            quad.push(x(-sm[(0, 1)].im));
            coherence.push((x(0.0).0, m.coherence_matrix(om * v)[(0, 1)].norm_sqr()));
        }
        out.push(CrossSpectrum {
            input: inp.name.clone(),
            unit: inp.unit.clone(),
            tracks: (m.component_name(0), m.component_name(1)),
            auto,
            co,
            quad,
            coherence,
        });
    }
    Ok(out)
}

/// The sources of a scenario's excitation and its speed, when it has both.
fn sources_at_speed(sc: &Scenario) -> Option<(&[Source], f64)> {
    let Excitation::Sources { sources, .. } = &sc.excitation else {
        return None;
    };
    Some((sources, sc.input.speed?))
}

/// The sources of more than one component (a road of two tracks) with their index.
fn multi_component(sources: &[Source]) -> impl Iterator<Item = (usize, &dyn SpectralMatrix)> {
    sources.iter().enumerate().filter_map(|(s, src)| match src {
        Source::Matrix(m) if m.n_components() >= 2 => Some((s, m.as_ref())),
        _ => None,
    })
}

/// The squared coherence γ²(n) = |S_01|²/(S_00 S_11) of every multi-component source of the scenario (a
/// road of two tracks, named `<input>: <track 0> and <track 1>`) against the spatial frequency n in
/// cycles/m; `None` when the scenario's excitation has no sources or no speed.
///
/// # Formula
/// ω = 2πnv with v the scenario's speed; γ² = |C_01(ω)|² with C the coherence matrix of the source
/// ([`crate::coherence::SpectralMatrix::coherence_matrix`]); n on a log grid over 1e-3 … 10 cycles/m.
///
/// # Errors
/// [`Error::InvalidParameter`] for fewer than 20 points.
pub fn coherence_curves(sc: &Scenario, points: usize) -> Result<Option<Vec<Curve>>> {
    let Some((sources, v)) = sources_at_speed(sc) else {
        return Ok(None);
    };
    check_points(points)?;
    let mut out = Vec::new();
    for (s, m) in multi_component(sources) {
        let name = sc
            .inputs
            .get(s)
            .map_or_else(|| format!("source {s}"), |i| i.name.clone());
        let points = (0..points)
            .map(|k| {
                let n = 10f64.powf(-3.0 + 4.0 * k as f64 / (points - 1) as f64);
                (n, m.coherence_matrix(2.0 * PI * n * v)[(0, 1)].norm_sqr())
            })
            .collect();
        out.push(Curve {
            name: format!("{name}: {} and {}", m.component_name(0), m.component_name(1)),
            points,
        });
    }
    Ok(Some(out))
}

/// |H_ij(iω)|² of one output for every input j (see [`transfer_curves`]).
#[derive(Debug, Clone, PartialEq)]
pub struct TransferCurves {
    /// The output's name and unit.
    pub output: OutputInfo,
    /// One curve per input j, against the convention's frequency.
    pub per_input: Vec<Points>,
    /// The natural frequencies ([`natural_frequencies`]).
    pub natural: Vec<f64>,
}

/// |H_ij(iω)|² of output `output` for every input j against the frequency of `convention`.
///
/// # Formula
/// The ω grid spans the natural frequencies |λ| and the input's breakpoints and support edges, a decade
/// beyond each side, log-spaced, with the natural frequencies themselves included.
///
/// # Errors
/// [`Error::InvalidParameter`] for an output index out of range.
pub fn transfer_curves(sc: &Scenario, output: usize, convention: Convention, points: usize) -> Result<TransferCurves> {
    let sys = sc.model.system.as_ref();
    let info = output_info(sc, output)?;
    let grid = system_grid(sc, points);
    let mut per_input: Vec<Points> = vec![Vec::with_capacity(grid.len()); sys.n_inputs()];
    for &w in &grid {
        let h = sys.response(w);
        for (j, c) in per_input.iter_mut().enumerate() {
            c.push((frequency(convention, w), h[(output, j)].norm_sqr()));
        }
    }
    Ok(TransferCurves {
        output: info,
        per_input,
        natural: natural_frequencies(sc, convention),
    })
}

/// The output's description, or an error naming the index.
fn output_info(sc: &Scenario, output: usize) -> Result<OutputInfo> {
    let outputs = sc.model.system.outputs();
    outputs
        .get(output)
        .cloned()
        .ok_or_else(|| Error::invalid("output", output, format!("the system has {} outputs", outputs.len())))
}

/// The density of one output and its cumulative variance (see [`output_density_curves`]).
#[derive(Debug, Clone, PartialEq)]
pub struct OutputDensityCurves {
    /// The output's name and unit.
    pub output: OutputInfo,
    /// Its density in the convention.
    pub density: Points,
    /// The cumulative variance against the convention's frequency.
    pub cumulative: Points,
    /// Whether the cumulative variance starts at zero frequency (else at the first point: the density is
    /// not integrable at 0).
    pub from_zero: bool,
    /// The variance over the whole axis; `None` when it diverges.
    pub whole: Option<f64>,
    /// The natural frequencies ([`natural_frequencies`]).
    pub natural: Vec<f64>,
}

/// The density of output `output` in `convention` with its cumulative variance.
///
/// # Formula
/// S_y(ω) = H S_u Hᴴ ([`output_density`]) on the grid of [`transfer_curves`] within the input's support.
/// The cumulative variance at grid point ω_k is σ²(ω_k) = 2∫_0^{ω_k} S_y dω = ∫_0^{f_k} G_y df
/// ([`cumulative_variance`]: adaptive Gauss–Kronrod quadrature segment by segment); the whole-axis variance
/// is [`variance_quadrature`].
///
/// # Errors
/// [`Error::InvalidParameter`] for an output index out of range; [`Error::Numerical`] when the input's
/// support lies outside the grid; quadrature errors.
pub fn output_density_curves(
    sc: &Scenario,
    output: usize,
    convention: Convention,
    points: usize,
) -> Result<OutputDensityCurves> {
    let sys = sc.model.system.as_ref();
    let exc = &sc.excitation;
    let info = output_info(sc, output)?;
    let (slo, shi) = exc.support();
    let grid: Vec<f64> = system_grid(sc, points)
        .into_iter()
        .filter(|w| *w >= slo && *w <= shi)
        .collect();
    if grid.is_empty() {
        return Err(Error::Numerical {
            what: "plot output density".into(),
            reason: "nothing to plot: the input's support lies outside the frequency grid".into(),
        });
    }
    let density = grid
        .iter()
        .map(|&w| convention.from_canonical(w, output_density(sys, exc, output, w)))
        .collect();
    let whole = match variance_quadrature(sys, exc, output) {
        Ok(r) => Some(r.value),
        Err(Error::Divergent { .. }) => None,
        Err(e) => return Err(e),
    };
    let (cumulative, from_zero) = cumulative_variance(sys, exc, output, &grid, whole)?;
    let cumulative = grid
        .iter()
        .zip(cumulative)
        .map(|(&w, v)| (frequency(convention, w), v))
        .collect();
    Ok(OutputDensityCurves {
        output: info,
        density,
        cumulative,
        from_zero,
        whole,
        natural: natural_frequencies(sc, convention),
    })
}

/// The weighted acceleration of one comfort axis (see [`weighted_density`]).
#[derive(Debug, Clone, PartialEq)]
pub struct WeightedDensity {
    /// Name of the weighted output (`<output>_<W>`).
    pub name: String,
    /// Name of the frequency weighting.
    pub weighting: String,
    /// The weighting's evaluation range in Hz.
    pub range_hz: (f64, f64),
    /// One-sided density G_w(f) against f in Hz, 401 log-spaced points over the bands.
    pub density: Points,
    /// The r.m.s. value of every one-third-octave band as a staircase (two points a band).
    pub bands: Points,
    /// The overall a_w over the bands.
    pub a_w: f64,
}

/// The weighted acceleration a_w(t) = W(s)·y(t) of comfort axis `axis` of `[analysis.comfort]`.
///
/// # Formula
/// G_w(f) = 4π·S_w(2πf) with S_w(ω) = |W(iω)|²·S_y(ω) the two-sided density of the weighted output
/// ([`weighted_output`], [`output_density`]); band r.m.s. = (∫_{f₁}^{f₂} G_w df)^{1/2} ([`band_rms`]) over
/// the one-third octaves covering the weighting's range ([`bands_covering`]); a_w = (Σ band mean
/// squares)^{1/2}.
///
/// # Errors
/// [`Error::InvalidParameter`] naming `analysis.comfort.axis` for an axis index the scenario does not
/// have; [`Error::NotApplicable`] for a model without a state-space form; the errors of
/// [`weighted_output`] and [`band_rms`].
pub fn weighted_density(sc: &Scenario, axis: usize) -> Result<WeightedDensity> {
    let spec = sc
        .analysis
        .verdicts
        .comfort
        .as_ref()
        .and_then(|c| c.axes.get(axis))
        .ok_or_else(|| Error::invalid("analysis.comfort.axis", axis, "the scenario has no such comfort axis"))?;
    let ss = sc.model.system.state_space().ok_or_else(|| Error::NotApplicable {
        method: "frequency weighting".into(),
        reason: "the model has no state-space form".into(),
    })?;
    let ws = weighted_output(ss, spec.output, &spec.weighting)?;
    let density_hz = |f: f64| 4.0 * PI * output_density(&ws, &sc.excitation, 0, 2.0 * PI * f);
    let range_hz = spec.weighting.evaluation_range_hz();
    let bands = bands_covering(BandFraction::ThirdOctave, range_hz.0, range_hz.1)?;
    let mut stairs = Vec::with_capacity(2 * bands.len());
    let mut total = 0.0;
    for b in &bands {
        let r = band_rms(&density_hz, b)?;
        total += r * r;
        stairs.push((b.lower_hz, r));
        stairs.push((b.upper_hz, r));
    }
    let (f0, f1) = (bands[0].lower_hz, bands[bands.len() - 1].upper_hz);
    let n = 400;
    let density = (0..=n)
        .map(|k| {
            let f = f0 * (f1 / f0).powf(k as f64 / n as f64);
            (f, density_hz(f))
        })
        .collect();
    Ok(WeightedDensity {
        name: ws.outputs()[0].name.clone(),
        weighting: spec.weighting.name().to_string(),
        range_hz,
        density,
        bands: stairs,
        a_w: total.sqrt(),
    })
}

/// The frequency-axis value of ω in a convention: f = ω/2π (cyclic) or ω.
pub fn frequency(conv: Convention, w: f64) -> f64 {
    if conv.is_cyclic() {
        w / (2.0 * PI)
    } else {
        w
    }
}

/// The system's natural frequencies |λ| (finite, positive, sorted, distinct to 1e-9) in the frequency of
/// `conv`.
pub fn natural_frequencies(sc: &Scenario, conv: Convention) -> Vec<f64> {
    let mut nat: Vec<f64> = positive_natural_frequencies(sc);
    nat.sort_by(|a, b| a.total_cmp(b));
    nat.dedup_by(|a, b| (*a - *b).abs() <= 1e-9 * b.abs());
    nat.into_iter().map(|w| frequency(conv, w)).collect()
}

/// The finite, positive natural frequencies |λ| (rad/s) in the system's order.
fn positive_natural_frequencies(sc: &Scenario) -> Vec<f64> {
    sc.model
        .system
        .natural_frequencies()
        .into_iter()
        .filter(|w| w.is_finite() && *w > 0.0)
        .collect()
}

/// Frequency range of a spectrum for plotting (rad/s or rad/m): its support where finite, otherwise a
/// factor 30 beyond its breakpoints and `hints`.
fn spectrum_range(s: &dyn Spectrum, hints: &[f64]) -> (f64, f64) {
    let (slo, shi) = s.support();
    let marks = s
        .breakpoints()
        .into_iter()
        .chain(hints.iter().cloned())
        .chain([slo, shi]);
    let (mlo, mhi) = positive_span(marks).unwrap_or((0.1, 100.0));
    let lo = if slo > 0.0 && slo.is_finite() { slo } else { mlo / 30.0 };
    let hi = if shi.is_finite() { shi } else { mhi * 30.0 };
    if hi > lo {
        (lo, hi)
    } else {
        (lo / 10.0, lo * 10.0)
    }
}

/// The smallest and largest of the finite, positive `marks`; `None` without one.
fn positive_span(marks: impl Iterator<Item = f64>) -> Option<(f64, f64)> {
    let marks: Vec<f64> = marks.filter(|w| w.is_finite() && *w > 0.0).collect();
    if marks.is_empty() {
        return None;
    }
    Some((
        marks.iter().cloned().fold(f64::INFINITY, f64::min),
        marks.iter().cloned().fold(0.0, f64::max),
    ))
}

/// ω grid (rad/s) for system plots: a decade beyond the natural frequencies and the input's breakpoints
/// and finite support edges.
fn system_grid(sc: &Scenario, points: usize) -> Vec<f64> {
    let nat = positive_natural_frequencies(sc);
    let (slo, shi) = sc.excitation.support();
    let marks = nat.iter().cloned().chain(sc.excitation.breakpoints()).chain([slo, shi]);
    let (lo, hi) = positive_span(marks).map_or((0.1, 100.0), |(a, b)| (a / 10.0, b * 10.0));
    let mut extra = nat;
    extra.extend([slo, shi].into_iter().filter(|w| w.is_finite() && *w > 0.0));
    log_grid(lo, hi, points.max(MIN_POINTS), &extra)
}

/// `n` log-spaced points from `lo` to `hi`, with the `extra` points in range added; sorted, distinct.
fn log_grid(lo: f64, hi: f64, n: usize, extra: &[f64]) -> Vec<f64> {
    let n = n.max(2);
    let r = (hi / lo).ln();
    let mut g: Vec<f64> = (0..n)
        .map(|k| lo * (r * k as f64 / (n - 1) as f64).exp())
        .chain(extra.iter().cloned().filter(|w| *w >= lo && *w <= hi))
        .collect();
    g.sort_by(|a, b| a.total_cmp(b));
    g.dedup_by(|a, b| (*a - *b).abs() <= 1e-12 * b.abs());
    g
}

/// Model correlation K(mΔt), m = 0..=max_lag, of the scenario output `name`, and the frequency step used.
///
/// # Formula
/// K(mΔt) = Σ_{j=0}^{L/2} w_j S_y(ω_j) Δω cos(ω_j mΔt), ω_j = jΔω, Δω = 2π/(LΔt), w_j = 2 except
/// w_0 = w_{L/2} = 1: the two-sided integral ∫ S_y(ω) e^{iωτ} dω over |ω| ≤ π/Δt (the band a record sampled
/// at Δt resolves), evaluated by one inverse real FFT of length L = 2^⌈log₂ max(8N, 2¹⁶)⌉ ≤ 2¹⁸, so the grid
/// is 8× finer than the record's own and resolves narrow density peaks. S_y is the library's analytic output
/// density ([`output_density`]).
pub fn model_correlation(sc: &Scenario, name: &str, dt: f64, n: usize, max_lag: usize) -> Result<(Vec<f64>, f64)> {
    // a weighted output of `[analysis.comfort]` (`<output>_<W>`) is an output of the system the run
    // simulated: the scenario's system extended by the weighting filters
    let extended;
    let mut sys = sc.model.system.as_ref();
    if !sys.outputs().iter().any(|o| o.name == name) && !sc.analysis.verdicts.is_empty() {
        extended = super::verdict_system(sc)?.0;
        sys = &extended;
    }
    let i = sys
        .outputs()
        .iter()
        .position(|o| o.name == name)
        .ok_or_else(|| Error::invalid("output", name, "not an output of the stored scenario"))?;
    let l = (8 * n)
        .max(1 << 16)
        .next_power_of_two()
        .min(1 << 18)
        .max(2 * (max_lag + 1));
    let dw = 2.0 * PI / (l as f64 * dt);
    let mut spec: Vec<realfft::num_complex::Complex<f64>> = (0..=l / 2)
        .map(|j| {
            let s = output_density(sys, &sc.excitation, i, j as f64 * dw);
            realfft::num_complex::Complex::new(s * dw, 0.0)
        })
        .collect();
    let c2r = realfft::RealFftPlanner::<f64>::new().plan_fft_inverse(l);
    let mut k = vec![0.0; l];
    c2r.process(&mut spec, &mut k)
        .map_err(|e| Error::invalid("correlation FFT", l, e.to_string()))?;
    k.truncate(max_lag + 1);
    Ok((k, dw))
}
