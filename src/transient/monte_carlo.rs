//! Monte Carlo of a non-stationary response: realizations stepped exactly with the frozen coefficients,
//! the ensemble statistics at every stored time written to a run file beside the exact curves; resumable,
//! in cluster shards, and merged bit-identically (layout: `docs/transients.md`, "The `/transient` group of a run file").

use super::mc_engine::{McGrid, McPlan, RealizationState, ShardBlock};
use super::mc_finish::{finish, is_transient_layout, layout, AnalyticOutput, AnalyticSide, Finished, MaximaVerdicts};
use super::series::TransientSolution;
use super::system::{Start, TimeVaryingSystem};
use crate::error::{Error, Result};
use crate::store::{
    Compression, CreateOptions, OutputStatistics, Part, Provenance, RunFile, RunMetadata, RunWriter, Signal,
};
use ndarray::Array2;
use rayon::prelude::*;
use std::path::{Path, PathBuf};

/// Options of a transient Monte Carlo run.
#[derive(Debug, Clone, PartialEq)]
pub struct TransientRunOptions {
    /// Realizations.
    pub realizations: usize,
    /// The grid.
    pub grid: McGrid,
    /// Master seed; realization i uses stream (seed, i).
    pub seed: u64,
    /// Realizations per shard.
    pub shard_size: usize,
    /// Confidence of the intervals and of the DKW band.
    pub confidence: f64,
    /// Store every realization at the stored times.
    pub store_raw: bool,
    /// Compression of the raw data.
    pub compression: Compression,
    /// The part of a cluster run (`--shard I --of N`).
    pub part: Option<Part>,
    /// Replace a finished file / discard an interrupted run of other settings.
    pub overwrite: bool,
    /// Refuse a batch whose computing time's lower bound exceeds this many hours (the stationary runs' cap,
    /// [`crate::simulate::resources::DEFAULT_MAX_HOURS`], by default in the CLI).
    pub max_hours: f64,
}

/// What a run is made of besides its options.
#[derive(Debug, Clone)]
pub struct TransientRunInput<'a> {
    /// The system and input.
    pub sys: &'a TimeVaryingSystem,
    /// Output indices to simulate.
    pub outputs: Vec<usize>,
    /// The start.
    pub start: Start,
    /// The exact solution at the grid's stored times (the analytic curves).
    pub exact: &'a TransientSolution,
    /// Whether Vanmarcke's stationary form applies (time-invariant, stationary start).
    pub stationary: bool,
    /// The scenario text (identifies the run).
    pub scenario_text: String,
    /// What else identifies the run.
    pub provenance: Vec<Provenance>,
}

/// What a transient run (or merge) did.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct TransientRunSummary {
    /// The run file.
    pub path: PathBuf,
    /// Realizations of the run.
    pub n_realizations: usize,
    /// Internal shards of this file.
    pub n_shards: usize,
    /// Shards found complete on disk (resumed).
    pub resumed_shards: usize,
    /// The part, for a cluster shard.
    pub part: Option<Part>,
    /// The statistics of the last stored time.
    pub outputs: Vec<OutputStatistics>,
    /// The maxima verdicts.
    pub verdicts: Vec<MaximaVerdicts>,
    /// Fraction of stored times at which the σ interval covers the exact σ, per output.
    pub sigma_coverage: Vec<(String, f64)>,
    /// DKW half-width.
    pub dkw_epsilon: f64,
    /// Remarks.
    pub notes: Vec<String>,
}

/// The generator text of a transient run.
fn generator(grid: &McGrid) -> String {
    format!(
        "{}; transient: exact transition of the frozen coefficients at the step midpoints (Van Loan), dt = {} s, \
         stored every {} steps",
        crate::simulate::GENERATOR,
        grid.dt,
        grid.store_every
    )
}

