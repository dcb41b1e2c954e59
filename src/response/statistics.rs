//! Per-output statistics: mean, the variance by every applicable method with their agreement, 3σ bounds,
//! spectral moments, Rice crossing rates, exceedance probabilities and expected peaks. Every quantity that
//! has no value says why ([`Outcome`]): infinite, not converged, not applicable, or unreliable.

use super::delayed::variance_lyapunov_delayed;
use super::delayed_quadrature::moments_oscillatory;
use super::outcome::Outcome;
use super::variance::{spectral_moment_quadrature_with, variance_integral_table, variance_lyapunov, LyapunovMoments};
use super::Excitation;
use crate::error::{Error, Result};
use crate::quad::QuadResult;
use crate::quad_oscillatory::OscillatoryOptions;
use crate::system::FrequencyResponse;
use serde::Serialize;
use std::f64::consts::PI;

/// Largest relative difference between the integral table and an exact Lyapunov route before the table's
/// value is reported as unreliable (both are exact in exact arithmetic; the table's Hurwitz elimination is
/// the less well-conditioned of the two).
pub const TABLE_AGREEMENT: f64 = 1e-8;

/// A variance method.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum VarianceMethod {
    /// Lyapunov equation of the system augmented with the input shaping filters (exact; delay-free inputs).
    Lyapunov,
    /// Covariance of the augmented system at the lags between delayed inputs (exact; rational inputs).
    #[serde(rename = "lyapunov (delays)")]
    LyapunovDelays,
    /// Closed-form integral table I_n (exact).
    IntegralTable,
    /// Adaptive Gauss–Kronrod quadrature of S_y, with Fourier-weighted tails for delayed inputs (any
    /// input; with an error estimate).
    Quadrature,
}

impl VarianceMethod {
    /// The name printed in reports.
    pub fn name(self) -> &'static str {
        match self {
            VarianceMethod::Lyapunov => "lyapunov",
            VarianceMethod::LyapunovDelays => "lyapunov (delays)",
            VarianceMethod::IntegralTable => "integral-table",
            VarianceMethod::Quadrature => "quadrature",
        }
    }
}

/// One method's answer for the variance.
#[derive(Debug, Clone, Serialize)]
pub struct VarianceValue {
    /// The method.
    pub method: VarianceMethod,
    /// Its outcome.
    pub outcome: Outcome,
    /// Relative difference to the reference variance.
    pub rel_diff: Option<f64>,
}

impl VarianceValue {
    /// The method's value, when it has a usable one.
    pub fn value(&self) -> Option<f64> {
        self.outcome.value()
    }
}

/// The statistics of one output of one system under one excitation: M_y, D_y, λ₂ and the method that
/// gave D_y. The one statistics type from `response` to the parameter-study table and its files:
/// [`ExactEvaluator`](super::ExactEvaluator) computes it by one exact route per point (four words, no heap,
/// for 10⁶ points), [`analyze_output`] as the reference values of a full analysis
/// ([`ResponseStatistics::values`]), the sweep table's rows hold it and write its columns (σ, 3σ bounds,
/// ν₀⁺ are derived from it here).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct PointStatistics {
    /// M_y = H(0)·M_u (None when the static gain is infinite).
    pub mean: Option<f64>,
    /// D_y (None when it is infinite: see [`ExactEvaluator::evaluate`](super::ExactEvaluator::evaluate)'s
    /// notes, or has no value).
    pub variance: Option<f64>,
    /// λ₂ = ∫ω² S_y dω = Var(ẏ) (None when infinite or not computed).
    pub lambda2: Option<f64>,
    /// The route that computed the variance (for an analysis without a variance value: the method whose
    /// outcome says why).
    pub method: VarianceMethod,
}

impl PointStatistics {
    /// σ_y = √D_y.
    pub fn sigma(&self) -> Option<f64> {
        self.variance.map(f64::sqrt)
    }

