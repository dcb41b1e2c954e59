//! A whole Monte Carlo run of a scenario, end to end: realizations in shards, accumulators, statistics with
//! intervals against the analytic values, Welch densities, all written to one HDF5 file
//! ([`crate::store`]) that survives interruption and resumes.
//!
//! # Routes
//! * [`Method::Exact`]: every input spectrum rational and the excitation delay-free. The system augmented
//!   with the inputs' shaping filters is discretised by Van Loan's method ([`augmented_response`]) and
//!   started from its stationary distribution, so every sample of every output is exactly a sample of the
//!   stationary response: no time-step bias, no transient.
//! * [`Method::Spectral`]: any spectrum and delayed inputs (road tracks). The input process is synthesised
//!   by the spectral representation ([`SpectralGenerator`], random Rayleigh amplitudes) on an FFT grid of
//!   N samples, so it is periodic with period NΔt; the recorded output is the periodic steady state of the
//!   exact first-order hold ([`SampledSystem`](super::SampledSystem)) driven by that periodic input. It is computed exactly in
//!   the frequency domain, with one inverse FFT per output: y_k = Σ_j G_j c_j e^{iω_j kΔt}, G_j the
//!   discrete transfer function H_d(ω_j) below (what time stepping through warm-up periods converges to,
//!   without the stepping or the residual transient). Delays τ_j become circular shifts by s_j = τ_j/Δt
//!   samples, which must be integers (Δt = τ/k). An output containing the input derivative (E ≠ 0) gets
//!   E·u̇_k with u̇ the exact derivative of the input's trigonometric interpolant (spectral
//!   differentiation: bin j times iω_j, the Nyquist bin dropped), while the states see the first-order
//!   hold of the samples.
//!
//! # Bias of the spectral route
//! The synthesised process is the spectrum sampled on the grid ω_j = 2πj/(NΔt), j ≤ N/2 (truncated at the
//! Nyquist frequency and piecewise constant in between), and its variance is
//! [`SpectralGenerator::grid_variance`], not the analytic variance. The recorded output is exactly the
//! periodic steady state of the first-order-hold system, whose variance is
//! ```text
//! σ²_d = Σ_j w_j S(ω_j) Δω |H_d(ω_j)|²,   w_j = 2 (1 for j = 0, N/2),
//! H_d(ω) = Σ_inputs g_l e^{−iω s_l Δt} [C (zI − Φ)⁻¹(Γ₀ + zΓ₁) + D + iω E]_l,   z = e^{iωΔt}
//! (the iω E term dropped at the Nyquist bin)
//! ```
//! (for independent inputs the |·|² add). This "discrete" variance is what the Monte Carlo estimates without
//! bias; it is reported next to the analytic one ([`OutputRun::discrete_variance`]). For the exact route it
//! is the stationary variance of the discretised augmented system, equal to the analytic variance.
//!
//! # Statistics
//! Realization i (stream (seed, i)) gives per output the time averages m_i = (1/N)Σ y_k and
//! v_i = (1/N)Σ y_k² of the zero-mean fluctuation (the deterministic mean H(0)·M_u is exact and not
//! simulated). E v_i = σ² exactly (known zero mean, stationary samples), and the v_i are independent
//! across realizations, so the Student-t interval on their mean is a valid interval for σ² by independence
//! and the central limit theorem (approximate at extreme confidence: the v_i are slightly skewed); the σ
//! interval is the square root of its bounds. The mean of the fluctuation gets a Student-t interval around
//! the analytic value 0. Welch densities (Hann, 50 % overlap, M = N/8 capped to 1024) are averaged over
//! realizations, with χ² intervals, and compared with the analytic output density.
//!
//! # Resuming
//! Per shard the file stores, per output, the accumulators `<output>:moments` = [m_i…, v_i…] (zero-padded
//! to 2·shard_size) and `<output>:welch` = [Welch sums…, segments, ν]. A rerun with the same options and
//! scenario reopens the `.tmp`, reads the completed shards' accumulators and computes only the missing
//! shards; since shard results depend only on (seed, i), the final statistics are bit-identical to those
//! of an uninterrupted run.

use super::{augmented_response, foh, run_batch, Amplitudes, GaussMarkov, SpectralGenerator};
use crate::error::{Error, Result};
use crate::estimate::{mean_interval, Interval, Welch, WelchSums};
use crate::response::{analyze_output, output_density, Excitation};
use crate::scenario::Scenario;
use crate::store::{Compression, OutputStatistics, PsdEstimate, RunMetadata, RunWriter, Signal, Statistic};
use nalgebra::DMatrix;
use ndarray::Array2;
use realfft::num_complex::Complex;
use serde::Serialize;
use std::path::{Path, PathBuf};

/// Warm-up criterion for time stepping a system through a periodic input to its periodic steady state:
/// σ_min · (warm-up time) ≥ this (e^{−36} ≈ 2.3·10⁻¹⁶). The spectral route of [`run_scenario`] computes the
/// steady state in the frequency domain and does not need it; time-stepping callers (the benches) do.
pub const WARMUP_DECAY: f64 = 36.0;

