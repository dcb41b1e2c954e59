//! The ISO 2631-1 frequency weightings realised as digital filters for sampled records (ISO 8041-1), and the
//! error of that realisation against the analytic weighting.
//!
//! # Discretisation
//! Each analog factor of the weighting (ISO 2631-1:1997 Annex A; [`Weighting`]) — the high pass H_h, the
//! low pass H_l, the acceleration–velocity transition H_t and the upward step H_s — becomes one digital
//! second-order section by the **bilinear transform prewarped at the section's own pole frequency**:
//!
//! ```text
//! s → c·(z − 1)/(z + 1),      c = ω_p / tan(ω_p/(2 f_s)),
//! ```
//! with ω_p the natural frequency of the section's denominator s² + ω_p s/Q + ω_p² (ω₁ for H_h, ω₂ for H_l,
//! ω₄ for H_t, ω₆ for H_s). The section is then exact at ω = ω_p and the mapping of the whole imaginary axis
//! onto the unit circle keeps every section stable and free of aliasing. This is the design of Rimell, A.N.
//! & Mansfield, N.J. (2007), "Design of digital filters for frequency weightings (A and C) required for risk
//! assessments of workers exposed to vibration", Industrial Health 45, 512–519, with the prewarping of the
//! HVLab toolbox (ISVR); ISO 8041:2005 Annex C describes the method but gives no coefficients. The sections
//! run in series, each in transposed direct form II with f64 states.
//!
//! # Error
//! The bilinear transform maps the analog zeros at s = ∞ (a weighting has relative degree ≥ 2) to z = −1, so
//! the digital weighting falls below the analytic one towards the Nyquist frequency; the error is largest
//! at the top band. [`DigitalWeighting::error_table`] gives it at every one-third-octave centre; measured
//! (`stochvib weighting Wk --sample-rate 1000`) at f_s = 1 kHz the largest magnitude error from 0.1 Hz to
//! 80 Hz is −0.12 dB (Wk, Wd, Wb) with at most 1.2° of phase; at 400 Hz −0.8 dB; at 250 Hz −2.6 dB.
//! [`DigitalWeighting::check_bands`] refuses a rate at which a band of the evaluation range is lost:
//! above the Nyquist frequency, or realised with more than [`MAX_BAND_ERROR_DB`] of error.

use crate::comfort::{bands_covering, Band, BandFraction, Weighting};
use crate::error::{Error, Result};
use nalgebra::Complex;
use std::f64::consts::{PI, TAU};

/// Largest magnitude error of the digital weighting at a one-third-octave centre of the evaluation range
/// that [`DigitalWeighting::check_bands`] accepts, dB (1 dB ≈ 12 %).
///
/// ISO 8041 specifies the tolerance of a weighting as limits around its nominal value (of the order of
/// ±1 dB in the main range, wider towards the band limits, as we understand the standard; check the
/// printed tables for compliance work): this toolkit holds its own realisation to 1 dB at every centre,
/// which f_s ≥ 400 Hz meets for the 0.5–80 Hz weightings.
pub const MAX_BAND_ERROR_DB: f64 = 1.0;

/// One digital second-order section y = (b₀ + b₁z⁻¹ + b₂z⁻²)/(1 + a₁z⁻¹ + a₂z⁻²)·x.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct Biquad {
    /// Numerator b₀, b₁, b₂.
    pub b: [f64; 3],
    /// Denominator a₁, a₂ (a₀ = 1).
    pub a: [f64; 2],
}