    /// The bounds M_y ± kσ_y (k = 3: two-sided probability 0.9973 for a Gaussian output).
    pub fn bounds(&self, k: f64) -> Option<(f64, f64)> {
        let (m, s) = (self.mean?, self.sigma()?);
        Some((m - k * s, m + k * s))
    }

    /// Rice's zero (mean-level) up-crossing rate ν₀⁺ = (1/2π)√(λ₂/λ₀), 1/s (per metre for a spatial
    /// system); none without both moments or for λ₀ = 0.
    pub fn zero_upcrossing_rate(&self) -> Option<f64> {
        match (self.variance, self.lambda2) {
            (Some(l0), Some(l2)) if l0 > 0.0 => Some((l2 / l0).sqrt() / (2.0 * PI)),
            _ => None,
        }
    }
}

/// The report of one analysis of one output: its statistics ([`PointStatistics`], which a
/// `ResponseStatistics` dereferences to: `st.mean`, `st.variance`, `st.lambda2`, `st.method`,
/// `st.bounds(3.0)`) with the evidence behind them — every variance method's outcome and their agreement,
/// why a value is missing, λ₄ and the bandwidth ε, the output's name and unit.
///
/// Its JSON (`stochvib analyze --json`) is flat, in the order of the fields below with `mean` first after
/// the unit and `variance`, `lambda2` at their places (the statistics' `method` is not written: `methods`
/// holds every method's outcome).
#[derive(Debug, Clone)]
pub struct ResponseStatistics {
    /// Output name.
    pub name: String,
    /// SI unit.
    pub unit: String,
    /// The statistics: mean M_y = H(0) M_u (None when the static gain is infinite), the reference variance
    /// (the first exact route with a value, else quadrature), λ₂ (the exact route where it applies, else
    /// quadrature) and the method of the reference variance.
    pub values: PointStatistics,
    /// Every method's variance.
    pub methods: Vec<VarianceValue>,
    /// Why the variance is what it is (a value, infinite, not converged, not available).
    pub variance_outcome: Outcome,
    /// σ_y.
    pub sigma: Option<f64>,
    /// How λ₂ came out.
    pub lambda2_outcome: Outcome,
    /// λ₄ = ∫ω⁴ S_y dω.
    pub lambda4: Option<f64>,
    /// How λ₄ came out.
    pub lambda4_outcome: Outcome,
    /// Zero (mean-level) up-crossing rate ν₀⁺ = (1/2π)√(λ₂/λ₀), per second (per metre for a spatial system).
    pub zero_upcrossing_rate: Option<f64>,
    /// Bandwidth parameter ε = √(1 − λ₂²/(λ₀λ₄)) (0 narrow-band, 1 broad-band).
    pub bandwidth: Option<f64>,
}

impl std::ops::Deref for ResponseStatistics {
    type Target = PointStatistics;
    fn deref(&self) -> &PointStatistics {
        &self.values
    }
}

/// The JSON layout of [`ResponseStatistics`]: its fields with the statistics' `mean`, `variance` and
/// `lambda2` at their places.
#[derive(Serialize)]
struct ResponseStatisticsJson<'a> {
    name: &'a str,
    unit: &'a str,
    mean: Option<f64>,
    methods: &'a [VarianceValue],
    variance: Option<f64>,
    variance_outcome: &'a Outcome,
    sigma: Option<f64>,
    lambda2: Option<f64>,
    lambda2_outcome: &'a Outcome,
    lambda4: Option<f64>,
    lambda4_outcome: &'a Outcome,
    zero_upcrossing_rate: Option<f64>,
    bandwidth: Option<f64>,
}

impl Serialize for ResponseStatistics {
    fn serialize<S: serde::Serializer>(&self, s: S) -> std::result::Result<S::Ok, S::Error> {
        ResponseStatisticsJson {
            name: &self.name,
            unit: &self.unit,
            mean: self.values.mean,
            methods: &self.methods,
            variance: self.values.variance,
            variance_outcome: &self.variance_outcome,
            sigma: self.sigma,
            lambda2: self.values.lambda2,
            lambda2_outcome: &self.lambda2_outcome,
            lambda4: self.lambda4,
            lambda4_outcome: &self.lambda4_outcome,
            zero_upcrossing_rate: self.zero_upcrossing_rate,
            bandwidth: self.bandwidth,
        }
        .serialize(s)
    }
}

