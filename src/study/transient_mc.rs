//! Monte Carlo of a scenario's transient (`stochvib transient --monte-carlo N`): the run of
//! [`crate::transient::run_transient`] on the scenario's setup, and the comparison of the ensemble σ(t)
//! with the exact curve, with a verdict that holds for every reported time at once.

use super::transient_run::{
    evolutionary_setup, exact_solution, has_exact_route, road_grid_setup, transient_setup, RoadGridSetup,
    TransientSetup,
};
use crate::error::{Error, Result};
use crate::estimate::ChiSquaredInterval;
use crate::scenario::Scenario;
use crate::store::transient_series::TransientSeries;
use crate::store::{Compression, Part};
use crate::transient::mc_finish::AnalyticSide;
use crate::transient::mission::analytic_side;
use crate::transient::{
    run_road_grid, run_transient, McGrid, McGridSpec, RoadGridRunInput, TransientRunInput, TransientRunOptions,
    TransientRunSummary, TransientSolution,
};
use std::path::Path;

/// Options of a transient Monte Carlo run of a scenario.
#[derive(Debug, Clone, PartialEq)]
pub struct TransientMcOptions {
    /// Realizations.
    pub realizations: usize,
    /// Integration steps per reported interval (the realizations are stepped exactly for coefficients
    /// frozen at each step's midpoint).
    pub substeps: usize,
    /// Master seed.
    pub seed: u64,
    /// Realizations per shard.
    pub shard_size: usize,
    /// Confidence of the intervals and of the DKW band.
    pub confidence: f64,
    /// Store every realization at the reported times.
    pub store_raw: bool,
    /// Compression of the raw data.
    pub compression: Compression,
    /// The part of a cluster run.
    pub part: Option<Part>,
    /// Replace a finished file.
    pub overwrite: bool,
    /// Refuse a batch whose computing time's lower bound exceeds this many hours.
    pub max_hours: f64,
}

/// The outputs a run simulates: the reported outputs with a finite σ and crossing rates (the analytic
/// distribution of the maxima needs them), and a note for each one left out.
pub fn simulated_outputs(setup: &TransientSetup, sol: &TransientSolution) -> (Vec<usize>, Vec<String>) {
    let mut notes = Vec::new();
    let outputs = setup
        .outputs
        .iter()
        .copied()
        .filter(|&i| {
            let o = &sol.outputs[i];
            match o.unavailable.as_ref().or(o.rate_note.as_ref()) {
                Some(why) => {
                    notes.push(format!("`{}` is not simulated: {why}", o.name));
                    false
                }
                None => true,
            }
        })
        .collect();
    (outputs, notes)
}

/// Runs the Monte Carlo batch of the scenario's transient into `out` (resuming an interrupted run).
///
/// # Errors
/// No output to simulate; the errors of [`run_transient`] (options, store, an existing finished file).
pub fn simulate_transient(
    sc: &Scenario,
    setup: &TransientSetup,
    sol: &TransientSolution,
    opts: &TransientMcOptions,
    out: &Path,
    progress: &dyn Fn(usize, usize),
) -> Result<(TransientRunSummary, Vec<String>)> {
    let (outputs, notes) = simulated_outputs(setup, sol);
    if outputs.is_empty() {
        return Err(Error::NotApplicable {
            method: "transient Monte Carlo".into(),
            reason: format!(
                "no reported output has a finite σ and crossing rates: {}",
                notes.join("; ")
            ),
        });
    }
    let duration = *setup.times.last().unwrap_or(&0.0);
    let intervals = setup.times.len() - 1;
    check_substeps(opts.substeps, intervals)?;
    let dt = duration / (intervals * opts.substeps) as f64;
    let grid = McGridSpec {
        duration_s: duration,
        dt_s: dt,
        store_every: opts.substeps,
    }
    .build()?;
    let input = TransientRunInput {
        sys: &setup.sys,
        outputs,
        start: setup.start.clone(),
        exact: sol,
        stationary: setup.stationary,
        scenario_text: sc.text.clone(),
        provenance: sc.run_input().provenance,
    };
    Ok((run_transient(&input, &run_options(opts, grid), out, progress)?, notes))
}

