//! Options of a Monte Carlo run, the route that produces the realizations, and the suggested time step.

use super::RunInput;
use crate::error::{require_positive, Error, Result};
use crate::numbers::num;
use crate::response::Excitation;
use crate::store::Compression;
use serde::Serialize;

/// How realizations are produced (see [`crate::simulate::run`](mod@crate::simulate::run) for the two routes).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Default, clap::ValueEnum)]
#[serde(rename_all = "kebab-case")]
pub enum Route {
    /// Exact when every input spectrum is rational and the excitation is delay-free, else spectral.
    #[default]
    Auto,
    /// Van Loan discretisation of the system augmented with its shaping filters (stationary start).
    Exact,
    /// Spectral-representation inputs, first-order-hold response, periodic steady state.
    Spectral,
    /// Streamed spectral synthesis (statistics only): white noise through FIR kernels designed from the
    /// spectrum and the first-order-hold response, by overlap-save in time order, with memory independent of
    /// the duration ([`FirSynthesis`](super::FirSynthesis)). [`Route::Auto`] takes it where the spectral route
    /// would be taken but its whole-record buffers exceed the available memory.
    SpectralStream,
}

impl Route {
    /// The name used on the command line and in JSON (`auto`, `exact`, `spectral`, `spectral-stream`).
    pub fn name(self) -> &'static str {
        match self {
            Route::Auto => "auto",
            Route::Exact => "exact",
            Route::Spectral => "spectral",
            Route::SpectralStream => "spectral-stream",
        }
    }
}

impl std::str::FromStr for Route {
    type Err = Error;

    /// Parses `auto`, `exact`, `spectral` or `spectral-stream`.
    ///
    /// # Examples
    /// ```
    /// use stochvib::simulate::Route;
    /// assert_eq!("exact".parse::<Route>().unwrap(), Route::Exact);
    /// assert!("euler".parse::<Route>().is_err());
    /// ```
    fn from_str(text: &str) -> Result<Route> {
        [Route::Auto, Route::Exact, Route::Spectral, Route::SpectralStream]
            .into_iter()
            .find(|r| r.name() == text)
            .ok_or_else(|| Error::invalid("route", text, "expected auto, exact, spectral or spectral-stream"))
    }
}

/// Default [`RunOptions::block_steps`]: 2¹⁴ steps (a few hundred kB per thread).
pub const DEFAULT_BLOCK_STEPS: usize = 1 << 14;

/// Most samples of one realization (2⁵⁰ ≈ 1.1·10¹⁵): the count T/Δt is checked against it before it
/// becomes an integer, so that no duration and step overflow it.
pub const MAX_SAMPLES: usize = 1 << 50;

/// Options of a Monte Carlo run.
#[derive(Debug, Clone, PartialEq)]
pub struct RunOptions {
    /// Number of realizations (≥ 2).
    pub realizations: usize,
    /// Duration of each recorded realization, s (N = round(T/Δt), made even; N ≥ 16).
    pub duration_s: f64,
    /// Time step Δt, s.
    pub dt_s: f64,
    /// Master seed; realization i uses stream (seed, i).
    pub seed: u64,
    /// Realizations per shard (the unit of writing and resuming).
    pub shard_size: usize,
    /// Store every realization of every output (else only accumulators and statistics).
    pub store_raw: bool,
    /// Compression of the raw datasets.
    pub compression: Compression,
    /// Route.
    pub route: Route,
    /// Confidence of the intervals, in (0, 1).
    pub confidence: f64,
    /// Time steps generated at once by the exact route of a statistics-only run (memory O(block), whatever
    /// the duration), and the least number of samples per block of the streamed spectral route (whole
    /// overlap-save segments); the statistics are bit-identical for any value.
    pub block_steps: usize,
    /// Fraction of each output's variance the kernels of the streamed spectral route may leave outside
    /// their window, in (0, 0.1] (default [`TAIL_FRACTION`](super::fir_stream::TAIL_FRACTION), where the
    /// choice is justified): the streamed variance is biased low by at most this fraction.
    pub stream_tail: f64,
    /// Replace an existing finished run file (only at the final rename, after the new run is complete),
    /// and discard an interrupted run of different settings.
    pub overwrite: bool,
    /// Compute only this part of the realizations (a shard file of a cluster run, see
    /// [`Part`](crate::store::Part)), or the whole run (`None`).
    pub part: Option<crate::store::Part>,
    /// The longest run accepted, hours: a run whose time estimate (a lower bound,
    /// [`resources::run_time_lower_bound`](super::resources::run_time_lower_bound)) is longer is refused
    /// before anything is computed or written (default
    /// [`DEFAULT_MAX_HOURS`](super::resources::DEFAULT_MAX_HOURS), `--max-hours`).
    pub max_hours: f64,
}

