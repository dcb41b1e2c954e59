//! Every error of the `[[input]]` reader and of the `kind = "mdof"` reader, pinned to the letter: the key it
//! names and its reason. The expected texts are the messages of the readers as they were before they were
//! split around their key tables (`src/scenario/inputs.rs`, `src/scenario/generic/mdof.rs` at the commit
//! that introduced the tables), so a change of any message fails here. The unknown-key errors of the other
//! sections whose readers take their check from a key table are pinned the same way
//! ([`every_section_unknown_key_is_the_same`]).

use crate::common;
use stochvib::Error;

/// A `[[model.element]]` of 20 kN/m and 1 kN s/m named `name` from the body (coordinate 0) to `to`.
fn spring(name: &str, to: &str) -> String {
    format!(
        "[[model.element]]\nname = \"{name}\"\npoint = [1]\nto = \"{to}\"\nstiffness = \"20 kN/m\"\n\
         damping = \"1 kN*s/m\"\n"
    )
}

/// A 500 kg body with the `[model]` lines `keys`, the elements `elements` and a velocity output.
fn model(keys: &str, elements: &str) -> String {
    format!(
        "[model]\nkind = \"mdof\"\n{keys}coordinates = [{{ name = \"body\", mass = \"500 kg\" }}]\n{elements}\
         [[model.output]]\nname = \"body\"\nquantity = \"velocity\"\npoint = [1]\n"
    )
}

/// A body on two springs (base inputs 0 and 1) with a force on it (input 2).
fn body_model() -> String {
    model(
        "base_inputs = 2\nforces = [[1]]\n",
        &(spring("left", "base 0") + &spring("right", "base 1")),
    )
}

/// A road of two tracks (`road = { … }` with a constant coherence).
const ROAD: &str = r#"road = { spectrum = "iso8608-c", track_width = "1.5 m", coherence = { kind = "constant", coherence_amplitude = 0.5 } }"#;

/// A force process.
const FORCE: &str = r#"spectrum = { kind = "band-white", unit = "N", convention = "one-sided-cyclic", level = 1.0, band = ["1 Hz", "20 Hz"] }"#;

/// A mass on a spring and damper over one base input, under one `[input]` process.
fn one_mass() -> String {
    model("base_inputs = 1\n", &spring("spring", "base 0")) + "[input]\nspectrum = \"white-1-80hz\"\n"
}

/// The (key, reason) of the error `text` gets.
fn error_of(text: &str) -> (String, String) {
    let root = common::root();
    let path = root.join("data").join("key-table-errors.toml");
    match stochvib::scenario::parse_document(text, &path, &root.join("spectra")) {
        Err(Error::File { key, reason, .. }) => (key, reason),
        Err(e) => panic!("not a file error: {e}\n{text}"),
        Ok(_) => panic!("accepted:\n{text}"),
    }
}

/// Checks each case: (scenario text, key, reason).
fn check(cases: &[(String, &str, &str)]) {
    for (text, key, reason) in cases {
        let (k, r) = error_of(text);
        assert_eq!((k.as_str(), r.as_str()), (*key, *reason), "\n{text}");
    }
}

/// [`body_model`] with the `[[input]]` tables `tables` (each a list of lines).
fn body(tables: &[&str]) -> String {
    let mut text = body_model();
    for t in tables {
        text.push_str("[[input]]\n");
        text.push_str(t);
        text.push('\n');
    }
    text
}

