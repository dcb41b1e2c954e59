//! Frequency weightings of ISO 2631-1:1997 (Wk, Wd, Wf, Wc, We, Wj), ISO 2631-4:2001 (Wb), all as
//! specified by ISO 8041 (parameter table reproduced in the Larson Davis HVM200 Reference Manual,
//! Table 3.1, "source: ISO 8041").

use crate::error::{Error, Result};
use crate::linalg::poly;
use crate::system::{OutputInfo, StateSpace, TransferFunction};
use nalgebra::{Complex, DMatrix};
use std::f64::consts::{FRAC_1_SQRT_2, TAU};
use std::fmt;
use std::str::FromStr;

/// Quality factor Q₁ = Q₂ = 1/√2 of the band-limiting filters (second-order Butterworth).
///
/// ISO 2631-4:2001 Table A.1 prints Q₁ of Wb rounded to 0.71; ISO 8041 (its parameter table, NOTE 1)
/// states that the exact value is 1/√2, which is used here for every weighting.
pub const Q_BAND_LIMITING: f64 = FRAC_1_SQRT_2;

/// Above this |ω| (rad/s) [`Weighting::response`] evaluates its factors in u = 1/s: a complex division
/// forms the squared modulus of its denominator, ~ω⁴ for the second-order factors, which overflows f64 from
/// about 1.3·10⁷⁷ rad/s (the literal form gave NaN there); 10⁵⁰ keeps ω⁴ far from it. Below it the literal
/// form of the standard is used, unchanged.
pub const LARGE_OMEGA: f64 = 1e50;

/// A whole-body frequency weighting.
///
/// # Formula
/// Every weighting is the product of four factors (ISO 2631-1:1997 Annex A, "Mathematical definition of
/// the frequency weightings"; the same forms in ISO 8041), with s = iω, ω in rad/s, and ωᵢ = 2π fᵢ
/// (fᵢ in Hz):
///
/// ```text
/// H(s)   = K · H_h(s) · H_l(s) · H_t(s) · H_s(s)
/// H_h(s) = s² / (s² + ω₁ s/Q₁ + ω₁²)                              high pass,  Q₁ = 1/√2
/// H_l(s) = ω₂² / (s² + ω₂ s/Q₂ + ω₂²)                             low pass,   Q₂ = 1/√2
/// H_t(s) = (1 + s/ω₃) / (1 + s/(Q₄ω₄) + s²/ω₄²)                   acceleration–velocity transition
/// H_s(s) = (1 + s/(Q₅ω₅) + s²/ω₅²) / (1 + s/(Q₆ω₆) + s²/ω₆²) · (ω₅/ω₆)²      upward step
/// ```
///
/// A parameter f = ∞ drops its term: f₃ = ∞ makes the numerator of H_t equal to 1, f₄ = ∞ its
/// denominator, and f₅ = f₆ = ∞ removes H_s (H_s = 1).
///
/// **Gain normalisation of H_s.** With the factor (ω₅/ω₆)², H_s → 1 as ω → ∞ and H_s(0) = (ω₅/ω₆)²: the
/// step is normalised to unity *above* the step (for Wk, (2.37/3.35)² = 0.50 below it). Equivalently
/// H_s = (s² + ω₅s/Q₅ + ω₅²)/(s² + ω₆s/Q₆ + ω₆²), which is the monic form used for the polynomials. This
/// matches the tabulated factors of ISO 2631-1 (Wk ≈ 0.48 at 1 Hz, 1.04 at 8 Hz) and the MATLAB listing
/// of the Larson Davis HVM200 Reference Manual (`B4 = [1/w5/w5 1/Q5/w5 1]*w5*w5/w6/w6`).
///
/// Parameters (Hz), ISO 8041 / ISO 2631-1 Table A.1 / ISO 2631-4 Table A.1:
///
/// | W  | f₁   | f₂   | f₃   | f₄   | Q₄   | f₅     | Q₅   | f₆   | Q₆   | K     |
/// |----|------|------|------|------|------|--------|------|------|------|-------|
/// | Wk | 0.4  | 100  | 12.5 | 12.5 | 0.63 | 2.37   | 0.91 | 3.35 | 0.91 | 1     |
/// | Wd | 0.4  | 100  | 2    | 2    | 0.63 | ∞      |      | ∞    |      | 1     |
/// | Wc | 0.4  | 100  | 8    | 8    | 0.63 | ∞      |      | ∞    |      | 1     |
/// | We | 0.4  | 100  | 1    | 1    | 0.63 | ∞      |      | ∞    |      | 1     |
/// | Wj | 0.4  | 100  | ∞    | ∞    | 1    | 3.75   | 0.91 | 5.32 | 0.91 | 1     |
/// | Wb | 0.4  | 100  | 16   | 16   | 0.55 | 2.5    | 0.9  | 4    | 0.95 | 1.024 |
/// | Wf | 0.08 | 0.63 | ∞    | 0.25 | 0.86 | 0.0625 | 0.80 | 0.1  | 0.80 | 1     |
///
/// # Errors
/// [`Weighting::parse`] rejects unknown names; [`Weighting::transfer_function`] and
/// [`Weighting::state_space`] propagate the (never expected) failures of the system constructors.
///
/// # Examples
/// ```
/// use stochvib::comfort::Weighting;
/// let wk = Weighting::parse("wk").unwrap();
/// // ISO 2631-1:1997 Table 3: Wk at 8 Hz is 1036/1000
/// assert!((wk.magnitude(8.0) - 1.036).abs() < 0.001);
/// assert_eq!(wk.to_string(), "Wk");
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, serde::Serialize, serde::Deserialize)]
pub enum Weighting {
    /// Vertical (z) on the seat surface, z standing, vertical recumbent (except head), feet of a seated
    /// person; ISO 2631-1 principal weighting.
    Wk,
    /// Horizontal (x, y) on the seat surface, standing or recumbent; y and z seat back; ISO 2631-1
    /// principal weighting.
    Wd,
    /// x on the seat back; ISO 2631-1 additional weighting.
    Wc,
    /// Rotational (r_x, r_y, r_z) on the seat surface; ISO 2631-1 additional weighting (rad/s²).
    We,
    /// Vertical under the head of a recumbent person; ISO 2631-1 additional weighting.
    Wj,
    /// Vertical in railway vehicles; ISO 2631-4:2001.
    Wb,
    /// Vertical, motion sickness (0.1–0.5 Hz); ISO 2631-1 principal weighting.
    Wf,
}

