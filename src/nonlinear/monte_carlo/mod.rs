//! Route 2: nonlinear Monte Carlo in the time domain, written to HDF5 run files like linear runs (shards,
//! resume, cluster parts and their bit-identical merge, `inspect`, `plot`).
//!
//! # Method
//! * Inputs: the processes of linear runs. On the exact route (delay-free rational Gaussian inputs) the
//!   linear part is augmented with the inputs' shaping filters and discretised by Van Loan's method, with the
//!   same draws as a linear run; elsewhere (delays, two coherent tracks, non-rational or non-Gaussian
//!   inputs) the linear runs' spectral generators synthesise the input samples ([`inputs`]) and the linear
//!   part follows their first-order hold.
//! * Integrator: the symmetric splitting of [`crate::nonlinear::integrator`] (exact linear flow, exact
//!   element flows), second order; every run reports the Δt-halving difference of the mean and σ of each
//!   output on its first realizations (the same noise path at Δt and Δt/2).
//! * Burn-in: computed from the system, [`BURN_IN_DECAY`]/σ_min with σ_min the slowest decay rate of the
//!   Gaussian equivalent (route 1), from its stationary law on the exact route and from rest on the spectral
//!   route.
//! * Per realization and output ([`record`]): mean, σ, kurtosis, max |y|, up-crossing rates of the levels
//!   (the clearances of the elements whose deflection the output is, and `[analysis.levels]`), the fraction
//!   of time in each element regime (contact, lift-off) and its entry rate, a histogram; intervals across
//!   realizations ([`stats`]).
//!
//! The run file has the standard accumulators and statistics of a linear run (`mean`, `variance`, `sigma`
//! of the fluctuation about route 1's mean, with route 1 as the analytic value) and the Welch densities, plus
//! the accumulators and statistics of [`stats`] and the group `/response_histogram` (see
//! `docs/run-file-format.md`).

mod engine;
mod flow;
pub mod inputs;
mod plan;
pub mod record;
mod references;
mod sink;
pub mod stats;
mod step;

pub use plan::{welch_segment, BURN_IN_DECAY};
pub use step::{suggest_nonlinear_step, RECORD_BURN_INS};

use crate::error::{Error, Result};
use crate::nonlinear::{NonlinearModel, Route1, Stationary};
use crate::response::{Excitation, ResponseStatistics};
use crate::simulate::{accumulators, Analytic, RunOptions, RunSummary};
use crate::store::{CreateOptions, OutputStatistics, Provenance, RunMetadata, RunWriter, Signal, Statistic};
use engine::{lockstep_groups, realize_group, NlRealization, NlScratch};
use plan::NlPlan;
use std::path::{Path, PathBuf};

/// Version of route 2's generator: how a seed becomes realizations and statistics. Version 3 reads the force
/// of dry friction in acceleration outputs from its kicks' impulses (the force it exerted over the step,
/// the constraint force while it sticks) instead of F_c·sgn v at the sampled state (0 while it sticks); the
/// realizations of models without dry friction are those of version 2. Version 2 takes burn-in plus record
/// and the Welch segment of 2^a·3^b·5^c steps ([`welch_segment`]); version 1 (files that record no version)
/// took them as computed, often with a large prime factor. A seed's statistics are
/// bit-identical across threads, shards, resume and merge within a version and differ between versions, so
/// a run file of another version is never resumed or merged ([`refuse_other_version`]).
pub const GENERATOR_VERSION: u32 = 3;

/// The text of the run file's identifying provenance part [`crate::store::GENERATOR_VERSION`].
fn version_text() -> String {
    format!(
        "{GENERATOR_VERSION} (nonlinear route 2: burn-in plus record and Welch segments of 2^a·3^b·5^c steps; dry \
         friction's force in acceleration outputs from its impulses)"
    )
}

