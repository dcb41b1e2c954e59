//! The single-degree-of-freedom oscillator, written once: as a state-space system driven by a force per unit
//! mass, and as a mass on a spring and damper driven through its base or by a force.

use super::{Attach, Element, Mdof, OutputInfo, StateSpace};
use crate::error::{require_non_negative, require_positive, Result};
use nalgebra::DMatrix;

/// How the mass of a [`MassSpringDamper`] is driven.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Drive {
    /// Input 0 is the base displacement u (m): the spring and the damper connect the mass to the base.
    Base,
    /// Input 0 is a force F (N) on the mass: the spring and the damper connect it to the fixed ground.
    Force,
}

impl StateSpace {
    /// The unit-mass oscillator ẍ + 2ζωₙẋ + ωₙ²x = u.
    ///
    /// # Formula
    /// States (x, ẋ), input u in m/s² (a force per unit mass), output `x` in m:
    /// ```text
    /// A = [[0, 1], [−ωₙ², −2ζωₙ]],   B = [0, 1]ᵀ,   C = [1, 0],   H(s) = 1/(s² + 2ζωₙ s + ωₙ²)
    /// ```
    ///
    /// # Errors
    /// [`Error::InvalidParameter`](crate::Error::InvalidParameter) for ωₙ ≤ 0 or ζ < 0 (or non-finite).
    ///
    /// # Examples
    /// ```
    /// use stochvib::system::{FrequencyResponse, StateSpace};
    /// let ss = StateSpace::oscillator(10.0, 0.05).unwrap();
    /// // at resonance |H| = 1/(2ζωₙ²)
    /// assert!((ss.response(10.0)[(0, 0)].norm() - 1.0 / (2.0 * 0.05 * 100.0)).abs() < 1e-12);
    /// ```
    pub fn oscillator(omega_n: f64, zeta: f64) -> Result<StateSpace> {
        let w = require_positive("omega_n", omega_n)?;
        let z = require_non_negative("zeta", zeta)?;
        StateSpace::new(
            DMatrix::from_row_slice(2, 2, &[0.0, 1.0, -w * w, -2.0 * z * w]),
            DMatrix::from_row_slice(2, 1, &[0.0, 1.0]),
            DMatrix::from_row_slice(1, 2, &[1.0, 0.0]),
            None,
            None,
            vec![OutputInfo::new("x", "m")],
        )
    }
}

/// A mass on a spring and a damper, each parameter named: coordinate `x` (m), element `spring` (its
/// deflection and forces are element 0 of [`Quantity`](super::Quantity)), driven through the base or by a
/// force ([`Drive`]). [`build`](Self::build) gives the [`Mdof`] model, with no outputs yet: add them with
/// [`Mdof::with_output`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MassSpringDamper {
    /// Mass m, kg (> 0).
    pub mass: f64,
    /// Spring stiffness k, N/m (≥ 0).
    pub stiffness: f64,
    /// Viscous damping b, N s/m (≥ 0).
    pub damping: f64,
    /// What drives the mass: its base (input u, m) or a force on it (input F, N).
    pub drive: Drive,
}

impl MassSpringDamper {
    /// The model of these parameters.
    ///
    /// # Formula
    /// ```text
    /// Base:  m ẍ + b (ẋ − u̇) + k (x − u) = 0     (input u, m)
    /// Force: m ẍ + b ẋ + k x = F                 (input F, N)
    /// ```
    ///
    /// # Errors
    /// [`Error::InvalidParameter`](crate::Error::InvalidParameter) for m ≤ 0, k < 0, b < 0 (or non-finite).
    ///
    /// # Examples
    /// ```
    /// use stochvib::system::{Drive, FrequencyResponse, MassSpringDamper, Quantity};
    /// let m = MassSpringDamper { mass: 100.0, stiffness: 1.0e4, damping: 200.0, drive: Drive::Base }
    ///     .build()
    ///     .unwrap()
    ///     .with_output("x", Quantity::Displacement(vec![1.0]))
    ///     .unwrap();
    /// // a base-driven mass follows the base at zero frequency
    /// assert!((m.static_gain().unwrap()[(0, 0)] - 1.0).abs() < 1e-12);
    /// ```
    pub fn build(&self) -> Result<Mdof> {
        let Self {
            mass,
            stiffness,
            damping,
            drive,
        } = *self;
        require_positive("mass", mass)?;
        require_non_negative("stiffness", stiffness)?;
        require_non_negative("damping", damping)?;
        let (to, n_base, forces) = match drive {
            Drive::Base => (Attach::Base(0), 1, vec![]),
            Drive::Force => (Attach::Ground, 0, vec![vec![1.0]]),
        };
        let el = Element {
            name: "spring".into(),
            point: vec![1.0],
            to,
            stiffness,
            damping,
        };
        Mdof::from_elements(&[("x", "m")], &[mass], vec![el], n_base, &forces)
    }
}
