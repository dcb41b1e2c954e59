//! The key tables of `[analysis]` and its sections (read by [`super::scenario_file`],
//! [`super::verdict_spec`], [`super::seat_factor`] and [`super::transient_keys`]). The reference page shows
//! them ([`super::key_table`]); each reader's unknown-key check takes its table.

use super::key_table::{key, KeyTable};

/// `[analysis]`: what to compute and report.
pub const ANALYSIS: KeyTable = KeyTable {
    file: "scenario",
    prefix: "analysis",
    kind: None,
    keys: &[
        key("outputs", "array of output names", "every output", r#"names of the model's outputs ("no such output; the model has: …"), not empty, none twice"#),
        key("band", "two frequencies with units", "the whole axis", r#"0 ≤ low < high ("need 0 <= low < high"): the band statistics"#),
        key("duration", r#"duration with unit (`"8 h"`)"#, "`1 h`", "> 0: the time of the exceedance probabilities and expected peaks"),
        key("levels", "table: output name = array of levels", "none", "levels in the output's unit (a number is SI; a string needs the output's dimension): exceedance and crossing statistics"),
        key("quadrature", "table `[analysis.quadrature]`", "the defaults below", "the effort of the adaptive quadrature"),
        key("bands", "string", "none", r#"`octave` or `third-octave` (IEC 61260-1 base-10 bands): an RMS per band ("unknown band table: …")"#),
        key("comfort", "table `[analysis.comfort]`", "none", "ISO 2631-1 weighted accelerations and the daily exposure"),
        key("fatigue", "table `[analysis.fatigue]`", "none", "a stress output, its S–N curve and the spectral methods"),
        key("seat_factor", "table `[analysis.seat_factor]`", "none", "the SEAT value of a seat: seat-pan over floor weighted r.m.s. acceleration"),
        key("mission", "table `[analysis.mission]`", "none", r#"the clearances and duration of P(max \|y\| > b within T) of `stochvib transient`"#),
    ],
};

/// `[analysis.quadrature]`: the effort of the adaptive quadrature.
pub const QUADRATURE: KeyTable = KeyTable {
    file: "scenario",
    prefix: "analysis.quadrature",
    kind: None,
    keys: &[
        key("rel_tol", "number", "1e-10", "finite, ≥ 0"),
        key(
            "max_subintervals",
            "integer",
            "2000",
            r#"1 … 10⁸ ("expected a count from 1 to 10^8")"#,
        ),
        key("max_half_periods", "integer", "10000", "1 … 10⁸"),
    ],
};

/// `[analysis.comfort]`: ISO 2631-1 and Directive 2002/44/EC.
pub const COMFORT: KeyTable = KeyTable {
    file: "scenario",
    prefix: "analysis.comfort",
    kind: None,
    keys: &[
        key(
            "purpose",
            "string",
            "`health`",
            r#"`health` (clause 7, the Directive) or `comfort` ("expected \"health\" or \"comfort\"")"#,
        ),
        key(
            "exposure",
            "duration with unit",
            "required",
            r#"the daily exposure T: 1 min … 24 h ("implausible: less than 0.01667 h …", "a daily exposure is at most 24 h")"#,
        ),
        key(
            "a8_action",
            "quantity, m/s²",
            "0.5",
            "> 0: the Directive's A(8) action value",
        ),
        key("a8_limit", "quantity, m/s²", "1.15", "> 0"),
        key("vdv_action", "number, m/s^1.75", "9.1", "> 0"),
        key("vdv_limit", "number, m/s^1.75", "21", "> 0"),
        key(
            "axis",
            "tables `[[analysis.comfort.axis]]`",
            "required",
            r#"one or more ("expected one or more [[analysis.comfort.axis]] tables")"#,
        ),
    ],
};

/// `[[analysis.comfort.axis]]`: one weighted axis of the comfort verdict.
pub const COMFORT_AXIS: KeyTable = KeyTable {
    file: "scenario",
    prefix: "analysis.comfort.axis[]",
    kind: None,
    keys: &[
        key("output", "string", "required", "an acceleration output (m/s², rad/s² for rotations) of the model"),
        key("location", "string", "required", "`seat-surface` (`seat`), `seat-back` (`back`), `feet`, `standing-floor` (`floor`)"),
        key("axis", "string", "required", "`x`, `y`, `z`, `rx`, `ry`, `rz`; each location and axis once (once more with Wf)"),
        key("weighting", "string", "the standard's for purpose, location and axis", "`Wk`, `Wd`, `Wc`, `We`, `Wj`, `Wb`, `Wf` (any case, `W_k` too); on an output that is not an acceleration: refused naming its unit"),
        key("k", "number", "the standard's multiplying factor", r#"> 0 ("a multiplying factor must be > 0")"#),
    ],
};

/// `[analysis.fatigue]`: spectral fatigue of a stress output.
pub const FATIGUE: KeyTable = KeyTable {
    file: "scenario",
    prefix: "analysis.fatigue",
    kind: None,
    keys: &[
        key(
            "output",
            "string",
            "required",
            r#"the output whose stress is judged; its moments up to λ₄ must be finite (refused when evaluated: "the spectral fatigue methods need finite moments up to λ₄")"#,
        ),
        key(
            "stress_factor",
            "number (SI) or quantity of dimension Pa per output unit",
            "required",
            "finite, non-zero",
        ),
        key("k", "number: S–N slope, N·S_a^k = C", "required", "> 0"),
        key(
            "c",
            "number, Pa^k",
            "give `c`, or `reference_amplitude` with `reference_cycles`",
            r#"> 0 ("give either c (in Pa^k) or reference_amplitude with reference_cycles")"#,
        ),
        key(
            "reference_amplitude",
            "quantity, Pa",
            "see `c`",
            "a point of the curve: this amplitude endures …",
        ),
        key(
            "reference_cycles",
            "number",
            "required with `reference_amplitude`",
            "… this many cycles",
        ),
        key(
            "endurance_limit",
            "quantity, Pa",
            "none",
            "amplitudes below it do no damage",
        ),
        key(
            "methods",
            "array of strings",
            "all five",
            "`narrow-band`, `wirsching-light`, `dirlik`, `tovo-benasciutti`, `zhao-baker`; not empty",
        ),
        key(
            "design_life",
            "duration with unit",
            "none",
            "≥ 1 h: the life to compare with",
        ),
        key(
            "design_distance",
            r#"distance with unit (`"200000 km"`)"#,
            "none",
            r#"≥ 1 km, at the `[input]` speed ("a distance needs the [input] speed to become a time"); not with `design_life`"#,
        ),
        key(
            "bins",
            "integer",
            "48",
            "1 … 100000: rainflow range histogram of a Monte Carlo run",
        ),
    ],
};

/// `[analysis.seat_factor]`: SEAT of a seat.
pub const SEAT_FACTOR: KeyTable = KeyTable {
    file: "scenario",
    prefix: "analysis.seat_factor",
    kind: None,
    keys: &[
        key(
            "seat",
            "string",
            "required",
            r#"an acceleration output on the seat pan ("no such output; the model has: …"; not an acceleration: refused naming its unit)"#,
        ),
        key(
            "floor",
            "string",
            "required",
            r#"an acceleration output of the floor under the seat, or `"base <j>"`: the second derivative of the model's base (displacement) input j ("expected \"base <j>\" with j below the model's … base inputs")"#,
        ),
        key(
            "weighting",
            "string",
            "`Wk`",
            "any weighting of `[analysis.comfort.axis]` (EN ISO 7096: Wk, vertical)",
        ),
    ],
};

/// `[analysis.mission]`: extremes of a mission.
pub const MISSION: KeyTable = KeyTable {
    file: "scenario",
    prefix: "analysis.mission",
    kind: None,
    keys: &[
        key(
            "duration",
            r#"duration with unit (`"20 min"`)"#,
            "the `[transient]` window",
            r#"> 0: T of P(max \|y\| > b within T); beyond the window the rates of its end are held"#,
        ),
        key(
            "levels",
            "table: output name = array of clearances b",
            "required",
            r#"outputs of the model ("no such output …"); b > 0 in the output's unit ("a clearance b > 0 …")"#,
        ),
    ],
};
