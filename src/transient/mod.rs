//! Non-stationary response: inputs and systems that change over a manoeuvre (a vehicle accelerating or
//! braking over a rough road, a load building up on start-up, a hoist winding its rope), the exact
//! time-varying mean and covariance, and the crossing rates and expected crossings over a mission. The
//! formulas, keys and conventions are collected in `docs/transients.md`.
//!
//! # Conventions (read this first)
//! * Time t in s from the start of the manoeuvre (t = 0).
//! * A speed profile v(t) ≥ 0 (m/s) maps the road coordinate x(t) = ∫₀ᵗ v ds onto time ([`SpeedProfile`]).
//! * White noise of two-sided density S₀ has E\[w(t)w(t+τ)\] = 2πS₀δ(τ); the Lyapunov noise matrix of a
//!   white input is Q = 2πS₀ (the crate's convention, `crate::spectrum`).
//! * An envelope a(t) multiplies a stationary process: u(t) = a(t)s(t) ([`Envelope`]).
//! * A scheduled system takes its model's equations at the parameter values of each instant (frozen
//!   coefficients, [`SystemFamily`]).
//!
//! # Pieces
//! * [`PiecewiseLinear`], [`SpeedProfile`], [`Envelope`], [`Schedule`]: the time functions, validated.
//! * [`TimeVaryingSystem`]: a (scheduled) system and its random input in the form ż = F(t)z + G(t)w + b(t),
//!   y = H(t)z + y₀(t) with unit-intensity white noise — exact for white inputs, rational spectra (a
//!   spatial shaping filter under v(t) becomes a time-varying filter) and w = 2 roads (white road velocity).
//! * [`propagate`] / [`solve`]: the differential Lyapunov equation Ṗ = FP + PFᵀ + GGᵀ, ṁ = Fm + b by matrix
//!   exponentials on an adaptive grid with an error estimate, and the output statistics over time
//!   ([`TransientSolution`]); [`affine_step`]: its exact step where only the noise intensity varies, linearly
//!   between knots.
//! * [`sources`]: several independent inputs ([`ExtraSource`]), their filters block-diagonal ahead of the
//!   system ([`TimeVaryingSystem::with_sources`]).
//! * [`evolutionary`]: inputs without a finite shaping filter (tabulated, measured, band-limited) by the
//!   evolutionary spectrum of the frozen system, with its slow-variation assumption checked at every time.
//! * [`road_grid`]: Monte Carlo of a vehicle on a road synthesised on a spatial grid and sampled along x(t),
//!   for any road spectrum under a speed profile; [`road_grid_run`] stores it as a transient run file;
//!   [`road_wheels`]: the same for wheels at positions on one track or on two coherent tracks.
//! * [`monte_carlo`]: the same by simulation ([`mc_engine`], [`mc_finish`]), stored as time series of
//!   statistics in a run file; [`mission`]: the analytic distributions of the maxima of a mission.

pub mod affine_step;
mod envelope;
pub mod evolutionary;
pub mod inputs;
pub mod lyapunov_ode;
pub mod mc_engine;
pub mod mc_finish;
pub mod mission;
pub mod monte_carlo;
mod profile;
pub mod road_grid;
pub mod road_grid_run;
pub mod road_wheels;
pub mod rope;
mod schedule;
pub mod series;
pub mod sources;
mod speed_profile;
pub mod system;

pub use envelope::Envelope;
pub use evolutionary::{solve_evolutionary, EvolutionaryInput, EvolutionarySolution};
pub use inputs::{input_model, white_slope_coefficient};
pub use lyapunov_ode::{propagate, ExactOptions, StepReport};
pub use mc_engine::{McGrid, McGridSpec};
pub use mission::{stationary_moments, StationaryMoments};
pub use monte_carlo::{run_transient, TransientRunInput, TransientRunOptions, TransientRunSummary};
pub use profile::PiecewiseLinear;
pub use road_grid::{road_grid_monte_carlo, RoadGridOptions, RoadGridStatistics};
pub use road_grid_run::{run_road_grid, RoadGridRunInput};
pub use road_wheels::{road_wheels_monte_carlo, MatrixCoherence, Wheel, WheelRoad};
pub use rope::RopeFormula;
pub use schedule::{check_stability, FamilyBuilder, FixedSystem, ModelAt, Schedule, ScheduledSystem, SystemFamily};
pub use series::{solve, Crossings, OutputSeries, TransientSolution};
pub use sources::ExtraSource;
pub use speed_profile::{ConstantAcceleration, SpeedProfile};
pub use system::{Frozen, InputModel, Start, TimeVaryingSystem, TransientInput};