/// Analyses output `i` of `sys` under `exc` by every applicable method, with the default quadrature effort.
///
/// # Errors
/// Only for a mismatch between the excitation and the system or an output index out of range; divergent,
/// unconverged or inapplicable methods are reported inside the statistics.
pub fn analyze_output(sys: &dyn FrequencyResponse, exc: &Excitation, i: usize) -> Result<ResponseStatistics> {
    analyze_output_with(sys, exc, i, &OscillatoryOptions::default())
}

fn quad_outcome(r: &Result<QuadResult>, effort: &OscillatoryOptions) -> Outcome {
    match r {
        Ok(q) => Outcome::Value {
            value: q.value,
            error_estimate: Some(q.abs_error),
        },
        Err(e) => Outcome::from_error(e, effort),
    }
}

fn moment_outcome(r: &Result<f64>, effort: &OscillatoryOptions) -> Outcome {
    Outcome::from_result(r, None, effort)
}

/// [`analyze_output`] with the tolerance and limits of `effort` for the quadratures.
///
/// # Formula
/// Delay-free inputs: Lyapunov, integral table and adaptive quadrature of S_y. Inputs that are delayed
/// copies of one process (wheels on a track): the exact covariance of the delayed augmented system
/// ("lyapunov (delays)", rational inputs) and the quadrature with Fourier-weighted tails
/// ([`moments_oscillatory`]); λ₂ and λ₄ come from the exact route where it applies, else from quadrature.
/// A divergence found by any method is the answer (never a finite number for it); the integral table is
/// reported unreliable where it disagrees with an exact Lyapunov route by more than [`TABLE_AGREEMENT`].
///
/// # Errors
/// As [`analyze_output`].
pub fn analyze_output_with(
    sys: &dyn FrequencyResponse,
    exc: &Excitation,
    i: usize,
    effort: &OscillatoryOptions,
) -> Result<ResponseStatistics> {
    super::variance::check_shapes(sys, exc, i)?;
    if let Some(ss) = sys.state_space() {
        ss.require_stable()
            .map_err(|e| Error::invalid("system/excitation", "", e.to_string()))?;
    }
    let info = sys.outputs()[i].clone();
    let delayed = !exc.delay_free();
    let (exact_method, exact) = exact_moments(sys, exc, i);
    let table = variance_integral_table(sys, exc, i, 0);
    // quadrature of the three moments (the plain rule, or Fourier-weighted tails for delays and sources)
    let (q0, q2, q4) = if delayed || matches!(exc, Excitation::Sources { .. }) {
        let m = moments_oscillatory(sys, exc, i, effort);
        (m.variance, m.lambda2, m.lambda4)
    } else {
        (
            spectral_moment_quadrature_with(sys, exc, i, 0, effort),
            spectral_moment_quadrature_with(sys, exc, i, 2, effort),
            spectral_moment_quadrature_with(sys, exc, i, 4, effort),
        )
    };
    let exact_outcome = match &exact {
        Ok(m) => Outcome::Value {
            value: m.variance,
            error_estimate: None,
        },
        Err(e) => Outcome::from_error(e, effort),
    };
    let methods = variance_methods(exc, (exact_method, exact_outcome), &table, &q0, effort);
    let (variance_outcome, method) = variance_answer(&methods, exact_method);
    let variance = variance_outcome.value();
    let mean = sys.static_gain().map(|g| {
        let mu = exc.means();
        (0..g.ncols()).map(|j| g[(i, j)] * mu[j]).sum::<f64>()
    });
    let (lambda2_outcome, lambda4_outcome) = higher_moments(&exact, (&q2, &q4), &variance_outcome, effort);
    let (lambda2, lambda4) = (lambda2_outcome.value(), lambda4_outcome.value());
    let values = PointStatistics {
        mean,
        variance,
        lambda2,
        method,
    };
    let bandwidth = match (variance, lambda2, lambda4) {
        (Some(l0), Some(l2), Some(l4)) if l0 > 0.0 && l4 > 0.0 => Some((1.0 - l2 * l2 / (l0 * l4)).max(0.0).sqrt()),
        _ => None,
    };
    Ok(ResponseStatistics {
        name: info.name,
        unit: info.unit,
        values,
        methods,
        variance_outcome,
        sigma: values.sigma(),
        lambda2_outcome,
        lambda4,
        lambda4_outcome,
        zero_upcrossing_rate: values.zero_upcrossing_rate(),
        bandwidth,
    })
}

