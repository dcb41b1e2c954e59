//! The modified Bessel function of the second kind K_ν(x) for real order ν and x > 0 (needed by the
//! isotropic coherence model), by Temme's series for x < 2 and Steed's continued fraction for x ≥ 2.

use crate::error::{Error, Result};
use std::f64::consts::PI;

/// Taylor coefficients c_k of 1/Γ(z) = Σ_{k≥1} c_k z^k (Abramowitz & Stegun 1964, eq. 6.1.34, after
/// Wrench 1968, "Concerning two series for the gamma function", Math. Comp. 22), to 20 significant
/// digits; `RGAMMA[k]` is c_k. With |μ| ≤ ½ the truncation after c₂₇ leaves less than 1e-19. (The digits
/// are kept as published; the compiler rounds them to the nearest f64.)
#[allow(clippy::excessive_precision)]
const RGAMMA: [f64; 28] = [
    0.0,
    1.0,
    0.577_215_664_901_532_860_61,
    -0.655_878_071_520_253_881_08,
    -0.042_002_635_034_095_235_529,
    0.166_538_611_382_291_489_5,
    -0.042_197_734_555_544_336_748,
    -0.009_621_971_527_876_973_562_1,
    0.007_218_943_246_663_099_542_4,
    -0.001_165_167_591_859_065_112_1,
    -0.000_215_241_674_114_950_972_82,
    0.000_128_050_282_388_116_186_15,
    -0.000_020_134_854_780_788_238_656,
    -1.250_493_482_142_670_657_3e-6,
    1.133_027_231_981_695_882_4e-6,
    -2.056_338_416_977_607_103_5e-7,
    6.116_095_104_481_415_817_9e-9,
    5.002_007_644_469_222_930_1e-9,
    -1.181_274_570_487_020_144_6e-9,
    1.043_426_711_691_100_510_5e-10,
    7.782_263_439_905_071_254e-12,
    -3.696_805_618_642_205_708_2e-12,
    5.100_370_287_454_475_979e-13,
    -2.058_326_053_566_506_783_2e-14,
    -5.348_122_539_423_017_982_4e-15,
    1.226_778_628_238_260_790_2e-15,
    -1.181_259_301_697_458_769_5e-16,
    1.186_692_254_751_600_332_6e-18,
];

/// Temme's auxiliary functions for |μ| ≤ ½:
/// Γ₁(μ) = (1/Γ(1−μ) − 1/Γ(1+μ))/(2μ), Γ₂(μ) = (1/Γ(1−μ) + 1/Γ(1+μ))/2, and 1/Γ(1+μ), 1/Γ(1−μ).
///
/// From 1/Γ(1+μ) = Σ c_k μ^{k−1}: Γ₂ = Σ_{k odd} c_k μ^{k−1} and Γ₁ = −Σ_{k even} c_k μ^{k−2}, both free
/// of the cancellation that the definitions suffer at small μ.
fn temme_gammas(mu: f64) -> (f64, f64, f64, f64) {
    let m2 = mu * mu;
    let mut g1 = 0.0;
    let mut g2 = 0.0;
    // Horner in μ² from the highest coefficient down
    for k in (1..RGAMMA.len()).rev() {
        if k % 2 == 1 {
            g2 = g2 * m2 + RGAMMA[k];
        } else {
            g1 = g1 * m2 + RGAMMA[k];
        }
    }
    let g1 = -g1;
    // 1/Γ(1+μ) = Γ₂ − μΓ₁, 1/Γ(1−μ) = Γ₂ + μΓ₁
    (g1, g2, g2 - mu * g1, g2 + mu * g1)
}

