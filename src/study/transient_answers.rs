//! The answers of `stochvib transient`: every reported output's mean(t), σ(t), ν₀⁺(t) and ν⁺(b, t), the
//! running weighted r.m.s. a_w(t) of the comfort axes, the expected up-crossings over the mission and the
//! extremes table, stationary and non-stationary (`docs/transients.md`).

use super::transient_run::{evolutionary_setup, exact_solution, has_exact_route, transient_setup, TransientSetup};
use crate::error::Result;
use crate::extremes::{davenport, der_kiureghian, Barrier, CrossingMoments, ExceedanceMethod, PeakFactor};
use crate::scenario::Scenario;
use crate::transient::{stationary_moments, Start, StepReport, TransientSolution};

/// One reported output over time (vectors indexed like [`TransientAnalysis::times`]; empty when the output
/// has no finite σ).
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct OutputOverTime {
    /// Output name.
    pub name: String,
    /// SI unit.
    pub unit: String,
    /// For a weighted output: the acceleration it weights (then σ(t) is a_w(t), the running r.m.s.).
    pub weighted_of: Option<String>,
    /// m(t).
    pub mean: Vec<f64>,
    /// σ(t).
    pub sigma: Vec<f64>,
    /// ν₀⁺(t), Hz.
    pub nu0_plus: Vec<f64>,
    /// (b, ν⁺(b, t) in Hz) per mission level.
    pub upcrossing_rates: Vec<(f64, Vec<f64>)>,
    /// Why the output has no finite σ, or no crossing rates.
    pub note: Option<String>,
}

/// The stationary extremes of one output (the frozen system at the end of the window in its stationary
/// state, over the mission duration).
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct StationaryExtremes {
    /// M_y.
    pub mean: f64,
    /// σ_y.
    pub sigma: f64,
    /// ν₀⁺, Hz.
    pub nu0_plus: f64,
    /// Vanmarcke's δ.
    pub delta: f64,
    /// Davenport's peak factor of max |y| (N = 2ν₀⁺T).
    pub davenport: Option<PeakFactor>,
    /// Der Kiureghian's peak factor of max |y| (N_e from 2ν₀⁺T and δ).
    pub der_kiureghian: Option<PeakFactor>,
}

/// One row of the mission table: P(max |y| > b within T) and the expected up-crossings of b.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct MissionRow {
    /// Output.
    pub output: String,
    /// Unit.
    pub unit: String,
    /// The clearance b.
    pub level: f64,
    /// ∫₀ᵀ ν⁺(b, t) dt (one-sided: up-crossings of +b).
    pub expected_upcrossings: f64,
    /// Non-stationary, Poisson at the integrated two-sided rate: 1 − exp(−∫(ν⁺(b) + ν⁻(−b)) dt).
    pub p_integrated_rate: f64,
    /// Stationary Poisson (Rice) with the end state's moments.
    pub p_poisson: Option<f64>,
    /// Stationary Vanmarcke (1975).
    pub p_vanmarcke: Option<f64>,
    /// Stationary Der Kiureghian (1980): 1 − exp(−N_e e^{−r²/2}).
    pub p_der_kiureghian: Option<f64>,
}

/// The whole answer.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct TransientAnalysis {
    /// Scenario title.
    pub title: String,
    /// The system, its schedules and input, in one line.
    pub description: String,
    /// The start.
    pub start: Start,
    /// The reported times, s.
    pub times: Vec<f64>,
    /// The reported outputs, then the weighted ones.
    pub outputs: Vec<OutputOverTime>,
    /// Mission duration T, s.
    pub mission_duration: f64,
    /// Per reported output with a stationary end state: its stationary extremes (None: why not in `notes`).
    pub stationary: Vec<(String, Option<StationaryExtremes>)>,
    /// The mission table.
    pub mission: Vec<MissionRow>,
    /// The exact route's integration report (steps, error estimate; zero for the evolutionary route).
    pub report: StepReport,
    /// Which route answered, with its error estimate, in one line.
    pub route: String,
    /// Remarks.
    pub notes: Vec<String>,
}

/// The clearances of output `i`: `[analysis.mission] levels`, else `[analysis.levels]`.
fn levels_of(sc: &Scenario, i: usize) -> Vec<f64> {
    let from = |l: &[(usize, Vec<f64>)]| l.iter().find(|(j, _)| *j == i).map(|(_, v)| v.clone());
    match &sc.analysis.mission {
        Some(m) => from(&m.levels).unwrap_or_default(),
        None => from(&sc.analysis.levels).unwrap_or_default(),
    }
}