impl Default for RunOptions {
    /// The four sizes of a run left unset — 0 realizations, NaN duration and time step, seed 0 — so that a run
    /// refuses options that do not name them ([`RunOptions::samples`]); shard size 50, no raw data, no
    /// compression, [`Route::Auto`], confidence 0.95, and the defaults of the other fields. Name the sizes
    /// with the struct update syntax (duration and time step cannot be swapped unseen):
    ///
    /// # Examples
    /// ```
    /// use stochvib::simulate::RunOptions;
    /// let o = RunOptions { realizations: 100, duration_s: 10.0, dt_s: 0.01, seed: 1, ..RunOptions::default() };
    /// assert_eq!((o.shard_size, o.samples().unwrap()), (50, 1000));
    /// assert!(RunOptions::default().samples().is_err());
    /// ```
    fn default() -> RunOptions {
        RunOptions {
            realizations: 0,
            duration_s: f64::NAN,
            dt_s: f64::NAN,
            seed: 0,
            shard_size: 50,
            store_raw: false,
            compression: Compression::None,
            route: Route::Auto,
            confidence: 0.95,
            block_steps: DEFAULT_BLOCK_STEPS,
            stream_tail: super::fir_stream::TAIL_FRACTION,
            overwrite: false,
            part: None,
            max_hours: super::resources::DEFAULT_MAX_HOURS,
        }
    }
}

impl RunOptions {
    /// Checks the options and returns the number of samples per realization, N = round(T/Δt) made even.
    ///
    /// # Errors
    /// [`Error::InvalidParameter`] naming the option: fewer than 2 realizations, shard size 0, Δt or T not
    /// positive, confidence outside (0, 1), fewer than 16 samples.
    pub fn samples(&self) -> Result<usize> {
        if self.realizations < 2 {
            return Err(Error::invalid("realizations", self.realizations, "need at least 2"));
        }
        if self.shard_size == 0 {
            return Err(Error::invalid("shard size", 0, "need at least 1"));
        }
        if self.block_steps == 0 {
            return Err(Error::invalid("block steps", 0, "need at least 1"));
        }
        if !(self.stream_tail > 0.0 && self.stream_tail <= 0.1) {
            return Err(Error::invalid(
                "stream tail",
                self.stream_tail,
                "the tolerated tail of the streamed kernels must lie in (0, 0.1]",
            ));
        }
        require_positive("dt", self.dt_s)?;
        require_positive("duration", self.duration_s)?;
        if self.max_hours.is_nan() || self.max_hours <= 0.0 {
            return Err(Error::invalid(
                "max hours",
                self.max_hours,
                "the cap on a run's computing time must be > 0 hours",
            ));
        }
        if !(self.confidence > 0.0 && self.confidence < 1.0) {
            return Err(Error::invalid("confidence", self.confidence, "must lie in (0, 1)"));
        }
        let ratio = (self.duration_s / self.dt_s).round();
        // NaN (0/0 cannot happen: both are > 0) and infinity fail this too
        let (d, dt) = (num(self.duration_s), num(self.dt_s));
        if ratio.is_nan() || ratio > MAX_SAMPLES as f64 {
            return Err(Error::invalid(
                "duration",
                format!("{d} s at Δt = {dt} s"),
                format!(
                    "gives {ratio:.4e} samples per realization, more than the 2⁵⁰ ≈ 1.126e15 a realization may \
                     have: a shorter --duration or a longer --dt"
                ),
            ));
        }
        let mut n = ratio as usize;
        n += n % 2;
        if n < 16 {
            return Err(Error::invalid(
                "duration",
                format!("{d} s at Δt = {dt} s"),
                format!("gives {n} samples per realization; need at least 16: a longer --duration or a shorter --dt"),
            ));
        }
        Ok(n)
    }
}

