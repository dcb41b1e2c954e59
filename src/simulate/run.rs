//! A whole Monte Carlo run, end to end: realizations in shards, accumulators, statistics with
//! intervals against the analytic values, Welch densities, all written to one HDF5 file
//! ([`crate::store`]) that survives interruption and resumes.
//!
//! # Routes
//! * [`Route::Exact`](super::Route::Exact): every input spectrum rational and the excitation delay-free. The system augmented
//!   with the inputs' shaping filters is discretised by Van Loan's method ([`augmented_response`](super::augmented_response)) and
//!   started from its stationary distribution, so every sample of every output is exactly a sample of the
//!   stationary response: no time-step bias, no transient.
//! * [`Route::Spectral`](super::Route::Spectral): any spectrum and delayed inputs (road tracks). The input process is synthesised
//!   by the spectral representation ([`SpectralGenerator`](super::SpectralGenerator), random Rayleigh amplitudes) on an FFT grid of
//!   N samples, so it is periodic with period NΔt; the recorded output is the periodic steady state of the
//!   exact first-order hold ([`SampledSystem`](super::SampledSystem)) driven by that periodic input. It is computed exactly in
//!   the frequency domain, with one inverse FFT per output: y_k = Σ_j G_j c_j e^{iω_j kΔt}, G_j the
//!   discrete transfer function H_d(ω_j) below (what time stepping through warm-up periods converges to,
//!   without the stepping or the residual transient). Delays τ_j become circular shifts by s_j = τ_j/Δt
//!   samples, which must be integers (Δt = τ/k). An output containing the input derivative (E ≠ 0) gets
//!   E·u̇_k with u̇ the exact derivative of the input's trigonometric interpolant (spectral
//!   differentiation: bin j times iω_j, the Nyquist bin dropped), while the states see the first-order
//!   hold of the samples.
//! * [`Route::SpectralStream`](super::Route::SpectralStream): the same inputs and the same first-order-hold
//!   response, statistics only, in time order with memory independent of the duration: independent white
//!   noise per input process through FIR kernels k_{g,r} designed on an L-point grid from
//!   b_j = H_d(ω_j)·√(S(ω_j)Δω/L) and windowed to T taps, filtered by overlap-save with an FFT size fixed
//!   by T ([`FirSynthesis`](super::FirSynthesis)). Its `sigma_discrete` is the exact σ of the FIR process,
//!   √(Σ_g Σ_i k²); it differs from the grid σ of the spectral route by the window tail (≤
//!   [`TAIL_FRACTION`](super::fir_stream::TAIL_FRACTION) of the variance) and the grid (≤
//!   [`GRID_TOLERANCE`](super::fir_stream::GRID_TOLERANCE) change over the last doubling), both stated in
//!   the notes. [`Route::Auto`](super::Route::Auto) takes it where the spectral route applies but its whole
//!   record does not fit in the available memory. Several sources get one white noise per source
//!   component; verdict channels are evaluated block by block
//!   ([`VerdictStream`]), as on the exact route's blocks.
//!
//! # Bias of the spectral route
//! The synthesised process is the spectrum sampled on the grid ω_j = 2πj/(NΔt), j ≤ N/2 (truncated at the
//! Nyquist frequency and piecewise constant in between), and its variance is
//! [`SpectralGenerator::grid_variance`](super::SpectralGenerator::grid_variance), not the analytic variance. The recorded output is exactly the
//! periodic steady state of the first-order-hold system, whose variance is
//! ```text
//! σ²_d = Σ_j w_j S(ω_j) Δω |H_d(ω_j)|²,   w_j = 2 (1 for j = 0, N/2),
//! H_d(ω) = Σ_inputs g_l e^{−iω s_l Δt} [C (zI − Φ)⁻¹(Γ₀ + zΓ₁) + D + iω E]_l,   z = e^{iωΔt}
//! (the iω E term dropped at the Nyquist bin)
//! ```
//! (for independent inputs the |·|² add). This "discrete" variance is what the Monte Carlo estimates without
//! bias; it is reported next to the analytic one (the statistic `sigma_discrete`). For the exact route it
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
//! realizations, with χ² intervals, and compared with the analytic output density. On the spectral route the
//! spread of v_i is known exactly too, and a run whose mean of the v_i lies outside distribution-free bounds
//! around σ²_d fails instead of reporting success ([`super::agreement`]).
//!
//! # Resuming
//! Per shard the file stores, per output, the accumulators of [`super::accumulators`] (the time averages
//! m_i, v_i and the Welch sums). A rerun with the same options and
//! scenario reopens the `.tmp`, reads the completed shards' accumulators and computes only the missing
//! shards; since shard results depend only on (seed, i), the final statistics are bit-identical to those
//! of an uninterrupted run.

