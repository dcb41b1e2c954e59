//! Coherence of two parallel tracks on an isotropic road surface with a power-law profile spectrum
//! (Dodds & Robson 1973).

use super::bessel_k::bessel_k_x_pow;
use super::Coherence;
use crate::error::{require_positive, Error, Result};
use std::f64::consts::PI;

/// Largest waviness accepted: ν = w/2 ≤ 50 keeps the normalisation 2^{ν−1}Γ(ν) and the recurrence of
/// [`bessel_k_x_pow`] far from overflow; measured roads have w between about 1 and 4.
const MAX_WAVINESS: f64 = 100.0;

/// The coherence of two parallel tracks a distance B apart on a homogeneous **isotropic** random surface
/// whose single-track spectrum is the power law G_d(n) ∝ n^{−w} (ISO 8608 form; Dodds & Robson 1973,
/// "The description of road surface roughness", J. Sound Vib. 31(2), 175–183).
///
/// # Formula
/// ```text
/// ρ(n) = 2^{1−ν}/Γ(ν) · x^ν K_ν(x),   x = 2π n B,   ν = w/2;      w = 2:  ρ(n) = x K₁(x)
/// γ²(n) = ρ(n)²,   ρ(0) = 1,   ρ(n) ~ √π/Γ(ν) (x/2)^{ν−½} e^{−x} as x → ∞
/// ```
/// n in cycles/m, B in m, K_ν the modified Bessel function of the second kind ([`bessel_k_x_pow`]).
///
/// **Derivation.** Let the surface z(x, y) be homogeneous and isotropic with two-dimensional density
/// S₂(k), k = |(Ω, κ)| (Ω along the road, κ across, rad/m). The density of one track (a line y = const)
/// and the cross-density of two tracks B apart are the projections
/// ```text
/// S(Ω)    = ∫ S₂(√(Ω² + κ²)) dκ,        S_LR(Ω) = ∫ S₂(√(Ω² + κ²)) e^{iκB} dκ      (over κ ∈ ℝ)
/// ```
/// (Dodds & Robson 1973; Robson et al. 1978, "The application of isotropy in road surface modelling").
/// S_LR is real because S₂ is even in κ. The power law S₂(k) = C k^{−(w+1)} projects to
/// S(Ω) = C √π Γ(w/2)/Γ((w+1)/2) · |Ω|^{−w}, the ISO form with the same w, and with Basset's integral
/// ∫₀^∞ cos(Bκ)(κ² + Ω²)^{−ν−½} dκ = √π (B/(2|Ω|))^ν K_ν(|Ω|B)/Γ(ν + ½) (Abramowitz & Stegun 1964,
/// 9.6.25) the ratio is
/// ```text
/// ρ = S_LR/S = 2 (ΩB/2)^ν K_ν(ΩB)/Γ(ν) = 2^{1−ν}/Γ(ν) x^ν K_ν(x),   x = |Ω|B = 2π|n|B
/// ```
/// which is the Matérn correlation function of x. As x → 0, x^ν K_ν(x) → 2^{ν−1}Γ(ν) (A&S 9.6.9), so
/// ρ(0) = 1. ρ is positive and decreasing in x for every ν > 0, so γ = |ρ| = ρ.
///
/// **Range of validity.** The projection integral of k^{−(w+1)} converges at large κ only for w > 0, and
/// ρ as written is then defined for every w > 0 (ν > 0). It is the exact coherence of the model surface:
/// isotropic, with a power law holding at all wavenumbers. A band-limited G_d (e.g. the ISO 8608 band
/// 0.011–2.83 cycles/m) is not the projection of a band-limited isotropic surface, so near the band
/// edges ρ is only an approximation; measured roads are not exactly isotropic either (Dodds & Robson found
/// the model acceptable for the roads they measured; the study "Model of coherence function of road
/// unevenness in parallel tracks for vehicle simulation", fitting 3492 measured records, reports clearly
/// better fits by empirical models such as [`AmmonBormann`](super::AmmonBormann)). Accepted here: 0 < w ≤ 100.
///
/// # Errors
/// [`IsotropicCoherence::new`] rejects B ≤ 0 or non-finite and w outside (0, 100].
///
/// # Examples
/// ```
/// use stochvib::coherence::{Coherence, IsotropicCoherence};
/// // w = 2: ρ = x K₁(x); at x = 1 (n = 1/(2πB)), K₁(1) = 0.6019072302 (A&S Table 9.8)
/// let b = 1.5;
/// let c = IsotropicCoherence::new(b, 2.0).unwrap();
/// let n = 1.0 / (2.0 * std::f64::consts::PI * b);
/// assert!((c.coherence_amplitude(n) - 0.6019072302).abs() < 1e-10);
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct IsotropicCoherence {
    track_width: f64,
    waviness: f64,
    /// ln(2^{1−ν}/Γ(ν)).
    ln_norm: f64,
}

impl IsotropicCoherence {
    /// The isotropic model for track width `track_width_m` (B, m) and ISO waviness `waviness` (w).
    ///
    /// # Errors
    /// See the type's `# Errors`.
    pub fn new(track_width_m: f64, waviness: f64) -> Result<Self> {
        require_positive("track_width", track_width_m)?;
        if !(waviness.is_finite() && waviness > 0.0 && waviness <= MAX_WAVINESS) {
            return Err(Error::invalid(
                "waviness",
                waviness,
                format!(
                    "the isotropic coherence needs 0 < w <= {MAX_WAVINESS} (the projection of k^-(w+1) \
                     converges only for w > 0)"
                ),
            ));
        }
        let nu = 0.5 * waviness;
        let ln_norm = (1.0 - nu) * std::f64::consts::LN_2 - statrs::function::gamma::ln_gamma(nu);
        Ok(IsotropicCoherence {
            track_width: track_width_m,
            waviness,
            ln_norm,
        })
    }

    /// The waviness w (ν = w/2).
    pub fn waviness(&self) -> f64 {
        self.waviness
    }
}

impl Coherence for IsotropicCoherence {
    fn describe(&self) -> String {
        format!(
            "isotropic surface coherence (Dodds & Robson 1973), track width B = {} m, waviness w = {}",
            crate::numbers::num(self.track_width),
            crate::numbers::num(self.waviness)
        )
    }

    fn coherence_amplitude(&self, n: f64) -> f64 {
        if !n.is_finite() {
            return f64::NAN;
        }
        let x = 2.0 * PI * n.abs() * self.track_width;
        if x == 0.0 {
            return 1.0;
        }
        match bessel_k_x_pow(0.5 * self.waviness, x) {
            // ρ ≤ 1 in exact arithmetic; rounding near x → 0 may give 1 + ulp
            Ok(v) if v > 0.0 => (v.ln() + self.ln_norm).exp().min(1.0),
            Ok(_) => 0.0,
            // x overflowed to ∞ (n near f64::MAX): the limit ρ → 0
            Err(_) => 0.0,
        }
    }

    fn track_width(&self) -> Option<f64> {
        Some(self.track_width)
    }
}