impl Biquad {
    /// The bilinear transform (prewarped at ω_p) of N(s)/D(s) with N = n₀ + n₁s + n₂s²,
    /// D = d₀ + d₁s + s² (coefficients ascending in s).
    fn bilinear(num: [f64; 3], den: [f64; 3], omega_p: f64, fs: f64) -> Biquad {
        let c = omega_p / (omega_p / (2.0 * fs)).tan();
        // p(s) = p₀ + p₁s + p₂s² with s = c(z − 1)/(z + 1), times (z + 1)²: coefficients of z², z, 1
        let sub = |p: [f64; 3]| {
            let c2 = c * c;
            [
                p[2] * c2 + p[1] * c + p[0],
                2.0 * (p[0] - p[2] * c2),
                p[2] * c2 - p[1] * c + p[0],
            ]
        };
        let (n, d) = (sub(num), sub(den));
        Biquad {
            b: [n[0] / d[0], n[1] / d[0], n[2] / d[0]],
            a: [d[1] / d[0], d[2] / d[0]],
        }
    }

    /// H(e^{iθ}), θ = 2πf/f_s.
    fn response(&self, theta: f64) -> Complex<f64> {
        let z1 = Complex::from_polar(1.0, -theta);
        let z2 = z1 * z1;
        (z1 * self.b[1] + z2 * self.b[2] + self.b[0]) / (z1 * self.a[0] + z2 * self.a[1] + 1.0)
    }
}

/// The analog factors N(s)/D(s) of a weighting (D monic of degree 2, ascending coefficients) with the
/// natural frequency ω_p of each denominator, in the order H_h, H_l, H_t, H_s (absent factors omitted).
fn analog_factors(w: Weighting) -> Vec<([f64; 3], [f64; 3], f64)> {
    let p = w.parameters();
    let (w1, w2) = (TAU * p.f1_hz, TAU * p.f2_hz);
    let mut out = vec![
        ([0.0, 0.0, 1.0], [w1 * w1, w1 / p.q1, 1.0], w1),
        ([w2 * w2, 0.0, 0.0], [w2 * w2, w2 / p.q2, 1.0], w2),
    ];
    if p.f4_hz.is_finite() {
        // (1 + s/ω₃)/(1 + s/(Q₄ω₄) + s²/ω₄²) = (ω₄² + (ω₄²/ω₃)s)/(s² + ω₄s/Q₄ + ω₄²)
        let w4 = TAU * p.f4_hz;
        let n1 = if p.f3_hz.is_finite() {
            w4 * w4 / (TAU * p.f3_hz)
        } else {
            0.0
        };
        out.push(([w4 * w4, n1, 0.0], [w4 * w4, w4 / p.q4, 1.0], w4));
    }
    if p.f5_hz.is_finite() && p.f6_hz.is_finite() {
        // (1 + s/(Q₅ω₅) + s²/ω₅²)/(1 + s/(Q₆ω₆) + s²/ω₆²)·(ω₅/ω₆)² = (s² + ω₅s/Q₅ + ω₅²)/(s² + ω₆s/Q₆ + ω₆²)
        let (w5, w6) = (TAU * p.f5_hz, TAU * p.f6_hz);
        out.push(([w5 * w5, w5 / p.q5, 1.0], [w6 * w6, w6 / p.q6, 1.0], w6));
    }
    out
}

/// One row of [`DigitalWeighting::error_table`]: the analytic and the digital weighting at a frequency.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct WeightingErrorRow {
    /// Frequency, Hz.
    pub frequency_hz: f64,
    /// |W(i2πf)| of the analytic weighting.
    pub analytic_magnitude: f64,
    /// arg W(i2πf), degrees.
    pub analytic_phase_deg: f64,
    /// |H(e^{i2πf/f_s})| of the digital filter.
    pub digital_magnitude: f64,
    /// arg H, degrees.
    pub digital_phase_deg: f64,
    /// 20·log₁₀(|H|/|W|), dB.
    pub error_db: f64,
    /// arg(H/W), degrees.
    pub phase_error_deg: f64,
}

