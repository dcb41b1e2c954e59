//! Fuzz and corruption harnesses, shared by
//! `examples/fuzz.rs` and `examples/corrupt_runs.rs` (long runs) and by `tests/fuzz_inputs.rs` and
//! `tests/fuzz_run_files.rs` (bounded runs with a fixed seed).
//!
//! * [`mutate`]: a structure-aware TOML mutator (no fuzzing crate, stable Rust).
//! * [`inputs`]: input-file cases, their evaluation through the library's entry points, the invariants.
//! * [`commands`]: the other formats and commands (road profiles, `replay`, `sweep`, `merge` sets,
//!   `workday` files): generation, evaluation, invariants.
//! * [`nonlinear`]: mutations of the `[[model.nonlinear]]` element tables of scenarios.
//! * [`records`]: the record commands (`exposure`, `fatigue`, `coherence`, `iri`, `weighting`) with
//!   their flags.
//! * [`transient`]: mutations of the non-stationary keys of transient scenarios (`stochvib transient`).
//! * [`optimize`]: `stochvib optimize` with hostile parameters, bounds, objectives and constraints.
//! * [`cli_commands`]: `simulate`, `plot`, `report`, `inspect`, `check-run`, `book`, `spectra`, `models`
//!   through the CLI with hostile flags, inputs and output targets.
//! * [`input_campaign`]: worker processes, supervisor, CLI runs, special files, minimisation, reproducers.
//! * [`runs`]: corruption of HDF5 run files and of interrupted runs' `.tmp` files.
//! * [`floats`]: the non-finite number scan of a report (through serde).
//! * [`process`]: child processes with a time limit and an address-space limit.
#![allow(dead_code)] // each harness uses a different subset

pub mod cli_commands;
pub mod commands;
pub mod floats;
pub mod input_campaign;
pub mod inputs;
pub mod mutate;
pub mod nonlinear;
pub mod optimize;
pub mod process;
pub mod records;
pub mod runs;
pub mod transient;
