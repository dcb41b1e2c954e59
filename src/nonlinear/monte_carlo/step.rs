//! Route 2's default time step and duration, derived from the system.

use super::{plan, NonlinearRunInput};
use crate::error::Result;
use crate::nonlinear::integrator::{CONTACT_STEP, FRICTION_STEP};
use crate::response::Excitation;
use crate::simulate::{suggest_step, RunInput, StepSuggestion};
use crate::system::Mdof;

/// Least record length of a default route-2 run, in burn-ins.
pub const RECORD_BURN_INS: f64 = 10.0;

/// A time step and duration for route 2, derived from the system:
/// * those of a linear run ([`suggest_step`]) of the Gaussian equivalent (route 1, else the linear part);
///   with an element that can stick (dry friction) also of the linear part, the shorter step and the longer
///   duration: while the element sticks or slips little the machine moves as its linear part, whose poles
///   are faster and whose slowest decay is slower than the equivalent's (friction's equivalent damping
///   hides both);
/// * Δt shortened to [`CONTACT_STEP`]/ω_c for the stiffest element (ω_c = √(κ k), k its largest stiffness
///   over route 1's response);
/// * Δt shortened so that dry friction changes the relative velocity by at most [`FRICTION_STEP`]·σ_v in a
///   step, κ F_c Δt ≤ FRICTION_STEP·σ_v (κ = dᵀM⁻¹d, σ_v route 1's σ of the element's velocity): the
///   splitting resolves each slip and the stick velocity is held to that fraction of σ_v;
/// * kept a whole fraction of the smallest input delay;
/// * the duration at least [`RECORD_BURN_INS`] burn-ins ([`BURN_IN_DECAY`](super::BURN_IN_DECAY)/σ_min of
///   the Gaussian equivalent, what every realization computes and discards before its record): the burn-in
///   then costs at most a tenth of the work, and every realization's time averages run over at least
///   10·BURN_IN_DECAY ≈ 140 decay times of its slowest mode.
///
/// # Errors
/// As [`suggest_step`] for the reference system.
pub fn suggest_nonlinear_step(input: &NonlinearRunInput) -> Result<StepSuggestion> {
    let mut s = linear_suggestion(input)?;
    if let Some(burn) = super::plan::default_burn_in(input) {
        let t = crate::simulate::readable_duration(RECORD_BURN_INS * burn);
        if t > s.duration_s {
            s.duration_s = t;
            s.reason.push_str(&format!(
                "; duration {RECORD_BURN_INS} burn-ins of {burn:.4} s (the burn-in at most a tenth of the work)"
            ));
        }
    }
    let moments = input.route1.map(|r| r.moments.as_slice());
    let mut bounds = Vec::new();
    let wc = plan::contact_frequency(input.model, moments);
    if wc > 0.0 {
        bounds.push((
            CONTACT_STEP / wc,
            format!("{CONTACT_STEP}/ω_c for the stiffest element (ω_c = {wc:.4e} rad/s)"),
        ));
    }
    bounds.extend(friction_steps(input));
    let shortest = bounds.into_iter().min_by(|a, b| a.0.total_cmp(&b.0));
    if let Some((dt, why)) = shortest.filter(|(dt, _)| *dt < s.dt_s) {
        let dt = whole_fraction_of_delays(dt, input.excitation);
        s.reason = format!("{}; Δt shortened to {dt:.4e} s = {why}", s.reason);
        s.dt_s = dt;
    }
    Ok(s)
}

/// [`suggest_step`] of the Gaussian equivalent, and with a sticking element also of the linear part.
fn linear_suggestion(input: &NonlinearRunInput) -> Result<StepSuggestion> {
    let lin = input.model.linear();
    let suggest = |sys: &Mdof| suggest_step(&RunInput::new(sys, input.excitation, input.outputs.clone(), vec![], ""));
    let Some(r) = input.route1 else {
        return suggest(lin);
    };
    let mut s = suggest(&r.equivalent)?;
    let sticks = input.model.elements().iter().any(|e| e.law.can_stick());
    if let (true, Ok(l)) = (sticks, suggest(lin)) {
        if l.dt_s < s.dt_s {
            s.dt_s = l.dt_s;
            s.reason = format!("{} (the linear part's, finer than the Gaussian equivalent's)", l.reason);
        }
        if l.duration_s > s.duration_s {
            s.duration_s = l.duration_s;
            s.reason
                .push_str("; duration of the linear part (dry friction: slower than the equivalent)");
        }
    }
    Ok(s)
}

/// κ F_c Δt ≤ FRICTION_STEP σ_v for every element with a sliding force, with route 1's σ_v.
fn friction_steps(input: &NonlinearRunInput) -> Vec<(f64, String)> {
    let (model, Some(r)) = (input.model, input.route1) else {
        return Vec::new();
    };
    model
        .elements()
        .iter()
        .enumerate()
        .filter_map(|(e, el)| {
            let rate = model.kappa(e) * el.law.sliding_force();
            let sv = r.moments[e].sigma_v;
            (rate > 0.0 && sv > 0.0).then(|| {
                (
                    FRICTION_STEP * sv / rate,
                    format!(
                        "{FRICTION_STEP}·σ_v/(κF_c) for the dry friction `{}` (σ_v = {sv:.4e} m/s, κF_c = {rate:.4e} m/s²)",
                        el.name
                    ),
                )
            })
        })
        .collect()
}

/// The largest step ≤ dt that is a whole fraction of the smallest difference of the input delays.
fn whole_fraction_of_delays(dt: f64, exc: &Excitation) -> f64 {
    let delays: Vec<f64> = match exc {
        Excitation::Track { delays, .. } => delays.clone(),
        Excitation::Sources { inputs, .. } => inputs.iter().map(|m| m.delay).collect(),
        Excitation::Independent { .. } => vec![],
    };
    let t0 = delays.iter().copied().fold(f64::INFINITY, f64::min);
    match delays.iter().map(|t| t - t0).filter(|t| *t > 0.0).reduce(f64::min) {
        Some(tau) => tau / (tau / dt).ceil(),
        None => dt,
    }
}
