//! The key tables of the `[model]` kinds other than `mdof` (whose tables are in
//! [`super::generic::mdof_keys`]): one table per kind with the keys of `[model]` besides `kind` and
//! `nonlinear`, and one per sub-table of a kind. The reference page shows them ([`super::key_table`]); the
//! unknown-key check of `[model]` takes the kind's table ([`model_table`]).

use super::key_table::{key, KeyTable, KEY_TABLES};

/// The table of the `[model]` keys of kind `kind` (the table with prefix `model` of that kind).
pub fn model_table(kind: &str) -> Option<&'static KeyTable> {
    KEY_TABLES
        .iter()
        .copied()
        .find(|t| t.prefix == "model" && t.kind == Some(kind))
}

/// `kind = "transfer-function"`: N(s)/D(s).
pub const TRANSFER_FUNCTION: KeyTable = KeyTable {
    file: "scenario",
    prefix: "model",
    kind: Some("transfer-function"),
    keys: &[
        key(
            "denominator",
            "array of SI numbers, ascending powers of s",
            "required",
            "finite numbers (the model must be stable, as every stochastic model)",
        ),
        key(
            "numerator",
            "array (one input), or array of rows (one row per input: y = Σ N_k(s)/D(s) u_k)",
            "required",
            "",
        ),
        key("output", "table `{ name, unit }`", "required", ""),
        key(
            "positions",
            "array of lengths",
            "all `0 m`",
            r#"rows form only ("a single numerator has one input: give `numerator = [[…], […]]` …")"#,
        ),
        key("gains", "array of numbers", "all 1", "rows form only"),
        key("tracks", r#"array of `"left"`/`"right"`"#, "none", "rows form only"),
    ],
};

/// `output = { name, unit }` of a transfer function.
pub const TRANSFER_FUNCTION_OUTPUT: KeyTable = KeyTable {
    file: "scenario",
    prefix: "model.output",
    kind: Some("transfer-function"),
    keys: &[
        key("name", "string", "required", "output name"),
        key("unit", "string", "`m`", "the output's SI unit"),
    ],
};

/// `kind = "state-space"`: ẋ = A x + B u, y = C x + D u + E u̇.
pub const STATE_SPACE: KeyTable = KeyTable {
    file: "scenario",
    prefix: "model",
    kind: Some("state-space"),
    keys: &[
        key(
            "a",
            "rows of SI numbers",
            "required",
            "n × n (the model must be stable, as every stochastic model)",
        ),
        key("b", "rows", "required", "n × m (m inputs)"),
        key("c", "rows", "required", "p × n, one row per output"),
        key("d", "rows", "zeros", "p × m"),
        key("e", "rows", "zeros", "p × m"),
        key("outputs", "array of `{ name, unit }`", "required", "one per row of C"),
        key("positions", "array of lengths", "all `0 m`", "as for `mdof`"),
        key("gains", "array of numbers", "all 1", ""),
        key("tracks", r#"array of `"left"`/`"right"`"#, "none", ""),
    ],
};

/// Each of `outputs = [{ name, unit }, …]` of a state space.
pub const STATE_SPACE_OUTPUTS: KeyTable = KeyTable {
    file: "scenario",
    prefix: "model.outputs[]",
    kind: Some("state-space"),
    keys: &[
        key("name", "string", "required", "output name"),
        key("unit", "string", "`m`", "the output's SI unit"),
    ],
};

/// `kind = "quarter-car"`.
pub const QUARTER_CAR: KeyTable = KeyTable {
    file: "scenario",
    prefix: "model",
    kind: Some("quarter-car"),
    keys: &[
        key("sprung_mass", "quantity, kg", "required", "> 0"),
        key("unsprung_mass", "quantity, kg", "required", "> 0"),
        key("suspension_stiffness", "quantity, N/m", "required", "> 0"),
        key("suspension_damping", "quantity, N s/m", "required", "≥ 0"),
        key("tyre_stiffness", "quantity, N/m", "required", "> 0"),
        key("tyre_damping", "quantity, N s/m", "0", "≥ 0"),
    ],
};

/// `kind = "isolator-single"`.
pub const ISOLATOR_SINGLE: KeyTable = KeyTable {
    file: "scenario",
    prefix: "model",
    kind: Some("isolator-single"),
    keys: &[
        key("mass", "quantity, kg", "required", "> 0"),
        key("stiffness", "quantity, N/m", "required", "> 0"),
        key(
            "damping",
            "quantity, N s/m",
            "undamped",
            r#"not with `damping_ratio` ("give either `damping` or `damping_ratio`, not both")"#,
        ),
        key(
            "damping_ratio",
            "number ζ",
            "undamped",
            r#"≥ 0 ("must be >= 0"); b = 2ζ√(cm)"#,
        ),
    ],
};

/// `kind = "isolator-two-stage"`.
pub const ISOLATOR_TWO_STAGE: KeyTable = KeyTable {
    file: "scenario",
    prefix: "model",
    kind: Some("isolator-two-stage"),
    keys: &[
        key("mass_1", "quantity, kg", "required", "> 0"),
        key("stiffness_1", "quantity, N/m", "required", "> 0"),
        key("damping_1", "quantity, N s/m", "0", "≥ 0"),
        key("mass_2", "quantity, kg", "required", "> 0"),
        key("stiffness_2", "quantity, N/m", "required", "> 0"),
        key("damping_2", "quantity, N s/m", "0", "≥ 0"),
    ],
};

/// `kind = "half-car"`.
pub const HALF_CAR: KeyTable = KeyTable {
    file: "scenario",
    prefix: "model",
    kind: Some("half-car"),
    keys: &[
        key("mass", "quantity, kg", "required", "> 0"),
        key("radius_of_gyration", "quantity, m", "required", "> 0"),
        key(
            "front_distance",
            "quantity, m: a, centre of mass to the front axle",
            "required",
            "> 0",
        ),
        key("rear_distance", "quantity, m: b", "required", "> 0"),
        key("front_stiffness", "quantity, N/m", "required", "> 0"),
        key("rear_stiffness", "quantity, N/m", "required", "> 0"),
        key("front_damping", "quantity, N s/m", "0", "≥ 0"),
        key("rear_damping", "quantity, N s/m", "0", "≥ 0"),
        key(
            "acc_point",
            "quantity, m ahead of the centre of mass",
            "0",
            "finite: the point of the `body_acc` output",
        ),
    ],
};

/// `kind = "full-vehicle"`: 7 DOF on two road tracks.
pub const FULL_VEHICLE: KeyTable = KeyTable {
    file: "scenario",
    prefix: "model",
    kind: Some("full-vehicle"),
    keys: &[
        key("mass", "quantity, kg", "required", "> 0"),
        key("pitch_inertia", "quantity, kg m²", "required", "> 0"),
        key("roll_inertia", "quantity, kg m²", "required", "> 0"),
        key("front_distance", "quantity, m", "required", "> 0"),
        key("rear_distance", "quantity, m", "required", "> 0"),
        key(
            "track_width",
            "quantity, m",
            "required",
            "> 0; an `[[input]]` road's `track_width` must equal it",
        ),
        key("tyre_stiffness", "quantity, N/m", "required", "> 0"),
        key(
            "suspension_stiffness",
            "table `{ front, rear }`, N/m",
            "required",
            "> 0",
        ),
        key(
            "suspension_damping",
            "table `{ front, rear }`, N s/m",
            "required",
            "≥ 0",
        ),
        key("unsprung_mass", "table `{ front, rear }`, kg", "required", "> 0"),
        key(
            "seat",
            "table `{ ahead, left }`, m from the centre of mass",
            "`{ ahead = 0, left = 0 }`",
            "the point of the seat outputs",
        ),
    ],
};

/// `suspension_stiffness = { front, rear }` of a full vehicle.
pub const FULL_VEHICLE_SUSPENSION_STIFFNESS: KeyTable = KeyTable {
    file: "scenario",
    prefix: "model.suspension_stiffness",
    kind: Some("full-vehicle"),
    keys: &[
        key("front", "quantity", "required", "value of the front axle (each wheel)"),
        key("rear", "quantity", "required", "value of the rear axle (each wheel)"),
    ],
};

/// `suspension_damping = { front, rear }` of a full vehicle.
pub const FULL_VEHICLE_SUSPENSION_DAMPING: KeyTable = KeyTable {
    file: "scenario",
    prefix: "model.suspension_damping",
    kind: Some("full-vehicle"),
    keys: &[
        key("front", "quantity", "required", ""),
        key("rear", "quantity", "required", ""),
    ],
};

/// `unsprung_mass = { front, rear }` of a full vehicle.
pub const FULL_VEHICLE_UNSPRUNG_MASS: KeyTable = KeyTable {
    file: "scenario",
    prefix: "model.unsprung_mass",
    kind: Some("full-vehicle"),
    keys: &[
        key("front", "quantity", "required", ""),
        key("rear", "quantity", "required", ""),
    ],
};

/// `seat = { ahead, left }` of a full vehicle.
pub const FULL_VEHICLE_SEAT: KeyTable = KeyTable {
    file: "scenario",
    prefix: "model.seat",
    kind: Some("full-vehicle"),
    keys: &[
        key("ahead", "quantity, m", "0", "ahead of the centre of mass"),
        key("left", "quantity, m", "0", "left of the centre line"),
    ],
};

/// `kind = "machine"`: body on axles, cab on mounts, seat.
pub const MACHINE: KeyTable = KeyTable {
    file: "scenario",
    prefix: "model",
    kind: Some("machine"),
    keys: &[
        key("body", "table `[model.body]`", "required", "the body"),
        key(
            "axle",
            "tables `[[model.axle]]`",
            "required",
            r#"two or more ("a machine needs two or more axles")"#,
        ),
        key("cab", "table `[model.cab]`", "none", "the cab on its mounts"),
        key(
            "seat",
            "table `[model.seat]`",
            "none",
            r#"the seat; needs a cab ("a seat sits on a cab")"#,
        ),
        key(
            "output",
            "tables `[[model.output]]`",
            "none",
            "more outputs at points of the body, cab or seat",
        ),
    ],
};

/// `[model.body]` of a machine.
pub const MACHINE_BODY: KeyTable = KeyTable {
    file: "scenario",
    prefix: "model.body",
    kind: Some("machine"),
    keys: &[
        key("mass", "quantity, kg", "required", "> 0"),
        key(
            "pitch_inertia",
            "quantity, kg m²",
            "required",
            "> 0, about the centre of gravity",
        ),
        key("roll_inertia", "quantity, kg m²", "required", "> 0"),
        key(
            "height",
            "quantity, m",
            "required",
            "the centre of gravity above the ground (the lever of horizontal motion)",
        ),
    ],
};

/// `[[model.axle]]` of a machine.
pub const MACHINE_AXLE: KeyTable = KeyTable {
    file: "scenario",
    prefix: "model.axle[]",
    kind: Some("machine"),
    keys: &[
        key("name", "string", "required", "names the axle's elements and outputs"),
        key(
            "position",
            "quantity, m",
            "required",
            "x of the axle, ahead of the body's centre of gravity (negative behind)",
        ),
        key(
            "track_width",
            "quantity, m",
            "required",
            r#"> 0, the same on every axle ("every axle must have the track width of the first"); an `[[input]]` road's `track_width` must equal it"#,
        ),
        key("tyre_stiffness", "quantity, N/m", "required", "> 0, per tyre"),
        key("tyre_damping", "quantity, N s/m", "0", "≥ 0, per tyre"),
        key(
            "oscillating",
            "table",
            "none (rigid axle)",
            r#"the axle rolls about a pin on the centre line; not with `suspension` ("an axle is oscillating or suspended, not both")"#,
        ),
        key(
            "suspension",
            "table",
            "none (rigid axle)",
            "a suspended wheel at each end",
        ),
    ],
};

/// `oscillating = { … }` of a machine's axle.
pub const MACHINE_OSCILLATING: KeyTable = KeyTable {
    file: "scenario",
    prefix: "model.axle[].oscillating",
    kind: Some("machine"),
    keys: &[
        key(
            "roll_inertia",
            "quantity, kg m²",
            "required",
            "> 0, of the axle about its pin",
        ),
        key(
            "roll_stiffness",
            "quantity, N m/rad",
            "0",
            "≥ 0, of the pin to the body's roll",
        ),
        key("roll_damping", "quantity, N m s/rad", "0", "≥ 0"),
    ],
};

/// `suspension = { … }` of a machine's axle.
pub const MACHINE_SUSPENSION: KeyTable = KeyTable {
    file: "scenario",
    prefix: "model.axle[].suspension",
    kind: Some("machine"),
    keys: &[
        key("stiffness", "quantity, N/m", "required", "> 0, per wheel"),
        key("damping", "quantity, N s/m", "required", "≥ 0, per wheel"),
        key("unsprung_mass", "quantity, kg", "required", "> 0, per wheel"),
    ],
};

/// `[model.cab]` of a machine.
pub const MACHINE_CAB: KeyTable = KeyTable {
    file: "scenario",
    prefix: "model.cab",
    kind: Some("machine"),
    keys: &[
        key("mass", "quantity, kg", "required", "> 0"),
        key("pitch_inertia", "quantity, kg m²", "required", "> 0"),
        key("roll_inertia", "quantity, kg m²", "required", "> 0"),
        key(
            "position",
            "three lengths `[x, y, height]`",
            "required",
            "the cab's centre of gravity",
        ),
        key(
            "mount_height",
            "quantity, m",
            "required",
            "the height of the mount plane, where the cab is held horizontally to the body",
        ),
        key(
            "mount",
            "tables `[[model.cab.mount]]`",
            "required",
            r#"three or more ("a cab needs three or more mounts")"#,
        ),
    ],
};

/// `[[model.cab.mount]]` of a machine's cab.
pub const MACHINE_MOUNT: KeyTable = KeyTable {
    file: "scenario",
    prefix: "model.cab.mount[]",
    kind: Some("machine"),
    keys: &[
        key("position", "two lengths `[x, y]`", "required", "in the body's frame"),
        key("stiffness", "quantity, N/m", "required", "> 0, vertical"),
        key("damping", "quantity, N s/m", "0", "≥ 0"),
    ],
};

/// `[model.seat]` of a machine.
pub const MACHINE_SEAT: KeyTable = KeyTable {
    file: "scenario",
    prefix: "model.seat",
    kind: Some("machine"),
    keys: &[
        key(
            "position",
            "three lengths `[x, y, height]`",
            "required",
            "the seat surface",
        ),
        key(
            "operator_mass",
            "quantity, kg",
            "required",
            "> 0; the seat mass moving is (5/7)·operator + seat (Sukharev 2012, 7.6)",
        ),
        key("seat_mass", "quantity, kg", "required", "≥ 0"),
        key("stiffness", "quantity, N/m", "required", "> 0"),
        key("damping", "quantity, N s/m", "required", "≥ 0"),
    ],
};

/// `[[model.output]]` of a machine.
pub const MACHINE_OUTPUT: KeyTable = KeyTable {
    file: "scenario",
    prefix: "model.output[]",
    kind: Some("machine"),
    keys: &[
        key("name", "string", "required", "the output's name"),
        key("part", "string", "required", r#"`body`, `cab`, `seat` ("expected body, cab or seat"; a part the machine lacks: "the machine has no cab")"#),
        key("point", "three lengths `[x, y, height]`", "the part's centre of gravity (the seat surface)", "the point whose motion is the output"),
        key("direction", "string", "required", "`x`, `y`, `z` (m), `roll`, `pitch` (rad): x and y are the motion at the point's height from pitch and roll"),
        key("quantity", "string", "`acceleration`", "`displacement`, `velocity`, `acceleration`"),
    ],
};

/// `kind = "operator-seat"` (Sukharev 2012, 7.6).
pub const OPERATOR_SEAT: KeyTable = KeyTable {
    file: "scenario",
    prefix: "model",
    kind: Some("operator-seat"),
    keys: &[
        key("operator_mass", "quantity, kg", "required", "> 0"),
        key("seat_mass", "quantity, kg", "required", "≥ 0"),
        key("stiffness", "quantity, N/m", "required", "> 0"),
        key(
            "damping",
            "quantity, N s/m",
            "give one",
            r#"exactly one of `damping` or `damping_rate` ("give either … not both", "give `damping` (N s/m) or `damping_rate` (the book's h, 1/s)")"#,
        ),
        key("damping_rate", "quantity, 1/s: the book's h, b = 2 h m", "give one", ""),
    ],
};

/// `kind = "balancer-bogie"` (Sukharev 2012, 8.5).
pub const BALANCER_BOGIE: KeyTable = KeyTable {
    file: "scenario",
    prefix: "model",
    kind: Some("balancer-bogie"),
    keys: &[
        key("r", "quantity, m: wheel radius", "required", "> 0"),
        key("ell", "quantity, m: ℓ", "required", "> 0"),
        key(
            "ell1",
            "quantity, m: ℓ₁",
            "required",
            r#"in [0, ℓ] ("must lie in [0, ell = …] m")"#,
        ),
    ],
};

/// `kind = "conveyor-idler"` (Sukharev 2012, 8.6).
pub const CONVEYOR_IDLER: KeyTable = KeyTable {
    file: "scenario",
    prefix: "model",
    kind: Some("conveyor-idler"),
    keys: &[
        key("m", "quantity, kg", "required", "> 0"),
        key("c", "quantity, N/m", "required", "> 0"),
        key(
            "b",
            "quantity, N s/m",
            "give one",
            r#"> 0; exactly one of `b` or `zeta` ("give `b` or `zeta`, not both", "give `b` (N s/m) or `zeta` (damping ratio)")"#,
        ),
        key("zeta", "number: damping ratio (the book's β)", "give one", "> 0"),
    ],
};

/// `kind = "scraper-rigid-cab"` (Sukharev 2012, 8.7).
pub const SCRAPER_RIGID_CAB: KeyTable = KeyTable {
    file: "scenario",
    prefix: "model",
    kind: Some("scraper-rigid-cab"),
    keys: &[
        key("m1", "quantity, kg: machine mass on the front axle", "required", "> 0"),
        key("c1", "quantity, N/m: tyre stiffness", "give `c1` or `omega1`", "> 0"),
        key(
            "omega1",
            "frequency with unit",
            "give `c1` or `omega1`",
            r#"> 0 ("must be > 0")"#,
        ),
        key("b1", "quantity, N s/m: tyre damping", "give `b1` or `zeta1`", "≥ 0"),
        key(
            "zeta1",
            "number",
            "give `b1` or `zeta1`",
            r#"≥ 0 ("a damping ratio must be >= 0")"#,
        ),
    ],
};

/// `kind = "scraper-sprung-cab"` (Sukharev 2012, 8.7).
pub const SCRAPER_SPRUNG_CAB: KeyTable = KeyTable {
    file: "scenario",
    prefix: "model",
    kind: Some("scraper-sprung-cab"),
    keys: &[
        key("m1", "quantity, kg", "required", "> 0"),
        key("c1", "quantity, N/m", "give `c1` or `omega1`", "> 0"),
        key("omega1", "frequency with unit", "give `c1` or `omega1`", "> 0"),
        key("b1", "quantity, N s/m", "give `b1` or `zeta1`", "≥ 0"),
        key("zeta1", "number", "give `b1` or `zeta1`", "≥ 0"),
        key("m2", "quantity, kg: cab mass", "required", "> 0"),
        key(
            "c2",
            "quantity, N/m: cab mount stiffness",
            "give `c2` or `omega2`",
            "> 0",
        ),
        key("omega2", "frequency with unit", "give `c2` or `omega2`", "> 0"),
        key(
            "b2",
            "quantity, N s/m: cab mount damping",
            "give `b2` or `zeta2`",
            "≥ 0",
        ),
        key("zeta2", "number", "give `b2` or `zeta2`", "≥ 0"),
    ],
};

/// `kind = "three-mass-hoist"` (Ofiy & Rakhmaniy 2010).
pub const THREE_MASS_HOIST: KeyTable = KeyTable {
    file: "scenario",
    prefix: "model",
    kind: Some("three-mass-hoist"),
    keys: &[
        key("I1", "quantity, kg m²", "required", "> 0"),
        key("I2", "quantity, kg m²", "required", "> 0"),
        key("I3", "quantity, kg m²", "required", "> 0"),
        key("c1", "quantity, N m/rad", "required", "> 0"),
        key("c2", "quantity, N m/rad", "required", "> 0"),
        key("M_start", "quantity, N m: starting torque", "required", ""),
        key("M_load", "quantity, N m: load torque", "required", ""),
        key(
            "M12_initial",
            "quantity, N m",
            "`M_start`",
            "initial moment of link 1–2",
        ),
        key("M23_initial", "quantity, N m", "0", "initial moment of link 2–3"),
    ],
};

/// `kind = "dynamic-stiffness-chain"` (Yurchenko 2011).
pub const DYNAMIC_STIFFNESS_CHAIN: KeyTable = KeyTable {
    file: "scenario",
    prefix: "model",
    kind: Some("dynamic-stiffness-chain"),
    keys: &[
        key("inertia", "n numbers, kg m²", "required", "> 0"),
        key("shaft_stiffness", "n − 1 numbers, N m/rad", "required", ""),
        key("shaft_damping", "n − 1 numbers, N m s/rad", "zeros", ""),
        key("ground_stiffness", "n numbers, N m/rad", "zeros", ""),
        key("ground_damping", "n numbers, N m s/rad", "zeros", ""),
        key(
            "frequency",
            "frequency with unit",
            "no load case",
            r#"the harmonic load's frequency, e.g. `"40 rad/s"`"#,
        ),
        key(
            "torques",
            "n numbers, N m",
            "required with `frequency`",
            r#"one per mass ("need n values")"#,
        ),
    ],
};

/// `kind = "mine-hoist"` (Dvornikov et al. 2014).
pub const MINE_HOIST: KeyTable = KeyTable {
    file: "scenario",
    prefix: "model",
    kind: Some("mine-hoist"),
    keys: &[
        key("young_modulus", "quantity, Pa", "required", "> 0"),
        key("rope_area_factor", "number", "required", "> 0"),
        key("rope_diameter", "quantity, m", "required", "> 0"),
        key("rope_mass_per_metre", "quantity, kg/m", "required", "≥ 0"),
        key(
            "rope_mass_factor",
            "number",
            "not given",
            "> 0 when given (descriptive: γ = γ̄ γ_st d²)",
        ),
        key("steel_density", "quantity, kg/m³", "not given", "> 0 when given"),
        key("drum_radius", "quantity, m", "required", "> 0"),
        key("sheave_radius", "quantity, m", "required", "> 0"),
        key("chord_length", "quantity, m", "required", "> 0"),
        key(
            "lift_height",
            "quantity, m",
            "required",
            r#"< `max_hanging_length` ("the hanging rope length L − H must stay positive")"#,
        ),
        key("max_hanging_length", "quantity, m", "required", "> 0"),
        key("chord_angle", r#"quantity, rad (or `"30 deg"`)"#, "required", "finite"),
        key("drum_inertia", "quantity, kg m²", "required", "> 0"),
        key("sheave_inertia", "quantity, kg m²", "required", "> 0"),
        key("end_mass", "quantity, kg", "required", "> 0"),
    ],
};