/// How realizations are produced (see the module docs).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Default)]
#[serde(rename_all = "kebab-case")]
pub enum Method {
    /// Exact when every input spectrum is rational and the excitation is delay-free, else spectral.
    #[default]
    Auto,
    /// Van Loan discretisation of the system augmented with its shaping filters (stationary start).
    Exact,
    /// Spectral-representation inputs, first-order-hold response, periodic steady state.
    Spectral,
}

impl Method {
    /// Parses `auto`, `exact` or `spectral`.
    ///
    /// # Errors
    /// [`Error::InvalidParameter`] for anything else.
    ///
    /// # Examples
    /// ```
    /// use stochvib::simulate::Method;
    /// assert_eq!(Method::parse("exact").unwrap(), Method::Exact);
    /// assert!(Method::parse("euler").is_err());
    /// ```
    pub fn parse(text: &str) -> Result<Method> {
        match text {
            "auto" => Ok(Method::Auto),
            "exact" => Ok(Method::Exact),
            "spectral" => Ok(Method::Spectral),
            _ => Err(Error::invalid("method", text, "expected auto, exact or spectral")),
        }
    }
}

impl std::str::FromStr for Method {
    type Err = Error;
    fn from_str(s: &str) -> Result<Method> {
        Method::parse(s)
    }
}

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
    pub method: Method,
    /// Confidence of the intervals, in (0, 1).
    pub confidence: f64,
}

impl RunOptions {
    /// Options with shard size 50, no raw data, no compression, [`Method::Auto`], confidence 0.95.
    ///
    /// # Examples
    /// ```
    /// let o = stochvib::simulate::RunOptions::new(100, 10.0, 0.01, 1);
    /// assert_eq!(o.shard_size, 50);
    /// ```
    pub fn new(realizations: usize, duration_s: f64, dt_s: f64, seed: u64) -> RunOptions {
        RunOptions {
            realizations,
            duration_s,
            dt_s,
            seed,
            shard_size: 50,
            store_raw: false,
            compression: Compression::None,
            method: Method::Auto,
            confidence: 0.95,
        }
    }
}

/// An interval in a serialisable form.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct IntervalRow {
    /// Estimate.
    pub estimate: f64,
    /// Lower bound.
    pub lower: f64,
    /// Upper bound.
    pub upper: f64,
    /// Confidence.
    pub confidence: f64,
}

impl From<Interval> for IntervalRow {
    fn from(i: Interval) -> Self {
        IntervalRow {
            estimate: i.estimate,
            lower: i.lower,
            upper: i.upper,
            confidence: i.confidence,
        }
    }
}

impl IntervalRow {
    /// Whether `v` lies in [lower, upper].
    pub fn covers(&self, v: f64) -> bool {
        self.lower <= v && v <= self.upper
    }
}

/// One simulated output's results.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct OutputRun {
    /// Output name.
    pub name: String,
    /// SI unit.
    pub unit: String,
    /// Analytic (reference) variance of the continuous stationary response.
    pub analytic_variance: f64,
    /// Exact variance of the simulated discretised process (see the module docs).
    pub discrete_variance: f64,
    /// Monte Carlo variance with its Student-t interval.
    pub variance: IntervalRow,
    /// Monte Carlo σ: √ of the variance interval.
    pub sigma: IntervalRow,
    /// Mean of the zero-mean fluctuation with its Student-t interval (analytic 0).
    pub fluctuation_mean: IntervalRow,
    /// Whether the σ interval covers the analytic σ.
    pub covers: bool,
    /// Whether the σ interval covers the discrete-process σ.
    pub covers_discrete: bool,
}

/// An output that was not simulated.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct SkippedOutput {
    /// Output name.
    pub name: String,
    /// Why.
    pub reason: String,
}

/// What [`run_scenario`] did.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct RunSummary {
    /// The finished file.
    pub path: PathBuf,
    /// The route taken (never `Auto`).
    pub method: Method,
    /// Generator description (also the file's `@generator`).
    pub generator: String,
    /// Samples per realization.
    pub n_samples: usize,
    /// Time step, s.
    pub dt_s: f64,
    /// Realizations.
    pub n_realizations: usize,
    /// Shards.
    pub n_shards: usize,
    /// Shards found complete in an interrupted run and not recomputed.
    pub resumed_shards: usize,
    /// Simulated outputs.
    pub outputs: Vec<OutputRun>,
    /// Outputs not simulated, with reasons.
    pub skipped: Vec<SkippedOutput>,
    /// Remarks (route, bias).
    pub notes: Vec<String>,
}