/// A time step and duration suggested by [`suggest_step`], with the reasons.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct StepSuggestion {
    /// Δt, s.
    pub dt_s: f64,
    /// Duration of a realization, s.
    pub duration_s: f64,
    /// How they were chosen.
    pub reason: String,
}

/// A time step and duration for a quick run: Δt = π/(8·ω_max) with ω_max the largest |λ| of the system
/// matrix (or of its natural frequencies), at most π/ω_hi for an input band ending at ω_hi, rounded down to a
/// readable value that keeps track delays whole steps ([`readable_step`]); duration 20/σ_min (σ_min =
/// min|Re λ|), at least 32π/ω_lo for an input band starting at ω_lo > 0 (grid Δω ≤ ω_lo/16), at least 64 and
/// at most 2¹⁵ steps. A scenario's own suggestion (`Scenario::suggest_step`) starts from this one and adds what
/// its verdicts, band tables and the discretisation bias need.
///
/// # Errors
/// [`Error::InvalidParameter`] for a system without state space or natural frequencies, or without a
/// positive decay rate: then the step must be given.
///
/// # Examples
/// ```
/// use stochvib::scenario::load_scenario;
/// use std::path::Path;
/// let sc = load_scenario(Path::new("data/half-car.toml"), Path::new("spectra")).unwrap();
/// let s = stochvib::simulate::suggest_step(&sc.run_input()).unwrap();
/// // the wheelbase delay L/v = 2.7 m / 10 m/s is a whole number of steps
/// let steps = 0.27 / s.dt_s;
/// assert!((steps - steps.round()).abs() < 1e-9 && s.duration_s > 64.0 * s.dt_s);
/// ```
pub fn suggest_step(input: &RunInput) -> Result<StepSuggestion> {
    let sys = input.system;
    let (wmax, smin) = match sys.state_space() {
        Some(ss) => {
            let ev = ss.a.complex_eigenvalues();
            (
                ev.iter().map(|l| l.norm()).fold(0.0, f64::max),
                ev.iter()
                    .map(|l| -l.re)
                    .filter(|s| *s > 0.0)
                    .fold(f64::INFINITY, f64::min),
            )
        }
        None => {
            let w = sys.natural_frequencies();
            let wmax = w.iter().copied().fold(0.0, f64::max);
            (wmax, w.iter().copied().fold(f64::INFINITY, f64::min) * 0.05)
        }
    };
    if !(wmax > 0.0 && smin.is_finite() && smin > 0.0) {
        return Err(Error::invalid(
            "dt",
            "<not given>",
            "cannot suggest a time step (no eigenvalues with a positive decay rate): give --dt and --duration",
        ));
    }
    let mut dt = std::f64::consts::PI / (8.0 * wmax);
    let mut reason = format!("Δt = π/(8·{wmax:.4e} rad/s) from the fastest pole");
    // a band-limited input: the Nyquist frequency above the band's upper edge, and the FFT grid
    // Δω = 2π/T at most 1/16 of its lower edge (spectral route)
    let (lo, hi) = input.excitation.support();
    if hi.is_finite() && hi > 0.0 && std::f64::consts::PI / hi < dt {
        dt = std::f64::consts::PI / hi;
        reason = format!("Δt = π/ω_hi with the input band ending at {hi:.4e} rad/s");
    }
    let min_duration = if lo > 0.0 && lo.is_finite() {
        32.0 * std::f64::consts::PI / lo
    } else {
        0.0
    };
    let delays = match input.excitation {
        Excitation::Track { delays, .. } => delays.clone(),
        Excitation::Sources { inputs, .. } => inputs.iter().map(|m| m.delay).collect(),
        Excitation::Independent { .. } => Vec::new(),
    };
    let (dt, how) = readable_step(dt, &delays);
    reason.push_str(&how);
    let duration = readable_duration((20.0 / smin).max(min_duration)).clamp(64.0 * dt, 32768.0 * dt);
    reason.push_str(&format!(
        "; duration 20/σ_min with σ_min = {smin:.4e} 1/s (slowest decay), rounded up to two significant digits, \
         within 64..32768 steps"
    ));
    Ok(StepSuggestion {
        dt_s: dt,
        duration_s: duration,
        reason,
    })
}

