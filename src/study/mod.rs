//! Studies: what is run on a scenario read by [`crate::scenario`], built on [`crate::response`],
//! [`crate::simulate`] and [`crate::store`].
//!
//! * Parameter studies ([`sweep`]): a scenario over a grid or a list of key values, their table
//!   ([`sweep_table`], written as CSV, JSON or HDF5, streamed block by block by [`sweep_stream`]), split
//!   into shard files of a cluster run and merged ([`merge_sweep`]), and the verdicts of every point
//!   ([`sweep_verdicts`]).
//! * The shard contract of a cluster run ([`shard`]: which part a process computes, from `--shard I --of N`
//!   or the scheduler, and the file it writes), shared by runs and parameter studies, and the bit-identical
//!   merge of a run's shard files ([`merge_runs`], and of a transient run's, [`merge_transient`]).
//! * A scenario's Monte Carlo run ([`Scenario::simulate`](crate::scenario::Scenario::simulate)).
//! * A measured road profile replayed through a scenario's model ([`replay`]); a measured profile's density,
//!   ISO 8608 fits, IRI and coherence ([`road_profile`]); the coherence of a model beside a profile's and the
//!   expected IRI of a road spectrum beside a profile's ([`road_numbers`]).
//! * The verdicts of a scenario: analytic ([`verdict_analysis()`], with the input's coverage of the
//!   frequencies they need, [`input_coverage`]) and by Monte Carlo with the weighted outputs appended
//!   (`verdict_run`), the time step of a scenario's run ([`run_step`]) and a working day of tasks
//!   ([`workday`]).
//! * Non-stationary runs ([`transient_run`], [`transient_answers`], [`transient_mc`]) and the three routes
//!   of a scenario with nonlinear elements (`nonlinear_run`) with what `stochvib analyze` reports of them
//!   ([`nonlinear_report()`]).
//!
//! * The curves of a scenario's pictures as plain data ([`scenario_curves`]: input densities, cross-spectra,
//!   coherence, |H|², output densities with the cumulative variance, weighted densities, the model
//!   correlation of a stored output), which [`crate::plot`] draws.
//! * What `stochvib analyze` and `stochvib spectrum` report ([`analysis`] with its band tables,
//!   [`band_section`], and Monte Carlo verdict values, [`mc_verdicts`]; [`spectrum_report()`]), and what
//!   `stochvib tailor` reports ([`tailoring`]: ERS and FDS of a spectrum file or a scenario output).
//! * The poles of a scenario's model ([`poles`]); the result tables of a deterministic scenario
//!   ([`deterministic`]).
//! * A frequency weighting at given frequencies, analytic and digital ([`weighting_table`]).
//!
//! The [`crate::report`] layer formats what these return; [`crate::store`] holds the run files.

pub mod analysis;
pub mod band_section;
pub mod deterministic;
mod float_text;
pub mod input_coverage;
pub mod mc_verdicts;
mod merge;
pub mod merge_kind;
mod merge_transient;
pub mod nonlinear_report;
mod nonlinear_run;
pub mod poles;
pub mod replay;
pub mod road_numbers;
pub mod road_profile;
pub mod run_step;
pub mod scenario_curves;
mod scenario_run;
pub mod seat_factor;
pub mod shard;
pub mod spectrum_report;
pub mod static_sag;
pub mod sweep;
mod sweep_h5;
pub mod sweep_stream;
pub mod sweep_table;
pub mod sweep_verdicts;
pub mod tailoring;
pub mod transient_answers;
pub mod transient_mc;
pub mod transient_run;
pub mod verdict_analysis;
mod verdict_run;
pub mod weighting_table;
pub mod workday;

pub use crate::nonlinear::monte_carlo::escaped;
pub use crate::store::MergeOptions;
pub use analysis::{analysis_report, attach_monte_carlo, AnalysisReport};
pub use deterministic::deterministic_tables;
pub use merge::{merge_runs, MergeSummary};
pub use merge_transient::merge_transient;
pub use nonlinear_report::{nonlinear_report, nonlinear_report_escaped, NonlinearReport};
pub use nonlinear_run::NonlinearAnswers;
pub use shard::{part_path, resolve_part, ShardChoice};
pub use spectrum_report::{spectrum_report, spectrum_report_at, DensityPoints, SpectrumReport};
pub use sweep::{
    substituted_text, value_text as sweep_value_text, Sweep, SweepMode, SweepParam, SweepPath, SweepSpec, FAILED_POINT,
};
pub use sweep_stream::{stream_sweep_csv, write_sweep_table, StreamOptions, StreamedTable};
pub use sweep_table::{
    check_monte_carlo_time, check_table_resources, compute_sweep, find_sweep_shards, merge_sweep, run_sweep_shard,
    SweepMonteCarlo, SweepResults, TableFormat, SWEEP_SHARD, SWEEP_TABLE,
};
pub use verdict_analysis::{
    verdict_analysis, ComfortAxisResult, ComfortVerdict, FatigueMethodResult, FatigueVerdict, HealthAxisResult,
    HealthEvaluation, VerdictAnalysis,
};
pub use verdict_run::{simulate_with_verdicts, verdict_system, with_verdict_input};