/// Whether a weighting applies to translational or rotational acceleration.
///
/// # Formula
/// Translational weightings take and return m/s²; the rotational weighting We takes and returns rad/s²
/// (ISO 2631-1:1997, Table 2).
///
/// # Errors
/// None.
///
/// # Examples
/// ```
/// use stochvib::comfort::{Motion, Weighting};
/// assert_eq!(Weighting::Wd.quantity().motion, Motion::Translational);
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize)]
pub enum Motion {
    /// Translational acceleration, m/s².
    Translational,
    /// Rotational (angular) acceleration, rad/s².
    Rotational,
}

impl Motion {
    /// SI unit of the weighted quantity: `"m/s^2"` or `"rad/s^2"`.
    ///
    /// # Formula
    /// Translational → m/s²; rotational → rad/s².
    ///
    /// # Errors
    /// None.
    ///
    /// # Examples
    /// ```
    /// use stochvib::comfort::Motion;
    /// assert_eq!(Motion::Rotational.unit(), "rad/s^2");
    /// ```
    pub fn unit(self) -> &'static str {
        match self {
            Motion::Translational => "m/s^2",
            Motion::Rotational => "rad/s^2",
        }
    }
}

/// What a weighting is applied to, and where it is defined.
///
/// # Formula
/// None (descriptive record returned by [`Weighting::quantity`]).
///
/// # Errors
/// None.
///
/// # Examples
/// ```
/// use stochvib::comfort::Weighting;
/// assert_eq!(Weighting::Wb.quantity().standard, "ISO 2631-4:2001");
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize)]
pub struct WeightingUse {
    /// Translational or rotational acceleration.
    pub motion: Motion,
    /// SI unit of the weighted acceleration (and of the input).
    pub unit: &'static str,
    /// Typical use (direction, location, purpose).
    pub typical_use: &'static str,
    /// The standard that defines it.
    pub standard: &'static str,
}