impl std::fmt::Display for RunSummary {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        writeln!(f, "run       {}", self.path.display())?;
        writeln!(f, "method    {:?}: {}", self.method, self.generator)?;
        writeln!(
            f,
            "size      {} realizations × {} samples (Δt = {} s), {} shards ({} resumed)",
            self.n_realizations, self.n_samples, self.dt_s, self.n_shards, self.resumed_shards
        )?;
        for n in &self.notes {
            writeln!(f, "note      {n}")?;
        }
        writeln!(
            f,
            "{:<14} {:>13} {:>13} {:>13} {:>27}  covers",
            "output", "analytic σ", "discrete σ", "MC σ", "interval"
        )?;
        for o in &self.outputs {
            writeln!(
                f,
                "{:<14} {:>13.6e} {:>13.6e} {:>13.6e} [{:.6e}, {:.6e}]  {} ({} %)",
                o.name,
                o.analytic_variance.sqrt(),
                o.discrete_variance.sqrt(),
                o.sigma.estimate,
                o.sigma.lower,
                o.sigma.upper,
                if o.covers { "yes" } else { "NO" },
                100.0 * o.sigma.confidence
            )?;
        }
        for s in &self.skipped {
            writeln!(f, "skipped   {}: {}", s.name, s.reason)?;
        }
        Ok(())
    }
}

/// One realization's per-output results.
struct Realization {
    m: Vec<f64>,
    v: Vec<f64>,
    welch: Vec<WelchSums>,
    raw: Vec<Vec<f64>>,
    raw_inputs: Vec<Vec<f64>>,
}

#[allow(clippy::large_enum_variant)] // one engine per run
enum Engine {
    Exact(GaussMarkov),
    Spectral {
        generators: Vec<SpectralGenerator>,
        /// gains[g][r][j]: the transfer from generator g's coefficient c_j to output r (discrete transfer
        /// function, gains, shift phases and the iω_j E term; see the module docs)
        gains: Vec<Vec<Vec<Complex<f64>>>>,
        /// inverse real FFT of size N
        inverse: std::sync::Arc<dyn realfft::ComplexToReal<f64>>,
    },
}

struct Plan {
    method: Method,
    engine: Engine,
    n: usize,
    /// Row stride of the sample buffer: outputs, then (exact route) the recorded input processes.
    stride: usize,
    /// The input processes recorded with the raw data (one per independent process).
    input_signals: Vec<Signal>,
    /// (system output index, name, unit, analytic variance, discrete variance)
    outputs: Vec<(usize, String, String, f64, f64)>,
    skipped: Vec<SkippedOutput>,
    notes: Vec<String>,
    generator: String,
    welch: Welch,
}

/// Names and units of the input processes recorded with raw data: `road` for a road track (m), `input` for
/// a single process, `input_k` for independent processes; the unit is read from the spectrum file.
fn input_signals(sc: &Scenario) -> Vec<Signal> {
    let unit = crate::report::resolve_spectrum(&sc.input_name, &crate::report::default_spectra_dir())
        .map(|f| f.unit)
        .unwrap_or_else(|_| "SI".into());
    match &sc.excitation {
        Excitation::Track { .. } => {
            let name = if sc.input_spectrum.domain() == crate::spectrum::Domain::Spatial {
                "road"
            } else {
                "input"
            };
            vec![Signal::new(name, &unit)]
        }
        Excitation::Independent { spectra, .. } => (0..spectra.len())
            .map(|k| Signal::new(&format!("input_{k}"), &unit))
            .collect(),
    }
}

/// The exact Gauss–Markov system of `outputs` with the input processes appended as extra rows: row k is
/// the output C_F,k x_F,k of process k's shaping filter (None when a filter has a white-noise feedthrough,
/// whose samples are undefined).
fn with_input_rows(
    sys: &dyn crate::system::FrequencyResponse,
    exc: &Excitation,
    outputs: &[usize],
    dt: f64,
) -> Option<GaussMarkov> {
    let ss = sys.state_space()?;
    let mut rows = Vec::new();
    let mut first = None;
    for &i in outputs {
        let aug = crate::response::augmented_system(ss, exc, i).ok()?;
        rows.push(aug.h.clone());
        first.get_or_insert(aug);
    }
    let aug = first?;
    let nz = aug.a.nrows();
    let mut off = 0;
    for sp in exc.spectra() {
        let f = sp.rational()?.shaping_filter().ok()?;
        let tf = crate::system::TransferFunction::new(
            f.num.clone(),
            f.den.clone(),
            crate::system::OutputInfo::new("u", "-"),
        )
        .ok()?;
        let part = crate::system::FrequencyResponse::state_space(&tf)?.clone();
        if part.d[(0, 0)] != 0.0 {
            return None;
        }
        let q = part.n_states();
        let mut h = DMatrix::zeros(1, nz);
        h.view_mut((0, off), (1, q)).copy_from(&part.c);
        rows.push(h);
        off += q;
    }
    let h = DMatrix::from_fn(rows.len(), nz, |r, j| rows[r][(0, j)]);
    GaussMarkov::new(aug.a, aug.g, h, dt).ok()
}

