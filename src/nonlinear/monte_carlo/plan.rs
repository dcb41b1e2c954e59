//! Planning a route-2 run: the route and its linear flow, the step and the burn-in computed from the
//! system, the simulated outputs with their levels, histograms and reference values.

use super::flow::{ExactFlow, FohFlow};
use super::inputs::InputSynthesis;
use super::{NonlinearRunInput, NonlinearRunOptions};
use crate::error::{Error, Result};
use crate::estimate::Welch;
use crate::nonlinear::integrator::{Kicks, CONTACT_STEP};
use crate::nonlinear::{ElementMoments, NonlinearModel};
use crate::response::{Excitation, Source};
use crate::simulate::{Route, SkippedOutput};
use crate::store::Signal;
use crate::system::{FrequencyResponse, Mdof};
use nalgebra::DVector;

/// Bins of every output's histogram (between μ ± 6σ of the reference law, plus under- and overflow).
pub(crate) const HISTOGRAM_BINS: usize = 120;

/// Burn-in criterion: the slowest mode's transient e^{−σ_min t} has decayed to e^{−BURN_IN_DECAY}
/// (ln 10⁶ for the covariance e^{−2σ_min t} after half the time, doubled because the decay rate is that of
/// the Gaussian equivalent, not of the nonlinear system).
pub const BURN_IN_DECAY: f64 = 13.815_510_557_964_274;

/// Reference values of one statistic: route 1 (Gaussian equivalent) and route 3 (exact), where known.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub(crate) struct Reference {
    pub route1: Option<f64>,
    pub exact: Option<f64>,
}

/// A simulated output.
#[derive(Debug, Clone)]
pub(crate) struct PlannedOutput {
    pub index: usize,
    pub signal: Signal,
    /// Route 1's mean (or the linear part's): the reference c of the records.
    pub centre: f64,
    /// The output at the linear part's static equilibrium under the input means.
    pub offset: f64,
    /// a_rᵀM⁻¹d_e per element (acceleration outputs: the elements' forces enter with a minus sign).
    pub acc: Vec<f64>,
    pub levels: Vec<f64>,
    /// Elements whose regime statistics this output carries.
    pub regimes: Vec<usize>,
    pub hist_lo: f64,
    pub hist_width: f64,
    /// mean, σ, kurtosis, then per level the rate, then per regime (fraction, rate).
    pub reference: Vec<Reference>,
    /// The reference density at the histogram's bin centres: route 1's Gaussian, the exact one.
    pub gaussian: Option<Vec<f64>>,
    pub exact: Option<Vec<f64>>,
}

/// How the realizations are produced.
pub(crate) enum Flow {
    Exact(Box<ExactFlow>),
    Hold {
        flow: Box<FohFlow>,
        inputs: Box<InputSynthesis>,
        /// The base inputs whose rates are synthesised (in the synthesis' order).
        rates: Vec<usize>,
    },
}

/// Everything a route-2 run needs besides the file.
pub(crate) struct NlPlan {
    pub route: Route,
    pub flow: Flow,
    pub kicks: Kicks,
    pub h: f64,
    pub n_burn: usize,
    pub n: usize,
    pub outputs: Vec<PlannedOutput>,
    pub skipped: Vec<SkippedOutput>,
    /// Static equilibrium q of the linear part under the input means, and the input means.
    pub q_eq: Vec<f64>,
    pub u_mean: Vec<f64>,
    /// Route 1's mean of q minus q_eq: where the exact route's Gaussian start is centred.
    pub start_shift: Vec<f64>,
    pub welch: Welch,
    pub notes: Vec<String>,
    pub generator: String,
    /// Realizations 0..checks get the Δt-halving check.
    pub checks: usize,
    pub input_signals: Vec<Signal>,
    pub n_coords: usize,
    pub n_base: usize,
}

impl NlPlan {
    /// The run's recorded duration, s.
    pub fn duration(&self) -> f64 {
        self.n as f64 * self.h
    }
}

