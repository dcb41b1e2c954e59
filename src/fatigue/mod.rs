//! Fatigue: S–N curves and Palmgren–Miner damage, rainflow counting of sampled signals, and spectral
//! (frequency-domain) fatigue-damage estimates of stationary Gaussian processes.
//!
//! # Conventions (read this first)
//! - **S–N curve in stress amplitude**: N·S_a^k = C, with S_a the cycle amplitude (half the range
//!   ΔS = 2S_a) in the unit of the signal (e.g. Pa or MPa) and C in (that unit)^k. A curve given in ranges,
//!   N·ΔS^k = C_Δ, is the same curve with C = C_Δ·2^{−k} ([`SnRangeCurve`]).
//! - **Rainflow** ([`rainflow()`]) reports every cycle's range *and* amplitude by name, its mean, and its
//!   count: 1 for a full cycle, 0.5 for a half cycle (the residue, counted as ASTM E1049-85 §5.4.4 does).
//! - **Spectral methods** ([`spectral`]) take the moments m_j = ∫₀^∞ f^j G(f) df of the **one-sided
//!   density in Hz**, G(f) = 4π S(2πf) where S(ω) is the crate's canonical two-sided density in rad/s
//!   (see [`crate::spectrum`]). With λ_j = ∫_{−∞}^{∞} |ω|^j S(ω) dω (the crate's spectral moments),
//!   m_j = (2π)^{−j} λ_j ([`TwoSidedAngularMoments`]). Many papers use ω and/or a
//!   two-sided density: the conversion is exact and explicit, never a silent factor.
//! - **Damage** is a rate per second (1/s) for the spectral methods (the expected Miner damage per unit
//!   time); the life is 1/rate in seconds. Rainflow damage is the Miner sum of the counted cycles (no unit).
//! - **Endurance limit** (optional): a cycle whose amplitude is strictly below S_e does no damage;
//!   amplitudes ≥ S_e follow N = C·S_a^{−k} (a plain cut-off, no second slope).

pub mod rainflow;
mod sn_curve;
pub mod spectral;

pub use rainflow::{rainflow, Cycle, RainflowCounter, RangeHistogram, TurningPoint, MAX_ABS_SAMPLE};
pub use sn_curve::{SnCurve, SnRangeCurve, SnReferencePoint};
pub use spectral::{
    compare_methods, Dirlik, DirlikCoefficients, MethodComparison, MethodEstimate, NarrowBand, OneSidedHzMoments,
    SpectralMethod, SpectralMethodKind, SpectralMoments, TovoBenasciutti, TovoBenasciuttiVariant,
    TwoSidedAngularMoments, WirschingLight, ZhaoBaker, ZhaoBakerCoefficients, ZhaoBakerVariant,
};