/// ∫₀^{t_end} y dt by the trapezoidal rule on the stored times, the last value held beyond the last time.
///
/// # Formula
/// Σ ½(y_k + y_{k+1})(t_{k+1} − t_k) over the intervals inside [0, t_end] (the last one cut, y interpolated
/// linearly), plus y_K (t_end − t_K) when t_end > t_K.
pub fn integrate_held(t: &[f64], y: &[f64], t_end: f64) -> f64 {
    let mut acc = 0.0;
    for k in 0..t.len().saturating_sub(1) {
        if t_end <= t[k] {
            return acc;
        }
        let b = t[k + 1].min(t_end);
        let yb = y[k] + (y[k + 1] - y[k]) * (b - t[k]) / (t[k + 1] - t[k]);
        acc += 0.5 * (y[k] + yb) * (b - t[k]);
    }
    let last = t.len() - 1;
    acc + y[last] * (t_end - t[last]).max(0.0)
}

/// The analysis of a scenario with `[transient]`: the exact route, or the evolutionary route for an input
/// without one ([`has_exact_route`]).
///
/// # Errors
/// The errors of [`transient_setup`] and [`exact_solution`], or of [`evolutionary_setup`].
pub fn transient_analysis(sc: &Scenario) -> Result<TransientAnalysis> {
    if !has_exact_route(sc)? {
        return evolutionary_analysis(sc);
    }
    let setup = transient_setup(sc)?;
    let sol = exact_solution(sc, &setup)?;
    Ok(answers(sc, &setup, &sol))
}

/// The analysis of a scenario by the evolutionary route ([`evolutionary_setup`]): σ(t), ν₀⁺(t) and the
/// crossing rates of the frozen system where the error estimate allows, the mission's integrated rates over
/// those times (n/a at the others: no stationary extremes, a note says where).
///
/// # Errors
/// The errors of [`evolutionary_setup`].
pub fn evolutionary_analysis(sc: &Scenario) -> Result<TransientAnalysis> {
    let ev = evolutionary_setup(sc)?;
    let sol = &ev.solution.solution;
    let window = *sol.times.last().unwrap_or(&0.0);
    let duration = sc.analysis.mission.as_ref().and_then(|m| m.duration).unwrap_or(window);
    let outputs: Vec<OutputOverTime> = ev
        .outputs
        .iter()
        .map(|&i| over_time(sc, &ev.weighted, sol, i))
        .collect();
    let missing = |i: usize| sol.outputs[i].sigma.iter().filter(|s| s.is_nan()).count();
    let mut notes = Vec::new();
    for &i in &ev.outputs {
        let n = missing(i);
        if n > 0 {
            notes.push(format!(
                "`{}`: n/a at {n} of {} times, where the error estimate δ(t) exceeds {}: use Monte Carlo there",
                sol.outputs[i].name,
                sol.times.len(),
                ev.solution.max_error
            ));
        }
    }
    let mission = ev
        .outputs
        .iter()
        .filter(|&&i| missing(i) == 0)
        .flat_map(|&i| {
            levels_of(sc, i)
                .into_iter()
                .filter_map(move |b| mission_row(sol, i, b, duration, None))
        })
        .collect();
    let worst = sol
        .error_estimate
        .iter()
        .copied()
        .filter(|d| *d <= ev.solution.max_error)
        .fold(0.0, f64::max);
    Ok(TransientAnalysis {
        title: sc.title.clone(),
        description: ev.description,
        start: sol.start.clone(),
        times: sol.times.clone(),
        outputs,
        mission_duration: duration,
        stationary: ev
            .outputs
            .iter()
            .map(|&i| (sol.outputs[i].name.clone(), None))
            .collect(),
        mission,
        report: sol.report,
        route: format!(
            "evolutionary-spectrum route (the system frozen at each time in the stationary state of the input's \
             evolutionary spectrum; no exact route for this input): values where the lag estimate δ(t) <= {}, \
             largest δ reported {worst:.1e}",
            ev.solution.max_error
        ),
        notes,
    })
}

/// The answers from a solved setup.
pub fn answers(sc: &Scenario, setup: &TransientSetup, sol: &TransientSolution) -> TransientAnalysis {
    let window = *sol.times.last().unwrap_or(&0.0);
    let duration = sc.analysis.mission.as_ref().and_then(|m| m.duration).unwrap_or(window);
    let mut notes = Vec::new();
    let outputs: Vec<OutputOverTime> = setup
        .outputs
        .iter()
        .map(|&i| over_time(sc, &setup.weighted, sol, i))
        .collect();
    let stationary: Vec<(String, Option<StationaryExtremes>)> = setup
        .outputs
        .iter()
        .map(|&i| {
            let name = sol.outputs[i].name.clone();
            match stationary_extremes(setup, sol, i, duration) {
                Ok(s) => (name, Some(s)),
                Err(why) => {
                    notes.push(format!("`{name}`: no stationary extremes: {why}"));
                    (name, None)
                }
            }
        })
        .collect();
    let mut mission = Vec::new();
    for (&i, st) in setup.outputs.iter().zip(&stationary) {
        for b in levels_of(sc, i) {
            if let Some(row) = mission_row(sol, i, b, duration, st.1.as_ref()) {
                mission.push(row);
            }
        }
    }
    if duration > window {
        notes.push(format!(
            "the mission ({duration} s) is longer than the window ({window} s): the integrated rates hold the \
             rates of the window's end for the rest (valid when the response has settled by then)"
        ));
    }
    TransientAnalysis {
        title: sc.title.clone(),
        description: setup.sys.describe(),
        start: setup.start.clone(),
        times: sol.times.clone(),
        outputs,
        mission_duration: duration,
        stationary,
        mission,
        report: sol.report,
        route: format!(
            "exact route: {} steps ({} exact), {} matrix exponentials, accumulated error estimate {:.1e} (relative \
             to the largest variance of each state over the window)",
            sol.report.steps, sol.report.exact_steps, sol.report.exponentials, sol.report.max_error_estimate
        ),
        notes,
    }
}