/// A weighting realised as a digital filter at a sample rate (see the [module docs](self)).
///
/// # Formula
/// H(z) = K·∏ᵢ (b₀ᵢ + b₁ᵢz⁻¹ + b₂ᵢz⁻²)/(1 + a₁ᵢz⁻¹ + a₂ᵢz⁻²), one section per analog factor, each the
/// bilinear transform of the factor prewarped at its pole frequency.
///
/// # Errors
/// [`DigitalWeighting::new`] refuses a sample rate that is not finite and > 0, or at which a pole frequency
/// of the weighting lies at or above the Nyquist frequency (it cannot be realised: tan(ω_p/2f_s) ≤ 0), or so
/// high that the rounded coefficients give no finite response in the evaluation range (10⁹ Hz for Wk).
///
/// # Examples
/// ```
/// use stochvib::comfort::Weighting;
/// use stochvib::record::DigitalWeighting;
/// let d = DigitalWeighting::new(Weighting::Wk, 1000.0).unwrap();
/// let row = d.error_at(8.0);
/// assert!(row.error_db.abs() < 0.01); // 8 Hz at 1 kHz
/// assert!(DigitalWeighting::new(Weighting::Wk, 150.0).is_err()); // the 100 Hz pole above Nyquist
/// ```
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct DigitalWeighting {
    /// The weighting.
    pub weighting: Weighting,
    /// Sample rate f_s, Hz.
    pub sample_rate_hz: f64,
    /// The sections, in the order H_h, H_l, H_t, H_s.
    pub sections: Vec<Biquad>,
    /// The gain K.
    pub gain: f64,
}

/// The running state of a [`DigitalWeighting`] on one signal: two states per section.
#[derive(Debug, Clone, PartialEq)]
pub struct FilterState {
    state: Vec<[f64; 2]>,
}

impl DigitalWeighting {
    /// The digital filter of `weighting` at `sample_rate_hz`.
    ///
    /// # Errors
    /// See the type's `# Errors`.
    pub fn new(weighting: Weighting, sample_rate_hz: f64) -> Result<Self> {
        if !(sample_rate_hz.is_finite() && sample_rate_hz > 0.0) {
            return Err(Error::invalid(
                "sample rate",
                sample_rate_hz,
                "must be finite and > 0 Hz",
            ));
        }
        let mut sections = Vec::new();
        for (num, den, wp) in analog_factors(weighting) {
            if wp / (2.0 * sample_rate_hz) >= PI / 2.0 {
                return Err(Error::invalid(
                    "sample rate",
                    format!("{sample_rate_hz} Hz"),
                    format!(
                        "too low for {weighting}: its pole at {} Hz lies at or above the Nyquist frequency {} Hz, \
                         so the band(s) {} are lost (the weighting needs a sample rate above {} Hz, and above \
                         400 Hz to keep its 80 Hz band within {MAX_BAND_ERROR_DB} dB)",
                        crate::numbers::num(wp / TAU),
                        crate::numbers::num(sample_rate_hz / 2.0),
                        bands_above(weighting, sample_rate_hz / 2.0),
                        crate::numbers::num(wp / PI),
                    ),
                ));
            }
            sections.push(Biquad::bilinear(num, den, wp, sample_rate_hz));
        }
        let digital = DigitalWeighting {
            weighting,
            sample_rate_hz,
            sections,
            gain: weighting.parameters().gain,
        };
        digital.require_finite_response()?;
        Ok(digital)
    }

    /// Refuses a realisation whose response at a one-third-octave centre of the evaluation range is not a
    /// finite number: at a sample rate so high (10⁹ Hz for Wk) that the sections' poles lie within about
    /// (2π·0.5 Hz/f_s)² of z = 1, the coefficients rounded to f64 no longer hold the weighting.
    fn require_finite_response(&self) -> Result<()> {
        let (lo, hi) = self.weighting.evaluation_range_hz();
        let bands = bands_covering(BandFraction::ThirdOctave, lo, hi)?;
        let Some(b) = bands.iter().find(|b| !self.error_at(b.centre_hz).error_db.is_finite()) else {
            return Ok(());
        };
        Err(Error::invalid(
            "sample rate",
            format!("{} Hz", crate::numbers::num(self.sample_rate_hz)),
            format!(
                "too high for {}: its sections' poles lie so close to z = 1 that their coefficients, rounded to \
                 f64, no longer give the weighting (not a finite number at the {} band); resample the record to \
                 a lower rate (the weighting ends at {} Hz: a few kHz are plenty)",
                self.weighting,
                b.label(),
                crate::numbers::num(hi)
            ),
        ))
    }

