//! The time step and duration of a scenario's Monte Carlo run when they are not given: chosen from
//! everything the run must resolve, so that by default its intervals cover the analytic values.
//!
//! # Formula
//! Starting from [`suggest_step`] of the model and its input (fastest pole, input band, delays as whole
//! steps), for the simulated system (the model with the weighting filters of `[analysis.comfort]` appended):
//! ```text
//! weighted output w (crest factor, MTVV):  Δt ≤ 1/(16 ν₀⁺_w)      ν₀⁺_w = (1/2π)√(λ₂/λ₀) of the weighted output
//! fatigue stress (rainflow peaks):         Δt ≤ 1/(32 ν_p)         ν_p = √(m₄/m₂), the stress's rate of peaks
//! band table up to f_hi:                   Δt ≤ 1/(2.5 · f_hi · 10^(3/20))   (Nyquist above the top band's edge)
//! discretisation bias of every σ:          |σ_d/σ − 1| ≤ min(cap, h/4),  h = 1.96·cv/(2√R)
//! ```
//! with σ_d the exact σ of the run's discrete process, h the predicted relative half-width of a 95 % σ
//! interval from R realizations (cv: the coefficient of variation of one realization's mean square,
//! [`PlannedVariance::mean_square_cv`]) and the cap 10⁻³ for a weighted output (its a_w), 10⁻² otherwise.
//! A sampled peak of a cycle at frequency f is missed by at most 1 − cos(πfΔt) of its height: 1.9 % at
//! fΔt = 1/16 (0.6 % on average over the phase) and 0.5 % at 1/32 (a damage rate ∝ S^k with k ≈ 3…5 then
//! errs by well under the few per cent of its Monte Carlo interval). The bias σ_d/σ − 1 is exact
//! ([`planned_variances`]: 0 on the exact route; the FFT grid and the first-order hold on the spectral route);
//! while a bias exceeds its target, Δt is halved or the duration doubled — whichever lowers the excess
//! Σ ln(|bias|/target) more (a longer record also narrows the interval, and so the target) — as long as a
//! doubling of the cost lowers it by [`MIN_EXCESS_GAIN`] (any decrease while the run is short,
//! [`CHEAP_STEPS`]) and the run stays within [`MAX_STEPS`] steps; the outputs left over their target are
//! named (their intervals may miss, and the run then says it is the bias). The
//! exact route has no bias: nothing is tightened there. Δt is rounded down to a readable value ([`readable_step`], delays whole steps) and
//! the duration up to two significant digits ([`readable_duration`]).

use crate::error::Result;
use crate::response::analyze_output;
use crate::scenario::Scenario;
use crate::simulate::{
    planned_variances, readable_duration, readable_step, suggest_step, PlannedVariance, RunInput, RunOptions,
    StepSuggestion,
};

/// Largest relative discretisation bias |σ_d/σ − 1| of a weighted output's σ (its a_w) that a suggested
/// step and duration leave however wide the interval (few realizations): 10⁻³, a verdict value.
pub const BIAS_TARGET: f64 = 1e-3;

/// The same for the other simulated outputs: 10⁻². With many realizations the target is the smaller
/// [`BIAS_OF_HALF_WIDTH`] of the interval's predicted half-width.
pub const OTHER_BIAS_TARGET: f64 = 1e-2;

/// Fraction of an interval's predicted half-width the discretisation bias of σ may take: 1/4. A bias of b
/// half-widths shifts a 95 % interval by 1.96·b standard errors; at b = 1/4 it still covers with probability
/// Φ(1.96 − 0.49) − Φ(−1.96 − 0.49) = 0.922.
pub const BIAS_OF_HALF_WIDTH: f64 = 0.25;

/// Most steps per realization a suggestion may reach while lowering the bias.
pub const MAX_STEPS: f64 = (1u64 << 18) as f64;

impl Scenario {
    /// Δt and duration for a Monte Carlo run of this scenario (see the module docs), with the reasons.
    ///
    /// # Errors
    /// Those of [`suggest_step`] (no decay rate: give the step), of building the verdict system, and of
    /// planning the run.
    ///
    /// # Examples
    /// ```
    /// use stochvib::scenario::load_scenario;
    /// use std::path::Path;
    /// let sc = load_scenario(Path::new("data/operator-seat-verdicts.toml"), Path::new("spectra")).unwrap();
    /// let s = sc.suggest_step(200).unwrap();
    /// assert!(s.dt_s <= 0.01 && s.reason.contains("Δt ≤ 1/("));
    /// ```
    pub fn suggest_step(&self, realizations: usize) -> Result<StepSuggestion> {
        // the model's poles, input band and delays (the weighting filters' poles at their upper edge are not
        // resolved in time: their effect is in the weighted output's peaks and in the bias, below)
        let base = suggest_step(&self.run_input())?;
        self.with_simulated_input(|input| {
            let mut s = base;
            let (limit, why) = resolution_limits(input);
            if limit < s.dt_s {
                let (dt, how) = readable_step(limit, &delays(input));
                s.reason = format!("{}; {why}{how}", s.reason);
                s.dt_s = dt;
                s.duration_s = s.duration_s.max(64.0 * dt);
            }
            lower_bias(input, &mut s, realizations)?;
            Ok(s)
        })
        // the planned runs refuse what the run would (a kurtosis beyond the grid): name the file's key
        .map_err(|e| self.name_run_error(e))
    }
}