/// The exact route of output `i` and its method: Lyapunov (delay-free), its delayed form, or for independent
/// sources the exact values of each source alone, summed.
fn exact_moments(sys: &dyn FrequencyResponse, exc: &Excitation, i: usize) -> (VarianceMethod, Result<LyapunovMoments>) {
    let delayed = !exc.delay_free();
    let method = if delayed {
        VarianceMethod::LyapunovDelays
    } else {
        VarianceMethod::Lyapunov
    };
    match exc {
        Excitation::Sources { sources, inputs } => (method, super::sources::variance_exact(sys, sources, inputs, i)),
        _ if delayed => (method, variance_lyapunov_delayed(sys, exc, i)),
        _ => (method, variance_lyapunov(sys, exc, i)),
    }
}

/// The variance of every method in report order — the plain Lyapunov route marked not applicable for
/// delayed inputs, the exact route (`exact`: method and outcome), the integral table (unreliable where it
/// disagrees with the exact value by more than [`TABLE_AGREEMENT`]), the quadrature — each with its
/// relative difference from the first value.
fn variance_methods(
    exc: &Excitation,
    (exact_method, exact_outcome): (VarianceMethod, Outcome),
    table: &Result<f64>,
    q0: &Result<QuadResult>,
    effort: &OscillatoryOptions,
) -> Vec<VarianceValue> {
    let mut methods = Vec::new();
    if !exc.delay_free() {
        methods.push(VarianceValue {
            method: VarianceMethod::Lyapunov,
            outcome: Outcome::NotApplicable {
                reason: format!("{}; see lyapunov (delays)", exc.inputs_described()),
            },
            rel_diff: None,
        });
    }
    let mut table_outcome = moment_outcome(table, effort);
    if let (Some(t), Some(x)) = (table_outcome.value(), exact_outcome.value()) {
        let d = crate::numbers::rel_diff(t, x);
        if d > TABLE_AGREEMENT {
            table_outcome = Outcome::Unreliable {
                value: t,
                reason: format!(
                    "differs from the Lyapunov value by {d:.1e} relative (both are exact in exact arithmetic; the \
                     table's Hurwitz elimination lost accuracy)"
                ),
            };
        }
    }
    methods.push(VarianceValue {
        method: exact_method,
        outcome: exact_outcome,
        rel_diff: None,
    });
    methods.push(VarianceValue {
        method: VarianceMethod::IntegralTable,
        outcome: table_outcome,
        rel_diff: None,
    });
    methods.push(VarianceValue {
        method: VarianceMethod::Quadrature,
        outcome: quad_outcome(q0, effort),
        rel_diff: None,
    });
    let reference = methods.iter().find_map(|m| m.value());
    for m in &mut methods {
        if let (Some(v), Some(r)) = (m.value(), reference) {
            m.rel_diff = Some(crate::numbers::rel_diff(v, r));
        }
    }
    methods
}

