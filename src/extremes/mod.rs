//! Extremes of a mission: the distribution of the largest value of a Gaussian response over a duration T,
//! peak factors, first-passage probabilities, and the spectra used to tailor a test from a response
//! (Lalanne's extreme response and fatigue damage spectra). The formulas, sources and conventions are
//! collected in `docs/transients.md`.
//!
//! # Conventions (read this first)
//! * A maximum is either of y itself (**one-sided**, [`Barrier::OneSided`]: up-crossings of +b count) or of
//!   |y| (**two-sided**, [`Barrier::TwoSided`]: up-crossings of +b and down-crossings of −b count).
//! * ν₀⁺ is the rate of up-crossings of the mean level by y, per second (Hz, not rad/s):
//!   ν₀⁺ = (1/2π)√(λ₂/λ₀) with λ_k = ∫|ω|ᵏS_y(ω)dω of the two-sided angular density.
//! * The "number of cycles" N of a peak-factor formula is ν₀⁺T for the maximum of y and 2ν₀⁺T (the
//!   zero crossings of both directions) for the maximum of |y|; every function names which N it takes.
//! * The peak factor is r = (max − M_y)/σ_y; a level b is measured from the mean: r = (b − M_y)/σ_y.
//! * Vanmarcke's bandwidth δ = √(1 − λ₁²/(λ₀λ₂)) (his q), λ₁ with |ω|.
//!
//! # Pieces
//! * [`peak_factor`]: Davenport's (1964) and Der Kiureghian's (1980) mean and standard deviation of the
//!   peak factor.
//! * [`first_passage`]: P(max ≤ b within T) by Poisson (Rice) crossings and by Vanmarcke's (1975)
//!   bandwidth-corrected form; the non-stationary Rice rate ν⁺(b, t) of a Gaussian process with a mean,
//!   a variance and a y–ẏ correlation that vary in time.
//! * [`ers_fds()`]: the extreme response spectrum and the fatigue damage spectrum (Lalanne) of any
//!   base-acceleration density.
//! * [`dkw`]: the Dvoretzky–Kiefer–Wolfowitz band of an empirical distribution and the verdict of an
//!   analytic distribution against it.

pub mod dkw;
pub mod ers_fds;
pub mod first_passage;
pub mod peak_factor;

pub use dkw::{dkw_epsilon, BandVerdict, EmpiricalDistribution};
pub use ers_fds::{ers_fds, ErsFdsOptions, ErsFdsPoint, FdsMaterial};
pub use first_passage::{
    bandwidth_vanmarcke, rice_rate, rice_rate_two_sided, BandwidthMoments, CrossingMoments, ExceedanceMethod,
    FirstPassage, RiceState,
};
pub use peak_factor::{davenport, der_kiureghian, PeakFactor, EULER_GAMMA};

/// Which maximum: of y (one-sided) or of |y| (two-sided).
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum Barrier {
    /// The largest value of y: up-crossings of +b; N = ν₀⁺T.
    OneSided,
    /// The largest value of |y|: up-crossings of +b and down-crossings of −b; N = 2ν₀⁺T.
    TwoSided,
}

impl Barrier {
    /// Crossings per mean-level up-crossing: 1 for y, 2 for |y|.
    pub fn crossings_per_cycle(self) -> f64 {
        match self {
            Barrier::OneSided => 1.0,
            Barrier::TwoSided => 2.0,
        }
    }

    /// `max y` or `max |y|`.
    pub fn label(self) -> &'static str {
        match self {
            Barrier::OneSided => "max y",
            Barrier::TwoSided => "max |y|",
        }
    }
}

/// Standard normal density φ(x).
pub fn normal_pdf(x: f64) -> f64 {
    (-0.5 * x * x).exp() / (2.0 * std::f64::consts::PI).sqrt()
}

/// Standard normal distribution function Φ(x) = erfc(−x/√2)/2 (statrs' erfc, accurate in both tails).
pub fn normal_cdf(x: f64) -> f64 {
    0.5 * statrs::function::erf::erfc(-x / std::f64::consts::SQRT_2)
}
