//! Lalanne's extreme response spectrum (ERS) and fatigue damage spectrum (FDS) of a random base
//! acceleration: the spectra that turn a measured or computed vibration (a cab floor, a seat base) into a
//! test specification.

use crate::error::{Error, Result};
use crate::quad::{integrate, QuadOptions};
use std::f64::consts::PI;

/// The material of the fatigue damage spectrum: stress σ = K·z (z the relative displacement of the
/// oscillator) and Basquin's curve N·σ^b = C in stress **amplitude** (a peak of σ).
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct FdsMaterial {
    /// Basquin exponent b (> 0).
    pub b: f64,
    /// K, stress per metre of relative displacement (Pa/m; 1 gives the FDS in m^b).
    pub k: f64,
    /// C of N·σ^b = C (Pa^b; 1 leaves the FDS unscaled).
    pub c: f64,
}

/// The family of oscillators and the duration.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct ErsFdsOptions {
    /// Natural frequencies f₀ of the family, Hz.
    pub frequencies_hz: Vec<f64>,
    /// Quality factor Q = 1/(2ζ) (Lalanne's usual choice: 10).
    pub q: f64,
    /// Duration T of the vibration, s.
    pub duration_s: f64,
    /// Fatigue material.
    pub material: FdsMaterial,
    /// Relative tolerance of the quadratures.
    pub rel_tol: f64,
}

/// The spectra at one natural frequency.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct ErsFdsPoint {
    /// f₀, Hz.
    pub f0_hz: f64,
    /// r.m.s. relative displacement z_rms, m.
    pub z_rms: f64,
    /// n₀⁺ = ż_rms/(2π z_rms): up-crossings of zero per second (not the zero-crossing rate 2n₀⁺), Hz.
    pub n0_plus: f64,
    /// ERS(f₀) = (2πf₀)² z_rms √(2 ln(n₀⁺T)), m/s² (NaN when n₀⁺T ≤ 1).
    pub ers: f64,
    /// FDS(f₀) = (K^b/C) n₀⁺T (√2 z_rms)^b Γ(1 + b/2), expected Miner damage.
    pub fds: f64,
}

/// ERS and FDS of a base acceleration with the two-sided angular density `density` (S(ω), (m/s²)²/(rad/s),
/// the crate's convention; `breakpoints` in rad/s help the quadrature).
///
/// # Formula
/// Lalanne, C., *Mechanical Vibration and Shock Analysis*, Vol. 5 "Specification Development" (ISTE/Wiley,
/// 2nd ed. 2009), the chapters on the extreme response spectrum and the fatigue damage spectrum of a random
/// vibration. A base-excited oscillator of natural frequency f₀ (ω₀ = 2πf₀) and quality factor Q has the
/// relative displacement z with |H(iω)|² = 1/((ω₀² − ω²)² + (ω ω₀/Q)²) from the base acceleration, so
/// ```text
/// z_rms² = ∫ S(ω)|H|² dω,   ż_rms² = ∫ ω² S(ω)|H|² dω   (over −∞ < ω < ∞),   n₀⁺ = ż_rms/(2π z_rms)
/// ERS = ω₀² z_rms √(2 ln(n₀⁺T))                 (the asymptotic most probable largest peak, Rayleigh peaks)
/// FDS = (K^b/C) n₀⁺T (√2 z_rms)^b Γ(1 + b/2)     (narrow band: n₀⁺T cycles with Rayleigh amplitudes)
/// ```
/// In the one-sided cyclic convention of the book, G(f) = 4πS(2πf) and z_rms² = ∫₀^∞ G(f)|H(2πf)|² df;
/// for a white G₀ this is Miles' z_rms² = QG₀/(32π³f₀³). Note: n₀⁺ counts up-crossings; a rate of
/// (1/π)ż_rms/z_rms (all zero crossings) doubles the FDS and shifts the ERS.
///
/// # Errors
/// Q ≤ 0.5 (not an underdamped oscillator), a frequency ≤ 0, T ≤ 0, b ≤ 0, K or C ≤ 0, a failed quadrature.
///
/// # Examples
/// ```
/// use stochvib::extremes::{ers_fds, ErsFdsOptions, FdsMaterial};
/// // white base acceleration G₀ = 1 (m/s²)²/Hz one-sided: S = G₀/(4π)
/// let s = 1.0 / (4.0 * std::f64::consts::PI);
/// let opts = ErsFdsOptions { frequencies_hz: vec![10.0], q: 10.0, duration_s: 3600.0,
///     material: FdsMaterial { b: 8.0, k: 1.0, c: 1.0 }, rel_tol: 1e-10 };
/// let p = ers_fds(&|_| s, &[], &opts).unwrap()[0];
/// let miles = (10.0f64 / (32.0 * std::f64::consts::PI.powi(3) * 1000.0)).sqrt();
/// assert!((p.z_rms / miles - 1.0).abs() < 1e-8);
/// ```
pub fn ers_fds(density: &dyn Fn(f64) -> f64, breakpoints: &[f64], opts: &ErsFdsOptions) -> Result<Vec<ErsFdsPoint>> {
    check(opts)?;
    opts.frequencies_hz
        .iter()
        .map(|&f0| point(density, breakpoints, f0, opts))
        .collect()
}