/// Refuses a nonlinear run file `path` (metadata `meta`) written by another version of route 2's generator
/// (a linear run passes): its realizations cannot be continued or merged bit-identically by this build.
///
/// # Errors
/// [`Error::Hdf5`] naming the file, both versions and what to do.
pub fn refuse_other_version(meta: &RunMetadata, path: &Path) -> Result<()> {
    let text = |name: &str| meta.provenance.iter().find(|p| p.name == name).map(|p| p.text.clone());
    if text("nonlinear").is_none() {
        return Ok(());
    }
    let found = text(crate::store::GENERATOR_VERSION);
    if found.as_deref() == Some(version_text().as_str()) {
        return Ok(());
    }
    Err(Error::Hdf5 {
        path: path.to_path_buf(),
        reason: format!(
            "is a nonlinear run of generator version {}, this build writes version {}: the versions turn a seed \
             into different realizations (version 2 changed the burn-in and Welch lengths to 2^a·3^b·5^c \
             steps, version 3 the acceleration outputs of models with dry friction), so its shards are never \
             resumed or merged with this build; run it again into a new file, \
             or merge it with the stochvib build that wrote it",
            found.unwrap_or_else(|| "1 (not recorded)".into()),
            version_text()
        ),
    })
}

/// The subject of a route-2 run.
#[derive(Debug, Clone)]
pub struct NonlinearRunInput<'a> {
    /// The model.
    pub model: &'a NonlinearModel,
    /// Its random excitation.
    pub excitation: &'a Excitation,
    /// Indices of the outputs to simulate.
    pub outputs: Vec<usize>,
    /// Names and units of the input processes (recorded with raw data when there is one per input).
    pub input_signals: Vec<Signal>,
    /// The scenario file's text.
    pub scenario_text: String,
    /// What else the run was resolved from (compared on resume).
    pub provenance: Vec<Provenance>,
    /// The files the run was read from (the run file may not be one of them).
    pub source_files: Vec<PathBuf>,
    /// Marginal kurtosis per input process (`None`: Gaussian).
    pub kurtosis: Vec<Option<f64>>,
    /// Extra levels (output index, levels in the output's unit) for up-crossing rates.
    pub levels: Vec<(usize, Vec<f64>)>,
    /// Route 1, if it converged.
    pub route1: Option<&'a Route1>,
    /// Route 1's statistics of every output of the model (with route 1's means).
    pub route1_statistics: Option<&'a [ResponseStatistics]>,
    /// The linear part's statistics of every output (the references when route 1 did not converge).
    pub linear_statistics: Option<&'a [ResponseStatistics]>,
    /// Route 3, where it applies.
    pub route3: Option<&'a Stationary>,
}

/// Options of a route-2 run.
#[derive(Debug, Clone)]
pub struct NonlinearRunOptions {
    /// Realizations, duration of the record (after the burn-in), Δt, seed, shards, raw storage, route
    /// (`auto`, `exact`, `spectral`), confidence.
    pub run: RunOptions,
    /// Burn-in, s (default computed from the system).
    pub burn_in_s: Option<f64>,
    /// Realizations with the Δt-halving check (default max(4, R/20), at most R).
    pub halving_checks: Option<usize>,
}

/// What a route-2 run did.
#[derive(Debug, Clone, serde::Serialize)]
pub struct NonlinearRunSummary {
    /// The run as a linear run reports it (file, route, sizes, every statistic, notes).
    pub run: RunSummary,
    /// Burn-in, s.
    pub burn_in_s: f64,
    /// Realizations with the Δt-halving check.
    pub halving_checks: usize,
}

