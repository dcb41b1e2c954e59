//! Spectral moments of the one-sided density in Hz, the input of every spectral fatigue method.

use crate::error::{Error, Result};
use crate::numbers::num;
use crate::quad::{integrate, QuadOptions};
use crate::spectrum::{Asymptote, Domain, Spectrum};
use std::cell::Cell;
use std::f64::consts::PI;

/// Relative tolerance of the moment quadratures.
const REL_TOL: f64 = 1e-10;

/// Relative slack allowed in the Cauchy–Schwarz checks m₁² ≤ m₀m₂, m₂² ≤ m₀m₄ (rounding of moments
/// computed by quadrature, or of a pure tone whose bandwidth parameters are exactly 1).
const CONSISTENCY_SLACK: f64 = 1e-9;

/// Spectral moments m_j = ∫₀^∞ f^j G(f) df of the **one-sided density in Hz** G(f) of a stationary
/// Gaussian stress process (unit²/Hz), for j = 0, 1, 2, 4 and optionally the fractional j = 0.75, 1.5.
///
/// # Formula
/// ```text
/// m_j = ∫₀^∞ f^j G(f) df                          (f in Hz; m_j in unit²·Hz^j)
/// G(f) = 4π S(2πf)                                (S: the crate's two-sided density in rad/s)
/// m_j = (2π)^{−j} λ_j,  λ_j = ∫_{−∞}^{∞} |ω|^j S(ω) dω = 2∫₀^∞ ω^j S(ω) dω
/// ν₀⁺ = √(m₂/m₀)  (mean rate of zero up-crossings, 1/s),   ν_p = √(m₄/m₂)  (rate of peaks, 1/s)
/// α_i = m_i / √(m₀ m_{2i})   (bandwidth parameters: α₁, α₂, α₀.₇₅),   ε = √(1 − α₂²)
/// x_m = (m₁/m₀)·√(m₂/m₄)     (Dirlik's mean-frequency parameter; x_m = α₁α₂)
/// ```
/// Derivation of the conversion: with ω = 2πf, ∫₀^∞ f^j G(f) df = ∫₀^∞ (ω/2π)^j 4π S(ω) dω/(2π)
/// = (2π)^{−j}·2∫₀^∞ ω^j S(ω) dω. Papers that use the one-sided density in ω, G(ω) = 2S(ω), have
/// m_j^{(ω)} = λ_j and rates ν = √(λ₂/λ₀)/(2π).
///
/// # Errors
/// Constructors reject negative, zero or non-finite moments (naming `m0`, `m1`, `m2`, `m4`, `m0_75` or
/// `m1_5`, the value and the reason; m₀ = 0 is a process without fluctuation and has no fatigue rate), and
/// moments that no density can have (m₁² > m₀m₂ or m₂² > m₀m₄ beyond rounding).
///
/// # Examples
/// ```
/// use stochvib::fatigue::{SpectralMoments, TwoSidedAngularMoments};
/// // Ideal band-limited white noise G = 2 unit²/Hz on [10, 20] Hz: m_j = 2 (20^{j+1} − 10^{j+1})/(j+1).
/// let m = SpectralMoments::from_one_sided_hz_with_fractional(|_f| 2.0, 10.0, 20.0, &[]).unwrap();
/// assert!((m.m0() - 20.0).abs() < 1e-9);
/// assert!((m.m2() - 2.0 * (8000.0 - 1000.0) / 3.0).abs() < 1e-6);
/// assert!((m.m0_75().unwrap() - 2.0 * (20f64.powf(1.75) - 10f64.powf(1.75)) / 1.75).abs() < 1e-8);
/// // The same moments from the crate's two-sided angular moments λ_j = (2π)^j m_j.
/// let w = 2.0 * std::f64::consts::PI;
/// let (lambda0, lambda1, lambda2, lambda4) = (m.m0(), w * m.m1(), w.powi(2) * m.m2(), w.powi(4) * m.m4());
/// let m2 = TwoSidedAngularMoments { lambda0, lambda1, lambda2, lambda4 }.build().unwrap();
/// assert!((m2.nu0_plus() - m.nu0_plus()).abs() < 1e-12);
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SpectralMoments {
    m0: f64,
    m1: f64,
    m2: f64,
    m4: f64,
    m0_75: Option<f64>,
    m1_5: Option<f64>,
}