use super::accumulators::{self, Moments, WelchAccumulator};
use super::bands::OutputBands;
use super::engine::{realize, realize_lanes, Engine, Realization, Scratch};
use super::finish::{density_estimate, output_statistics, read_output, Analytic};
use super::plan::{plan, Plan};
use super::verdict_stream::VerdictStream;
use super::{run_batch_groups, stream, RunInput, RunOptions, RunSummary, LANES};
use crate::error::Result;
use crate::response::output_density;
use crate::store::{CreateOptions, OutputStatistics, Provenance, RunFile, RunMetadata, RunWriter};
use ndarray::Array2;
use std::path::Path;

/// Warm-up criterion for time stepping a system through a periodic input to its periodic steady state:
/// σ_min · (warm-up time) ≥ this (e^{−36} ≈ 2.3·10⁻¹⁶). The spectral route of [`run`] computes the
/// steady state in the frequency domain and does not need it; time-stepping callers (the benches) do.
pub const WARMUP_DECAY: f64 = 36.0;

/// Version of the linear routes' generator: how a seed becomes realizations and statistics. Version 2 takes
/// every realization's time sums in eight partial sums ([`TimeSums`](super::TimeSums)); version 1 (files
/// that record no version) summed left to right, which differs in the last bits. A seed's statistics are
/// bit-identical across threads, shards, resume and merge within a version, so a run file of another
/// version is never resumed or merged with this build (`store::metadata_differences` names the versions).
pub const GENERATOR_VERSION: u32 = 2;

/// The text of the run file's identifying provenance part [`crate::store::GENERATOR_VERSION`].
fn version_text() -> String {
    format!("{GENERATOR_VERSION} (linear routes: every realization's time sums in eight partial sums)")
}

