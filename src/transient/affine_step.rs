//! The exact step of the differential Lyapunov equation when F, b and H are constant and the noise
//! intensity varies linearly in time: G(t)G(t)ᵀ = κ(t)·ḠḠᵀ with κ linear between the knots (a w = 2 road
//! under a piecewise-linear speed, white noise under a piecewise-linear intensity envelope).

use super::system::Frozen;
use super::PiecewiseLinear;
use crate::error::Result;
use nalgebra::{DMatrix, DVector};

/// The structure of a system whose only time-varying coefficient is the scalar factor κ(t) ≥ 0 of its noise
/// intensity, linear between the system's knots: ż = Fz + √κ(t)·Ḡw + b, y = Hz + y₀ with F, Ḡ, b, H, y₀
/// constant.
///
/// # Formula
/// ```text
/// w = 2 road under v(t):                   Ḡ = √(2πc)·A⁻¹B,   κ(t) = v(t)   (the speed table)
/// white s (density S₀), intensity e(t):    Ḡ = √(2πS₀)·B,     κ(t) = e(t)   (the intensity table; M_u = 0)
/// ```
/// Both tables are piecewise linear with their kinks among the system's knots, so κ is linear on every
/// step of the exact route. This is structure, read from the kind of input and table, not found by
/// comparing samples.
#[derive(Debug, Clone)]
pub struct AffineNoise {
    /// F, Ḡ (in place of G), b, H and y₀.
    pub(crate) unit: Frozen,
    /// κ(t).
    pub(crate) factor: PiecewiseLinear,
}

impl AffineNoise {
    /// κ(t), the factor on ḠḠᵀ at t.
    pub fn factor(&self, t: f64) -> f64 {
        self.factor.value(t)
    }
}

/// One step's transition under an intensity linear on the step: P ← ΦPΦᵀ + κ(t+h)·L₀ + (κ(t) − κ(t+h))·W,
/// m ← Φm + Γ.
#[derive(Debug, Clone)]
pub(super) struct AffineTransition {
    phi: DMatrix<f64>,
    phi_t: DMatrix<f64>,
    /// L₀ = ∫₀ʰ e^{Fu} ḠḠᵀ e^{Fᵀu} du.
    l0: DMatrix<f64>,
    /// W = ∫₀ʰ (u/h) e^{Fu} ḠḠᵀ e^{Fᵀu} du.
    w: DMatrix<f64>,
    gamma: DVector<f64>,
}

/// The transition of the affine form `aff` over h; `count` is raised by the exponentials computed.
///
/// # Formula
/// Over a step [t, t + h] with κ(t + s) = κ₀ + (κ_h − κ₀)s/h, u = h − s the time from s to the step's end:
/// ```text
/// P(t+h) = ΦP(t)Φᵀ + ∫₀ʰ e^{F(h−s)} κ(t+s)ḠḠᵀ e^{Fᵀ(h−s)} ds = ΦPΦᵀ + κ_h·L₀ + (κ₀ − κ_h)·W
/// L₀ = ∫₀ʰ e^{Fu} ḠḠᵀ e^{Fᵀu} du,   W = (1/h)∫₀ʰ u e^{Fu} ḠḠᵀ e^{Fᵀu} du,   Φ = e^{Fh}
/// ```
/// (κ(t + s) = κ_h − (κ_h − κ₀)u/h). Van Loan, C.F. (1978), "Computing integrals involving the matrix
/// exponential", IEEE Trans. Autom. Control 23(3), 395–404, Theorem 1: the exponential of the block upper
/// triangular Ĉh, Ĉ = [[A₁, B₁, C₁], [0, A₂, B₂], [0, 0, A₃]], has the blocks F₂ = e^{A₂h},
/// G₁ = ∫₀ʰ e^{A₁(h−s)}B₁e^{A₂s} ds and H₁ = ∫₀ʰ∫₀ˢ e^{A₁(h−s)}B₁e^{A₂(s−r)}B₂e^{A₃r} dr ds (C₁ = 0).
/// With A₁ = −F, B₁ = ḠḠᵀ, A₂ = A₃ = Fᵀ, B₂ = I the inner integral of H₁ is s·e^{Fᵀs}, so
/// ```text
/// Φ = F₂ᵀ,   L₀ = Φ G₁,   W = Φ H₁ / h
/// ```
/// one exponential of a 3n × 3n matrix per step length h, whatever κ₀ and κ_h (they enter linearly). The
/// mean's b is constant: Γ = ∫₀ʰ e^{Fs}ds·b as for a constant step. With κ₀ = κ_h the step is the constant
/// step κ·L₀.
///
/// # Errors
/// A failed matrix exponential.
pub(super) fn affine_transition(aff: &AffineNoise, h: f64, count: &mut usize) -> Result<AffineTransition> {
    let fr = &aff.unit;
    let n = fr.f.nrows();
    let ft = fr.f.transpose() * h;
    let mut big = DMatrix::zeros(3 * n, 3 * n);
    big.view_mut((0, 0), (n, n)).copy_from(&(&fr.f * -h));
    big.view_mut((0, n), (n, n)).copy_from(&(&fr.g * fr.g.transpose() * h));
    big.view_mut((n, n), (n, n)).copy_from(&ft);
    big.view_mut((n, 2 * n), (n, n))
        .copy_from(&(DMatrix::identity(n, n) * h));
    big.view_mut((2 * n, 2 * n), (n, n)).copy_from(&ft);
    let e = crate::linalg::expm(&big)?;
    *count += 1 + usize::from(fr.b.iter().any(|v| *v != 0.0));
    let phi = e.view((n, n), (n, n)).transpose();
    let l0 = &phi * e.view((0, n), (n, n));
    let w = &phi * e.view((0, 2 * n), (n, n)) / h;
    Ok(AffineTransition {
        phi_t: phi.transpose(),
        l0: (&l0 + l0.transpose()) * 0.5,
        w: (&w + w.transpose()) * 0.5,
        gamma: super::lyapunov_ode::mean_step(fr, h)?,
        phi,
    })
}

