//! A process seen through a moving average: the contact patch of a pneumatic tyre enveloping a road.

use super::{Asymptote, Domain, Spectrum};
use crate::error::{Error, Result};
use std::sync::Arc;

/// The squared gain of a moving average of length L at the angular frequency Ω (rad/m, or rad/s with L in s).
///
/// # Formula
/// ```text
/// y(x) = (1/L) ∫_{x−L/2}^{x+L/2} z(s) ds,      H(Ω) = sin(ΩL/2)/(ΩL/2),
/// |H|² = (sin(πnL)/(πnL))²                     (n = Ω/2π in cycles/m; 1 at n = 0)
/// ```
/// zero at n = k/L (k = 1, 2, …), 4/π² at n = 1/(2L).
///
/// # Examples
/// ```
/// use stochvib::spectrum::sinc_squared;
/// use std::f64::consts::PI;
/// let l = 0.25; // m
/// assert!((sinc_squared(2.0 * PI * 2.0, l) - 4.0 / (PI * PI)).abs() < 1e-15); // n = 1/(2L) = 2 cycles/m
/// assert!(sinc_squared(2.0 * PI * 4.0, l) < 1e-30); // n = 1/L: the first zero
/// assert_eq!(sinc_squared(0.0, l), 1.0);
/// ```
pub fn sinc_squared(omega: f64, length: f64) -> f64 {
    let x = 0.5 * omega * length;
    if x.abs() < 1e-8 {
        // sin x / x = 1 − x²/6 + …: below 1e-8 the correction is below the rounding of 1
        return 1.0;
    }
    let s = x.sin() / x;
    s * s
}

/// Most zeros of |H|² given to the quadratures as breakpoints.
const MAX_ZERO_BREAKPOINTS: usize = 256;

/// A spectrum seen through a moving average of length L: the usual first model of a pneumatic tyre's
/// enveloping of a road profile, the contact patch averaging the profile over its length.
///
/// # Formula
/// ```text
/// S_y(Ω) = S(Ω) · (sin(ΩL/2)/(ΩL/2))²            (two-sided, Ω in rad/m; L in m)
/// ```
/// ([`sinc_squared`]). The 250 mm moving average is the profile smoothing of the "golden car" quarter car
/// that defines the International Roughness Index (Sayers & Karamihas, *The Little Book of Profiling*,
/// UMTRI 1998; ASTM E1926, which applies it to the profile before the quarter-car filter), there standing
/// for the tyre's enveloping. It is a model of a tyre on short wavelengths, not a tyre model: it passes the
/// profile unchanged where n ≪ 1/L and falls as n⁻² (on average) above.
///
/// The density is not rational, so the Lyapunov (exact) route does not apply to it: variances come from
/// quadrature of the output density, and Monte Carlo runs take the spectral route.
///
/// # Errors
/// [`MovingAverage::new`] rejects a length that is not finite and > 0.
///
/// # Examples
/// ```
/// use stochvib::spectrum::{Domain, MovingAverage, PowerLawParameters, Spectrum};
/// use std::sync::Arc;
/// let band = Some((0.011, 30.0));
/// let road = PowerLawParameters { g0: 64e-6, n0: 0.1, waviness: 2.0, band, domain: Domain::Spatial };
/// let road = Arc::new(road.build().unwrap());
/// let tyre = MovingAverage::new(road.clone(), 0.25).unwrap();
/// let w = 2.0 * std::f64::consts::PI * 2.0; // n = 2 cycles/m = 1/(2L)
/// let pi2 = std::f64::consts::PI * std::f64::consts::PI;
/// assert!((tyre.density(w) / road.density(w) - 4.0 / pi2).abs() < 1e-15);
/// assert!(tyre.variance().unwrap() < road.variance().unwrap());
/// ```
#[derive(Debug, Clone)]
pub struct MovingAverage {
    inner: Arc<dyn Spectrum>,
    length: f64,
}

impl MovingAverage {
    /// `inner` seen through a moving average of `length` (m for a spatial spectrum, s for a temporal one).
    ///
    /// # Errors
    /// See the type's `# Errors`.
    pub fn new(inner: Arc<dyn Spectrum>, length: f64) -> Result<Self> {
        if !(length.is_finite() && length > 0.0) {
            return Err(Error::invalid("length", length, "must be a finite length > 0"));
        }
        Ok(MovingAverage { inner, length })
    }

    /// The averaging length L (in the lag unit of the spectrum's domain).
    pub fn length(&self) -> f64 {
        self.length
    }
}

impl Spectrum for MovingAverage {
    fn describe(&self) -> String {
        format!(
            "{} through a moving average of length {} {} (tyre enveloping, sinc² filter: not rational)",
            self.inner.describe(),
            crate::numbers::num(self.length),
            self.domain().lag_unit()
        )
    }
    fn domain(&self) -> Domain {
        self.inner.domain()
    }
    fn density(&self, omega: f64) -> f64 {
        let s = self.inner.density(omega);
        if s == 0.0 {
            return 0.0;
        }
        s * sinc_squared(omega, self.length)
    }
    /// S(Ω) ≈ c|Ω|^e becomes on average (2c/L²)|Ω|^(e−2) (the mean of sin² is 1/2).
    fn high_frequency(&self) -> Asymptote {
        match self.inner.high_frequency() {
            Asymptote::Power { exponent, coefficient } => Asymptote::Power {
                exponent: exponent - 2.0,
                coefficient: 2.0 * coefficient / (self.length * self.length),
            },
            Asymptote::Vanishing => Asymptote::Vanishing,
        }
    }
    fn low_frequency(&self) -> Asymptote {
        self.inner.low_frequency()
    }
    fn support(&self) -> (f64, f64) {
        self.inner.support()
    }
    /// The inner breakpoints and the zeros 2πk/L of the filter inside the support (at most 256).
    fn breakpoints(&self) -> Vec<f64> {
        let (lo, hi) = self.support();
        let step = 2.0 * std::f64::consts::PI / self.length;
        let mut b = self.inner.breakpoints();
        b.extend(
            (1..=MAX_ZERO_BREAKPOINTS)
                .map(|k| k as f64 * step)
                .skip_while(|w| *w <= lo)
                .take_while(|w| *w < hi),
        );
        b
    }
    fn moving_average(&self) -> Option<(Arc<dyn Spectrum>, f64)> {
        Some((self.inner.clone(), self.length))
    }
}