/// The slowest decay rate min|Re λ| of a stable model.
fn slowest_decay(m: &Mdof) -> Option<f64> {
    let ss = m.state_space()?;
    let s =
        ss.a.complex_eigenvalues()
            .iter()
            .map(|l| -l.re)
            .fold(f64::INFINITY, f64::min);
    (s.is_finite() && s > 0.0).then_some(s)
}

/// The model whose Gaussian law starts the realizations and sets the burn-in: route 1's equivalent, else
/// the linear part if it is stable.
fn start_model<'a>(input: &'a NonlinearRunInput) -> Result<&'a Mdof> {
    if let Some(r) = input.route1 {
        return Ok(&r.equivalent);
    }
    let lin = input.model.linear();
    if slowest_decay(lin).is_some() {
        return Ok(lin);
    }
    Err(Error::invalid(
        "route 1",
        "not converged",
        "route 2 starts from the Gaussian equivalent's stationary law and takes its burn-in from its slowest \
         decay; without it (and with a linear part that has no stationary response) give --burn-in",
    ))
}

/// The default burn-in, s: [`BURN_IN_DECAY`]/σ_min of the model that starts the realizations (`None` without
/// one).
pub(crate) fn default_burn_in(input: &NonlinearRunInput) -> Option<f64> {
    Some(BURN_IN_DECAY / slowest_decay(start_model(input).ok()?)?)
}

/// The largest contact frequency √(κ_e k_e) of the elements over the response route 1 predicts (rad/s).
pub(crate) fn contact_frequency(model: &NonlinearModel, moments: Option<&[ElementMoments]>) -> f64 {
    model
        .elements()
        .iter()
        .enumerate()
        .map(|(e, el)| {
            let m = moments.map(|m| m[e]).unwrap_or(ElementMoments {
                sigma_x: 0.0,
                ..Default::default()
            });
            (model.kappa(e) * el.law.stiffness_bound(&m)).sqrt()
        })
        .fold(0.0, f64::max)
}

/// Plans a run (see the module docs of [`super`]).
pub(crate) fn plan(input: &NonlinearRunInput, opts: &NonlinearRunOptions) -> Result<NlPlan> {
    let n = opts.run.samples()?;
    let h = opts.run.dt_s;
    let model = input.model;
    let start = start_model(input);
    let mut notes = Vec::new();
    let wc = contact_frequency(model, input.route1.map(|r| r.moments.as_slice()));
    if h * wc > 2.0 {
        return Err(Error::invalid(
            "dt",
            h,
            format!(
                "the stiffest element has ω_c = √(κ k) = {wc:.4e} rad/s: the splitting's explicit element kick is \
                 unstable for Δt·ω_c > 2; take Δt ≤ {:.4e} s (default {CONTACT_STEP}/ω_c)",
                2.0 / wc
            ),
        ));
    }
    if h * wc > CONTACT_STEP {
        notes.push(format!(
            "Δt·ω_c = {:.3} > {CONTACT_STEP}: the stiffest element (ω_c = √(κ k) = {wc:.4e} rad/s) is resolved \
             coarsely; its contact rates are biased (see the Δt-halving difference)",
            h * wc
        ));
    }
    let burn = match (opts.burn_in_s, &start) {
        (Some(b), _) => b,
        (None, Ok(_)) => default_burn_in(input).unwrap_or(f64::NAN),
        (None, Err(e)) => return Err(Error::invalid("burn-in", "<not given>", e.to_string())),
    };
    if !(burn.is_finite() && burn >= 0.0) {
        return Err(Error::invalid("burn-in", burn, "must be finite and >= 0"));
    }
    let n_burn = synthesis_length((burn / h).ceil() as usize + n) - n;
    notes.push(format!(
        "burn-in {:.4} s ({n_burn} steps){}, rounded up so that burn-in and record are 2^a·3^b·5^c steps",
        n_burn as f64 * h,
        if opts.burn_in_s.is_some() {
            " at least as given".to_string()
        } else {
            format!(" ≥ {BURN_IN_DECAY:.2}/σ_min, σ_min the slowest decay rate of the Gaussian equivalent")
        }
    ));
    let lin = model.linear();
    let (q_eq, u_mean) = equilibrium(lin, input.excitation)?;
    let rates: Vec<bool> = (0..lin.n_base())
        .map(|j| {
            model
                .elements()
                .iter()
                .any(|e| e.law.velocity_dependent() && e.base() == Some(j))
        })
        .collect();
    let (mut outputs, mut skipped) = plan_outputs(input, &q_eq, &u_mean)?;
    let (route, flow, generator) = choose_flow(
        input,
        opts,
        start.ok(),
        &mut outputs,
        &mut skipped,
        &rates,
        n_burn + n,
        &mut notes,
    )?;
    if outputs.is_empty() {
        return Err(Error::invalid(
            "outputs",
            skipped.iter().map(|s| s.name.as_str()).collect::<Vec<_>>().join(", "),
            "no output can be simulated",
        ));
    }
    let m_welch = welch_segment(n);
    let r = opts.run.realizations;
    Ok(NlPlan {
        route,
        flow,
        kicks: Kicks::new(model),
        h,
        n_burn,
        n,
        outputs,
        skipped,
        start_shift: match input.route1 {
            Some(r) => r.mean_q.iter().zip(&q_eq).map(|(a, b)| a - b).collect(),
            None => vec![0.0; q_eq.len()],
        },
        q_eq,
        u_mean,
        welch: Welch::new(m_welch, h)?,
        notes,
        generator,
        checks: opts.halving_checks.unwrap_or_else(|| r.min((r / 20).max(4))).min(r),
        input_signals: input.input_signals.clone(),
        n_coords: lin.n_coords(),
        n_base: lin.n_base(),
    })
}

