//! Exposure doses: VDV and MSDV of a stationary Gaussian signal, daily exposure A(8), total VDV.

use crate::error::{Error, Result};

/// Reference duration T₀ = 8 h = 28 800 s of the daily exposure A(8).
pub const REFERENCE_DURATION_S: f64 = 8.0 * 3600.0;

/// Shortest daily exposure accepted, s: 1 min. A shorter "daily exposure" is almost surely a unit slip
/// (`"7 s"` for 7 h); ISO 2631-1:1997 Annex B (Figure B.1) guides exposures from 10 min to 24 h.
pub const MIN_DAILY_EXPOSURE_S: f64 = 60.0;

/// Longest daily exposure, s: the 24 h of a day (a workday's tasks add up to at most this).
pub const MAX_DAILY_EXPOSURE_S: f64 = 24.0 * 3600.0;

fn require_non_negative(name: &str, v: f64) -> Result<f64> {
    if v.is_finite() && v >= 0.0 {
        Ok(v)
    } else {
        Err(Error::invalid(name, v, "must be finite and >= 0"))
    }
}

fn require_duration(name: &str, t: f64) -> Result<f64> {
    if t.is_finite() && t > 0.0 {
        Ok(t)
    } else {
        Err(Error::invalid(name, t, "a duration must be finite and > 0 s"))
    }
}

/// The vibration dose value of a stationary zero-mean Gaussian weighted acceleration of r.m.s. a_w over
/// a duration T.
///
/// # Formula
/// VDV = (∫₀ᵀ a_w⁴(t) dt)^(1/4) (ISO 2631-1:1997, 6.3.2), in m/s^1.75. For a zero-mean Gaussian variable
/// of variance σ², E(a⁴) = 3σ⁴ (the fourth moment of N(0, σ²)), so for a stationary process with σ = a_w
///
/// ```text
/// E[VDV⁴] = ∫₀ᵀ E[a⁴] dt = 3 a_w⁴ T      ⇒      VDV = (3T)^(1/4) · a_w,
/// ```
/// in the sense of the fourth-power mean (the record's VDV⁴ converges to 3a_w⁴T as T grows, for an
/// ergodic process). Compare the "estimated VDV" 1.4·a_w·T^(1/4) of the standard: 3^(1/4) = 1.316.
///
/// # Errors
/// [`Error::InvalidParameter`] naming `a_w` (must be finite, ≥ 0) or `duration_s` (finite, > 0).
///
/// # Examples
/// ```
/// use stochvib::comfort::vdv_gaussian;
/// // 0.5 m/s² for 8 h: (3·28800)^(1/4)·0.5 = 8.62 m/s^1.75
/// let v = vdv_gaussian(0.5, 8.0 * 3600.0).unwrap();
/// assert!((v - (3.0f64 * 28800.0).powf(0.25) * 0.5).abs() < 1e-12);
/// ```
pub fn vdv_gaussian(a_w: f64, duration_s: f64) -> Result<f64> {
    let a = require_non_negative("a_w", a_w)?;
    let t = require_duration("duration_s", duration_s)?;
    Ok((3.0 * t).powf(0.25) * a)
}

/// The motion sickness dose value of a Wf-weighted vertical acceleration of r.m.s. a_w over a duration T.
///
/// # Formula
/// MSDV = (∫₀ᵀ a_w²(t) dt)^(1/2) = a_w·√T  (ISO 2631-1:1997, clause 9.2), in m/s^1.5. This holds for any
/// signal, since a_w² is by definition (1/T)∫a_w² dt.
///
/// # Errors
/// [`Error::InvalidParameter`] naming `a_w` (finite, ≥ 0) or `duration_s` (finite, > 0).
///
/// # Examples
/// ```
/// use stochvib::comfort::msdv;
/// assert!((msdv(0.1, 3600.0).unwrap() - 6.0).abs() < 1e-12);
/// ```
pub fn msdv(a_w: f64, duration_s: f64) -> Result<f64> {
    let a = require_non_negative("a_w", a_w)?;
    let t = require_duration("duration_s", duration_s)?;
    Ok(a * t.sqrt())
}

