//! Power-law road spectra and the ISO 8608 road classes.

use super::{Asymptote, Domain, Spectrum};
use crate::error::{require_positive, Error, Result};
use std::f64::consts::PI;
use std::fmt;
use std::str::FromStr;

/// Reference spatial frequency of ISO 8608, n₀ = 0.1 cycles/m.
pub const ISO_N0: f64 = 0.1;
/// ISO 8608 waviness exponent w = 2.
pub const ISO_WAVINESS: f64 = 2.0;
/// ISO 8608 standard band for the RMS, 0.011–2.83 cycles/m.
pub const ISO_BAND: (f64, f64) = (0.011, 2.83);

/// A road (or any) spectrum of power-law form, written in the ISO 8608 one-sided cyclic convention.
///
/// # Formula
/// ```text
/// G_d(n) = G_d(n₀) (n/n₀)^{−w}          one-sided, n in cycles/m (Hz for a temporal process)
/// S(Ω)   = G_d(Ω/2π) / (4π)             canonical two-sided, Ω in rad/m
/// D      = ∫_{n₁}^{n₂} G_d(n) dn = G_d(n₀) n₀^w (n₁^{1−w} − n₂^{1−w}) / (w − 1)     (w ≠ 1)
/// ```
/// Without a band the variance is infinite for every w (the integral diverges at n → 0 for w ≥ 1 and at
/// n → ∞ for w ≤ 1): [`Spectrum::variance`] then returns [`Error::Divergent`] asking for a band.
///
/// # Errors
/// [`PowerLawParameters::build`] rejects non-positive or non-finite G_d(n₀), n₀, w, and a band that is not
/// 0 < n₁ < n₂ < ∞.
///
/// # Examples
/// ```
/// use stochvib::spectrum::{PowerLaw, IsoClass, IsoBound, Spectrum, ISO_BAND};
/// // ISO class A (geometric mean 16e-6 m³) over the standard band:
/// let a = PowerLaw::iso8608(IsoClass::A, IsoBound::GeometricMean, Some(ISO_BAND)).unwrap();
/// let expected = 16e-6 * 0.1f64.powi(2) * (1.0 / 0.011 - 1.0 / 2.83);
/// assert!((a.variance().unwrap() - expected).abs() < 1e-15 * expected);
/// // without a band the variance is infinite, and said so:
/// let unbounded = PowerLaw::iso8608(IsoClass::A, IsoBound::GeometricMean, None).unwrap();
/// assert!(unbounded.variance().is_err());
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct PowerLaw {
    g0: f64,
    n0: f64,
    waviness: f64,
    band: Option<(f64, f64)>,
    domain: Domain,
    label: String,
}

/// ISO 8608 road class.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord)]
#[allow(missing_docs)]
pub enum IsoClass {
    A,
    B,
    C,
    D,
    E,
    F,
    G,
    H,
}

/// Which value of an ISO 8608 class: the lower limit, the geometric mean or the upper limit.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum IsoBound {
    /// Lower class limit, half the geometric mean.
    Lower,
    /// Geometric mean of the class (16·4ᵏ × 10⁻⁶ m³ for class index k = 0 for A … 7 for H).
    GeometricMean,
    /// Upper class limit, twice the geometric mean.
    Upper,
}

impl IsoClass {
    /// All classes A–H.
    pub const ALL: [IsoClass; 8] = [
        IsoClass::A,
        IsoClass::B,
        IsoClass::C,
        IsoClass::D,
        IsoClass::E,
        IsoClass::F,
        IsoClass::G,
        IsoClass::H,
    ];

    /// G_d(n₀) in m³ (m² per cycle/m) for the requested bound (ISO 8608:2016, Table 3: the geometric mean
    /// of class k is 16·4^k ×10⁻⁶ m³, its limits ½ and 2 times that).
    ///
    /// # Errors
    /// [`Error::InvalidParameter`] (`bound`) for the bounds the standard does not define: class A has no
    /// lower limit and class H no upper limit (open-ended classes).
    ///
    /// # Examples
    /// ```
    /// use stochvib::spectrum::{IsoBound, IsoClass};
    /// assert_eq!(IsoClass::C.g0(IsoBound::Upper).unwrap(), 512e-6);
    /// assert!(IsoClass::A.g0(IsoBound::Lower).is_err());
    /// ```
    pub fn g0(self, bound: IsoBound) -> Result<f64> {
        let mean = 16e-6 * 4f64.powi(self as i32);
        match (self, bound) {
            (IsoClass::A, IsoBound::Lower) | (IsoClass::H, IsoBound::Upper) => Err(Error::invalid(
                "bound",
                format!("{bound:?}"),
                format!(
                    "ISO 8608 defines no {} limit for class {self} (the class is open-ended)",
                    if bound == IsoBound::Lower { "lower" } else { "upper" }
                ),
            )),
            (_, IsoBound::Lower) => Ok(mean / 2.0),
            (_, IsoBound::GeometricMean) => Ok(mean),
            (_, IsoBound::Upper) => Ok(mean * 2.0),
        }
    }
}

