//! What `stochvib analyze` reports of a scenario with nonlinear elements, as computed: route 1 (statistical
//! linearization, labelled an approximation everywhere), route 3 (the exact density, where it applies) and,
//! with `--monte-carlo N`, route 2 beside them with the relative difference and a verdict wherever route 1
//! lies outside the Monte Carlo interval; [`crate::report::nonlinear_report`] prints it.

use super::NonlinearAnswers;
use crate::comfort::{weighted_output, Weighting};
use crate::error::Result;
use crate::estimate::Interval;
use crate::nonlinear::monte_carlo::{reference_table, NonlinearRunSummary};
use crate::nonlinear::{output_variance, Route1Outcome};
use crate::scenario::Scenario;
use crate::system::FrequencyResponse;
use serde::Serialize;

/// Route 1 fails to reproduce route 2 by more than this factor on a rate: the report says so loudly.
pub const RATE_FACTOR_ALARM: f64 = 2.0;

/// One element under route 1.
#[derive(Debug, Clone, Serialize)]
pub struct ElementRow {
    /// Name.
    pub name: String,
    /// Kind and parameters.
    pub description: String,
    /// F₀, k_eq, c_eq of its remainder (route 1).
    pub equivalent: Option<crate::nonlinear::Equivalent>,
    /// μ_x, σ_x, σ_v (route 1).
    pub moments: Option<crate::nonlinear::ElementMoments>,
}

/// One statistic of an output: route 1, route 3 and route 2.
#[derive(Debug, Clone, Serialize)]
pub struct CompareRow {
    /// The run's statistic name (`sigma_response`, `upcrossing_rate[0.08 m]`, `contact_fraction[stops]`, …).
    pub statistic: String,
    /// Unit.
    pub unit: String,
    /// Route 1 (Gaussian equivalent: an approximation).
    pub route1: Option<f64>,
    /// Route 3 (exact), where it applies.
    pub exact: Option<f64>,
    /// Route 2's estimate and interval (with `--monte-carlo`).
    pub monte_carlo: Option<Interval>,
    /// route 1 / route 2 − 1.
    pub route1_rel_diff: Option<f64>,
    /// Whether route 1 lies inside route 2's interval.
    pub route1_covered: Option<bool>,
}

/// One output's section.
#[derive(Debug, Clone, Serialize)]
pub struct NonlinearOutput {
    /// Output name.
    pub name: String,
    /// Unit.
    pub unit: String,
    /// Route 1's variance by every method of the equivalent linear system (method, value, relative
    /// difference to the reference).
    pub route1_methods: Vec<(String, Option<f64>, Option<f64>)>,
    /// Route 1's ISO 2631-1 weighted r.m.s. a_w (W_k) of an acceleration output, m/s².
    pub route1_a_w: Option<f64>,
    /// Route 1's zero up-crossing rate ν₀⁺, 1/s.
    pub route1_nu0: Option<f64>,
    /// The statistics compared.
    pub rows: Vec<CompareRow>,
    /// Route 2's Δt-halving differences of the mean and σ (with `--monte-carlo`).
    pub dt_halving: Vec<(String, Interval)>,
}

/// The whole report.
#[derive(Debug, Clone, Serialize)]
pub struct NonlinearReport {
    /// Scenario title.
    pub title: String,
    /// Scenario file.
    pub scenario: String,
    /// Model description.
    pub model: String,
    /// Input description.
    pub input: String,
    /// Route 1: converged (iterations, variance method) or why not and what to change.
    pub route1: String,
    /// Whether route 1 converged.
    pub route1_converged: bool,
    /// Route 3: applies, or why not.
    pub route3: String,
    /// The elements.
    pub elements: Vec<ElementRow>,
    /// The outputs.
    pub outputs: Vec<NonlinearOutput>,
    /// The outputs without statistics (route 2 would not simulate them), each with the reason.
    pub skipped: Vec<crate::simulate::SkippedOutput>,
    /// Route 2: realizations, route, step, burn-in and notes (with `--monte-carlo`).
    pub monte_carlo: Option<String>,
    /// Verdicts: route 1 outside route 2's interval, said loudly.
    pub verdicts: Vec<String>,
}