#[allow(clippy::needless_range_loop)] // the bin loop fills several per-bin tables
fn plan(sc: &Scenario, opts: &RunOptions) -> Result<Plan> {
    if opts.realizations < 2 {
        return Err(Error::invalid("realizations", opts.realizations, "need at least 2"));
    }
    if opts.shard_size == 0 {
        return Err(Error::invalid("shard size", 0, "need at least 1"));
    }
    crate::error::require_positive("dt", opts.dt_s)?;
    crate::error::require_positive("duration", opts.duration_s)?;
    if !(opts.confidence > 0.0 && opts.confidence < 1.0) {
        return Err(Error::invalid("confidence", opts.confidence, "must lie in (0, 1)"));
    }
    let mut n = (opts.duration_s / opts.dt_s).round() as usize;
    n += n % 2;
    if n < 16 {
        return Err(Error::invalid(
            "duration",
            format!("{} s", opts.duration_s),
            format!("gives {n} samples at Δt = {} s; need at least 16", opts.dt_s),
        ));
    }
    let sys = sc.model.system.as_ref();
    let exc = &sc.excitation;
    let mut skipped = Vec::new();
    let mut finite = Vec::new();
    for &i in &sc.analysis.outputs {
        let st = analyze_output(sys, exc, i)?;
        match st.variance {
            Some(v) => finite.push((i, st.name, st.unit, v)),
            None => skipped.push(SkippedOutput {
                name: st.name,
                reason: format!(
                    "analytic variance infinite or undefined: {}",
                    st.variance_note.unwrap_or_default()
                ),
            }),
        }
    }
    if finite.is_empty() {
        return Err(Error::invalid(
            "outputs",
            skipped.iter().map(|s| s.name.as_str()).collect::<Vec<_>>().join(", "),
            "no output has a finite variance: nothing to simulate",
        ));
    }
    let idx: Vec<usize> = finite.iter().map(|f| f.0).collect();
    let exact = match opts.method {
        Method::Spectral => None,
        Method::Exact => Some(augmented_response(sys, exc, &idx, opts.dt_s)?),
        Method::Auto => {
            if exc.delay_free() {
                augmented_response(sys, exc, &idx, opts.dt_s).ok()
            } else {
                None
            }
        }
    };
    let mut notes = Vec::new();
    let m_welch = ((n / 8) & !1).clamp(4, 1024);
    let welch = Welch::new(m_welch, opts.dt_s)?;
    let input_signals = input_signals(sc);
    // exact route: append the input processes (shaping-filter outputs) as extra rows of the simulated system
    let exact = exact.map(|gm| with_input_rows(sys, exc, &idx, opts.dt_s).unwrap_or(gm));
    if let Some(gm) = exact {
        let cov = gm.output_covariance();
        let outputs = finite
            .into_iter()
            .enumerate()
            .map(|(r, (i, name, unit, v))| (i, name, unit, v, cov[(r, r)]))
            .collect();
        notes.push(
            "exact route: Van Loan discretisation of the system with its shaping filters, stationary start (no \
             time-step bias, no transient)"
                .into(),
        );
        let stride = gm.n_outputs();
        let input_signals = if stride == idx.len() + input_signals.len() {
            input_signals
        } else {
            vec![]
        };
        return Ok(Plan {
            method: Method::Exact,
            engine: Engine::Exact(gm),
            n,
            stride,
            input_signals,
            outputs,
            skipped,
            notes,
            generator: format!(
                "{}, stream (seed, i) per realization; exact Van Loan discretisation of the system augmented \
                 with its shaping filters, stationary start",
                super::GENERATOR
            ),
            welch,
        });
    }
    // Spectral route
    let ss = sys.state_space().ok_or_else(|| Error::Numerical {
        what: "spectral Monte Carlo".into(),
        reason: "the system has no finite state-space form".into(),
    })?;
    let kept = finite;
    let p_kept = kept.len();
    let rows: Vec<usize> = kept.iter().map(|f| f.0).collect();
    let sub = ss.select_outputs(&rows)?;
    let sigma_min =
        ss.a.complex_eigenvalues()
            .iter()
            .map(|l| -l.re)
            .fold(f64::INFINITY, f64::min);
    if sigma_min.is_nan() || sigma_min <= 0.0 {
        return Err(Error::Numerical {
            what: "spectral Monte Carlo".into(),
            reason: format!(
                "the system is not asymptotically stable (min −Re λ = {sigma_min:e}): no stationary response"
            ),
        });
    }
    let period = n as f64 * opts.dt_s;
    notes.push(format!(
        "spectral route: periodic input of period NΔt = {period} s; the recorded period is the periodic steady \
         state of the first-order-hold system, computed exactly in the frequency domain (one inverse FFT per \
         output; slowest decay rate min|Re λ| = {sigma_min:.4e} 1/s)"
    ));
    let (generators, inputs) = match exc {
        Excitation::Track {
            spectrum,
            delays,
            gains,
            ..
        } => {
            let g = SpectralGenerator::new(spectrum.as_ref(), opts.dt_s, n, Amplitudes::Rayleigh)?;
            let t0 = delays.iter().copied().fold(f64::INFINITY, f64::min);
            let mut inp = Vec::new();
            for (j, (&tau, &gain)) in delays.iter().zip(gains).enumerate() {
                let s = ((tau - t0) / opts.dt_s).round();
                if ((s * opts.dt_s) - (tau - t0)).abs() > 1e-9 * (tau - t0).max(opts.dt_s) {
                    let k = ((tau - t0) / opts.dt_s).ceil().max(1.0);
                    return Err(Error::invalid(
                        "dt",
                        format!("{} s", opts.dt_s),
                        format!(
                            "input {j} is delayed by {} s, not an integer number of steps (exact delays need \
                             τ = s·Δt, i.e. positions multiples of vΔt); choose e.g. Δt = {:e} s",
                            tau - t0,
                            (tau - t0) / k
                        ),
                    ));
                }
                inp.push((0, gain, s as usize % n));
            }
            (vec![g], inp)
        }
        Excitation::Independent { spectra, .. } => {
            let gens = spectra
                .iter()
                .map(|s| SpectralGenerator::new(s.as_ref(), opts.dt_s, n, Amplitudes::Rayleigh))
                .collect::<Result<Vec<_>>>()?;
            (gens, (0..spectra.len()).map(|j| (j, 1.0, 0)).collect())
        }
    };
    // exact variance of the simulated (grid, first-order-hold, periodic) process
    let f = foh(&sub.a, &sub.b, opts.dt_s)?;
    let nst = sub.n_states();
    let dw = 2.0 * std::f64::consts::PI / period;
    let mut disc = vec![0.0; kept.len()];
    let mut gains = vec![vec![vec![Complex::new(0.0, 0.0); n / 2 + 1]; kept.len()]; generators.len()];
    let spectra = exc.spectra();
    let to_c = |m: &DMatrix<f64>| m.map(|v| Complex::new(v, 0.0));
    let (phi, g0, g1, c, d) = (
        to_c(&f.phi),
        to_c(&f.gamma0),
        to_c(&f.gamma1),
        to_c(&sub.c),
        to_c(&sub.d),
    );
    for j in 0..=n / 2 {
        let w = j as f64 * dw;
        let weight = if j == 0 || j == n / 2 { 1.0 } else { 2.0 };
        let z = Complex::new(0.0, w * opts.dt_s).exp();
        let zi = DMatrix::<Complex<f64>>::identity(nst, nst) * z - &phi;
        let rhs = &g0 + &g1 * z;
        let x = zi.lu().solve(&rhs).ok_or_else(|| Error::Numerical {
            what: "discrete transfer function".into(),
            reason: format!("zI − Φ singular at ω = {w:e}"),
        })?;
        let mut h = &c * x + &d; // p × m
        if j < n / 2 {
            h += to_c(&sub.e) * Complex::new(0.0, w);
        }
        for (r, dv) in disc.iter_mut().enumerate() {
            for (gi, gen) in generators.iter().enumerate() {
                let s = spectra[gi].density(w);
                let mut acc = Complex::new(0.0, 0.0);
                for (l, &(src, gain, shift)) in inputs.iter().enumerate() {
                    if src == gi {
                        acc += h[(r, l)] * gain * Complex::new(0.0, -w * shift as f64 * opts.dt_s).exp();
                    }
                }
                let _ = gen;
                gains[gi][r][j] = acc;
                *dv += weight * s * dw * acc.norm_sqr();
            }
        }
    }
    notes.push(
        "spectral route bias: the synthesised input is the spectrum on the FFT grid (truncated at Nyquist, \
         sampled at Δω = 2π/(NΔt)); `discrete σ` is the exact σ of that simulated process"
            .into(),
    );
    let outputs = kept
        .into_iter()
        .zip(disc)
        .map(|((i, name, unit, v), dv)| (i, name, unit, v, dv))
        .collect();
    Ok(Plan {
        method: Method::Spectral,
        engine: Engine::Spectral {
            generators,
            gains,
            inverse: realfft::RealFftPlanner::<f64>::new().plan_fft_inverse(n),
        },
        n,
        stride: p_kept,
        input_signals,
        outputs,
        skipped,
        notes,
        generator: format!(
            "{}, stream (seed, i) per realization; spectral representation (Rayleigh amplitudes) on an FFT grid of \
             N = {n}, first-order-hold response (periodic steady state, frequency domain)",
            super::GENERATOR
        ),
        welch,
    })
}

