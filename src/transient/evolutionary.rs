//! The evolutionary-spectrum route (frozen system, slowly varying input) for inputs without a finite shaping
//! filter: tabulated, measured or band-limited spectra under an envelope, a speed profile or a schedule.

use super::series::{OutputSeries, TransientSolution};
use super::{Envelope, SpeedProfile, Start, StepReport, SystemFamily};
use crate::error::{Error, Result};
use crate::response::{spectral_moment_quadrature, Excitation};
use crate::spectrum::{AtSpeed, Domain, Spectrum};
use crate::system::{FrequencyResponse, StateSpace};
use std::sync::Arc;

/// The largest first-order error estimate δ(t) (relative, on the variance) at which the route still reports
/// a value: 5 %.
pub const DEFAULT_MAX_ERROR: f64 = 0.05;

/// The input of the evolutionary route: u(t) = a(t)·(M_u + s(t)) with s a stationary temporal process, or a
/// spatial road traversed at v(t), felt by the system inputs with `gains`.
#[derive(Debug, Clone)]
pub struct EvolutionaryInput {
    /// The process (temporal, or spatial with `speed`).
    pub spectrum: Arc<dyn Spectrum>,
    /// v(t) for a spatial spectrum.
    pub speed: Option<SpeedProfile>,
    /// a(t).
    pub envelope: Envelope,
    /// M_u.
    pub mean: f64,
    /// Gain at each system input.
    pub gains: Vec<f64>,
}

/// The route's answer: the output statistics over time (NaN where the assumption fails), and per output
/// and time the first-order error estimate δ(t) of the variance.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct EvolutionarySolution {
    /// mean(t), σ(t), σ_ẏ(t) (ρ = 0 in the frozen stationary state); `error_estimate` is max over the
    /// outputs of δ(t).
    pub solution: TransientSolution,
    /// δ(t) per output.
    pub error_estimate: Vec<Vec<f64>>,
    /// τ(t) = 1/min|Re λ(A(t))|, the memory of the frozen system (decay time of its impulse response), s (∞
    /// where the frozen system is not asymptotically stable).
    pub relaxation_time: Vec<f64>,
    /// The threshold on δ above which a value is not reported.
    pub max_error: f64,
}

/// The temporal evolutionary spectrum of the input at t (without the envelope): S_s(ω), or S_Ω(ω/v)/v.
fn spectrum_at(input: &EvolutionaryInput, t: f64) -> Result<Option<Arc<dyn Spectrum>>> {
    match (input.spectrum.domain(), &input.speed) {
        (Domain::Temporal, _) => Ok(Some(input.spectrum.clone())),
        (Domain::Spatial, Some(v)) if v.speed(t) > 0.0 => {
            Ok(Some(Arc::new(AtSpeed::new(input.spectrum.clone(), v.speed(t))?)))
        }
        (Domain::Spatial, Some(_)) => Ok(None),
        (Domain::Spatial, None) => Err(Error::invalid(
            "speed",
            "<missing>",
            "a road (spatial) spectrum needs a speed or a speed profile",
        )),
    }
}

/// Per output at one time: (mean, σ², λ₂) of the frozen stationary state.
type PointStats = Vec<(f64, f64, f64)>;

/// The frozen stationary statistics at t: per output (mean, σ², λ₂), and τ(t). A standing vehicle on a road
/// (v = 0) or an unstable frozen system gives NaN.
fn frozen_point(
    family: &dyn SystemFamily,
    input: &EvolutionaryInput,
    t: f64,
    outputs: usize,
) -> Result<(PointStats, f64)> {
    let ss = family.at(t)?.ss;
    let abscissa = ss.spectral_abscissa();
    let tau = if abscissa < 0.0 { -1.0 / abscissa } else { f64::INFINITY };
    let nan = vec![(f64::NAN, f64::NAN, f64::NAN); outputs];
    let Some(spec) = spectrum_at(input, t)? else {
        return Ok((nan, tau));
    };
    if !tau.is_finite() {
        return Ok((nan, tau));
    }
    let a = input.envelope.value(t);
    let gains: Vec<f64> = input.gains.iter().map(|g| g * a).collect();
    let exc = Excitation::track(spec, vec![0.0; gains.len()], gains.clone(), input.mean)?;
    let mean = static_mean(&ss, &gains, input.mean);
    let stats = (0..outputs)
        .map(|i| {
            let l0 = spectral_moment_quadrature(&ss, &exc, i, 0).map_or(f64::NAN, |q| q.value);
            let l2 = spectral_moment_quadrature(&ss, &exc, i, 2).map_or(f64::NAN, |q| q.value);
            (mean[i], l0, l2)
        })
        .collect();
    Ok((stats, tau))
}