/// The report of a nonlinear scenario with its `answers` (routes 1 and 3) and, if run, route 2.
///
/// # Errors
/// Route 3's quadratures; an excitation that does not fit the model.
pub fn nonlinear_report(
    sc: &Scenario,
    answers: &NonlinearAnswers,
    mc: Option<&NonlinearRunSummary>,
) -> Result<NonlinearReport> {
    report_of(sc, answers, mc).map_err(|e| sc.name_model_error(e))
}

/// The report of a nonlinear scenario whose route 2 found no stationary response (its realizations escaped:
/// `reason`, from [`crate::nonlinear::monte_carlo::escaped`]): routes 1 and 3 as [`nonlinear_report()`]
/// gives them, route 2 as the outcome "no stationary response" with its reason, and a verdict that says
/// what it means for route 1's statistics, said loudly (a converged Gaussian equivalent describes a
/// stationary response the nonlinear system does not have).
///
/// # Errors
/// As [`nonlinear_report()`].
pub fn nonlinear_report_escaped(sc: &Scenario, answers: &NonlinearAnswers, reason: &str) -> Result<NonlinearReport> {
    let mut r = nonlinear_report(sc, answers, None)?;
    r.monte_carlo = Some(format!("NO STATIONARY RESPONSE: {reason}"));
    r.verdicts.push(if r.route1_converged {
        "route 2's response escaped: route 1's Gaussian statistics describe a stationary response that the \
         nonlinear system does not have here; do not use them as its statistics"
            .into()
    } else {
        "route 2's response escaped, and route 1 found no Gaussian equivalent: no stationary statistics exist at \
         this excitation level"
            .into()
    });
    Ok(r)
}

fn report_of(sc: &Scenario, answers: &NonlinearAnswers, mc: Option<&NonlinearRunSummary>) -> Result<NonlinearReport> {
    let model = sc.nonlinear_model().expect("a nonlinear scenario");
    let input = sc.nonlinear_run_input(answers);
    // the static equilibrium and output plan of the model's linear part: a fault is the model's, name it
    let (refs, skipped) = reference_table(&input)?;
    let r1 = answers.route1.converged();
    let route1 = match &answers.route1 {
        Route1Outcome::Converged(r) => format!(
            "converged in {} iterations (variances by {}); an APPROXIMATION: Gaussian closure of a non-Gaussian response",
            r.iterations, r.method
        ),
        Route1Outcome::NotConverged { reason, advice, iterations } => {
            format!("NOT CONVERGED after {iterations} iterations: {reason}; {advice}")
        }
    };
    let route3 = match &answers.route3 {
        Ok(_) => "applies: exact stationary Fokker–Planck density (one degree of freedom, linear damping, white noise)"
            .into(),
        Err(why) => format!("not applicable: {why}"),
    };
    let elements = model
        .elements()
        .iter()
        .enumerate()
        .map(|(e, el)| ElementRow {
            name: el.name.clone(),
            description: el.law.describe(),
            equivalent: r1.map(|r| r.coefficients[e]),
            moments: r1.map(|r| r.moments[e]),
        })
        .collect();
    let mut verdicts = Vec::new();
    let outputs = refs
        .iter()
        .map(|o| output_section(sc, answers, o, mc, &mut verdicts))
        .collect::<Result<Vec<_>>>()?;
    if mc.is_some() && verdicts.is_empty() && r1.is_some() {
        verdicts.push("route 1 lies inside every Monte Carlo interval".into());
    }
    Ok(NonlinearReport {
        title: sc.title.clone(),
        scenario: sc.path.display().to_string(),
        model: sc.model.description.clone(),
        input: crate::study::analysis::input_description(sc),
        route1_converged: r1.is_some(),
        route1,
        route3,
        elements,
        outputs,
        skipped,
        monte_carlo: mc.map(|m| {
            format!(
                "{} realizations, {} route, Δt = {} s, burn-in {:.4} s, {} samples each; {}",
                m.run.n_realizations,
                m.run.route.name(),
                m.run.dt_s,
                m.burn_in_s,
                m.run.n_samples,
                m.run.notes.join("; ")
            )
        }),
        verdicts,
    })
}