#[test]
fn every_input_table_error_is_the_same() {
    let road =
        |extra: &str| format!("{ROAD}\nspeed = \"20 m/s\"\ndrives = [0, 1]\ntracks = [\"left\", \"right\"]\n{extra}");
    let force = format!("{FORCE}\ndrives = [2]");
    let kurtosis_reason = "a non-Gaussian road of two tracks with a coherence is not available: a Laplace moving \
        average per track mixed to the prescribed cross-spectrum would not keep the prescribed kurtosis, and no \
        sound construction of a non-Gaussian pair with a given coherence is implemented; give `kurtosis` to an \
        [[input]] of one process (spectrum = …), or use a Gaussian road";
    let cases: Vec<(String, &str, &str)> = vec![
        (
            format!("input = []\n{}", body_model()),
            "input",
            "no [[input]] table: give at least one",
        ),
        (
            format!("input = [1]\n{}", body_model()),
            "input[0]",
            "expected an [[input]] table",
        ),
        (
            body(&[&road("drivs = [0]"), &force]),
            "input[0].drivs",
            "unknown key (known keys here: name, spectrum, road, band, enveloping, speed, speed_profile, mean, drives, \
             tracks, positions, gains, kurtosis)",
        ),
        (
            body(&[&road("spectrum = \"iso8608-c\""), &force]),
            "input[0].road",
            "give either spectrum (one process) or road (two tracks), not both",
        ),
        (
            body(&["speed = \"20 m/s\"", &force]),
            "input[0].spectrum",
            "give spectrum = … (one process) or road = { spectrum, coherence, track_width } (two tracks)",
        ),
        (
            body(&[&road("").replace("iso8608-c", "white-1-80hz"), &force]),
            "input[0].road.spectrum",
            "a road of two tracks needs a spatial spectrum (a profile in cycles/m or rad/m)",
        ),
        (
            body(&[&road("").replace("track_width = \"1.5 m\", ", ""), &force]),
            "input[0].road.track_width",
            "required (a length, e.g. \"1.5 m\")",
        ),
        (
            body(&[&road("").replace("1.5 m", "0 m"), &force]),
            "input[0].road.track_width",
            "must be a finite length > 0",
        ),
        (
            body(&[&road("").replace("speed = \"20 m/s\"\n", ""), &force]),
            "input[0].speed",
            "a road is a spatial process: give the speed (e.g. speed = \"20 m/s\")",
        ),
        (
            body(&[&road("name = \"a\""), &format!("{force}\nname = \"a\"")]),
            "input[1].name",
            "input[0] has this name already",
        ),
        (
            body(&[&road("name = \"a b\""), &force]),
            "input[0].name",
            "a signal name: not empty, without spaces or '/'",
        ),
        (
            body(&[&road("").replace("drives = [0, 1]\n", ""), &force]),
            "input[0].drives",
            "with several [[input]] tables each names the model inputs it drives (0 to 2)",
        ),
        (
            body(&[&road("").replace("drives = [0, 1]", "drives = []"), &force]),
            "input[0].drives",
            "expected a non-empty array of model input indices",
        ),
        (
            body(&[&road("").replace("drives = [0, 1]", "drives = [0, 7]"), &force]),
            "input[0].drives[1]",
            "expected a model input index from 0 to 2",
        ),
        (
            body(&[&road("positions = [\"0 m\"]"), &force]),
            "input[0].positions",
            "1 values for 2 driven inputs (`drives`): need one per driven input",
        ),
        (
            body(&[&road("positions = \"0 m\""), &force]),
            "input[0].positions",
            "expected an array of 2 values, one per driven input",
        ),
        (
            body(&[&road("positions = [\"0 m\", \"-1 m\"]"), &force]),
            "input[0].positions[1]",
            "must be a finite distance >= 0 behind the first contact",
        ),
        (
            body(&[&road("gains = [1, \"x\"]"), &force]),
            "input[0].gains[1]",
            "expected a finite number",
        ),
        (
            body(&[&road(""), &format!("{force}\ntracks = [\"left\"]")]),
            "input[1].tracks",
            "only a road of two tracks (road = { … }) has tracks; this input is one process",
        ),
        (
            body(&[&road("").replace("tracks = [\"left\", \"right\"]\n", ""), &force]),
            "input[0].tracks",
            "model input 0 has no track: name the track of each driven input, tracks = [\"left\", \"right\", …]",
        ),
        (
            body(&[&road(""), &format!("{FORCE}\ndrives = [1, 2]")]),
            "input[1].drives[0]",
            "model input 1 is driven by input[0] already: each model input by one table",
        ),
        (
            body(&[&road("")]),
            "input",
            "model input 2 is driven by no [[input]] table: add it to some table's drives",
        ),
        (
            body(&[&road("kurtosis = 6"), &force]),
            "input[0].kurtosis",
            kurtosis_reason,
        ),
        (
            body(&[
                &format!("{force}\npositions = [\"1 m\"]"),
                &road("").replace("speed = \"20 m/s\"\n", ""),
            ]),
            "input[0].speed",
            "model input 2 is 1 m behind the first contact: give the speed (e.g. speed = \"20 m/s\")",
        ),
        (
            body(&[
                "spectrum = \"iso8608-c\"\ndrives = [2]",
                &road("").replace("speed = \"20 m/s\"\n", ""),
            ]),
            "input[0].speed",
            "the spectrum is spatial (a road): give the speed (e.g. speed = \"20 m/s\")",
        ),
    ];
    check(&cases);
}