impl fmt::Display for IsoClass {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{:?}", self)
    }
}

impl FromStr for IsoClass {
    type Err = Error;
    fn from_str(s: &str) -> Result<Self> {
        IsoClass::ALL
            .into_iter()
            .find(|c| c.to_string().eq_ignore_ascii_case(s.trim()))
            .ok_or_else(|| Error::invalid("class", s, "ISO 8608 classes are A, B, C, D, E, F, G, H"))
    }
}

impl FromStr for IsoBound {
    type Err = Error;
    fn from_str(s: &str) -> Result<Self> {
        match s {
            "lower" => Ok(IsoBound::Lower),
            "mean" | "geometric-mean" => Ok(IsoBound::GeometricMean),
            "upper" => Ok(IsoBound::Upper),
            _ => Err(Error::invalid("bound", s, "expected lower, mean or upper")),
        }
    }
}

/// The parameters of a [`PowerLaw`] density G(n) = G(n₀)(n/n₀)^{−w} as named fields.
///
/// # Errors
/// As [`PowerLaw`]'s `# Errors`.
///
/// # Examples
/// ```
/// use stochvib::spectrum::{Domain, PowerLawParameters, Spectrum};
/// let band = Some((0.011, 2.83));
/// let p = PowerLawParameters { g0: 256e-6, n0: 0.1, waviness: 2.0, band, domain: Domain::Spatial };
/// let p = p.build().unwrap();
/// assert!(p.variance().unwrap() > 0.0);
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PowerLawParameters {
    /// G(n₀) > 0, the one-sided cyclic density at n₀ (m³ for a spatial road).
    pub g0: f64,
    /// n₀ > 0, the reference frequency (cycles/m for spatial, Hz for temporal).
    pub n0: f64,
    /// w > 0, the exponent: G(n) = G(n₀)(n/n₀)^{−w}.
    pub waviness: f64,
    /// The band [n₁, n₂] outside which G = 0 (cycles/m or Hz), if any.
    pub band: Option<(f64, f64)>,
    /// Temporal or spatial.
    pub domain: Domain,
}

impl PowerLawParameters {
    /// The [`PowerLaw`] of these parameters, checked.
    ///
    /// # Errors
    /// See [`PowerLaw`]'s `# Errors`.
    pub fn build(self) -> Result<PowerLaw> {
        let PowerLawParameters {
            g0,
            n0,
            waviness,
            band,
            domain,
        } = self;
        require_positive("g0", g0)?;
        require_positive("n0", n0)?;
        require_positive("waviness", waviness)?;
        if let Some((lo, hi)) = band {
            require_positive("band.low", lo)?;
            if !(hi.is_finite() && hi > lo) {
                return Err(Error::invalid(
                    "band.high",
                    hi,
                    format!("must be finite and > band.low = {lo}"),
                ));
            }
        }
        Ok(PowerLaw {
            g0,
            n0,
            waviness,
            band,
            domain,
            label: format!("power law G(n0) = {}", crate::numbers::num(g0)),
        })
    }
}

impl PowerLaw {
    /// ISO 8608 class `class` (n₀ = 0.1 cycles/m, w = 2), spatial, with an optional band in cycles/m
    /// (the standard one is [`ISO_BAND`]).
    ///
    /// # Errors
    /// As [`IsoClass::g0`] for an undefined bound, as [`PowerLawParameters::build`] for the band.
    pub fn iso8608(class: IsoClass, bound: IsoBound, band: Option<(f64, f64)>) -> Result<Self> {
        let g0 = class.g0(bound)?;
        let mut p = PowerLawParameters {
            g0,
            n0: ISO_N0,
            waviness: ISO_WAVINESS,
            band,
            domain: Domain::Spatial,
        }
        .build()?;
        p.label = format!("ISO 8608 class {class} ({bound:?}), G_d(n0) = {g0} m^3");
        Ok(p)
    }