/// Runs route 2 of `input` into the HDF5 file `out` (see the module docs); resumes an interrupted run of the
/// same subject and options.
///
/// # Errors
/// Invalid options (a step that cannot resolve the contacts, no burn-in available); a route that does not
/// apply; the store's errors.
pub fn run_nonlinear(
    input: &NonlinearRunInput,
    opts: &NonlinearRunOptions,
    out: &Path,
    progress: &dyn Fn(usize, usize),
) -> Result<NonlinearRunSummary> {
    let plan = plan::plan(input, opts)?;
    refuse_inputs_as_output(input, out)?;
    let ro = &opts.run;
    // every step of burn-in and record draws at least one normal: refused before anything is written when
    // that alone exceeds --max-hours (the exact route allocates nothing per sample, so nothing else stops it)
    crate::simulate::resources::check_run_time(ro, plan.n_burn + plan.n, 1)?;
    let shard_size = ro.shard_size.min(ro.realizations);
    let bins = plan.welch.segment_len() / 2 + 1;
    let record_inputs = ro.store_raw && plan.input_signals.len() == raw_input_count(&plan);
    let meta = metadata(input, &plan, ro, shard_size, bins, record_inputs);
    meta.validate()?;
    let mut writer = RunWriter::create_with(
        out,
        &meta,
        CreateOptions {
            overwrite: ro.overwrite,
            ..CreateOptions::default()
        },
    )?;
    let mut notes = plan.notes.clone();
    notes.extend(writer.notes().iter().cloned());
    let n_shards = meta.local_shards().len();
    let resumed = writer.completed_shards().len();
    progress(resumed, n_shards);
    let mut done = resumed;
    // the shards' lockstep groups taken in order by every thread, each shard written when its groups are done
    crate::simulate::shard_pipeline::realize_and_write(
        &writer.pending_shards(),
        |shard| {
            let range = meta.shard_range(shard);
            lockstep_groups(range.start as u64..range.end as u64)
        },
        || NlScratch::new(&plan),
        |s, first, width| realize_group(&plan, s, ro.seed, first, width, ro.store_raw),
        |shard, results| {
            refuse_escaped(input.model, &plan, meta.shard_range(shard).start, ro.seed, &results)?;
            write_shard(
                &mut writer,
                shard,
                &results,
                &plan,
                shard_size,
                ro.store_raw,
                record_inputs,
            )?;
            done += 1;
            progress(done, n_shards);
            Ok(())
        },
    )?;
    let (stats, psds, hists) = finish(&writer, &meta, &plan, input, ro.confidence)?;
    writer.write_statistics(&stats)?;
    for psd in &psds {
        writer.write_psd(psd)?;
    }
    for h in &hists {
        writer.write_response_histogram(h)?;
    }
    let path = writer.finish()?;
    Ok(NonlinearRunSummary {
        run: RunSummary {
            path,
            route: plan.route,
            generator: plan.generator.clone(),
            n_samples: plan.n,
            dt_s: ro.dt_s,
            n_realizations: ro.realizations,
            n_shards,
            resumed_shards: resumed,
            part: meta.part,
            realizations: meta.local_realizations(),
            outputs: stats,
            skipped: plan.skipped.clone(),
            notes,
            rainflow: Vec::new(),
            // a model with nonlinear elements takes no comfort verdicts, so it has no weighted outputs to check
            basic_method: Vec::new(),
        },
        burn_in_s: plan.n_burn as f64 * plan.h,
        halving_checks: plan.checks,
    })
}

fn raw_input_count(plan: &NlPlan) -> usize {
    match &plan.flow {
        plan::Flow::Exact(_) => usize::MAX,
        plan::Flow::Hold { .. } => plan.input_signals.len(),
    }
}

fn metadata(
    input: &NonlinearRunInput,
    plan: &NlPlan,
    ro: &RunOptions,
    shard_size: usize,
    bins: usize,
    record_inputs: bool,
) -> RunMetadata {
    let names: Vec<&str> = plan.outputs.iter().map(|o| o.signal.name.as_str()).collect();
    let mut acc = accumulators::layout(&names, shard_size, bins);
    for o in &plan.outputs {
        acc.push((stats::values_name(&o.signal.name), quantities(o) * shard_size));
        acc.push((stats::histogram_name(&o.signal.name), plan::HISTOGRAM_BINS + 2));
    }
    let mut provenance = input.provenance.clone();
    provenance.push(Provenance::identity(crate::store::GENERATOR_VERSION, version_text()));
    provenance.push(Provenance::identity(
        "nonlinear",
        format!(
            "route 2: {} elements ({}); burn-in {} steps; Δt-halving check on realizations 0..{}",
            input.model.elements().len(),
            input
                .model
                .elements()
                .iter()
                .map(|e| format!("{}: {}", e.name, e.law.describe()))
                .collect::<Vec<_>>()
                .join("; "),
            plan.n_burn,
            plan.checks
        ),
    ));
    RunMetadata {
        scenario_text: input.scenario_text.clone(),
        seed: ro.seed,
        generator: plan.generator.clone(),
        dt: ro.dt_s,
        n_samples: plan.n,
        n_realizations: ro.realizations,
        shard_size,
        inputs: if record_inputs {
            plan.input_signals.clone()
        } else {
            vec![]
        },
        outputs: plan.outputs.iter().map(|o| o.signal.clone()).collect(),
        accumulators: acc,
        store_raw: ro.store_raw,
        compression: ro.compression,
        provenance,
        part: ro.part,
    }
}

