//! Reports: the tables the command-line tool prints, as plain data (serialisable to JSON) plus a text
//! rendering. The CLI only parses arguments, calls these and prints. Where a report's numbers are computed
//! by [`crate::study`] (the analysis, its band tables and Monte Carlo verdicts, a spectrum's numbers), the
//! module here only renders them.

pub mod analysis_text;
pub mod band_text;
pub mod book;
pub mod catalogue;
pub mod handover;
pub mod html;
pub mod markdown;
pub mod mc_verdicts_text;
pub mod nonlinear_report;
pub mod record_report;
pub mod replay_report;
pub mod road_numbers;
pub mod road_report;
pub mod run_handover;
pub mod run_summary;
pub mod spectrum_text;
pub mod table;
pub mod tables;
pub mod tailoring_text;
pub mod transient_report;
pub mod verdict_report;
pub mod workday_handover;
pub mod workday_report;

pub use book::BookReport;
pub use catalogue::{catalogue_report, models_report, CatalogueReport, ModelsReport};
pub use markdown::inspect_markdown;
pub use run_summary::summarize;
pub use tables::{deterministic_report, reference_report, TablesReport};
pub use workday_report::WorkdayReport;
