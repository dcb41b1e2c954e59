//! A system known only through its frequency response: a state space whose `state_space()` is hidden, so
//! the library takes its dense (response-only) paths.

use nalgebra::{Complex, DMatrix};
use stochvib::spectrum::Asymptote;
use stochvib::system::{FrequencyResponse, OutputInfo, StateSpace};

/// The frequency response of the wrapped state space, without its state-space form (exercises the dense
/// path of the quadrature and the "not applicable" answer of the exact route).
#[derive(Debug)]
pub struct ResponseOnly(pub StateSpace);

impl FrequencyResponse for ResponseOnly {
    fn n_inputs(&self) -> usize {
        self.0.n_inputs()
    }
    fn outputs(&self) -> &[OutputInfo] {
        self.0.outputs()
    }
    fn response(&self, omega: f64) -> DMatrix<Complex<f64>> {
        self.0.response(omega)
    }
    fn static_gain(&self) -> Option<DMatrix<f64>> {
        self.0.static_gain()
    }
    fn high_frequency(&self) -> Vec<Vec<Asymptote>> {
        self.0.high_frequency()
    }
    fn low_frequency(&self) -> Vec<Vec<Asymptote>> {
        self.0.low_frequency()
    }
    fn natural_frequencies(&self) -> Vec<f64> {
        self.0.natural_frequencies()
    }
    fn state_space(&self) -> Option<&StateSpace> {
        None
    }
}