/// What [`Error::Divergent`] names when a realization of route 2 escapes ([`escaped`] recognises it).
pub const ESCAPED_RESPONSE: &str = "route 2's response";

/// The reason of an error of [`run_nonlinear`] that says the response escaped (left every finite value),
/// `None` for any other error: the outcome "no stationary response", to report beside routes 1 and 3.
pub fn escaped(e: &Error) -> Option<String> {
    match e {
        Error::Divergent { quantity, reason } if quantity == ESCAPED_RESPONSE => Some(reason.clone()),
        _ => None,
    }
}

/// Refuses a shard with a realization whose response escaped: once a softening element has lost its
/// stiffness (or nothing restrains a coordinate) the state grows without bound, its records' sums are no
/// longer numbers, and no statistic of the run would be (the first such realization and output are named;
/// nothing of the shard is written).
fn refuse_escaped(
    model: &NonlinearModel,
    plan: &NlPlan,
    first: usize,
    seed: u64,
    results: &[NlRealization],
) -> Result<()> {
    for (i, re) in results.iter().enumerate() {
        let bad = (0..plan.outputs.len()).find(|&r| !(re.m[r].is_finite() && re.v[r].is_finite()));
        let Some(r) = bad else { continue };
        let softening: Vec<String> = model
            .elements()
            .iter()
            .filter(|e| e.law.softening())
            .map(|e| format!("`{}`", e.name))
            .collect();
        let cause = if softening.is_empty() {
            "nothing restrains a coordinate at this excitation level".to_string()
        } else {
            format!(
                "a softening element ({}) lost its stiffness: the potential has a barrier, and the state that \
                 crosses it runs away",
                softening.join(", ")
            )
        };
        return Err(Error::Divergent {
            quantity: ESCAPED_RESPONSE.into(),
            reason: format!(
                "realization {} of seed {seed}: output `{}` left every finite value within the run ({} s of \
                 burn-in and {} s recorded): {cause}; the nonlinear system has no stationary response here, so \
                 route 2 has no statistics (lower the excitation, or make the element harden)",
                first + i,
                plan.outputs[r].signal.name,
                crate::numbers::num(plan.n_burn as f64 * plan.h),
                crate::numbers::num(plan.duration()),
            ),
        });
    }
    Ok(())
}

/// Values per realization of an output: mean, variance, kurtosis, max |y|, a rate per level, two per
/// regime, two halving differences.
fn quantities(o: &plan::PlannedOutput) -> usize {
    4 + o.levels.len() + 2 * o.regimes.len() + 2
}