/// Whether n = 2^a·3^b·5^c (n ≥ 1): a length rustfft transforms by its radix-2/3/5 butterflies, not by
/// Rader's or Bluestein's algorithm for a large prime factor.
pub(crate) fn is_5_smooth(n: usize) -> bool {
    let mut n = n;
    for p in [2, 3, 5] {
        while n > 0 && n.is_multiple_of(p) {
            n /= p;
        }
    }
    n == 1
}

/// The steps of burn-in plus record (the synthesis length of the spectral route's inputs): the smallest
/// even 2^a·3^b·5^c ≥ `n` (since version 2 of the route, [`super::GENERATOR_VERSION`]).
///
/// The candidates 2^a·3^b·5^c (a ≥ 1) are enumerated, O(log³ n): a search upwards in steps of 2 took
/// hours for the lengths of a mistyped duration (the gaps between such numbers grow with n), before the run
/// time could be checked.
pub(crate) fn synthesis_length(n: usize) -> usize {
    let target = n.max(2);
    let mut best = usize::MAX;
    let mut p2: usize = 2;
    while p2 < best {
        let mut p23 = p2;
        while p23 < best {
            let mut p = p23;
            while p < target {
                p = p.saturating_mul(5);
            }
            best = best.min(p);
            p23 = p23.saturating_mul(3);
        }
        p2 = p2.saturating_mul(2);
    }
    best
}

/// The Welch segment of a route-2 record of `n` samples: the largest even 2^a·3^b·5^c ≤ min(1024, n/8)
/// (at least 4), so that a record holds at least about 15 half-overlapping segments and the segment's FFT
/// has only the factors 2, 3, 5 (since version 2 of the route, [`super::GENERATOR_VERSION`]).
pub fn welch_segment(n: usize) -> usize {
    let mut m = ((n / 8) & !1).clamp(4, 1024);
    while !is_5_smooth(m) {
        m -= 2;
    }
    m
}

/// The linear part's static equilibrium C q = K_u μ_u + F μ_f under the input means, and the means.
pub(crate) fn equilibrium(lin: &Mdof, exc: &Excitation) -> Result<(Vec<f64>, Vec<f64>)> {
    let mu = exc.means();
    let n = lin.n_coords();
    if mu.iter().all(|m| *m == 0.0) {
        return Ok((vec![0.0; n], mu));
    }
    let nb = lin.n_base();
    let rhs = lin.base_stiffness() * DVector::from_column_slice(&mu[..nb])
        + lin.force_distribution() * DVector::from_column_slice(&mu[nb..]);
    let q = lin.stiffness().clone().lu().solve(&rhs).ok_or_else(|| {
        Error::invalid(
            "input mean",
            format!("{mu:?}"),
            "the linear part has no static equilibrium under the input means (a free rigid-body mode)",
        )
    })?;
    Ok((q.as_slice().to_vec(), mu))
}