/// The relative delays of the inputs, s.
fn delays(input: &RunInput) -> Vec<f64> {
    use crate::response::Excitation;
    match input.excitation {
        Excitation::Track { delays, .. } => delays.clone(),
        Excitation::Sources { inputs, .. } => inputs.iter().map(|m| m.delay).collect(),
        Excitation::Independent { .. } => Vec::new(),
    }
}

/// The smallest Δt that the weighted outputs, the fatigue stress and the band table ask for, with why.
fn resolution_limits(input: &RunInput) -> (f64, String) {
    let mut best = (f64::INFINITY, String::new());
    let mut take = |dt: f64, why: String| {
        if dt.is_finite() && dt > 0.0 && dt < best.0 {
            best = (dt, why);
        }
    };
    let names: Vec<&str> = input.system.outputs().iter().map(|o| o.name.as_str()).collect();
    for c in &input.verdicts.comfort {
        let Some(i) = names.iter().position(|n| *n == c.output) else {
            continue;
        };
        if let Ok(st) = analyze_output(input.system, input.excitation, i)
            && let Some(nu) = st.zero_upcrossing_rate
        {
            take(
                1.0 / (16.0 * nu),
                format!("Δt ≤ 1/(16 ν0+) with ν0+ = {nu:.4e} /s of `{}` (its peaks)", c.output),
            );
        }
    }
    for c in &input.verdicts.fatigue {
        if let Some(m) = &c.moments {
            let nu = m.nu_peak();
            take(
                1.0 / (32.0 * nu),
                format!(
                    "Δt ≤ 1/(32 ν_p) with the rate of peaks ν_p = {nu:.4e} /s of the stress `{}`",
                    c.output
                ),
            );
        }
    }
    if let Some((_, hi)) = input.bands.and_then(|b| b.range_hz) {
        take(
            1.0 / (2.5 * hi * 10f64.powf(0.15)),
            format!(
                "Δt ≤ 1/(2.5·f_top) with the band table's top edge f_top = {:.4e} Hz",
                hi * 10f64.powf(0.15)
            ),
        );
    }
    best
}

/// The bias target of one simulated output of a run of `realizations`: [`BIAS_OF_HALF_WIDTH`] of the
/// predicted relative half-width z·cv/(2√R) of its σ interval (z = 1.96, cv of one realization's mean square,
/// [`PlannedVariance::mean_square_cv`]), at most [`BIAS_TARGET`] for a weighted output (its a_w) and
/// [`OTHER_BIAS_TARGET`] for the others.
fn bias_target(v: &PlannedVariance, weighted: bool, realizations: usize) -> f64 {
    let cap = if weighted { BIAS_TARGET } else { OTHER_BIAS_TARGET };
    match v.mean_square_cv {
        Some(cv) if cv > 0.0 => cap.min(BIAS_OF_HALF_WIDTH * 1.96 * cv / (2.0 * (realizations as f64).sqrt())),
        _ => cap,
    }
}

/// An output over its bias target: (name, σ_d/σ − 1, target).
type OverTarget = (String, f64, f64);

/// The outputs of a run with Δt `dt` and duration `duration` whose |σ_d/σ − 1| exceeds its target
/// ([`bias_target`]), as (name, bias, target), and the excess E = Σ ln(|bias|/target) over them (0 when every
/// bias is within its target): the number of e-fold reductions of the bias still missing.
fn bias_excess(input: &RunInput, dt: f64, duration: f64, realizations: usize) -> Result<(f64, Vec<OverTarget>)> {
    let r = realizations.max(2);
    let opts = RunOptions {
        realizations: r,
        duration_s: duration,
        dt_s: dt,
        seed: 1,
        ..RunOptions::default()
    };
    let weighted = |name: &str| input.verdicts.comfort.iter().any(|c| c.output == name);
    let over: Vec<OverTarget> = planned_variances(input, &opts)?
        .into_iter()
        .filter(|v| v.analytic > 0.0)
        .map(|v| {
            let target = bias_target(&v, weighted(&v.name), r);
            (v.bias(), target, v.name)
        })
        .filter(|(b, t, _)| b.abs() > *t)
        .map(|(b, t, name)| (name, b, t))
        .collect();
    // + 0.0: an empty sum is −0.0, printed "-0.00"
    let excess: f64 = over.iter().map(|(_, b, t)| (b.abs() / t).ln()).sum::<f64>() + 0.0;
    Ok((excess, over))
}

/// Least decrease of the excess (`bias_excess`) that a doubling of the run's cost must buy: 0.5. Halving
/// Δt cuts a first-order-hold bias (∝ Δt²) by ln 4 = 1.39 per output; doubling the record cuts a band edge's
/// grid bias (∝ 1/T) by ln 2 while the narrower interval tightens its target by ln √2 — a net 0.35 that
/// oscillates with where the edge falls on the grid, which is not worth chasing.
pub const MIN_EXCESS_GAIN: f64 = 0.5;

