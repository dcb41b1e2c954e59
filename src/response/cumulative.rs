//! The cumulative variance of an output over a frequency grid: where its variance comes from.

use super::variance::band_variance_with;
use super::Excitation;
use crate::error::{Error, Result};
use crate::quad_oscillatory::OscillatoryOptions;
use crate::system::FrequencyResponse;

/// The cumulative variance σ²(ω_k) = 2∫_0^{ω_k} S_y dω of output `i` at the points of `grid` (rad/s,
/// ascending), and whether it starts at ω = 0.
///
/// # Formula
/// Accumulated segment by segment, σ²(ω_k) = σ²(ω_{k−1}) + 2∫_{ω_{k−1}}^{ω_k} S_y dω, each segment by
/// [`band_variance_with`] (adaptive Gauss–Kronrod quadrature; no trapezoid). When S_y is not integrable
/// at ω = 0 the first segment [0, ω_0] is divergent: the curve then starts at 0 at ω_0 and the flag is
/// `false`. Each segment is integrated to the default relative tolerance or to an absolute tolerance of
/// that fraction of the whole-axis variance `whole`, whichever is looser: a segment holding a negligible
/// share of the variance (e.g. at a band edge of a road) needs no more, and its own relative tolerance may
/// be out of reach there.
///
/// # Errors
/// The quadrature's errors (a divergence of the first segment excepted); `grid` must not be empty.
pub fn cumulative_variance(
    sys: &dyn FrequencyResponse,
    exc: &Excitation,
    i: usize,
    grid: &[f64],
    whole: Option<f64>,
) -> Result<(Vec<f64>, bool)> {
    let first = *grid
        .first()
        .ok_or_else(|| Error::invalid("grid", "[]", "the grid has no points"))?;
    let mut q = OscillatoryOptions::default();
    q.abs_tol = whole.map_or(0.0, |v| q.rel_tol * v);
    let (mut acc, from_zero) = match band_variance_with(sys, exc, i, (0.0, first), &q) {
        Ok(r) => (r.value, true),
        Err(Error::Divergent { .. }) => (0.0, false),
        Err(e) => return Err(e),
    };
    let mut cumulative = Vec::with_capacity(grid.len());
    cumulative.push(acc);
    for k in 1..grid.len() {
        acc += band_variance_with(sys, exc, i, (grid[k - 1], grid[k]), &q)?.value;
        cumulative.push(acc);
    }
    Ok((cumulative, from_zero))
}