/// Runs the Monte Carlo batch of `input` and writes the HDF5 file `out` (see the module docs); resumes an
/// interrupted run of the same subject and options from `<out>.tmp`. `progress(done, total)` is called after
/// every shard written (and once at the start with the resumed count).
///
/// # Errors
/// Invalid options ([`Error::InvalidParameter`](crate::Error::InvalidParameter)); [`Route::Exact`](super::Route::Exact)
/// requested for an excitation that does not allow it; delays that are not whole steps (spectral route); no
/// output with a finite variance; the store's errors (an existing `out` is never overwritten).
///
/// # Examples
/// ```
/// use stochvib::simulate::{run, Route, RunOptions};
/// use stochvib::scenario::load_scenario;
/// use std::path::Path;
/// let sc = load_scenario(Path::new("data/conveyor-idler.toml"), Path::new("spectra")).unwrap();
/// let out = std::env::temp_dir().join(format!("stochvib-doc-run-{}.h5", std::process::id()));
/// # let _ = std::fs::remove_file(&out);
/// let opts = RunOptions { realizations: 20, duration_s: 5.0, dt_s: 0.01, seed: 1, ..RunOptions::default() };
/// let s = run(&sc.run_input(), &opts, &out, &|done, total| eprintln!("{done}/{total}"))
///     .unwrap();
/// assert_eq!(s.route, Route::Exact); // exponential (rational) lump load, one input
/// // the exact route simulates the stationary response: its variance is the analytic one
/// let sigma = s.outputs[0].get("sigma_discrete").unwrap();
/// assert!((sigma.analytic.unwrap() / s.outputs[0].get("sigma").unwrap().analytic.unwrap() - 1.0).abs() < 1e-6);
/// # std::fs::remove_file(&out).unwrap();
/// ```
pub fn run(input: &RunInput, opts: &RunOptions, out: &Path, progress: &dyn Fn(usize, usize)) -> Result<RunSummary> {
    let plan = plan(input, opts)?;
    refuse_inputs_as_output(input, out)?;
    let names: Vec<&str> = plan.outputs.iter().map(|o| o.signal.name.as_str()).collect();
    // the exact mean of every output's Welch estimate (stored with its density; band integrals of it are
    // the expected band mean squares)
    let expected: Vec<Vec<f64>> = plan.autocov.iter().map(|a| plan.welch.expected_all(a)).collect();
    let (bands, band_notes) = match &input.bands {
        Some(spec) => {
            let outs: Vec<(usize, f64, String)> = plan
                .outputs
                .iter()
                .map(|o| (o.index, o.analytic_variance, o.signal.name.clone()))
                .collect();
            super::bands::plan_bands(input, spec, &outs, &expected, &plan.welch, opts.dt_s)
        }
        None => (Vec::new(), Vec::new()),
    };
    let meta = run_metadata(input, opts, &plan, &names, &bands);
    input.verdicts.check(&names)?;
    meta.validate()?;
    // cluster shard: a complete shard file of this run is the result (a rerun does nothing)
    if let Some(done) = super::finished_part::finished_part(&meta, &plan, out, opts)? {
        return Ok(done);
    }
    super::resources::check_disk(&meta, out)?;
    super::resources::check_run_time(opts, plan.n, input.excitation.spectra().len())?;
    let mut writer = RunWriter::create_with(
        out,
        &meta,
        CreateOptions {
            overwrite: opts.overwrite,
            ..CreateOptions::default()
        },
    )?;
    let mut notes = plan.notes.clone();
    notes.extend(band_notes);
    notes.extend(writer.notes().iter().cloned());
    let n_shards = meta.local_shards().len();
    let resumed_shards = writer.completed_shards().len();
    simulate_pending_shards(&mut writer, &meta, &plan, input, opts, &bands, progress)?;
    let (mut stats, psds) = output_results(input, &writer, &meta, &plan, opts, expected)?;
    let rainflow = finish_verdicts(input, &writer, &meta, &plan, opts, &mut stats)?;
    add_band_statistics(&writer, &meta, &plan, &bands, opts, &mut stats)?;
    let path = writer.finish_with(&stats, &rainflow, &psds)?;
    Ok(RunSummary {
        path,
        route: plan.route,
        generator: plan.generator,
        n_samples: plan.n,
        dt_s: opts.dt_s,
        n_realizations: opts.realizations,
        n_shards,
        resumed_shards,
        part: meta.part,
        realizations: meta.local_realizations(),
        basic_method: super::basic_method_rows(&stats, plan.n as f64 * opts.dt_s),
        outputs: stats,
        skipped: plan.skipped,
        notes,
        rainflow,
    })
}

/// The metadata of the run file of `plan`: its outputs `names`, the accumulators of the outputs, verdict
/// channels and band tables `bands`, and the options.
fn run_metadata(
    input: &RunInput,
    opts: &RunOptions,
    plan: &Plan,
    names: &[&str],
    bands: &[OutputBands],
) -> RunMetadata {
    let shard_size = opts.shard_size.min(opts.realizations);
    let bins = plan.welch.segment_len() / 2 + 1;
    let mut accumulators = accumulators::layout(names, shard_size, bins);
    accumulators.extend(input.verdicts.layout(shard_size));
    accumulators.extend(bands.iter().map(|b| {
        (
            super::bands::accumulator_name(names[b.output]),
            b.bands.len() * shard_size,
        )
    }));
    RunMetadata {
        scenario_text: input.scenario_text.clone(),
        seed: opts.seed,
        generator: plan.generator.clone(),
        dt: opts.dt_s,
        n_samples: plan.n,
        n_realizations: opts.realizations,
        shard_size,
        inputs: if opts.store_raw {
            plan.input_signals.clone()
        } else {
            vec![]
        },
        outputs: plan.outputs.iter().map(|o| o.signal.clone()).collect(),
        accumulators,
        store_raw: opts.store_raw,
        compression: opts.compression,
        provenance: input
            .provenance
            .iter()
            .cloned()
            .chain([Provenance::identity(crate::store::GENERATOR_VERSION, version_text())])
            .collect(),
        part: opts.part,
    }
}

