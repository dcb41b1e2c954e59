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
//! discretisation bias of every σ:          |σ_d/σ − 1| ≤ 10⁻³ (a_w), 10⁻² (others)   σ_d: exact σ of the run's process
//! ```
//! A sampled peak of a cycle at frequency f is missed by at most 1 − cos(πfΔt) of its height: 1.9 % at
//! fΔt = 1/16 (0.6 % on average over the phase) and 0.5 % at 1/32 (a damage rate ∝ S^k with k ≈ 3…5 then
//! errs by well under the few per cent of its Monte Carlo interval). The bias σ_d/σ − 1 is exact
//! ([`planned_variances`]: 0 on the exact route; the FFT grid and the first-order hold on the spectral route);
//! while it exceeds the target, Δt is halved or the duration doubled — whichever lowers it more — up to
//! [`MAX_STEPS`] steps. Δt is rounded down to a readable value ([`readable_step`], delays whole steps) and
//! the duration up to two significant digits ([`readable_duration`]).

use super::Scenario;
use crate::error::Result;
use crate::response::analyze_output;
use crate::simulate::{
    planned_variances, readable_duration, readable_step, suggest_step, RunInput, RunOptions, StepSuggestion,
};

/// Largest relative discretisation bias |σ_d/σ − 1| of a weighted output's σ (its a_w) that a suggested
/// step and duration leave: 10⁻³, a third to a tenth of the half-width of a 95 % interval of σ from a few
/// hundred realizations (about 2·√(2/N_eff)/√R with N_eff the record's independent samples), so that the
/// interval covers the analytic a_w as often as its confidence says.
pub const BIAS_TARGET: f64 = 1e-3;

/// The same for the other simulated outputs: 10⁻². Low-frequency outputs (a body's displacement on a road
/// whose band starts at 0.011 cycles/m) carry few independent samples per record, so their intervals are
/// wide (±1–2 % at 95 % for 200 records), while their grid bias falls only as the record grows.
pub const OTHER_BIAS_TARGET: f64 = 1e-2;

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

/// The largest |σ_d/σ − 1|/target over the simulated outputs of a run with Δt `dt` and duration `duration`
/// (target [`BIAS_TARGET`] for a weighted output, [`OTHER_BIAS_TARGET`] for the others): at most 1 when
/// every bias is within its target.
fn max_bias(input: &RunInput, dt: f64, duration: f64, realizations: usize) -> Result<f64> {
    let opts = RunOptions::new(realizations.max(2), duration, dt, 1);
    let weighted = |name: &str| input.verdicts.comfort.iter().any(|c| c.output == name);
    Ok(planned_variances(input, &opts)?
        .iter()
        .filter(|(_, a, _)| *a > 0.0)
        .map(|(name, a, d)| {
            let target = if weighted(name) { BIAS_TARGET } else { OTHER_BIAS_TARGET };
            ((d / a).sqrt() - 1.0).abs() / target
        })
        .fold(0.0, f64::max))
}

/// Halves Δt or doubles the duration, whichever lowers the bias more, until every bias is within its target
/// or the run would exceed [`MAX_STEPS`] steps; says what it did in the reason.
fn lower_bias(input: &RunInput, s: &mut StepSuggestion, realizations: usize) -> Result<()> {
    let d = delays(input);
    let mut bias = max_bias(input, s.dt_s, s.duration_s, realizations)?;
    let start = bias;
    while bias > 1.0 {
        let finer = readable_step(0.5 * s.dt_s, &d).0;
        let longer = readable_duration(2.0 * s.duration_s);
        let mut options = Vec::new();
        if s.duration_s / finer <= MAX_STEPS {
            options.push((finer, s.duration_s));
        }
        if longer / s.dt_s <= MAX_STEPS {
            options.push((s.dt_s, longer));
        }
        let mut best: Option<(f64, f64, f64)> = None;
        for (dt, t) in options {
            if let Ok(b) = max_bias(input, dt, t, realizations)
                && best.is_none_or(|x| b < x.2)
            {
                best = Some((dt, t, b));
            }
        }
        let Some((dt, t, b)) = best.filter(|x| x.2 < bias) else {
            break;
        };
        (s.dt_s, s.duration_s, bias) = (dt, t, b);
    }
    if start > 0.0 {
        s.reason.push_str(&format!(
            "; discretisation bias, largest |σ_d/σ − 1| in units of its target ({BIAS_TARGET:.0e} for a_w, \
             {OTHER_BIAS_TARGET:.0e} otherwise): {start:.2} → {bias:.2}{}",
            if bias > 1.0 {
                format!(": NOT reached within {MAX_STEPS} steps")
            } else {
                String::new()
            }
        ));
    }
    Ok(())
}