/// What identifies a run besides its options: the outputs, the scenario text, the provenance, the generator.
pub(crate) struct RunIdentity {
    /// The simulated outputs.
    pub outputs: Vec<Signal>,
    /// The scenario text.
    pub scenario_text: String,
    /// What else identifies the run.
    pub provenance: Vec<Provenance>,
    /// The generator text.
    pub generator: String,
}

/// The metadata of the run.
pub(crate) fn metadata(id: RunIdentity, opts: &TransientRunOptions) -> Result<RunMetadata> {
    let names: Vec<String> = id.outputs.iter().map(|s| s.name.clone()).collect();
    let shard_size = opts.shard_size.min(opts.realizations).max(1);
    let meta = RunMetadata {
        scenario_text: id.scenario_text,
        seed: opts.seed,
        generator: id.generator,
        dt: opts.grid.dt * opts.grid.store_every as f64,
        n_samples: opts.grid.n_stored(),
        n_realizations: opts.realizations,
        shard_size,
        inputs: vec![],
        outputs: id.outputs,
        accumulators: layout(&names, opts.grid.n_stored(), shard_size),
        store_raw: opts.store_raw,
        compression: opts.compression,
        provenance: id.provenance,
        part: opts.part,
    };
    meta.validate()?;
    Ok(meta)
}

/// The analytic side from the exact solution.
fn analytic(input: &TransientRunInput<'_>) -> Result<AnalyticSide> {
    let method = format!(
        "differential Lyapunov equation, matrix exponentials on an adaptive grid ({} steps, {} exact), accumulated \
         error estimate {:.1e} relative to the largest variance of each state",
        input.exact.report.steps, input.exact.report.exact_steps, input.exact.report.max_error_estimate
    );
    let fr0 = if input.stationary {
        Some(input.sys.frozen(0.0)?)
    } else {
        None
    };
    super::mission::analytic_side(input.exact, fr0.as_ref(), &input.outputs, method)
}

/// Runs the transient Monte Carlo batch into `out` (resuming an interrupted run of the same settings).
///
/// # Formula
/// Realization i draws from stream (seed, i): n normals for z₀ = m₀ + L₀ε (L₀L₀ᵀ = P(0)), then n normals per
/// step for z ← Φ_jz + Γ_j + L_jε_j, with Φ_j, Q_j = L_jL_jᵀ, Γ_j the exact transition over the step of the
/// coefficients frozen at its midpoint (exact for coefficients constant over the step). At every stored
/// time the shard stores the mean and M₂ of its realizations (two passes, realization order), and every
/// realization's max y and max |y| over all grid points; the statistics fold the shards in order
/// ([`super::mc_finish::finish`]).
///
/// # Errors
/// Invalid options; the plan's, the store's and the exact route's errors; an existing finished `out`
/// without `overwrite`.
pub fn run_transient(
    input: &TransientRunInput<'_>,
    opts: &TransientRunOptions,
    out: &Path,
    progress: &dyn Fn(usize, usize),
) -> Result<TransientRunSummary> {
    check_options(opts, &input.exact.times)?;
    let plan = McPlan::new(input.sys, input.outputs.clone(), &input.start, opts.grid)?;
    let id = RunIdentity {
        outputs: input
            .outputs
            .iter()
            .map(|&i| {
                let o = &input.sys.outputs()[i];
                Signal::new(&o.name, &o.unit)
            })
            .collect(),
        scenario_text: input.scenario_text.clone(),
        provenance: input.provenance.clone(),
        generator: generator(&opts.grid),
    };
    let meta = metadata(id, opts)?;
    check_resources(&meta, opts, input.sys.n_states(), out)?;
    run_batch(&plan, &meta, &analytic(input)?, opts, out, progress)
}

