//! Fit of the ISO 8608:2016 power law G_d(n) = G_d(n₀)(n/n₀)^{−w} to an estimated spatial density,
//! and the road class.

use super::SpatialPsd;
use crate::error::{Error, Result};
use crate::estimate::Interval;
use crate::spectrum::{IsoBound, IsoClass, ISO_BAND, ISO_N0};
use statrs::distribution::{ContinuousCDF, Normal};

/// The waviness in an ISO 8608 fit: fixed (ISO 8608 classifies with w = 2) or estimated.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Waviness {
    /// w held at the given value (2 for the ISO classification).
    Fixed(f64),
    /// w estimated together with G_d(n₀).
    Free,
}

/// Result of [`fit_iso8608`].
#[derive(Debug, Clone, PartialEq)]
pub struct IsoFit {
    /// Fitted G_d(n₀) in m³, n₀ = 0.1 cycles/m.
    pub g0_m3: f64,
    /// Standard error of ln G_d(n₀) (a relative standard error of G_d(n₀)).
    pub ln_g0_std_error: f64,
    /// The waviness w (fitted, or the fixed value).
    pub waviness: f64,
    /// Standard error of w (0 when fixed).
    pub waviness_std_error: f64,
    /// ISO 8608 class of G_d(n₀) ([`iso8608_class`]).
    pub class: IsoClass,
    /// The band actually fitted, cycles/m (first and last bin centre used).
    pub band: (f64, f64),
    /// Number of bins used.
    pub bins: usize,
    /// Welch's ν of each bin.
    pub dof: f64,
    /// Residual sum of squares over its expectation under the model, RSS/(σ²(N − p)); near 1 when the
    /// density is a power law, larger when the road departs from it (the standard errors then understate
    /// the uncertainty of the fitted line as a description of the road).
    pub reduced_chi2: f64,
    /// P(T ≥ t) under the model for the fit's residual statistic t = RSS/σ² (the probability that a road whose
    /// density is this power law gives a fit this poor or worse): T taken as c·χ²_k with the bins'
    /// correlation r_d (d ≤ 3 bins apart, Welch's window), c = 1 + 2 Σ_{d≥1} r_d², k = (N − p)/c (the mean
    /// N − p and the variance 2(N − p)c of a sum of correlated squares, Satterthwaite's match). Below
    /// [`POWER_LAW_REJECT_P`] the power law does not describe the track over the band, and its class is the
    /// level of G_d at n₀ only.
    pub fit_p_value: f64,
}

/// A fit whose [`IsoFit::fit_p_value`] is below this is reported as not describing the road: a road that
/// follows the power law is flagged with a probability of about 10⁻⁶ (the χ² approximation of the
/// correlated bins is coarser than that in the far tail; the reduced χ² of a power-law road stays near 1:
/// 0.86 for the shipped class C profile, 1.05 for another of its seeds).
pub const POWER_LAW_REJECT_P: f64 = 1e-6;

impl IsoFit {
    /// Whether the power law describes the track over the band: [`IsoFit::fit_p_value`] ≥
    /// [`POWER_LAW_REJECT_P`].
    pub fn describes_the_road(&self) -> bool {
        self.fit_p_value >= POWER_LAW_REJECT_P
    }

    /// Normal-theory interval of G_d(n₀): exp(ln Ĝ₀ ± q·se).
    ///
    /// # Errors
    /// confidence ∉ (0, 1).
    pub fn g0_interval(&self, confidence: f64) -> Result<Interval> {
        let q = normal_quantile(confidence)?;
        Ok(Interval {
            estimate: self.g0_m3,
            lower: self.g0_m3 * (-q * self.ln_g0_std_error).exp(),
            upper: self.g0_m3 * (q * self.ln_g0_std_error).exp(),
            confidence,
        })
    }

    /// Normal-theory interval of w: ŵ ± q·se (zero width when w was fixed).
    ///
    /// # Errors
    /// confidence ∉ (0, 1).
    pub fn waviness_interval(&self, confidence: f64) -> Result<Interval> {
        let q = normal_quantile(confidence)?;
        Ok(Interval {
            estimate: self.waviness,
            lower: self.waviness - q * self.waviness_std_error,
            upper: self.waviness + q * self.waviness_std_error,
            confidence,
        })
    }
}