    /// H(e^{i2πf/f_s}), the digital filter's frequency response at f (Hz).
    pub fn response(&self, f_hz: f64) -> Complex<f64> {
        let theta = TAU * f_hz / self.sample_rate_hz;
        self.sections
            .iter()
            .fold(Complex::new(self.gain, 0.0), |h, s| h * s.response(theta))
    }

    /// The analytic and the digital weighting at f (Hz), with their difference.
    ///
    /// # Formula
    /// error = 20 log₁₀(|H(e^{i2πf/f_s})|/|W(i2πf)|) dB, phase error = arg(H/W) in degrees.
    pub fn error_at(&self, f_hz: f64) -> WeightingErrorRow {
        let w = self.weighting.response(TAU * f_hz);
        let h = self.response(f_hz);
        WeightingErrorRow {
            frequency_hz: f_hz,
            analytic_magnitude: w.norm(),
            analytic_phase_deg: w.arg().to_degrees(),
            digital_magnitude: h.norm(),
            digital_phase_deg: h.arg().to_degrees(),
            error_db: 20.0 * (h.norm() / w.norm()).log10(),
            phase_error_deg: (h / w).arg().to_degrees(),
        }
    }

    /// [`DigitalWeighting::error_at`] at the exact centre of every one-third-octave band from `f_lo` to
    /// `f_hi` (Hz) whose upper edge lies below the Nyquist frequency.
    ///
    /// # Errors
    /// The errors of [`bands_covering`].
    pub fn error_table(&self, f_lo_hz: f64, f_hi_hz: f64) -> Result<Vec<WeightingErrorRow>> {
        Ok(bands_covering(BandFraction::ThirdOctave, f_lo_hz, f_hi_hz)?
            .iter()
            .filter(|b| b.upper_hz < self.sample_rate_hz / 2.0)
            .map(|b| self.error_at(b.centre_hz))
            .collect())
    }

    /// Checks that every one-third-octave band of the evaluation range ([`Weighting::evaluation_range_hz`]) survives
    /// the sampling: its upper edge below the Nyquist frequency and the digital error at its centre within
    /// [`MAX_BAND_ERROR_DB`].
    ///
    /// # Errors
    /// [`Error::InvalidParameter`] naming `sample rate`, the lost bands and why.
    pub fn check_bands(&self) -> Result<Vec<Band>> {
        let (lo, hi) = self.weighting.evaluation_range_hz();
        let bands = bands_covering(BandFraction::ThirdOctave, lo, hi)?;
        let mut lost = Vec::new();
        for b in &bands {
            if b.upper_hz >= self.sample_rate_hz / 2.0 {
                lost.push(format!("{} (above the Nyquist frequency)", b.label()));
            } else {
                let e = self.error_at(b.centre_hz).error_db;
                if e.is_nan() || e.abs() > MAX_BAND_ERROR_DB {
                    lost.push(format!("{} ({e:+.2} dB)", b.label()));
                }
            }
        }
        if lost.is_empty() {
            return Ok(bands);
        }
        Err(Error::invalid(
            "sample rate",
            format!("{} Hz", self.sample_rate_hz),
            format!(
                "too low for {} ({} to {} Hz): the band(s) {} are lost (a band needs its upper edge below the Nyquist \
                 frequency and the digital weighting within {MAX_BAND_ERROR_DB} dB of the analytic one at its centre)",
                self.weighting,
                lo,
                hi,
                lost.join(", ")
            ),
        ))
    }

    /// A fresh (zero) state.
    pub fn state(&self) -> FilterState {
        FilterState {
            state: vec![[0.0; 2]; self.sections.len()],
        }
    }

