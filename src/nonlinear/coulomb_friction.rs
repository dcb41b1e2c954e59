//! Coulomb (dry) friction: F = F_c sgn v.
//!
//! # Formula
//! No linear part. For v ~ N(μ, σ²), h = μ/σ:
//! ```text
//! E[F] = F_c (2Φ(h) − 1),     c_eq = E[F (v − μ)]/σ² = 2F_c φ(h)/σ      (= F_c √(2/π)/σ at μ = 0)
//! ```
//! The derivative of sgn is 2δ(v): c_eq is its expectation, or equivalently Stein's form. It grows without
//! bound as σ → 0: a friction force that the excitation cannot overcome makes the element stick, and route 1
//! then has no Gaussian equivalent (it reports non-convergence).
//!
//! # The sign function in each route
//! * Route 1: sgn is replaced by its Gaussian expectations above (no regularisation). Where the fixed point
//!   makes c_eq more than [`STICK_DAMPING_RATIO`](crate::nonlinear::linearization::STICK_DAMPING_RATIO) times
//!   the critical damping along the element, the Gaussian equivalent describes an element that is locked:
//!   route 1 reports that it has no meaningful answer.
//! * Route 2: the force alone has the exact (Filippov) flow v′ = −κ F_c sgn v: |v| decreases at the rate
//!   κF_c and stays at 0 once it gets there, v(τ) = sgn(v₀) max(|v₀| − κF_cτ, 0). The splitting integrator
//!   applies this flow between exact linear flows, so sticking is represented without a regularised tanh;
//!   the discontinuity makes the scheme first order in Δt near stick–slip transitions (the Δt-halving
//!   difference of every run reports it).
//! * Route 3: no exact stationary density exists with a spring (the dissipation is not linear in v); not
//!   applicable. What is known exactly and approximately is below.
//!
//! # References for x″ + (F_c/m) sgn ẋ + ω²x = f/m
//! White force f, E[f(t)f(t+τ)] = 2πS_f δ(τ), D = πS_f/m² (the velocity's diffusion coefficient), b = mD/F_c:
//! * **Without the spring (exact).** The velocity alone is Markov, dv = −(F_c/m) sgn v dt + √(2D) dW; its
//!   stationary Fokker–Planck equation 0 = ∂_v[(F_c/m) sgn(v) p] + D ∂²_v p has zero flux,
//!   (F_c/m) sgn(v) p + D p′ = 0, so p(v) = e^{−|v|/b}/(2b): a Laplace law, σ_v² = 2b², kurtosis 6. (With a
//!   linear damper c as well, p(v) ∝ exp(−(c v²/2 + F_c|v|)/(m²D)), the same way.)
//! * **Weak friction and noise (stochastic averaging, approximate).** With H = v²/2 + ω²x²/2, Itô gives
//!   dH = (D − (F_c/m)|v|)dt + v√(2D) dW; averaged over a period at fixed H (⟨|v|⟩ = (2/π)√(2H), ⟨v²⟩ = H)
//!   the drift is D − (2F_c/(πm))√(2H) and the diffusion 2DH, whose stationary law is
//!   p(H) ∝ exp(−γ√H), γ = 4√2 F_c/(π m D). Then E[H] = 6/γ², σ_x² = (3π²/16) b²/ω², σ_v² = (3π²/16) b²
//!   (1.85 b²) and the kurtosis of x and of v is 5. It becomes exact as F_c and S_f go to zero together
//!   (many periods per change of energy: Khasminskii's averaging theorem; Roberts & Spanos 1986, "Stochastic
//!   averaging: an approximate method of solving random vibration problems", Int. J. Non-Linear Mech. 21(2),
//!   111–134).
//! * **Route 1** gives σ_v² = πS_f/(m c_eq) with c_eq = F_c√(2/π)/σ_v at any ω: σ_v² = (π/2) b² (1.57 b²,
//!   kurtosis 3), 15 % below the averaging result and 21 % below the spring-free law.
//!
//! `tests/suite/nonlinear_monte_carlo.rs` checks route 2 against the spring-free law with a weak spring and
//! route 1 against its closed form.
//!
//! # Errors
//! [`CoulombFriction::new`] rejects a force that is not finite and ≥ 0.
//!
//! # Examples
//! ```
//! use stochvib::nonlinear::{CoulombFriction, ForceLaw};
//! let f = CoulombFriction::new(1.5).unwrap();
//! // the flow of friction alone stops a slow element: the impulse is its whole momentum
//! assert_eq!(f.impulse(0.0, 0.1, 0.5, 10.0), 0.1 / 0.5);
//! ```

use super::gauss::{density_at_zero, prob_positive};
use super::{ElementMoments, Equivalent, ForceLaw};
use crate::error::{Error, Result};

/// Coulomb friction of force F_c (see the module docs).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CoulombFriction {
    /// F_c, N.
    pub force: f64,
}

impl CoulombFriction {
    /// Friction of force F_c ≥ 0 (N).
    ///
    /// # Errors
    /// See the module's `# Errors`.
    pub fn new(force: f64) -> Result<Self> {
        if !(force.is_finite() && force >= 0.0) {
            return Err(Error::invalid("force", force, "must be finite and >= 0"));
        }
        Ok(CoulombFriction { force })
    }
}

impl ForceLaw for CoulombFriction {
    fn kind(&self) -> &'static str {
        "coulomb-friction"
    }
    fn describe(&self) -> String {
        format!("Coulomb friction F_c = {} N", self.force)
    }
    fn force(&self, _x: f64, v: f64) -> f64 {
        if v > 0.0 {
            self.force
        } else if v < 0.0 {
            -self.force
        } else {
            0.0
        }
    }
    fn velocity_dependent(&self) -> bool {
        true
    }
    fn set_valued(&self) -> bool {
        self.force > 0.0
    }
    fn is_zero(&self) -> bool {
        self.force == 0.0
    }
    fn gaussian(&self, m: &ElementMoments) -> Equivalent {
        let (mu, s) = (m.mean_v, m.sigma_v);
        Equivalent {
            mean_force: self.force * (2.0 * prob_positive(mu, s) - 1.0),
            stiffness: 0.0,
            damping: if s > 0.0 {
                2.0 * self.force * density_at_zero(mu, s)
            } else {
                f64::INFINITY
            },
        }
    }
    fn impulse(&self, _x: f64, v: f64, kappa: f64, tau: f64) -> f64 {
        // |v| falls by κF_cτ, not below 0: the impulse is the momentum removed
        let dv = (kappa * self.force * tau).min(v.abs());
        v.signum() * dv / kappa
    }
    fn potential(&self, _x: f64) -> Option<f64> {
        None
    }
    fn can_stick(&self) -> bool {
        true
    }
    fn sliding_force(&self) -> f64 {
        self.force
    }
    fn stiffness_bound(&self, _m: &ElementMoments) -> f64 {
        0.0
    }
}
