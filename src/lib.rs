//! # stochvib
//!
//! Stochastic vibration and random-road analysis of machines: spectral densities of random roads and
//! loads, linear models of machines, and the statistics of their responses computed three independent
//! ways (analytic, frequency-domain quadrature, Monte Carlo).
//!
//! See [`spectrum`] for the normalization of spectral densities used everywhere in the crate.

pub mod coherence;
pub mod error;
pub mod estimate;
pub mod linalg;
pub mod models;
pub mod plot;
pub mod quad;
pub mod report;
pub mod response;
pub mod road;
pub mod scenario;
pub mod simulate;
pub mod spectrum;
pub mod store;
pub mod system;
pub mod tolerance;
pub mod units;

pub use error::{Error, Result};
