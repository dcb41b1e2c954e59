//! Linear systems: anything with a frequency response H(iω) (outputs × inputs).
//!
//! # Convention
//! H(iω) maps input amplitudes to output amplitudes at angular frequency ω (rad/s, or rad/m for a system
//! driven along a road coordinate): y(iω) = H(iω) u(iω). Every output carries a name and an SI unit.
//! A system may also pass the **derivative** of its inputs to its outputs (a damper attached to a moving
//! base transmits b·u̇): [`StateSpace`] therefore has the form
//!
//! ```text
//! ẋ = A x + B u,      y = C x + D u + E u̇,      H(s) = C (sI − A)⁻¹ B + D + s E.
//! ```

use crate::spectrum::Asymptote;
use nalgebra::{Complex, DMatrix};
use std::fmt::Debug;

pub mod mdof;
mod oscillator;
mod state_space;
mod transfer_function;
mod transfer_row;

pub use mdof::{modal_analysis, Attach, Element, Mdof, Output, OutputWeights, Quantity};
pub use oscillator::{Drive, MassSpringDamper};
pub use state_space::{StateSpace, STABILITY_RESOLUTION};
pub use transfer_function::TransferFunction;
pub use transfer_row::TransferRow;

/// Name and SI unit of a system output (e.g. `x1_acc`, `m/s^2`).
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct OutputInfo {
    /// Name used in scenario files and reports.
    pub name: String,
    /// SI unit.
    pub unit: String,
}

impl OutputInfo {
    /// Builds an output description.
    pub fn new(name: impl Into<String>, unit: impl Into<String>) -> Self {
        OutputInfo {
            name: name.into(),
            unit: unit.into(),
        }
    }
}

/// A linear time-invariant system known through its frequency response.
pub trait FrequencyResponse: Debug + Send + Sync {
    /// Number of inputs.
    fn n_inputs(&self) -> usize;
    /// The outputs with names and units.
    fn outputs(&self) -> &[OutputInfo];
    /// H(iω), outputs × inputs.
    fn response(&self, omega: f64) -> DMatrix<Complex<f64>>;
    /// The zero-frequency gain H(0) (for the mean response); `None` when it is infinite (a free rigid-body
    /// mode, an integrator).
    fn static_gain(&self) -> Option<DMatrix<f64>>;
    /// How |H_ij(iω)|² behaves as ω → ∞, per output × input.
    fn high_frequency(&self) -> Vec<Vec<Asymptote>>;
    /// How |H_ij(iω)|² behaves as ω → 0, per output × input (`Power { exponent: 0, .. }` for a finite
    /// non-zero static gain; a positive exponent when H(0) = 0, e.g. a relative displacement).
    fn low_frequency(&self) -> Vec<Vec<Asymptote>>;
    /// Natural frequencies |λ| of the poles (rad/s), for quadrature breakpoints.
    fn natural_frequencies(&self) -> Vec<f64>;
    /// The exact state-space form, when the system is finite-dimensional.
    fn state_space(&self) -> Option<&StateSpace>;

    /// The multi-degree-of-freedom model behind the response, when it is one (nonlinear elements are
    /// placed on its coordinates).
    fn as_mdof(&self) -> Option<&Mdof> {
        None
    }

    /// Index of the output called `name`.
    ///
    /// # Errors
    /// [`Error::InvalidParameter`](crate::Error::InvalidParameter) naming the outputs there are.
    fn output_index(&self, name: &str) -> crate::Result<usize> {
        let outs = self.outputs();
        outs.iter().position(|o| o.name == name).ok_or_else(|| {
            crate::Error::invalid(
                "output",
                name,
                format!(
                    "no such output; the system has: {}",
                    outs.iter().map(|o| o.name.as_str()).collect::<Vec<_>>().join(", ")
                ),
            )
        })
    }
}