fn write_shard(
    writer: &mut RunWriter,
    shard: usize,
    results: &[NlRealization],
    plan: &NlPlan,
    shard_size: usize,
    store_raw: bool,
    record_inputs: bool,
) -> Result<()> {
    let (rows, n) = (results.len(), plan.n);
    let mut accs: Vec<Vec<f64>> = Vec::new();
    for r in 0..plan.outputs.len() {
        let moments = accumulators::Moments {
            mean: results.iter().map(|re| re.m[r]).collect(),
            mean_square: results.iter().map(|re| re.v[r]).collect(),
        };
        let mut ws = plan.welch.sums();
        for re in results {
            ws.merge(&re.welch[r])?;
        }
        accs.push(moments.encode(shard_size));
        accs.push(accumulators::WelchAccumulator(ws).encode());
    }
    for r in 0..plan.outputs.len() {
        let values: Vec<Vec<f64>> = results.iter().map(|re| re.values[r].clone()).collect();
        accs.push(stats::encode(&values, shard_size));
        let mut h = vec![0.0; plan::HISTOGRAM_BINS + 2];
        for re in results {
            h.iter_mut().zip(&re.hist[r]).for_each(|(a, b)| *a += b);
        }
        accs.push(h);
    }
    let grid = |pick: &dyn Fn(&NlRealization) -> &Vec<Vec<f64>>, count: usize| -> Vec<ndarray::Array2<f64>> {
        (0..count)
            .map(|r| ndarray::Array2::from_shape_fn((rows, n), |(i, k)| pick(&results[i])[r][k]))
            .collect()
    };
    let raw = if store_raw {
        grid(&|re| &re.raw, plan.outputs.len())
    } else {
        vec![]
    };
    let raw_in = if record_inputs {
        grid(&|re| &re.raw_inputs, plan.input_signals.len())
    } else {
        vec![]
    };
    let views: Vec<_> = raw.iter().map(|a| a.view()).collect();
    let in_views: Vec<_> = raw_in.iter().map(|a| a.view()).collect();
    // the writer's order: the standard accumulators of every output, then the nonlinear ones
    let refs: Vec<&[f64]> = accs.iter().map(|a| a.as_slice()).collect();
    writer.write_shard(shard, &in_views, &views, &refs)
}

/// The statistics templates of a planned output: the quantities in accumulator order, then the `exact:`
/// repetitions.
fn templates(o: &plan::PlannedOutput, input: &NonlinearRunInput) -> Vec<Statistic> {
    let unit = &o.signal.unit;
    let per_s = "1/s".to_string();
    let route1 = "route 1 (statistical linearization: an approximation)";
    let mut names: Vec<(String, String, String)> = vec![
        (
            "mean_response".into(),
            unit.clone(),
            format!("time average per realization; Student-t; analytic = {route1}"),
        ),
        (
            "sigma_response".into(),
            unit.clone(),
            format!("√ of the per-realization variance interval; analytic = {route1}"),
        ),
        (
            "kurtosis".into(),
            "-".into(),
            "pooled μ̄₄/σ̄⁴ with the delta-method interval; analytic = 3 (Gaussian, route 1)".into(),
        ),
        (
            "max_abs".into(),
            unit.clone(),
            "largest |y| per realization; Student-t".into(),
        ),
    ];
    for a in &o.levels {
        names.push((
            format!("upcrossing_rate[{} {unit}]", crate::numbers::short(*a)),
            per_s.clone(),
            format!(
                "up-crossings of the level counted on the samples, per second; Student-t widened to the exact \
                 Poisson interval of the total count; analytic = Rice's rate of {route1}"
            ),
        ));
    }
    for &e in &o.regimes {
        let el = &input.model.elements()[e];
        let reg = el.law.regime().expect("a regime element");
        names.push((
            format!("{}[{}]", reg.fraction, el.name),
            "-".into(),
            format!(
                "fraction of samples in the regime; Student-t within [0, 1] ([0, 1] when never in it); analytic \
                 = Gaussian probability of {route1}"
            ),
        ));
        names.push((
            format!("{}[{}]", reg.rate, el.name),
            per_s.clone(),
            format!(
                "entries into the regime per second; Student-t widened to the exact Poisson interval of the \
                 total count; analytic = Rice's rate of {route1}"
            ),
        ));
    }
    names.push((
        "dt_halving_mean".into(),
        unit.clone(),
        "mean at Δt minus mean at Δt/2, same noise path; analytic 0".into(),
    ));
    names.push((
        "dt_halving_sigma".into(),
        unit.clone(),
        "σ at Δt minus σ at Δt/2, same noise path; analytic 0".into(),
    ));
    let n_refs = o.reference.len();
    let mut out: Vec<Statistic> = names
        .into_iter()
        .enumerate()
        .map(|(k, (name, unit, method))| {
            // the references skip max |y| (no reference) and end before the halving differences (0)
            let analytic = match k {
                0..=2 => o.reference[k].route1,
                3 => None,
                k if k <= n_refs => o.reference[k - 1].route1,
                _ => Some(0.0),
            };
            template(&name, &unit, &method, analytic)
        })
        .collect();
    let exact: Vec<Statistic> = out
        .iter()
        .filter(|t| t.name != "max_abs" && !t.name.starts_with("dt_halving"))
        .zip(&o.reference)
        .filter_map(|(t, r)| {
            r.exact.map(|a| {
                template(
                    &format!("{}{}", stats::EXACT, t.name),
                    &t.unit,
                    "the same estimate; analytic = route 3 (exact Fokker–Planck density)",
                    Some(a),
                )
            })
        })
        .collect();
    out.extend(exact);
    out
}

