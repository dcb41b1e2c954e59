//! Input files: spectrum files (`spectra/*.toml`) and, later, scenario files (`data/*.toml`).
//!
//! Every value read from a file is validated; an error names the file, the dotted key, the value as
//! written and the reason ([`Error::File`](crate::Error::File)).

mod fields;
pub mod scenario_file;
pub mod spectrum_file;

pub use fields::Fields;
pub use scenario_file::{load_scenario, parse_scenario, AnalysisOptions, Scenario};
pub use spectrum_file::{load_spectrum, parse_spectrum, spectrum_catalogue, CatalogueEntry, SpectrumFile};