/// e^x·(K_μ(x), K_{μ+1}(x)) for |μ| ≤ ½, x > 0.
fn k_pair_scaled(mu: f64, x: f64) -> Result<(f64, f64)> {
    const EPS: f64 = 1e-17;
    const MAX_ITER: usize = 100_000;
    let fail = |what: &str| Error::Numerical {
        what: "modified Bessel function K".into(),
        reason: format!("{what} did not converge for μ = {mu}, x = {x}"),
    };
    if x < 2.0 {
        // Temme (1975), "On the numerical evaluation of the modified Bessel function of the third kind",
        // J. Comput. Phys. 19, 324–337: series (4.6)–(4.8) in f_k, p_k, q_k.
        let x2 = 0.5 * x;
        let pimu = PI * mu;
        let fact = if pimu.abs() < EPS { 1.0 } else { pimu / pimu.sin() };
        let d = -x2.ln();
        let e = mu * d;
        let fact2 = if e.abs() < EPS { 1.0 } else { e.sinh() / e };
        let (g1, g2, gpl, gmi) = temme_gammas(mu);
        let mut ff = fact * (g1 * e.cosh() + g2 * fact2 * d);
        let mut sum = ff;
        let ee = e.exp();
        let mut p = 0.5 * ee / gpl;
        let mut q = 0.5 / (ee * gmi);
        let mut c = 1.0;
        let dd = x2 * x2;
        let mut sum1 = p;
        let mut converged = false;
        for i in 1..MAX_ITER {
            let fi = i as f64;
            ff = (fi * ff + p + q) / (fi * fi - mu * mu);
            c *= dd / fi;
            p /= fi - mu;
            q /= fi + mu;
            let del = c * ff;
            sum += del;
            sum1 += c * (p - fi * ff);
            if del.abs() < sum.abs() * EPS {
                converged = true;
                break;
            }
        }
        if !converged {
            return Err(fail("Temme's series"));
        }
        let s = x.exp();
        Ok((sum * s, sum1 * (2.0 / x) * s))
    } else {
        // Steed's continued fraction CF2 with Temme's normalisation (Thompson & Barnett 1987, "Modified
        // Bessel functions I_ν(z) and K_ν(z) of real order and complex argument", Comput. Phys. Commun.
        // 47, 245–257; as arranged in Press et al., Numerical Recipes, 2nd ed. 1992, §6.7, routine bessik).
        let a1 = 0.25 - mu * mu;
        let mut b = 2.0 * (1.0 + x);
        let mut d = 1.0 / b;
        let mut delh = d;
        let mut h = d;
        let mut q1 = 0.0;
        let mut q2 = 1.0;
        let mut q = a1;
        let mut c = a1;
        let mut a = -a1;
        let mut s = 1.0 + q * delh;
        let mut converged = false;
        for i in 2..MAX_ITER {
            let fi = i as f64;
            a -= 2.0 * (fi - 1.0);
            c = -a * c / fi;
            let qnew = (q1 - b * q2) / a;
            q1 = q2;
            q2 = qnew;
            q += c * qnew;
            b += 2.0;
            d = 1.0 / (b + a * d);
            delh *= b * d - 1.0;
            h += delh;
            let dels = q * delh;
            s += dels;
            if (dels / s).abs() < EPS {
                converged = true;
                break;
            }
        }
        if !converged {
            return Err(fail("Steed's continued fraction"));
        }
        let kmu = (PI / (2.0 * x)).sqrt() / s;
        let k1 = kmu * (mu + x + 0.5 - a1 * h) / x;
        Ok((kmu, k1))
    }
}

/// Validates (ν, x) and splits |ν| = n + μ with n = ⌊|ν| + ½⌋, −½ ≤ μ < ½.
fn check(nu: f64, x: f64) -> Result<(usize, f64)> {
    if !nu.is_finite() {
        return Err(Error::invalid("nu", nu, "order of K_ν must be finite"));
    }
    if !(x.is_finite() && x > 0.0) {
        return Err(Error::invalid("x", x, "argument of K_ν must be finite and > 0"));
    }
    let nu = nu.abs(); // K_{−ν} = K_ν
    let nl = (nu + 0.5).floor();
    Ok((nl as usize, nu - nl))
}

/// The exponentially scaled modified Bessel function of the second kind, e^x K_ν(x), for real ν and x > 0.
///
/// # Formula
/// ```text
/// K_ν(x) = ∫₀^∞ e^{−x cosh t} cosh(νt) dt          (Abramowitz & Stegun 1964, 9.6.24),   K_{−ν} = K_ν
/// ```
/// With ν = n + μ, n = ⌊ν + ½⌋, |μ| ≤ ½: K_μ and K_{μ+1} by Temme's series (x < 2; Temme 1975) or Steed's
/// continued fraction CF2 (x ≥ 2; Thompson & Barnett 1987), as in Numerical Recipes (Press et al. 1992,
/// §6.7), then the stable upward recurrence K_{m+1}(x) = K_{m−1}(x) + (2m/x) K_m(x) (A&S 9.6.26) to ν.
/// The auxiliary 1/Γ(1 ± μ) come from the series of 1/Γ (A&S 6.1.34). Relative accuracy is a few ulps
/// times the number of recurrence steps.
///
/// # Errors
/// [`Error::InvalidParameter`] for a non-finite ν or x ≤ 0; [`Error::Numerical`] if a series does not
/// converge (not observed).
///
/// # Examples
/// ```
/// use stochvib::coherence::bessel_k::bessel_k_scaled;
/// // K_{1/2}(x) = √(π/(2x)) e^{−x}  (A&S 10.2.17)
/// let x = 3.0;
/// let v = bessel_k_scaled(0.5, x).unwrap();
/// assert!((v - (std::f64::consts::PI / (2.0 * x)).sqrt()).abs() < 1e-14);
/// ```
pub fn bessel_k_scaled(nu: f64, x: f64) -> Result<f64> {
    let (n, mu) = check(nu, x)?;
    let (mut k0, mut k1) = k_pair_scaled(mu, x)?;
    for i in 1..=n {
        let next = (mu + i as f64) * (2.0 / x) * k1 + k0;
        k0 = k1;
        k1 = next;
    }
    Ok(k0)
}