fn template(name: &str, unit: &str, method: &str, analytic: Option<f64>) -> Statistic {
    Statistic {
        name: name.into(),
        interval: crate::estimate::Interval {
            estimate: f64::NAN,
            lower: f64::NAN,
            upper: f64::NAN,
            confidence: 0.95,
        },
        unit: unit.into(),
        method: method.into(),
        analytic,
        covers: None,
    }
}

/// The method texts of the standard statistics of a nonlinear run (the fluctuation about route 1's mean).
pub(crate) fn relabel_standard(st: &mut OutputStatistics) {
    for s in &mut st.statistics {
        let text = match s.name.as_str() {
            "mean" => {
                "time average of y − μ₁ per realization (μ₁ route 1's mean); Student-t; analytic 0 = route 1's mean"
            }
            "variance" => {
                "time average of (y − μ₁)² per realization; Student-t; analytic = route 1's variance (an approximation)"
            }
            "sigma" | "sigma_discrete" => {
                "square root of the variance interval; analytic = route 1's σ (an approximation)"
            }
            _ => continue,
        };
        s.method = text.into();
    }
}

type Finished = (
    Vec<OutputStatistics>,
    Vec<crate::store::PsdEstimate>,
    Vec<crate::store::ResponseHistogram>,
);

/// Each realization's record time, s (what its rates are counts per).
fn record_seconds(meta: &RunMetadata) -> f64 {
    meta.n_samples as f64 * meta.dt
}

fn finish(
    writer: &RunWriter,
    meta: &RunMetadata,
    plan: &NlPlan,
    input: &NonlinearRunInput,
    confidence: f64,
) -> Result<Finished> {
    let welch = &plan.welch;
    let mut stats = Vec::new();
    let mut psds = Vec::new();
    let mut hists = Vec::new();
    let acc = |name: &str, shard: usize| writer.read_accumulator(name, shard);
    for o in &plan.outputs {
        let (m, v, ws) = crate::simulate::read_output_accumulators(&acc, meta, &o.signal.name, welch)?;
        let r1 = o.reference[1].route1.unwrap_or(f64::NAN);
        let analytic = Analytic {
            mean: 0.0,
            variance: r1 * r1,
            sigma: r1,
            sigma_discrete: r1,
        };
        let mut st = crate::simulate::output_statistics(&o.signal, &analytic, &m, &v, confidence)?;
        relabel_standard(&mut st);
        let (per_q, counts) = fold_nonlinear(&acc, meta, &o.signal.name)?;
        st.statistics.extend(stats::statistics(
            &templates(o, input),
            &per_q,
            confidence,
            record_seconds(meta),
        )?);
        stats.push(st);
        let density = route1_density(input, o.index);
        psds.push(crate::simulate::density_estimate(
            &o.signal,
            welch,
            &ws,
            confidence,
            |omega| Ok(density.map(|f| omega.iter().map(|w| f(*w)).collect())),
        )?);
        let edges = (0..=plan::HISTOGRAM_BINS)
            .map(|b| o.hist_lo + b as f64 * o.hist_width)
            .collect();
        hists.push(stats::histogram(
            &o.signal.name,
            &o.signal.unit,
            edges,
            &counts,
            o.gaussian.clone(),
            o.exact.clone(),
        ));
    }
    Ok((stats, psds, hists))
}