/// The Monte Carlo σ(t) of one output against the exact σ(t).
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct SigmaComparison {
    /// Output.
    pub output: String,
    /// Unit.
    pub unit: String,
    /// Realizations.
    pub realizations: usize,
    /// Confidence of the per-time intervals (as stored).
    pub confidence: f64,
    /// The route whose σ(t) the run is compared with: `exact` (the differential Lyapunov equation) or
    /// `evolutionary` (the evolutionary spectrum of the frozen system), from the run's stored method.
    pub route: String,
    /// Per reported time: (t, analytic σ of `route`, Monte Carlo σ, lower, upper) of the per-time interval.
    pub rows: Vec<(f64, f64, f64, f64, f64)>,
    /// Fraction of the times whose per-time interval covers the analytic σ.
    pub coverage: f64,
    /// The simultaneous level 1 − α of the verdict (Bonferroni over the K times).
    pub simultaneous_confidence: f64,
    /// Times at which the analytic σ is outside the simultaneous interval.
    pub outside: Vec<f64>,
}

impl SigmaComparison {
    /// `agree` or `DISAGREE at t = …`.
    pub fn verdict(&self) -> String {
        match self.outside.first() {
            None => format!(
                "agree: the {} σ(t) lies inside the simultaneous {} % band at every one of the {} times",
                self.route,
                100.0 * self.simultaneous_confidence,
                self.rows.iter().filter(|r| !r.1.is_nan()).count()
            ),
            Some(t) => format!(
                "DISAGREE: the {} σ lies outside the simultaneous {} % band at {} of {} times (first t = {t} s)",
                self.route,
                100.0 * self.simultaneous_confidence,
                self.outside.len(),
                self.rows.len()
            ),
        }
    }
}

/// The comparison of every output of a run's series, with a verdict at the simultaneous level 1 − α.
///
/// # Formula
/// At each of the K times, σ̂² (R − 1)/σ² ~ χ²_{R−1} for the Gaussian response of a linear system, so
/// [σ̂²(R−1)/χ²_{R−1}(1 − α/2K), σ̂²(R−1)/χ²_{R−1}(α/2K)] covers σ² at every time at once with probability
/// ≥ 1 − α (Bonferroni). A time with σ = 0 exactly (a start at rest) counts as inside when
/// |σ̂ − σ| ≤ 10⁻¹² max σ. A time whose analytic σ is NaN (where the evolutionary route reports none) is
/// not compared (and not counted in the coverage).
///
/// # Errors
/// α outside (0, 1); fewer than 2 realizations.
pub fn compare_sigma(series: &TransientSeries, alpha: f64) -> Result<Vec<SigmaComparison>> {
    if !(alpha > 0.0 && alpha < 1.0) {
        return Err(Error::invalid("alpha", alpha, "must be in (0, 1)"));
    }
    let k = series.times.len().max(1);
    let level = 1.0 - alpha / k as f64;
    let route = route_of(&series.exact_method);
    series
        .outputs
        .iter()
        .map(|o| {
            let r = o.max_y.len();
            let scale = o.exact_sigma.iter().copied().fold(0.0, f64::max);
            let mut rows = Vec::with_capacity(k);
            let mut outside = Vec::new();
            let mut covered = 0usize;
            // the quantiles once per output, at its first compared time
            let mut chi: Option<ChiSquaredInterval> = None;
            for (j, &t) in series.times.iter().enumerate() {
                let (ex, est) = (o.exact_sigma[j], o.sigma[j]);
                if ex.is_nan() {
                    rows.push((t, ex, est, o.sigma_lower[j], o.sigma_upper[j]));
                    continue;
                }
                let iv = match chi {
                    Some(c) => c,
                    None => *chi.insert(ChiSquaredInterval::new(r as f64 - 1.0, level)?),
                }
                .interval(est * est)?;
                let tiny = (ex - est).abs() <= 1e-12 * scale;
                if !(tiny || (iv.lower.sqrt() <= ex && ex <= iv.upper.sqrt())) {
                    outside.push(t);
                }
                if tiny || (o.sigma_lower[j] <= ex && ex <= o.sigma_upper[j]) {
                    covered += 1;
                }
                rows.push((t, ex, est, o.sigma_lower[j], o.sigma_upper[j]));
            }
            let compared = rows.iter().filter(|row| !row.1.is_nan()).count().max(1);
            Ok(SigmaComparison {
                output: o.output.clone(),
                unit: o.unit.clone(),
                route: route.to_string(),
                realizations: r,
                confidence: series.confidence,
                coverage: covered as f64 / compared as f64,
                rows,
                simultaneous_confidence: 1.0 - alpha,
                outside,
            })
        })
        .collect()
}

