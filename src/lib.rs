//! # stochvib
//!
//! Stochastic vibration and random-road analysis of machines: spectral densities of random roads and
//! loads, linear models of machines, and the statistics of their responses computed three independent
//! ways — analytically (exact Lyapunov covariance, the integral table I_n), by adaptive quadrature of the
//! output density, and by Monte Carlo in the time domain with every run stored in HDF5.
//!
//! Every spectral density inside the crate is the **two-sided density in angular frequency** S(ω) (ω in
//! rad/s, or rad/m for road profiles); other conventions are named conversions ([`spectrum`] explains the
//! normalization, [`spectrum::Convention`] converts).
//!
//! # Example
//! A passenger-car corner on an ISO 8608 class C road at 20 m/s: σ and 3σ bounds of the body acceleration
//! and the suspension travel, then a small seeded Monte Carlo batch of the same outputs.
//! ```
//! use stochvib::prelude::*;
//! use std::sync::Arc;
//!
//! let car = QuarterCar {
//!     sprung_mass: 300.0,         // kg
//!     unsprung_mass: 40.0,        // kg
//!     suspension_stiffness: 20e3, // N/m
//!     suspension_damping: 1.5e3,  // N s/m
//!     tyre_stiffness: 200e3,      // N/m
//!     tyre_damping: 0.0,          // N s/m
//! }
//! .build()?;
//! let sys = car.system()?;
//! let road = Excitation::road(Arc::new(PowerLaw::iso_class(IsoClass::C)?), 20.0, &[0.0])?;
//! let outputs = vec![sys.output_index("body_acc")?, sys.output_index("travel")?];
//! for &i in &outputs {
//!     let st = analyze_output(&sys, &road, i)?;
//!     let (lo, hi) = st.bounds(3.0).unwrap();
//!     println!("{}: σ = {:.4} {u}, 3σ bounds [{lo:.4}, {hi:.4}] {u}", st.name, st.sigma.unwrap(), u = st.unit);
//! }
//! let input = RunInput::new(&sys, &road, outputs, vec![Signal::new("road", "m")], "quarter car, class C");
//! let file = std::env::temp_dir().join(format!("stochvib-crate-example-{}.h5", std::process::id()));
//! # let _ = std::fs::remove_file(&file);
//! let opts = RunOptions { realizations: 20, duration_s: 20.0, dt_s: 0.005, seed: 7, ..RunOptions::default() };
//! let mc = run(&input, &opts, &file, &|_, _| {})?;
//! for o in &mc.outputs {
//!     let s = o.get("sigma").unwrap();
//!     let (iv, analytic) = (s.interval, s.analytic.unwrap());
//!     println!("{}: Monte Carlo σ = {:.4} in [{:.4}, {:.4}] (analytic {analytic:.4})", o.output, iv.estimate, iv.lower, iv.upper);
//! }
//! # std::fs::remove_file(&file)?;
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```
//!
//! # Layers
//! Data flows one way, and no module imports from a layer above its own (checked by `tests/suite/layers.rs`):
//!
//! | layer | modules | what |
//! |---|---|---|
//! | 0 | [`error`], [`numbers`], [`units`], [`fields`], [`io_rules`], [`quad`], [`quad_oscillatory`], [`linalg`] | errors, units, file fields, the file and resource rules, numerics |
//! | 1 | [`spectrum`], [`coherence`] | spectral densities and correlation functions; coherence of parallel tracks |
//! | 2 | [`system`] | frequency responses: state space, transfer functions, multi-degree-of-freedom models |
//! | 3 | [`response`], [`comfort`], [`extremes`] | response statistics: variance three ways, moments, crossing rates; ISO 2631 weightings and exposure; extremes of a mission, ERS and FDS |
//! | 4 | [`estimate`], [`store`], [`fatigue`] | estimators with intervals; HDF5 run files; S–N curves, rainflow, spectral fatigue |
//! | 5 | [`simulate`], [`road`], [`nonlinear`], [`record`], [`transient`] | Monte Carlo runs; measured and synthesised road profiles, IRI, a profile replayed through a model; nonlinear elements and their three routes; measured records (CSV, HDF5, WAV): ISO 2631-1 exposure and rainflow fatigue; non-stationary response (exact and Monte Carlo) |
//! | 6 | [`models`] | the catalogue of the source documents |
//! | 7 | [`scenario`] | reading scenario, spectrum, reference and workday files; the spectrum catalogue; the registry of model kinds |
//! | 8 | [`study`], [`optimize`] | what is run on a scenario: the numbers of the analysis and spectrum reports; parameter sweeps and their tables, shard files and the merge of runs and tables; replay of a measured profile; analytic and Monte Carlo verdicts; a working day; transients; the nonlinear routes; design by constrained optimisation over scenario values |
//! | 9 | [`report`], [`plot`] | what the command-line tool prints and draws |
//! | 10 | [`prelude`] | the common imports |

#![warn(missing_docs)]
// No function a reader has to scroll: `cargo clippy` (with `-D warnings`) refuses a function of more than
// 100 lines of code (the default threshold of the lint).
#![warn(clippy::too_many_lines)]

/// The README's Rust example, compiled and run as a doctest.
#[cfg(doctest)]
#[doc = include_str!("../README.md")]
pub struct ReadmeExample;

pub mod coherence;
pub mod comfort;
pub mod error;
pub mod estimate;
pub mod extremes;
pub mod fatigue;
pub mod fields;
pub mod io_rules;
pub mod linalg;
pub mod models;
pub mod nonlinear;
pub mod numbers;
pub mod optimize;
pub mod plot;
pub mod prelude;
pub mod quad;
pub mod quad_oscillatory;
pub mod record;
pub mod report;
pub mod response;
pub mod road;
pub mod scenario;
pub mod simulate;
pub mod spectrum;
pub mod store;
pub mod study;
pub mod system;
pub mod transient;
pub mod units;

pub use error::{Error, Result};

/// The test suite's named tolerances (`tests/common/tolerance.rs`), for the unit tests.
#[cfg(test)]
#[path = "../tests/common/tolerance.rs"]
#[allow(dead_code)]
mod tolerance;
