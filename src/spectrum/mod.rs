//! Spectral densities and correlation functions of stationary random processes.
//!
//! # Normalization (read this first)
//! Inside the library every spectrum is the **two-sided density in angular frequency**, `S(ω)`, defined
//! for ω ∈ (−∞, ∞) in rad/s (temporal processes) or rad/m (spatial road profiles, see [`Domain`]):
//!
//! ```text
//! K(τ) = ∫_{−∞}^{∞} S(ω) e^{iωτ} dω,      S(ω) = (1/2π) ∫ K(τ) e^{−iωτ} dτ,      D = K(0) = ∫ S(ω) dω.
//! ```
//!
//! Every other convention is a named, exact conversion ([`Convention`]), never a silent factor:
//!
//! | [`Convention`] | relation to S | used by |
//! |---|---|---|
//! | `TwoSidedAngular` | S itself | this crate |
//! | `OneSidedAngular` G(ω), ω ≥ 0 | G = 2S | textbook (8.19) |
//! | `OneSidedCyclic` G(f), f in Hz or cycles/m | G(f) = 4π S(2πf) | measurements, Welch, ISO 8608 G_d(n) |
//! | `Engineering` Ŝ(ω), σ² = (1/2π)∫Ŝ dω | Ŝ = 2π S | textbook (8.66)–(8.69) |
//!
//! A spatial spectrum S_Ω(Ω) (Ω in rad/m) seen at speed v is the temporal spectrum
//! S_t(ω) = S_Ω(ω/v)/v ([`AtSpeed`]).
//!
//! The mean of a process is not part of its spectrum: spectra describe the zero-mean fluctuation.

use crate::error::Result;
use std::fmt::Debug;

mod at_speed;
mod band_limited;
mod band_white;
mod butterworth;
mod convention;
mod exp_cosine;
mod exponential;
mod gauss_cosine;
mod gaussian;
mod moving_average;
pub mod numeric;
pub mod power_law;
mod rational;
mod tabulated;
pub mod two_pole_road;

pub use at_speed::AtSpeed;
pub use band_limited::BandLimited;
pub use band_white::{BandWhite, BandWhiteParameters};
pub use butterworth::{butterworth_band, ButterworthFilter, MAX_BUTTERWORTH_ORDER};
pub use convention::Convention;
pub use exp_cosine::ExpCosine;
pub use exponential::Exponential;
pub use gauss_cosine::{GaussCosine, GaussCosineParameters};
pub use gaussian::Gaussian;
pub use moving_average::{sinc_squared, MovingAverage};
pub use power_law::{IsoBound, IsoClass, PowerLaw, PowerLawParameters, ISO_BAND, ISO_N0, ISO_WAVINESS};
pub use rational::{RationalSpectrum, ShapingFilter};
pub use tabulated::Tabulated;
pub use two_pole_road::TwoPoleRoad;

/// Whether the independent variable of a spectrum is time or distance along a road.
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Domain {
    /// ω in rad/s, τ in s.
    Temporal,
    /// Ω in rad/m, lag in m (road profiles).
    Spatial,
}

impl Domain {
    /// Unit of the angular frequency variable: `rad/s` or `rad/m`.
    pub fn angular_unit(self) -> &'static str {
        match self {
            Domain::Temporal => "rad/s",
            Domain::Spatial => "rad/m",
        }
    }
    /// Unit of the cyclic frequency variable: `Hz` or `cycles/m`.
    pub fn cyclic_unit(self) -> &'static str {
        match self {
            Domain::Temporal => "Hz",
            Domain::Spatial => "cycles/m",
        }
    }
    /// Unit of the lag variable: `s` or `m`.
    pub fn lag_unit(self) -> &'static str {
        match self {
            Domain::Temporal => "s",
            Domain::Spatial => "m",
        }
    }
}

/// Asymptotic behaviour of S(ω) as |ω| → ∞ or as ω → 0, used to decide whether moments and variances of
/// responses are finite before integrating.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Asymptote {
    /// S(ω) ≈ coefficient · |ω|^exponent.
    Power {
        /// Exponent (negative: decay; 0: a finite non-zero limit).
        exponent: f64,
        /// Leading coefficient (> 0).
        coefficient: f64,
    },
    /// S is zero there, or decays faster than any power (Gaussian, band-limited).
    Vanishing,
}