/// The outcomes of λ₂ and λ₄: the exact route's where it applies, else the quadratures `(q2, q4)`; a moment is
/// meaningful only with a finite variance, λ₄ only with λ₂.
fn higher_moments(
    exact: &Result<LyapunovMoments>,
    (q2, q4): (&Result<QuadResult>, &Result<QuadResult>),
    variance: &Outcome,
    effort: &OscillatoryOptions,
) -> (Outcome, Outcome) {
    let moment = |from_exact: Option<&Result<f64>>, quad: &Result<QuadResult>| -> Outcome {
        match from_exact {
            Some(r) => moment_outcome(r, effort),
            None => quad_outcome(quad, effort),
        }
    };
    let (l2o, l4o) = match exact {
        Ok(m) => (moment(Some(&m.lambda2), q2), moment(Some(&m.lambda4), q4)),
        Err(_) => (moment(None, q2), moment(None, q4)),
    };
    let not_without = |what: &str, o: Outcome, base: &Outcome| -> Outcome {
        if base.value().is_some() {
            o
        } else {
            Outcome::NotApplicable {
                reason: format!("{what} needs a finite {}", if what == "λ₄" { "λ₂" } else { "variance" }),
            }
        }
    };
    let lambda2 = not_without("λ₂", l2o, variance);
    let lambda4 = not_without("λ₄", l4o, &lambda2);
    (lambda2, lambda4)
}

/// The reference variance's outcome and method. A divergence found by any method is the answer (never a
/// finite number for it); else the first method with a value; with none, the quadrature (the last method)
/// says best why (not converged, not applicable), unless only the exact route did not converge.
fn variance_answer(methods: &[VarianceValue], exact_method: VarianceMethod) -> (Outcome, VarianceMethod) {
    if let Some(m) = methods.iter().find(|m| m.outcome.is_divergent()) {
        return (m.outcome.clone(), m.method);
    }
    if let Some((value, m)) = methods.iter().find_map(|m| Some((m.value()?, m.method))) {
        let outcome = Outcome::Value {
            value,
            error_estimate: None,
        };
        return (outcome, m);
    }
    let quadrature = &methods[methods.len() - 1];
    let exact = methods.iter().find(|m| m.method == exact_method).unwrap_or(quadrature);
    let why = [quadrature, exact]
        .into_iter()
        .find(|m| matches!(m.outcome, Outcome::NotConverged { .. }))
        .unwrap_or(quadrature);
    (why.outcome.clone(), why.method)
}

impl ResponseStatistics {
    /// Rice's rate of up-crossings of level `a`: ν_a⁺ = ν₀⁺ exp(−(a − M_y)²/(2σ_y²)).
    pub fn upcrossing_rate(&self, a: f64) -> Option<f64> {
        let (m, s, n0) = (self.mean?, self.sigma?, self.zero_upcrossing_rate?);
        Some(n0 * (-(a - m).powi(2) / (2.0 * s * s)).exp())
    }

    /// Probability that level `a` is up-crossed at least once in duration `t` (Poisson crossings):
    /// P = 1 − exp(−ν_a⁺ t).
    pub fn exceedance_probability(&self, a: f64, t: f64) -> Option<f64> {
        Some(-(-self.upcrossing_rate(a)? * t).exp_m1())
    }

    /// Expected largest value in duration `t` (Davenport):
    /// E\[max\] ≈ M_y + σ_y (√(2 ln ν₀⁺t) + γ/√(2 ln ν₀⁺t)), γ = 0.5772…, valid for ν₀⁺t ≫ 1.
    pub fn expected_largest_peak(&self, t: f64) -> Option<f64> {
        let n = self.zero_upcrossing_rate? * t;
        if n <= 1.0 {
            return None;
        }
        let r = (2.0 * n.ln()).sqrt();
        Some(self.mean? + self.sigma? * (r + 0.577_215_664_901_532_9 / r))
    }

    /// Why ν₀⁺ (and with it the level rates and the expected peak) is missing, if it is.
    pub fn rate_note(&self) -> Option<String> {
        if self.zero_upcrossing_rate.is_some() {
            return None;
        }
        Some(match (&self.variance_outcome, &self.lambda2_outcome) {
            (v, _) if v.value().is_none() => format!("variance {}", v.describe()),
            (_, l2) => format!("λ₂ {}", l2.describe()),
        })
    }
}