fn normal_quantile(confidence: f64) -> Result<f64> {
    if !(confidence > 0.0 && confidence < 1.0) {
        return Err(Error::invalid("confidence", confidence, "must be in (0, 1)"));
    }
    Ok(Normal::new(0.0, 1.0)
        .map_err(|e| Error::Numerical {
            what: "normal quantile".into(),
            reason: e.to_string(),
        })?
        .inverse_cdf(0.5 + 0.5 * confidence))
}

/// The ISO 8608 class of a degree of roughness G_d(n₀) (m³, n₀ = 0.1 cycles/m).
///
/// # Formula
/// Class k (A = 0 … H = 7) has the geometric mean 16·4^k × 10⁻⁶ m³ and the limits ×½ and ×2
/// ([`IsoClass::g0`]); a value on a limit belongs to the rougher class (intervals [lower, upper)). Below the
/// upper limit of A (32e-6 m³) the class is A, from the lower limit of H (131072e-6 m³) up it is H (ISO
/// 8608 gives no lower limit for A and no upper limit for H).
///
/// # Errors
/// G_d(n₀) not finite and > 0.
///
/// # Examples
/// ```
/// use stochvib::road::iso8608_class;
/// use stochvib::spectrum::IsoClass;
/// assert_eq!(iso8608_class(256e-6).unwrap(), IsoClass::C);
/// assert_eq!(iso8608_class(128e-6).unwrap(), IsoClass::C);     // the B/C limit belongs to C
/// assert_eq!(iso8608_class(1e-9).unwrap(), IsoClass::A);
/// assert_eq!(iso8608_class(1.0).unwrap(), IsoClass::H);
/// ```
pub fn iso8608_class(g0_m3: f64) -> Result<IsoClass> {
    crate::error::require_positive("G_d(n0)", g0_m3)?;
    Ok(IsoClass::ALL
        .into_iter()
        .rev()
        .find(|c| *c == IsoClass::A || c.g0(IsoBound::Lower).is_ok_and(|lo| g0_m3 >= lo))
        .unwrap_or(IsoClass::A))
}

/// ψ'(x), the trigamma function, x > 0: recurrence ψ'(x) = ψ'(x + 1) + 1/x² up to x ≥ 20, then the
/// asymptotic series 1/x + 1/(2x²) + 1/(6x³) − 1/(30x⁵) + 1/(42x⁷) − 1/(30x⁹) + 5/(66x¹¹) (Abramowitz &
/// Stegun 6.4.6, 6.4.12; the next term, 691/(2730x¹³), is below 4e-18 at x = 20).
fn trigamma(mut x: f64) -> f64 {
    let mut acc = 0.0;
    while x < 20.0 {
        acc += 1.0 / (x * x);
        x += 1.0;
    }
    let r = 1.0 / x;
    let r2 = r * r;
    let tail = 1.0 / 6.0 - r2 * (1.0 / 30.0 - r2 * (1.0 / 42.0 - r2 * (1.0 / 30.0 - r2 * 5.0 / 66.0)));
    acc + r + 0.5 * r2 + r * r2 * tail
}

