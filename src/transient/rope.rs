//! The parameters of a hoist as functions of its rope length l: what a `[[transient.schedule]]` with a
//! `rope` formula computes from the winding schedule l(t) (`docs/transients.md`, "Time-varying systems").

use crate::error::{Error, Result};

/// A parameter of a skip (end mass) hanging on a rope of length l, as a function of l.
///
/// # Formula
/// * `Stiffness`: c(l) = EF/l with EF = E·ā·d_k² the rope's axial rigidity (Dvornikov, Kondrakhin &
///   Velebnik 2014, "Natural frequencies and mode shapes of a lifting machine with one end", eq. (3):
///   C_отв = E ā d_k²/l₂; the same law in Sukharev 2012, "Fundamentals of dynamics of lifting-transport and
///   road-construction machines", the rope as a spring of stiffness EF/l).
/// * `RayleighMass`: m + γl/3, the end mass with a third of the rope's mass (Rayleigh's estimate for a
///   spring of uniform mass, the textbook's reduction of the rope to its end).
/// * `LumpedMass`: m + γl/4, the skip's diagonal entry of the mass matrix of Dvornikov et al. 2014, eq. (14)
///   (the rope's kinetic energy γl(ẏ₁ + ẏ₂)²/8 of eq. (11), the sheave held fixed).
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
#[serde(rename_all = "kebab-case", tag = "formula")]
pub enum RopeFormula {
    /// EF/l, N/m.
    Stiffness {
        /// EF, N.
        axial_rigidity: f64,
    },
    /// m + γl/3, kg.
    RayleighMass {
        /// m, kg.
        end_mass: f64,
        /// γ, kg/m.
        mass_per_metre: f64,
    },
    /// m + γl/4, kg.
    LumpedMass {
        /// m, kg.
        end_mass: f64,
        /// γ, kg/m.
        mass_per_metre: f64,
    },
}

impl RopeFormula {
    /// The parameter at rope length `l` (m).
    ///
    /// # Errors
    /// l not finite and > 0.
    pub fn value(&self, l: f64) -> Result<f64> {
        if !(l.is_finite() && l > 0.0) {
            return Err(Error::invalid("rope length", l, "must be finite and > 0 m"));
        }
        Ok(match *self {
            RopeFormula::Stiffness { axial_rigidity } => axial_rigidity / l,
            RopeFormula::RayleighMass {
                end_mass,
                mass_per_metre,
            } => end_mass + mass_per_metre * l / 3.0,
            RopeFormula::LumpedMass {
                end_mass,
                mass_per_metre,
            } => end_mass + mass_per_metre * l / 4.0,
        })
    }
}