fn positive(name: &str, v: f64) -> Result<f64> {
    if v.is_nan() || v.is_infinite() {
        return Err(Error::invalid(name, v, "a spectral moment must be finite"));
    }
    if v < 0.0 {
        return Err(Error::invalid(
            name,
            v,
            "a spectral moment of a density is never negative",
        ));
    }
    if v == 0.0 {
        return Err(Error::invalid(
            name,
            v,
            "must be > 0 (m0 = 0 is a process without fluctuation; m1, m2, m4 = 0 leave no cycles): no fatigue \
             rate can be formed",
        ));
    }
    Ok(v)
}

/// Checks a² ≤ b·c (Cauchy–Schwarz for moments) up to rounding.
fn schwarz(name: &str, a: f64, b: f64, c: f64, what: &str) -> Result<()> {
    if a * a > b * c * (1.0 + CONSISTENCY_SLACK) {
        return Err(Error::invalid(
            name,
            a,
            format!("{what}: no density has these moments (Cauchy-Schwarz); check the units and the one-sided Hz convention"),
        ));
    }
    Ok(())
}

/// The moments m₀, m₁, m₂, m₄ of a one-sided density in Hz, from which [`SpectralMoments`] is built.
///
/// # Formula
/// m_j = ∫₀^∞ f^j G(f) df; consistency m₁² ≤ m₀m₂ and m₂² ≤ m₀m₄.
///
/// # Examples
/// ```
/// use stochvib::fatigue::OneSidedHzMoments;
/// let m = OneSidedHzMoments { m0: 1.0, m1: 50.0, m2: 2600.0, m4: 7.0e6 }.build().unwrap();
/// assert!((m.nu0_plus() - 2600f64.sqrt()).abs() < 1e-12);
/// let e = OneSidedHzMoments { m0: 0.0, m1: 50.0, m2: 2600.0, m4: 7.0e6 }.build().unwrap_err().to_string();
/// assert!(e.contains("`m0`"));
/// assert!(OneSidedHzMoments { m0: 1.0, m1: f64::NAN, m2: 2600.0, m4: 7.0e6 }.build().is_err());
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct OneSidedHzMoments {
    /// m₀, unit².
    pub m0: f64,
    /// m₁, unit²·Hz.
    pub m1: f64,
    /// m₂, unit²·Hz².
    pub m2: f64,
    /// m₄, unit²·Hz⁴.
    pub m4: f64,
}

impl OneSidedHzMoments {
    /// The moments, validated.
    ///
    /// # Errors
    /// See [`SpectralMoments`].
    pub fn build(self) -> Result<SpectralMoments> {
        let OneSidedHzMoments { m0, m1, m2, m4 } = self;
        let m0 = positive("m0", m0)?;
        let m1 = positive("m1", m1)?;
        let m2 = positive("m2", m2)?;
        let m4 = positive("m4", m4)?;
        schwarz("m1", m1, m0, m2, "m1^2 > m0*m2")?;
        schwarz("m2", m2, m0, m4, "m2^2 > m0*m4")?;
        Ok(SpectralMoments {
            m0,
            m1,
            m2,
            m4,
            m0_75: None,
            m1_5: None,
        })
    }
}

/// The crate's two-sided angular moments λ_j = ∫_{−∞}^{∞} |ω|^j S(ω) dω (ω in rad/s), from which
/// [`SpectralMoments`] is built.
///
/// # Formula
/// m_j = (2π)^{−j} λ_j (see [`SpectralMoments`] for the derivation).
///
/// # Examples
/// ```
/// use stochvib::fatigue::TwoSidedAngularMoments;
/// use std::f64::consts::PI;
/// // Variance 1, all power at ω = 20π rad/s (10 Hz): λ_j = (20π)^j.
/// let w0: f64 = 20.0 * PI;
/// let m = TwoSidedAngularMoments { lambda0: 1.0, lambda1: w0, lambda2: w0 * w0, lambda4: w0.powi(4) }
///     .build()
///     .unwrap();
/// assert!((m.nu0_plus() - 10.0).abs() < 1e-12);
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TwoSidedAngularMoments {
    /// λ₀, unit².
    pub lambda0: f64,
    /// λ₁, unit²·rad/s.
    pub lambda1: f64,
    /// λ₂, unit²·(rad/s)².
    pub lambda2: f64,
    /// λ₄, unit²·(rad/s)⁴.
    pub lambda4: f64,
}