#[test]
fn every_mdof_error_is_the_same() {
    let mdof = one_mass();
    let with = |from: &str, to: &str| {
        assert!(mdof.contains(from), "{from}");
        mdof.replacen(from, to, 1)
    };
    let coordinates = "coordinates = [{ name = \"body\", mass = \"500 kg\" }]";
    let element_block = spring("spring", "base 0");
    let outputs = "[[model.output]]\nname = \"body\"\nquantity = \"velocity\"\npoint = [1]\n";
    let matrices = |mass: &str| {
        with(
            coordinates,
            &format!("coordinates = [{{ name = \"body\" }}]\nmass_matrix = {mass}"),
        )
    };
    let cases: Vec<(String, &str, &str)> = vec![
        (
            with(coordinates, "coordinates = 3"),
            "model.coordinates",
            "expected an array of { name, unit, mass }",
        ),
        (
            with(coordinates, "coordinates = [3]"),
            "model.coordinates[0]",
            "expected { name, unit, mass }",
        ),
        (
            with("name = \"body\", mass", "name = \"body\", unit = \"deg\", mass"),
            "model.coordinates[0].unit",
            "coordinate units are \"m\" (mass in kg) or \"rad\" (inertia in kg m^2)",
        ),
        (
            with("\"500 kg\"", "\"-5 kg\""),
            "model.coordinates[0].mass",
            "must be > 0",
        ),
        (
            with(
                coordinates,
                "coordinates = [{ name = \"a\", mass = \"1e-10 kg\" }, { name = \"b\", mass = \"1e4 kg\" }]",
            )
            .replace("point = [1]", "point = [1, 0]"),
            "model.coordinates[1].mass",
            "1.0e14 times the mass of `a`: double precision cannot resolve masses more than 1e12 apart (check the \
             units)",
        ),
        (
            with("base_inputs = 1", "base_inputs = -1"),
            "model.base_inputs",
            "expected a count from 0 to 10000",
        ),
        (
            with(&element_block, "").replace("base_inputs = 1", "base_inputs = 1\nelement = 3"),
            "model.element",
            "expected [[model.element]] tables",
        ),
        (
            with(&element_block, "").replace("base_inputs = 1", "base_inputs = 1\nelement = [3]"),
            "model.element[0]",
            "expected a table",
        ),
        (
            with("base_inputs = 1", "base_inputs = 1\nforces = 3"),
            "model.forces",
            "expected an array of points (coordinate weights)",
        ),
        (
            with("base_inputs = 1", "base_inputs = 1\nforces = [[1]]"),
            "model.forces",
            "the model has 1 base inputs as well: one [input] process cannot drive both base displacements (m) \
             and forces (N); write [[input]] tables, one per source, each naming the inputs it drives",
        ),
        (
            matrices("[[500]]"),
            "model.element",
            "give either elements with coordinate masses, or full matrices (mass_matrix, …), not both",
        ),
        (
            matrices("[[500, 0]]").replace(&element_block, ""),
            "model.mass_matrix",
            "must be 1x1",
        ),
        (
            with(outputs, "").replace("base_inputs = 1", "base_inputs = 1\noutput = 3"),
            "model.output",
            "expected [[model.output]] tables",
        ),
        (
            with(outputs, "").replace("base_inputs = 1", "base_inputs = 1\noutput = [3]"),
            "model.output[0]",
            "expected a table",
        ),
        (
            with("quantity = \"velocity\"", "quantity = \"jerk\""),
            "model.output[0].quantity",
            "expected displacement, velocity, acceleration, relative-displacement, relative-velocity, deflection, \
             spring-force, damper-force or element-force",
        ),
        (
            with(
                "quantity = \"velocity\"\npoint = [1]",
                "quantity = \"deflection\"\nelement = \"nope\"",
            ),
            "model.output[0].element",
            "no such element; known: spring",
        ),
        (
            with(
                "quantity = \"velocity\"",
                "quantity = \"relative-displacement\"\nbase = 3",
            ),
            "model.output[0].base",
            "expected the index of a base input (0 to 0)",
        ),
        (
            with("\"20 kN/m\"", "\"-20 kN/m\""),
            "model.element[0].stiffness",
            "must be >= 0",
        ),
        (
            with("to = \"base 0\"", "to = \"base 5\""),
            "model.element[0].to",
            "only 1 base inputs (set model.base_inputs)",
        ),
        (
            with("base_inputs = 1\n", "").replace("to = \"base 0\"", "to = \"ground\""),
            "model.base_inputs",
            "a generic mdof scenario needs at least one input: base_inputs > 0 or forces",
        ),
    ];
    check(&cases);
}