/// Writes the pending shards of `meta` run by `source` into `out` (resuming), then the statistics.
pub(crate) fn run_batch(
    source: &dyn ShardSource,
    meta: &RunMetadata,
    analytic: &AnalyticSide,
    opts: &TransientRunOptions,
    out: &Path,
    progress: &dyn Fn(usize, usize),
) -> Result<TransientRunSummary> {
    let mut writer = RunWriter::create_with(
        out,
        meta,
        CreateOptions {
            overwrite: opts.overwrite,
            ..CreateOptions::default()
        },
    )?;
    let notes = writer.notes().to_vec();
    let n_shards = meta.local_shards().len();
    let resumed = writer.completed_shards().len();
    progress(resumed, n_shards);
    let mut done = resumed;
    write_while_computing(
        &writer.pending_shards(),
        |shard| run_shard(source, meta, meta.shard_range(shard), opts),
        |shard, (accs, raw)| {
            let acc_refs: Vec<&[f64]> = accs.iter().map(|a| a.as_slice()).collect();
            let raw_views: Vec<_> = raw.iter().map(|a| a.view()).collect();
            writer.write_shard(shard, &[], &raw_views, &acc_refs)?;
            done += 1;
            progress(done, n_shards);
            Ok(())
        },
    )?;
    let times = opts.grid.stored_times();
    let fin = finish(
        &|name, b| writer.read_accumulator(name, b),
        meta,
        &times,
        analytic,
        opts.confidence,
    )?;
    write_finished(&mut writer, &fin)?;
    let path = writer.finish()?;
    Ok(summary(path, meta, resumed, fin, notes))
}

/// Computes `shards` in order with `compute` (which may run in parallel on the current rayon pool) and hands
/// each to `write` on the calling thread, in order, writing shard k while shard k + 1 is computed by the
/// pool: the write (HDF5, checksums) and the progress report no longer leave the other threads idle, and the
/// shards, computed by the same code, have the same bits. The next shard is a job spawned in an
/// [`rayon::in_place_scope`], so the write and the progress callback run on the calling thread, and the
/// scope's end waits for that job as rayon waits (a pool thread that calls this helps compute it; a stop
/// that unwinds from `write` waits for it too): nothing blocks a pool thread outside rayon, which would
/// deadlock the shard's own parallel loops.
///
/// # Errors
/// The first error of `compute` or `write`, in shard order (a shard computed ahead is then dropped).
fn write_while_computing<T: Send>(
    shards: &[usize],
    compute: impl Fn(usize) -> Result<T> + Sync,
    mut write: impl FnMut(usize, T) -> Result<()>,
) -> Result<()> {
    let mut ready: Option<(usize, T)> = None;
    for &shard in shards {
        let mut next = None;
        let written = rayon::in_place_scope(|scope| {
            scope.spawn(|_| next = Some(compute(shard)));
            ready.take().map_or(Ok(()), |(s, data)| write(s, data))
        });
        written?;
        let data = next.unwrap_or_else(|| unreachable!("the scope ran the spawned job"))?;
        ready = Some((shard, data));
    }
    ready.map_or(Ok(()), |(s, data)| write(s, data))
}

/// Refuses, before anything is allocated or written, a batch whose computing time's lower bound exceeds
/// `opts.max_hours` or whose run file would not fit on the disk of `out` — the rules of the stationary runs.
///
/// # Formula
/// Time ≥ R·N·g / (r·P) ([`crate::simulate::resources::run_time_lower_bound`]): R realizations of this file,
/// N = the grid's steps, g the normals drawn per step (one per state of the augmented system), r the fastest
/// normal draw rate, P threads.
/// File: [`RunMetadata::estimated_file_bytes`].
pub(crate) fn check_resources(meta: &RunMetadata, opts: &TransientRunOptions, states: usize, out: &Path) -> Result<()> {
    use crate::simulate::resources::{check_disk, run_time_lower_bound};
    if opts.max_hours.is_nan() || opts.max_hours <= 0.0 {
        return Err(Error::invalid("max hours", opts.max_hours, "must be > 0"));
    }
    let local = meta.local_realizations().len();
    let threads = rayon::current_num_threads();
    let t = run_time_lower_bound(local as f64, opts.grid.n_steps, states, threads);
    crate::io_rules::check_time(
        t,
        opts.max_hours,
        "realizations",
        opts.realizations,
        &format!(
            "{local} realizations × {} steps × {states} states on {threads} threads",
            opts.grid.n_steps
        ),
        "fewer realizations, fewer --substeps, or a cluster run (--shard I --of N)",
    )?;
    check_disk(meta, out)
}