/// A stationary random process described by its two-sided spectral density S(ω).
///
/// Implementors give `density` and the asymptotes; the variance and correlation have numerical default
/// implementations (adaptive quadrature) that closed forms override.
pub trait Spectrum: Debug + Send + Sync {
    /// Short human-readable description with parameters and units.
    fn describe(&self) -> String;

    /// Temporal (rad/s) or spatial (rad/m).
    fn domain(&self) -> Domain;

    /// Two-sided density S(ω) ≥ 0, even in ω, in (unit of the process)² per (rad/s or rad/m).
    fn density(&self, omega: f64) -> f64;

    /// S(ω) on a grid: `out[k] = density(omega[k])` for k < min(omega.len(), out.len()) (the rest of
    /// `out` is left untouched).
    ///
    /// # Formula
    /// The same values as [`Spectrum::density`]. The provided body is compiled for each implementing type,
    /// so one dynamic call covers the whole grid and `density` is inlined into the loop, and it runs as the
    /// widest SIMD code of the CPU ([`vmath::map`](crate::linalg::vmath::map): AVX-512, AVX2 or SSE2; the
    /// same bits on each, as no operation is fused). Densities built on `exp`, `ln` or `powf` override it
    /// with [`vmath`](crate::linalg::vmath)'s vectorised functions: within the ulp bound their docs state.
    ///
    /// # Examples
    /// ```
    /// use stochvib::spectrum::{Domain, Exponential, Spectrum};
    /// let s = Exponential::new(1.0, 2.0, Domain::Temporal).unwrap();
    /// let w = [0.0, 1.0, 10.0];
    /// let mut out = [0.0; 3];
    /// s.density_into(&w, &mut out);
    /// assert!(out.iter().zip(&w).all(|(o, &x)| *o == s.density(x)));
    /// ```
    fn density_into(&self, omega: &[f64], out: &mut [f64]) {
        crate::linalg::vmath::map(omega, out, |w| self.density(w));
    }

    /// Behaviour as |ω| → ∞.
    fn high_frequency(&self) -> Asymptote;

    /// Behaviour as ω → 0⁺ (`Power { exponent: 0, .. }` for a finite non-zero S(0)).
    fn low_frequency(&self) -> Asymptote;

    /// The |ω| interval outside which S is exactly zero; `(0, ∞)` by default.
    fn support(&self) -> (f64, f64) {
        (0.0, f64::INFINITY)
    }

    /// Characteristic |ω| values (peaks, corners, band edges) that help quadrature; empty by default.
    fn breakpoints(&self) -> Vec<f64> {
        Vec::new()
    }

    /// Variance D = ∫ S dω = K(0). Closed form where one exists; adaptive quadrature otherwise.
    ///
    /// # Errors
    /// [`Error::Divergent`](crate::Error::Divergent) when the integral is infinite (e.g. a power-law road
    /// without a band), [`Error::Quadrature`](crate::Error::Quadrature) when quadrature fails.
    fn variance(&self) -> Result<f64> {
        numeric::variance(self).map(|r| r.value)
    }

    /// Correlation function K(τ) = ∫ S(ω) cos(ωτ) dω. Closed form where one exists; quadrature otherwise.
    ///
    /// # Errors
    /// As for [`Spectrum::variance`].
    fn correlation(&self, tau: f64) -> Result<f64> {
        numeric::correlation(self, tau).map(|r| r.value)
    }

    /// The rational form S(ω) = N(ω²)/D(ω²) when the density is exactly rational (types 1 and 3, the
    /// book roads (8.66), (8.69), white-noise-free rational models); `None` otherwise.
    fn rational(&self) -> Option<RationalSpectrum> {
        None
    }

    /// For a spectrum that is another one seen through a moving average of length L ([`MovingAverage`], a
    /// tyre's enveloping of the road): the unfiltered spectrum and L in the lag unit (m, or s once a speed
    /// turned the road into time); `None` otherwise.
    fn moving_average(&self) -> Option<(std::sync::Arc<dyn Spectrum>, f64)> {
        None
    }
}