    /// ISO 8608 class `class` as the standard classifies roads: the geometric mean of the class, over the
    /// standard band [`ISO_BAND`] (0.011–2.83 cycles/m).
    ///
    /// # Errors
    /// None for the standard band (the `Result` is [`PowerLaw::iso8608`]'s).
    ///
    /// # Examples
    /// ```
    /// use stochvib::spectrum::{IsoClass, PowerLaw};
    /// let c = PowerLaw::iso_class(IsoClass::C).unwrap();
    /// assert_eq!(c.one_sided_cyclic(0.1), 256e-6);
    /// ```
    pub fn iso_class(class: IsoClass) -> Result<Self> {
        PowerLaw::iso8608(class, IsoBound::GeometricMean, Some(ISO_BAND))
    }

    /// The band in cycles/m (or Hz), if any.
    pub fn band(&self) -> Option<(f64, f64)> {
        self.band
    }

    /// One-sided cyclic density G(n).
    pub fn one_sided_cyclic(&self, n: f64) -> f64 {
        self.g0 * (n / self.n0).powf(-self.waviness)
    }

    fn asymptote(&self) -> Asymptote {
        // S(Ω) = g0/(4π) (Ω/(2π n0))^{−w}
        Asymptote::Power {
            exponent: -self.waviness,
            coefficient: self.g0 / (4.0 * PI) * (2.0 * PI * self.n0).powf(self.waviness),
        }
    }
}

impl Spectrum for PowerLaw {
    fn describe(&self) -> String {
        let band = match self.band {
            Some((a, b)) => format!(
                "band {}..{} {}",
                crate::numbers::num(a),
                crate::numbers::num(b),
                self.domain.cyclic_unit()
            ),
            None => "no band (infinite variance)".to_string(),
        };
        format!(
            "{}, n0 = {} {}, w = {}, {band}",
            self.label,
            crate::numbers::num(self.n0),
            self.domain.cyclic_unit(),
            crate::numbers::num(self.waviness)
        )
    }
    fn domain(&self) -> Domain {
        self.domain
    }
    fn density(&self, omega: f64) -> f64 {
        let n = omega.abs() / (2.0 * PI);
        if let Some((lo, hi)) = self.band
            && (n < lo || n > hi)
        {
            return 0.0;
        }
        if n == 0.0 {
            return f64::INFINITY;
        }
        self.one_sided_cyclic(n) / (4.0 * PI)
    }
    /// For an integer waviness w ≤ 4 (ISO 8608: w = 2), (n/n₀)^−w as 1/(n/n₀)^w by multiplications,
    /// vectorised by [`vmath::map`](crate::linalg::vmath::map): within 5 ulp of `density` (which calls
    /// `powf`); any other waviness point by point through `density`.
    fn density_into(&self, omega: &[f64], out: &mut [f64]) {
        let wv = self.waviness;
        if wv.fract() != 0.0 || wv > 4.0 {
            for (o, &w) in out.iter_mut().zip(omega) {
                *o = self.density(w);
            }
            return;
        }
        let k = wv as u32;
        let (lo, hi) = self.band.unwrap_or((f64::NEG_INFINITY, f64::INFINITY));
        crate::linalg::vmath::map(omega, out, |om: f64| {
            let n = om.abs() / (2.0 * PI);
            let x = n / self.n0;
            let x2 = x * x;
            let p = match k {
                1 => x,
                2 => x2,
                3 => x2 * x,
                _ => x2 * x2,
            };
            let v = self.g0 / p / (4.0 * PI);
            if n < lo || n > hi {
                0.0
            } else if n == 0.0 {
                f64::INFINITY
            } else {
                v
            }
        });
    }
    fn high_frequency(&self) -> Asymptote {
        if self.band.is_some() {
            Asymptote::Vanishing
        } else {
            self.asymptote()
        }
    }
    fn low_frequency(&self) -> Asymptote {
        if self.band.is_some() {
            Asymptote::Vanishing
        } else {
            self.asymptote()
        }
    }
    fn support(&self) -> (f64, f64) {
        match self.band {
            Some((lo, hi)) => (2.0 * PI * lo, 2.0 * PI * hi),
            None => (0.0, f64::INFINITY),
        }
    }
    fn variance(&self) -> Result<f64> {
        let Some((n1, n2)) = self.band else {
            return Err(Error::Divergent {
                quantity: "variance of a power-law spectrum".into(),
                reason: format!(
                    "∫ G(n) dn of n^-{} diverges at n → {}; give a band (ISO 8608: 0.011–2.83 cycles/m) \
                     or a low-frequency cut-off",
                    self.waviness,
                    if self.waviness >= 1.0 { "0" } else { "∞" }
                ),
            });
        };
        let w = self.waviness;
        Ok(if (w - 1.0).abs() < 1e-12 {
            self.g0 * self.n0 * (n2 / n1).ln()
        } else {
            self.g0 * self.n0.powf(w) * (n1.powf(1.0 - w) - n2.powf(1.0 - w)) / (w - 1.0)
        })
    }
}
