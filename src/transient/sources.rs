//! Several independent random inputs of a transient analysis (a road under v(t) and a force on the body,
//! each felt by its own model inputs): their shaping filters side by side, block-diagonal, ahead of the
//! system (`docs/transients.md`, "Several inputs").

use super::system::{FilterParts, Frozen, InputModel};
use crate::error::{Error, Result};
use crate::system::StateSpace;
use nalgebra::{DMatrix, DVector};
use std::f64::consts::PI;

/// An independent random source besides the first one ([`super::TransientInput`]): the process s_k(t), felt
/// by the system inputs as u_j = g_kj (μ_k + s_k(t)), without an envelope.
#[derive(Debug, Clone)]
pub struct ExtraSource {
    /// The process s_k: white, a temporal rational spectrum, or a rational road under v(t).
    pub model: InputModel,
    /// Gain of the process at each system input (0 where it does not drive).
    pub gains: Vec<f64>,
    /// Its mean μ_k (its unit).
    pub mean: f64,
}

/// One source in the frozen form: its process, filter, gains, mean, envelope value a and slope ȧ at t.
pub(super) struct Block<'a> {
    pub model: &'a InputModel,
    pub filter: Option<&'a FilterParts>,
    pub gains: &'a [f64],
    pub mean: f64,
    pub a: f64,
    pub ad: f64,
}

/// Refuses the processes that have no place among several sources: a w = 2 road (its relative coordinates
/// x + A⁻¹Bu are those of one input process).
pub(super) fn check_model(model: &InputModel) -> Result<()> {
    match model {
        InputModel::WhiteSlope { .. } => Err(Error::NotApplicable {
            method: "exact route with several inputs".into(),
            reason: "a w = 2 road without a band (white road velocity) is exact only as the one input of the \
                     system (its relative coordinates x + A⁻¹Bu are those of that input); with other inputs give \
                     the road a band-limited (rational) spectrum, or use Monte Carlo"
                .into(),
        }),
        InputModel::White { density } if !(density.is_finite() && *density >= 0.0) => Err(Error::invalid(
            "density",
            density,
            "a white-noise density is finite and >= 0",
        )),
        _ => Ok(()),
    }
}

/// The frozen form of `ss` (all its inputs) driven by the independent `blocks` at time t.
///
/// # Formula
/// With block k's filter (A_k, B_k, C_k) (times v(t) and √v(t) for a road), the system's columns
/// B_k = B g_k, D_k = D g_k, E_k = E g_k and the states z = \[z_f1; …; z_fK; x\]:
/// ```text
/// F = [[blockdiag(A_k), 0], [… a_k B_k C_k …, A]],   G = [blockdiag(B_fk); 0] (white k: a_k√(2πS₀) B_k below)
/// H = [… a_k D_k C_k + E_k(ȧ_k C_k + a_k C_k A_k) …, C],   b = [0; Σ a_k B_k μ_k + f],   y₀ = Σ (a_k D_k + ȧ_k E_k) μ_k
/// ```
/// (one noise column per source: the sources are independent).
pub(super) fn frozen_blocks(ss: &StateSpace, blocks: &[Block], forcing: DVector<f64>, t: f64) -> Result<Frozen> {
    let ns = ss.a.nrows();
    let p = ss.c.nrows();
    let nf: usize = blocks.iter().map(|b| b.filter.map_or(0, |f| f.a.nrows())).sum();
    let n = nf + ns;
    let mut f = DMatrix::zeros(n, n);
    let mut g = DMatrix::zeros(n, blocks.len());
    let mut h = DMatrix::zeros(p, n);
    let mut b = DVector::zeros(n);
    let mut y0 = DVector::zeros(p);
    f.view_mut((nf, nf), (ns, ns)).copy_from(&ss.a);
    h.view_mut((0, nf), (p, ns)).copy_from(&ss.c);
    let mut bx = forcing;
    let mut off = 0;
    for (k, blk) in blocks.iter().enumerate() {
        let w = DMatrix::from_column_slice(blk.gains.len(), 1, blk.gains);
        let (bk, dk, ek) = (&ss.b * &w, &ss.d * &w, &ss.e * &w);
        bx += bk.column(0) * (blk.a * blk.mean);
        y0 += (&dk * blk.a + &ek * blk.ad).column(0) * blk.mean;
        let v = match blk.model {
            InputModel::SpatialRational { speed, .. } => speed.speed(t),
            _ => 1.0,
        };
        match (blk.model, blk.filter) {
            (InputModel::White { density }, _) => {
                g.view_mut((nf, k), (ns, 1))
                    .copy_from(&(&bk * (blk.a * (2.0 * PI * density).sqrt())));
            }
            (InputModel::Rational { .. } | InputModel::SpatialRational { .. }, Some(fp)) => {
                let q = fp.a.nrows();
                let af = &fp.a * v;
                f.view_mut((off, off), (q, q)).copy_from(&af);
                f.view_mut((nf, off), (ns, q)).copy_from(&(&bk * &fp.c * blk.a));
                g.view_mut((off, k), (q, 1)).copy_from(&(&fp.b * v.sqrt()));
                h.view_mut((0, off), (p, q))
                    .copy_from(&(&dk * &fp.c * blk.a + &ek * (&fp.c * blk.ad + &fp.c * &af * blk.a)));
                off += q;
            }
            _ => {
                return Err(Error::Numerical {
                    what: "transient system".into(),
                    reason: "a source without its filter, or a w = 2 road among several sources".into(),
                })
            }
        }
    }
    b.rows_mut(nf, ns).copy_from(&bx);
    Ok(Frozen { f, g, b, h, y0 })
}