/// A transfer function 1/(4s² + 0.4s + 1) with the output `y` in m.
const TRANSFER: &str = r#"[model]
kind = "transfer-function"
numerator = [1.0]
denominator = [4.0, 0.4, 1.0]
output = { name = "y", unit = "m" }
"#;

/// [`TRANSFER`] on a road at 10 m/s.
fn on_road() -> String {
    TRANSFER.to_string()
        + r#"[input]
spectrum = { kind = "exponential", domain = "spatial", variance = "1 cm^2", alpha = "0.2 1/m" }
speed = "10 m/s"
"#
}

/// The operator seat of Sukharev (2012) 7.6 under its cab-floor process (outputs `seat_acc`, `travel`).
const SEAT: &str = r#"[model]
kind = "operator-seat"
operator_mass = "80 kg"
seat_mass = "26 kg"
stiffness = "6500 N/m"
damping_rate = "4.22 1/s"
[input]
spectrum = { kind = "rational", domain = "temporal", unit = "m", numerator = [9.978705857784458], denominator = [124596039.48735943, -448861.0914846832, 404.2589962686201, 1.0] }
"#;

/// The `[model]` table of a data file with the unknown key `extra = 1`.
fn model_with_extra(file: &str) -> String {
    let text = std::fs::read_to_string(common::root().join("data").join(file)).unwrap();
    text.replacen("[model]\n", "[model]\nextra = 1\n", 1)
}