struct Scratch {
    x: Vec<f64>,
    buf: Vec<f64>,
    q: Vec<Vec<f64>>,
    spec: Vec<super::SpectralScratch>,
    welch: crate::estimate::WelchScratch,
    fft_in: Vec<f64>,
    fft_out: Vec<Complex<f64>>,
    fft_scratch: Vec<Complex<f64>>,
}

fn realize(
    plan: &Plan,
    s: &mut Scratch,
    rng: &mut rand::rngs::Xoshiro256PlusPlus,
    keep_raw: bool,
) -> Result<Realization> {
    let n = plan.n;
    let p = plan.outputs.len();
    match &plan.engine {
        Engine::Exact(gm) => {
            gm.initial_state(rng, &mut s.x);
            gm.advance(&mut s.x, rng, &mut s.buf);
        }
        Engine::Spectral {
            generators,
            gains,
            inverse,
        } => {
            let fft_err = |e: realfft::FftError| Error::Numerical {
                what: "inverse real FFT".into(),
                reason: e.to_string(),
            };
            for (g, sc) in generators.iter().zip(s.spec.iter_mut()) {
                g.draw(rng, sc);
            }
            let half = n / 2;
            for r in 0..p {
                // output r's coefficients: Σ_g G_{g,r}(ω_j) c_{g,j}, then one inverse FFT
                for (j, o) in s.fft_out.iter_mut().enumerate() {
                    let mut acc = Complex::new(0.0, 0.0);
                    for (gain, sc) in gains.iter().zip(&s.spec) {
                        acc += gain[r][j] * sc.coefficients()[j];
                    }
                    *o = acc;
                }
                s.fft_out[0].im = 0.0;
                s.fft_out[half].im = 0.0;
                inverse
                    .process_with_scratch(&mut s.fft_out, &mut s.fft_in, &mut s.fft_scratch)
                    .map_err(fft_err)?;
                for (k, v) in s.fft_in.iter().enumerate() {
                    s.buf[k * p + r] = *v;
                }
            }
            if keep_raw {
                for (q, sc) in s.q.iter_mut().zip(&s.spec) {
                    for (o, c) in s.fft_out.iter_mut().zip(sc.coefficients()) {
                        *o = *c;
                    }
                    inverse
                        .process_with_scratch(&mut s.fft_out, q, &mut s.fft_scratch)
                        .map_err(fft_err)?;
                }
            }
        }
    }
    let stride = plan.stride;
    let mut out = Realization {
        m: Vec::with_capacity(p),
        v: Vec::with_capacity(p),
        welch: Vec::with_capacity(p),
        raw: Vec::new(),
        raw_inputs: Vec::new(),
    };
    if keep_raw {
        match &plan.engine {
            Engine::Exact(_) => {
                for r in p..stride {
                    out.raw_inputs.push((0..n).map(|k| s.buf[k * stride + r]).collect());
                }
            }
            // the recorded period is aligned with the input processes' own samples
            Engine::Spectral { .. } => out.raw_inputs = s.q.clone(),
        }
    }
    let mut sig = vec![0.0; n];
    for r in 0..p {
        for (k, v) in sig.iter_mut().enumerate() {
            *v = s.buf[k * stride + r];
        }
        out.m.push(sig.iter().sum::<f64>() / n as f64);
        out.v.push(sig.iter().map(|v| v * v).sum::<f64>() / n as f64);
        let mut ws = plan.welch.sums();
        plan.welch.accumulate(&sig, &mut ws, &mut s.welch)?;
        out.welch.push(ws);
        if keep_raw {
            out.raw.push(sig.clone());
        }
    }
    Ok(out)
}

