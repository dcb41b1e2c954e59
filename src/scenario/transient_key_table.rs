//! The key tables of `[transient]` and its schedules (read by [`super::transient_keys`]). The reference page
//! shows them ([`super::key_table`]); each reader's unknown-key check takes its table.

use super::key_table::{key, KeyTable};

/// `[transient]`: the time window of `stochvib transient`.
pub const TRANSIENT: KeyTable = KeyTable {
    file: "scenario",
    prefix: "transient",
    kind: None,
    keys: &[
        key("duration", "time", r#"required by `stochvib transient` ("a transient analysis needs a [transient] section with the duration …")"#, "> 0"),
        key("step", "time", "duration/400", r#"> 0, ≤ `duration` ("longer than the duration"), at most 10⁶ reported times (duration/step ≤ 10⁶, refused before anything is allocated): the spacing of the reported times (rounded to divide the duration)"#),
        key("start", "string", "`stationary`", r#"`rest` (every state 0) or `stationary` (the stationary state at t = 0; refused for a system without one: "… start from rest")"#),
        key("state", "array of SI numbers, one per model state", "none", "the model's states at t = 0 (positions, then velocities), without scatter; not with `start`"),
        key("rel_tol", "number", "1e-9", "in (0, 0.01): the local error of the exact route's steps, relative to the largest variance of each state over the window"),
        key("max_error", "number", "0.05", r#"in (0, 1): the evolutionary route (inputs without an exact route: tabulated, measured, band-limited spectra) reports σ(t) only where its lag estimate δ(t) is at most this; elsewhere NaN (printed —) and a note "use Monte Carlo there""#),
        key("schedule", "tables `[[transient.schedule]]`", "none", "model keys as functions of time (below)"),
    ],
};

/// `[[transient.schedule]]`: a `[model]` key as a function of time.
pub const SCHEDULE: KeyTable = KeyTable {
    file: "scenario",
    prefix: "transient.schedule[]",
    kind: None,
    keys: &[
        key(
            "key",
            "string: a dotted `[model]` key (`model.element.0.stiffness`, `model.coordinates.0.mass`)",
            "required",
            r#"a `model.` key ("a schedule varies a key of [model] …"), not twice"#,
        ),
        key(
            "times",
            "array of times",
            "required",
            r#"increasing strictly ("… is not a function of time")"#,
        ),
        key(
            "values",
            "array, one per time, of numbers (SI) or quantities of one dimension; with `rope`, rope lengths",
            "required",
            r#"as the key takes them; the model's reader checks each value; a value at which the system is unstable is refused naming the time ("the system is unstable at t = … s"); with `rope`, lengths > 0 ("a rope length is finite and > 0 m"): the winding schedule l(t), linear between its times"#,
        ),
        key(
            "rope",
            "table `{ formula = …, … }`",
            "none",
            r#"the key's value is a function of the rope length l(t) given by `values` (below; [transients.md](transients.md), "Time-varying systems")"#,
        ),
    ],
};

/// `rope = { … }` of a schedule: the scheduled key as a function of the rope length.
pub const ROPE: KeyTable = KeyTable {
    file: "scenario",
    prefix: "transient.schedule[].rope",
    kind: None,
    keys: &[
        key(
            "formula",
            "string",
            "required",
            "`stiffness` (EF/l: Dvornikov, Kondrakhin & Velebnik 2014, eq. (3)), `rayleigh-mass` (m + γl/3: the textbook's reduction of the rope to its end), `lumped-mass` (m + γl/4: the skip's entry of the mass matrix, Dvornikov et al. 2014, eq. (14))",
        ),
        key("axial_rigidity", "force", "required by `stiffness`", "> 0: EF = E·ā·d_k² of the rope"),
        key("end_mass", "mass", "required by the masses", "> 0: m, the skip"),
        key("mass_per_metre", "mass per length", "required by the masses", "> 0: γ of the rope"),
    ],
};