/// The modified Bessel function of the second kind K_ν(x) for real ν and x > 0.
///
/// # Formula
/// K_ν(x) = e^{−x}·[`bessel_k_scaled`]`(ν, x)`; it underflows to 0 for x ≳ 700 and overflows to ∞ when
/// K_ν(x) > 1.8e308 (small x and large ν): use [`bessel_k_scaled`] or [`bessel_k_x_pow`] there.
///
/// # Errors
/// As [`bessel_k_scaled`].
///
/// # Examples
/// ```
/// use stochvib::coherence::bessel_k::bessel_k;
/// // Abramowitz & Stegun (1964), Table 9.8: K₁(1) = 0.6019072302
/// assert!((bessel_k(1.0, 1.0).unwrap() - 0.6019072302).abs() < 1e-10);
/// ```
pub fn bessel_k(nu: f64, x: f64) -> Result<f64> {
    Ok(bessel_k_scaled(nu, x)? * (-x).exp())
}

/// x^ν K_ν(x) for ν ≥ 0 and x > 0, without the overflow of K_ν at small x or the underflow of e^{−x}
/// at large x for moderate x^ν.
///
/// # Formula
/// With T_m = x^m e^x K_m(x), the recurrence of K becomes T_{m+1} = 2m T_m + x² T_{m−1}, started from
/// Temme/Steed's T_μ, T_{μ+1}; then x^ν K_ν(x) = exp(ln T_ν − x). As x → 0, x^ν K_ν(x) → 2^{ν−1} Γ(ν)
/// (ν > 0; A&S 9.6.9).
///
/// # Errors
/// As [`bessel_k_scaled`], and ν < 0.
///
/// # Examples
/// ```
/// use stochvib::coherence::bessel_k::bessel_k_x_pow;
/// // x K₁(x) → 1 as x → 0 (A&S 9.6.9): here x = 1e-12, the first correction is (x²/2) ln x ~ 1e-23
/// assert!((bessel_k_x_pow(1.0, 1e-12).unwrap() - 1.0).abs() < 1e-15);
/// ```
pub fn bessel_k_x_pow(nu: f64, x: f64) -> Result<f64> {
    if nu < 0.0 {
        return Err(Error::invalid("nu", nu, "x^ν K_ν(x) is provided for ν >= 0"));
    }
    let (n, mu) = check(nu, x)?;
    let (k0, k1) = k_pair_scaled(mu, x)?;
    let mut t0 = x.powf(mu) * k0;
    let mut t1 = x.powf(mu + 1.0) * k1;
    let x2 = x * x;
    for i in 1..=n {
        let next = 2.0 * (mu + i as f64) * t1 + x2 * t0;
        t0 = t1;
        t1 = next;
    }
    Ok(if x < 1.0 { t0 * (-x).exp() } else { (t0.ln() - x).exp() })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn temme_gammas_match_the_gamma_function() {
        // At μ = ±½ the definitions have no cancellation: Γ(1/2) = √π, Γ(3/2) = √π/2.
        let sp = PI.sqrt();
        let (g1, g2, gpl, gmi) = temme_gammas(0.5);
        assert!((gpl - 2.0 / sp).abs() < 1e-15);
        assert!((gmi - 1.0 / sp).abs() < 1e-15);
        assert!((g1 - (1.0 / sp - 2.0 / sp)).abs() < 1e-15);
        assert!((g2 - 1.5 / sp).abs() < 1e-15);
        // Γ₁(0) = −γ (Euler's constant), Γ₂(0) = 1
        let (g1, g2, _, _) = temme_gammas(0.0);
        assert!((g1 + 0.577_215_664_901_532_9).abs() < 1e-16);
        assert_eq!(g2, 1.0);
    }
}