/// Least-squares fit of ISO 8608's G_d(n) = G_d(n₀)(n/n₀)^{−w} (n₀ = 0.1 cycles/m) to a Welch estimate,
/// in log–log coordinates, with w fixed or free, and the ISO class of the fitted G_d(n₀).
///
/// # Formula
/// Bins in the band (default: ISO 8608's 0.011–2.83 cycles/m intersected with what the estimate resolves,
/// n ≥ 3Δn, Δn = 1/(MΔx): the Hann main lobe at n = 0 covers the first two bins; the Nyquist bin is not in
/// a [`SpatialPsd`]). With x_j = ln(n_j/n₀):
/// ```text
/// y_j = ln Ĝ_j − b,  b = ψ(ν/2) − ln(ν/2)      (E ln(χ²_ν/ν) = b: the log of a χ² estimate is biased low)
/// y_j = ln G₀ − w x_j + e_j,   Var e_j = σ² = ψ'(ν/2)  (≈ 2/ν),   corr(e_j, e_{j+d}) = r_d
/// ```
/// ψ, ψ' digamma and trigamma. **Weights: equal for all bins.** Every bin of a Welch estimate has the same
/// ν, so equal weights are the inverse-variance (χ²-dof) weights and give the minimum-variance unbiased
/// line under the model. (Averaging into log-spaced bands first, as often done for plots, weights the
/// decades equally instead; it discards information when the road is a power law and only changes which
/// part of the band dominates when it is not — the reduced χ² reports the latter.) Neighbouring Hann bins
/// are correlated (r₁ ≈ 0.46, r₂ ≈ 0.03, [`SpatialPsd::bin_correlation`]), so the standard errors come
/// from the sandwich covariance
/// ```text
/// Cov(β̂) = (XᵀX)⁻¹ XᵀΣX (XᵀX)⁻¹,   Σ_jk = σ² r_{|j−k|}  (r_d for d ≤ 3, 0 beyond)
/// ```
/// with X = \[1, −x_j\] (w free) or \[1\] on y_j + w x_j (w fixed). The class is [`iso8608_class`] of Ĝ₀.
/// The model ignores the smoothing bias of the window (small where G_d is smooth on the scale of Δn; see
/// [`Welch::expected`](crate::estimate::Welch::expected) for its exact value).
///
/// # Errors
/// A waviness that is not finite and > 0; a band that is not 0 < n₁ < n₂; fewer than 2 bins in the band
/// (3 with w free); non-positive density estimates in the band (nothing to take the log of).
///
/// # Examples
/// ```
/// use stochvib::road::{fit_iso8608, SpatialPsd, Waviness};
/// use stochvib::spectrum::IsoClass;
/// // an exact ISO class C density (256e-6 m³, w = 2) sampled on a Welch grid fits back exactly (up to the
/// // log-χ² bias correction, removed here by giving the fit its own expectation)
/// let (m, dx, nu) = (2048usize, 0.05, 30.0);
/// let n: Vec<f64> = (1..m / 2).map(|j| j as f64 / (m as f64 * dx)).collect();
/// let b = statrs::function::gamma::digamma(nu / 2.0) - (nu / 2.0f64).ln();
/// let g_d = n.iter().map(|x| 256e-6 * (x / 0.1f64).powi(-2) * b.exp()).collect();
/// let psd = SpatialPsd { n, g_d, segments: 16, dof: nu, nominal_dof: 32.0, step_m: dx, segment_len: m };
/// let fit = fit_iso8608(&psd, Waviness::Free, None).unwrap();
/// assert!((fit.g0_m3 / 256e-6 - 1.0).abs() < 1e-12 && (fit.waviness - 2.0).abs() < 1e-12);
/// assert_eq!(fit.class, IsoClass::C);
/// ```
pub fn fit_iso8608(psd: &SpatialPsd, waviness: Waviness, band: Option<(f64, f64)>) -> Result<IsoFit> {
    if let Waviness::Fixed(w) = waviness {
        crate::error::require_positive("waviness", w)?;
    }
    let (lo, hi) = match band {
        Some((a, b)) => {
            crate::error::require_positive("band.low", a)?;
            if !(b.is_finite() && b > a) {
                return Err(Error::invalid(
                    "band.high",
                    b,
                    format!("must be finite and > band.low = {a}"),
                ));
            }
            (a, b)
        }
        None => (ISO_BAND.0.max(3.0 * psd.resolution() * (1.0 - 1e-12)), ISO_BAND.1),
    };
    let idx: Vec<usize> = (0..psd.n.len()).filter(|&j| psd.n[j] >= lo && psd.n[j] <= hi).collect();
    let p = if waviness == Waviness::Free { 2 } else { 1 };
    if idx.len() < p + 1 {
        return Err(Error::invalid(
            "band",
            format!("{lo}..{hi} cycles/m"),
            format!(
                "holds {} bins of the estimate (resolution {} cycles/m, bins up to {} cycles/m); need at \
                 least {}: use a longer segment or a wider band",
                idx.len(),
                psd.resolution(),
                psd.n.last().copied().unwrap_or(0.0),
                p + 1
            ),
        ));
    }
    if let Some(&j) = idx.iter().find(|&&j| !(psd.g_d[j] > 0.0 && psd.g_d[j].is_finite())) {
        return Err(Error::invalid(
            &format!("G_d({} cycles/m)", psd.n[j]),
            psd.g_d[j],
            "density estimate must be finite and > 0 to fit in log-log",
        ));
    }
    let nu = psd.dof;
    let bias = statrs::function::gamma::digamma(nu / 2.0) - (nu / 2.0).ln();
    let sigma2 = trigamma(nu / 2.0);
    let r: Vec<f64> = (0..=3).map(|d| psd.bin_correlation(d)).collect();
    let x: Vec<f64> = idx.iter().map(|&j| (psd.n[j] / ISO_N0).ln()).collect();
    let y: Vec<f64> = idx.iter().map(|&j| psd.g_d[j].ln() - bias).collect();
    let nb = x.len();
    // Σ-weighted quadratic form uᵀΣv / σ² over the band, correlation r_d of bins d apart (d ≤ 3)
    let quad = |u: &dyn Fn(usize) -> f64, v: &dyn Fn(usize) -> f64| -> f64 {
        let mut s = 0.0;
        for i in 0..nb {
            for k in i.saturating_sub(3)..(i + 4).min(nb) {
                let d = idx[i].abs_diff(idx[k]);
                if d <= 3 {
                    s += u(i) * r[d] * v(k);
                }
            }
        }
        s
    };
    let (ln_g0, w, var_ln_g0, var_w, fitted): (f64, f64, f64, f64, Vec<f64>) = match waviness {
        Waviness::Fixed(w) => {
            let a = y.iter().zip(&x).map(|(yi, xi)| yi + w * xi).sum::<f64>() / nb as f64;
            let one = |_: usize| 1.0 / nb as f64;
            let var = sigma2 * quad(&one, &one);
            let fitted = x.iter().map(|xi| a - w * xi).collect();
            (a, w, var, 0.0, fitted)
        }
        Waviness::Free => {
            let xbar = x.iter().sum::<f64>() / nb as f64;
            let ybar = y.iter().sum::<f64>() / nb as f64;
            let sxx: f64 = x.iter().map(|xi| (xi - xbar).powi(2)).sum();
            let sxy: f64 = x.iter().zip(&y).map(|(xi, yi)| (xi - xbar) * (yi - ybar)).sum();
            let w = -sxy / sxx;
            let a = ybar + w * xbar;
            // both estimates are linear in y: â = Σ_j la(j) y_j, ŵ = Σ_j lw(j) y_j
            let la = |j: usize| 1.0 / nb as f64 - xbar * (x[j] - xbar) / sxx;
            let lw = |j: usize| -(x[j] - xbar) / sxx;
            let var_a = sigma2 * quad(&la, &la);
            let var_w = sigma2 * quad(&lw, &lw);
            let fitted = x.iter().map(|xi| a - w * xi).collect();
            (a, w, var_a, var_w, fitted)
        }
    };
    let rss: f64 = y
        .iter()
        .zip(&fitted)
        .map(|(yi, fi): (&f64, &f64)| (yi - fi).powi(2))
        .sum();
    let g0 = ln_g0.exp();
    Ok(IsoFit {
        g0_m3: g0,
        ln_g0_std_error: var_ln_g0.sqrt(),
        waviness: w,
        waviness_std_error: var_w.sqrt(),
        class: iso8608_class(g0)?,
        band: (psd.n[idx[0]], psd.n[idx[nb - 1]]),
        bins: nb,
        dof: nu,
        reduced_chi2: rss / (sigma2 * (nb - p) as f64),
        fit_p_value: goodness_of_fit(rss / sigma2, nb - p, &r),
    })
}

/// P(T ≥ `t`) for T = c·χ²_k, c = 1 + 2 Σ_{d≥1} r_d², k = `dof`/c: the residual statistic t = RSS/σ² of a
/// fit with `dof` = N − p degrees of freedom over bins of correlation `r` (r₀ = 1), see
/// [`IsoFit::fit_p_value`].
fn goodness_of_fit(t: f64, dof: usize, r: &[f64]) -> f64 {
    let c = 1.0 + 2.0 * r[1..].iter().map(|v| v * v).sum::<f64>();
    statrs::distribution::ChiSquared::new(dof as f64 / c).map_or(f64::NAN, |chi2| chi2.sf(t / c))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn trigamma_known_values() {
        // ψ'(1) = π²/6, ψ'(1/2) = π²/2 (A&S 6.4.2, 6.4.4); ψ'(x+1) = ψ'(x) − 1/x²
        let pi2 = std::f64::consts::PI.powi(2);
        assert!((trigamma(1.0) - pi2 / 6.0).abs() < 1e-14);
        assert!((trigamma(0.5) - pi2 / 2.0).abs() < 1e-14);
        assert!((trigamma(13.5) - (trigamma(12.5) - 1.0 / 12.5f64.powi(2))).abs() < 1e-15);
    }
}
