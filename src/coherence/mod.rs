//! Coherence between two parallel road tracks (left and right wheel paths).
//!
//! # Conventions (read this first)
//! For tracks L and R with the same auto-density S(n) (n in cycles/m), a coherence model gives the
//! **coherence amplitude** ρ(n) ∈ [0, 1] with
//!
//! ```text
//! S_LR(n) = ρ(n) · S(n)          (real: the models here have no phase between the tracks)
//! γ²(n)   = |S_LR|² / (S_LL S_RR) = ρ(n)²          the squared coherence (magnitude-squared coherence)
//! ```
//!
//! Literature and tools use the single word "coherence" for ρ, for |ρ| and for γ². Every name in this
//! module says which one: [`Coherence::coherence_amplitude`] is ρ, [`Coherence::squared_coherence`] is γ²,
//! and a table or a fitted formula states its [`CoherenceKind`] (the file keys `coherence_amplitude` and
//! `squared_coherence`). Roll of a vehicle of track width B responds to S_LL + S_RR − 2 Re S_LR
//! = 2(1 − ρ)S.
//!
//! Models (one per file):
//! * [`IsotropicCoherence`]: the isotropic surface of Dodds & Robson (1973) with a power-law profile
//!   spectrum G_d ∝ n^{−w}: ρ = 2^{1−ν}/Γ(ν) x^ν K_ν(x), x = 2πnB, ν = w/2 (for w = 2: ρ = x K₁(x)).
//! * [`AmmonBormann`]: the empirical [1 + (Ω B^a/Ω_p)^w]^{−p} of Ammon & Bormann, with literature presets.
//! * [`TabulatedCoherence`]: a measured table, linear interpolation in n.
//! * [`ConstantCoherence`]: ρ independent of n (ρ = 1: identical tracks, ρ = 0: independent tracks).
//!
//! Multi-component processes: [`SpectralMatrix`] (a cross-spectral density matrix S(ω), checked Hermitian
//! and positive semi-definite by [`check_spectral_matrix`]) and its two-track form [`TwoTracks`].
//!
//! [`bessel_k`] holds the modified Bessel function K_ν of real order that the isotropic model needs.

use crate::error::{Error, Result};
use std::fmt::{self, Debug};
use std::str::FromStr;

mod ammon_bormann;
pub mod bessel_k;
mod constant;
mod isotropic;
mod spectral_matrix;
mod tabulated;
mod two_tracks;

pub use ammon_bormann::{AmmonBormann, AmmonBormannParameters, AmmonBormannRoad};
pub use constant::ConstantCoherence;
pub use isotropic::IsotropicCoherence;
pub use spectral_matrix::{check_spectral_matrix, semidefinite_cholesky, SpectralMatrix, SPECTRAL_MATRIX_TOLERANCE};
pub use tabulated::TabulatedCoherence;
pub use two_tracks::TwoTracks;

/// Which quantity a number called "coherence" is: the amplitude ρ or its square γ² = ρ².
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum CoherenceKind {
    /// ρ(n) = S_LR(n)/S(n) ∈ [0, 1] (file key `coherence_amplitude`).
    CoherenceAmplitude,
    /// γ²(n) = |S_LR|²/(S_LL S_RR) = ρ² ∈ [0, 1] (file key `squared_coherence`).
    SquaredCoherence,
}

impl CoherenceKind {
    /// The file key naming this kind: `coherence_amplitude` or `squared_coherence`.
    pub fn key(self) -> &'static str {
        match self {
            CoherenceKind::CoherenceAmplitude => "coherence_amplitude",
            CoherenceKind::SquaredCoherence => "squared_coherence",
        }
    }

    /// Converts a value of this kind into the amplitude ρ.
    ///
    /// # Formula
    /// ρ = v for `CoherenceAmplitude`, ρ = √v for `SquaredCoherence`.
    ///
    /// # Examples
    /// ```
    /// use stochvib::coherence::CoherenceKind;
    /// assert_eq!(CoherenceKind::SquaredCoherence.to_amplitude(0.25), 0.5);
    /// assert_eq!(CoherenceKind::CoherenceAmplitude.to_amplitude(0.25), 0.25);
    /// ```
    pub fn to_amplitude(self, value: f64) -> f64 {
        match self {
            CoherenceKind::CoherenceAmplitude => value,
            CoherenceKind::SquaredCoherence => value.sqrt(),
        }
    }
}

impl fmt::Display for CoherenceKind {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.key())
    }
}

impl FromStr for CoherenceKind {
    type Err = Error;
    fn from_str(s: &str) -> Result<Self> {
        match s.trim() {
            "coherence_amplitude" => Ok(CoherenceKind::CoherenceAmplitude),
            "squared_coherence" => Ok(CoherenceKind::SquaredCoherence),
            other => Err(Error::invalid(
                "coherence kind",
                other,
                "expected `coherence_amplitude` (ρ, with S_LR = ρ S) or `squared_coherence` (γ² = ρ²); the \
                 bare word `coherence` is ambiguous",
            )),
        }
    }
}

/// A model of the coherence between two parallel tracks with the same auto-density.
///
/// # Formula
/// ```text
/// S_LR(n) = ρ(n) S(n),   0 ≤ ρ(n) ≤ 1,   γ²(n) = ρ(n)²,   n in cycles/m (ρ is even in n)
/// ```
///
/// # Errors
/// Evaluation does not fail: constructors validate. A non-finite n gives NaN.
///
/// # Examples
/// ```
/// use stochvib::coherence::{Coherence, IsotropicCoherence};
/// let c = IsotropicCoherence::new(1.5, 2.0).unwrap();   // track width 1.5 m, ISO waviness 2
/// assert_eq!(c.coherence_amplitude(0.0), 1.0);
/// let r = c.coherence_amplitude(0.1);
/// assert!((c.squared_coherence(0.1) - r * r).abs() < 1e-16);
/// ```
pub trait Coherence: Debug + Send + Sync {
    /// Short description with parameters and units.
    fn describe(&self) -> String;

    /// The coherence amplitude ρ(n) ∈ [0, 1] at spatial frequency n (cycles/m).
    fn coherence_amplitude(&self, n: f64) -> f64;

    /// The squared coherence γ²(n) = ρ(n)².
    fn squared_coherence(&self, n: f64) -> f64 {
        let r = self.coherence_amplitude(n);
        r * r
    }

    /// The track width B in m that the model was built for, if it depends on one.
    fn track_width(&self) -> Option<f64> {
        None
    }

    /// ρ₀ when the amplitude is the same at every spatial frequency (a [`ConstantCoherence`]), `None` for a
    /// model that depends on n: only a constant coherence lets [`TwoTracks`] factor into independent
    /// processes ([`SpectralMatrix::independent_parts`]).
    fn constant_amplitude(&self) -> Option<f64> {
        None
    }
}