impl TwoSidedAngularMoments {
    /// The one-sided moments in Hz m_j = (2π)^{−j} λ_j, validated.
    ///
    /// # Errors
    /// As [`OneSidedHzMoments::build`] (the names are those of the converted moments `m0`…`m4`).
    pub fn build(self) -> Result<SpectralMoments> {
        let w = 2.0 * PI;
        OneSidedHzMoments {
            m0: self.lambda0,
            m1: self.lambda1 / w,
            m2: self.lambda2 / (w * w),
            m4: self.lambda4 / (w * w * w * w),
        }
        .build()
    }
}

impl SpectralMoments {
    /// Adds given fractional moments m₀.₇₅ and m₁.₅ (one-sided, Hz), needed by
    /// [`ZhaoBakerVariant::K3`](crate::fatigue::ZhaoBakerVariant::K3).
    ///
    /// # Formula
    /// m_j = ∫₀^∞ f^j G(f) df = (2π)^{−j} λ_j for j = 0.75, 1.5; consistency m₀.₇₅² ≤ m₀m₁.₅.
    ///
    /// # Errors
    /// As [`OneSidedHzMoments::build`], naming `m0_75` or `m1_5`.
    ///
    /// # Examples
    /// ```
    /// use stochvib::fatigue::OneSidedHzMoments;
    /// // A pure tone of variance 1 at 10 Hz: m_j = 10^j, every α = 1.
    /// let m = OneSidedHzMoments { m0: 1.0, m1: 10.0, m2: 100.0, m4: 1e4 }
    ///     .build()
    ///     .unwrap()
    ///     .with_fractional(10f64.powf(0.75), 10f64.powf(1.5))
    ///     .unwrap();
    /// assert!((m.alpha_0_75().unwrap() - 1.0).abs() < 1e-12);
    /// ```
    pub fn with_fractional(mut self, m0_75: f64, m1_5: f64) -> Result<Self> {
        let a = positive("m0_75", m0_75)?;
        let b = positive("m1_5", m1_5)?;
        schwarz("m0_75", a, self.m0, b, "m0_75^2 > m0*m1_5")?;
        self.m0_75 = Some(a);
        self.m1_5 = Some(b);
        Ok(self)
    }

    /// Moments m₀, m₁, m₂, m₄ of a one-sided density in Hz given as a closure `density(f)` (unit²/Hz,
    /// f in Hz) on the band [`f_lo`, `f_hi`] (`f_hi` may be +∞), by adaptive Gauss–Kronrod quadrature
    /// ([`crate::quad`], relative tolerance 1e-10) with optional `breakpoints` (Hz: peaks, band edges
    /// inside the band). [`SpectralMoments::from_one_sided_hz_with_fractional`] adds m₀.₇₅ and m₁.₅.
    ///
    /// # Formula
    /// m_j = ∫_{f_lo}^{f_hi} f^j G(f) df, j ∈ {0, 1, 2, 4}.
    ///
    /// # Errors
    /// [`Error::InvalidParameter`] naming `band` unless 0 ≤ f_lo < f_hi, or `density` when it returns a
    /// negative or non-finite value at some frequency (which is named); [`Error::Quadrature`] when a
    /// moment does not converge (e.g. m₄ of a density decaying no faster than f⁻⁵ on an infinite band);
    /// then as [`OneSidedHzMoments::build`].
    ///
    /// # Examples
    /// ```
    /// use stochvib::fatigue::SpectralMoments;
    /// // G(f) = e^{−f} on [0, ∞): m_j = Γ(j + 1).
    /// let m = SpectralMoments::from_one_sided_hz(|f| (-f).exp(), 0.0, f64::INFINITY, &[]).unwrap();
    /// assert!((m.m4() - 24.0).abs() < 1e-8);
    /// assert_eq!(m.m0_75(), None);
    /// ```
    pub fn from_one_sided_hz(density: impl Fn(f64) -> f64, f_lo: f64, f_hi: f64, breakpoints: &[f64]) -> Result<Self> {
        quadrature_moments(density, f_lo, f_hi, breakpoints, false)
    }

