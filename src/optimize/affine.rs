//! The model's state space as an affine function of the parameters, where the reader's models are: the
//! search then writes each point's matrices from a fixed base and slopes instead of rebuilding the model
//! from its substituted `[model]` table.
//!
//! Stiffnesses and dampings enter the matrices (A, B, C, D, E) of a mechanical model affinely (M⁻¹K,
//! M⁻¹C and their output rows, M fixed); masses do not (M⁻¹). Whether a problem's model is affine in its
//! parameters is not assumed from the keys' names: it is checked on models the reader builds.

use crate::system::StateSpace;
use nalgebra::DMatrix;

/// Largest difference between a reader's model and the affine prediction, relative to the largest entry of
/// the same matrix, for the model to be called affine: a few hundred roundings of the entries.
pub(crate) const AFFINE_TOLERANCE: f64 = 1e-12;

/// M(x) = M(x₀) + Σ_k (x_k − x₀_k) S_k for each of the matrices A, B, C, D, E of a state space.
#[derive(Debug, Clone)]
pub(crate) struct AffineModel {
    x0: Vec<f64>,
    base: StateSpace,
    slopes: Vec<[DMatrix<f64>; 5]>,
}

fn mats(ss: &StateSpace) -> [&DMatrix<f64>; 5] {
    [&ss.a, &ss.b, &ss.c, &ss.d, &ss.e]
}

impl AffineModel {
    /// The affine model through the reader's model `base` at `x0` with the slopes S_k = (M(x₀ + h_k e_k) −
    /// M(x₀))/h_k from `up[k] = (h_k, model)`, or `None` unless every `checks` model (a point and the
    /// reader's model there) equals the prediction within [`AFFINE_TOLERANCE`] of each matrix's largest
    /// entry, and every model has the base's shape.
    pub(crate) fn fit(
        x0: &[f64],
        base: &StateSpace,
        up: &[(f64, StateSpace)],
        checks: &[(Vec<f64>, StateSpace)],
    ) -> Option<AffineModel> {
        let shape = |s: &StateSpace| mats(s).map(|m| m.shape());
        let mut slopes = Vec::with_capacity(up.len());
        for (h, m) in up {
            if shape(m) != shape(base) || *h == 0.0 {
                return None;
            }
            let (mb, mm) = (mats(base), mats(m));
            slopes.push(std::array::from_fn(|i| (mm[i] - mb[i]) / *h));
        }
        let model = AffineModel {
            x0: x0.to_vec(),
            base: base.clone(),
            slopes,
        };
        let mut predicted = base.clone();
        for (x, actual) in checks {
            if shape(actual) != shape(base) || !model.write(x, &mut predicted) {
                return None;
            }
            let (p, a) = (mats(&predicted), mats(actual));
            let close = (0..5).all(|i| {
                let scale = a[i].amax().max(p[i].amax());
                (p[i] - a[i]).amax() <= AFFINE_TOLERANCE * scale
            });
            if !close {
                return None;
            }
        }
        Some(model)
    }

    /// The base model (its shape and output names; the numbers are those at x₀).
    pub(crate) fn base(&self) -> &StateSpace {
        &self.base
    }

    /// Writes M(x) into `ss` (a state space of the base's shape); false when an entry is not finite.
    pub(crate) fn write(&self, x: &[f64], ss: &mut StateSpace) -> bool {
        let base = mats(&self.base);
        let targets = [&mut ss.a, &mut ss.b, &mut ss.c, &mut ss.d, &mut ss.e];
        for (i, t) in targets.into_iter().enumerate() {
            t.copy_from(base[i]);
            for ((s, &xk), &x0k) in self.slopes.iter().zip(x).zip(&self.x0) {
                let f = xk - x0k;
                t.iter_mut().zip(s[i].iter()).for_each(|(t, s)| *t += f * s);
            }
            if !t.iter().all(|v| v.is_finite()) {
                return false;
            }
        }
        true
    }
}