/// The simulated outputs with their references, levels, regimes and histograms; outputs without a finite
/// reference variance are skipped with the reason.
pub(crate) fn plan_outputs(
    input: &NonlinearRunInput,
    q_eq: &[f64],
    u_mean: &[f64],
) -> Result<(Vec<PlannedOutput>, Vec<SkippedOutput>)> {
    let model = input.model;
    let lin = model.linear();
    let mut out = Vec::new();
    let mut skipped = Vec::new();
    let mut attached = vec![false; model.elements().len()];
    for &r in &input.outputs {
        let info = &lin.outputs()[r];
        let refs = match super::references::output_references(input, r) {
            Ok(x) => x,
            Err(reason) => {
                skipped.push(SkippedOutput {
                    name: info.name.clone(),
                    reason,
                });
                continue;
            }
        };
        let w = lin.output_weights(r).expect("an output of the model");
        let offset = dot(w.q, q_eq) + dot(w.u, u_mean);
        let minv = lin.mass_inverse();
        let acc = model
            .elements()
            .iter()
            .map(|e| {
                let d = DVector::from_vec(e.direction());
                (DVector::from_column_slice(w.a).transpose() * minv * d)[(0, 0)]
            })
            .collect();
        let mut levels: Vec<f64> = input
            .levels
            .iter()
            .filter(|(o, _)| *o == r)
            .flat_map(|(_, l)| l.iter().copied())
            .collect();
        let mut regimes = Vec::new();
        for (e, el) in model.elements().iter().enumerate() {
            let (Some(reg), Some(f)) = (el.law.regime(), model.deflection_factor(r, e)) else {
                continue;
            };
            levels.extend(reg.levels.iter().map(|(a, _)| f * a));
            if !attached[e] {
                attached[e] = true;
                regimes.push(e);
            }
        }
        levels.sort_by(f64::total_cmp);
        levels.dedup();
        out.push(super::references::planned_output(
            input, r, info, refs, offset, acc, levels, regimes,
        )?);
    }
    Ok((out, skipped))
}

fn dot(a: &[f64], b: &[f64]) -> f64 {
    a.iter().zip(b).map(|(x, y)| x * y).sum()
}