fn over_time(sc: &Scenario, weighted: &[(usize, usize)], sol: &TransientSolution, i: usize) -> OutputOverTime {
    let o = &sol.outputs[i];
    let weighted_of = weighted
        .iter()
        .find(|w| w.1 == i)
        .map(|w| sol.outputs[w.0].name.clone());
    let rates_ok = o.unavailable.is_none() && o.rate_note.is_none();
    let levels = if weighted_of.is_none() {
        levels_of(sc, i)
    } else {
        Vec::new()
    };
    OutputOverTime {
        name: o.name.clone(),
        unit: o.unit.clone(),
        weighted_of,
        mean: o.mean.clone(),
        sigma: o.sigma.clone(),
        nu0_plus: if rates_ok {
            (0..o.sigma.len()).map(|k| o.nu0_plus(k)).collect()
        } else {
            Vec::new()
        },
        upcrossing_rates: if rates_ok {
            levels
                .iter()
                .map(|&b| (b, sol.crossing_rates(i, b, Barrier::OneSided)))
                .collect()
        } else {
            Vec::new()
        },
        note: o.unavailable.clone().or(o.rate_note.clone()),
    }
}

/// The stationary moments of output i of the frozen system at the end of the window.
fn stationary_extremes(
    setup: &TransientSetup,
    sol: &TransientSolution,
    i: usize,
    duration: f64,
) -> std::result::Result<StationaryExtremes, String> {
    let o = &sol.outputs[i];
    if let Some(why) = o.unavailable.as_ref().or(o.rate_note.as_ref()) {
        return Err(why.clone());
    }
    let t_end = *sol.times.last().unwrap_or(&0.0);
    let fr = setup.sys.frozen(t_end).map_err(|e| e.to_string())?;
    if !crate::linalg::is_stable(&fr.f) {
        return Err(format!(
            "the system frozen at t = {t_end} s is not asymptotically stable: no stationary state"
        ));
    }
    let m = stationary_moments(&fr, i, 1e-9).map_err(|e| e.to_string())?;
    let mean_states = fr.f.clone().lu().solve(&(-&fr.b)).ok_or("singular F")?;
    let mean = (fr.h.row(i) * mean_states)[(0, 0)] + fr.y0[i];
    let nt = m.nu0_plus * duration;
    Ok(StationaryExtremes {
        mean,
        sigma: m.lambda0.sqrt(),
        nu0_plus: m.nu0_plus,
        delta: m.delta,
        davenport: davenport(nt, Barrier::TwoSided).ok(),
        der_kiureghian: der_kiureghian(nt, m.delta).ok(),
    })
}

/// The mission row of output i at clearance b (None when the output has no crossing rates).
fn mission_row(
    sol: &TransientSolution,
    i: usize,
    b: f64,
    duration: f64,
    st: Option<&StationaryExtremes>,
) -> Option<MissionRow> {
    let o = &sol.outputs[i];
    if o.unavailable.is_some() || o.rate_note.is_some() {
        return None;
    }
    let up = sol.crossing_rates(i, b, Barrier::OneSided);
    let both = sol.crossing_rates(i, b, Barrier::TwoSided);
    let count = integrate_held(&sol.times, &both, duration);
    let moments = st.map(|s| CrossingMoments {
        mean: s.mean,
        sigma: s.sigma,
        nu0_plus: s.nu0_plus,
        delta: Some(s.delta),
    });
    let p = |method| moments.and_then(|m| m.exceedance(b, duration, Barrier::TwoSided, method).ok());
    let dk = st.and_then(|s| {
        let pf = s.der_kiureghian?;
        let r = (b - s.mean) / s.sigma;
        (s.mean == 0.0 && r > 0.0).then(|| -(-pf.n * (-0.5 * r * r).exp()).exp_m1())
    });
    Some(MissionRow {
        output: o.name.clone(),
        unit: o.unit.clone(),
        level: b,
        expected_upcrossings: integrate_held(&sol.times, &up, duration),
        p_integrated_rate: -(-count).exp_m1(),
        p_poisson: p(ExceedanceMethod::Poisson),
        p_vanmarcke: p(ExceedanceMethod::Vanmarcke1975),
        p_der_kiureghian: dk,
    })
}