/// Simulates and writes every shard of the run that the file does not hold yet, in shard order, calling
/// `progress(done, total)` before the first and after each.
fn simulate_pending_shards(
    writer: &mut RunWriter,
    meta: &RunMetadata,
    plan: &Plan,
    input: &RunInput,
    opts: &RunOptions,
    bands: &[OutputBands],
    progress: &dyn Fn(usize, usize),
) -> Result<()> {
    let n_shards = meta.local_shards().len();
    let mut done = writer.completed_shards().len();
    progress(done, n_shards);
    for shard in writer.pending_shards() {
        let range = meta.shard_range(shard);
        let batch = run_batch_groups(
            opts.seed,
            range.start as u64..range.end as u64,
            || Scratch::new(plan),
            |s, group| realize_group(plan, s, opts, &input.verdicts, group),
        )?;
        let (results, verdicts): (Vec<Realization>, Vec<Vec<Vec<f64>>>) = batch.into_results().into_iter().unzip();
        let mut extra = input.verdicts.encode(&verdicts, meta.shard_size);
        extra.extend(super::bands::encode_shard(
            bands,
            results.len(),
            &|i, r| &results[i].welch[r],
            meta.shard_size,
        )?);
        write_shard(writer, shard, &results, plan, meta.shard_size, opts.store_raw, &extra)?;
        done += 1;
        progress(done, n_shards);
    }
    Ok(())
}

/// The statistics and the density estimate of every output, from the accumulators of every shard in shard
/// order; `expected` is the exact mean of each output's Welch estimate.
fn output_results(
    input: &RunInput,
    writer: &RunWriter,
    meta: &RunMetadata,
    plan: &Plan,
    opts: &RunOptions,
    expected: Vec<Vec<f64>>,
) -> Result<(Vec<OutputStatistics>, Vec<crate::store::PsdEstimate>)> {
    let mut stats = Vec::new();
    let mut psds = Vec::new();
    let acc = |name: &str, shard: usize| writer.read_accumulator(name, shard);
    for (o, exp) in plan.outputs.iter().zip(expected) {
        let (m, v, ws) = read_output(&acc, meta, &o.signal.name, &plan.welch)?;
        super::agreement::check_mean_square(o, &v)?;
        let analytic = Analytic::from_variances(o.analytic_variance, o.discrete_variance);
        stats.push(output_statistics(&o.signal, &analytic, &m, &v, opts.confidence)?);
        let mut psd = density_estimate(&o.signal, &plan.welch, &ws, opts.confidence, |omega| {
            Ok(Some(
                omega
                    .iter()
                    .map(|&w| output_density(input.system, input.excitation, o.index, w))
                    .collect(),
            ))
        })?;
        psd.expected = Some(exp);
        psds.push(psd);
    }
    Ok((stats, psds))
}

/// Appends the band r.m.s. statistics of every output with a band table to its statistics.
fn add_band_statistics(
    writer: &RunWriter,
    meta: &RunMetadata,
    plan: &Plan,
    bands: &[OutputBands],
    opts: &RunOptions,
    stats: &mut [OutputStatistics],
) -> Result<()> {
    let acc = |name: &str, shard: usize| writer.read_accumulator(name, shard);
    let local: Vec<(usize, usize)> = meta.local_shards().map(|s| (s, meta.shard_range(s).len())).collect();
    for ob in bands {
        let o = &plan.outputs[ob.output];
        let per_band = super::bands::read_bands(&acc, &o.signal.name, &local, meta.shard_size)?;
        let labels: Vec<String> = ob.bands.iter().map(|b| b.label()).collect();
        let rms = |v: &[f64]| v.iter().map(|x| Some(x.max(0.0).sqrt())).collect::<Vec<_>>();
        stats[ob.output].statistics.extend(super::bands::band_statistics(
            &o.signal.unit,
            &labels,
            &per_band,
            &rms(&ob.analytic),
            &rms(&ob.expected),
            opts.confidence,
        )?);
    }
    Ok(())
}

