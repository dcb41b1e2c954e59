//! Peak factors: the mean and standard deviation of r = (max − M_y)/σ_y over a duration.

use super::Barrier;
use crate::error::{Error, Result};

/// Euler–Mascheroni constant γ.
pub const EULER_GAMMA: f64 = 0.577_215_664_901_532_9;

/// Mean and standard deviation of a peak factor, with the count N the formula used.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct PeakFactor {
    /// E\[r\].
    pub mean: f64,
    /// σ\[r\].
    pub std: f64,
    /// The count N the formula was evaluated with (after any bandwidth correction: N_e for Der Kiureghian).
    pub n: f64,
}

fn check_count(name: &str, n: f64) -> Result<()> {
    if !(n.is_finite() && n > 1.0) {
        return Err(Error::invalid(
            name,
            n,
            "the expected number of cycles must be > 1 (the asymptotic peak-factor formulas need ln N > 0): \
             lengthen the duration",
        ));
    }
    Ok(())
}

/// Davenport's peak factor of a stationary Gaussian process.
///
/// # Formula
/// Davenport, A.G. (1964), "Note on the distribution of the largest value of a random function with
/// application to gust loading", Proc. ICE 28(2), 187–196: the asymptotic (Gumbel) form of the
/// distribution of the largest value, whose mean and standard deviation are
/// ```text
/// E[r] = √(2 ln N) + γ/√(2 ln N),      σ[r] = (π/√6)/√(2 ln N),      γ = 0.5772…
/// N = ν₀⁺T for the maximum of y (Davenport's own case), N = 2ν₀⁺T for the maximum of |y|
/// ```
/// (the |y| form treats the crossings of +b and −b as independent).
///
/// # Errors
/// ν₀⁺T·(crossings per cycle) ≤ 1 or not finite.
///
/// # Examples
/// ```
/// use stochvib::extremes::{davenport, Barrier};
/// let p = davenport(100.0, Barrier::OneSided).unwrap();
/// let l = (2.0 * 100f64.ln()).sqrt();
/// assert!((p.mean - (l + 0.5772156649015329 / l)).abs() < 1e-15);
/// ```
pub fn davenport(nu0_t: f64, barrier: Barrier) -> Result<PeakFactor> {
    let n = nu0_t * barrier.crossings_per_cycle();
    check_count("nu0+ T", n)?;
    let l = (2.0 * n.ln()).sqrt();
    Ok(PeakFactor {
        mean: l + EULER_GAMMA / l,
        std: std::f64::consts::PI / 6f64.sqrt() / l,
        n,
    })
}

/// Der Kiureghian's peak factor of the maximum of |y| of a stationary Gaussian process, corrected for
/// the bandwidth (clumping of narrow-band crossings).
///
/// # Formula
/// Der Kiureghian, A. (1980), "Structural response to stationary excitation", J. Eng. Mech. Div. ASCE
/// 106(EM6), 1195–1213 (the peak-factor equations as used in his CQC rule), with ν = 2ν₀⁺ the rate of zero
/// crossings of both directions and δ Vanmarcke's bandwidth:
/// ```text
/// ν_e = (1.63 δ^0.45 − 0.38) ν   for δ < 0.69,   ν_e = ν   otherwise;      N_e = max(ν_e T, 2.1)
/// E[r] = √(2 ln N_e) + γ/√(2 ln N_e),     σ[r] = 1.2/√(2 ln N_e) − 5.4/(13 + (2 ln N_e)^3.2)
/// ```
/// Only the maximum of |y| (his convention) is defined.
///
/// # Errors
/// δ outside \[0, 1\], or 2ν₀⁺T ≤ 1.
///
/// # Examples
/// ```
/// use stochvib::extremes::der_kiureghian;
/// // broad band (δ ≥ 0.69): the mean is Davenport's with N = 2ν₀⁺T
/// let p = der_kiureghian(100.0, 0.8).unwrap();
/// let l = (2.0 * 200f64.ln()).sqrt();
/// assert!((p.mean - (l + 0.5772156649015329 / l)).abs() < 1e-14);
/// ```
pub fn der_kiureghian(nu0_t: f64, delta: f64) -> Result<PeakFactor> {
    if !(0.0..=1.0).contains(&delta) {
        return Err(Error::invalid("bandwidth", delta, "Vanmarcke's δ lies in [0, 1]"));
    }
    let n = 2.0 * nu0_t;
    check_count("2 nu0+ T", n)?;
    let factor = if delta < 0.69 {
        1.63 * delta.powf(0.45) - 0.38
    } else {
        1.0
    };
    let ne = (factor * n).max(2.1);
    let l2 = 2.0 * ne.ln();
    let l = l2.sqrt();
    Ok(PeakFactor {
        mean: l + EULER_GAMMA / l,
        std: 1.2 / l - 5.4 / (13.0 + l2.powf(3.2)),
        n: ne,
    })
}