/// The route that produced a run's analytic σ(t), from its stored method: `evolutionary` when the method
/// names the evolutionary spectrum (the road-grid route on a road without an exact route), `stationary`
/// (wheels at positions or on two tracks at a constant speed), `analytic` where there is none (NaN), else
/// `exact`.
pub fn route_of(method: &str) -> &'static str {
    if method.starts_with("evolutionary") {
        "evolutionary"
    } else if method.starts_with("stationary") {
        "stationary"
    } else if method.starts_with("none") {
        "analytic"
    } else {
        "exact"
    }
}

/// The default road step Δx of the road-grid route.
///
/// # Formula
/// Δx = 0.1 / min(ω_max/v_ref, Ω_hi), with ω_max the largest |λ| of the model's own A (the vehicle's
/// fastest mode; the comfort weighting filters appended for `[analysis.comfort]` are left out: their poles
/// at the band limit of ISO 2631-1 weight, but do not create, motion), v_ref the profile's smallest speed
/// (a tenth of its largest where it stops), and Ω_hi the upper edge of the road's band (rad/m, ∞ without
/// one). A reported output that passes the road directly (D ≠ 0: a tyre force) sees every wave of the
/// road, so on a band-limited road it takes Δx = 0.1/Ω_hi. The vehicle's fastest mode, and the shortest
/// wave the road has where an output follows it, then see the grid at ΩΔx ≤ 0.1: the linear interpolation
/// loses about (ΩΔx)²/6 ≈ 0.2 % of the power there, less below. Without a mode or a band (a static model on
/// an unbounded road) Δx = v_ref/100.
pub fn default_road_step(setup: &RoadGridSetup) -> f64 {
    let (lo, hi) = setup.speed.table_points().range();
    let v_ref = if lo > 0.0 { lo } else { 0.1 * hi };
    let n = setup.model_states.min(setup.ss.a.nrows());
    let w_max = setup
        .ss
        .a
        .view((0, 0), (n, n))
        .into_owned()
        .complex_eigenvalues()
        .iter()
        .map(|l| l.norm())
        .fold(0.0, f64::max);
    let direct = setup
        .outputs
        .iter()
        .any(|&i| i < setup.ss.d.nrows() && setup.ss.d.row(i).iter().any(|v| *v != 0.0));
    let wavenumber = if direct && setup.band_edge.is_finite() {
        setup.band_edge
    } else {
        (w_max / v_ref).min(setup.band_edge)
    };
    if wavenumber > 0.0 && wavenumber.is_finite() {
        0.1 / wavenumber
    } else {
        v_ref * 0.01
    }
}

