//! Per-output statistics: mean, the variance by every applicable method with their agreement, 3σ bounds,
//! spectral moments, Rice crossing rates, exceedance probabilities and expected peaks.

use super::variance::{spectral_moment_quadrature, variance_integral_table, variance_lyapunov, variance_quadrature};
use super::Excitation;
use crate::error::{Error, Result};
use crate::system::FrequencyResponse;
use serde::Serialize;
use std::f64::consts::PI;

/// A variance method.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum VarianceMethod {
    /// Lyapunov equation of the system augmented with the input shaping filters (exact).
    Lyapunov,
    /// Closed-form integral table I_n (exact).
    IntegralTable,
    /// Adaptive Gauss–Kronrod quadrature of S_y (any input, delays; with an error estimate).
    Quadrature,
}

/// One method's answer for the variance.
#[derive(Debug, Clone, Serialize)]
pub struct VarianceValue {
    /// The method.
    pub method: VarianceMethod,
    /// Variance, when the method applies and the variance is finite.
    pub value: Option<f64>,
    /// Absolute error estimate (quadrature only).
    pub error_estimate: Option<f64>,
    /// Relative difference to the reference variance.
    pub rel_diff: Option<f64>,
    /// Why there is no value (not applicable, or divergent).
    pub note: Option<String>,
}

/// Statistics of one output.
#[derive(Debug, Clone, Serialize)]
pub struct ResponseStatistics {
    /// Output name.
    pub name: String,
    /// SI unit.
    pub unit: String,
    /// Mean M_y = H(0) M_u (None when the static gain is infinite).
    pub mean: Option<f64>,
    /// Every method's variance.
    pub methods: Vec<VarianceValue>,
    /// Reference variance (Lyapunov, else table, else quadrature).
    pub variance: Option<f64>,
    /// Why the variance is infinite or unavailable.
    pub variance_note: Option<String>,
    /// σ_y.
    pub sigma: Option<f64>,
    /// λ₂ = ∫ω² S_y dω (variance of the derivative).
    pub lambda2: Option<f64>,
    /// λ₄ = ∫ω⁴ S_y dω.
    pub lambda4: Option<f64>,
    /// Zero (mean-level) up-crossing rate ν₀⁺ = (1/2π)√(λ₂/λ₀), per second (per metre for a spatial system).
    pub zero_upcrossing_rate: Option<f64>,
    /// Bandwidth parameter ε = √(1 − λ₂²/(λ₀λ₄)) (0 narrow-band, 1 broad-band).
    pub bandwidth: Option<f64>,
}

/// Analyses output `i` of `sys` under `exc` by every applicable method.
///
/// # Errors
/// Only for a mismatch between the excitation and the system or an output index out of range; divergent
/// or inapplicable methods are reported inside the statistics.
pub fn analyze_output(sys: &dyn FrequencyResponse, exc: &Excitation, i: usize) -> Result<ResponseStatistics> {
    let quad = variance_quadrature(sys, exc, i);
    if let Err(e @ Error::InvalidParameter { .. }) = &quad {
        return Err(Error::invalid("system/excitation", "", e.to_string()));
    }
    let info = sys.outputs()[i].clone();
    let lyap = variance_lyapunov(sys, exc, i);
    let table = variance_integral_table(sys, exc, i, 0);
    let note = |e: &Error| Some(e.to_string());
    let mut methods = vec![
        VarianceValue {
            method: VarianceMethod::Lyapunov,
            value: lyap.as_ref().ok().map(|m| m.variance),
            error_estimate: None,
            rel_diff: None,
            note: lyap.as_ref().err().and_then(note),
        },
        VarianceValue {
            method: VarianceMethod::IntegralTable,
            value: table.as_ref().ok().copied(),
            error_estimate: None,
            rel_diff: None,
            note: table.as_ref().err().and_then(note),
        },
        VarianceValue {
            method: VarianceMethod::Quadrature,
            value: quad.as_ref().ok().map(|q| q.value),
            error_estimate: quad.as_ref().ok().map(|q| q.abs_error),
            rel_diff: None,
            note: quad.as_ref().err().and_then(note),
        },
    ];
    let reference = methods.iter().find_map(|m| m.value);
    for m in &mut methods {
        if let (Some(v), Some(r)) = (m.value, reference) {
            m.rel_diff = Some(crate::numbers::rel_diff(v, r));
        }
    }
    // A divergence found by any method is the answer: never report a finite number for it.
    let divergence = [&quad.as_ref().err(), &lyap.as_ref().err(), &table.as_ref().err()]
        .into_iter()
        .flatten()
        .find(|e| matches!(e, Error::Divergent { .. }))
        .map(|e| e.to_string());
    let (variance, variance_note) = match divergence {
        Some(d) => (None, Some(d)),
        None => (
            reference,
            if reference.is_none() {
                quad.as_ref().err().and_then(note)
            } else {
                None
            },
        ),
    };
    let mean = sys.static_gain().map(|g| {
        let mu = exc.means();
        (0..g.ncols()).map(|j| g[(i, j)] * mu[j]).sum::<f64>()
    });
    let (lambda2, lambda4) = match &lyap {
        Ok(m) => (m.lambda2.as_ref().ok().copied(), m.lambda4.as_ref().ok().copied()),
        Err(_) => (
            spectral_moment_quadrature(sys, exc, i, 2).ok().map(|q| q.value),
            spectral_moment_quadrature(sys, exc, i, 4).ok().map(|q| q.value),
        ),
    };
    let lambda2 = variance.and(lambda2);
    let lambda4 = lambda2.and(lambda4);
    let zero_upcrossing_rate = match (variance, lambda2) {
        (Some(l0), Some(l2)) if l0 > 0.0 => Some((l2 / l0).sqrt() / (2.0 * PI)),
        _ => None,
    };
    let bandwidth = match (variance, lambda2, lambda4) {
        (Some(l0), Some(l2), Some(l4)) if l0 > 0.0 && l4 > 0.0 => Some((1.0 - l2 * l2 / (l0 * l4)).max(0.0).sqrt()),
        _ => None,
    };
    Ok(ResponseStatistics {
        name: info.name,
        unit: info.unit,
        mean,
        methods,
        variance,
        variance_note,
        sigma: variance.map(f64::sqrt),
        lambda2,
        lambda4,
        zero_upcrossing_rate,
        bandwidth,
    })
}

impl ResponseStatistics {
    /// The bounds M_y ± kσ_y (k = 3: two-sided probability 0.9973 for a Gaussian output).
    pub fn bounds(&self, k: f64) -> Option<(f64, f64)> {
        Some((self.mean? - k * self.sigma?, self.mean? + k * self.sigma?))
    }

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
}