fn check(opts: &ErsFdsOptions) -> Result<()> {
    if !(opts.q > 0.5 && opts.q.is_finite()) {
        return Err(Error::invalid(
            "quality factor",
            opts.q,
            "Q = 1/(2ζ) must be > 0.5 and finite",
        ));
    }
    if let Some(f) = opts.frequencies_hz.iter().find(|f| !(f.is_finite() && **f > 0.0)) {
        return Err(Error::invalid(
            "frequency",
            f,
            "natural frequencies must be finite and > 0 Hz",
        ));
    }
    let m = &opts.material;
    for (name, v) in [("duration", opts.duration_s), ("b", m.b), ("K", m.k), ("C", m.c)] {
        if !(v.is_finite() && v > 0.0) {
            return Err(Error::invalid(name, v, "must be finite and > 0"));
        }
    }
    Ok(())
}

fn point(density: &dyn Fn(f64) -> f64, breakpoints: &[f64], f0: f64, opts: &ErsFdsOptions) -> Result<ErsFdsPoint> {
    let w0 = 2.0 * PI * f0;
    let h2 = |w: f64| 1.0 / ((w0 * w0 - w * w).powi(2) + (w * w0 / opts.q).powi(2));
    let mut bp: Vec<f64> = breakpoints
        .iter()
        .copied()
        .filter(|b| *b > 0.0 && b.is_finite())
        .collect();
    let half = w0 / (2.0 * opts.q);
    bp.extend([w0 - half, w0, w0 + half]);
    bp.retain(|b| *b > 0.0);
    bp.sort_by(f64::total_cmp);
    bp.dedup();
    let q = QuadOptions {
        rel_tol: opts.rel_tol,
        breakpoints: bp,
        ..QuadOptions::default()
    };
    let z2 = 2.0 * integrate(|w| density(w) * h2(w), 0.0, f64::INFINITY, &q)?.value;
    let v2 = 2.0 * integrate(|w| w * w * density(w) * h2(w), 0.0, f64::INFINITY, &q)?.value;
    let z = z2.sqrt();
    let n0 = v2.sqrt() / (2.0 * PI * z);
    let nt = n0 * opts.duration_s;
    let ers = if nt > 1.0 {
        w0 * w0 * z * (2.0 * nt.ln()).sqrt()
    } else {
        f64::NAN
    };
    let m = &opts.material;
    let fds = m.k.powf(m.b) / m.c * nt * (2f64.sqrt() * z).powf(m.b) * statrs::function::gamma::gamma(1.0 + m.b / 2.0);
    Ok(ErsFdsPoint {
        f0_hz: f0,
        z_rms: z,
        n0_plus: n0,
        ers,
        fds,
    })
}