/// Refuses R < 2, a confidence outside (0, 1), and analytic curves not at the grid's stored times.
pub(crate) fn check_options(opts: &TransientRunOptions, exact_times: &[f64]) -> Result<()> {
    if opts.realizations < 2 {
        return Err(Error::invalid("realizations", opts.realizations, "need at least 2"));
    }
    if !(opts.confidence > 0.0 && opts.confidence < 1.0) {
        return Err(Error::invalid("confidence", opts.confidence, "must be in (0, 1)"));
    }
    let times = opts.grid.stored_times();
    if exact_times.len() != times.len()
        || exact_times
            .iter()
            .zip(&times)
            .any(|(a, b)| (a - b).abs() > 1e-9 * b.max(1.0))
    {
        return Err(Error::invalid(
            "exact",
            exact_times.len(),
            "the exact solution must be computed at the grid's stored times",
        ));
    }
    Ok(())
}

/// A shard's accumulators (in the layout's order) and its raw rows per output (empty without raw storage).
type ShardData = (Vec<Vec<f64>>, Vec<Array2<f64>>);

/// Every realization's largest y and largest |y| per output over the grid.
pub(crate) type Maxima = (Vec<f64>, Vec<f64>);

/// What steps the realizations of a shard: the exact transitions of the frozen coefficients ([`McPlan`]) or
/// the road synthesised on a spatial grid ([`super::road_grid_run`]).
pub(crate) trait ShardSource: Sync {
    /// The number of simulated outputs.
    fn n_outputs(&self) -> usize;
    /// Runs realizations `range` (realization i from stream (seed, i)), handing the stored outputs to `sink`
    /// block by block in time order; returns every realization's maxima.
    fn realizations(
        &self,
        range: std::ops::Range<usize>,
        seed: u64,
        sink: &mut dyn FnMut(ShardBlock),
    ) -> Result<Vec<Maxima>>;
}

impl ShardSource for McPlan<'_> {
    fn n_outputs(&self) -> usize {
        self.outputs().len()
    }

    fn realizations(
        &self,
        range: std::ops::Range<usize>,
        seed: u64,
        sink: &mut dyn FnMut(ShardBlock),
    ) -> Result<Vec<Maxima>> {
        let mut states: Vec<RealizationState> = range.map(|i| self.initial(seed, i as u64)).collect();
        for (j0, j1) in self.blocks() {
            sink(self.advance(&mut states, j0, j1)?);
        }
        Ok(states.into_iter().map(|s| (s.max_y, s.max_abs)).collect())
    }
}

/// One shard, the realizations `range`: its accumulators (in the layout's order) and, with raw storage, its
/// rows per output.
fn run_shard(
    source: &dyn ShardSource,
    meta: &RunMetadata,
    range: std::ops::Range<usize>,
    opts: &TransientRunOptions,
) -> Result<ShardData> {
    let (p, k, ss) = (source.n_outputs(), meta.n_samples, meta.shard_size);
    let rows = range.len();
    let mut series = vec![vec![0.0; 2 * k]; p];
    let mut raw = if opts.store_raw {
        vec![Array2::<f64>::zeros((rows, k)); p]
    } else {
        Vec::new()
    };
    let maxima = source.realizations(range, opts.seed, &mut |block| {
        for (c, (mean, m2)) in block_moments(&block, rows).into_iter().enumerate() {
            let (at, o) = (block.first_stored + c / p, c % p);
            (series[o][at], series[o][k + at]) = (mean, m2);
            if opts.store_raw {
                for (r, v) in block.stored.chunks_exact(block.width).enumerate() {
                    raw[o][(r, at)] = v[c];
                }
            }
        }
    })?;
    let mut accs = Vec::with_capacity(2 * p);
    for (o, s) in series.into_iter().enumerate() {
        accs.push(s);
        let mut m = vec![0.0; 2 * ss];
        for (r, (max_y, max_abs)) in maxima.iter().enumerate() {
            m[r] = max_y[o];
            m[ss + r] = max_abs[o];
        }
        accs.push(m);
    }
    Ok((accs, raw))
}