/// (D − CA⁻¹B)·g·M_u, the frozen static response to the input's mean (NaN for a singular A).
fn static_mean(ss: &StateSpace, gains: &[f64], mean: f64) -> Vec<f64> {
    let p = ss.c.nrows();
    if mean == 0.0 {
        return vec![0.0; p];
    }
    let g = nalgebra::DVector::from_column_slice(gains) * mean;
    match ss.a.clone().lu().solve(&(&ss.b * &g)) {
        Some(x) => (&ss.d * &g - &ss.c * x).iter().copied().collect(),
        None => vec![f64::NAN; p],
    }
}

/// The central difference of y on the grid t at k (one-sided at the ends).
fn rate(t: &[f64], y: &[f64], k: usize) -> f64 {
    let (a, b) = (k.saturating_sub(1), (k + 1).min(t.len() - 1));
    if a == b {
        0.0
    } else {
        (y[b] - y[a]) / (t[b] - t[a])
    }
}

/// δ_k = E(t_k)/Σ(t_k) of one output, with the lag E of the relaxation model ė = −e/τ − Σ̇ in absolute
/// value: E_k = E_{k−1}e^{−h/τ} + |Σ_k − Σ_{k−1}|·τ(1 − e^{−h/τ})/h (Σ linear and τ its mean over the
/// interval), E_0 = Σ(0) after a start from rest, else 0. 0 where Σ = E = 0; ∞ where Σ or τ is not finite.
fn error_estimates(times: &[f64], var: &[f64], tau: &[f64], start: &Start) -> Vec<f64> {
    let mut lag = match start {
        Start::Rest => var[0],
        _ => 0.0,
    };
    (0..times.len())
        .map(|k| {
            if k > 0 {
                let (h, tm) = (times[k] - times[k - 1], 0.5 * (tau[k] + tau[k - 1]));
                let decay = (-h / tm).exp();
                lag = lag * decay + (var[k] - var[k - 1]).abs() * tm * (-(-h / tm).exp_m1()) / h;
            }
            match (lag, var[k]) {
                (l, _) if l.is_nan() => f64::INFINITY,
                (l, s) if l == 0.0 && s == 0.0 => 0.0,
                (l, s) => l / s,
            }
        })
        .collect()
}

