//! The key tables of the top level of a scenario file and of `[model]` before its kind (read by
//! [`super::scenario_file`]). The reference page shows them ([`super::key_table`]); the readers' unknown-key
//! checks take them: the top level's, and `[model]`'s with the table of its kind ([`super::model_keys`]).

use super::key_table::{key, KeyTable};

/// The top level of a scenario file.
pub const TOP: KeyTable = KeyTable {
    file: "scenario",
    prefix: ".",
    kind: None,
    keys: &[
        key("title", "string", "empty", "shown in reports"),
        key("source", "string", "empty", "provenance of the values"),
        key(
            "model",
            "table `[model]`",
            "required",
            "the model: `kind` and its parameters",
        ),
        key(
            "input",
            "table `[input]` (one process) or tables `[[input]]` (several sources)",
            "required for a stochastic model",
            "the random input; `[road]` is another way to write one road of two tracks",
        ),
        key(
            "analysis",
            "table `[analysis]`",
            "every output, duration 1 h",
            "what to compute and report",
        ),
        key(
            "transient",
            "table `[transient]`",
            "none",
            "the time window, start and schedules of `stochvib transient` (below)",
        ),
    ],
};

/// `[model]`: the keys of every kind; the others are in the table of its kind.
pub const MODEL: KeyTable = KeyTable {
    file: "scenario",
    prefix: "model",
    kind: None,
    keys: &[
        key("kind", "string", "required", r#"one of the kinds below (`stochvib models` lists them); else "unknown model kind; known kinds: …""#),
        key("nonlinear", "tables `[[model.nonlinear]]`", "none", "the nonlinear elements (below, [`[[model.nonlinear]]`](#nonlinear-elements-modelnonlinear)); a deterministic kind refuses them"),
    ],
};
