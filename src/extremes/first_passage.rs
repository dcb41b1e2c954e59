//! First passage: the probability that a Gaussian response exceeds a level within a duration, stationary
//! (Poisson crossings, Vanmarcke's bandwidth correction) and non-stationary (the time-varying Rice rate).

use super::{normal_cdf, normal_pdf, Barrier};
use crate::error::{Error, Result};

/// How a probability of exceedance is computed.
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum ExceedanceMethod {
    /// Independent (Poisson) crossings at Rice's rate.
    Poisson,
    /// Vanmarcke's (1975) two-state (envelope) correction with δ_e = δ^1.2.
    Vanmarcke1975,
}

impl ExceedanceMethod {
    /// Short name for tables.
    pub fn label(self) -> &'static str {
        match self {
            ExceedanceMethod::Poisson => "Poisson (Rice)",
            ExceedanceMethod::Vanmarcke1975 => "Vanmarcke (1975)",
        }
    }
}

/// A first-passage question about a zero-mean stationary Gaussian process started in its stationary
/// state: P(max > b within T) for a level b = rσ, with ν₀⁺T zero up-crossings expected within T, of the
/// maximum of y or of |y|. Named fields: r and ν₀⁺T are both plain numbers and cannot be swapped silently.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FirstPassage {
    /// r = b/σ, the level in standard deviations.
    pub level_over_sigma: f64,
    /// ν₀⁺T, the expected number of zero up-crossings within the duration T.
    pub zero_upcrossings: f64,
    /// The maximum of y (one-sided) or of |y| (two-sided).
    pub barrier: Barrier,
}

impl FirstPassage {
    /// P(max > b within T) with Poisson crossings.
    ///
    /// # Formula
    /// Rice's rate of up-crossings of b is ν₀⁺e^{−r²/2}; crossings assumed independent (a Poisson stream):
    /// ```text
    /// P(max y > b)   = 1 − exp(−ν₀⁺T e^{−r²/2})          (one-sided)
    /// P(max |y| > b) = 1 − exp(−2ν₀⁺T e^{−r²/2})         (two-sided)
    /// ```
    ///
    /// # Examples
    /// ```
    /// use stochvib::extremes::{Barrier, FirstPassage};
    /// let q = FirstPassage { level_over_sigma: 3.0, zero_upcrossings: 100.0, barrier: Barrier::OneSided };
    /// assert!((q.poisson() - (1.0 - (-100.0 * (-4.5f64).exp()).exp())).abs() < 1e-15);
    /// ```
    pub fn poisson(&self) -> f64 {
        let r = self.level_over_sigma;
        -(-self.barrier.crossings_per_cycle() * self.zero_upcrossings * (-0.5 * r * r).exp()).exp_m1()
    }

    /// P(max > b within T) by Vanmarcke's (1975) bandwidth-corrected first-passage form, r ≥ 0, bandwidth δ
    /// (Vanmarcke's q).
    ///
    /// # Formula
    /// Vanmarcke, E.H. (1975), "On the distribution of the first-passage time for normal stationary random
    /// processes", J. Appl. Mech. 42(1), 215–220: crossings of the envelope, of which only a fraction are
    /// followed by crossings of y (clumping), with the empirical effective bandwidth δ_e = δ^1.2:
    /// ```text
    /// P(max ≤ b) = A · exp(−c ν₀⁺T e^{−r²/2} (1 − e^{−k δ_e r}) / (1 − e^{−r²/2})),   A = 1 − e^{−r²/2}
    /// two-sided (|y|): c = 2, k = √(π/2);     one-sided (y): c = 1, k = √(2π)
    /// ```
    /// A is the probability that the envelope starts below the level. For δ → 1 the bracket tends to
    /// Poisson's rate over A (the envelope correction vanishes only in that limit).
    ///
    /// # Errors
    /// r < 0 or δ outside \[0, 1\].
    ///
    /// # Examples
    /// ```
    /// use stochvib::extremes::{Barrier, FirstPassage};
    /// // narrow band: fewer exceedances than Poisson (crossings come in clumps)
    /// let q = FirstPassage { level_over_sigma: 3.0, zero_upcrossings: 100.0, barrier: Barrier::TwoSided };
    /// assert!(q.vanmarcke(0.1).unwrap() < q.poisson());
    /// ```
    pub fn vanmarcke(&self, bandwidth: f64) -> Result<f64> {
        let (r, delta) = (self.level_over_sigma, bandwidth);
        if !(r >= 0.0 && r.is_finite()) {
            return Err(Error::invalid(
                "level/sigma",
                r,
                "Vanmarcke's form needs a level at or above the mean",
            ));
        }
        if !(0.0..=1.0).contains(&delta) {
            return Err(Error::invalid("bandwidth", delta, "Vanmarcke's δ lies in [0, 1]"));
        }
        if r == 0.0 {
            return Ok(1.0);
        }
        let de = delta.powf(1.2);
        let e = (-0.5 * r * r).exp();
        let a = -(-0.5 * r * r).exp_m1();
        let k = match self.barrier {
            Barrier::OneSided => (2.0 * std::f64::consts::PI).sqrt(),
            Barrier::TwoSided => (std::f64::consts::PI / 2.0).sqrt(),
        };
        let hazard = self.barrier.crossings_per_cycle() * self.zero_upcrossings * e * (-(-k * de * r).exp_m1()) / a;
        Ok(1.0 - a * (-hazard).exp())
    }
}

