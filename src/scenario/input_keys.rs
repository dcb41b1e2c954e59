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
            "speed_profile",
            "table, as `[input.speed_profile]`",
            "constant `speed`",
            r#"v(t) for `stochvib transient`, in one table only ("one machine moves along one speed profile"); without `speed` the stationary analyses take its final speed"#,
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

/// `[input]`: one random process drives every input of the model.
pub const PROCESS: KeyTable = KeyTable {
    file: "scenario",
    prefix: "input",
    kind: None,
    keys: &[
        key("spectrum", "catalogue name, path, or inline table of [spectrum-file keys](spectrum-files.md)", "required", r#"an unknown name or path: the resolution's reason; another type: "expected a catalogue name, a path or an inline table""#),
        key("band", "two frequencies with units of the spectrum's variable (`cycles/m`, `rad/m`; `Hz`, `rad/s`)", "the spectrum's own", "0 ≤ low < high; a bare `1/m` or `1/s` is refused (it would be rad/m). Replaces the own band of `iso8608`, `power-law`, `band-white`; restricts any other spectrum, and cannot extend a tabulated or measured one beyond its data"),
        key("enveloping", "table `{ kind, length }`", "none", "a road (spatial spectrum) only: the profile seen through a tyre's contact patch, applied after the band"),
        key("speed", "quantity, m/s", "none", r#"> 0 ("must be > 0"); required for a spatial spectrum ("the input spectrum is spatial (a road): give the speed …") and for wheels at different positions"#),
        key("mean", "number (SI) or quantity in the process's unit", "0", "a string needs the process's dimension"),
        key("kurtosis", "number κ", "Gaussian", r#"≥ 3, finite: a Laplace moving average of this marginal kurtosis with the same spectrum ("must be finite and >= 3 …")"#),
        key("speed_profile", "table `[input.speed_profile]`", "constant `speed`", "a speed v(t) for `stochvib transient` (below); without `speed`, the stationary analyses take the profile's final speed (its largest if it ends at rest)"),
        key("envelope", "table `[input.envelope]`", "a = 1", "an amplitude envelope u(t) = a(t)·s(t) for `stochvib transient` (below)"),
    ],
};

/// `enveloping = { kind, length }` of `[input]`: a tyre's contact patch.
pub const ENVELOPING: KeyTable = KeyTable {
    file: "scenario",
    prefix: "input.enveloping",
    kind: None,
    keys: &[
        key(
            "kind",
            "string",
            "required",
            r#"`moving-average`: \|H(n)\|² = (sin(πnL)/(πnL))²"#,
        ),
        key("length", "quantity, m", "required", "> 0 (a contact patch: 0.1–0.3 m)"),
    ],
};

/// `[input.speed_profile]`: v(t) over a road, a table or constant acceleration.
pub const SPEED_PROFILE: KeyTable = KeyTable {
    file: "scenario",
    prefix: "input.speed_profile",
    kind: None,
    keys: &[
        key(
            "times",
            "array of times",
            "with `speeds`",
            r#"increasing strictly ("not after times[k−1] …: the table is not a function of time"), finite"#,
        ),
        key(
            "speeds",
            "array of speeds, one per time",
            "with `times`",
            r#"≥ 0 ("a speed is >= 0: the road is traversed in one direction"); one per time; not all 0 ("the vehicle never moves")"#,
        ),
        key("from", "speed", "required without `times`", "≥ 0"),
        key("to", "speed", "required without `times`", "≥ 0"),
        key(
            "acceleration",
            "acceleration, m/s²",
            "required without `times`",
            r#"finite, ≠ 0, of the sign that goes from `from` to `to` ("goes the wrong way …")"#,
        ),
        key(
            "start",
            "time",
            "`0 s`",
            r#"≥ 0: v = `from` until then; the table form refuses it ("… not both")"#,
        ),
    ],
};

/// `[input.envelope]`: an amplitude envelope.
pub const ENVELOPE: KeyTable = KeyTable {
    file: "scenario",
    prefix: "input.envelope",
    kind: None,
    keys: &[
        key("times", "array of times", "required", "increasing strictly, finite"),
        key(
            "amplitude",
            "array of numbers a(t), one per time",
            "give `amplitude` or `intensity`",
            r#"finite ("an envelope value is a finite number")"#,
        ),
        key(
            "intensity",
            "array of numbers a(t)², one per time",
            "give `amplitude` or `intensity`",
            r#"finite, ≥ 0 ("an intensity … is >= 0")"#,
        ),
    ],
};

/// `enveloping = { kind, length }` of an `[[input]]` table (and of `[road]`): as in `[input]`.
pub const ENVELOPING_EACH: KeyTable = KeyTable {
    prefix: "input[].enveloping",
    ..ENVELOPING
};