fn output_section(
    sc: &Scenario,
    answers: &NonlinearAnswers,
    o: &crate::nonlinear::monte_carlo::OutputReferences,
    mc: Option<&NonlinearRunSummary>,
    verdicts: &mut Vec<String>,
) -> Result<NonlinearOutput> {
    let idx = sc.model.system.output_index(&o.output)?;
    let st1 = answers.route1_statistics.as_ref().map(|s| &s[idx]);
    let stored = mc.and_then(|m| m.run.outputs.iter().find(|x| x.output == o.output));
    let rows: Vec<CompareRow> = o
        .rows
        .iter()
        .map(|(name, unit, route1, exact)| {
            let iv = stored.and_then(|s| s.get(name)).map(|s| s.interval);
            let covered = iv.zip(*route1).map(|(iv, a)| iv.covers(a));
            let rel = iv
                .zip(*route1)
                .and_then(|(iv, a)| (iv.estimate != 0.0 && a != 0.0).then(|| a / iv.estimate - 1.0));
            if covered == Some(false) {
                verdicts.push(verdict(
                    &o.output,
                    name,
                    route1.unwrap_or(f64::NAN),
                    iv.expect("an interval"),
                ));
            }
            CompareRow {
                statistic: name.clone(),
                unit: unit.clone(),
                route1: *route1,
                exact: *exact,
                monte_carlo: iv,
                route1_rel_diff: rel,
                route1_covered: covered,
            }
        })
        .collect();
    let dt_halving = stored
        .map(|s| {
            s.statistics
                .iter()
                .filter(|x| x.name.starts_with("dt_halving"))
                .map(|x| (x.name.clone(), x.interval))
                .collect()
        })
        .unwrap_or_default();
    let route1_a_w = match (answers.route1.converged(), o.unit.as_str()) {
        (Some(r), "m/s^2") => r
            .equivalent
            .state_space()
            .and_then(|ss| weighted_output(ss, idx, &Weighting::Wk).ok())
            .and_then(|w| output_variance(&w, &sc.excitation, 0, &sc.analysis.effort).ok())
            .map(|(v, _)| v.sqrt()),
        _ => None,
    };
    Ok(NonlinearOutput {
        name: o.output.clone(),
        unit: o.unit.clone(),
        route1_methods: st1
            .map(|s| {
                s.methods
                    .iter()
                    .map(|m| (m.method.name().to_string(), m.value(), m.rel_diff))
                    .collect()
            })
            .unwrap_or_default(),
        route1_a_w,
        route1_nu0: st1.and_then(|s| s.zero_upcrossing_rate),
        rows,
        dt_halving,
    })
}

/// The loud line for route 1 outside route 2's interval.
fn verdict(output: &str, statistic: &str, route1: f64, iv: Interval) -> String {
    let ratio = route1 / iv.estimate;
    let rate = statistic.contains("rate") || statistic.contains("fraction");
    let factor = if ratio > 0.0 {
        ratio.max(1.0 / ratio)
    } else {
        f64::INFINITY
    };
    let why = if rate && factor >= RATE_FACTOR_ALARM {
        format!(
            " — off by a factor {factor:.3e}: the Gaussian closure misses the non-Gaussian tail (beyond a stiff \
             contact, by orders of magnitude); trust route 2 (or route 3) for contact and crossing rates"
        )
    } else {
        String::new()
    };
    format!(
        "ROUTE 1 OUTSIDE THE MONTE CARLO INTERVAL: {output} {statistic}: route 1 {route1:.4e}, Monte Carlo {:.4e} \
         [{:.4e}, {:.4e}] (route 1 / MC = {ratio:.4}){why}",
        iv.estimate, iv.lower, iv.upper
    )
}
