//! Planning a run: which outputs can be simulated, which route produces the realizations (and why), the
//! engine of that route, and the exact variance of the simulated discrete process.

use super::engine::{Engine, Gains, RawMix};
use super::fir_stream::{KernelDesign, KernelSpectra, GRID_TOLERANCE};
use super::{
    augmented_response, foh, Amplitudes, FirSynthesis, GaussMarkov, Route, RunInput, RunOptions, SpectralGenerator,
};
use crate::error::{Error, Result};
use crate::estimate::Welch;
use crate::response::{analyze_output, Excitation};
use crate::store::Signal;
use crate::system::{FrequencyResponse, OutputInfo, StateSpace, TransferFunction};
use nalgebra::DMatrix;
use realfft::num_complex::Complex;
use serde::Serialize;

/// An output that is not simulated, with the reason.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct SkippedOutput {
    /// Output name.
    pub name: String,
    /// Why.
    pub reason: String,
}

/// A simulated output: its system row, name, unit and the two reference variances.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct PlannedOutput {
    /// Index of the output in the system.
    pub index: usize,
    /// Name and unit.
    pub signal: Signal,
    /// Analytic variance of the continuous stationary response.
    pub analytic_variance: f64,
    /// Exact variance of the simulated discretised process.
    pub discrete_variance: f64,
    /// Exact marginal kurtosis E y⁴/(E y²)² of the simulated process when an input is non-Gaussian (a
    /// Laplace moving average, [`laplace_generators`]); `None` for Gaussian inputs (kurtosis 3).
    pub kurtosis: Option<f64>,
    /// Exact standard deviation of one realization's mean square v_i = (1/N)Σy_k² on the (whole-record)
    /// spectral route, Gaussian or not ([`mean_square_sd`]); `None` on the other routes. The run checks its
    /// Monte Carlo variance against `discrete_variance` with it ([`super::agreement`]).
    pub mean_square_sd: Option<f64>,
}

/// Everything a run needs besides the file: the route's engine, sizes, outputs and remarks.
pub(crate) struct Plan {
    pub route: Route,
    pub engine: Engine,
    /// Samples per realization.
    pub n: usize,
    /// Row stride of the sample buffer: outputs, then (exact route) the recorded input processes.
    pub stride: usize,
    /// The input processes recorded with the raw data (one per independent process).
    pub input_signals: Vec<Signal>,
    pub outputs: Vec<PlannedOutput>,
    pub skipped: Vec<SkippedOutput>,
    pub notes: Vec<String>,
    pub generator: String,
    pub welch: Welch,
    /// Steps per block of the exact route when no raw data are kept (0: whole realizations).
    pub block_steps: usize,
    /// Exact autocovariance of each simulated output process at lags 0..M (M the Welch segment length):
    /// what the Welch estimate is compared with (window ⊛ sampled-process density).
    pub autocov: Vec<Vec<f64>>,
    /// Estimated working memory of the run, bytes ([`super::resources`]).
    pub memory_bytes: u128,
}

/// The route a run would take and its estimated working memory (see [`planned_memory`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct PlannedMemory {
    /// The route (never [`Route::Auto`]).
    pub route: Route,
    /// Estimated working memory, bytes: for the whole-record routes
    /// [`memory_bytes`](super::resources::memory_bytes), for the streamed spectral route
    /// [`streamed_memory_bytes`](super::resources::streamed_memory_bytes) (independent of the duration).
    pub bytes: u128,
}

/// Plans a run without running it (the kernels of the streamed spectral route are designed) and returns
/// its route and estimated working memory.
///
/// # Formula
/// See [`PlannedMemory::bytes`].
///
/// # Errors
/// As [`run`](super::run()) before it starts: invalid options, no output with a finite variance, a route
/// that does not apply, a run larger than the available memory.
///
/// # Examples
/// ```
/// use stochvib::scenario::load_scenario;
/// use stochvib::simulate::{planned_memory, Route, RunOptions};
/// use std::path::Path;
/// let sc = load_scenario(Path::new("data/conveyor-idler.toml"), Path::new("spectra")).unwrap();
/// let opts = RunOptions { realizations: 20, duration_s: 5.0, dt_s: 0.01, seed: 1, ..RunOptions::default() };
/// let m = planned_memory(&sc.run_input(), &opts).unwrap();
/// assert_eq!(m.route, Route::Exact);
/// assert!(m.bytes > 0);
/// ```
pub fn planned_memory(input: &RunInput, opts: &RunOptions) -> Result<PlannedMemory> {
    let p = plan(input, opts)?;
    Ok(PlannedMemory {
        route: p.route,
        bytes: p.memory_bytes,
    })
}

/// What a run would simulate of one output, without running it ([`planned_variances`]).
#[derive(Debug, Clone, PartialEq)]
pub struct PlannedVariance {
    /// The output.
    pub name: String,
    /// Analytic variance of the continuous stationary response.
    pub analytic: f64,
    /// Exact variance of the simulated discrete process (equal to `analytic` on the exact route; on the
    /// spectral route that of the FFT grid truncated at the Nyquist frequency, through the first-order hold).
    pub discrete: f64,
    /// Coefficient of variation of one realization's mean square on the spectral route (the width of the
    /// run's intervals: a σ interval from R realizations has the relative half-width ≈ z·cv/(2√R));
    /// `None` on the other routes.
    pub mean_square_cv: Option<f64>,
}

impl PlannedVariance {
    /// The discretisation bias of σ, √(discrete/analytic) − 1.
    pub fn bias(&self) -> f64 {
        (self.discrete / self.analytic).sqrt() - 1.0
    }
}

