//! The types most programs need, in one import: `use stochvib::prelude::*;`.
//!
//! Spectra (the four standard correlation types, rational, ISO 8608 roads, tabulated), systems (state space,
//! transfer functions, multi-degree-of-freedom models, the oscillator and the quarter car), the response
//! statistics, Monte Carlo runs and their HDF5 files, and scenario files.

pub use crate::error::{Error, Result};
pub use crate::models::quarter_car::QuarterCar;
pub use crate::response::{analyze_output, band_variance, output_density, Excitation, ResponseStatistics};
pub use crate::scenario::{load_document, load_scenario, Catalogue, Document, Scenario};
pub use crate::simulate::{run, suggest_step, Route, RunInput, RunOptions, RunSummary};
pub use crate::spectrum::{
    AtSpeed, BandWhite, BandWhiteParameters, Convention, Domain, ExpCosine, Exponential, GaussCosine,
    GaussCosineParameters, Gaussian, IsoClass, PowerLaw, PowerLawParameters, RationalSpectrum, Spectrum, Tabulated,
};
pub use crate::store::{RunFile, Signal};
pub use crate::system::{
    Attach, Drive, Element, FrequencyResponse, MassSpringDamper, Mdof, OutputInfo, Quantity, StateSpace,
    TransferFunction,
};
