//! Spectral (frequency-domain) fatigue damage of a stationary Gaussian stress process from the moments of
//! its one-sided density in Hz ([`SpectralMoments`]), one method per file.
//!
//! Every method estimates the expected Palmgren–Miner damage rate of rainflow cycles,
//! ```text
//! E[D]/T = ν · ∫_{S_e}^∞ S_a^k p(S_a) dS_a / C        (1/s)
//! ```
//! with ν a cycle rate (ν₀⁺ or ν_p) and p(S_a) a model of the rainflow amplitude density, for the S–N
//! curve N·S_a^k = C in **amplitudes** ([`SnCurve`]). The life is 1/rate (s).
//!
//! | method | file | cycle rate | amplitude model |
//! |---|---|---|---|
//! | [`NarrowBand`] (Rayleigh) | `narrow_band.rs` | ν₀⁺ | Rayleigh(√m₀) |
//! | [`WirschingLight`] | `wirsching_light.rs` | ν₀⁺ | Rayleigh × λ(ε, k) |
//! | [`Dirlik`] | `dirlik.rs` | ν_p | exponential + 2 Rayleigh |
//! | [`TovoBenasciutti`] | `tovo_benasciutti.rs` | ν₀⁺, ν_p | Rayleigh(√m₀), Rayleigh(α₂√m₀) |
//! | [`ZhaoBaker`] | `zhao_baker.rs` | ν_p | Weibull + Rayleigh |
//!
//! [`SpectralMethodKind`] lists them all and [`compare_methods`] runs them all and reports the spread.

use crate::error::Result;
use crate::fatigue::SnCurve;

mod comparison;
mod dirlik;
mod gamma;
mod moments;
mod narrow_band;
mod tovo_benasciutti;
mod wirsching_light;
mod zhao_baker;

pub use comparison::{compare_methods, MethodComparison, MethodEstimate, SpectralMethodKind};
pub use dirlik::{Dirlik, DirlikCoefficients};
pub use moments::{OneSidedHzMoments, SpectralMoments, TwoSidedAngularMoments};
pub use narrow_band::NarrowBand;
pub use tovo_benasciutti::{TovoBenasciutti, TovoBenasciuttiVariant};
pub use wirsching_light::WirschingLight;
pub use zhao_baker::{ZhaoBaker, ZhaoBakerCoefficients, ZhaoBakerVariant};

/// A spectral fatigue-damage method: the expected Miner damage per second of a stationary Gaussian process
/// with one-sided Hz moments `moments`, for the amplitude S–N curve `sn`.
///
/// # Formula
/// damage_rate = E\[D\]/T (1/s); life = 1/damage_rate (s; +∞ when the rate is 0, e.g. every cycle below
/// the endurance limit in the model).
///
/// # Errors
/// A method that needs moments the caller did not give (e.g. m₀.₇₅) returns
/// [`Error::NotApplicable`](crate::Error::NotApplicable).
///
/// # Examples
/// ```
/// use stochvib::fatigue::{Dirlik, NarrowBand, SnCurve, SpectralMethod, OneSidedHzMoments};
/// let m = OneSidedHzMoments { m0: 100.0, m1: 4.0e3, m2: 1.7e5, m4: 3.5e8 }.build().unwrap();
/// let sn = SnCurve { k: 4.0, c: 1e12, endurance_limit: None }.build().unwrap();
/// let methods: [&dyn SpectralMethod; 2] = [&NarrowBand, &Dirlik];
/// for method in methods {
///     let rate = method.damage_rate(&m, &sn).unwrap();
///     assert!((method.life(&m, &sn).unwrap() - 1.0 / rate).abs() <= 1e-12 / rate);
/// }
/// ```
pub trait SpectralMethod: std::fmt::Debug + Send + Sync {
    /// Name with the reference, e.g. `Dirlik (1985)`.
    fn name(&self) -> &'static str;

    /// Expected damage per second (1/s).
    fn damage_rate(&self, moments: &SpectralMoments, sn: &SnCurve) -> Result<f64>;

    /// Expected life 1/damage_rate (s).
    fn life(&self, moments: &SpectralMoments, sn: &SnCurve) -> Result<f64> {
        let d = self.damage_rate(moments, sn)?;
        Ok(if d > 0.0 { 1.0 / d } else { f64::INFINITY })
    }
}