/// An unknown key `extra` in every section whose reader takes its unknown-key check from a key table: the
/// key named and the keys listed. The lists are the keys each reader asked for, alphabetically, as the
/// readers' unknown-key check (`Fields::finish`) wrote them before the tables (the sections of
/// `src/scenario/scenario_file.rs`, `verdict_spec.rs`, `transient_keys.rs`, `input_filters.rs`,
/// `inputs.rs`, `generic/io.rs` and `generic/mdof.rs` at the commit that introduced the tables).
#[test]
fn every_section_unknown_key_is_the_same() {
    let unknown = |known: &str| format!("unknown key (known keys here: {known})");
    let white = format!("{TRANSFER}[input]\nspectrum = \"white-1-80hz\"\n");
    let comfort = |section: &str, axis: &str| {
        format!(
            "{SEAT}[analysis.comfort]\nexposure = \"6 h\"\n{section}[[analysis.comfort.axis]]\noutput = \
             \"seat_acc\"\nlocation = \"seat-surface\"\naxis = \"z\"\n{axis}"
        )
    };
    let road = |road: &str, coherence: &str| {
        format!(
            "{}[[input]]\nroad = {{ spectrum = \"iso8608-c\", track_width = \"1.5 m\", {road}coherence = {{ kind = \
             \"dodds-robson\"{coherence} }} }}\nspeed = \"20 m/s\"\ntracks = [\"left\", \"right\"]\n",
            body_model().replace("forces = [[1]]\n", "")
        )
    };
    let cases: Vec<(String, &str, String)> = vec![
        (
            format!("extra = 1\n{white}"),
            "extra",
            unknown("analysis, input, model, source, title, transient"),
        ),
        (
            format!("{white}extra = 1\n"),
            "input.extra",
            unknown("band, envelope, enveloping, kurtosis, mean, spectrum, speed, speed_profile"),
        ),
        (
            on_road() + "enveloping = { kind = \"moving-average\", length = \"0.25 m\", extra = 1 }\n",
            "input.enveloping.extra",
            unknown("kind, length"),
        ),
        (
            on_road()
                + "[input.speed_profile]\ntimes = [\"0 s\", \"4 s\"]\nspeeds = [\"10 m/s\", \"0 m/s\"]\nextra = 1\n",
            "input.speed_profile.extra",
            unknown("acceleration, from, speeds, start, times, to"),
        ),
        (
            on_road()
                + "[input.speed_profile]\nfrom = \"0 m/s\"\nto = \"10 m/s\"\nacceleration = \"2 m/s^2\"\nextra = 1\n",
            "input.speed_profile.extra",
            unknown("acceleration, from, speeds, start, times, to"),
        ),
        (
            on_road() + "[input.envelope]\ntimes = [\"0 s\", \"1 s\"]\nintensity = [0.0, 1.0]\nextra = 1\n",
            "input.envelope.extra",
            unknown("amplitude, intensity, times"),
        ),
        (
            format!("{white}[analysis]\nextra = 1\n"),
            "analysis.extra",
            unknown("band, bands, comfort, duration, fatigue, levels, mission, outputs, quadrature, seat_factor"),
        ),
        (
            format!("{white}[analysis.quadrature]\nrel_tol = 1e-8\nextra = 1\n"),
            "analysis.quadrature.extra",
            unknown("max_half_periods, max_subintervals, rel_tol"),
        ),
        (
            comfort("extra = 1\n", ""),
            "analysis.comfort.extra",
            unknown("a8_action, a8_limit, axis, exposure, purpose, vdv_action, vdv_limit"),
        ),
        (
            comfort("", "extra = 1\n"),
            "analysis.comfort.axis[0].extra",
            unknown("axis, k, location, output, weighting"),
        ),
        (
            format!(
                "{SEAT}[analysis.fatigue]\noutput = \"travel\"\nstress_factor = 1.29313e10\nk = 5\n\
                 reference_amplitude = \"100 MPa\"\nreference_cycles = 2e6\nextra = 1\n"
            ),
            "analysis.fatigue.extra",
            unknown(
                "bins, c, design_distance, design_life, endurance_limit, k, methods, output, reference_amplitude, \
                 reference_cycles, stress_factor",
            ),
        ),
        (
            format!("{SEAT}[analysis.seat_factor]\nseat = \"seat_acc\"\nfloor = \"base 0\"\nextra = 1\n"),
            "analysis.seat_factor.extra",
            unknown("floor, seat, weighting"),
        ),
        (
            on_road() + "[transient]\nduration = \"5 s\"\n[analysis.mission]\nlevels = { y = [\"1 cm\"] }\nextra = 1\n",
            "analysis.mission.extra",
            unknown("duration, levels"),
        ),
        (
            on_road() + "[transient]\nduration = \"5 s\"\nextra = 1\n",
            "transient.extra",
            unknown("duration, max_error, rel_tol, schedule, start, state, step"),
        ),
        (
            on_road()
                + "[transient]\nduration = \"5 s\"\n[[transient.schedule]]\nkey = \"model.denominator\"\n\
                   times = [\"0 s\", \"1 s\"]\nvalues = [1.0, 2.0]\nextra = 1\n",
            "transient.schedule[0].extra",
            // `rope` (the rope-length formulas of a winding schedule) is a key of the schedule since this pin
            // was transcribed: the list of known keys names it
            unknown("key, rope, times, values"),
        ),
        (
            on_road()
                + "[transient]\nduration = \"5 s\"\n[[transient.schedule]]\nkey = \"model.denominator\"\n\
                   times = [\"0 s\", \"1 s\"]\nvalues = [1.0, 2.0]\n\
                   rope = { formula = \"stiffness\", axial_rigidity = \"1 MN\", extra = 1 }\n",
            "transient.schedule[0].rope.extra",
            unknown("axial_rigidity, end_mass, formula, mass_per_metre"),
        ),
        (
            model_with_extra("quarter-car-model.toml"),
            "model.extra",
            unknown(
                "kind, nonlinear, sprung_mass, suspension_damping, suspension_stiffness, tyre_damping, \
                 tyre_stiffness, unsprung_mass",
            ),
        ),
        (
            model_with_extra("mine-hoist.toml"),
            "model.extra",
            unknown(
                "chord_angle, chord_length, drum_inertia, drum_radius, end_mass, kind, lift_height, \
                 max_hanging_length, nonlinear, rope_area_factor, rope_diameter, rope_mass_factor, \
                 rope_mass_per_metre, sheave_inertia, sheave_radius, steel_density, young_modulus",
            ),
        ),
        (
            white.replace("unit = \"m\" }", "unit = \"m\", extra = 1 }"),
            "model.output.extra",
            unknown("name, unit"),
        ),
        (
            road("", ", extra = 1"),
            "input[0].road.coherence.extra",
            unknown("kind, waviness"),
        ),
        (
            road("extra = 1, ", ""),
            "input[0].road.extra",
            unknown("coherence, spectrum, track_width"),
        ),
    ];
    for (text, key, reason) in &cases {
        let (k, r) = error_of(text);
        assert_eq!((k.as_str(), r.as_str()), (*key, reason.as_str()), "\n{text}");
    }
}

