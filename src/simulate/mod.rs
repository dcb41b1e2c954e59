//! Monte Carlo simulation of stationary Gaussian processes and of the responses of linear systems.
//!
//! * Random streams ([`rng`]): one documented portable generator ([`GENERATOR`], xoshiro256++); realization
//!   i of seed s draws from its own stream, so results are identical for any thread count or sharding.
//! * Generators: the spectral representation on an FFT grid for any spectrum ([`SpectralGenerator`],
//!   Rayleigh amplitudes by default, [`Amplitudes::PhaseOnly`] labelled), exact discrete-time shaping filters
//!   for rational spectra, streaming in constant memory ([`shaping_simulator`], [`GaussMarkov`]), road
//!   profiles felt by several wheels at speed v ([`RoadTrack`]), and the streamed spectral synthesis of any
//!   spectrum through any system with memory independent of the record length ([`FirSynthesis`]).
//! * Lockstep: [`LANES`] consecutive realizations side by side, each with its own bits — their normals
//!   ([`NormalLanes`], [`fill_standard_normal_lanes`]) and the exact recursion ([`GaussMarkovLanes`]).
//! * A non-Gaussian input with the same spectrum and a prescribed kurtosis: the Laplace moving average of
//!   Bogsjö, Podgórski and Rychlik (2012) on the spectral grid ([`LaplaceMovingAverage`]; a run takes it from
//!   [`RunInput::kurtosis`], one per generator; a scenario from `[input] kurtosis` or `[[input]] kurtosis`).
//! * Time response: exact zero/first-order-hold discretisation ([`zoh`], [`foh`], [`SampledSystem`]) and
//!   Van Loan's white-noise discretisation of the system augmented with its input filters
//!   ([`van_loan`], [`augmented_response`]) — no time-step bias.
//! * Batches ([`run_batch`], [`run_batch_groups`], [`Shard`]): rayon-parallel, mergeable shards.
//! * Whole runs to HDF5 ([`run()`](run::run)): the subject ([`RunInput`]), the options ([`RunOptions`],
//!   [`Route`], [`suggest_step`]), the plan (route choice with its reasons), the engine, the typed per-shard
//!   [`accumulators`] and the [`RunSummary`].
//! * Beyond one machine: one part of a run per process ([`crate::study::shard`]; `simulate --shard I
//!   --of N`) and the bit-identical merge of the parts ([`crate::study::merge_runs`]).

pub mod accumulators;
pub mod agreement;
pub mod bands;
pub mod basic_method;
pub mod batch;
pub mod discretize;
mod engine;
pub mod fft_plans;
mod finish;
mod finished_part;
pub mod fir_stream;
mod input;
pub(crate) mod lane_normals;
pub mod laplace;
mod normal_lanes;
mod options;
mod plan;
pub mod resources;
pub mod rng;
pub mod road_track;
pub mod run;
pub mod shaping;
mod shaping_lanes;
pub(crate) mod shard_pipeline;
pub mod spectral;
mod summary;
pub mod time_sums;
pub mod transfer_grid;
pub mod verdict_stream;
pub mod verdicts;
mod ziggurat_f;

pub use bands::RunBands;
pub use basic_method::{basic_method_rows, RunBasicMethod};
pub use batch::{run_batch, run_batch_groups, Shard};
pub use discretize::{
    augmented_response, covariance_factor, expm, foh, van_loan, zoh, FirstOrderHold, SampledSystem,
    WhiteNoiseDiscretization, ZeroOrderHold,
};
pub use fir_stream::{FirScratch, FirSynthesis, KernelDesign};
pub use input::{source_signals, RunInput};
pub use laplace::{LaplaceGrid, LaplaceMovingAverage, LaplaceScratch, LAPLACE_DRAWS};
pub use normal_lanes::{fill_standard_normal_lanes, NormalLanes, LANES};
pub use options::{readable_duration, readable_step, suggest_step, Route, RunOptions, StepSuggestion};
pub use plan::{planned_memory, planned_variances, PlannedMemory, PlannedVariance, SkippedOutput};
pub use rng::{fill_standard_normal, splitmix64, standard_normal, stream, stream_key, uniform01, GENERATOR};
pub use road_track::{RoadScratch, RoadTrack, RoadTrackGrid};
pub use run::{run, run_temporary, run_temporary_with, WARMUP_DECAY};
pub use shaping::{shaping_simulator, GaussMarkov, GaussMarkovStream};
pub use shaping_lanes::{GaussMarkovLanes, LANE_DRAW_STEPS};
pub use spectral::{Amplitudes, SpectralGenerator, SpectralScratch};
pub(crate) use summary::write_band_tables;
pub use summary::{coverage_cause, covers_word, RunSummary};
pub use time_sums::{TimeSumLanes, TimeSums, TIME_SUM_WAYS};
pub use verdicts::{ComfortChannel, FatigueChannel, RainflowSummary, VerdictChannels};
// the engine and plan of linear runs, for the input synthesis of nonlinear runs (crate::nonlinear), and the
// finishing of a run's statistics, for the merge of shard files (crate::study)
pub(crate) use engine::{samples, Scratch};
pub(crate) use finish::{
    density_estimate, interval as finish_interval, output_statistics, read_output as read_output_accumulators,
    Analytic, OutputFold,
};
pub(crate) use lane_normals::StreamNormals;
pub(crate) use plan::{plan, Plan};