/// The exact route where it applies (or is asked for), else the spectral route.
#[allow(clippy::too_many_arguments)]
fn choose_flow(
    input: &NonlinearRunInput,
    opts: &NonlinearRunOptions,
    start: Option<&Mdof>,
    outputs: &mut Vec<PlannedOutput>,
    skipped: &mut Vec<SkippedOutput>,
    rates: &[bool],
    n_total: usize,
    notes: &mut Vec<String>,
) -> Result<(Route, Flow, String)> {
    let exc = input.excitation;
    let lin = input.model.linear();
    let h = opts.run.dt_s;
    let non_gaussian = input.kurtosis.iter().any(Option::is_some);
    let two_tracks =
        matches!(exc, Excitation::Sources { sources, .. } if sources.iter().any(|s| matches!(s, Source::Matrix(_))));
    let rational = exc.spectra().iter().all(|s| s.rational().is_some());
    let exact_possible = exc.delay_free() && rational && !non_gaussian && !two_tracks;
    let want_exact = match opts.run.route {
        Route::Exact => true,
        Route::Spectral => false,
        Route::Auto => exact_possible,
        Route::SpectralStream => {
            return Err(Error::invalid(
                "route",
                "spectral-stream",
                "a nonlinear run keeps whole records of its inputs: use auto, exact or spectral",
            ))
        }
    };
    if !want_exact && opts.run.route == Route::Auto {
        notes.push(format!(
            "spectral route: {}",
            if non_gaussian {
                "non-Gaussian inputs (Laplace moving averages on the spectral grid)".to_string()
            } else if two_tracks {
                "two coherent tracks (no rational factorisation of their cross-spectral matrix)".to_string()
            } else if !exc.delay_free() {
                format!(
                    "{} (pure delays have no finite state-space form)",
                    exc.inputs_described()
                )
            } else {
                "an input spectrum without a shaping filter (not rational)".to_string()
            }
        ));
    }
    if want_exact {
        let start = start.ok_or_else(|| Error::invalid("route", "exact", "no stationary law to start from"))?;
        loop {
            let idx: Vec<usize> = outputs.iter().map(|o| o.index).collect();
            match ExactFlow::new(lin, start, exc, &idx, rates, h) {
                Ok(f) => {
                    notes.push(
                        "exact route: Van Loan discretisation of the linear part augmented with the inputs' shaping \
                         filters (the draws of a linear run), element flows by symmetric splitting; stationary start \
                         from route 1's Gaussian law"
                            .into(),
                    );
                    let generator = format!(
                        "{}, stream (seed, i) per realization; exact Van Loan discretisation of the linear part \
                         augmented with its shaping filters, Strang splitting with exact element flows (Δt = {h} s)",
                        crate::simulate::GENERATOR
                    );
                    return Ok((Route::Exact, Flow::Exact(Box::new(f)), generator));
                }
                Err(Error::Divergent { quantity, reason }) => {
                    let name = quantity
                        .trim_start_matches("samples of `")
                        .trim_end_matches('`')
                        .to_string();
                    let pos = outputs.iter().position(|o| o.signal.name == name);
                    match pos {
                        Some(p) => {
                            outputs.remove(p);
                            skipped.push(SkippedOutput { name, reason });
                        }
                        None => return Err(Error::Divergent { quantity, reason }),
                    }
                    if outputs.is_empty() {
                        return Err(Error::invalid("outputs", "[]", "no output can be sampled"));
                    }
                }
                Err(e) if opts.run.route == Route::Exact => return Err(e),
                Err(e) => {
                    notes.push(format!("spectral route: the exact route does not apply ({e})"));
                    break;
                }
            }
        }
    }
    hold_flow(input, opts, outputs, skipped, rates, n_total, notes)
}

fn hold_flow(
    input: &NonlinearRunInput,
    opts: &NonlinearRunOptions,
    outputs: &mut Vec<PlannedOutput>,
    skipped: &mut Vec<SkippedOutput>,
    rates: &[bool],
    n_total: usize,
    notes: &mut Vec<String>,
) -> Result<(Route, Flow, String)> {
    let lin = input.model.linear();
    let h = opts.run.dt_s;
    let idx: Vec<usize> = outputs.iter().map(|o| o.index).collect();
    let flow = FohFlow::new(lin, &idx, h)?;
    // outputs that feed u̇ through (E ≠ 0) need the rate of that input
    let mut rate_inputs: Vec<usize> = (0..lin.n_base()).filter(|&j| rates[j]).collect();
    let needs = |k: usize| -> Vec<usize> { (0..flow.m).filter(|&j| flow.e_rows[k][j] != 0.0).collect() };
    for k in 0..idx.len() {
        for j in needs(k) {
            if !rate_inputs.contains(&j) {
                rate_inputs.push(j);
            }
        }
    }
    let synth = match InputSynthesis::new(
        input.excitation,
        rate_inputs.clone(),
        &input.kurtosis,
        &input.input_signals,
        n_total,
        h,
    ) {
        Ok(s) => s,
        Err(e) if rate_inputs.iter().any(|j| !rates[*j]) => {
            // a rate only some outputs need is infinite: drop those outputs, keep the elements' rates
            let keep: Vec<usize> = rate_inputs.iter().copied().filter(|j| rates[*j]).collect();
            let mut k = 0;
            outputs.retain(|_| {
                let ok = needs(k).iter().all(|j| keep.contains(j));
                k += 1;
                ok
            });
            let dropped: Vec<String> = idx
                .iter()
                .filter(|i| !outputs.iter().any(|o| o.index == **i))
                .map(|i| lin.outputs()[*i].name.clone())
                .collect();
            for name in dropped {
                skipped.push(SkippedOutput {
                    name,
                    reason: format!("needs the rate of a base input, which has infinite variance ({e})"),
                });
            }
            return hold_flow_with(input, opts, outputs, keep, n_total, notes);
        }
        Err(e) => return Err(e),
    };
    finish_hold(input, flow, synth, rate_inputs, notes)
}