/// Runs the Monte Carlo batch of a scenario and writes the HDF5 file `out` (see the module docs); resumes
/// an interrupted run of the same scenario and options from `<out>.tmp`. `progress(done, total)` is called
/// after every shard written (and once at the start with the resumed count).
///
/// # Errors
/// Invalid options ([`Error::InvalidParameter`]); [`Method::Exact`] requested for an excitation that does
/// not allow it; delays that are not whole steps (spectral route); no output with a finite variance; the
/// store's errors (an existing `out` is never overwritten).
///
/// # Examples
/// ```
/// use stochvib::simulate::{run_scenario, Method, RunOptions};
/// use stochvib::scenario::load_scenario;
/// use std::path::Path;
/// let sc = load_scenario(Path::new("data/conveyor-idler.toml"), Path::new("spectra")).unwrap();
/// let out = std::env::temp_dir().join(format!("stochvib-doc-run-{}.h5", std::process::id()));
/// # let _ = std::fs::remove_file(&out);
/// let s = run_scenario(&sc, &RunOptions::new(20, 5.0, 0.01, 1), &out, &|done, total| eprintln!("{done}/{total}"))
///     .unwrap();
/// assert_eq!(s.method, Method::Exact); // exponential (rational) lump load, one input
/// // the exact route simulates the stationary response: its variance is the analytic one
/// assert!((s.outputs[0].discrete_variance / s.outputs[0].analytic_variance - 1.0).abs() < 1e-6);
/// # std::fs::remove_file(&out).unwrap();
/// ```
pub fn run_scenario(
    sc: &Scenario,
    opts: &RunOptions,
    out: &Path,
    progress: &dyn Fn(usize, usize),
) -> Result<RunSummary> {
    let plan = plan(sc, opts)?;
    let n = plan.n;
    let p = plan.outputs.len();
    let shard_size = opts.shard_size.min(opts.realizations);
    let nbins = plan.welch.segment_len() / 2 + 1;
    let mut accumulators = Vec::new();
    for o in &plan.outputs {
        accumulators.push((format!("{}:moments", o.1), 2 * shard_size));
        accumulators.push((format!("{}:welch", o.1), nbins + 2));
    }
    let meta = RunMetadata {
        scenario_text: sc.text.clone(),
        seed: opts.seed,
        generator: plan.generator.clone(),
        dt: opts.dt_s,
        n_samples: n,
        n_realizations: opts.realizations,
        shard_size,
        inputs: if opts.store_raw {
            plan.input_signals.clone()
        } else {
            vec![]
        },
        outputs: plan.outputs.iter().map(|o| Signal::new(&o.1, &o.2)).collect(),
        accumulators,
        store_raw: opts.store_raw,
        compression: opts.compression,
    };
    let mut writer = RunWriter::create(out, &meta)?;
    let n_shards = meta.n_shards();
    let done0 = writer.completed_shards();
    let resumed_shards = done0.len();
    progress(resumed_shards, n_shards);
    let mut done = resumed_shards;
    let (nx, nq, nfft) = match &plan.engine {
        Engine::Exact(gm) => (gm.n_states(), 0, 0),
        Engine::Spectral {
            generators, inverse, ..
        } => (0, generators.len(), inverse.get_scratch_len()),
    };
    for shard in writer.pending_shards() {
        let range = meta.shard_range(shard);
        let batch = run_batch(
            opts.seed,
            range.start as u64..range.end as u64,
            || Scratch {
                x: vec![0.0; nx],
                buf: vec![0.0; n * plan.stride],
                q: vec![vec![0.0; n]; nq],
                spec: match &plan.engine {
                    Engine::Spectral { generators, .. } => generators.iter().map(|g| g.scratch()).collect(),
                    Engine::Exact(_) => vec![],
                },
                welch: plan.welch.scratch(),
                fft_in: vec![0.0; n],
                fft_out: vec![Complex::new(0.0, 0.0); n / 2 + 1],
                fft_scratch: vec![Complex::new(0.0, 0.0); nfft],
            },
            |s, _i, rng| realize(&plan, s, rng, opts.store_raw),
        );
        let results: Vec<Realization> = batch.into_results().into_iter().collect::<Result<_>>()?;
        let rows = results.len();
        let mut accs: Vec<Vec<f64>> = Vec::with_capacity(2 * p);
        for r in 0..p {
            let mut mom = vec![0.0; 2 * shard_size];
            for (k, re) in results.iter().enumerate() {
                mom[k] = re.m[r];
                mom[shard_size + k] = re.v[r];
            }
            let mut ws = plan.welch.sums();
            for re in &results {
                ws.merge(&re.welch[r])?;
            }
            let mut wv = ws.sum.clone();
            wv.push(ws.segments as f64);
            wv.push(ws.dof);
            accs.push(mom);
            accs.push(wv);
        }
        let raw: Vec<Array2<f64>> = if opts.store_raw {
            (0..p)
                .map(|r| Array2::from_shape_fn((rows, n), |(i, k)| results[i].raw[r][k]))
                .collect()
        } else {
            vec![]
        };
        let raw_in: Vec<Array2<f64>> = if opts.store_raw {
            (0..plan.input_signals.len())
                .map(|r| Array2::from_shape_fn((rows, n), |(i, k)| results[i].raw_inputs[r][k]))
                .collect()
        } else {
            vec![]
        };
        let views: Vec<_> = raw.iter().map(|a| a.view()).collect();
        let in_views: Vec<_> = raw_in.iter().map(|a| a.view()).collect();
        let acc_refs: Vec<&[f64]> = accs.iter().map(|a| a.as_slice()).collect();
        writer.write_shard(shard, &in_views, &views, &acc_refs)?;
        done += 1;
        progress(done, n_shards);
    }
    // statistics from the accumulators of every shard, in shard order
    let mut stats = Vec::new();
    let mut psds = Vec::new();
    let mut runs = Vec::new();
    let conf = opts.confidence;
    for (i, name, unit, analytic, discrete) in &plan.outputs {
        let mut m = Vec::with_capacity(opts.realizations);
        let mut v = Vec::with_capacity(opts.realizations);
        let mut ws = plan.welch.sums();
        for shard in 0..n_shards {
            let rows = meta.shard_range(shard).len();
            let mom = writer.read_accumulator(&format!("{name}:moments"), shard)?;
            m.extend_from_slice(&mom[..rows]);
            v.extend_from_slice(&mom[shard_size..shard_size + rows]);
            let wv = writer.read_accumulator(&format!("{name}:welch"), shard)?;
            ws.merge(&WelchSums {
                sum: wv[..nbins].to_vec(),
                segments: wv[nbins] as u64,
                dof: wv[nbins + 1],
            })?;
        }
        let mi = mean_interval(&m, conf)?;
        let vi = mean_interval(&v, conf)?;
        let si = Interval {
            estimate: vi.estimate.max(0.0).sqrt(),
            lower: vi.lower.max(0.0).sqrt(),
            upper: vi.upper.max(0.0).sqrt(),
            confidence: conf,
        };
        let var_unit = format!("({unit})^2");
        let stat = |sname: &str, iv: &Interval, u: &str, method: &str, a: f64| Statistic {
            name: sname.into(),
            estimate: iv.estimate,
            lower: iv.lower,
            upper: iv.upper,
            confidence: conf,
            unit: u.into(),
            method: method.into(),
            analytic: Some(a),
            covers: Some(iv.covers(a)),
        };
        stats.push(OutputStatistics {
            output: name.clone(),
            unit: unit.clone(),
            n_used: opts.realizations as u64,
            statistics: vec![
                stat(
                    "mean",
                    &mi,
                    unit,
                    "time average of the zero-mean fluctuation per realization; Student-t across realizations \
                     (the deterministic mean H(0)·M_u is not simulated)",
                    0.0,
                ),
                stat(
                    "variance",
                    &vi,
                    &var_unit,
                    "time average of y² per realization (known zero mean, unbiased); Student-t across \
                     independent realizations (CLT); analytic = reference analytic variance",
                    *analytic,
                ),
                stat(
                    "sigma",
                    &si,
                    unit,
                    "square root of the variance interval; analytic σ",
                    analytic.sqrt(),
                ),
                stat(
                    "sigma_discrete",
                    &si,
                    unit,
                    "as sigma, compared with the exact σ of the simulated discretised process",
                    discrete.sqrt(),
                ),
            ],
        });
        let est = plan.welch.finish(&ws)?;
        let mut lower = Vec::with_capacity(est.density.len());
        let mut upper = Vec::with_capacity(est.density.len());
        for j in 0..est.density.len() {
            let iv = est.interval(j, conf)?;
            lower.push(iv.lower);
            upper.push(iv.upper);
        }
        let analytic_psd = est
            .omega
            .iter()
            .map(|&w| output_density(sc.model.system.as_ref(), &sc.excitation, *i, w))
            .collect();
        psds.push(PsdEstimate {
            output: name.clone(),
            unit: format!("({unit})^2 s/rad"),
            omega: est.omega.clone(),
            density: est.density.clone(),
            lower,
            upper,
            analytic: Some(analytic_psd),
            dof: est.dof,
            confidence: conf,
            method: format!(
                "Welch, Hann window of {} samples, 50 % overlap, averaged over realizations; χ² interval with \
                 Welch's equivalent ν",
                plan.welch.segment_len()
            ),
        });
        runs.push(OutputRun {
            name: name.clone(),
            unit: unit.clone(),
            analytic_variance: *analytic,
            discrete_variance: *discrete,
            variance: vi.into(),
            sigma: si.into(),
            fluctuation_mean: mi.into(),
            covers: si.covers(analytic.sqrt()),
            covers_discrete: si.covers(discrete.sqrt()),
        });
    }
    writer.write_statistics(&stats)?;
    for psd in &psds {
        writer.write_psd(psd)?;
    }
    let path = writer.finish()?;
    Ok(RunSummary {
        path,
        method: plan.method,
        generator: plan.generator,
        n_samples: n,
        dt_s: opts.dt_s,
        n_realizations: opts.realizations,
        n_shards,
        resumed_shards,
        outputs: runs,
        skipped: plan.skipped,
        notes: plan.notes,
    })
}