    /// As [`SpectralMoments::from_one_sided_hz`], with the fractional moments m₀.₇₅ and m₁.₅ too (two more
    /// quadratures; needed by [`ZhaoBakerVariant::K3`](crate::fatigue::ZhaoBakerVariant::K3)).
    ///
    /// # Formula
    /// m_j = ∫_{f_lo}^{f_hi} f^j G(f) df, j ∈ {0, 0.75, 1, 1.5, 2, 4}.
    ///
    /// # Errors
    /// As [`SpectralMoments::from_one_sided_hz`].
    ///
    /// # Examples
    /// ```
    /// use stochvib::fatigue::SpectralMoments;
    /// let m = SpectralMoments::from_one_sided_hz_with_fractional(|f| (-f).exp(), 0.0, f64::INFINITY, &[]).unwrap();
    /// assert!((m.m1_5().unwrap() - 1.329_340_388_179_137).abs() < 1e-9); // Γ(2.5) = 3√π/4
    /// ```
    pub fn from_one_sided_hz_with_fractional(
        density: impl Fn(f64) -> f64,
        f_lo: f64,
        f_hi: f64,
        breakpoints: &[f64],
    ) -> Result<Self> {
        quadrature_moments(density, f_lo, f_hi, breakpoints, true)
    }

    /// Moments m₀, m₁, m₂, m₄ (and m₀.₇₅, m₁.₅ when `fractional`) of a **tabulated** one-sided density in
    /// Hz, e.g. a measured (Welch) estimate: frequencies `f` (Hz, strictly increasing, ≥ 0) and values `g`
    /// (unit²/Hz, ≥ 0), taken as the piecewise-linear interpolant between the points (zero outside).
    ///
    /// # Formula
    /// m_j = Σ_i ∫_{f_i}^{f_{i+1}} f^j ĝ(f) df with ĝ linear on each interval. For j = 0, 1, 2, 4 each
    /// interval's integral is taken in closed form, with s = f_i + f_{i+1} (twice the midpoint),
    /// h = f_{i+1} − f_i, P = (g_i + g_{i+1})·h and D = (g_{i+1} − g_i)·h²:
    /// ```text
    /// ∫ ĝ    = P/2
    /// ∫ f ĝ  = (P s + D/3)/4
    /// ∫ f² ĝ = (P (s² + h²/3) + (2/3) D s)/8
    /// ∫ f⁴ ĝ = (P ((s² + h²)² − (4/5) h⁴) + D s ((4/3) s² + (4/5) h²))/32
    /// ```
    /// (expand f^j = (s/2 + u)^j about the midpoint and integrate u^k over [−h/2, h/2]: odd k multiply the
    /// slope). Since ĝ ≥ 0 at both ends, |D| ≤ P·h and h ≤ s: the D terms cancel at most two thirds of the
    /// P terms (the worst case, at f_i = 0), so each interval is accurate to a few roundings. For j = 0.75,
    /// 1.5 (not polynomials) each interval is integrated by the 3-point Gauss–Legendre rule, whose error is
    /// O(h⁶) per interval (negligible away from f = 0).
    ///
    /// # Errors
    /// [`Error::InvalidParameter`] naming `f` (fewer than 2 points, a length different from `g`'s, a
    /// negative, non-finite or non-increasing frequency, with its index) or `g` (a negative or non-finite
    /// value, with its index); then as [`OneSidedHzMoments::build`].
    ///
    /// # Examples
    /// ```
    /// use stochvib::fatigue::SpectralMoments;
    /// // A ramp G = f on [0, 10] Hz: m_j = 10^{j+2}/(j + 2), exactly.
    /// let f: Vec<f64> = (0..=10).map(|i| i as f64).collect();
    /// let m = SpectralMoments::from_tabulated_one_sided_hz(&f, &f, false).unwrap();
    /// assert!((m.m4() - 1e6 / 6.0).abs() < 1e-9);
    /// assert!(SpectralMoments::from_tabulated_one_sided_hz(&[1.0, 1.0], &[1.0, 1.0], false).is_err());
    /// ```
    pub fn from_tabulated_one_sided_hz(f: &[f64], g: &[f64], fractional: bool) -> Result<Self> {
        if f.len() < 2 || f.len() != g.len() {
            return Err(Error::invalid(
                "f",
                format!("{} points ({} values)", f.len(), g.len()),
                "a tabulated density needs at least 2 frequencies and one value per frequency",
            ));
        }
        // One branch-free pass checks the table while it integrates it; the culprit is located only when
        // something is wrong.
        let (acc, ok) = linear_table_moments(f, g);
        for (i, (&fi, &gi)) in f.iter().zip(g).enumerate().filter(|_| !ok) {
            if !(fi.is_finite() && fi >= 0.0) || (i > 0 && fi <= f[i - 1]) {
                return Err(Error::invalid(
                    "f",
                    fi,
                    format!("frequency {i}: frequencies must be finite, >= 0 and strictly increasing (Hz)"),
                ));
            }
            if !(gi.is_finite() && gi >= 0.0) {
                return Err(Error::invalid(
                    "g",
                    gi,
                    format!("value {i} (at f = {} Hz): a density must be finite and >= 0", num(fi)),
                ));
            }
        }
        let m = OneSidedHzMoments {
            m0: acc[0],
            m1: acc[1],
            m2: acc[2],
            m4: acc[3],
        }
        .build()?;
        if fractional {
            let frac = gauss3_fractional_moments(f, g);
            m.with_fractional(frac[0], frac[1])
        } else {
            Ok(m)
        }
    }