/// The analytic side of a road-grid run and the outputs it simulates: the exact route where the road has
/// one, else the evolutionary route (NaN where its error estimate exceeds `[transient] max_error`; the
/// distributions of the maxima are then NaN and have no verdict).
fn road_grid_analytic(sc: &Scenario, outputs: &[usize]) -> Result<(AnalyticSide, Vec<usize>, Vec<String>)> {
    if has_exact_route(sc)? {
        let setup = transient_setup(sc)?;
        let sol = exact_solution(sc, &setup)?;
        let (outs, notes) = simulated_outputs(&setup, &sol);
        let fr0 = if setup.stationary {
            Some(setup.sys.frozen(0.0)?)
        } else {
            None
        };
        let method = format!(
            "differential Lyapunov equation (the exact route), accumulated error estimate {:.1e}",
            sol.report.max_error_estimate
        );
        return Ok((analytic_side(&sol, fr0.as_ref(), &outs, method)?, outs, notes));
    }
    let ev = evolutionary_setup(sc)?;
    let sol = &ev.solution.solution;
    let mut notes = Vec::new();
    let outs: Vec<usize> = outputs
        .iter()
        .copied()
        .filter(|&i| {
            match sol.outputs[i]
                .unavailable
                .as_ref()
                .or(sol.outputs[i].rate_note.as_ref())
            {
                Some(why) => {
                    notes.push(format!("`{}` is not simulated: {why}", sol.outputs[i].name));
                    false
                }
                None => true,
            }
        })
        .collect();
    let method = format!(
        "evolutionary spectrum of the frozen system (no exact route); NaN where its error estimate exceeds {}",
        ev.solution.max_error
    );
    Ok((analytic_side(sol, None, &outs, method)?, outs, notes))
}

/// The analytic side of a road-grid run of wheels at positions or on two tracks, and the outputs it
/// simulates (every reported output).
///
/// # Formula
/// At a constant speed the response is stationary: per output the stationary analysis of the scenario
/// (`analyze_output`: mean m, σ, ν₀⁺ from the inputs' cross-spectral matrix with the delays) at every time,
/// and the Poisson distributions of the maxima at Rice's rates, F_y(b) = exp(−ν₀⁺T e^{−(b−m)²/2σ²}) and
/// F_|y|(b) = exp(−ν₀⁺T(e^{−(b−m)²/2σ²} + e^{−(b+m)²/2σ²})). Under a varying speed there is no analytic
/// route (the delays ℓ/v(t) vary in time; the coherent pair has no finite filter): NaN, and the run stands
/// alone. The weighted comfort outputs have no stationary curve here (NaN).
fn wheels_analytic(sc: &Scenario, setup: &RoadGridSetup) -> Result<(AnalyticSide, Vec<usize>, Vec<String>)> {
    let k = setup.times.len();
    let duration = *setup.times.last().unwrap_or(&0.0);
    let sys = sc.model.system.as_ref();
    let constant = setup.speed.table_points().is_constant();
    let stationary = |i: usize| -> Option<(f64, f64, f64)> {
        let st = crate::response::analyze_output(sys, &sc.excitation, i).ok()?;
        Some((st.mean?, st.sigma?, st.zero_upcrossing_rate.unwrap_or(f64::NAN)))
    };
    let outputs = setup
        .outputs
        .iter()
        .map(|&i| {
            let (m, sd, nu) = match (constant, i < sys.outputs().len()) {
                (true, true) => stationary(i).unwrap_or((f64::NAN, f64::NAN, f64::NAN)),
                _ => (f64::NAN, f64::NAN, f64::NAN),
            };
            let (lo, hi) = (m.min(0.0), m.abs() + 7.0 * sd);
            let n = crate::transient::mission::LEVELS;
            let levels: Vec<f64> = (0..n).map(|j| lo + (hi - lo) * j as f64 / (n - 1) as f64).collect();
            let up = |b: f64| nu * duration * (-(b - m).powi(2) / (2.0 * sd * sd)).exp();
            let down = |b: f64| nu * duration * (-(b + m).powi(2) / (2.0 * sd * sd)).exp();
            crate::transient::mc_finish::AnalyticOutput {
                mean: vec![m; k],
                sigma: vec![sd; k],
                cdf_y_rice: levels.iter().map(|&b| (-up(b)).exp()).collect(),
                cdf_abs_rice: levels.iter().map(|&b| (-up(b) - down(b)).exp()).collect(),
                cdf_y_vanmarcke: vec![f64::NAN; n],
                cdf_abs_vanmarcke: vec![f64::NAN; n],
                levels,
            }
        })
        .collect();
    let method = if constant {
        "stationary analysis at the constant speed (cross-spectral matrix of the wheels' inputs, with their \
         delays), constant over time"
    } else {
        "none: wheels at positions or on two tracks under a varying speed have no finite-dimensional route \
         (docs/transients.md); the Monte Carlo stands alone"
    };
    let notes = if constant {
        Vec::new()
    } else {
        vec![format!("no analytic σ(t) to compare with: {method}")]
    };
    Ok((
        AnalyticSide {
            method: method.to_string(),
            outputs,
        },
        setup.outputs.clone(),
        notes,
    ))
}