/// The summary of a finished run file of this plan (a shard that is already complete).
pub(crate) fn summary_of_file(run: &RunFile, plan: &Plan, notes: Vec<String>) -> Result<RunSummary> {
    let m = run.metadata();
    Ok(RunSummary {
        path: run.path().to_path_buf(),
        route: plan.route,
        generator: plan.generator.clone(),
        n_samples: m.n_samples,
        dt_s: m.dt,
        n_realizations: m.n_realizations,
        n_shards: m.local_shards().len(),
        resumed_shards: m.local_shards().len(),
        part: m.part,
        realizations: m.local_realizations(),
        basic_method: super::basic_method_rows(&run.statistics()?, m.n_samples as f64 * m.dt),
        outputs: run.statistics()?,
        skipped: plan.skipped.clone(),
        notes,
        rainflow: Vec::new(),
    })
}

/// The realizations of `group` (consecutive, of the run's seed) with their verdict values: a whole group
/// of the exact route in blocks in lockstep ([`realize_lanes`], bit-identical to one at a time), any other
/// one at a time.
fn realize_group(
    plan: &Plan,
    s: &mut Scratch,
    opts: &RunOptions,
    verdicts: &super::VerdictChannels,
    group: std::ops::Range<u64>,
) -> Result<Vec<(Realization, Vec<Vec<f64>>)>> {
    match &plan.engine {
        Engine::Exact(gm) if plan.block_steps > 0 && !opts.store_raw && group.end - group.start == LANES as u64 => {
            let names: Vec<&str> = plan.outputs.iter().map(|o| o.signal.name.as_str()).collect();
            let mut vs = match verdicts.is_empty() {
                true => Vec::new(),
                false => (0..LANES)
                    .map(|_| VerdictStream::new(verdicts, opts.dt_s, &names))
                    .collect::<Result<Vec<_>>>()?,
            };
            let channels = (!vs.is_empty()).then_some(vs.as_mut_slice());
            let results = realize_lanes(plan, gm, s, (opts.seed, group.start), channels)?;
            if vs.is_empty() {
                return Ok(results.into_iter().map(|r| (r, Vec::new())).collect());
            }
            results.into_iter().zip(vs).map(|(r, v)| Ok((r, v.finish()?))).collect()
        }
        _ => group
            .map(|i| realize_with_verdicts(plan, s, &mut stream(opts.seed, i), opts, verdicts))
            .collect(),
    }
}

/// One realization and, when the run has verdict channels, their per-realization values (the raw samples
/// are kept only as long as the channels need them, unless the run stores them).
fn realize_with_verdicts(
    plan: &Plan,
    s: &mut Scratch,
    rng: &mut rand::rngs::Xoshiro256PlusPlus,
    opts: &RunOptions,
    verdicts: &super::VerdictChannels,
) -> Result<(Realization, Vec<Vec<f64>>)> {
    if verdicts.is_empty() {
        return Ok((realize(plan, s, rng, opts.store_raw, None)?, Vec::new()));
    }
    // the block-wise routes (statistics only) evaluate the channels block by block, bit-identical to the
    // whole record
    if plan.block_steps > 0 && !opts.store_raw {
        let names: Vec<&str> = plan.outputs.iter().map(|o| o.signal.name.as_str()).collect();
        let mut vs = VerdictStream::new(verdicts, opts.dt_s, &names)?;
        let re = realize(plan, s, rng, false, Some(&mut vs))?;
        return Ok((re, vs.finish()?));
    }
    let mut re = realize(plan, s, rng, true, None)?;
    let signal = |name: &str| {
        plan.outputs
            .iter()
            .position(|o| o.signal.name == name)
            .map(|r| re.raw[r].as_slice())
    };
    let values = verdicts.evaluate(opts.dt_s, &signal)?;
    if !opts.store_raw {
        re.raw = Vec::new();
        re.raw_inputs = Vec::new();
    }
    Ok((re, values))
}

