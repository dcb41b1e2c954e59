//! The force law of a nonlinear element: its force, its Gaussian expectations (route 1), the exact flow of
//! its force alone (route 2) and its potential (route 3).

use super::Kernel;
use serde::Serialize;
use std::fmt::Debug;

/// Means and standard deviations of an element's relative displacement x (point minus far end, positive
/// when the element is stretched) and relative velocity v = ẋ, for a Gaussian response.
///
/// In a stationary response x and v are uncorrelated (E\[x ẋ\] = ½ d/dt E\[x²\] = 0) and E\[v\] = 0; the
/// expectations below use the marginals of x and v only.
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize)]
pub struct ElementMoments {
    /// μ_x, m (rad for an element between angles).
    pub mean_x: f64,
    /// σ_x.
    pub sigma_x: f64,
    /// μ_v, m/s.
    pub mean_v: f64,
    /// σ_v.
    pub sigma_v: f64,
}

/// The Gaussian equivalent of an element's nonlinear force: F ≈ F₀ + k_eq (x − μ_x) + c_eq (v − μ_v).
///
/// # Formula
/// F₀ = E\[F\], k_eq = E\[∂F/∂x\], c_eq = E\[∂F/∂v\] over the Gaussian law of (x, v). By Stein's lemma
/// (E[F(z)(z − μ)] = σ² E[F′(z)]) these are also the coefficients that minimise E[(F − F₀ − k x − c v)²]
/// (Atalik & Utku 1976, "Stochastic linearization of multi-degree-of-freedom non-linear systems",
/// Earthquake Eng. Struct. Dyn. 4, 411–420).
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize)]
pub struct Equivalent {
    /// F₀ = E\[F\], N (N m).
    pub mean_force: f64,
    /// k_eq = E[∂F/∂x], N/m.
    pub stiffness: f64,
    /// c_eq = E[∂F/∂v], N s/m.
    pub damping: f64,
}

/// What the statistics of route 2 count for an element with a regime (a stop in contact, a tyre off the
/// ground): the names of the time fraction and of the entry rate, and the levels of its deflection where
/// the regime begins.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Regime {
    /// Name of the fraction of time in the regime, e.g. `contact_fraction`.
    pub fraction: &'static str,
    /// Name of the rate of entries into the regime, e.g. `impact_rate`.
    pub rate: &'static str,
    /// Deflections where the regime begins (the clearances), in the element's unit, each with whether the
    /// regime lies above it (true) or below it.
    pub levels: Vec<(f64, bool)>,
}

/// The nonlinear part of an element's force as a function of its relative displacement x and velocity v.
///
/// An element's force is a linear part k x + c v ([`ForceLaw::linear_part`], added to the linear model)
/// plus this remainder F(x, v) (zero at the static equilibrium x = v = 0). The element pulls its point
/// back with F: the generalised force on the coordinates is −d F, d the element's direction (point
/// weights minus far-end weights).
pub trait ForceLaw: Debug + Send + Sync {
    /// The element kind as written in scenario files, e.g. `bump-stop`.
    fn kind(&self) -> &'static str;

    /// One line with the parameters and units.
    fn describe(&self) -> String;

    /// (k, c) of the linear part, N/m and N s/m, added to the linear model.
    fn linear_part(&self) -> (f64, f64) {
        (0.0, 0.0)
    }

    /// The remainder F(x, v), N.
    fn force(&self, x: f64, v: f64) -> f64;

    /// Whether F depends on v (a damper or friction) rather than on x alone.
    fn velocity_dependent(&self) -> bool;

    /// Whether the remainder vanishes identically (zero nonlinearity: the element is its linear part).
    fn is_zero(&self) -> bool;

    /// Whether the element softens without bound (its force turns back towards zero and beyond at large
    /// deflections, so the motion can escape over a barrier): named when route 2's response escapes.
    fn softening(&self) -> bool {
        false
    }

    /// Whether the force is set-valued at rest (dry friction: any value in [−F_c, F_c] at v = 0, the one
    /// that holds the element stuck). Route 2 then reads the force the element exerts over a step from its
    /// kicks' impulses, not from [`ForceLaw::force`] at the sampled state (which gives 0 while it sticks).
    fn set_valued(&self) -> bool {
        false
    }

    /// F₀, k_eq, c_eq of the remainder over the Gaussian law `m` (see [`Equivalent`]).
    fn gaussian(&self, m: &ElementMoments) -> Equivalent;

    /// The impulse ∫₀^τ F dt of the remainder along its own exact flow v′ = −κ F(x, v) with x fixed, κ the
    /// element's inverse effective mass dᵀM⁻¹d (1/kg). A force of x alone gives τ F(x); velocity laws
    /// override this with their closed-form flow (route 2's integrator applies the impulse as it is).
    fn impulse(&self, x: f64, v: f64, kappa: f64, tau: f64) -> f64 {
        let _ = kappa;
        tau * self.force(x, v)
    }

    /// The law in closed form for route 2's inner loop at κ and a kick duration τ ([`Kernel`]: the same
    /// bits as [`ForceLaw::force`], [`ForceLaw::impulse`] and [`ForceLaw::engaged`], with the constants of
    /// the step computed once); `None` (the default) evaluates the trait methods.
    fn kernel(&self, kappa: f64, tau: f64) -> Option<Kernel> {
        let _ = (kappa, tau);
        None
    }

    /// The potential V(x) = ∫₀ˣ F dx of a force of x alone (J), `None` for a velocity law.
    fn potential(&self, x: f64) -> Option<f64>;

    /// Displacements where F has a kink (clearances), for quadrature breakpoints.
    fn kinks(&self) -> Vec<f64> {
        Vec::new()
    }

    /// The element's regime (contact, lift-off), if it has one.
    fn regime(&self) -> Option<Regime> {
        None
    }

    /// Whether the element is in its regime at deflection x (false without a regime).
    fn engaged(&self, x: f64) -> bool {
        let _ = x;
        false
    }

    /// The magnitude of a force that does not vanish as the velocity goes to zero (dry friction's F_c), N;
    /// 0 for every other law. With κ it is the rate κF_c at which the force alone changes the relative
    /// velocity, which bounds route 2's default step.
    fn sliding_force(&self) -> f64 {
        0.0
    }

    /// Whether the element can stick (dry friction): route 1 then checks that its Gaussian equivalent does
    /// not lock the element.
    fn can_stick(&self) -> bool {
        false
    }

    /// The largest |∂F/∂x| over the displacements the response visits (μ ± 6σ of `m`), N/m: with κ it
    /// gives the element's contact frequency √(κ k), which bounds route 2's time step.
    fn stiffness_bound(&self, m: &ElementMoments) -> f64;
}