    /// The state of the filter at rest under a constant input `x0` held since t = −∞ (every section at its
    /// steady state; the output is K·H(1)·x0, which is 0 for a weighting: its high pass removes a constant).
    /// Starting a record from this state keeps a constant offset of the first sample (gravity on a z
    /// accelerometer, a static stress) from ringing through the high pass as a step (as scipy's
    /// `sosfilt_zi(sos)·x[0]` does).
    ///
    /// # Formula
    /// Section by section with input u (the previous section's steady output): y = g·u with
    /// g = (b₀ + b₁ + b₂)/(1 + a₁ + a₂), s₁ = y − b₀u, s₂ = b₂u − a₂y.
    pub fn state_at_rest(&self, x0: f64) -> FilterState {
        let mut u = x0;
        let state = self
            .sections
            .iter()
            .map(|q| {
                let y = (q.b[0] + q.b[1] + q.b[2]) / (1.0 + q.a[0] + q.a[1]) * u;
                let s = [y - q.b[0] * u, q.b[2] * u - q.a[1] * y];
                u = y;
                s
            })
            .collect();
        FilterState { state }
    }

    /// Filters `x` into `y` (same length), continuing from `state`.
    ///
    /// # Formula
    /// Per section, transposed direct form II: y = b₀x + s₁, s₁ ← b₁x − a₁y + s₂, s₂ ← b₂x − a₂y; the
    /// sections of one sample in series, then the gain K.
    ///
    /// # Panics
    /// If `y` is shorter than `x` or `state` belongs to another filter.
    pub fn filter(&self, state: &mut FilterState, x: &[f64], y: &mut [f64]) {
        assert!(y.len() >= x.len() && state.state.len() == self.sections.len());
        let y = &mut y[..x.len()];
        match self.sections.len() {
            2 => cascade::<2>(&self.sections, &mut state.state, self.gain, x, y),
            3 => cascade::<3>(&self.sections, &mut state.state, self.gain, x, y),
            4 => cascade::<4>(&self.sections, &mut state.state, self.gain, x, y),
            _ => unreachable!("a weighting has 2 to 4 sections"),
        }
    }
}

/// The labels of the one-third-octave bands of `weighting`'s evaluation range whose upper edge is at or
/// above `nyquist_hz` (or, when none is, of its top band: a pole above the Nyquist frequency distorts it).
fn bands_above(weighting: Weighting, nyquist_hz: f64) -> String {
    let (lo, hi) = weighting.evaluation_range_hz();
    let bands = bands_covering(BandFraction::ThirdOctave, lo, hi).unwrap_or_default();
    let lost: Vec<String> = bands
        .iter()
        .filter(|b| b.upper_hz >= nyquist_hz)
        .map(|b| b.label())
        .collect();
    match (lost.is_empty(), bands.last()) {
        (false, _) => lost.join(", "),
        (true, Some(top)) => top.label(),
        (true, None) => format!("up to {hi} Hz"),
    }
}

/// N sections in series over a block, sample by sample (so that the sections of consecutive samples
/// overlap in the processor's pipeline).
#[inline(always)]
fn cascade<const N: usize>(sections: &[Biquad], state: &mut [[f64; 2]], gain: f64, x: &[f64], y: &mut [f64]) {
    let secs: [Biquad; N] = std::array::from_fn(|i| sections[i]);
    let mut s: [[f64; 2]; N] = std::array::from_fn(|i| state[i]);
    for (xi, yi) in x.iter().zip(y.iter_mut()) {
        let mut v = *xi;
        for k in 0..N {
            let q = &secs[k];
            let out = q.b[0] * v + s[k][0];
            s[k][0] = q.b[1] * v - q.a[0] * out + s[k][1];
            s[k][1] = q.b[2] * v - q.a[1] * out;
            v = out;
        }
        *yi = gain * v;
    }
    state.copy_from_slice(&s);
}
