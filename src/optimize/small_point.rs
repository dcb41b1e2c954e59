//! The variances of a search point and their sensitivities for a small affine model in one pass: the
//! state space written from the affine model into storage kept across the evaluations of one search, and
//! P with every dP solved with one factorisation of the small Lyapunov form
//! ([`SmallLyapunov`](crate::linalg::SmallLyapunov)). Anything out of the ordinary (an error, an output of
//! infinite variance, a system the small solver declines) gives `None`, and the caller takes the general
//! path, which reports it.

use super::affine::AffineModel;
use super::gradient::sensitivities_by;
use super::problem::Param;
use crate::linalg::SmallLyapunov;
use crate::response::{AugmentedSystem, ExactEvaluator, Excitation};
use crate::system::{FrequencyResponse, StateSpace};
use nalgebra::DMatrix;

/// The storage of [`small_point`], kept between the evaluations of one search.
#[derive(Debug, Default)]
pub(crate) struct PointScratch {
    solver: SmallLyapunov,
    /// The state spaces at x, x + δe_k and x − δe_k (the affine model's shape), once written.
    systems: Option<[StateSpace; 3]>,
    /// The output indices.
    idx: Vec<usize>,
    /// The directions of the last gradient.
    directions: Vec<AugmentedSystem>,
}

/// What the model and the search share: the evaluator of the base excitation, the affine model and the
/// outputs evaluated.
pub(crate) struct SmallModel<'m> {
    pub(crate) evaluator: &'m ExactEvaluator,
    pub(crate) excitation: &'m Excitation,
    pub(crate) affine: &'m AffineModel,
    pub(crate) outputs: &'m [String],
}

/// The central-difference step of parameter `p` at `xk`: small against x_k (and against the range where
/// x_k is 0).
pub(crate) fn difference_step(p: &Param, xk: f64) -> f64 {
    1e-5 * xk.abs().max(1e-3 * (p.high - p.low))
}

/// The variance of every output at `x` and, when `gradients`, their derivatives along each parameter
/// (per parameter, per output), as [`variance_sensitivities`](super::gradient::variance_sensitivities) of
/// the realization and its central-difference derivative gives them; `None` where the general path must
/// decide (module docs).
pub(crate) fn small_point(
    m: &SmallModel,
    params: &[Param],
    x: &[f64],
    gradients: bool,
    s: &mut PointScratch,
) -> Option<(Vec<f64>, Vec<Vec<f64>>)> {
    let [at, plus, minus] = s.systems.get_or_insert_with(|| {
        let b = m.affine.base();
        [b.clone(), b.clone(), b.clone()]
    });
    if !m.affine.write(x, at) {
        return None;
    }
    s.idx.clear();
    for o in m.outputs {
        s.idx.push(at.output_index(o).ok()?);
    }
    let (base, finite) = m.evaluator.realization_with_finite(at, m.excitation, &s.idx)?.ok()?;
    if !finite.iter().all(|&f| f) || !s.solver.factor(&base.a) {
        return None;
    }
    s.directions.clear();
    if gradients {
        let mut y = x.to_vec();
        for (k, (p, &xk)) in params.iter().zip(x).enumerate() {
            let delta = difference_step(p, xk);
            y[k] = xk + delta;
            let ok_plus = m.affine.write(&y, plus);
            y[k] = xk - delta;
            let ok_minus = m.affine.write(&y, minus);
            y[k] = xk;
            if !(ok_plus && ok_minus) {
                return None;
            }
            let d = m
                .evaluator
                .realization_derivative(at, plus, minus, delta, m.excitation, &s.idx)?;
            s.directions.push(d.ok()?);
        }
    }
    let solver = &mut s.solver;
    let solve = |q: &DMatrix<f64>| {
        let mut p = DMatrix::zeros(0, 0);
        solver.solve(q, &mut p).then_some(p).ok_or(())
    };
    let (var, dvar) = sensitivities_by(&base, &s.directions, solve).ok()?;
    var.iter().all(|v| v.is_finite() && *v >= 0.0).then_some((var, dvar))
}