/// The parameters of one weighting (frequencies in Hz; `f64::INFINITY` where the standard prints ∞).
///
/// # Formula
/// ωᵢ = 2πfᵢ enter H_h, H_l, H_t, H_s as in [`Weighting`]; Q₁ = Q₂ = 1/√2.
///
/// # Errors
/// None (returned by [`Weighting::parameters`]).
///
/// # Examples
/// ```
/// use stochvib::comfort::Weighting;
/// let p = Weighting::Wk.parameters();
/// assert_eq!((p.f5_hz, p.f6_hz), (2.37, 3.35));
/// ```
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct WeightingParameters {
    /// High-pass corner f₁, Hz.
    pub f1_hz: f64,
    /// High-pass quality factor Q₁ (1/√2).
    pub q1: f64,
    /// Low-pass corner f₂, Hz.
    pub f2_hz: f64,
    /// Low-pass quality factor Q₂ (1/√2).
    pub q2: f64,
    /// Transition numerator corner f₃, Hz (∞: numerator 1).
    pub f3_hz: f64,
    /// Transition denominator corner f₄, Hz (∞: denominator 1).
    pub f4_hz: f64,
    /// Transition quality factor Q₄.
    pub q4: f64,
    /// Upward-step numerator corner f₅, Hz (∞ together with f₆: no step).
    pub f5_hz: f64,
    /// Upward-step numerator quality factor Q₅.
    pub q5: f64,
    /// Upward-step denominator corner f₆, Hz.
    pub f6_hz: f64,
    /// Upward-step denominator quality factor Q₆.
    pub q6: f64,
    /// Gain K.
    pub gain: f64,
}

/// One factor N(s)/D(s) with D monic of degree 2 and deg N ≤ 2, coefficients ascending in s.
#[derive(Debug, Clone)]
pub(crate) struct Section {
    pub(crate) num: [f64; 3],
    pub(crate) den: [f64; 3],
}

impl Weighting {
    /// All weightings, in the order Wk, Wd, Wc, We, Wj, Wb, Wf.
    pub const ALL: [Weighting; 7] = [
        Weighting::Wk,
        Weighting::Wd,
        Weighting::Wc,
        Weighting::We,
        Weighting::Wj,
        Weighting::Wb,
        Weighting::Wf,
    ];

    /// Parses a weighting name, case-insensitively, with or without an underscore: `"Wk"`, `"wk"`,
    /// `"WK"`, `"W_k"`.
    ///
    /// # Formula
    /// Name lookup; no computation.
    ///
    /// # Errors
    /// [`Error::InvalidParameter`] naming `weighting`, the text and the accepted names.
    ///
    /// # Examples
    /// ```
    /// use stochvib::comfort::Weighting;
    /// assert_eq!(Weighting::parse("W_d").unwrap(), Weighting::Wd);
    /// assert!(Weighting::parse("Wz").is_err());
    /// ```
    pub fn parse(name: &str) -> Result<Weighting> {
        let key: String = name
            .trim()
            .chars()
            .filter(|c| *c != '_')
            .collect::<String>()
            .to_ascii_lowercase();
        Weighting::ALL
            .iter()
            .copied()
            .find(|w| w.name().to_ascii_lowercase() == key)
            .ok_or_else(|| {
                Error::invalid(
                    "weighting",
                    format!("\"{name}\""),
                    "unknown frequency weighting; expected one of Wk, Wd, Wc, We, Wj, Wb, Wf",
                )
            })
    }