/// The most integration steps (and, on a road grid, road points) one realization of a transient Monte Carlo
/// may take: 2²⁶ ≈ 6.7·10⁷, half a gigabyte of road in f64. More `substeps` or a finer `road step` is refused
/// before any work (the counts are formed in f64, so no product overflows).
pub const MAX_STEPS_PER_REALIZATION: f64 = (1u64 << 26) as f64;

/// Refuses `substeps` of 0 or more than [`MAX_STEPS_PER_REALIZATION`] steps over `intervals` reported intervals.
fn check_substeps(substeps: usize, intervals: usize) -> Result<()> {
    let steps = substeps as f64 * intervals as f64;
    if substeps == 0 || steps > MAX_STEPS_PER_REALIZATION {
        return Err(Error::invalid(
            "substeps",
            substeps,
            format!(
                "must be >= 1, and at most {MAX_STEPS_PER_REALIZATION:e} integration steps per realization \
                 over the {intervals} reported intervals (this asks {steps:.3e})"
            ),
        ));
    }
    Ok(())
}

/// The grid step Δx (m) and the integration steps per reported interval of a road-grid run.
struct GridSteps {
    dx: f64,
    substeps: usize,
}

/// The grid step of `road_step` (default [`default_road_step`]) and the integration steps per reported interval
/// (see [`simulate_road_grid`]), refused when either asks more than [`MAX_STEPS_PER_REALIZATION`].
fn grid_steps(setup: &RoadGridSetup, opts: &TransientMcOptions, road_step: Option<f64>) -> Result<GridSteps> {
    let dx = road_step.unwrap_or_else(|| default_road_step(setup));
    if !(dx.is_finite() && dx > 0.0) {
        return Err(Error::invalid(
            "road step",
            dx,
            "the grid step Δx must be finite and > 0 m",
        ));
    }
    let duration = *setup.times.last().unwrap_or(&0.0);
    let intervals = setup.times.len() - 1;
    let step = duration / intervals as f64;
    let v_max = setup.speed.table_points().range().1;
    // in f64 before any cast: a tiny Δx must be refused, not overflow a count
    let per_interval = (step * v_max / dx).ceil();
    let road_points = v_max * duration / dx;
    if per_interval * intervals as f64 > MAX_STEPS_PER_REALIZATION || road_points > MAX_STEPS_PER_REALIZATION {
        return Err(Error::invalid(
            "road step",
            dx,
            format!(
                "a grid step of {dx:e} m over the mission (up to {:.3e} m at {v_max} m/s) needs {:.3e} road \
                 points and {:.3e} integration steps per realization; at most {MAX_STEPS_PER_REALIZATION:e} each",
                v_max * duration,
                road_points,
                per_interval * intervals as f64
            ),
        ));
    }
    check_substeps(opts.substeps, intervals)?;
    Ok(GridSteps {
        dx,
        substeps: opts.substeps.max(per_interval as usize),
    })
}