/// Runs up to this many steps are cheap: a candidate that lowers the excess at all is taken (2¹⁵, the most
/// steps of the model's own suggestion).
pub const CHEAP_STEPS: f64 = (1u64 << 15) as f64;

/// Halves Δt or doubles the duration, whichever lowers the excess ([`bias_excess`]) more, while that lowers it
/// by at least [`MIN_EXCESS_GAIN`] (or to 0, or at all within [`CHEAP_STEPS`]) and the run stays within
/// [`MAX_STEPS`] steps; says what it did and which outputs stay over their target in the reason.
fn lower_bias(input: &RunInput, s: &mut StepSuggestion, realizations: usize) -> Result<()> {
    let d = delays(input);
    let (excess, over) = bias_excess(input, s.dt_s, s.duration_s, realizations)?;
    let start = excess;
    let mut cur = Candidate {
        dt: s.dt_s,
        duration: s.duration_s,
        excess,
        over,
    };
    while cur.excess > 0.0 {
        let Some(next) = next_step(input, &cur, &d, realizations) else {
            break;
        };
        cur = next;
    }
    if cur.excess == 0.0 && cur.dt < s.dt_s {
        cur = relaxed(input, cur, &d, realizations, s.dt_s);
    }
    (s.dt_s, s.duration_s) = (cur.dt, cur.duration);
    if start > 0.0 {
        s.reason.push_str(&format!(
            "; discretisation bias (target 1/4 of each σ interval's predicted half-width, at most \
             {BIAS_TARGET:.0e} for a_w, {OTHER_BIAS_TARGET:.0e} otherwise): excess Σ ln(|bias|/target) {start:.2} → \
             {:.2}{}",
            cur.excess,
            over_text(&cur.over)
        ));
    }
    Ok(())
}

/// A step and duration with the excess of its biases and the outputs over their target ([`bias_excess`]).
struct Candidate {
    dt: f64,
    duration: f64,
    excess: f64,
    over: Vec<OverTarget>,
}

impl Candidate {
    fn of(input: &RunInput, dt: f64, duration: f64, realizations: usize) -> Option<Candidate> {
        let (excess, over) = bias_excess(input, dt, duration, realizations).ok()?;
        Some(Candidate {
            dt,
            duration,
            excess,
            over,
        })
    }
}

/// The better of halving Δt and doubling the duration (within [`MAX_STEPS`]) when it is worth its cost: it
/// brings the excess to 0, or lowers it by [`MIN_EXCESS_GAIN`], or lowers it at all within [`CHEAP_STEPS`].
fn next_step(input: &RunInput, cur: &Candidate, delays: &[f64], realizations: usize) -> Option<Candidate> {
    let finer = readable_step(0.5 * cur.dt, delays).0;
    let longer = readable_duration(2.0 * cur.duration);
    let try_one = |dt: f64, t: f64| {
        (t / dt <= MAX_STEPS)
            .then(|| Candidate::of(input, dt, t, realizations))
            .flatten()
    };
    // the two plans in parallel (each is one thread's work)
    let (a, b) = rayon::join(|| try_one(finer, cur.duration), || try_one(cur.dt, longer));
    let best = [a, b]
        .into_iter()
        .flatten()
        .min_by(|a, b| a.excess.total_cmp(&b.excess))?;
    let worth = best.excess == 0.0
        || best.excess <= cur.excess - MIN_EXCESS_GAIN
        || (best.excess < cur.excess && best.duration / best.dt <= CHEAP_STEPS);
    worth.then_some(best)
}

/// After halvings that brought every bias within its target: the largest readable Δt up to twice the final
/// one (and at most `dt_max`, where the halvings started) that still does (a halving overshoots by up to 4×
/// in a bias ∝ Δt²).
fn relaxed(input: &RunInput, cur: Candidate, delays: &[f64], realizations: usize, dt_max: f64) -> Candidate {
    for f in [1.9, 1.5, 1.25] {
        let dt = readable_step((f * cur.dt).min(dt_max), delays).0;
        if dt > cur.dt
            && let Some(c) = Candidate::of(input, dt, cur.duration, realizations)
            && c.excess == 0.0
        {
            return c;
        }
    }
    cur
}

/// `; still over target (not worth a longer run): body σ_d/σ − 1 = −0.97 % (target 0.21 %)`.
fn over_text(over: &[OverTarget]) -> String {
    if over.is_empty() {
        return String::new();
    }
    let list: Vec<String> = over
        .iter()
        .map(|(n, b, t)| format!("`{n}` σ_d/σ − 1 = {:+.3} % (target {:.3} %)", 100.0 * b, 100.0 * t))
        .collect();
    format!(
        "; still over its target (a finer Δt or a longer record would not lower it enough for its cost: the run \
         says when an interval misses because of it): {}",
        list.join(", ")
    )
}