/// Readable mantissas of a suggested time step (×10ᵏ), largest first: neighbours differ by at most a factor
/// 4/3, so rounding down costs at most a third more steps.
const READABLE: [f64; 11] = [8.0, 6.0, 5.0, 4.0, 3.0, 2.5, 2.0, 1.5, 1.25, 1.2, 1.0];

/// The largest readable time step m·10ᵏ ≤ `dt_max` (m from 1, 1.2, 1.25, 1.5, 2, 2.5, 3, 4, 5, 6, 8) that
/// keeps every relative delay τ_j − min τ a whole number of steps (relative 10⁻⁹, as the spectral route
/// requires), tried down to `dt_max`/10; if none fits, Δt = τ/⌈τ/dt_max⌉ of the smallest relative delay τ
/// (a whole fraction of it, not rounded). Returns Δt and a note.
///
/// # Examples
/// ```
/// use stochvib::simulate::readable_step;
/// assert_eq!(readable_step(0.0444, &[]).0, 0.04);
/// assert_eq!(readable_step(6.25e-4, &[]).0, 6e-4);
/// // a wheelbase delay of 0.27 s: 0.015 s is 18 steps
/// assert_eq!(readable_step(0.016875, &[0.0, 0.27]).0, 0.015);
/// ```
pub fn readable_step(dt_max: f64, delays: &[f64]) -> (f64, String) {
    let t0 = delays.iter().copied().fold(f64::INFINITY, f64::min);
    let rel: Vec<f64> = delays.iter().map(|t| t - t0).filter(|t| *t > 0.0).collect();
    let whole = |dt: f64| {
        rel.iter()
            .all(|&tau| ((tau / dt).round() * dt - tau).abs() <= 1e-9 * tau.max(dt))
    };
    let top = dt_max.log10().floor() as i32;
    for k in (top - 1..=top).rev() {
        for &m in &READABLE {
            // m·10ᵏ written through a decimal string: 0.015, not 0.015000000000000001
            let dt: f64 = format!("{m}e{k}").parse().unwrap_or(f64::NAN);
            if dt <= dt_max * (1.0 + 1e-12) && whole(dt) {
                let note = if rel.is_empty() {
                    format!(", rounded down to {dt} s")
                } else {
                    format!(", rounded down to {dt} s (every delay a whole number of steps)")
                };
                return (dt, note);
            }
        }
    }
    let tau = rel.iter().copied().fold(f64::INFINITY, f64::min);
    let dt = tau / (tau / dt_max).ceil();
    (dt, format!(", shortened to a whole fraction of the delay {tau:.4e} s"))
}

/// A duration rounded up to two significant digits (176.05 s → 180 s, 4.739 s → 4.8 s).
///
/// # Examples
/// ```
/// assert_eq!(stochvib::simulate::readable_duration(176.05), 180.0);
/// assert_eq!(stochvib::simulate::readable_duration(4.739), 4.8);
/// ```
pub fn readable_duration(d: f64) -> f64 {
    if !(d.is_finite() && d > 0.0) {
        return d;
    }
    let k = d.log10().floor() as i32 - 1;
    let m = (d / 10f64.powi(k) * (1.0 - 1e-12)).ceil();
    format!("{m}e{k}").parse().unwrap_or(d)
}