    /// Moments of a temporal [`Spectrum`] (the crate's two-sided S(ω), rad/s) over the band
    /// [`f_lo`, `f_hi`] in Hz (`f_hi` may be +∞), by quadrature of G(f) = 4π S(2πf), with the spectrum's
    /// breakpoints.
    ///
    /// # Formula
    /// m_j = ∫_{f_lo}^{f_hi} f^j 4π S(2πf) df, j ∈ {0, 1, 2, 4}.
    ///
    /// # Errors
    /// [`Error::NotApplicable`] for a spatial spectrum (convert it with
    /// [`AtSpeed`](crate::spectrum::AtSpeed) first); [`Error::Divergent`] naming m₄ when `f_hi` is infinite
    /// and S(ω) decays no faster than |ω|⁻⁵ (then give a finite band); otherwise as
    /// [`SpectralMoments::from_one_sided_hz`].
    ///
    /// # Examples
    /// ```
    /// use stochvib::fatigue::SpectralMoments;
    /// use stochvib::spectrum::{Domain, Gaussian, Spectrum};
    /// let s = Gaussian::new(4.0, 100.0, Domain::Temporal).unwrap(); // K = 4 e^{−100 τ²}
    /// let m = SpectralMoments::from_spectrum(&s, 0.0, f64::INFINITY).unwrap();
    /// assert!((m.m0() - 4.0).abs() < 1e-8);
    /// ```
    pub fn from_spectrum(spectrum: &dyn Spectrum, f_lo: f64, f_hi: f64) -> Result<Self> {
        spectrum_moments(spectrum, f_lo, f_hi, false)
    }

    /// As [`SpectralMoments::from_spectrum`], with the fractional moments m₀.₇₅ and m₁.₅ too.
    ///
    /// # Formula
    /// m_j = ∫_{f_lo}^{f_hi} f^j 4π S(2πf) df, j ∈ {0, 0.75, 1, 1.5, 2, 4}.
    ///
    /// # Errors
    /// As [`SpectralMoments::from_spectrum`].
    ///
    /// # Examples
    /// ```
    /// use stochvib::fatigue::SpectralMoments;
    /// use stochvib::spectrum::{Domain, Gaussian};
    /// let s = Gaussian::new(4.0, 100.0, Domain::Temporal).unwrap();
    /// let m = SpectralMoments::from_spectrum_with_fractional(&s, 0.0, f64::INFINITY).unwrap();
    /// assert!(m.alpha_0_75().unwrap() < 1.0);
    /// ```
    pub fn from_spectrum_with_fractional(spectrum: &dyn Spectrum, f_lo: f64, f_hi: f64) -> Result<Self> {
        spectrum_moments(spectrum, f_lo, f_hi, true)
    }

    /// m₀ = variance (unit²).
    pub fn m0(&self) -> f64 {
        self.m0
    }
    /// m₁ (unit²·Hz).
    pub fn m1(&self) -> f64 {
        self.m1
    }
    /// m₂ (unit²·Hz²).
    pub fn m2(&self) -> f64 {
        self.m2
    }
    /// m₄ (unit²·Hz⁴).
    pub fn m4(&self) -> f64 {
        self.m4
    }
    /// m₀.₇₅ (unit²·Hz^0.75), if given.
    pub fn m0_75(&self) -> Option<f64> {
        self.m0_75
    }
    /// m₁.₅ (unit²·Hz^1.5), if given.
    pub fn m1_5(&self) -> Option<f64> {
        self.m1_5
    }

