//! Input files: spectrum files (`spectra/*.toml`), scenario files (`data/*.toml`), reference tables
//! (`data/reference/*.toml`) and workday files ([`workday_file`]), the spectrum catalogue and the registry of model kinds.
//!
//! Every value read from a file is validated; an error names the file, the dotted key, the value as
//! written and the reason ([`Error::File`](crate::Error::File)). What is run on a scenario (sweeps,
//! replays, verdicts, transients, nonlinear routes) is [`crate::study`].

pub mod analysis_keys;
mod butterworth_keys;
mod catalogue;
pub mod full_vehicle_keys;
pub mod generic;
mod input_filters;
pub mod input_keys;
pub mod inputs;
pub mod key_table;
mod machine_keys;
pub mod model_keys;
pub mod nonlinear_keys;
mod profile_identity;
pub mod reference;
mod registry;
pub mod scenario_file;
pub mod seat_factor;
pub mod spectrum_file;
pub mod top_keys;
pub mod transient_key_table;
pub mod transient_keys;
pub mod verdict_spec;
pub mod workday_file;

pub use catalogue::{spectrum_catalogue, Catalogue, CatalogueEntry, SpectrumOrigin};
pub use inputs::coherence_from_toml;
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
pub use verdict_spec::{ComfortAxisSpec, ComfortSpec, FatigueSpec, VerdictSpec};