impl AffineTransition {
    /// (P, m) after the step from (`p`, `m`) with κ = `k0` at its start and `kh` at its end (see
    /// [`affine_transition`]).
    pub(super) fn apply(&self, k0: f64, kh: f64, p: &DMatrix<f64>, m: &DVector<f64>) -> (DMatrix<f64>, DVector<f64>) {
        let q = &self.phi * p * &self.phi_t + &self.l0 * kh + &self.w * (k0 - kh);
        ((&q + q.transpose()) * 0.5, &self.phi * m + &self.gamma)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::simulate::van_loan;
    use crate::tolerance::ULPS;

    /// An underdamped oscillator ẍ + 2ζωẋ + ω²x = w (ω = 3 rad/s, ζ = 0.1), Ḡ = [0; 0.7], b = [0; 0.2].
    fn oscillator() -> AffineNoise {
        let (w0, z) = (3.0, 0.1);
        AffineNoise {
            unit: Frozen {
                f: DMatrix::from_row_slice(2, 2, &[0.0, 1.0, -w0 * w0, -2.0 * z * w0]),
                g: DMatrix::from_row_slice(2, 1, &[0.0, 0.7]),
                b: DVector::from_column_slice(&[0.0, 0.2]),
                h: DMatrix::identity(2, 2),
                y0: DVector::zeros(2),
            },
            factor: PiecewiseLinear::constant(1.0).unwrap(),
        }
    }

    /// With κ₀ = κ_h = κ the affine step is the constant step ΦPΦᵀ + κQ_d of the 2n × 2n Van Loan
    /// exponential (`van_loan`, a different matrix and exponential): equal to rounding (a few ε of the
    /// largest entry, the 3n × 3n exponential's normwise rounding, Higham (2008) §10.3).
    #[test]
    fn a_constant_factor_gives_the_constant_step() {
        let aff = oscillator();
        let (h, k) = (0.37, 2.5);
        let mut count = 0;
        let tr = affine_transition(&aff, h, &mut count).unwrap();
        assert_eq!(count, 2, "one block exponential and one for the mean");
        let p = DMatrix::from_row_slice(2, 2, &[0.3, 0.05, 0.05, 0.9]);
        let m = DVector::from_column_slice(&[0.1, -0.2]);
        let (pa, ma) = tr.apply(k, k, &p, &m);
        let d = van_loan(&aff.unit.f, &(&aff.unit.g * k.sqrt()), h).unwrap();
        let pc = &d.phi * &p * d.phi.transpose() + &d.qd;
        let scale = pc.amax();
        assert!((&pa - &pc).amax() <= 16.0 * ULPS * scale, "{pa} vs {pc}");
        assert!((&tr.phi - &d.phi).amax() <= 16.0 * ULPS * d.phi.amax());
        let mc = &d.phi * &m + super::super::lyapunov_ode::mean_step(&aff.unit, h).unwrap();
        assert!((&ma - &mc).amax() <= 16.0 * ULPS * mc.amax());
    }

    /// The scalar case ẋ = −ax + √κ(t)·w with κ linear over the step, from P = 0: in closed form (derived
    /// here) ∫₀ʰ e^{−2au} du = (1 − e^{−2ah})/(2a) = L₀ and (1/h)∫₀ʰ u e^{−2au} du
    /// = (1 − (1 + 2ah)e^{−2ah})/(4a²h) = W, so P(h) = κ_h L₀ + (κ₀ − κ_h) W.
    #[test]
    fn scalar_step_matches_its_closed_form() {
        let (a, h, k0, kh) = (1.3, 0.8, 0.5, 2.0);
        let aff = AffineNoise {
            unit: Frozen {
                f: DMatrix::from_element(1, 1, -a),
                g: DMatrix::from_element(1, 1, 1.0),
                b: DVector::zeros(1),
                h: DMatrix::identity(1, 1),
                y0: DVector::zeros(1),
            },
            factor: PiecewiseLinear::constant(1.0).unwrap(),
        };
        let mut count = 0;
        let tr = affine_transition(&aff, h, &mut count).unwrap();
        assert_eq!(count, 1, "no mean forcing: one exponential");
        let e = (-2.0 * a * h).exp();
        let l0 = (1.0 - e) / (2.0 * a);
        let w = (1.0 - (1.0 + 2.0 * a * h) * e) / (4.0 * a * a * h);
        let expected = kh * l0 + (k0 - kh) * w;
        let (p, _) = tr.apply(k0, kh, &DMatrix::zeros(1, 1), &DVector::zeros(1));
        assert!(
            (p[(0, 0)] - expected).abs() <= 16.0 * ULPS * expected,
            "{} vs {expected}",
            p[(0, 0)]
        );
    }
}
