//! A spatial (road) spectrum seen in time by a vehicle moving at constant speed.

use super::{Asymptote, Domain, RationalSpectrum, Spectrum};
use crate::error::{require_positive, Error, Result};
use std::sync::Arc;

/// The temporal spectrum of a spatial profile traversed at speed v.
///
/// # Formula
/// With x = v t, K_t(τ) = K_Ω(vτ), hence
/// ```text
/// S_t(ω) = S_Ω(ω/v) / v           (ω in rad/s, Ω = ω/v in rad/m, v in m/s);   D_t = D_Ω
/// ```
///
/// # Errors
/// [`AtSpeed::new`] rejects v ≤ 0 or non-finite, and an input that is not spatial.
///
/// # Examples
/// ```
/// use stochvib::spectrum::{AtSpeed, Exponential, Domain, Spectrum};
/// use std::sync::Arc;
/// // textbook (8.69): spatial type 1, α = 0.16 1/m; at v = 10 m/s it is type 1 in time with αv = 1.6 1/s
/// let road = Arc::new(Exponential::new(32e-4, 0.16, Domain::Spatial).unwrap());
/// let t = AtSpeed::new(road, 10.0).unwrap();
/// let direct = Exponential::new(32e-4, 1.6, Domain::Temporal).unwrap();
/// assert!((t.density(2.0) - direct.density(2.0)).abs() < 1e-18);
/// ```
#[derive(Debug, Clone)]
pub struct AtSpeed {
    inner: Arc<dyn Spectrum>,
    speed: f64,
    /// The temporal rational form (and so its shaping filter), factored once here: `None` when the inner
    /// spectrum is not rational.
    rational: Option<RationalSpectrum>,
}

impl AtSpeed {
    /// Wraps a spatial spectrum at speed `speed` (m/s).
    ///
    /// # Errors
    /// See the type's `# Errors`.
    pub fn new(inner: Arc<dyn Spectrum>, speed: f64) -> Result<Self> {
        require_positive("speed", speed)?;
        if inner.domain() != Domain::Spatial {
            return Err(Error::invalid(
                "spectrum",
                inner.describe(),
                "only a spatial spectrum (rad/m) can be turned into time at a speed",
            ));
        }
        let rational = inner.rational().and_then(|r| r.at_speed(speed).ok());
        Ok(AtSpeed { inner, speed, rational })
    }
    /// The speed in m/s.
    pub fn speed(&self) -> f64 {
        self.speed
    }
    /// The spatial spectrum.
    pub fn spatial(&self) -> &Arc<dyn Spectrum> {
        &self.inner
    }
}

impl Spectrum for AtSpeed {
    fn describe(&self) -> String {
        format!("{} at {} m/s", self.inner.describe(), self.speed)
    }
    fn domain(&self) -> Domain {
        Domain::Temporal
    }
    fn density(&self, omega: f64) -> f64 {
        self.inner.density(omega / self.speed) / self.speed
    }
    /// One dynamic call of the inner spectrum's `density_into` per chunk of 256 points (the same values as
    /// `density`).
    fn density_into(&self, omega: &[f64], out: &mut [f64]) {
        const CHUNK: usize = 256;
        let mut scaled = [0.0; CHUNK];
        for (w, o) in omega.chunks(CHUNK).zip(out.chunks_mut(CHUNK)) {
            let m = w.len().min(o.len());
            crate::linalg::vmath::map(&w[..m], &mut scaled[..m], |x| x / self.speed);
            self.inner.density_into(&scaled[..m], &mut o[..m]);
            crate::linalg::vmath::div_in_place(&mut o[..m], self.speed);
        }
    }
    fn high_frequency(&self) -> Asymptote {
        scale(self.inner.high_frequency(), self.speed)
    }
    fn low_frequency(&self) -> Asymptote {
        scale(self.inner.low_frequency(), self.speed)
    }
    fn support(&self) -> (f64, f64) {
        let (a, b) = self.inner.support();
        (a * self.speed, b * self.speed)
    }
    fn breakpoints(&self) -> Vec<f64> {
        self.inner.breakpoints().into_iter().map(|w| w * self.speed).collect()
    }
    fn variance(&self) -> Result<f64> {
        self.inner.variance()
    }
    fn correlation(&self, tau: f64) -> Result<f64> {
        self.inner.correlation(tau * self.speed)
    }
    fn rational(&self) -> Option<RationalSpectrum> {
        self.rational.clone()
    }
}

/// S_t ≈ c (ω/v)^e / v = c v^{−e−1} ω^e.
fn scale(a: Asymptote, v: f64) -> Asymptote {
    match a {
        Asymptote::Power { exponent, coefficient } => Asymptote::Power {
            exponent,
            coefficient: coefficient * v.powf(-exponent - 1.0),
        },
        Asymptote::Vanishing => Asymptote::Vanishing,
    }
}
