//! What a Monte Carlo run simulates: a system, its random excitation, the outputs to record, the names and
//! units of the input processes, and the provenance text stored with the run.

use crate::response::Excitation;
use crate::store::Signal;
use crate::system::FrequencyResponse;

/// The subject of a Monte Carlo run (built from a scenario by
/// [`Scenario::run_input`](crate::scenario::Scenario::run_input), or by hand).
///
/// # Examples
/// ```
/// use stochvib::response::Excitation;
/// use stochvib::simulate::RunInput;
/// use stochvib::spectrum::{Domain, Exponential};
/// use stochvib::store::Signal;
/// use stochvib::system::StateSpace;
/// use std::sync::Arc;
/// let sys = StateSpace::oscillator(10.0, 0.1).unwrap();
/// let exc = Excitation::single(Arc::new(Exponential::new(1.0, 2.0, Domain::Temporal).unwrap()), 0.0).unwrap();
/// let input = RunInput::new(&sys, &exc, vec![0], vec![Signal::new("force", "N/kg")], "unit oscillator");
/// assert_eq!(input.outputs, vec![0]);
/// ```
#[derive(Debug, Clone)]
pub struct RunInput<'a> {
    /// The system.
    pub system: &'a dyn FrequencyResponse,
    /// Its random excitation.
    pub excitation: &'a Excitation,
    /// Indices of the outputs to simulate (outputs with an infinite variance are skipped with the reason).
    pub outputs: Vec<usize>,
    /// Names and units of the independent input processes, recorded with raw realizations: one signal for
    /// a track (`road` for a road, `input` otherwise), `input_k` for independent processes.
    pub input_signals: Vec<Signal>,
    /// Provenance stored in the run file's `@scenario` attribute (the scenario file's text) and compared
    /// when an interrupted run is resumed.
    pub provenance: String,
}

impl<'a> RunInput<'a> {
    /// Collects the parts of a run's subject.
    pub fn new(
        system: &'a dyn FrequencyResponse,
        excitation: &'a Excitation,
        outputs: Vec<usize>,
        input_signals: Vec<Signal>,
        provenance: impl Into<String>,
    ) -> Self {
        RunInput {
            system,
            excitation,
            outputs,
            input_signals,
            provenance: provenance.into(),
        }
    }
}