/// The verdict statistics (appended to their outputs' statistics; the analytic VDV is (3T)^{1/4}·σ_d of
/// the simulated discretised weighted output, (κ_w T)^{1/4}·σ_d with its exact kurtosis κ_w for a
/// non-Gaussian input) and the rainflow histograms, from the accumulators.
fn finish_verdicts(
    input: &RunInput,
    writer: &RunWriter,
    meta: &RunMetadata,
    plan: &Plan,
    opts: &RunOptions,
    stats: &mut [OutputStatistics],
) -> Result<Vec<super::RainflowSummary>> {
    if input.verdicts.is_empty() {
        return Ok(Vec::new());
    }
    // the file's own shards (all of them but for a shard file of a cluster run)
    let local = meta.local_shards();
    let rows: Vec<usize> = local.clone().map(|s| meta.shard_range(s).len()).collect();
    let duration = opts.dt_s * plan.n as f64;
    let (comfort, fatigue) = input.verdicts.finish(
        &|name, k| writer.read_accumulator(name, local.start + k),
        &rows,
        meta.shard_size,
        duration,
        opts.confidence,
    )?;
    for (output, mut extra) in comfort {
        if let Some(o) = plan.outputs.iter().find(|o| o.signal.name == output) {
            match o.kurtosis {
                None => {
                    let vdv = (3.0 * duration).powf(0.25) * o.discrete_variance.sqrt();
                    super::verdicts::set_analytic(&mut extra, "vdv", vdv);
                }
                Some(kappa) => super::verdicts::set_non_gaussian_vdv(
                    &mut extra,
                    &super::verdicts::WeightedProcess {
                        kurtosis: kappa,
                        variance: o.discrete_variance,
                        duration_s: duration,
                    },
                ),
            }
        }
        if let Some(st) = stats.iter_mut().find(|s| s.output == output) {
            st.statistics.extend(extra);
        }
    }
    let mut hist = Vec::new();
    for ((output, mut st, mut h), ch) in fatigue.into_iter().zip(&input.verdicts.fatigue) {
        // Dirlik's rate is a Gaussian result: for a non-Gaussian output it is no prediction to compare with
        if let Some(kappa) = plan
            .outputs
            .iter()
            .find(|o| o.signal.name == output)
            .and_then(|o| o.kurtosis)
        {
            super::verdicts::unset_gaussian_damage(&mut st, kappa);
        }
        if let Some(s) = stats.iter_mut().find(|s| s.output == output) {
            s.statistics.push(st);
        }
        h.unit = ch.sn_unit.clone();
        hist.push(h);
    }
    Ok(hist)
}

/// Refuses a run file that is one of the files the run is read from (a scenario or spectrum file would
/// be replaced by HDF5).
fn refuse_inputs_as_output(input: &RunInput, out: &Path) -> Result<()> {
    if let Some(f) = input.source_files.iter().find(|f| crate::io_rules::same_file(f, out)) {
        return Err(crate::Error::Hdf5 {
            path: out.to_path_buf(),
            reason: format!(
                "is an input of the run ({}, the same file): choose another output",
                f.display()
            ),
        });
    }
    Ok(())
}

/// Runs into a temporary file `stochvib-run-<pid>.h5` in `dir`, hands the finished file to `then` (e.g. to
/// draw its pictures), and removes the file and its `.tmp` afterwards, whether the run succeeded or not;
/// what killed earlier temporary runs left in `dir` is removed first.
///
/// # Errors
/// As [`run`].
///
/// # Examples
/// ```
/// use stochvib::scenario::load_scenario;
/// use stochvib::simulate::{run_temporary, RunOptions};
/// use std::path::Path;
/// let sc = load_scenario(Path::new("data/conveyor-idler.toml"), Path::new("spectra")).unwrap();
/// let dir = std::env::temp_dir();
/// let opts = RunOptions { realizations: 10, duration_s: 2.0, dt_s: 0.01, seed: 1, ..RunOptions::default() };
/// let (s, existed) = run_temporary(&sc.run_input(), &opts, &dir, &|_, _| {}, |p| p.is_file())
///     .unwrap();
/// assert!(existed && !s.path.exists());
/// ```
pub fn run_temporary<T>(
    input: &RunInput,
    opts: &RunOptions,
    dir: &Path,
    progress: &dyn Fn(usize, usize),
    then: impl FnOnce(&Path) -> T,
) -> Result<(RunSummary, T)> {
    run_temporary_with(dir, |path| run(input, opts, path, progress), then)
}