    /// Mean rate of zero up-crossings ν₀⁺ = √(m₂/m₀) (1/s).
    pub fn nu0_plus(&self) -> f64 {
        (self.m2 / self.m0).sqrt()
    }

    /// Mean rate of peaks (local maxima) ν_p = √(m₄/m₂) (1/s).
    pub fn nu_peak(&self) -> f64 {
        (self.m4 / self.m2).sqrt()
    }

    /// α₁ = m₁/√(m₀m₂) ∈ (0, 1] (clamped to 1 against rounding).
    pub fn alpha1(&self) -> f64 {
        (self.m1 / (self.m0 * self.m2).sqrt()).min(1.0)
    }

    /// α₂ = m₂/√(m₀m₄) = ν₀⁺/ν_p ∈ (0, 1] (irregularity factor; clamped to 1 against rounding).
    pub fn alpha2(&self) -> f64 {
        (self.m2 / (self.m0 * self.m4).sqrt()).min(1.0)
    }

    /// α₀.₇₅ = m₀.₇₅/√(m₀m₁.₅), when the fractional moments are given.
    pub fn alpha_0_75(&self) -> Option<f64> {
        match (self.m0_75, self.m1_5) {
            (Some(a), Some(b)) => Some((a / (self.m0 * b).sqrt()).min(1.0)),
            _ => None,
        }
    }

    /// Spectral width ε = √(1 − α₂²) (Wirsching–Light's parameter; 0 for a pure tone).
    pub fn epsilon(&self) -> f64 {
        let a = self.alpha2();
        (1.0 - a * a).max(0.0).sqrt()
    }

    /// Dirlik's x_m = (m₁/m₀)·√(m₂/m₄) (= α₁α₂).
    pub fn x_m(&self) -> f64 {
        ((self.m1 / self.m0) * (self.m2 / self.m4).sqrt()).min(1.0)
    }

    /// One-line description.
    pub fn describe(&self) -> String {
        format!(
            "one-sided Hz moments m0 = {}, m1 = {}, m2 = {}, m4 = {}; nu0+ = {} 1/s, nu_p = {} 1/s, alpha1 = {}, \
             alpha2 = {}",
            num(self.m0),
            num(self.m1),
            num(self.m2),
            num(self.m4),
            num(self.nu0_plus()),
            num(self.nu_peak()),
            num(self.alpha1()),
            num(self.alpha2())
        )
    }
}

/// Moments of a temporal spectrum by quadrature of G(f) = 4π S(2πf) (see `from_spectrum`).
fn spectrum_moments(spectrum: &dyn Spectrum, f_lo: f64, f_hi: f64, fractional: bool) -> Result<SpectralMoments> {
    if spectrum.domain() != Domain::Temporal {
        return Err(Error::NotApplicable {
            method: "spectral fatigue moments".into(),
            reason: format!(
                "{} is a spatial spectrum (rad/m); convert it to time at a speed (AtSpeed) first",
                spectrum.describe()
            ),
        });
    }
    if f_hi.is_infinite() {
        let (_, hi) = spectrum.support();
        if hi.is_infinite()
            && let Asymptote::Power { exponent, .. } = spectrum.high_frequency()
            && exponent >= -5.0
        {
            return Err(Error::Divergent {
                quantity: "spectral moment m4".into(),
                reason: format!(
                    "S(omega) ~ |omega|^{} at high frequency: m4 = int f^4 G df needs a decay faster than \
                             |omega|^-5; give a finite band f_hi",
                    num(exponent)
                ),
            });
        }
    }
    let (lo_w, hi_w) = spectrum.support();
    let lo = f_lo.max(lo_w / (2.0 * PI));
    let hi = f_hi.min(hi_w / (2.0 * PI));
    let bps: Vec<f64> = spectrum.breakpoints().iter().map(|w| w.abs() / (2.0 * PI)).collect();
    quadrature_moments(|f| 4.0 * PI * spectrum.density(2.0 * PI * f), lo, hi, &bps, fractional)
}

