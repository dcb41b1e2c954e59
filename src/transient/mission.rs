//! Extremes of a mission from the exact route: P(max > b within T) by the integrated Rice rate, and for a
//! stationary mission Vanmarcke's form with the bandwidth of the stationary output density.

use super::mc_finish::{AnalyticOutput, AnalyticSide};
use super::series::TransientSolution;
use super::system::Frozen;
use crate::error::{Error, Result};
use crate::extremes::{Barrier, FirstPassage};
use crate::quad::{integrate, QuadOptions};
use nalgebra::{Complex, DMatrix};
use rayon::prelude::*;

/// Levels of the analytic distributions of the maxima.
pub const LEVELS: usize = 400;

/// One output's stationary moments (frozen system at t = 0) for Vanmarcke's form.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct StationaryMoments {
    /// λ₀ = σ².
    pub lambda0: f64,
    /// λ₁ = ∫|ω|S dω.
    pub lambda1: f64,
    /// λ₂ = σ_ẏ².
    pub lambda2: f64,
    /// ν₀⁺ = (1/2π)√(λ₂/λ₀), Hz.
    pub nu0_plus: f64,
    /// Vanmarcke's δ.
    pub delta: f64,
}

/// λ₀, λ₁, λ₂ of output i of the frozen form by quadrature of S_y(ω) = |h(iωI − F)⁻¹G|²/(2π) (unit
/// white noise has the two-sided density 1/(2π)), and Vanmarcke's bandwidth.
///
/// # Errors
/// A failed quadrature (a divergent moment: ẏ with a white component).
pub fn stationary_moments(fr: &Frozen, i: usize, rel_tol: f64) -> Result<StationaryMoments> {
    let n = fr.f.nrows();
    let h = fr.h.row(i).map(|v| Complex::new(v, 0.0));
    let g = fr.g.map(|v| Complex::new(v, 0.0));
    let f = fr.f.map(|v| Complex::new(v, 0.0));
    let density = |w: f64| -> f64 {
        let m = DMatrix::from_diagonal_element(n, n, Complex::new(0.0, w)) - &f;
        match m.lu().solve(&g) {
            Some(x) => (&h * x).iter().map(|c| c.norm_sqr()).sum::<f64>() / (2.0 * std::f64::consts::PI),
            None => f64::NAN,
        }
    };
    let mut bp: Vec<f64> =
        fr.f.complex_eigenvalues()
            .iter()
            .map(|l| l.norm())
            .filter(|w| *w > 0.0)
            .collect();
    bp.sort_by(f64::total_cmp);
    bp.dedup();
    let q = QuadOptions {
        rel_tol,
        breakpoints: bp,
        ..QuadOptions::default()
    };
    let moment = |k: i32| integrate(|w| 2.0 * w.powi(k) * density(w), 0.0, f64::INFINITY, &q).map(|r| r.value);
    let (l0, l1, l2) = (moment(0)?, moment(1)?, moment(2)?);
    Ok(StationaryMoments {
        lambda0: l0,
        lambda1: l1,
        lambda2: l2,
        nu0_plus: (l2 / l0).sqrt() / (2.0 * std::f64::consts::PI),
        delta: crate::extremes::bandwidth_vanmarcke(crate::extremes::BandwidthMoments {
            lambda0: l0,
            lambda1: l1,
            lambda2: l2,
        })?,
    })
}

/// The levels of the distributions of output i's maxima: from min(0, min m) to max|m| + 7 max σ.
fn levels(sol: &TransientSolution, i: usize) -> Vec<f64> {
    let o = &sol.outputs[i];
    let lo = o.mean.iter().copied().fold(0.0, f64::min);
    let hi = o.mean.iter().map(|m| m.abs()).fold(0.0, f64::max) + 7.0 * o.sigma.iter().copied().fold(0.0, f64::max);
    (0..LEVELS)
        .map(|k| lo + (hi - lo) * k as f64 / (LEVELS - 1) as f64)
        .collect()
}

/// The analytic side of a Monte Carlo run of outputs `outputs` of `sys`: the exact curves and the
/// distributions of the maxima (Poisson at the integrated Rice rate, F(b) = exp(−∫ν dt); Vanmarcke's form
/// with `stationary`, the frozen system at t = 0 of a time-invariant system started in its stationary state).
///
/// # Errors
/// An output without crossing rates (ẏ with a white component); the quadrature of the moments.
pub fn analytic_side(
    sol: &TransientSolution,
    stationary: Option<&Frozen>,
    outputs: &[usize],
    method: String,
) -> Result<AnalyticSide> {
    let duration = sol.times.last().copied().unwrap_or(0.0) - sol.times.first().copied().unwrap_or(0.0);
    let outputs = outputs
        .iter()
        .map(|&i| {
            let o = &sol.outputs[i];
            if let Some(note) = o.unavailable.as_ref().or(o.rate_note.as_ref()) {
                return Err(Error::NotApplicable {
                    method: format!("distribution of the maxima of `{}`", o.name),
                    reason: note.clone(),
                });
            }
            let lv = levels(sol, i);
            // P(max ≤ b) of y and of |y| from one pass over the levels (both barriers' rates at once), in parallel
            let (cdf_y_rice, cdf_abs_rice): (Vec<f64>, Vec<f64>) = lv
                .par_iter()
                .map(|&b| {
                    let (up, both) = sol.crossing_rates_both(i, b);
                    let cdf = |rates: &[f64]| (-sol.crossings(rates).expected).exp();
                    (cdf(&up), cdf(&both))
                })
                .unzip();
            let van = |barrier: Barrier| -> Result<Vec<f64>> {
                let Some(fr0) = stationary else {
                    return Ok(vec![f64::NAN; lv.len()]);
                };
                let m = stationary_moments(fr0, i, 1e-9)?;
                let (mean, sigma) = (o.mean[0], o.sigma[0]);
                lv.iter()
                    .map(|&b| {
                        let r = (b - mean) / sigma;
                        if r <= 0.0 || (barrier == Barrier::TwoSided && mean != 0.0) {
                            return Ok(if r <= 0.0 { 0.0 } else { f64::NAN });
                        }
                        let q = FirstPassage {
                            level_over_sigma: r,
                            zero_upcrossings: m.nu0_plus * duration,
                            barrier,
                        };
                        Ok(1.0 - q.vanmarcke(m.delta)?)
                    })
                    .collect()
            };
            Ok(AnalyticOutput {
                mean: o.mean.clone(),
                sigma: o.sigma.clone(),
                cdf_y_rice,
                cdf_abs_rice,
                cdf_y_vanmarcke: van(Barrier::OneSided)?,
                cdf_abs_vanmarcke: van(Barrier::TwoSided)?,
                levels: lv,
            })
        })
        .collect::<Result<Vec<_>>>()?;
    Ok(AnalyticSide { method, outputs })
}