/// An unknown key `extra` in each sub-table of the `full-vehicle` and `machine` kinds, whose readers take
/// their unknown-key check from the key tables `FULL_VEHICLE_*` and `MACHINE_*`: the key named with its
/// dotted path, and the keys of the sub-table listed alphabetically (the keys of its row in
/// `docs/scenario-reference.md`).
#[test]
fn full_vehicle_and_machine_sub_tables_unknown_key() {
    let unknown = |known: &str| format!("unknown key (known keys here: {known})");
    let data = |file: &str| std::fs::read_to_string(common::root().join("data").join(file)).unwrap();
    let (car, loader) = (data("full-vehicle-two-tracks.toml"), data("wheel-loader-cab-seat.toml"));
    let suspended = common::CAR_AS_MACHINE.to_string()
        + "[[input]]\nname = \"road\"\nroad = { spectrum = \"iso8608-c\", track_width = \"1.5 m\", coherence = { \
           kind = \"dodds-robson\", waviness = 2 } }\nspeed = \"20 m/s\"\n";
    // `text` with `extra = 1` written after the first `after`
    let with = |text: &str, after: &str| {
        assert!(text.contains(after), "{after}");
        text.replacen(after, &format!("{after}\nextra = 1"), 1)
    };
    // `text` with `, extra = 1` in the inline table that ends in the first `end`
    let inline = |text: &str, end: &str| {
        assert!(text.contains(end), "{end}");
        text.replacen(end, &end.replace(" }", ", extra = 1 }"), 1)
    };
    let cases: Vec<(String, &str, String)> = vec![
        (
            inline(&car, r#"rear = "22 kN/m" }"#),
            "model.suspension_stiffness.extra",
            unknown("front, rear"),
        ),
        (
            inline(&car, r#"rear = "1800 N*s/m" }"#),
            "model.suspension_damping.extra",
            unknown("front, rear"),
        ),
        (
            inline(&car, r#"rear = "35 kg" }"#),
            "model.unsprung_mass.extra",
            unknown("front, rear"),
        ),
        (
            inline(&car, r#"left = "0.35 m" }"#),
            "model.seat.extra",
            unknown("ahead, left"),
        ),
        (
            with(&loader, r#"height = "1.2 m""#),
            "model.body.extra",
            unknown("height, mass, pitch_inertia, roll_inertia"),
        ),
        (
            with(&loader, r#"tyre_damping = "4 kN*s/m""#),
            "model.axle[0].extra",
            unknown("name, oscillating, position, suspension, track_width, tyre_damping, tyre_stiffness"),
        ),
        (
            inline(&loader, r#"roll_damping = "2 kN*m*s/rad" }"#),
            "model.axle[1].oscillating.extra",
            unknown("roll_damping, roll_inertia, roll_stiffness"),
        ),
        (
            inline(&suspended, r#"unsprung_mass = "40 kg" }"#),
            "model.axle[0].suspension.extra",
            unknown("damping, stiffness, unsprung_mass"),
        ),
        (
            with(&loader, r#"mount_height = "1.7 m""#),
            "model.cab.extra",
            unknown("mass, mount, mount_height, pitch_inertia, position, roll_inertia"),
        ),
        (
            with(&loader, "stiffness = \"250 kN/m\"\ndamping = \"3 kN*s/m\""),
            "model.cab.mount[0].extra",
            unknown("damping, position, stiffness"),
        ),
        (
            with(&loader, r#"damping = "470 N*s/m""#),
            "model.seat.extra",
            unknown("damping, operator_mass, position, seat_mass, stiffness"),
        ),
        (
            with(&loader, r#"quantity = "displacement""#),
            "model.output[2].extra",
            unknown("direction, name, part, point, quantity"),
        ),
    ];
    for (text, key, reason) in &cases {
        let (k, r) = error_of(text);
        assert_eq!((k.as_str(), r.as_str()), (*key, reason.as_str()), "\n{text}");
    }
}