/// Route 1's output density (of the equivalent linear system), if route 1 converged.
fn route1_density<'a>(input: &'a NonlinearRunInput, r: usize) -> Option<impl Fn(f64) -> f64 + 'a> {
    let eq = &input.route1?.equivalent;
    Some(move |w: f64| crate::response::output_density(eq, input.excitation, r, w))
}

/// The nonlinear accumulator of an output over the file's shards (per quantity, in realization order) and
/// its summed histogram counts.
pub(crate) fn fold_nonlinear(
    acc: &dyn Fn(&str, usize) -> Result<Vec<f64>>,
    meta: &RunMetadata,
    output: &str,
) -> Result<(Vec<Vec<f64>>, Vec<f64>)> {
    let mut per_q = Vec::new();
    let mut counts: Vec<f64> = Vec::new();
    for shard in meta.local_shards() {
        let rows = meta.shard_range(shard).len();
        stats::decode_into(
            &acc(&stats::values_name(output), shard)?,
            rows,
            meta.shard_size,
            &mut per_q,
        )?;
        let h = acc(&stats::histogram_name(output), shard)?;
        if counts.is_empty() {
            counts = vec![0.0; h.len()];
        }
        if h.len() != counts.len() {
            return Err(Error::Numerical {
                what: "reading a histogram accumulator".into(),
                reason: "shards of different lengths: the run file is damaged".into(),
            });
        }
        counts.iter_mut().zip(&h).for_each(|(a, b)| *a += b);
    }
    Ok((per_q, counts))
}

/// The nonlinear statistics and histograms of a merged run, appended as a single-process run appends them
/// (the templates, i.e. names, units, methods and analytic values, and the reference densities are taken
/// from the first shard file's statistics `stats0` and histograms `hist0`). Does nothing for a linear run.
///
/// # Errors
/// A damaged accumulator; statistics missing from the shard file.
pub(crate) fn finish_merged(
    writer: &mut RunWriter,
    meta: &RunMetadata,
    confidence: f64,
    stats0: &[OutputStatistics],
    hist0: &[crate::store::ResponseHistogram],
    stats: &mut [OutputStatistics],
) -> Result<()> {
    for st in stats.iter_mut() {
        let name = stats::values_name(&st.output);
        if !meta.accumulators.iter().any(|a| a.0 == name) {
            continue;
        }
        relabel_standard(st);
        let acc = |n: &str, b: usize| writer.read_accumulator(n, b);
        let all: Vec<(usize, usize)> = (0..meta.n_shards()).map(|b| (b, meta.shard_range(b).len())).collect();
        let mut per_q = Vec::new();
        let mut counts: Vec<f64> = Vec::new();
        for (b, rows) in all {
            stats::decode_into(&acc(&name, b)?, rows, meta.shard_size, &mut per_q)?;
            let h = acc(&stats::histogram_name(&st.output), b)?;
            counts.resize(h.len(), 0.0);
            counts.iter_mut().zip(&h).for_each(|(a, x)| *a += x);
        }
        let stored = stats0
            .iter()
            .find(|o| o.output == st.output)
            .ok_or_else(|| Error::Numerical {
                what: "merge".into(),
                reason: format!("no statistics of `{}` in the first shard file", st.output),
            })?;
        let templates: Vec<Statistic> = stored.statistics.iter().skip(4).cloned().collect();
        st.statistics
            .extend(stats::statistics(&templates, &per_q, confidence, record_seconds(meta))?);
        let h0 = hist0
            .iter()
            .find(|h| h.output == st.output)
            .ok_or_else(|| Error::Numerical {
                what: "merge".into(),
                reason: format!("no response histogram of `{}` in the first shard file", st.output),
            })?;
        let h = stats::histogram(
            &st.output,
            &h0.unit,
            h0.edges.clone(),
            &counts,
            h0.gaussian.clone(),
            h0.exact.clone(),
        );
        writer.write_response_histogram(&h)?;
    }
    Ok(())
}