/// The first three spectral moments λ_k = ∫|ω|ᵏS dω of a stationary process, the input of
/// [`bandwidth_vanmarcke`] (named fields: three numbers of different powers of ω cannot be swapped silently).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BandwidthMoments {
    /// λ₀ = σ², unit².
    pub lambda0: f64,
    /// λ₁, unit²·rad/s.
    pub lambda1: f64,
    /// λ₂ = σ_ẋ², unit²·(rad/s)².
    pub lambda2: f64,
}

/// Vanmarcke's bandwidth δ = √(1 − λ₁²/(λ₀λ₂)) from the spectral moments λ_k = ∫|ω|ᵏS dω.
///
/// # Formula
/// Vanmarcke, E.H. (1972), "Properties of spectral moments with applications to random vibration",
/// J. Eng. Mech. Div. ASCE 98(EM2), 425–446 (his q). 0 for a pure tone, ≈ √(4ζ/π) for a lightly damped
/// oscillator under white noise.
///
/// # Errors
/// Non-positive or non-finite moments; λ₁² > λ₀λ₂ beyond rounding (impossible for a density: Cauchy–Schwarz).
pub fn bandwidth_vanmarcke(m: BandwidthMoments) -> Result<f64> {
    let BandwidthMoments {
        lambda0: l0,
        lambda1: l1,
        lambda2: l2,
    } = m;
    for (name, v) in [("lambda0", l0), ("lambda1", l1), ("lambda2", l2)] {
        if !(v.is_finite() && v > 0.0) {
            return Err(Error::invalid(name, v, "spectral moments must be finite and > 0"));
        }
    }
    let q = 1.0 - l1 * l1 / (l0 * l2);
    if q < -1e-9 {
        return Err(Error::invalid(
            "lambda1",
            l1,
            "λ₁² > λ₀λ₂: the moments do not come from one density",
        ));
    }
    Ok(q.max(0.0).sqrt())
}

/// The moments of a stationary response that the exceedance forms need.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct CrossingMoments {
    /// M_y.
    pub mean: f64,
    /// σ_y.
    pub sigma: f64,
    /// ν₀⁺, Hz.
    pub nu0_plus: f64,
    /// Vanmarcke's δ, when λ₁ is known.
    pub delta: Option<f64>,
}