/// As [`run_temporary`], with the run done by `runner(path)` (e.g. a scenario's run with its verdict
/// channels, `Scenario::simulate`).
///
/// # Errors
/// What `runner` returns.
pub fn run_temporary_with<T>(
    dir: &Path,
    runner: impl FnOnce(&Path) -> Result<RunSummary>,
    then: impl FnOnce(&Path) -> T,
) -> Result<(RunSummary, T)> {
    struct Remove(std::path::PathBuf);
    impl Drop for Remove {
        fn drop(&mut self) {
            let _ = std::fs::remove_file(&self.0);
            let _ = std::fs::remove_file(crate::store::tmp_path(&self.0));
        }
    }
    remove_dead_temporaries(dir);
    let path = dir.join(format!("stochvib-run-{}.h5", std::process::id()));
    let guard = Remove(path.clone());
    drop(Remove(path.clone())); // a leftover of an earlier process with the same id
    let summary = runner(&guard.0)?;
    let t = then(&guard.0);
    Ok((summary, t))
}

/// Removes what killed temporary runs left in `dir`: `stochvib-run-<pid>.h5*` files of processes that no
/// longer exist.
fn remove_dead_temporaries(dir: &Path) {
    let Ok(rd) = std::fs::read_dir(dir) else { return };
    for e in rd.flatten() {
        let name = e.file_name().to_string_lossy().into_owned();
        let Some(rest) = name.strip_prefix("stochvib-run-") else {
            continue;
        };
        let Some((pid, _)) = rest.split_once(".h5") else {
            continue;
        };
        if let Ok(pid) = pid.parse::<u32>()
            && pid != std::process::id()
            && !crate::store::process_alive(pid)
        {
            let _ = std::fs::remove_file(e.path());
        }
    }
}

/// Writes one shard: its accumulators and, with raw storage, its realizations.
fn write_shard(
    writer: &mut RunWriter,
    shard: usize,
    results: &[Realization],
    plan: &Plan,
    shard_size: usize,
    store_raw: bool,
    extra: &[Vec<f64>],
) -> Result<()> {
    let (rows, n, p) = (results.len(), plan.n, plan.outputs.len());
    let mut accs: Vec<Vec<f64>> = Vec::with_capacity(2 * p);
    for r in 0..p {
        let moments = Moments {
            mean: results.iter().map(|re| re.m[r]).collect(),
            mean_square: results.iter().map(|re| re.v[r]).collect(),
        };
        let mut ws = plan.welch.sums();
        for re in results {
            ws.merge(&re.welch[r])?;
        }
        accs.push(moments.encode(shard_size));
        accs.push(WelchAccumulator(ws).encode());
    }
    let raw_of = |pick: &dyn Fn(&Realization) -> &Vec<Vec<f64>>, count: usize| -> Vec<Array2<f64>> {
        (0..count)
            .map(|r| Array2::from_shape_fn((rows, n), |(i, k)| pick(&results[i])[r][k]))
            .collect()
    };
    let (raw, raw_in) = if store_raw {
        (
            raw_of(&|re| &re.raw, p),
            raw_of(&|re| &re.raw_inputs, plan.input_signals.len()),
        )
    } else {
        (vec![], vec![])
    };
    let views: Vec<_> = raw.iter().map(|a| a.view()).collect();
    let in_views: Vec<_> = raw_in.iter().map(|a| a.view()).collect();
    let acc_refs: Vec<&[f64]> = accs.iter().chain(extra).map(|a| a.as_slice()).collect();
    writer.write_shard(shard, &in_views, &views, &acc_refs)
}
