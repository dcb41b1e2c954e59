//! The key tables of `kind = "mdof"` ([`super::mdof`]): the `[model]` table, its coordinates, elements and
//! outputs. The reference page shows them ([`crate::scenario::key_table`]).

use crate::scenario::key_table::{key, KeyTable};

/// `[model]` of kind `mdof`: elements (coordinates with masses) or full matrices.
pub const MDOF: KeyTable = KeyTable {
    file: "scenario",
    prefix: "model",
    kind: Some("mdof"),
    keys: &[
        key(
            "coordinates",
            "array of tables `{ name, unit, mass }`",
            "required",
            "see below",
        ),
        key(
            "base_inputs",
            "integer N",
            "0",
            r#"0 … 10000 ("expected a count from 0 to 10000"); the model needs N > 0 or `forces` ("a generic mdof scenario needs at least one input")"#,
        ),
        key(
            "element",
            "tables `[[model.element]]`",
            "none",
            r#"see below; not with `mass_matrix` ("give either elements with coordinate masses, or full matrices …, not both")"#,
        ),
        key(
            "forces",
            "array of points",
            "none",
            r#"force inputs, each applied at a point (N on lengths, N m on angles alone); with one `[input]` process not together with base inputs ("one [input] process cannot drive both base displacements (m) and forces (N)": use `[[input]]` tables)"#,
        ),
        key(
            "mass_matrix",
            "n × n rows of SI numbers",
            "–",
            "its presence selects the matrix form",
        ),
        key("damping_matrix", "n × n rows", "zeros", "matrix form only"),
        key("stiffness_matrix", "n × n rows", "zeros", "matrix form only"),
        key("base_stiffness", "n × N rows", "zeros", "K_u, matrix form only"),
        key(
            "base_damping",
            "n × N rows",
            "zeros",
            r#"B_u, matrix form only; every matrix of the wrong size: "must be RxC""#,
        ),
        key("output", "tables `[[model.output]]`", "required", "see below"),
        key(
            "positions",
            "array of lengths, one per input",
            "all `0 m`",
            r#"≥ 0: distance behind the first contact (delay = position/speed); "need one position and one gain per input""#,
        ),
        key(
            "gains",
            "array of numbers, one per input",
            "all 1",
            "u_j = gain · x(t − delay)",
        ),
        key(
            "tracks",
            r#"array of `"left"`/`"right"`, one per input"#,
            "none",
            r#"a machine on two tracks (driven by an `[[input]]` road); "expected \"left\" or \"right\"""#,
        ),
    ],
};

/// `coordinates = [{ … }]` of an mdof model.
pub const COORDINATE: KeyTable = KeyTable {
    file: "scenario",
    prefix: "model.coordinates[]",
    kind: Some("mdof"),
    keys: &[
        key("name", "string", "required", ""),
        key(
            "unit",
            "string",
            "`m`",
            r#"`m` (mass in kg) or `rad` (inertia in kg m²); else "coordinate units are \"m\" … or \"rad\" …""#,
        ),
        key(
            "mass",
            "quantity, kg or kg m²",
            "required with elements; not read with matrices",
            r#"> 0 ("must be > 0"); masses more than 1e12 apart are refused ("check the units")"#,
        ),
    ],
};

/// `[[model.element]]` of an mdof model: a spring and a damper between a point and its far end.
pub const ELEMENT: KeyTable = KeyTable {
    file: "scenario",
    prefix: "model.element[]",
    kind: Some("mdof"),
    keys: &[
        key("name", "string", "required", "named by outputs `element = …`"),
        key(
            "point",
            "point (n weights)",
            "required",
            r#""expected n weights (one per coordinate)""#,
        ),
        key(
            "to",
            r#"`"ground"`, `"base j"` or a point"#,
            "required",
            r#"j < `base_inputs` ("only N base inputs (set model.base_inputs)")"#,
        ),
        key(
            "stiffness",
            "quantity: N/m, or N m/rad for a point on angles alone",
            "0",
            r#"≥ 0 ("must be >= 0")"#,
        ),
        key("damping", "quantity: N s/m, or N m s/rad", "0", "≥ 0"),
    ],
};

/// `[[model.output]]` of an mdof model.
pub const OUTPUT: KeyTable = KeyTable {
    file: "scenario",
    prefix: "model.output[]",
    kind: Some("mdof"),
    keys: &[
        key("name", "string", "required", "unique in the model"),
        key("quantity", "string", "required", "`displacement`, `velocity`, `acceleration` (with `point`); `relative-displacement`, `relative-velocity` (with `point` and `base`: gᵀq − u_j); `deflection`, `spring-force`, `damper-force`, `element-force` (with `element`)"),
        key("point", "point", "required by the point quantities", ""),
        key("base", "integer: index of a base input", "required by the relative quantities", r#"0 … N−1 ("expected the index of a base input")"#),
        key("element", "string: an element's name", "required by the element quantities", r#""no such element; known: …""#),
    ],
};