/// Columns of a block whose moments are summed together (a vector of sums over contiguous values).
const MOMENT_COLUMNS: usize = 64;

/// The mean and M₂ of every column of `block` over its `rows` realizations: per column
/// m = (Σ_r y_r)/R and M₂ = Σ_r (y_r − m)², each sum from −0.0 in realization order (as `Iterator::sum`
/// over the column); the columns in parallel, [`MOMENT_COLUMNS`] at a time.
fn block_moments(block: &ShardBlock, rows: usize) -> Vec<(f64, f64)> {
    let w = block.width;
    let starts: Vec<usize> = (0..w).step_by(MOMENT_COLUMNS).collect();
    let parts: Vec<Vec<(f64, f64)>> = starts
        .into_par_iter()
        .map(|c0| {
            let cols = c0..(c0 + MOMENT_COLUMNS).min(w);
            let mut mean = vec![-0.0; cols.len()];
            for row in block.stored.chunks_exact(w) {
                mean.iter_mut().zip(&row[cols.clone()]).for_each(|(a, v)| *a += v);
            }
            mean.iter_mut().for_each(|m| *m /= rows as f64);
            let mut m2 = vec![-0.0; cols.len()];
            for row in block.stored.chunks_exact(w) {
                let d = m2.iter_mut().zip(&mean).zip(&row[cols.clone()]);
                d.for_each(|((a, m), v)| *a += (v - m) * (v - m));
            }
            mean.into_iter().zip(m2).collect()
        })
        .collect();
    parts.concat()
}

fn write_finished(writer: &mut RunWriter, fin: &Finished) -> Result<()> {
    writer.write_statistics(&fin.statistics)?;
    writer.write_transient(&fin.series)
}

fn summary(
    path: PathBuf,
    meta: &RunMetadata,
    resumed: usize,
    fin: Finished,
    notes: Vec<String>,
) -> TransientRunSummary {
    let sigma_coverage = fin
        .series
        .outputs
        .iter()
        .map(|o| {
            let covered = (0..o.sigma.len())
                .filter(|&j| o.sigma_lower[j] <= o.exact_sigma[j] && o.exact_sigma[j] <= o.sigma_upper[j])
                .count();
            (o.output.clone(), covered as f64 / o.sigma.len() as f64)
        })
        .collect();
    TransientRunSummary {
        path,
        n_realizations: meta.n_realizations,
        n_shards: meta.local_shards().len(),
        resumed_shards: resumed,
        part: meta.part,
        outputs: fin.statistics,
        verdicts: fin.verdicts,
        sigma_coverage,
        dkw_epsilon: fin.series.dkw_epsilon,
        notes,
    }
}

/// Whether the run file at `path` (or the first run file among shard inputs) is a transient run.
pub fn is_transient_run(meta: &RunMetadata) -> bool {
    is_transient_layout(&meta.accumulators)
}

/// Finishes the merged file of a transient run whose parts' shards `writer` has adopted: the statistics by
/// the code of a single-process run (so they are bit-identical) from the accumulators in shard order, the
/// analytic side from `stored` (the `/transient` group of the first part file, which every part stores alike),
/// the intervals at `confidence`; `notes` are the merge's remarks. The merge of the part files itself is
/// [`crate::study::merge_transient`].
///
/// # Errors
/// The store's errors reading the accumulators and writing the statistics.
pub fn finish_merged(
    mut writer: RunWriter,
    meta: &RunMetadata,
    stored: &crate::store::transient_series::TransientSeries,
    confidence: f64,
    notes: Vec<String>,
) -> Result<TransientRunSummary> {
    let analytic = AnalyticSide {
        method: stored.exact_method.clone(),
        outputs: stored.outputs.iter().map(AnalyticOutput::from_stored).collect(),
    };
    let fin = finish(
        &|name, b| writer.read_accumulator(name, b),
        meta,
        &stored.times,
        &analytic,
        confidence,
    )?;
    write_finished(&mut writer, &fin)?;
    let path = writer.finish()?;
    Ok(summary(path, meta, 0, fin, notes))
}

