//! A flat density shaped by Butterworth high- and low-pass filters: the target spectra of laboratory
//! seat tests (the input spectral classes of EN ISO 7096, the classes of ISO 5007).

use super::{Domain, RationalSpectrum};
use crate::error::{Error, Result};
use crate::linalg::poly;

/// Largest Butterworth order accepted (the classes of EN ISO 7096 use orders 1 to 8).
pub const MAX_BUTTERWORTH_ORDER: u32 = 8;

/// One Butterworth filter: its order n and corner frequency ω_c (rad/s, or rad/m for a spatial spectrum).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ButterworthFilter {
    /// Order n (1 … [`MAX_BUTTERWORTH_ORDER`]).
    pub order: u32,
    /// Corner (−3 dB) frequency ω_c, rad per lag unit.
    pub corner: f64,
}

impl ButterworthFilter {
    fn check(&self, name: &str) -> Result<()> {
        if !(1..=MAX_BUTTERWORTH_ORDER).contains(&self.order) {
            return Err(Error::invalid(
                &format!("{name}.order"),
                self.order,
                format!("a Butterworth order is 1 to {MAX_BUTTERWORTH_ORDER}"),
            ));
        }
        crate::error::require_positive(&format!("{name}.corner"), self.corner).map(drop)
    }

    /// The monic Butterworth polynomial Π (s − p_k), |p_k| = ω_c in the left half plane: the quadratic factors
    /// s² + 2ω_c sin((2k + 1)π/(2n)) s + ω_c² and, for odd n, s + ω_c (ascending powers of s). Its
    /// |·|² at s = iω is ω_c²ⁿ + ω²ⁿ.
    fn poles_polynomial(&self) -> Vec<f64> {
        let (n, w) = (self.order, self.corner);
        let mut p = vec![1.0];
        for k in 0..n / 2 {
            let angle = (2 * k + 1) as f64 * std::f64::consts::PI / (2 * n) as f64;
            p = poly::mul(&p, &[w * w, 2.0 * w * angle.sin(), 1.0]);
        }
        if n % 2 == 1 {
            p = poly::mul(&p, &[w, 1.0]);
        }
        p
    }

    /// 1 + (x/ω_c²)ⁿ, ascending powers of x = ω².
    fn denominator(&self) -> Vec<f64> {
        let mut d = vec![0.0; self.order as usize + 1];
        d[0] = 1.0;
        d[self.order as usize] = self.corner.powi(-2 * self.order as i32);
        d
    }
}

/// The density S(ω) = S₀ |H_HP(iω)|² |H_LP(iω)|² / ω^(2k): a level S₀ (two-sided, angular) through an
/// optional Butterworth high pass and a Butterworth low pass, seen as its k-th time integral (k = 0, 1, 2:
/// an acceleration class as a velocity or a displacement, to drive a model whose input is a displacement).
///
/// # Formula
/// ```text
/// |H_HP|² = (ω/ω_h)^(2n) / (1 + (ω/ω_h)^(2n)),   |H_LP|² = 1 / (1 + (ω/ω_l)^(2m))
/// S(ω) = S₀ (ω²/ω_h²)ⁿ / [(1 + (ω²/ω_h²)ⁿ)(1 + (ω²/ω_l²)ᵐ)] / (ω²)ᵏ
/// ```
/// (the exact Butterworth magnitudes), a [`RationalSpectrum`] in ω², so every analytic route applies.
///
/// # Errors
/// [`Error::InvalidParameter`]: a level that is not finite and > 0, an order outside 1 … 8, a corner that
/// is not finite and > 0, k > 2 or k above the high-pass order (the integral's density would not be
/// integrable at ω = 0); the errors of [`RationalSpectrum::new`].
///
/// # Examples
/// ```
/// use stochvib::spectrum::{butterworth_band, ButterworthFilter, Domain, Spectrum};
/// // a one-pole low pass: S = S0/(1 + ω²/ω_l²), variance π S0 ω_l
/// let lp = ButterworthFilter { order: 1, corner: 2.0 };
/// let s = butterworth_band(0.5, None, lp, 0, Domain::Temporal).unwrap();
/// assert!((s.variance().unwrap() - std::f64::consts::PI * 0.5 * 2.0).abs() < 1e-9);
/// ```
pub fn butterworth_band(
    level: f64,
    high_pass: Option<ButterworthFilter>,
    low_pass: ButterworthFilter,
    integrate: u32,
    domain: Domain,
) -> Result<RationalSpectrum> {
    crate::error::require_positive("level", level)?;
    low_pass.check("low_pass")?;
    let hp_order = match high_pass {
        Some(h) => {
            h.check("high_pass")?;
            h.order
        }
        None => 0,
    };
    if integrate > 2 || integrate > hp_order {
        return Err(Error::invalid(
            "integrate",
            integrate,
            format!(
                "0, 1 or 2, and at most the high-pass order ({hp_order}): the integral's density ∝ ω^(2(n−k)) \
                 must stay finite at ω = 0"
            ),
        ));
    }
    let k = (hp_order - integrate) as usize;
    let mut num = vec![0.0; k + 1];
    num[k] = level * high_pass.map_or(1.0, |h| h.corner.powi(-2 * h.order as i32));
    let mut den = low_pass.denominator();
    // the spectral factor in closed form: B(s) = √(2πS₀) ω_l^m sᵏ, A(s) = B_m(s; ω_l) B_n(s; ω_h)
    let mut b = vec![0.0; k + 1];
    b[k] = (2.0 * std::f64::consts::PI * level).sqrt() * low_pass.corner.powi(low_pass.order as i32);
    let mut a = low_pass.poles_polynomial();
    let mut corners = vec![low_pass.corner];
    if let Some(h) = high_pass {
        den = poly::mul(&den, &h.denominator());
        a = poly::mul(&a, &h.poles_polynomial());
        corners.push(h.corner);
    }
    corners.sort_by(f64::total_cmp);
    RationalSpectrum::with_factor(num, den, domain, (b, a), corners)
}