fn refuse_inputs_as_output(input: &NonlinearRunInput, out: &Path) -> Result<()> {
    let same = |a: &Path| match (a.canonicalize(), out.canonicalize()) {
        (Ok(x), Ok(y)) => x == y,
        _ => a == out,
    };
    if let Some(f) = input.source_files.iter().find(|f| same(f)) {
        return Err(Error::Hdf5 {
            path: out.to_path_buf(),
            reason: format!("is an input of the run ({}): choose another output", f.display()),
        });
    }
    Ok(())
}

/// The statistics route 2 estimates for one output, with their reference values, as a report lists them.
#[derive(Debug, Clone, serde::Serialize)]
pub struct OutputReferences {
    /// Output name.
    pub output: String,
    /// Its unit.
    pub unit: String,
    /// (statistic name, unit, route 1's value, route 3's value) in the order of the run's statistics
    /// (`mean_response`, `sigma_response`, `kurtosis`, `max_abs`, the level rates, the regimes); the
    /// Δt-halving differences are left out.
    pub rows: Vec<(String, String, Option<f64>, Option<f64>)>,
}

/// The references of every output route 2 would simulate, and the outputs it would skip with the reason: what
/// `analyze` prints for routes 1 and 3, under the names of the run's statistics.
///
/// # Errors
/// An input mean without a static equilibrium; route 3's quadratures.
pub fn reference_table(
    input: &NonlinearRunInput,
) -> Result<(Vec<OutputReferences>, Vec<crate::simulate::SkippedOutput>)> {
    let lin = input.model.linear();
    let (q_eq, u_mean) = plan::equilibrium(lin, input.excitation)?;
    let (outputs, skipped) = plan::plan_outputs(input, &q_eq, &u_mean)?;
    let refs = outputs
        .iter()
        .map(|o| {
            let t = templates(o, input);
            let exact = |name: &str| {
                t.iter()
                    .find(|s| s.name.strip_prefix(stats::EXACT) == Some(name))
                    .and_then(|s| s.analytic)
            };
            OutputReferences {
                output: o.signal.name.clone(),
                unit: o.signal.unit.clone(),
                rows: t
                    .iter()
                    .filter(|s| !s.name.starts_with(stats::EXACT) && !s.name.starts_with("dt_halving"))
                    .map(|s| (s.name.clone(), s.unit.clone(), s.analytic, exact(&s.name)))
                    .collect(),
            }
        })
        .collect();
    Ok((refs, skipped))
}

impl std::fmt::Display for NonlinearRunSummary {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let r = &self.run;
        writeln!(f, "run       {}", r.path.display())?;
        writeln!(f, "route     {} (nonlinear, route 2): {}", r.route.name(), r.generator)?;
        writeln!(
            f,
            "size      {} realizations × {} samples (Δt = {} s) after a burn-in of {:.4} s, {} shards ({} resumed)",
            r.n_realizations, r.n_samples, r.dt_s, self.burn_in_s, r.n_shards, r.resumed_shards
        )?;
        for n in &r.notes {
            writeln!(f, "note      {n}")?;
        }
        for s in &r.skipped {
            writeln!(f, "skipped   {}: {}", s.name, s.reason)?;
        }
        writeln!(
            f,
            "{:<16} {:<28} {:>13} {:>29} {:>13} {:>13}",
            "output", "statistic", "Monte Carlo", "interval", "route 1", "exact"
        )?;
        for o in &r.outputs {
            for s in o
                .statistics
                .iter()
                .skip(4)
                .filter(|s| !s.name.starts_with(stats::EXACT))
            {
                let exact = o.get(&format!("{}{}", stats::EXACT, s.name)).and_then(|e| e.analytic);
                let show = |v: Option<f64>| v.map_or("-".to_string(), |x| format!("{x:.6e}"));
                writeln!(
                    f,
                    "{:<16} {:<28} {:>13.6e} [{:>13.6e}, {:>13.6e}] {:>13} {:>13}",
                    o.output,
                    s.name,
                    s.interval.estimate,
                    s.interval.lower,
                    s.interval.upper,
                    show(s.analytic),
                    show(exact)
                )?;
            }
        }
        Ok(())
    }
}