    /// The name as printed in the standards: `"Wk"`, `"Wd"`, …
    ///
    /// # Formula
    /// None.
    ///
    /// # Errors
    /// None.
    ///
    /// # Examples
    /// ```
    /// use stochvib::comfort::Weighting;
    /// assert_eq!(Weighting::Wf.name(), "Wf");
    /// ```
    pub fn name(self) -> &'static str {
        match self {
            Weighting::Wk => "Wk",
            Weighting::Wd => "Wd",
            Weighting::Wc => "Wc",
            Weighting::We => "We",
            Weighting::Wj => "Wj",
            Weighting::Wb => "Wb",
            Weighting::Wf => "Wf",
        }
    }

    /// The parameters of the weighting (see the table in the type's `# Formula`).
    ///
    /// # Formula
    /// ISO 8041 parameter table (as reproduced in the Larson Davis HVM200 Reference Manual, Table 3.1);
    /// identical to ISO 2631-1:1997 Table A.1 and ISO 2631-4:2001 Table A.1 except that Q₁ = Q₂ = 1/√2
    /// exactly.
    ///
    /// # Errors
    /// None.
    ///
    /// # Examples
    /// ```
    /// use stochvib::comfort::Weighting;
    /// let p = Weighting::Wb.parameters();
    /// assert_eq!((p.f3_hz, p.q4, p.gain), (16.0, 0.55, 1.024));
    /// assert!(Weighting::Wj.parameters().f4_hz.is_infinite());
    /// ```
    pub fn parameters(self) -> WeightingParameters {
        let inf = f64::INFINITY;
        let q = Q_BAND_LIMITING;
        let p = |f1, f2, f3, f4, q4, f5, q5, f6, q6, gain| WeightingParameters {
            f1_hz: f1,
            q1: q,
            f2_hz: f2,
            q2: q,
            f3_hz: f3,
            f4_hz: f4,
            q4,
            f5_hz: f5,
            q5,
            f6_hz: f6,
            q6,
            gain,
        };
        match self {
            Weighting::Wk => p(0.4, 100.0, 12.5, 12.5, 0.63, 2.37, 0.91, 3.35, 0.91, 1.0),
            Weighting::Wd => p(0.4, 100.0, 2.0, 2.0, 0.63, inf, 1.0, inf, 1.0, 1.0),
            Weighting::Wc => p(0.4, 100.0, 8.0, 8.0, 0.63, inf, 1.0, inf, 1.0, 1.0),
            Weighting::We => p(0.4, 100.0, 1.0, 1.0, 0.63, inf, 1.0, inf, 1.0, 1.0),
            Weighting::Wj => p(0.4, 100.0, inf, inf, 1.0, 3.75, 0.91, 5.32, 0.91, 1.0),
            Weighting::Wb => p(0.4, 100.0, 16.0, 16.0, 0.55, 2.5, 0.9, 4.0, 0.95, 1.024),
            Weighting::Wf => p(0.08, 0.63, inf, 0.25, 0.86, 0.0625, 0.80, 0.1, 0.80, 1.0),
        }
    }

    /// What the weighting applies to (translational m/s² or rotational rad/s², We) and its typical use.
    ///
    /// # Formula
    /// ISO 2631-1:1997 Table 1 (guide to the application of the principal weightings) and Table 2
    /// (additional weightings); ISO 2631-4:2001 for Wb.
    ///
    /// # Errors
    /// None.
    ///
    /// # Examples
    /// ```
    /// use stochvib::comfort::{Motion, Weighting};
    /// assert_eq!(Weighting::We.quantity().motion, Motion::Rotational);
    /// assert_eq!(Weighting::Wk.quantity().unit, "m/s^2");
    /// ```
    pub fn quantity(self) -> WeightingUse {
        let (motion, typical_use, standard) = match self {
            Weighting::Wk => (
                Motion::Translational,
                "vertical (z): seat surface, feet of a seated person, standing; health, comfort, perception",
                "ISO 2631-1:1997",
            ),
            Weighting::Wd => (
                Motion::Translational,
                "horizontal (x, y): seat surface, standing, recumbent; y and z on the seat back",
                "ISO 2631-1:1997",
            ),
            Weighting::Wc => (
                Motion::Translational,
                "x on the seat back (fore-and-aft back-rest vibration); comfort",
                "ISO 2631-1:1997",
            ),
            Weighting::We => (
                Motion::Rotational,
                "rotational (r_x, r_y, r_z) on the seat surface; comfort",
                "ISO 2631-1:1997",
            ),
            Weighting::Wj => (
                Motion::Translational,
                "vertical under the head of a recumbent person; comfort",
                "ISO 2631-1:1997",
            ),
            Weighting::Wb => (
                Motion::Translational,
                "vertical in railway vehicles (passengers and crew); comfort",
                "ISO 2631-4:2001",
            ),
            Weighting::Wf => (
                Motion::Translational,
                "vertical, 0.1 Hz to 0.5 Hz: motion sickness (with MSDV)",
                "ISO 2631-1:1997",
            ),
        };
        WeightingUse {
            motion,
            unit: motion.unit(),
            typical_use,
            standard,
        }
    }

    /// The frequency range of an evaluation with this weighting, Hz: 0.1–0.5 Hz for motion sickness (Wf,
    /// ISO 2631-1:1997 clause 9), 0.5–80 Hz for health, comfort and perception (clause 6.4; ISO 2631-4 for
    /// Wb).
    ///
    /// # Formula
    /// None (the ranges of the standards).
    ///
    /// # Errors
    /// None.
    ///
    /// # Examples
    /// ```
    /// use stochvib::comfort::Weighting;
    /// assert_eq!(Weighting::Wf.evaluation_range_hz(), (0.1, 0.5));
    /// assert_eq!(Weighting::Wk.evaluation_range_hz(), (0.5, 80.0));
    /// ```
    pub fn evaluation_range_hz(self) -> (f64, f64) {
        match self {
            Weighting::Wf => (0.1, 0.5),
            _ => (0.5, 80.0),
        }
    }

    /// The frequency response H(iω), evaluated literally as the product K·H_h·H_l·H_t·H_s of the standard.
    ///
    /// # Formula
    /// The four factors of the type's `# Formula` with s = iω (ω in rad/s; negative ω gives the complex
    /// conjugate). H(0) = 0 (the high pass). A non-finite ω gives a non-finite result. Above
    /// [`LARGE_OMEGA`] rad/s, where the complex divisions would overflow (it gave NaN), every factor is divided through by its
    /// highest power of s and evaluated in u = 1/s (`response_at_large_omega`): the same
    /// function, no overflow; below it the literal form, bit for bit as before.
    ///
    /// # Errors
    /// None.
    ///
    /// # Examples
    /// ```
    /// use stochvib::comfort::Weighting;
    /// let h = Weighting::Wd.response(2.0 * std::f64::consts::PI * 1.0);
    /// // ISO 2631-1:1997 Table 3: Wd at 1 Hz is 1011/1000
    /// assert!((h.norm() - 1.011).abs() < 0.001);
    /// // far above the band the low pass has taken it to (nearly) nothing, not NaN
    /// assert!(Weighting::Wk.response(1e300).norm() < 1e-290);
    /// ```
    pub fn response(self, omega_rad_s: f64) -> Complex<f64> {
        if omega_rad_s.abs() > LARGE_OMEGA && omega_rad_s.is_finite() {
            return self.response_at_large_omega(omega_rad_s);
        }
        let p = self.parameters();
        let s = Complex::new(0.0, omega_rad_s);
        let one = Complex::new(1.0, 0.0);
        let (w1, w2) = (TAU * p.f1_hz, TAU * p.f2_hz);
        let h_h = s * s / (s * s + s * (w1 / p.q1) + w1 * w1);
        let h_l = Complex::new(w2 * w2, 0.0) / (s * s + s * (w2 / p.q2) + w2 * w2);
        let t_num = if p.f3_hz.is_finite() {
            one + s / (TAU * p.f3_hz)
        } else {
            one
        };
        let t_den = if p.f4_hz.is_finite() {
            let w4 = TAU * p.f4_hz;
            one + s / (p.q4 * w4) + s * s / (w4 * w4)
        } else {
            one
        };
        let h_s = if p.f5_hz.is_finite() && p.f6_hz.is_finite() {
            let (w5, w6) = (TAU * p.f5_hz, TAU * p.f6_hz);
            (one + s / (p.q5 * w5) + s * s / (w5 * w5)) / (one + s / (p.q6 * w6) + s * s / (w6 * w6))
                * ((w5 / w6) * (w5 / w6))
        } else {
            one
        };
        h_h * h_l * (t_num / t_den) * h_s * p.gain
    }

    /// H(iω) for |ω| > [`LARGE_OMEGA`]: the factors of [`Weighting::response`] with numerator and
    /// denominator divided by their highest power of s, in u = 1/s, and the powers of u gathered into one
    /// factor u^m taken last (so that a small factor does not underflow before a large one multiplies it):
    /// ```text
    /// H_h = 1/(1 + u ω₁/Q₁ + u² ω₁²),   H_l = u² · ω₂²/(1 + u ω₂/Q₂ + u² ω₂²),
    /// H_t = u^(d−n) · (u + 1/ω₃)ⁿ/(u² + u/(Q₄ω₄) + 1/ω₄²)^(d/2)   (n = 1 with ω₃, d = 2 with ω₄, else 0),
    /// H_s = (ω₅/ω₆)² (u² + u/(Q₅ω₅) + 1/ω₅²)/(u² + u/(Q₆ω₆) + 1/ω₆²),   m = 2 + d − n
    /// ```
    fn response_at_large_omega(self, omega_rad_s: f64) -> Complex<f64> {
        let p = self.parameters();
        let u = Complex::new(0.0, -1.0 / omega_rad_s); // 1/(iω)
        let one = Complex::new(1.0, 0.0);
        let (w1, w2) = (TAU * p.f1_hz, TAU * p.f2_hz);
        let h_h = one / (one + u * (w1 / p.q1) + u * u * (w1 * w1));
        let h_l = (w2 * w2) / (one + u * (w2 / p.q2) + u * u * (w2 * w2));
        let (t_num, n) = if p.f3_hz.is_finite() {
            (u + one / (TAU * p.f3_hz), 1)
        } else {
            (one, 0)
        };
        let (t_den, d) = if p.f4_hz.is_finite() {
            let w4 = TAU * p.f4_hz;
            (u * u + u / (p.q4 * w4) + one / (w4 * w4), 2)
        } else {
            (one, 0)
        };
        let h_s = if p.f5_hz.is_finite() && p.f6_hz.is_finite() {
            let (w5, w6) = (TAU * p.f5_hz, TAU * p.f6_hz);
            (u * u + u / (p.q5 * w5) + one / (w5 * w5)) / (u * u + u / (p.q6 * w6) + one / (w6 * w6))
                * ((w5 / w6) * (w5 / w6))
        } else {
            one
        };
        h_h * h_l * (t_num / t_den) * h_s * p.gain * u.powi(2 + d - n)
    }

    /// |H(i2πf)|, the weighting factor at frequency f (Hz).
    ///
    /// # Formula
    /// |H(iω)| with ω = 2πf; see [`Weighting::response`].
    ///
    /// # Errors
    /// None (non-finite f gives a non-finite value).
    ///
    /// # Examples
    /// ```
    /// use stochvib::comfort::Weighting;
    /// // ISO 2631-1:1997 Table 3: Wf at 0.16 Hz is 1006/1000
    /// assert!((Weighting::Wf.magnitude(0.16) - 1.006).abs() < 0.001);
    /// ```
    pub fn magnitude(self, f_hz: f64) -> f64 {
        self.response(TAU * f_hz).norm()
    }

    /// The factors as monic second-order sections N(s)/(s² + ωs/Q + ω²) (numerators carry the gains).
    pub(crate) fn sections(self) -> Vec<Section> {
        let p = self.parameters();
        let (w1, w2) = (TAU * p.f1_hz, TAU * p.f2_hz);
        // H_h·H_l = [ω₁s/(s² + ω₁s/Q₁ + ω₁²)]·[(ω₂²/ω₁)s/(s² + ω₂s/Q₂ + ω₂²)]: the s² of the high pass is
        // split over two strictly proper sections, so that no section computes its (small) low-frequency
        // output as the difference of a feedthrough and an almost equal state term.
        let mut out = vec![
            Section {
                num: [0.0, w1, 0.0],
                den: [w1 * w1, w1 / p.q1, 1.0],
            },
            Section {
                num: [0.0, w2 * w2 / w1, 0.0],
                den: [w2 * w2, w2 / p.q2, 1.0],
            },
        ];
        if p.f4_hz.is_finite() {
            // (1 + s/ω₃)/(1 + s/(Q₄ω₄) + s²/ω₄²) = (ω₄² + (ω₄²/ω₃) s)/(s² + ω₄s/Q₄ + ω₄²)
            let w4 = TAU * p.f4_hz;
            let n1 = if p.f3_hz.is_finite() {
                w4 * w4 / (TAU * p.f3_hz)
            } else {
                0.0
            };
            out.push(Section {
                num: [w4 * w4, n1, 0.0],
                den: [w4 * w4, w4 / p.q4, 1.0],
            });
        }
        if p.f5_hz.is_finite() && p.f6_hz.is_finite() {
            // (1 + s/(Q₅ω₅) + s²/ω₅²)/(1 + s/(Q₆ω₆) + s²/ω₆²)·(ω₅/ω₆)² = (s² + ω₅s/Q₅ + ω₅²)/(s² + ω₆s/Q₆ + ω₆²)
            let (w5, w6) = (TAU * p.f5_hz, TAU * p.f6_hz);
            out.push(Section {
                num: [w5 * w5, w5 / p.q5, 1.0],
                den: [w6 * w6, w6 / p.q6, 1.0],
            });
        }
        out
    }

    /// Numerator and denominator polynomials of H(s), ascending powers of s (denominator monic).
    ///
    /// # Formula
    /// N(s) = K·∏ Nᵢ(s), D(s) = ∏ Dᵢ(s) over the monic second-order factors
    /// Dᵢ = s² + ωᵢs/Qᵢ + ωᵢ² of H_h, H_l, H_t, H_s (H_t as (ω₄² + (ω₄²/ω₃)s)/(s² + ω₄s/Q₄ + ω₄²), H_s as
    /// (s² + ω₅s/Q₅ + ω₅²)/(s² + ω₆s/Q₆ + ω₆²)). Every factor coefficient is ≥ 0, so every product
    /// coefficient is a sum of non-negative terms: no cancellation, relative error ≤ (number of
    /// factors)·ε per coefficient. Degrees (num/den): Wk, Wb 5/8; Wd, Wc, We 3/6; Wj 4/6; Wf 4/8: every
    /// weighting is strictly proper with relative degree ≥ 2.
    ///
    /// The spread of the coefficients is intrinsic to the monomial basis (for Wk the constant term of D is
    /// ≈ 7·10¹² and the leading one 1). Evaluating N(iω)/D(iω) by Horner's rule is nevertheless accurate:
    /// with coefficients ≥ 0, Σ|cₖ||ω|ᵏ = P(|ω|) = ∏ Pᵢ(|ω|), and each quadratic factor satisfies
    /// Pᵢ(|ω|)/|Pᵢ(iω)| ≤ 1 + 2Qᵢ ≤ 3 (equality at ω = ωᵢ), so the evaluation's condition number is at most
    /// 3^(n/2); measured ≤ 1.5e-15 relative to the product form from f₁/100 to 100 f₂. The companion-form
    /// realisation that [`TransferFunction`] builds from these coefficients is poorer (measured ≤ 1.5e-15
    /// except Wf, 4.4e-10 near 110 rad/s): use [`Weighting::state_space`] for state-space work.
    ///
    /// # Errors
    /// None.
    ///
    /// # Examples
    /// ```
    /// use stochvib::comfort::Weighting;
    /// let (num, den) = Weighting::Wd.polynomials();
    /// assert_eq!((num.len(), den.len()), (4, 7)); // degrees 3 and 6
    /// assert_eq!(num[0], 0.0); // the high pass: N(0) = 0
    /// assert_eq!(den[6], 1.0);
    /// ```
    pub fn polynomials(self) -> (Vec<f64>, Vec<f64>) {
        let mut num = vec![self.parameters().gain];
        let mut den = vec![1.0];
        for sec in self.sections() {
            num = poly::mul(&num, &sec.num);
            den = poly::mul(&den, &sec.den);
        }
        (poly::trim(&num), poly::trim(&den))
    }

    /// H(s) as a rational [`TransferFunction`] with the given output name and unit (e.g.
    /// `OutputInfo::new("a_w", "m/s^2")`).
    ///
    /// # Formula
    /// H(s) = N(s)/D(s) from [`Weighting::polynomials`], coefficients ascending in s.
    ///
    /// # Errors
    /// Those of [`TransferFunction::new`] (none expected: the polynomials are finite and proper).
    ///
    /// # Examples
    /// ```
    /// use stochvib::comfort::Weighting;
    /// use stochvib::system::{FrequencyResponse, OutputInfo};
    /// let w = Weighting::Wk;
    /// let tf = w.transfer_function(OutputInfo::new("a_w", "m/s^2")).unwrap();
    /// let omega = 2.0 * std::f64::consts::PI * 8.0;
    /// let h = tf.response(omega)[(0, 0)];
    /// assert!((h - w.response(omega)).norm() < 1e-12);
    /// ```
    pub fn transfer_function(self, output: OutputInfo) -> Result<TransferFunction> {
        let (num, den) = self.polynomials();
        TransferFunction::new(num, den, output)
    }

    /// A well-conditioned state-space realisation of H(s): the cascade of its second-order sections.
    ///
    /// # Formula
    /// Sections: ω₁s/(s² + ω₁s/Q₁ + ω₁²), (ω₂²/ω₁)s/(s² + ω₂s/Q₂ + ω₂²) (together H_h·H_l: the s² of the
    /// high pass is split over two strictly proper sections, so that no section forms its small
    /// low-frequency output as the difference of a feedthrough and an almost equal state term), then H_t
    /// and H_s in the monic forms of [`Weighting::polynomials`].
    ///
    /// Section i, Nᵢ(s)/(s² + ωᵢs/Qᵢ + ωᵢ²) with Nᵢ = n₀ + n₁s + n₂s², is realised with the scaled states
    /// x₁ (the section's low-pass response ωᵢ²/Dᵢ) and x₂ = ẋ₁/ωᵢ:
    ///
    /// ```text
    /// Aᵢ = [[0, ωᵢ], [−ωᵢ, −ωᵢ/Qᵢ]],  bᵢ = [0; ωᵢ],  cᵢ = [r₀/ωᵢ², r₁/ωᵢ],  dᵢ = n₂,
    /// r₀ = n₀ − n₂ωᵢ²,  r₁ = n₁ − n₂ωᵢ/Qᵢ          (Nᵢ = n₂Dᵢ + r₀ + r₁s)
    /// ```
    /// (X₁/U = ωᵢ²/Dᵢ, X₂/U = ωᵢs/Dᵢ). Sections are connected in series (G₂ after G₁:
    /// A = [[A₁, 0], [b₂c₁, A₂]], b = [b₁; b₂d₁], c = [d₂c₁, c₂], d = d₂d₁) and the gain K scales c and d.
    /// Every entry of A is of the order of a corner frequency ωᵢ, unlike a companion matrix built from the
    /// expanded polynomial. The realisation is strictly proper (d = 0) with c·b = 0 (relative degree ≥ 2)
    /// and no derivative feedthrough. Measured against the product form from f₁/100 to 100 f₂: ≤ 1.5e-15
    /// relative.
    ///
    /// # Errors
    /// Those of [`StateSpace::new`] (none expected).
    ///
    /// # Examples
    /// ```
    /// use stochvib::comfort::Weighting;
    /// use stochvib::system::{FrequencyResponse, OutputInfo};
    /// let w = Weighting::Wf;
    /// let ss = w.state_space(OutputInfo::new("a_w", "m/s^2")).unwrap();
    /// assert_eq!(ss.n_states(), 8);
    /// let h = ss.response(1.0)[(0, 0)];
    /// assert!((h - w.response(1.0)).norm() < 1e-12);
    /// ```
    pub fn state_space(self, output: OutputInfo) -> Result<StateSpace> {
        let (a, b, c, d) = self.cascade();
        StateSpace::new(a, b, c, Some(DMatrix::from_element(1, 1, d)), None, vec![output])
    }

    /// (A, b, c, d) of the cascade realisation (see [`Weighting::state_space`]).
    pub(crate) fn cascade(self) -> (DMatrix<f64>, DMatrix<f64>, DMatrix<f64>, f64) {
        let mut a = DMatrix::<f64>::zeros(0, 0);
        let mut b = DMatrix::<f64>::zeros(0, 1);
        let mut c = DMatrix::<f64>::zeros(1, 0);
        let mut d = 1.0;
        for sec in self.sections() {
            let w = sec.den[0].sqrt();
            let two_zeta_w = sec.den[1];
            let n2 = sec.num[2];
            let r0 = sec.num[0] - n2 * sec.den[0];
            let r1 = sec.num[1] - n2 * two_zeta_w;
            let a2 = DMatrix::from_row_slice(2, 2, &[0.0, w, -w, -two_zeta_w]);
            let b2 = DMatrix::from_row_slice(2, 1, &[0.0, w]);
            let c2 = DMatrix::from_row_slice(1, 2, &[r0 / (w * w), r1 / w]);
            let d2 = n2;
            // series: first (a, b, c, d), then (a2, b2, c2, d2)
            let n = a.nrows();
            let mut a_new = DMatrix::zeros(n + 2, n + 2);
            a_new.view_mut((0, 0), (n, n)).copy_from(&a);
            a_new.view_mut((n, 0), (2, n)).copy_from(&(&b2 * &c));
            a_new.view_mut((n, n), (2, 2)).copy_from(&a2);
            let mut b_new = DMatrix::zeros(n + 2, 1);
            b_new.view_mut((0, 0), (n, 1)).copy_from(&b);
            b_new.view_mut((n, 0), (2, 1)).copy_from(&(&b2 * d));
            let mut c_new = DMatrix::zeros(1, n + 2);
            c_new.view_mut((0, 0), (1, n)).copy_from(&(&c * d2));
            c_new.view_mut((0, n), (1, 2)).copy_from(&c2);
            a = a_new;
            b = b_new;
            c = c_new;
            d *= d2;
        }
        let k = self.parameters().gain;
        (a, b, c * k, d * k)
    }
}

impl fmt::Display for Weighting {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

impl FromStr for Weighting {
    type Err = Error;
    fn from_str(s: &str) -> Result<Self> {
        Weighting::parse(s)
    }
}