/// The daily exposure A(8) of one exposure of magnitude a_w lasting T.
///
/// # Formula
/// A(8) = a_w·√(T/T₀), T₀ = 8 h (UK Control of Vibration at Work Regulations 2005, Schedule 2 Part I;
/// Directive 2002/44/EC Annex B: "equivalent continuous acceleration over an eight-hour period"), in
/// m/s². For health the a_w passed in is the axis value already multiplied by its factor k
/// (1.4 a_wx, 1.4 a_wy, a_wz for a seated person, see [`crate::comfort::axis_factor`]), and A(8) is
/// that of the axis with the highest value.
///
/// # Errors
/// [`Error::InvalidParameter`] naming `a_w` (finite, ≥ 0) or `duration_s` (finite, > 0).
///
/// # Examples
/// ```
/// use stochvib::comfort::daily_exposure_a8;
/// // 1 m/s² for 2 h: A(8) = 1·√(2/8) = 0.5 m/s²
/// assert!((daily_exposure_a8(1.0, 2.0 * 3600.0).unwrap() - 0.5).abs() < 1e-15);
/// ```
pub fn daily_exposure_a8(a_w: f64, duration_s: f64) -> Result<f64> {
    let a = require_non_negative("a_w", a_w)?;
    let t = require_duration("duration_s", duration_s)?;
    Ok(a * (t / REFERENCE_DURATION_S).sqrt())
}

/// One period of a working day: a (k-multiplied) weighted r.m.s. a_w, m/s², lasting `duration_s`.
///
/// # Formula
/// Contributes a_w²·T to the daily energy of [`daily_exposure_a8_periods`].
///
/// # Errors
/// [`daily_exposure_a8_periods`] rejects a negative or non-finite a_w and a non-positive duration.
///
/// # Examples
/// ```
/// use stochvib::comfort::{daily_exposure_a8_periods, ExposurePeriod};
/// let p = ExposurePeriod { a_w: 1.0, duration_s: 8.0 * 3600.0 };
/// assert_eq!(daily_exposure_a8_periods(&[p]).unwrap(), 1.0);
/// ```
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct ExposurePeriod {
    /// Weighted r.m.s. acceleration of the period (k-multiplied for health), m/s².
    pub a_w: f64,
    /// Duration of the period, s.
    pub duration_s: f64,
}

/// The daily exposure A(8) of a day made of several periods.
///
/// # Formula
/// A(8) = √( Σᵢ a_wᵢ² Tᵢ / T₀ ),  T₀ = 8 h (UK Control of Vibration at Work Regulations 2005, Schedule 2
/// Part I, second formula) — the energy-equivalent sum, m/s².
///
/// # Errors
/// [`Error::InvalidParameter`] naming `periods` when empty, or `periods[i].a_w` / `periods[i].duration_s`
/// when invalid.
///
/// # Examples
/// ```
/// use stochvib::comfort::{daily_exposure_a8_periods, ExposurePeriod};
/// let day = [
///     ExposurePeriod { a_w: 0.8, duration_s: 3.0 * 3600.0 },
///     ExposurePeriod { a_w: 0.4, duration_s: 4.0 * 3600.0 },
/// ];
/// // √((0.64·3 + 0.16·4)/8) = √0.32
/// assert!((daily_exposure_a8_periods(&day).unwrap() - 0.32f64.sqrt()).abs() < 1e-15);
/// ```
pub fn daily_exposure_a8_periods(periods: &[ExposurePeriod]) -> Result<f64> {
    if periods.is_empty() {
        return Err(Error::invalid("periods", "[]", "need at least one exposure period"));
    }
    let mut energy = 0.0;
    for (i, p) in periods.iter().enumerate() {
        let a = require_non_negative(&format!("periods[{i}].a_w"), p.a_w)?;
        let t = require_duration(&format!("periods[{i}].duration_s"), p.duration_s)?;
        energy += a * a * t;
    }
    Ok((energy / REFERENCE_DURATION_S).sqrt())
}

/// The total vibration dose value of several exposure periods.
///
/// # Formula
/// VDV_total = (Σᵢ VDVᵢ⁴)^(1/4), m/s^1.75 — the fourth-power dose adds over periods
/// (ISO 2631-1:1997, 6.3.2; it follows from VDV⁴ = ∫a_w⁴ dt over the union of the periods).
///
/// # Errors
/// [`Error::InvalidParameter`] naming `vdvs` when empty, or `vdvs[i]` when not finite and ≥ 0.
///
/// # Examples
/// ```
/// use stochvib::comfort::vdv_total;
/// assert!((vdv_total(&[10.0, 10.0]).unwrap() - 10.0 * 2f64.powf(0.25)).abs() < 1e-12);
/// ```
pub fn vdv_total(vdvs: &[f64]) -> Result<f64> {
    if vdvs.is_empty() {
        return Err(Error::invalid("vdvs", "[]", "need at least one vibration dose value"));
    }
    let mut sum = 0.0;
    for (i, &v) in vdvs.iter().enumerate() {
        let v = require_non_negative(&format!("vdvs[{i}]"), v)?;
        sum += v.powi(4);
    }
    Ok(sum.powf(0.25))
}