/// Refuses, before any analysis, a transient Monte Carlo whose `substeps` (or, on a road grid, `road_step`)
/// asks more than [`MAX_STEPS_PER_REALIZATION`] steps per realization: the checks [`simulate_transient`] and
/// [`simulate_road_grid`] make, without the exact route or the analytic curves they need first.
///
/// # Errors
/// The refusals of those checks (key `substeps` or `road step`); the errors of reading the scenario's
/// transient set-up.
pub fn check_run_size(sc: &Scenario, opts: &TransientMcOptions, road_grid: bool, road_step: Option<f64>) -> Result<()> {
    if road_grid {
        return grid_steps(&road_grid_setup(sc)?, opts, road_step).map(|_| ());
    }
    check_run_size_of(&transient_setup(sc)?, opts)
}

/// [`check_run_size`] of the exact route's run from its set-up, already read.
///
/// # Errors
/// The refusal of `substeps`.
pub fn check_run_size_of(setup: &TransientSetup, opts: &TransientMcOptions) -> Result<()> {
    check_substeps(opts.substeps, setup.times.len() - 1)
}

/// Runs the road-grid Monte Carlo of the scenario's transient into `out` (resuming an interrupted run): a
/// road synthesised on a spatial grid of step `road_step` (default [`default_road_step`]) and sampled along
/// x(t), for any road spectrum under a speed profile; the analytic curves of `road_grid_analytic`.
///
/// # Formula
/// The integration step is Δt = step/s with s = max(`substeps`, ⌈step·v_max/Δx⌉), so that the vehicle moves
/// at most one grid step per integration step (the first-order hold then interpolates the road as finely as
/// the grid does).
///
/// # Errors
/// The refusals of [`road_grid_setup`]; no output to simulate; the errors of
/// [`crate::transient::run_road_grid`].
pub fn simulate_road_grid(
    sc: &Scenario,
    opts: &TransientMcOptions,
    road_step: Option<f64>,
    out: &Path,
    progress: &dyn Fn(usize, usize),
) -> Result<(TransientRunSummary, Vec<String>)> {
    let setup = road_grid_setup(sc)?;
    let GridSteps { dx, substeps } = grid_steps(&setup, opts, road_step)?;
    let (analytic, outputs, mut notes) = match &setup.wheels {
        Some(_) => wheels_analytic(sc, &setup)?,
        None => road_grid_analytic(sc, &setup.outputs)?,
    };
    if outputs.is_empty() {
        return Err(Error::NotApplicable {
            method: "road-grid Monte Carlo".into(),
            reason: format!("no reported output to simulate: {}", notes.join("; ")),
        });
    }
    let duration = *setup.times.last().unwrap_or(&0.0);
    let intervals = setup.times.len() - 1;
    notes.push(format!(
        "road-grid Monte Carlo: Δx = {dx:.4e} m, {substeps} integration steps per reported interval"
    ));
    let grid = McGridSpec {
        duration_s: duration,
        dt_s: duration / (intervals * substeps) as f64,
        store_every: substeps,
    }
    .build()?;
    let input = RoadGridRunInput {
        ss: &setup.ss,
        wheels: setup.wheels.as_ref(),
        spectrum: sc.input.spectrum.as_ref(),
        speed: &setup.speed,
        outputs,
        dx,
        analytic,
        scenario_text: sc.text.clone(),
        provenance: sc.run_input().provenance,
    };
    Ok((run_road_grid(&input, &run_options(opts, grid), out, progress)?, notes))
}

/// The run options of `opts` on `grid`.
fn run_options(opts: &TransientMcOptions, grid: McGrid) -> TransientRunOptions {
    TransientRunOptions {
        realizations: opts.realizations,
        grid,
        seed: opts.seed,
        shard_size: opts.shard_size,
        confidence: opts.confidence,
        store_raw: opts.store_raw,
        compression: opts.compression,
        part: opts.part,
        overwrite: opts.overwrite,
        max_hours: opts.max_hours,
    }
}