/// Moments m₀, m₁, m₂, m₄ (and m₀.₇₅, m₁.₅) of a one-sided Hz density by adaptive quadrature.
fn quadrature_moments(
    density: impl Fn(f64) -> f64,
    f_lo: f64,
    f_hi: f64,
    breakpoints: &[f64],
    fractional: bool,
) -> Result<SpectralMoments> {
    if !(f_lo >= 0.0 && f_hi > f_lo) || f_lo.is_infinite() || f_hi.is_nan() {
        return Err(Error::invalid(
            "band",
            format!("[{f_lo}, {f_hi}] Hz"),
            "need 0 <= f_lo < f_hi (f_hi may be infinite)",
        ));
    }
    let bad: Cell<Option<(f64, f64)>> = Cell::new(None);
    let g = |f: f64| {
        let v = density(f);
        if !(v.is_finite() && v >= 0.0) {
            if bad.get().is_none() {
                bad.set(Some((f, v)));
            }
            return 0.0;
        }
        v
    };
    let mut bps: Vec<f64> = breakpoints
        .iter()
        .copied()
        .filter(|b| b.is_finite() && *b > f_lo && *b < f_hi)
        .collect();
    bps.sort_by(f64::total_cmp);
    bps.dedup();
    let opts = QuadOptions {
        rel_tol: REL_TOL,
        breakpoints: bps,
        max_subintervals: 4000,
        ..QuadOptions::default()
    };
    let check = |r: Result<crate::quad::QuadResult>| -> Result<f64> {
        if let Some((f, v)) = bad.get() {
            return Err(Error::invalid(
                "density",
                v,
                format!("the one-sided density at f = {} Hz must be finite and >= 0", num(f)),
            ));
        }
        r.map(|r| r.value)
    };
    // Integer powers by multiplication (powf only for the fractional moments).
    let m0 = check(integrate(g, f_lo, f_hi, &opts))?;
    let m1 = check(integrate(|f: f64| f * g(f), f_lo, f_hi, &opts))?;
    let m2 = check(integrate(|f: f64| f * f * g(f), f_lo, f_hi, &opts))?;
    let m4 = check(integrate(|f: f64| (f * f) * (f * f) * g(f), f_lo, f_hi, &opts))?;
    let m = OneSidedHzMoments { m0, m1, m2, m4 }.build()?;
    if !fractional {
        return Ok(m);
    }
    let frac = |j: f64| integrate(|f: f64| if f > 0.0 { f.powf(j) * g(f) } else { 0.0 }, f_lo, f_hi, &opts);
    let m0_75 = check(frac(0.75))?;
    let m1_5 = check(frac(1.5))?;
    m.with_fractional(m0_75, m1_5)
}

/// Independent accumulators per moment in [`linear_table_moments`]: eight addition chains run side by side
/// (instruction-level parallelism; the compiler packs the lanes into SIMD registers). Measured on the
/// 50 001-point table of `benches/fatigue.rs`: 8 lanes take about half the time of 4, 16 no less than 8.
const LANES: usize = 8;

/// The closed-form integrals over one interval [a, b] of the linear interpolant ĝ between g_a and g_b,
/// scaled by powers of two: [2∫ĝ, 4∫fĝ, 8∫f²ĝ, 32∫f⁴ĝ] (formulas in
/// [`SpectralMoments::from_tabulated_one_sided_hz`]).
#[inline(always)]
fn linear_interval_moments(a: f64, b: f64, ga: f64, gb: f64) -> [f64; 4] {
    const THIRD: f64 = 1.0 / 3.0;
    const TWO_THIRDS: f64 = 2.0 / 3.0;
    const FOUR_THIRDS: f64 = 4.0 / 3.0;
    const FOUR_FIFTHS: f64 = 0.8;
    let s = a + b;
    let h = b - a;
    let hh = h * h;
    let p = (ga + gb) * h;
    let d = (gb - ga) * hh;
    let s2 = s * s;
    let ds = d * s;
    let t = s2 + hh;
    [
        p,
        p * s + d * THIRD,
        p * (s2 + hh * THIRD) + ds * TWO_THIRDS,
        p * (t * t - FOUR_FIFTHS * (hh * hh)) + ds * (FOUR_THIRDS * s2 + FOUR_FIFTHS * hh),
    ]
}