impl CrossingMoments {
    /// P(max > b within `duration`) by `method`, for the maximum of y or of |y| (levels from zero, not
    /// from the mean).
    ///
    /// # Formula
    /// Poisson with a mean: the crossing count is ν₀⁺T(e^{−(b−M)²/2σ²} + [two-sided] e^{−(b+M)²/2σ²}).
    /// Vanmarcke: [`FirstPassage::vanmarcke`] with r = (b − M)/σ; the two-sided form needs M = 0 (barriers
    /// symmetric about the mean).
    ///
    /// # Errors
    /// Vanmarcke without δ, with a two-sided barrier about a non-zero mean, or a level below the mean.
    pub fn exceedance(&self, b: f64, duration: f64, barrier: Barrier, method: ExceedanceMethod) -> Result<f64> {
        let r = (b - self.mean) / self.sigma;
        let nt = self.nu0_plus * duration;
        match method {
            ExceedanceMethod::Poisson => {
                let mut count = nt * (-0.5 * r * r).exp();
                if barrier == Barrier::TwoSided {
                    let r2 = (b + self.mean) / self.sigma;
                    count += nt * (-0.5 * r2 * r2).exp();
                }
                Ok(-(-count).exp_m1())
            }
            ExceedanceMethod::Vanmarcke1975 => {
                let delta = self.delta.ok_or_else(|| Error::NotApplicable {
                    method: "Vanmarcke (1975)".into(),
                    reason: "needs the bandwidth δ (λ₁ of the output density)".into(),
                })?;
                if barrier == Barrier::TwoSided && self.mean != 0.0 {
                    return Err(Error::NotApplicable {
                        method: "Vanmarcke (1975), two-sided".into(),
                        reason: format!("the barriers ±b are not symmetric about the mean {}", self.mean),
                    });
                }
                FirstPassage {
                    level_over_sigma: r,
                    zero_upcrossings: nt,
                    barrier,
                }
                .vanmarcke(delta)
            }
        }
    }
}

/// The state of a non-stationary Gaussian process at one time that the Rice rate needs.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct RiceState {
    /// m(t) = E y.
    pub mean: f64,
    /// ṁ(t) = E ẏ.
    pub mean_rate: f64,
    /// σ_y(t).
    pub sigma: f64,
    /// σ_ẏ(t).
    pub sigma_rate: f64,
    /// ρ(t), the correlation of y and ẏ at the same time (zero for a stationary process).
    pub rho: f64,
}

/// Rice's rate of up-crossings of level b by a non-stationary Gaussian process, per second.
///
/// # Formula
/// ν⁺(b, t) = ∫₀^∞ ẏ p(b, ẏ; t) dẏ (Rice, S.O. (1944), "Mathematical analysis of random noise", Bell Syst.
/// Tech. J. 23, 282–332, the crossing-rate integral) for jointly Gaussian (y, ẏ) with means (m, ṁ),
/// standard deviations (σ, σ̇) and correlation ρ; conditioning ẏ on y = b gives mean ṁ + ρσ̇β and
/// standard deviation s = σ̇√(1 − ρ²), so
/// ```text
/// ν⁺(b, t) = (φ(β)/σ) · s · [φ(η) + η Φ(η)],    β = (b − m)/σ,   η = (ṁ + ρσ̇β)/s
/// ```
/// For ρ = 0, ṁ = 0 it is (1/2π)(σ̇/σ)e^{−β²/2}, the stationary rate. A process with σ = 0 (started at
/// rest) has rate 0; with s = 0 the rate is φ(β)/σ·max(ṁ + ρσ̇β, 0).
pub fn rice_rate(b: f64, s: &RiceState) -> f64 {
    if s.sigma <= 0.0 {
        return 0.0;
    }
    let beta = (b - s.mean) / s.sigma;
    let cond_mean = s.mean_rate + s.rho * s.sigma_rate * beta;
    let cond_sd = s.sigma_rate * (1.0 - s.rho * s.rho).max(0.0).sqrt();
    let lead = normal_pdf(beta) / s.sigma;
    if cond_sd <= 0.0 {
        return lead * cond_mean.max(0.0);
    }
    let eta = cond_mean / cond_sd;
    lead * cond_sd * (normal_pdf(eta) + eta * normal_cdf(eta))
}

/// Rate of the crossings out of the band \[−b, b\]: up-crossings of +b plus down-crossings of −b (the
/// up-crossings of +b by −y, whose mean and mean rate change sign and whose ρ is the same).
pub fn rice_rate_two_sided(b: f64, s: &RiceState) -> f64 {
    let mirrored = RiceState {
        mean: -s.mean,
        mean_rate: -s.mean_rate,
        ..*s
    };
    rice_rate(b, s) + rice_rate(b, &mirrored)
}
