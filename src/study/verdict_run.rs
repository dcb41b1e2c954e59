//! A Monte Carlo run of a scenario with verdicts: the system is extended by the weighted outputs
//! W(s)·H_i(s) of `[analysis.comfort]` (the weighting filters become states of the simulated system, so
//! they are discretised exactly with it), and the run evaluates the ISO 2631-1 metrics of every weighted
//! output and the rainflow damage of the `[analysis.fatigue]` stress on every realization
//! ([`crate::simulate::verdicts`]).

use super::verdict_analysis::fatigue_moments;
use crate::comfort::weighted_output;
use crate::error::{Error, Result};
use crate::scenario::Scenario;
use crate::simulate::{ComfortChannel, FatigueChannel, RunInput, RunOptions, RunSummary, VerdictChannels};
use crate::system::{FrequencyResponse, OutputInfo, StateSpace};
use nalgebra::DMatrix;
use std::path::Path;

/// The scenario's system with the weighted outputs of `[analysis.comfort]` appended (in axis order), and
/// their output indices.
///
/// # Formula
/// With ẋ = Ax + Bu, y = Cx + Du + Eu̇ and the weighted outputs z_j = W_j(s)·y_{i_j} realised as in
/// [`weighted_output`] (states ξ_j driven by x and u), the extended state is [x; ξ_1; …; ξ_J]:
/// ```text
/// A_ext = [[A, 0, …], [B_{ξ1,x}, A_{ξ1}, 0, …], …],   B_ext = [B; B_{ξ1}; …],
/// C_ext = [[C, 0, …], [C_{z1,x}, C_{z1,ξ1}, 0, …], …], D_ext = [D; D_{z1}; …], E_ext = [E; E_{z1}; …]
/// ```
/// so every original output keeps its frequency response and output n + j has W_j(iω)·H_{i_j}(iω).
///
/// # Errors
/// [`Error::NotApplicable`] for a model without a state-space form; the errors of [`weighted_output`].
pub fn verdict_system(sc: &Scenario) -> Result<(StateSpace, Vec<usize>)> {
    let ss = sc.model.system.state_space().ok_or_else(|| Error::NotApplicable {
        method: "frequency-weighted simulation".into(),
        reason: "the model has no state-space form".into(),
    })?;
    let axes = sc
        .analysis
        .verdicts
        .comfort
        .as_ref()
        .map(|c| c.axes.clone())
        .unwrap_or_default();
    with_weighted_outputs(ss, &axes)
}

/// `ss` with the weighted outputs of `axes` appended (in axis order), and their output indices (the
/// formula of [`verdict_system`]).
///
/// # Errors
/// The errors of [`weighted_output`].
pub fn with_weighted_outputs(
    ss: &StateSpace,
    axes: &[crate::scenario::ComfortAxisSpec],
) -> Result<(StateSpace, Vec<usize>)> {
    let parts: Vec<StateSpace> = axes
        .iter()
        .map(|a| weighted_output(ss, a.output, &a.weighting))
        .collect::<Result<_>>()?;
    let (n, m, p) = (ss.n_states(), ss.b.ncols(), ss.c.nrows());
    let nw: Vec<usize> = parts.iter().map(|w| w.n_states() - n).collect();
    let nt = n + nw.iter().sum::<usize>();
    let pt = p + parts.len();
    let mut a = DMatrix::zeros(nt, nt);
    let mut b = DMatrix::zeros(nt, m);
    let mut c = DMatrix::zeros(pt, nt);
    let mut d = DMatrix::zeros(pt, m);
    let mut e = DMatrix::zeros(pt, m);
    a.view_mut((0, 0), (n, n)).copy_from(&ss.a);
    b.view_mut((0, 0), (n, m)).copy_from(&ss.b);
    c.view_mut((0, 0), (p, n)).copy_from(&ss.c);
    d.view_mut((0, 0), (p, m)).copy_from(&ss.d);
    e.view_mut((0, 0), (p, m)).copy_from(&ss.e);
    let mut outputs: Vec<OutputInfo> = ss.outputs().to_vec();
    let mut off = n;
    for (j, (w, &q)) in parts.iter().zip(&nw).enumerate() {
        a.view_mut((off, 0), (q, n)).copy_from(&w.a.view((n, 0), (q, n)));
        a.view_mut((off, off), (q, q)).copy_from(&w.a.view((n, n), (q, q)));
        b.view_mut((off, 0), (q, m)).copy_from(&w.b.view((n, 0), (q, m)));
        c.view_mut((p + j, 0), (1, n)).copy_from(&w.c.view((0, 0), (1, n)));
        c.view_mut((p + j, off), (1, q)).copy_from(&w.c.view((0, n), (1, q)));
        d.view_mut((p + j, 0), (1, m)).copy_from(&w.d);
        e.view_mut((p + j, 0), (1, m)).copy_from(&w.e);
        outputs.push(w.outputs()[0].clone());
        off += q;
    }
    let ext = StateSpace::new(a, b, c, Some(d), Some(e), outputs)?;
    Ok((ext, (p..pt).collect()))
}

/// Runs the Monte Carlo batch of a scenario with `[analysis.comfort]` or `[analysis.fatigue]`: the
/// reported outputs, the weighted outputs and the fatigue output are simulated, and the file gets the
/// verdict statistics (`vdv`, `mtvv`, `crest_factor` of each weighted output; `damage_rate` of the fatigue
/// output, with Dirlik's rate as its analytic value) and the rainflow histogram.
///
/// # Errors
/// As [`crate::simulate::run()`], and those of [`verdict_system`] and of the stress moments.
pub fn simulate_with_verdicts(
    sc: &Scenario,
    opts: &RunOptions,
    out: &Path,
    progress: &dyn Fn(usize, usize),
) -> Result<RunSummary> {
    with_verdict_input(sc, |input| crate::simulate::run(input, opts, out, progress))
}

/// Calls `f` with the subject of the scenario's verdict run ([`simulate_with_verdicts`]): the system with
/// the weighted outputs appended, the reported, weighted and fatigue outputs, and the verdict channels.
///
/// # Errors
/// Those of [`verdict_system`] and of the stress moments; what `f` returns.
pub fn with_verdict_input<T>(sc: &Scenario, f: impl FnOnce(&RunInput) -> Result<T>) -> Result<T> {
    let (ext, weighted) = verdict_system(sc)?;
    let mut input = sc.run_input();
    input.system = &ext;
    let mut outputs = sc.analysis.outputs.clone();
    outputs.extend(&weighted);
    let mut channels = VerdictChannels {
        comfort: weighted
            .iter()
            .map(|&i| ComfortChannel {
                output: ext.outputs()[i].name.clone(),
            })
            .collect(),
        fatigue: Vec::new(),
    };
    if let Some(f) = &sc.analysis.verdicts.fatigue {
        if !outputs.contains(&f.output) {
            outputs.push(f.output);
        }
        let (m, _, _) = fatigue_moments(sc, f)?;
        channels.fatigue.push(FatigueChannel {
            output: f.output_name.clone(),
            stress_factor: f.stress_factor,
            sn: f.sn,
            // amplitudes up to 5σ of the stress: ranges up to 10σ (a Gaussian peak above 5σ has
            // probability e^{−12.5} ≈ 4·10⁻⁶ per peak; the rest is the overflow count)
            max_range: 10.0 * m.m0().sqrt(),
            bins: f.bins,
            sn_unit: "Pa".into(),
            moments: Some(m),
        });
    }
    input.outputs = outputs;
    input.verdicts = channels;
    f(&input)
}