/// Reads the finished transient series and statistics of a run file (for `inspect` and `plot`).
///
/// # Errors
/// The store's errors; a run file that is not a transient run.
pub fn read_transient_run(path: &Path) -> Result<(RunFile, crate::store::transient_series::TransientSeries)> {
    let run = RunFile::open(path)?;
    let series = run.transient()?.ok_or_else(|| Error::Hdf5 {
        path: path.to_path_buf(),
        reason: "not a transient run (no /transient group)".into(),
    })?;
    Ok((run, series))
}

#[cfg(test)]
mod tests {
    use super::write_while_computing;
    use crate::error::{Error, Result};
    use rayon::prelude::*;

    /// A shard's value computed by a parallel loop inside the job (as a transient shard's lanes are): the sum
    /// of i·shard over 2000 items, worked by hand as shard·(0 + … + 1999) = shard·1 999 000.
    fn compute(shard: usize) -> Result<u64> {
        Ok((0..2000u64).into_par_iter().map(|i| i * shard as u64).sum())
    }

    /// Every shard written once, in order, with its own value: called from a thread outside any pool (the
    /// global pool computes) and from a thread of pools of 1, 2 and 3 threads (`install`: that thread helps
    /// compute); the parallel loop inside each shard's job does not deadlock (a pool thread blocked outside
    /// rayon would hang this test).
    #[test]
    fn every_shard_written_in_order_with_its_value() {
        let shards = [3usize, 0, 7, 1, 9];
        let want: Vec<(usize, u64)> = shards.iter().map(|&s| (s, s as u64 * 1_999_000)).collect();
        let run = || {
            let mut got = Vec::new();
            write_while_computing(&shards, compute, |s, v| {
                got.push((s, v));
                Ok(())
            })
            .unwrap();
            got
        };
        assert_eq!(run(), want, "outside any pool");
        for threads in [1, 2, 3] {
            let pool = rayon::ThreadPoolBuilder::new().num_threads(threads).build().unwrap();
            assert_eq!(pool.install(run), want, "inside a pool of {threads} threads");
        }
    }

    /// A shard's error comes back after the shards before it are written and stops the run; so does a
    /// write's error; a panic in the write (a stop requested from a progress callback) unwinds out.
    #[test]
    fn errors_in_shard_order_and_a_panic_unwinds() {
        let failing = |s: usize| {
            if s == 2 {
                Err(Error::invalid("shard", s, "fails"))
            } else {
                compute(s)
            }
        };
        let mut written = Vec::new();
        let e = write_while_computing(&[0, 1, 2, 3], failing, |s, _| {
            written.push(s);
            Ok(())
        })
        .unwrap_err();
        assert!(e.to_string().contains("fails") && written == [0, 1], "{e}, {written:?}");
        let mut written = Vec::new();
        let e = write_while_computing(&[0, 1, 2, 3], compute, |s, _| {
            written.push(s);
            if s == 1 {
                Err(Error::invalid("write", s, "disk full"))
            } else {
                Ok(())
            }
        })
        .unwrap_err();
        assert!(
            e.to_string().contains("disk full") && written == [0, 1],
            "{e}, {written:?}"
        );
        let unwound = std::panic::catch_unwind(|| {
            let _ = write_while_computing(&[0, 1, 2], compute, |s, _| if s == 1 { panic!("stop") } else { Ok(()) });
        });
        assert!(unwound.is_err());
    }
}
