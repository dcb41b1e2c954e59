//! The integration tests, one binary: every file of this directory is a module (one test binary links
//! HDF5 and nalgebra once instead of once per file). `cargo test --test suite MODULE::` runs one file.

#[path = "../common/mod.rs"]
mod common;
#[path = "../fuzz/mod.rs"]
mod fuzz;

mod band_mc;
mod band_table;
mod book;
mod checksum_stability;
mod coherence;
mod comfort;
mod comfort_report;
mod data_files;
mod delays;
mod drawn_and_installed;
mod fast_paths;
mod fast_sweep;
mod fatigue;
mod fuzz_inputs;
mod fuzz_run_files;
mod html_report;
mod laplace_road;
mod layers;
mod limits;
mod linalg;
mod mc_pipeline;
mod merge_streaming;
mod models_articles;
mod models_ch7;
mod models_ch8;
mod monte_carlo;
mod multi_input_scenarios;
mod numerical_truth;
mod output_rule;
mod plots;
mod quad;
mod report_format;
mod response;
mod road;
mod road_cli;
mod road_replay;
mod robustness;
mod scenario;
mod shards;
mod spectra;
mod store;
mod stream_edges;
mod stream_sources;
mod stream_verdicts;
mod streaming;
mod sweep_stream;
mod two_tracks;
mod two_tracks_mc;
mod value_stability;
mod verdict_traps;
mod verdicts;
mod workday;
