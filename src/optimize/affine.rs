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
    /// Per parameter, the non-zero entries of its slopes: (matrix 0..5 of A, B, C, D, E, index in the
    /// matrix's column-major storage, slope). A stiffness or a damping moves a few entries of each matrix.
    slopes: Vec<Vec<(usize, usize, f64)>>,
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
        if !mats(base).iter().all(|m| m.iter().all(|v| v.is_finite())) {
            return None;
        }
        let mut slopes = Vec::with_capacity(up.len());
        for (h, m) in up {
            if shape(m) != shape(base) || *h == 0.0 {
                return None;
            }
            let (mb, mm) = (mats(base), mats(m));
            let mut terms = Vec::new();
            for i in 0..5 {
                let entries = mm[i].iter().zip(mb[i].iter()).enumerate();
                terms.extend(
                    entries
                        .filter(|(_, (u, b))| u != b)
                        .map(|(e, (u, b))| (i, e, (u - b) / *h)),
                );
            }
            slopes.push(terms);
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
        let mut targets = [&mut ss.a, &mut ss.b, &mut ss.c, &mut ss.d, &mut ss.e];
        for (t, b) in targets.iter_mut().zip(mats(&self.base)) {
            t.copy_from(b);
        }
        // the base is finite (`fit`), so only the entries a slope moves can become infinite
        for ((terms, &xk), &x0k) in self.slopes.iter().zip(x).zip(&self.x0) {
            let f = xk - x0k;
            for &(i, e, s) in terms {
                let t = &mut targets[i].as_mut_slice()[e];
                *t += f * s;
                if !t.is_finite() {
                    return false;
                }
            }
        }
        true
    }
}
