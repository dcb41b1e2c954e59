//! Input files: spectrum files (`spectra/*.toml`), scenario files (`data/*.toml`) and reference tables
//! (`data/reference/*.toml`), the spectrum catalogue and the registry of model kinds.
//!
//! Every value read from a file is validated; an error names the file, the dotted key, the value as
//! written and the reason ([`Error::File`](crate::Error::File)).
//!
//! [`replay`] replays a measured road profile through a scenario's model (`stochvib replay`).

mod butterworth_keys;
mod catalogue;
pub mod generic;
pub mod input_coverage;
mod input_filters;
pub mod inputs;
pub mod nonlinear_keys;
mod nonlinear_run;
mod profile_identity;
pub mod reference;
mod registry;
pub mod replay;
pub mod run_step;
pub mod scenario_file;
pub mod seat_factor;
pub mod spectrum_file;
pub mod sweep;
pub mod transient_answers;
pub mod transient_keys;
pub mod transient_mc;
pub mod transient_run;
pub mod verdict_analysis;
mod verdict_run;
pub mod verdict_spec;
pub mod workday;

pub use catalogue::{spectrum_catalogue, Catalogue, CatalogueEntry, SpectrumOrigin};
pub use inputs::coherence_from_toml;
pub use nonlinear_run::NonlinearAnswers;
pub use profile_identity::input_as_written;
pub use reference::ReferenceTable;
pub use registry::{
    build_model, kind_names, model_kind, BuiltModel, Family, ModelContext, ModelKind, NumericModel, MODEL_KINDS,
};
pub use scenario_file::{
    load_document, load_scenario, parse_document, parse_scenario, AnalysisOptions, DeterministicScenario, Document,
    Scenario, ScenarioInput,
};
pub use spectrum_file::{load_spectrum, parse_spectrum, SpectrumFile};
pub use sweep::{
    substituted_text, value_text as sweep_value_text, Sweep, SweepMode, SweepParam, SweepPath, SweepSpec, FAILED_POINT,
};
pub use verdict_analysis::{
    verdict_analysis, ComfortAxisResult, ComfortVerdict, FatigueMethodResult, FatigueVerdict, HealthAxisResult,
    HealthEvaluation, VerdictAnalysis,
};
pub use verdict_run::{simulate_with_verdicts, verdict_system, with_verdict_input};
pub use verdict_spec::{ComfortAxisSpec, ComfortSpec, FatigueSpec, VerdictSpec};