fn hold_flow_with(
    input: &NonlinearRunInput,
    opts: &NonlinearRunOptions,
    outputs: &[PlannedOutput],
    rates: Vec<usize>,
    n_total: usize,
    notes: &mut Vec<String>,
) -> Result<(Route, Flow, String)> {
    let idx: Vec<usize> = outputs.iter().map(|o| o.index).collect();
    let flow = FohFlow::new(input.model.linear(), &idx, opts.run.dt_s)?;
    let synth = InputSynthesis::new(
        input.excitation,
        rates.clone(),
        &input.kurtosis,
        &input.input_signals,
        n_total,
        opts.run.dt_s,
    )?;
    finish_hold(input, flow, synth, rates, notes)
}

fn finish_hold(
    _input: &NonlinearRunInput,
    flow: FohFlow,
    synth: InputSynthesis,
    rates: Vec<usize>,
    notes: &mut Vec<String>,
) -> Result<(Route, Flow, String)> {
    notes.push(
        "spectral route: synthesised input samples (the generators of linear runs), first-order hold of the linear \
         part between them, element flows by symmetric splitting; started at rest, burn-in discarded"
            .into(),
    );
    let generator = format!(
        "{}; first-order hold of the linear part, Strang splitting with exact element flows",
        synth.generator
    );
    Ok((
        Route::Spectral,
        Flow::Hold {
            flow: Box::new(flow),
            inputs: Box::new(synth),
            rates,
        },
        generator,
    ))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Brute force: every 2^a 3^b 5^c ≤ `limit`, sorted (an independent enumeration).
    fn smooth_numbers(limit: usize) -> Vec<usize> {
        let mut v = Vec::new();
        let mut p2 = 1;
        while p2 <= limit {
            let mut p3 = p2;
            while p3 <= limit {
                let mut p5 = p3;
                while p5 <= limit {
                    v.push(p5);
                    p5 *= 5;
                }
                p3 *= 3;
            }
            p2 *= 2;
        }
        v.sort_unstable();
        v
    }

    /// The lengths are the nearest even 2^a·3^b·5^c above (synthesis) and below (Welch segment) at every n up
    /// to 10⁵, and the benchmark's lengths of version 1 (9914 = 2·4957, 922 = 2·461, both through Rader's
    /// algorithm) become 10000 = 2⁴5⁴ and 900 = 2²3²5².
    #[test]
    fn lengths_are_the_nearest_even_2_3_5_smooth_numbers() {
        let even: Vec<usize> = smooth_numbers(100_000).into_iter().filter(|m| m % 2 == 0).collect();
        for n in 1..90_000 {
            let up = *even.iter().find(|&&m| m >= n).unwrap();
            assert_eq!(synthesis_length(n), up, "n = {n}");
            let cap = ((n / 8) & !1).clamp(4, 1024);
            let down = *even.iter().rev().find(|&&m| m <= cap).unwrap();
            assert_eq!(welch_segment(n), down, "n = {n}");
        }
        assert_eq!((synthesis_length(9914), welch_segment(7380)), (10_000, 900));
        // lengths of a mistyped duration (10¹² s at a few ms a step) come at once, and right
        let big: Vec<usize> = smooth_numbers(1 << 52).into_iter().filter(|m| m % 2 == 0).collect();
        for n in [172_117_866_053_627usize, 1 << 40, (1 << 40) + 1, 999_999_999_999_989] {
            assert_eq!(synthesis_length(n), *big.iter().find(|&&m| m >= n).unwrap(), "n = {n}");
        }
        assert!(!is_5_smooth(0) && is_5_smooth(1) && !is_5_smooth(922) && !is_5_smooth(9914));
    }
}