/// A time step and duration for a quick run of `sc`: Δt = π/(8·ω_max) with ω_max the largest |λ| of the
/// system matrix (or of its natural frequencies), at most π/ω_hi for an input band ending at ω_hi, shortened
/// so that track delays are whole steps; duration 20/σ_min (σ_min = min|Re λ|), at least 32π/ω_lo for an
/// input band starting at ω_lo > 0 (grid Δω ≤ ω_lo/16), at least 64 and at most 2¹⁵ steps.
///
/// # Errors
/// A system without state space or natural frequencies.
///
/// # Examples
/// ```
/// use stochvib::scenario::load_scenario;
/// use std::path::Path;
/// let sc = load_scenario(Path::new("data/half-car.toml"), Path::new("spectra")).unwrap();
/// let (dt, duration) = stochvib::simulate::suggest_step(&sc).unwrap();
/// // the wheelbase delay L/v = 2.7 m / 10 m/s is a whole number of steps
/// let steps = 0.27 / dt;
/// assert!((steps - steps.round()).abs() < 1e-9 && duration > 64.0 * dt);
/// ```
pub fn suggest_step(sc: &Scenario) -> Result<(f64, f64)> {
    let sys = sc.model.system.as_ref();
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
            "scenario",
            sc.path.display(),
            "cannot suggest a time step: give --dt and --duration",
        ));
    }
    let mut dt = std::f64::consts::PI / (8.0 * wmax);
    // a band-limited input: the Nyquist frequency above the band's upper edge, and the FFT grid
    // Δω = 2π/T at most 1/16 of its lower edge (spectral route)
    let (lo, hi) = sc.excitation.support();
    if hi.is_finite() && hi > 0.0 {
        dt = dt.min(std::f64::consts::PI / hi);
    }
    let min_duration = if lo > 0.0 && lo.is_finite() {
        32.0 * std::f64::consts::PI / lo
    } else {
        0.0
    };
    if let Excitation::Track { delays, .. } = &sc.excitation {
        let t0 = delays.iter().copied().fold(f64::INFINITY, f64::min);
        if let Some(tau) = delays.iter().map(|t| t - t0).filter(|t| *t > 0.0).reduce(f64::min) {
            // the smallest non-zero delay as a whole number of steps (other delays must be its multiples)
            dt = tau / (tau / dt).ceil();
        }
    }
    let duration = (20.0 / smin).max(min_duration).clamp(64.0 * dt, 32768.0 * dt);
    Ok((dt, duration))
}
