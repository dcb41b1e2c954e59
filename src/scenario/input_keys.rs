//! The key tables of the `[[input]]` sections ([`super::inputs`]): the `[[input]]` table, its `road` and the
//! road's `coherence` of each kind. The reference page shows them ([`super::key_table`]).

use super::key_table::{key, KeyTable};

/// `[[input]]`: one table per independent source (a process or a road of two tracks) and the model inputs it
/// drives; the order is that of the "known keys" message of an unknown key.
pub const INPUT: KeyTable = KeyTable {
    file: "scenario",
    prefix: "input[]",
    kind: None,
    keys: &[
        key(
            "name",
            "string",
            "`input_<i>`",
            r#"signal name in run files: not empty, no spaces or `/`; unique ("input[k] has this name already")"#,
        ),
        key(
            "spectrum",
            "as `[input] spectrum`",
            "give `spectrum` or `road`",
            r#"one process; "give either spectrum (one process) or road (two tracks), not both""#,
        ),
        key(
            "road",
            "table `{ spectrum, track_width, coherence }`",
            "give `spectrum` or `road`",
            "a road of two tracks (below)",
        ),
        key("band", "as in `[input]`", "the spectrum's own", ""),
        key("enveloping", "as in `[input]`", "none", ""),
        key(
            "speed",
            "quantity, m/s",
            "none",
            r#"> 0; every table that gives one gives the same ("one machine moves at one speed")"#,
        ),
        key(
            "mean",
            "number or quantity in the process's unit",
            "0",
            "mean of the process (of each track)",
        ),
        key(
            "drives",
            "array of model input indices",
            "every input, if there is one table",
            r#"0 … m−1 ("expected a model input index from 0 to …"); required with several tables"#,
        ),
        key(
            "tracks",
            r#"array of `"left"`/`"right"`, one per driven input"#,
            "the model's layout",
            r#"a road only ("only a road of two tracks … has tracks"); a road needs a track for every driven input"#,
        ),
        key(
            "positions",
            "array of lengths, one per driven input",
            "the model's layout, else `0 m`",
            r#"≥ 0 behind the first contact ("N values for M driven inputs (`drives`)")"#,
        ),
        key(
            "gains",
            "array of numbers, one per driven input",
            "the model's layout, else 1",
            "finite",
        ),
        key(
            "kurtosis",
            "number κ ≥ 3",
            "Gaussian",
            "a process only (a road of two tracks refuses it); Monte Carlo then draws every source the Laplace way",
        ),
    ],
};

/// `road = { … }` of an `[[input]]` table: a road of two tracks.
pub const ROAD: KeyTable = KeyTable {
    file: "scenario",
    prefix: "input[].road",
    kind: None,
    keys: &[
        key(
            "spectrum",
            "as `[input] spectrum`",
            "required",
            r#"a spatial spectrum ("a road of two tracks needs a spatial spectrum")"#,
        ),
        key(
            "track_width",
            "quantity, m",
            "the model's own (full-vehicle)",
            r#"> 0; must equal the model's ("the model's track width is B m …")"#,
        ),
        key(
            "coherence",
            "table `{ kind, … }`",
            "required",
            "the coherence of the two tracks, below",
        ),
    ],
};

/// `road.coherence`: the coherence of the two tracks; the other keys depend on its `kind`.
pub const COHERENCE: KeyTable = KeyTable {
    file: "scenario",
    prefix: "input[].road.coherence",
    kind: None,
    keys: &[key(
        "kind",
        "string",
        "required",
        r#"`dodds-robson`, `ammon-bormann`, `tabulated`, `constant` ("expected dodds-robson, ammon-bormann, tabulated or constant")"#,
    )],
};

/// `road.coherence` of kind `dodds-robson`: the isotropic surface.
pub const DODDS_ROBSON: KeyTable = KeyTable {
    file: "scenario",
    prefix: "input[].road.coherence",
    kind: Some("dodds-robson"),
    keys: &[key(
        "waviness",
        "number w",
        "2",
        "the isotropic surface, ρ = 2^(1−ν)/Γ(ν) x^ν K_ν(x), x = 2πnB, ν = w/2",
    )],
};

/// `road.coherence` of kind `ammon-bormann`: a preset, or the formula's parameters.
pub const AMMON_BORMANN: KeyTable = KeyTable {
    file: "scenario",
    prefix: "input[].road.coherence",
    kind: Some("ammon-bormann"),
    keys: &[
        key("preset", "string", "none (then the four parameters)", "`iso-a` … `iso-e`, `major-road-concrete`, `major-road-asphaltic-concrete`, `main-road-asphaltic-concrete-on-pavement`, `main-road-asphaltic-concrete`, `track-tiled-concrete-pavement`"),
        key("omega_p", "number, rad/m", "required without `preset`", "> 0; the formula [1 + (Ω B^a/Ω_p)^w]^(−p)"),
        key("w", "number", "required without `preset`", "> 0"),
        key("p", "number", "required without `preset`", "> 0"),
        key("a", "number", "1", "≥ 0"),
        key("values", "string", "`squared_coherence`", "`squared_coherence` or `coherence_amplitude`: the quantity the formula gives"),
    ],
};

/// `road.coherence` of kind `tabulated`: a table over the wavenumber.
pub const TABULATED: KeyTable = KeyTable {
    file: "scenario",
    prefix: "input[].road.coherence",
    kind: Some("tabulated"),
    keys: &[
        key("n", "array of numbers, cycles/m", "required", "interpolated linearly"),
        key(
            "squared_coherence",
            "array, one value per `n`",
            "give exactly one of the two",
            r#"γ² ("give exactly one of squared_coherence (γ²) or coherence_amplitude (ρ), one value per n")"#,
        ),
        key(
            "coherence_amplitude",
            "array, one value per `n`",
            "give exactly one of the two",
            "ρ",
        ),
    ],
};

/// `road.coherence` of kind `constant`.
pub const CONSTANT: KeyTable = KeyTable {
    file: "scenario",
    prefix: "input[].road.coherence",
    kind: Some("constant"),
    keys: &[key(
        "coherence_amplitude",
        "number ρ",
        "required",
        "the same coherence at every wavenumber",
    )],
};