/// [m₀, m₁, m₂, m₄] of the piecewise-linear interpolant of a table: the closed-form integral of every
/// interval ([`linear_interval_moments`]), summed in [`LANES`] interleaved accumulators per moment (the
/// intervals i ≡ l mod `LANES` go to lane l), the lanes added in order at the end and the powers of two
/// divided out. One pass, no division, no powf. The same pass checks the table: the `bool` is true when
/// every frequency is ≥ 0 and strictly increasing, every value ≥ 0, and the sums are finite (a NaN or an
/// infinity anywhere makes them NaN or infinite, since every interval's m₀ term (g_a + g_b)·h carries its
/// two frequencies and values); when false the sums mean nothing.
fn linear_table_moments(f: &[f64], g: &[f64]) -> ([f64; 4], bool) {
    let n = f.len().min(g.len()).saturating_sub(1);
    let (fa, fb, ga, gb) = (&f[..n], &f[1..=n], &g[..n], &g[1..=n]);
    let mut acc = [[0.0f64; LANES]; 4];
    // running minima of min(f_i, g_i) and of f_{i+1} − f_i per lane (NaNs are left to the sums)
    let mut low = [f64::INFINITY; LANES];
    let mut step = [f64::INFINITY; LANES];
    let mut add = |l: usize, a: f64, b: f64, x: f64, y: f64| {
        let m = if x < a { x } else { a };
        low[l] = if m < low[l] { m } else { low[l] };
        let h = b - a;
        step[l] = if h < step[l] { h } else { step[l] };
        let t = linear_interval_moments(a, b, x, y);
        for j in 0..4 {
            acc[j][l] += t[j];
        }
    };
    let mut chunks = fa
        .chunks_exact(LANES)
        .zip(fb.chunks_exact(LANES))
        .zip(ga.chunks_exact(LANES).zip(gb.chunks_exact(LANES)));
    for ((a, b), (x, y)) in &mut chunks {
        for l in 0..LANES {
            add(l, a[l], b[l], x[l], y[l]);
        }
    }
    let done = n - n % LANES;
    for (l, i) in (done..n).enumerate() {
        add(l, fa[i], fb[i], ga[i], gb[i]);
    }
    let sum = |a: &[f64; LANES]| a.iter().sum::<f64>();
    let m = [
        0.5 * sum(&acc[0]),
        0.25 * sum(&acc[1]),
        0.125 * sum(&acc[2]),
        0.03125 * sum(&acc[3]),
    ];
    let last = g.get(n).copied().unwrap_or(f64::NAN);
    let ok = m.iter().all(|v| v.is_finite())
        & low.iter().all(|&v| v >= 0.0)
        & step.iter().all(|&v| v > 0.0)
        & (last >= 0.0)
        & last.is_finite()
        & (f.len() == g.len());
    (m, ok)
}

/// Σ over the intervals of a table of the 3-point Gauss–Legendre rule applied to f^j·ĝ(f) for the fractional
/// j = 0.75, 1.5, ĝ the linear interpolant: nodes a + t_k h with t = ((1 − √(3/5))/2, 1/2, (1 + √(3/5))/2),
/// weights h·(5, 8, 5)/18, where ĝ = g_a + (g_b − g_a) t_k needs no division. Returns [m₀.₇₅, m₁.₅].
fn gauss3_fractional_moments(f: &[f64], g: &[f64]) -> [f64; 2] {
    let r = 0.6f64.sqrt();
    let t = [0.5 * (1.0 - r), 0.5, 0.5 * (1.0 + r)];
    let w = [5.0 / 18.0, 8.0 / 18.0, 5.0 / 18.0];
    // One accumulator set per node: three independent addition chains instead of one.
    let mut acc = [[0.0f64; 2]; 3];
    for (fw, gw) in f.windows(2).zip(g.windows(2)) {
        let (a, h, ga, dg) = (fw[0], fw[1] - fw[0], gw[0], gw[1] - gw[0]);
        for k in 0..3 {
            let x = a + t[k] * h;
            let gx = (ga + dg * t[k]) * (w[k] * h);
            let q = x.sqrt().sqrt(); // x^0.25
            acc[k][0] += q * q * q * gx; // x^0.75
            acc[k][1] += x * x.sqrt() * gx; // x^1.5
        }
    }
    [acc[0][0] + acc[1][0] + acc[2][0], acc[0][1] + acc[1][1] + acc[2][1]]
}