/// σ_y(t) of every output of `family` under a non-rational input by the evolutionary spectrum, frozen at
/// each time, with a first-order estimate of its error; NaN where that estimate exceeds `max_error`.
///
/// # Formula
/// For a uniformly modulated input u(t) = a(t)s(t), Priestley's evolutionary spectrum is a(t)²S_s(ω); for a
/// road traversed at a slowly varying speed, S_Ω(ω/v(t))/v(t). The route takes the frozen system at t
/// (transfer H_t) in the stationary state of the frozen input:
/// ```text
/// Σ(t) = σ_y²(t) ≈ ∫ |H_t(ω)|² a(t)² S(ω, t) dω,     σ_ẏ²(t) ≈ ∫ ω² |H_t(ω)|² a(t)² S(ω, t) dω,   ρ = 0
/// ```
/// by the crate's adaptive quadrature (band edges and tabulated knots included). This neglects the
/// system's memory: it holds when the input and the system change little over the memory
/// τ(t) = 1/min|Re λ(A(t))| of the frozen system (the decay time of its impulse response). The exact
/// variance relaxes towards Σ, so the lag e = P − Σ follows ė ≈ −e/τ_v − Σ̇ with a relaxation time τ_v
/// between τ/2 (white input: the variance relaxes at twice the rate of the amplitude) and τ (a coloured
/// input, whose memory carries the amplitude's). The route takes τ, the upper end, and reports
/// ```text
/// δ(t) = E(t)/Σ(t),   E(t) = ∫₀ᵗ e^{−(t−s)/τ}|Σ̇(s)|ds + E(0)e^{−t/τ}
/// ```
/// (E(0) = Σ(0) after a start from rest, 0 from the stationary state; Σ linear between the reported
/// times). For white noise through a first-order system E is between 1 and 2 times the true error |P − Σ|
/// (closed forms in the tests); for a coloured (band-limited) input and for a quarter car on a rational
/// road it lies above the true error, which the tests check against Priestley's exact evolutionary
/// variance and the exact route. Priestley, M.B. (1965), "Evolutionary spectra and non-stationary
/// processes", J. R. Stat. Soc. B 27(2), 204–237 (the evolutionary spectrum of an
/// oscillatory process and its slow-variation condition).
///
/// # Errors
/// [`Error::NotApplicable`] ("not available: use Monte Carlo") when δ exceeds `max_error` at every time
/// after the first of every output, or for a stated start (the route starts in the frozen stationary state, or from rest); a
/// road without a speed; the model's errors; `times` not increasing.
pub fn solve_evolutionary(
    family: &dyn SystemFamily,
    input: &EvolutionaryInput,
    start: &Start,
    times: &[f64],
    max_error: f64,
) -> Result<EvolutionarySolution> {
    if let Start::State(_) = start {
        return Err(not_available(
            "a stated start: the route starts stationary or from rest",
        ));
    }
    if times.is_empty()
        || times.iter().any(|t| !t.is_finite())
        || times.windows(2).any(|w| w[1] <= w[0])
        || times[0] < 0.0
    {
        return Err(Error::invalid(
            "times",
            times.len(),
            "finite, >= 0 and strictly increasing",
        ));
    }
    let ss0 = family.at(0.0)?.ss;
    let p = ss0.c.nrows();
    let mut stats = Vec::with_capacity(times.len());
    let mut tau = Vec::with_capacity(times.len());
    for &t in times {
        let (s, r) = frozen_point(family, input, t, p)?;
        stats.push(s);
        tau.push(r);
    }
    let mut errors = Vec::with_capacity(p);
    let outputs: Vec<OutputSeries> = (0..p)
        .map(|i| {
            let var: Vec<f64> = stats.iter().map(|s| s[i].1).collect();
            let delta = error_estimates(times, &var, &tau, start);
            let series = output_series(&ss0.outputs()[i], times, &stats, i, &delta, max_error);
            errors.push(delta);
            series
        })
        .collect();
    // the start itself (t = 0) is exact by construction: the route needs one later time
    if errors
        .iter()
        .all(|e| e.iter().skip(1).all(|d| d.is_nan() || *d > max_error))
    {
        return Err(not_available(&format!(
            "the input or the system changes too fast against the system's memory (first-order error estimate \
             above {max_error} at every time)"
        )));
    }
    let worst = (0..times.len())
        .map(|k| errors.iter().map(|e| e[k]).fold(0.0, f64::max))
        .collect();
    Ok(EvolutionarySolution {
        solution: TransientSolution {
            times: times.to_vec(),
            outputs,
            error_estimate: worst,
            report: StepReport::default(),
            start: start.clone(),
        },
        error_estimate: errors,
        relaxation_time: tau,
        max_error,
    })
}

fn not_available(reason: &str) -> Error {
    Error::NotApplicable {
        method: "evolutionary-spectrum route (frozen system, slowly varying input)".into(),
        reason: format!("{reason}; not available: use Monte Carlo"),
    }
}

/// One output's series from the frozen statistics, NaN where δ > `max_error`.
fn output_series(
    info: &crate::system::OutputInfo,
    times: &[f64],
    stats: &[PointStats],
    i: usize,
    delta: &[f64],
    max_error: f64,
) -> OutputSeries {
    let keep = |k: usize, v: f64| if delta[k] <= max_error { v } else { f64::NAN };
    let mean: Vec<f64> = stats.iter().map(|s| s[i].0).collect();
    let n = times.len();
    OutputSeries {
        name: info.name.clone(),
        unit: info.unit.clone(),
        mean: (0..n).map(|k| keep(k, mean[k])).collect(),
        sigma: (0..n).map(|k| keep(k, stats[k][i].1.sqrt())).collect(),
        mean_rate: (0..n).map(|k| keep(k, rate(times, &mean, k))).collect(),
        sigma_rate: (0..n).map(|k| keep(k, stats[k][i].2.sqrt())).collect(),
        rho: (0..n).map(|k| keep(k, 0.0)).collect(),
        unavailable: None,
        rate_note: stats
            .iter()
            .any(|s| s[i].2.is_nan())
            .then(|| "σ_ẏ is not finite (ẏ has a white component) at some time: no crossing rate there".into()),
    }
}