/// The analytic and discrete variance of every simulated output of a run with these options, and the spread
/// of its per-realization mean squares, without running it ([`PlannedVariance`]; on the spectral route the
/// discrete variance agrees with the run's `sigma_discrete` to rounding, not bit for bit).
///
/// # Errors
/// As [`planned_memory`].
pub fn planned_variances(input: &RunInput, opts: &RunOptions) -> Result<Vec<PlannedVariance>> {
    let p = plan_with(input, opts, true)?;
    Ok(p.outputs
        .into_iter()
        .map(|o| PlannedVariance {
            name: o.signal.name,
            analytic: o.analytic_variance,
            discrete: o.discrete_variance,
            // the spread of one realization's mean square relative to its mean, the discrete variance
            mean_square_cv: o.mean_square_sd.map(|sd| sd / o.discrete_variance),
        })
        .collect())
}

/// An output with a finite analytic variance, before the route is chosen.
struct Simulable {
    index: usize,
    info: OutputInfo,
    variance: f64,
}

/// Splits the requested outputs into those with a finite analytic variance and the skipped ones.
fn simulable_outputs(input: &RunInput) -> Result<(Vec<Simulable>, Vec<SkippedOutput>)> {
    let mut finite = Vec::new();
    let mut skipped = Vec::new();
    for &i in &input.outputs {
        let st = analyze_output(input.system, input.excitation, i)?;
        match st.variance {
            Some(v) => finite.push(Simulable {
                index: i,
                info: OutputInfo::new(st.name, st.unit),
                variance: v,
            }),
            None => skipped.push(SkippedOutput {
                name: st.name,
                reason: format!("analytic variance {}", st.variance_outcome.describe()),
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
    Ok((finite, skipped))
}

/// The route choice: the exact engine when it applies (or is required), with the reason.
struct RouteChoice {
    exact: Option<GaussMarkov>,
    reason: String,
}

impl RouteChoice {
    /// [`Route::Exact`] when requested (an error if it does not apply), [`Route::Spectral`] when requested,
    /// and for [`Route::Auto`] the exact route whenever the excitation is delay-free and every input spectrum
    /// has a shaping filter.
    fn choose(input: &RunInput, opts: &RunOptions, idx: &[usize]) -> Result<RouteChoice> {
        let (sys, exc, dt) = (input.system, input.excitation, opts.dt_s);
        if input.is_non_gaussian() {
            let k = input.kurtosis_text();
            return match opts.route {
                Route::Auto | Route::Spectral => Ok(RouteChoice {
                    exact: None,
                    reason: format!(
                        "spectral route: non-Gaussian inputs (kurtosis {k}) are Laplace moving averages synthesised \
                         on the spectral grid"
                    ),
                }),
                Route::Exact | Route::SpectralStream => Err(Error::invalid(
                    "route",
                    opts.route.name(),
                    format!(
                        "an input with kurtosis {k} (a Laplace moving average) is simulated on the spectral route \
                         only: use --route spectral or auto"
                    ),
                )),
            };
        }
        Ok(match opts.route {
            Route::Spectral => RouteChoice {
                exact: None,
                reason: "spectral route requested".into(),
            },
            Route::SpectralStream => RouteChoice {
                exact: None,
                reason: "streamed spectral route requested".into(),
            },
            Route::Exact => RouteChoice {
                exact: Some(augmented_response(sys, exc, idx, dt)?),
                reason: "exact route requested".into(),
            },
            Route::Auto if !exc.delay_free() => RouteChoice {
                exact: None,
                reason: format!(
                    "spectral route: {}, which the exact route cannot represent (pure delays have no finite \
                     state-space form)",
                    exc.inputs_described()
                ),
            },
            Route::Auto => match augmented_response(sys, exc, idx, dt) {
                Ok(gm) => RouteChoice {
                    exact: Some(gm),
                    reason: "exact route: delay-free inputs with rational spectra".into(),
                },
                Err(e) => RouteChoice {
                    exact: None,
                    reason: format!("spectral route: the exact route does not apply ({e})"),
                },
            },
        })
    }
}

/// Plans a run (see the module docs).
///
/// # Errors
/// Invalid options; no output with a finite variance; [`Route::Exact`] requested where it does not apply;
/// delays that are not whole steps on the spectral route; an unstable system.
pub(crate) fn plan(input: &RunInput, opts: &RunOptions) -> Result<Plan> {
    plan_with(input, opts, false)
}

/// [`plan`]; with `schur_grid` the spectral route's discrete transfer on the FFT grid comes from one Schur
/// form of Φ for every bin instead of an LU per bin (the same values to rounding, several times faster):
/// for [`planned_variances`], whose variances need not be bit-identical to a run's.
fn plan_with(input: &RunInput, opts: &RunOptions, schur_grid: bool) -> Result<Plan> {
    let n = opts.samples()?;
    let (p_all, g_all) = (input.outputs.len(), input.excitation.spectra().len());
    // a run that keeps whole records (raw data) needs them in memory on every route; a statistics-only run
    // (verdict channels included: they are evaluated block by block) of the exact route streams in blocks,
    // of the streamed spectral route in segments
    let records = opts.store_raw;
    // before any buffer of the realization's size exists
    if opts.route == Route::Spectral || (opts.route == Route::Exact && records) {
        super::resources::check_memory(n, p_all, g_all, opts)?;
    }
    let (finite, skipped) = simulable_outputs(input)?;
    let idx: Vec<usize> = finite.iter().map(|f| f.index).collect();
    let mut choice = RouteChoice::choose(input, opts, &idx)?;
    // for the automatic route the verdict decides between the whole-record and the streamed spectral route
    let whole = match opts.route {
        Route::Auto if choice.exact.is_none() || records => super::resources::check_memory(n, p_all, g_all, opts),
        _ => Ok(()),
    };
    let streamed = match (opts.route, whole) {
        (Route::SpectralStream, _) => true,
        (_, Ok(())) => false,
        (_, Err(e)) if choice.exact.is_some() || records || input.is_non_gaussian() => return Err(e),
        (_, Err(e)) => {
            choice.reason = format!(
                "{}; streamed spectral route: the whole-record spectral route does not fit ({e})",
                choice.reason
            );
            true
        }
    };
    let m_welch = ((n / 8) & !1).clamp(4, 1024);
    let start = PlanStart {
        n,
        finite,
        skipped,
        notes: vec![choice.reason],
        welch: Welch::new(m_welch, opts.dt_s)?,
    };
    if streamed {
        return streamed_plan(input, opts, start);
    }
    // exact route: append the input processes (shaping-filter outputs) as extra rows of the simulated system
    let exact = choice
        .exact
        .map(|gm| with_input_rows(input.system, input.excitation, &idx, opts.dt_s).unwrap_or(gm));
    match exact {
        Some(gm) => exact_plan(input, opts, start, gm),
        None => spectral_plan(input, opts, start, schur_grid),
    }
}

/// What the plan of every route starts from: N samples per realization, the outputs with a finite variance
/// (`finite`) and those skipped, the notes so far (the route's reason) and the Welch estimator.
struct PlanStart {
    n: usize,
    finite: Vec<Simulable>,
    skipped: Vec<SkippedOutput>,
    notes: Vec<String>,
    welch: Welch,
}

/// The plan of the exact route with the discretised system `gm` (the simulated outputs, then the input
/// processes where [`with_input_rows`] appended them).
fn exact_plan(input: &RunInput, opts: &RunOptions, mut start: PlanStart, gm: GaussMarkov) -> Result<Plan> {
    let (p_all, g_all) = (input.outputs.len(), input.excitation.spectra().len());
    let threads = rayon::current_num_threads();
    let p = start.finite.len();
    let block_steps = if opts.store_raw {
        0
    } else {
        opts.block_steps.min(start.n)
    };
    let memory_bytes = if block_steps > 0 {
        let bytes = super::resources::exact_block_memory_bytes(
            gm.n_states(),
            gm.n_outputs(),
            p,
            block_steps,
            start.n,
            opts,
            threads,
        );
        super::resources::check_block_memory(bytes, start.n, opts)?;
        bytes
    } else {
        super::resources::memory_bytes(start.n, p_all, g_all, opts, threads)
    };
    let cov = gm.output_covariance();
    let autocov = gm
        .output_autocovariances(start.welch.segment_len())
        .into_iter()
        .take(p)
        .collect();
    let outputs = start
        .finite
        .into_iter()
        .enumerate()
        .map(|(r, f)| PlannedOutput {
            index: f.index,
            signal: Signal::new(&f.info.name, &f.info.unit),
            analytic_variance: f.variance,
            discrete_variance: cov[(r, r)],
            kurtosis: None,
            mean_square_sd: None,
        })
        .collect();
    start.notes.push(
        "exact route: Van Loan discretisation of the system with its shaping filters, stationary start (no \
         time-step bias, no transient)"
            .into(),
    );
    let stride = gm.n_outputs();
    let input_signals = if stride == p + input.input_signals.len() {
        input.input_signals.clone()
    } else {
        vec![]
    };
    Ok(Plan {
        route: Route::Exact,
        engine: Engine::Exact(gm),
        n: start.n,
        stride,
        input_signals,
        outputs,
        skipped: start.skipped,
        notes: start.notes,
        generator: format!(
            "{}, stream (seed, i) per realization; exact Van Loan discretisation of the system augmented \
             with its shaping filters, stationary start",
            super::GENERATOR
        ),
        welch: start.welch,
        block_steps,
        autocov,
        memory_bytes,
    })
}

/// The plan of the whole-record spectral route (`schur_grid`: see [`plan_with`]).
fn spectral_plan(input: &RunInput, opts: &RunOptions, mut start: PlanStart, schur_grid: bool) -> Result<Plan> {
    let n = start.n;
    let (p_all, g_all) = (input.outputs.len(), input.excitation.spectra().len());
    let memory_bytes = super::resources::memory_bytes(n, p_all, g_all, opts, rayon::current_num_threads());
    let idx: Vec<usize> = start.finite.iter().map(|f| f.index).collect();
    let (engine, discrete, autocov, moments) = spectral_engine(
        input,
        opts,
        n,
        &idx,
        &mut start.notes,
        start.welch.segment_len(),
        schur_grid,
    )?;
    let outputs = start
        .finite
        .into_iter()
        .zip(discrete)
        .zip(moments)
        .map(|((f, dv), m)| PlannedOutput {
            index: f.index,
            signal: Signal::new(&f.info.name, &f.info.unit),
            analytic_variance: f.variance,
            discrete_variance: dv,
            kurtosis: m.kurtosis,
            mean_square_sd: Some(m.mean_square_sd),
        })
        .collect();
    Ok(Plan {
        route: Route::Spectral,
        engine,
        n,
        stride: idx.len(),
        input_signals: input.input_signals.clone(),
        outputs,
        skipped: start.skipped,
        notes: start.notes,
        generator: match input.is_non_gaussian().then(|| input.kurtosis_text()) {
            None => format!(
                "{}, stream (seed, i) per realization; spectral representation (Rayleigh amplitudes) on an FFT grid \
                 of N = {n}, first-order-hold response (periodic steady state, frequency domain)",
                super::GENERATOR
            ),
            Some(k) => format!(
                "{}, stream (seed, i) per realization; Laplace moving average of kurtosis {k} on an FFT grid of N = \
                 {n} ({}), first-order-hold response (periodic steady state, frequency domain)",
                super::GENERATOR,
                super::LAPLACE_DRAWS
            ),
        },
        welch: start.welch,
        block_steps: 0,
        autocov,
        memory_bytes,
    })
}

/// The plan of the streamed spectral route: FIR kernels designed from the discrete transfer gains of
/// the first-order-hold system and the input spectra on doubling grids ([`FirSynthesis::design`]), the exact
/// variance and autocovariance of the FIR process, and the memory check with the streamed estimate.
fn streamed_plan(input: &RunInput, opts: &RunOptions, start: PlanStart) -> Result<Plan> {
    let PlanStart {
        n,
        finite,
        skipped,
        mut notes,
        welch,
    } = start;
    if opts.store_raw {
        return Err(Error::invalid(
            "store raw",
            true,
            "the streamed spectral route (--route spectral-stream) keeps no realizations: drop --store-raw, or use \
             --route spectral",
        ));
    }
    let idx: Vec<usize> = finite.iter().map(|f| f.index).collect();
    let (sys, exc, dt) = (input.system, input.excitation, opts.dt_s);
    let ss = sys.state_space().ok_or_else(|| Error::Numerical {
        what: "streamed spectral Monte Carlo".into(),
        reason: "the system has no finite state-space form".into(),
    })?;
    let sub = ss.select_outputs(&idx)?;
    stability_margin(ss)?;
    // the largest delay in whole steps: the first grid holds it 16 times
    let max_shift = max_delay_steps(exc, dt);
    let spectra = exc.spectra();
    let schur = super::transfer_grid::SchurTransfer::new(&sub, dt)?;
    let kernel_spectra = |l: usize| -> Result<KernelSpectra> {
        let (generators, inputs) = spectral_inputs(exc, dt, l)?;
        let (gains, _, _) = discrete_gains(&sub, exc, &generators, &inputs, dt, l, schur.as_ref())?;
        let dw = 2.0 * std::f64::consts::PI / (l as f64 * dt);
        Ok(gains
            .into_iter()
            .zip(&spectra)
            .map(|(gg, sp)| {
                let amp: Vec<f64> = (0..=l / 2)
                    .map(|j| (sp.density(j as f64 * dw) * dw / l as f64).sqrt())
                    .collect();
                gg.into_iter()
                    .map(|row| row.into_iter().zip(&amp).map(|(c, a)| c * *a).collect())
                    .collect()
            })
            .collect())
    };
    let min_grid = 16usize.saturating_mul(max_shift + 1);
    let (fir, design) =
        FirSynthesis::design(&kernel_spectra, min_grid, opts.stream_tail, GRID_TOLERANCE).map_err(|e| match e {
            // name the output (the design counts the simulated outputs 0..p)
            Error::Numerical { what, reason } => Error::Numerical {
                what: finite.iter().enumerate().rev().fold(what, |w, (r, f)| {
                    w.replace(&format!("output {r}"), &format!("output `{}`", f.info.name))
                }),
                reason,
            },
            e => e,
        })?;
    let p = idx.len();
    let memory_bytes = streamed_memory(&fir, &design, n, p, opts)?;
    let discrete: Vec<f64> = (0..p).map(|r| fir.variance(r)).collect();
    notes.extend(streamed_notes(&fir, &design, &finite, &discrete, opts));
    let autocov = (0..p).map(|r| fir.autocovariance(r, welch.segment_len())).collect();
    let outputs = finite
        .into_iter()
        .zip(&discrete)
        .map(|(f, dv)| PlannedOutput {
            index: f.index,
            signal: Signal::new(&f.info.name, &f.info.unit),
            analytic_variance: f.variance,
            discrete_variance: *dv,
            kurtosis: None,
            mean_square_sd: None,
        })
        .collect();
    Ok(Plan {
        route: Route::SpectralStream,
        generator: format!(
            "{}, stream (seed, i) per realization; streamed spectral synthesis: white noise through FIR kernels of {} \
             taps (kernel grid {}, window tail ≤ {:e}), overlap-save FFT of {}, first-order-hold \
             response, stationary start",
            super::GENERATOR,
            fir.taps(),
            design.grid_len,
            opts.stream_tail,
            fir.fft_len()
        ),
        engine: Engine::SpectralStream(fir),
        n,
        stride: p,
        input_signals: input.input_signals.clone(),
        outputs,
        skipped,
        notes,
        welch,
        block_steps: opts.block_steps.min(n),
        autocov,
        memory_bytes,
    })
}

/// The memory of the streamed route with kernels `fir` for `p` outputs, checked against the limit.
///
/// # Errors
/// As [`super::resources::check_streamed_memory`].
fn streamed_memory(fir: &FirSynthesis, design: &KernelDesign, n: usize, p: usize, opts: &RunOptions) -> Result<u128> {
    let bytes = super::resources::streamed_memory_bytes(
        &super::resources::StreamSizes {
            taps: fir.taps(),
            fft_len: fir.fft_len(),
            grid_len: design.grid_len,
            block_steps: opts.block_steps.min(n),
            outputs: p,
            generators: fir.n_generators(),
        },
        opts,
        rayon::current_num_threads(),
    );
    super::resources::check_streamed_memory(bytes, n, opts)?;
    Ok(bytes)
}

/// The largest delay of the excitation's inputs relative to the earliest, in whole steps of `dt`.
fn max_delay_steps(exc: &Excitation, dt: f64) -> usize {
    let steps = |delays: &mut dyn Iterator<Item = f64>| {
        let d: Vec<f64> = delays.collect();
        let t0 = d.iter().copied().fold(f64::INFINITY, f64::min);
        d.iter().map(|t| ((t - t0) / dt).round() as usize).max().unwrap_or(0)
    };
    match exc {
        Excitation::Track { delays, .. } => steps(&mut delays.iter().copied()),
        Excitation::Independent { .. } => 0,
        // several independent sources: one white noise per component of every source, each through its own
        // kernels (a multi-component source's mixing is part of its kernels), summed per output
        Excitation::Sources { inputs, .. } => steps(&mut inputs.iter().map(|m| m.delay)),
    }
}

/// The notes of the streamed spectral route: its kernels, and per output the bias of the design (`discrete`:
/// the FIR process's exact variances).
fn streamed_notes(
    fir: &FirSynthesis,
    design: &KernelDesign,
    finite: &[Simulable],
    discrete: &[f64],
    opts: &RunOptions,
) -> Vec<String> {
    let mut notes = vec![format!(
        "spectral-stream route: white noise through FIR kernels of {} taps (lags {}..{}), designed on a grid of {} \
         points (Δω = {:.4e} rad/s) from the first-order-hold response and the input spectra; overlap-save with an \
         FFT of {} ({} new samples per segment), memory independent of the duration",
        fir.taps(),
        design.first_lag,
        design.first_lag + fir.taps() as i64 - 1,
        design.grid_len,
        2.0 * std::f64::consts::PI / (design.grid_len as f64 * opts.dt_s),
        fir.fft_len(),
        fir.hop()
    )];
    for (r, f) in finite.iter().enumerate() {
        notes.push(format!(
            "spectral-stream bias of {}: window tail {:.3e} of the grid variance (bound {:e}), grid \
             variance change over the last doubling {:.3e} (bound {GRID_TOLERANCE:e}); simulated σ {:.6e} vs \
             analytic σ {:.6e} (relative {:+.3e}); `discrete σ` is the exact σ of the simulated FIR process",
            f.info.name,
            design.tail_fraction[r],
            opts.stream_tail,
            design.grid_change[r],
            discrete[r].sqrt(),
            f.variance.sqrt(),
            discrete[r].sqrt() / f.variance.sqrt() - 1.0
        ));
    }
    notes
}

/// The slowest decay rate min(−Re λ) of `ss`, > 0 for an asymptotically stable system.
///
/// # Errors
/// [`Error::Numerical`] when the system is not asymptotically stable.
fn stability_margin(ss: &StateSpace) -> Result<f64> {
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
    Ok(sigma_min)
}

/// The exact Gauss–Markov system of `outputs` with the input processes appended as extra rows: row k is
/// the output C_F,k x_F,k of process k's shaping filter (None when a filter has a white-noise feedthrough,
/// whose samples are undefined).
fn with_input_rows(sys: &dyn FrequencyResponse, exc: &Excitation, outputs: &[usize], dt: f64) -> Option<GaussMarkov> {
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
        let tf = TransferFunction::new(f.num.clone(), f.den.clone(), OutputInfo::new("u", "-")).ok()?;
        let part = tf.state_space()?.clone();
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

/// One input of the spectral route: the generator it comes from, its gain and its delay in whole steps.
struct SpectralInput {
    generator: usize,
    gain: f64,
    shift: usize,
    /// For a component of a multi-component source: the source's matrix, this input's component, and
    /// the index of the generator of its component 0 (its m components have consecutive generators).
    mixing: Option<(std::sync::Arc<dyn crate::coherence::SpectralMatrix>, usize, usize)>,
}

/// Exact higher moments of one simulated output process of the spectral route.
#[derive(Debug, Clone, Copy, PartialEq)]
struct OutputMoments {
    /// Marginal kurtosis (non-Gaussian inputs; `None` for Gaussian ones).
    kurtosis: Option<f64>,
    /// Standard deviation of one realization's mean square ([`mean_square_sd`]).
    mean_square_sd: f64,
}

/// The standard deviation of one realization's mean square v = (1/N)Σ_k y_k² of a periodic stationary
/// process of N samples with power `power[j]` in bin j (j = 0..=N/2, K(m) = Σ_j power_j cos(2πjm/N)) and
/// fourth-cumulant term `cumulant` = Σ_g 3ν̃_g D_g² (0 for a Gaussian process).
///
/// # Formula
/// Cov(y_k², y_l²) = 2K(k − l)² + κ₄(y_k, y_k, y_l, y_l); for a Laplace moving average
/// y = Σ_g Σ_m g⁽ᵍ⁾_m ε⁽ᵍ⁾_{k−m} the joint cumulant is Σ_g 3ν̃_g Σ_m (g⁽ᵍ⁾_{k−m})²(g⁽ᵍ⁾_{l−m})² (the increments'
/// fourth cumulant is 3ν̃). Summed over k, l on the period (Σ_k (g_{k−m})² = D_g for every m):
/// ```text
/// Var v = (2 Σ_m K(m)² + Σ_g 3ν̃_g D_g²) / N,   Σ_m K(m)² = N (p₀² + p_{N/2}²) + (N/2) Σ_{0<j<N/2} p_j²
/// ```
/// (orthogonality of the cosines over the period).
fn mean_square_sd(power: &[f64], n: usize, cumulant: f64) -> f64 {
    let nf = n as f64;
    let last = power.len().saturating_sub(1);
    let k2: f64 = power
        .iter()
        .enumerate()
        .map(|(j, p)| {
            if j == 0 || j == last {
                nf * p * p
            } else {
                0.5 * nf * p * p
            }
        })
        .sum();
    ((2.0 * k2 + cumulant) / nf).sqrt()
}

/// The spectral engine: one generator per independent process, the inputs as (generator, gain, shift), and
/// the discrete transfer gains from every generator's coefficients to every output; returns the engine, the
/// exact variance of each simulated (grid, first-order-hold, periodic) output process, its autocovariance,
/// and its exact kurtosis (non-Gaussian inputs) and standard deviation of a realization's mean square.
#[allow(clippy::type_complexity)]
fn spectral_engine(
    input: &RunInput,
    opts: &RunOptions,
    n: usize,
    outputs: &[usize],
    notes: &mut Vec<String>,
    lags: usize,
    schur_grid: bool,
) -> Result<(Engine, Vec<f64>, Vec<Vec<f64>>, Vec<OutputMoments>)> {
    let (sys, exc, dt) = (input.system, input.excitation, opts.dt_s);
    let ss = sys.state_space().ok_or_else(|| Error::Numerical {
        what: "spectral Monte Carlo".into(),
        reason: "the system has no finite state-space form".into(),
    })?;
    let sub = ss.select_outputs(outputs)?;
    let sigma_min = stability_margin(ss)?;
    let period = n as f64 * dt;
    notes.push(format!(
        "spectral route: periodic input of period NΔt = {period} s; the recorded period is the periodic steady \
         state of the first-order-hold system, computed exactly in the frequency domain (one inverse FFT per \
         output; slowest decay rate min|Re λ| = {sigma_min:.4e} 1/s)"
    ));
    let (generators, inputs) = spectral_inputs(exc, dt, n)?;
    let schur = match schur_grid {
        true => super::transfer_grid::SchurTransfer::new(&sub, dt)?,
        false => None,
    };
    let (gains, discrete, spectrum) = discrete_gains(&sub, exc, &generators, &inputs, dt, n, schur.as_ref())?;
    let autocov = spectrum
        .iter()
        .map(|p| periodic_autocovariance(p, n, lags))
        .collect::<Result<Vec<_>>>()?;
    notes.push(
        "spectral route bias: the synthesised input is the spectrum on the FFT grid (truncated at Nyquist, \
         sampled at Δω = 2π/(NΔt)); `discrete σ` is the exact σ of that simulated process"
            .into(),
    );
    let (laplace, cumulants) = if input.is_non_gaussian() {
        laplace_generators(exc, &generators, &gains, &input.kurtosis, outputs, sys, notes)?
    } else {
        (vec![], vec![])
    };
    let moments = spectrum
        .iter()
        .enumerate()
        .map(|(r, p)| {
            let c = cumulants.get(r).copied();
            OutputMoments {
                kurtosis: c.map(|c| c.0),
                mean_square_sd: mean_square_sd(p, n, c.map_or(0.0, |c| c.1)),
            }
        })
        .collect();
    Ok((
        Engine::Spectral {
            laplace,
            raw_mix: if opts.store_raw {
                raw_mixing(generators.len(), &inputs, dt, n)
            } else {
                vec![None; generators.len()]
            },
            generators,
            gains,
            inverse: super::fft_plans::inverse_real_fft(n),
        },
        discrete,
        autocov,
        moments,
    ))
}

/// The Laplace moving averages of a run's generators and, per output, its exact kurtosis and the fourth-cumulant
/// term of its mean square (see [`laplace_generators`]).
type LaplaceGenerators = (Vec<super::LaplaceMovingAverage>, Vec<(f64, f64)>);

/// The Laplace moving averages of a non-Gaussian run, one per generator (generator g with the kurtosis
/// `kurtosis[g]`, κ = 3 for `None`), a note per generator (its ν) and per output (its kurtosis), and for every
/// simulated output process its exact kurtosis and the fourth-cumulant term Σ_g 3ν̃_g D_g² of its mean
/// square's variance ([`mean_square_sd`]).
///
/// # Formula
/// Output r is y = Σ_g Σ_m g^{(g)}_m ε^{(g)}_{k−m}, a sum of independent filtered Laplace moving averages;
/// fourth cumulants and variances add over the generators
/// ([`LaplaceMovingAverage::filtered_cumulants`](super::LaplaceMovingAverage::filtered_cumulants)):
/// ```text
/// κ_y = 3 + Σ_g 3ν̃_g Σ_l (g^{(g)}_l)⁴ / (Σ_g Σ_l (g^{(g)}_l)²)²
/// ```
/// For one generator this is κ_y − 3 = (κ_x − 3)·r_y/r_x with r = Σg⁴/(Σg²)² the kernel ratios of output and
/// input (since 3ν̃ = (κ_x − 3)/r_x): the continuous form (κ_x − 3)·[∫g⁴/(∫g²)²]/[∫f⁴/(∫f²)²], g = h * f.
///
/// # Errors
/// A non-Gaussian component of a multi-component source (two tracks with a coherence): its mixed components
/// would not have the prescribed kurtosis; a kurtosis list whose length is not the number of generators; the
/// errors of [`LaplaceMovingAverage::from_generator`](super::LaplaceMovingAverage::from_generator).
fn laplace_generators(
    exc: &Excitation,
    generators: &[SpectralGenerator],
    gains: &Gains,
    kurtosis: &[Option<f64>],
    outputs: &[usize],
    sys: &dyn FrequencyResponse,
    notes: &mut Vec<String>,
) -> Result<LaplaceGenerators> {
    if kurtosis.len() != generators.len() {
        return Err(Error::invalid(
            "kurtosis",
            format!("{kurtosis:?}"),
            format!(
                "one kurtosis per independent input process: the excitation has {} processes",
                generators.len()
            ),
        ));
    }
    if let Excitation::Sources { sources, .. } = exc {
        let mut g = 0;
        for s in sources {
            let m = s.n_components();
            if m > 1
                && let Some(k) = kurtosis[g..g + m].iter().flatten().next()
            {
                return Err(Error::invalid(
                    "kurtosis",
                    k,
                    "a non-Gaussian input is not available for a source of several correlated components (two \
                         tracks with a coherence): the mixed track would not have the prescribed kurtosis",
                ));
            }
            g += m;
        }
    }
    let lma = generators
        .iter()
        .zip(kurtosis)
        .map(|(g, k)| super::LaplaceMovingAverage::from_generator(g.clone(), k.unwrap_or(3.0)))
        .collect::<Result<Vec<_>>>()?;
    for (i, (l, k)) in lma.iter().zip(kurtosis).enumerate() {
        let Some(k) = k else { continue };
        notes.push(format!(
            "non-Gaussian input {i}: Laplace moving average (Bogsjö, Podgórski & Rychlik 2012) of kurtosis {k}, same \
             spectrum as the Gaussian input; kernel ratio Σf⁴/(Σf²)² = {:.4e}, ν = {:.4e} steps = {:.4e} s (Gamma \
             shape Δt/ν = {:.4e})",
            l.kernel_ratio(),
            l.nu_steps(),
            l.nu(),
            if l.nu_steps() > 0.0 {
                1.0 / l.nu_steps()
            } else {
                f64::INFINITY
            }
        ));
    }
    let names = sys.outputs();
    let mut out = Vec::with_capacity(outputs.len());
    for (r, &o) in outputs.iter().enumerate() {
        let (mut k4, mut var, mut cum) = (0.0, 0.0, 0.0);
        for (l, g) in lma.iter().zip(gains) {
            let (a, b) = l.filtered_cumulants(&g[r])?;
            k4 += a;
            var += b;
            cum += 3.0 * l.nu_steps() * b * b;
        }
        let kappa = if var > 0.0 { 3.0 + k4 / (var * var) } else { 3.0 };
        if var > 0.0 {
            notes.push(format!(
                "non-Gaussian response: kurtosis of `{}` (simulated process) = {:.6} (Gaussian: 3); σ is that of the \
                 Gaussian input, extremes and VDV are not",
                names.get(o).map(|i| i.name.as_str()).unwrap_or("?"),
                kappa
            ));
        }
        out.push((kappa, cum));
    }
    Ok((lma, out))
}

/// Autocovariance at lags 0..lags of the periodic process whose variance per bin is `power[j]`
/// (j = 0..=N/2, already weighted: K(0) = Σ power): K(m) = Σ_j power_j cos(2πjm/N), by one inverse real FFT.
fn periodic_autocovariance(power: &[f64], n: usize, lags: usize) -> Result<Vec<f64>> {
    let mut spec: Vec<Complex<f64>> = power
        .iter()
        .enumerate()
        .map(|(j, p)| {
            // the inverse real FFT doubles interior bins: halve them to get Σ_j power_j cos(...)
            let w = if j == 0 || j == n / 2 { 1.0 } else { 0.5 };
            Complex::new(p * w, 0.0)
        })
        .collect();
    let mut k = vec![0.0; n];
    super::fft_plans::inverse_real_fft(n)
        .process(&mut spec, &mut k)
        .map_err(|e| Error::Numerical {
            what: "periodic autocovariance".into(),
            reason: e.to_string(),
        })?;
    k.truncate(lags.min(n));
    Ok(k)
}

/// The generators of the excitation's independent processes and the system inputs they feed.
fn spectral_inputs(exc: &Excitation, dt: f64, n: usize) -> Result<(Vec<SpectralGenerator>, Vec<SpectralInput>)> {
    match exc {
        Excitation::Track {
            spectrum,
            delays,
            gains,
            ..
        } => {
            let g = SpectralGenerator::new(spectrum.as_ref(), dt, n, Amplitudes::Rayleigh)?;
            let t0 = delays.iter().copied().fold(f64::INFINITY, f64::min);
            let mut inp = Vec::new();
            for (j, (&tau, &gain)) in delays.iter().zip(gains).enumerate() {
                let s = ((tau - t0) / dt).round();
                if ((s * dt) - (tau - t0)).abs() > 1e-9 * (tau - t0).max(dt) {
                    let k = ((tau - t0) / dt).ceil().max(1.0);
                    return Err(Error::invalid(
                        "dt",
                        format!("{dt} s"),
                        format!(
                            "input {j} is delayed by {} s, not an integer number of steps (exact delays need \
                             τ = s·Δt, i.e. positions multiples of vΔt); choose e.g. Δt = {:e} s",
                            tau - t0,
                            (tau - t0) / k
                        ),
                    ));
                }
                inp.push(SpectralInput {
                    generator: 0,
                    gain,
                    shift: s as usize % n,
                    mixing: None,
                });
            }
            Ok((vec![g], inp))
        }
        Excitation::Independent { spectra, .. } => {
            let gens = spectra
                .iter()
                .map(|s| SpectralGenerator::new(s.as_ref(), dt, n, Amplitudes::Rayleigh))
                .collect::<Result<Vec<_>>>()?;
            let inp = (0..spectra.len())
                .map(|j| SpectralInput {
                    generator: j,
                    gain: 1.0,
                    shift: 0,
                    mixing: None,
                })
                .collect();
            Ok((gens, inp))
        }
        Excitation::Sources { sources, inputs } => {
            // one generator per component of every source, in order (Excitation::spectra)
            let gens = exc
                .spectra()
                .iter()
                .map(|s| SpectralGenerator::new(s.as_ref(), dt, n, Amplitudes::Rayleigh))
                .collect::<Result<Vec<_>>>()?;
            let mut first = Vec::with_capacity(sources.len());
            let mut k = 0;
            for s in sources {
                first.push(k);
                k += s.n_components();
            }
            let t0 = inputs.iter().map(|m| m.delay).fold(f64::INFINITY, f64::min);
            let mut inp = Vec::new();
            for (j, m) in inputs.iter().enumerate() {
                let shift = delay_steps(j, m.delay - t0, dt)?;
                inp.push(SpectralInput {
                    generator: first[m.source] + m.component,
                    gain: m.gain,
                    shift: shift % n,
                    mixing: match &sources[m.source] {
                        crate::response::Source::Matrix(mx) => Some((mx.clone(), m.component, first[m.source])),
                        crate::response::Source::Process(_) => None,
                    },
                });
            }
            Ok((gens, inp))
        }
    }
}

/// Row c of the per-bin mixing of a multi-component source at ω (rad/s): component c's coefficient is
/// Σ_k M_ck c_k over the source's generators k, M_ck = L_ck √(S_cc/S_kk) with C = L Lᴴ the coherence matrix.
fn mixing_row(mx: &dyn crate::coherence::SpectralMatrix, c: usize, w: f64) -> Vec<Complex<f64>> {
    let l = crate::coherence::semidefinite_cholesky(&mx.coherence_matrix(w));
    let s = mx.matrix(w);
    (0..mx.n_components())
        .map(|k| {
            let (scc, skk) = (s[(c, c)].re, s[(k, k)].re);
            if skk > 0.0 {
                l[(c, k)] * (scc / skk).sqrt()
            } else {
                Complex::new(0.0, 0.0)
            }
        })
        .collect()
}

/// For raw records: per generator of a multi-component source, (its source's first generator, the mixing
/// row of its component at every bin j = 0 … N/2), so that the recorded input is the component itself
/// (e.g. the right track), not the generator's innovation.
fn raw_mixing(generators: usize, inputs: &[SpectralInput], dt: f64, n: usize) -> Vec<RawMix> {
    let dw = 2.0 * std::f64::consts::PI / (n as f64 * dt);
    let mut out: Vec<RawMix> = vec![None; generators];
    for inp in inputs {
        if let Some((mx, _, first)) = &inp.mixing {
            for c in 0..mx.n_components() {
                if out[first + c].is_none() {
                    let rows = (0..=n / 2).map(|j| mixing_row(mx.as_ref(), c, j as f64 * dw)).collect();
                    out[first + c] = Some((*first, rows));
                }
            }
        }
    }
    out
}

/// A relative delay as a whole number of steps, or the error that says which Δt would make it one.
fn delay_steps(j: usize, tau: f64, dt: f64) -> Result<usize> {
    let s = (tau / dt).round();
    if ((s * dt) - tau).abs() > 1e-9 * tau.max(dt) {
        let k = (tau / dt).ceil().max(1.0);
        return Err(Error::invalid(
            "dt",
            format!("{dt} s"),
            format!(
                "input {j} is delayed by {tau} s, not an integer number of steps (exact delays need τ = s·Δt, \
                 i.e. positions multiples of vΔt); choose e.g. Δt = {:e} s",
                tau / k
            ),
        ));
    }
    Ok(s as usize)
}

/// gains\[g\]\[r\]\[j\]: the transfer from generator g's coefficient c_j to output r (discrete transfer
/// function of the first-order hold, input gains, shift phases and the iω_j E term), the exact variance
/// σ²_d = Σ_j w_j S(ω_j) Δω |H_d(ω_j)|² of each output (see [`crate::simulate::run`]), and its terms per bin.
#[allow(clippy::needless_range_loop, clippy::too_many_arguments)] // the bin loop fills several tables
fn discrete_gains(
    sub: &StateSpace,
    exc: &Excitation,
    generators: &[SpectralGenerator],
    inputs: &[SpectralInput],
    dt: f64,
    n: usize,
    fast: Option<&super::transfer_grid::SchurTransfer>,
) -> Result<(Gains, Vec<f64>, Vec<Vec<f64>>)> {
    let f = foh(&sub.a, &sub.b, dt)?;
    let nst = sub.n_states();
    let p = sub.c.nrows();
    let dw = 2.0 * std::f64::consts::PI / (n as f64 * dt);
    let mut disc = vec![0.0; p];
    let mut power = vec![vec![0.0; n / 2 + 1]; p];
    let mut gains = vec![vec![vec![Complex::new(0.0, 0.0); n / 2 + 1]; p]; generators.len()];
    let spectra = exc.spectra();
    let to_c = |m: &DMatrix<f64>| m.map(|v| Complex::new(v, 0.0));
    let (phi, g0, g1, c, d) = (
        to_c(&f.phi),
        to_c(&f.gamma0),
        to_c(&f.gamma1),
        to_c(&sub.c),
        to_c(&sub.d),
    );
    let (mut work, mut hv) = match fast {
        Some(t) => (t.work(), vec![Complex::new(0.0, 0.0); p * sub.b.ncols()]),
        None => (Vec::new(), Vec::new()),
    };
    let mut h = DMatrix::<Complex<f64>>::zeros(p, sub.b.ncols());
    for j in 0..=n / 2 {
        let w = j as f64 * dw;
        let weight = if j == 0 || j == n / 2 { 1.0 } else { 2.0 };
        if let Some(t) = fast {
            // the streamed route's design: one Schur form for every bin (the periodic route keeps its LU)
            t.eval(w, j == n / 2, &mut work, &mut hv);
            let m = h.ncols();
            for r in 0..p {
                for k in 0..m {
                    h[(r, k)] = hv[r * m + k];
                }
            }
        } else {
            let z = Complex::new(0.0, w * dt).exp();
            let zi = DMatrix::<Complex<f64>>::identity(nst, nst) * z - &phi;
            let rhs = &g0 + &g1 * z;
            let x = zi.lu().solve(&rhs).ok_or_else(|| Error::Numerical {
                what: "discrete transfer function".into(),
                reason: format!("zI − Φ singular at ω = {w:e}"),
            })?;
            h = &c * x + &d; // p × m
            if j < n / 2 {
                h += to_c(&sub.e) * Complex::new(0.0, w);
            }
        }
        // multi-component sources: input l's component c is Σ_k M_ck(ω_j) c_k over the source's generators
        // k, M_ck = L_ck √(S_cc/S_kk) with C = L Lᴴ the coherence matrix (Z_R = ρ Z_L + √(1 − ρ²) W for two
        // tracks): the cross-spectra are exact in expectation, bin by bin
        let mix: Vec<Option<(usize, Vec<Complex<f64>>)>> = inputs
            .iter()
            .map(|inp| {
                inp.mixing
                    .as_ref()
                    .map(|(mx, c, first)| (*first, mixing_row(mx.as_ref(), *c, w)))
            })
            .collect();
        for (r, dv) in disc.iter_mut().enumerate() {
            for gi in 0..generators.len() {
                let s = spectra[gi].density(w);
                let mut acc = Complex::new(0.0, 0.0);
                for (l, inp) in inputs.iter().enumerate() {
                    if let Some((first, row)) = &mix[l] {
                        if gi >= *first && gi < first + row.len() {
                            acc += h[(r, l)]
                                * inp.gain
                                * row[gi - first]
                                * Complex::new(0.0, -w * inp.shift as f64 * dt).exp();
                        }
                    } else if inp.generator == gi {
                        acc += h[(r, l)] * inp.gain * Complex::new(0.0, -w * inp.shift as f64 * dt).exp();
                    }
                }
                gains[gi][r][j] = acc;
                *dv += weight * s * dw * acc.norm_sqr();
                power[r][j] += weight * s * dw * acc.norm_sqr();
            }
        }
    }
    Ok((gains, disc, power))
}
