//! Scenario files with several inputs (`[[input]]` tables): a road and a force on one generic model, a
//! generic machine whose wheels name their tracks, the full vehicle of the catalogue, the errors of the
//! format, and the natural frequencies of the seven-degree-of-freedom vehicle in a decoupled case.

mod common;
use common::tolerance::{EXACT, QUADRATURE, ROUNDING};
use std::f64::consts::PI;
use std::path::{Path, PathBuf};
use std::sync::Arc;
use stochvib::coherence::{IsotropicCoherence, TwoTracks};
use stochvib::models::full_vehicle::FullVehicle;
use stochvib::response::{analyze_output, Excitation};
use stochvib::scenario::{load_scenario, parse_scenario, Scenario};
use stochvib::spectrum::{IsoClass, PowerLaw};

fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).to_path_buf()
}

fn parse(text: &str) -> Scenario {
    parse_scenario(text, &root().join("data/test-multi.toml"), &root().join("spectra")).unwrap()
}

fn parse_err(text: &str) -> String {
    parse_scenario(text, &root().join("data/test-multi.toml"), &root().join("spectra"))
        .unwrap_err()
        .to_string()
}

/// Variance and mean of output `name` by the best route of `analyze_output`.
fn stats(sc: &Scenario, name: &str) -> (f64, f64) {
    let sys = sc.model.system.as_ref();
    let i = sys.outputs().iter().position(|o| o.name == name).unwrap();
    let st = analyze_output(sys, &sc.excitation, i).unwrap();
    (st.variance.unwrap(), st.mean.unwrap())
}

// A quarter car (body 300 kg, wheel 40 kg, suspension 20 kN/m and 1.5 kN s/m, tyre 200 kN/m).
const QUARTER_CAR: &str = r#"
coordinates = [
  { name = "body", unit = "m", mass = "300 kg" },
  { name = "wheel", unit = "m", mass = "40 kg" },
]
[[model.element]]
name = "suspension"
point = [1, 0]
to = [0, 1]
stiffness = "20 kN/m"
damping = "1.5 kN*s/m"
[[model.output]]
name = "body"
quantity = "displacement"
point = [1, 0]
[[model.output]]
name = "travel"
quantity = "deflection"
element = "suspension"
"#;

const ROAD: &str = r#"{ kind = "exponential", domain = "spatial", variance = "1 cm^2", alpha = "0.2 1/m" }"#;
const FORCE: &str = r#"{ kind = "exponential", unit = "N", variance = "1e4 N^2", alpha = "3 1/s" }"#;

#[test]
fn a_road_and_a_force_on_one_model_add_their_variances_and_means() {
    // Independent sources add: Var = Var(road alone) + Var(force alone). The oracles are the one-input
    // scenarios of the old `[input]` form (the road under the tyre with `base_inputs = 1`; the force with the
    // tyre on the ground), each by the exact Lyapunov route of a one-process excitation: other files, other
    // excitation variants, other code paths than the [[input]] sources under test.
    // Means (closed form, statics): the road mean μ_r lifts the whole car by μ_r; a mean force F on the body
    // compresses the suspension and the tyre in series: body = μ_r + F(1/k + 1/k_t), travel = F/k.
    let both = format!(
        r#"[model]
kind = "mdof"
base_inputs = 1
forces = [[1, 0]]
{QUARTER_CAR}
[[model.element]]
name = "tyre"
point = [0, 1]
to = "base 0"
stiffness = "200 kN/m"

[[input]]
name = "road"
spectrum = {ROAD}
speed = "20 m/s"
mean = "1 cm"
drives = [0]

[[input]]
name = "load"
spectrum = {FORCE}
mean = "100 N"
drives = [1]
"#
    );
    let road_only = format!(
        r#"[model]
kind = "mdof"
base_inputs = 1
{QUARTER_CAR}
[[model.element]]
name = "tyre"
point = [0, 1]
to = "base 0"
stiffness = "200 kN/m"

[input]
spectrum = {ROAD}
speed = "20 m/s"
"#
    );
    let force_only = format!(
        r#"[model]
kind = "mdof"
forces = [[1, 0]]
{QUARTER_CAR}
[[model.element]]
name = "tyre"
point = [0, 1]
to = "ground"
stiffness = "200 kN/m"

[input]
spectrum = {FORCE}
"#
    );
    let (sb, sr, sf) = (parse(&both), parse(&road_only), parse(&force_only));
    assert!(matches!(sb.excitation, Excitation::Sources { .. }));
    assert_eq!(sb.inputs.len(), 2);
    let signals: Vec<String> = sb
        .input_signals()
        .iter()
        .map(|s| format!("{} [{}]", s.name, s.unit))
        .collect();
    assert_eq!(signals, ["road [m]", "load [N]"]);
    let (k, kt, f, mu) = (20e3, 200e3, 100.0, 0.01);
    for (name, mean) in [("body", mu + f * (1.0 / k + 1.0 / kt)), ("travel", f / k)] {
        let (v, m) = stats(&sb, name);
        let oracle = stats(&sr, name).0 + stats(&sf, name).0;
        assert!((v - oracle).abs() <= QUADRATURE * oracle, "{name}: {v:e} vs {oracle:e}");
        assert!((m - mean).abs() <= EXACT * mean, "{name}: mean {m:e} vs {mean:e}");
    }
    // the single-[input] form still refuses the mixture, and says what to write instead
    let mixed_single = both.split("[[input]]").next().unwrap().to_string() + "[input]\nspectrum = \"type1\"\n";
    let e = parse_err(&mixed_single);
    assert!(e.contains("model.forces") && e.contains("[[input]]"), "{e}");
}

// A body in bounce z and roll φ on two wheels whose `[model] tracks` name their tracks.
fn two_wheels(tracks: &str, gains: &str, input: &str) -> String {
    format!(
        r#"[model]
kind = "mdof"
base_inputs = 2
{tracks}
gains = {gains}
positions = ["0 m", "0 m"]
coordinates = [
  {{ name = "z", unit = "m", mass = "800 kg" }},
  {{ name = "phi", unit = "rad", mass = "300 kg*m^2" }},
]
[[model.element]]
name = "left"
point = [1, 0.75]
to = "base 0"
stiffness = "30 kN/m"
damping = "2 kN*s/m"
[[model.element]]
name = "right"
point = [1, -0.75]
to = "base 1"
stiffness = "30 kN/m"
damping = "2 kN*s/m"
[[model.output]]
name = "bounce"
quantity = "displacement"
point = [1, 0]
[[model.output]]
name = "roll"
quantity = "displacement"
point = [0, 1]
{input}
"#
    )
}

#[test]
fn wheels_that_name_their_tracks_see_the_sum_and_difference_of_the_tracks() {
    // Closed form (derived here): the symmetric body obeys M z̈ + 2C ż + 2K z = 2(C ḃ + K b) with
    // b = (u_L + u_R)/2, and I φ̈ + 2Ch² φ̇ + 2Kh² φ = 2h(C ḋ + K d) with d = (u_L − u_R)/2. For two tracks of
    // density S and constant coherence ρ: S_b = S(1 + ρ)/2, S_d = S(1 − ρ)/2. The old one-track form
    // with gains (1, 1) gives b = q, d = 0 (bounce variance V_b under S); with gains (1, −1) it gives
    // b = 0, d = q (roll variance V_r under S). Hence Var bounce = (1 + ρ)/2 V_b and
    // Var roll = (1 − ρ)/2 V_r, the oracles by the exact Lyapunov route of a one-process track.
    let rho = 0.4;
    let road = format!(
        r#"[[input]]
road = {{ spectrum = {ROAD}, track_width = "1.5 m", coherence = {{ kind = "constant", coherence_amplitude = {rho} }} }}
speed = "15 m/s"
"#
    );
    let sc = parse(&two_wheels(r#"tracks = ["left", "right"]"#, "[1, 1]", &road));
    let single = |gains: &str| {
        parse(&two_wheels(
            "",
            gains,
            &format!("[input]\nspectrum = {ROAD}\nspeed = \"15 m/s\"\n"),
        ))
    };
    let vb = stats(&single("[1, 1]"), "bounce").0;
    let vr = stats(&single("[1, -1]"), "roll").0;
    for (name, oracle) in [("bounce", (1.0 + rho) / 2.0 * vb), ("roll", (1.0 - rho) / 2.0 * vr)] {
        let v = stats(&sc, name).0;
        assert!((v - oracle).abs() <= QUADRATURE * oracle, "{name}: {v:e} vs {oracle:e}");
    }
    // the same tracks written in the [[input]] table instead of the model give the same excitation
    let in_table = parse(&two_wheels(
        "",
        "[1, 1]",
        &format!("{road}tracks = [\"left\", \"right\"]\npositions = [\"0 m\", \"0 m\"]\n"),
    ));
    for w in [0.1, 1.0, 10.0] {
        assert_eq!(in_table.excitation.matrix(w), sc.excitation.matrix(w));
    }
}

#[test]
fn the_full_vehicle_file_is_the_passenger_car_on_an_isotropic_class_c_road() {
    // Wiring: the file's [model] is FullVehicle::passenger_car (same numbers as the source code's
    // constructor), its road the ISO class C geometric mean with the Dodds–Robson coherence of a 1.5 m
    // track width at 20 m/s, its wheels fl, fr at 0 m and rl, rr at the wheelbase on left/right. The
    // cross-spectral matrix of the inputs and the frequency responses must be the hand-built ones exactly.
    let sc = load_scenario(
        &root().join("data/full-vehicle-two-tracks.toml"),
        &root().join("spectra"),
    )
    .unwrap();
    let car = FullVehicle::passenger_car();
    let road = Arc::new(PowerLaw::iso_class(IsoClass::C).unwrap());
    let tracks = Arc::new(TwoTracks::new(road, Arc::new(IsotropicCoherence::new(1.5, 2.0).unwrap()), 20.0).unwrap());
    let exc = Excitation::two_tracks(tracks, &car.wheels()).unwrap();
    let sys = car.mdof().unwrap();
    use stochvib::system::FrequencyResponse;
    for w in [0.3, 2.0, 8.0, 60.0] {
        let (a, b) = (sc.excitation.matrix(w), exc.matrix(w));
        assert!((a - &b).norm() <= ROUNDING * b.norm(), "S_uu at {w}");
        assert_eq!(sc.model.system.response(w), sys.response(w));
    }
    assert!(sc.model.description.contains("natural frequencies"));
}

#[test]
fn the_full_vehicle_on_identical_tracks_does_not_roll() {
    // γ = 1 (constant coherence amplitude 1): u_L = u_R at every axle, and a left–right symmetric vehicle
    // does not roll; the roll density is S|h|²(1 + 1 − 1 − 1) summed over the axle pairs, zero up to the
    // rounding of terms of the size of the pitch variance (lever arms of order 1 m).
    let text = std::fs::read_to_string(root().join("data/full-vehicle-two-tracks.toml"))
        .unwrap()
        .replace(
            r#"coherence = { kind = "dodds-robson", waviness = 2 }"#,
            r#"coherence = { kind = "constant", coherence_amplitude = 1 }"#,
        )
        .replace(r#"seat = { ahead = "0.3 m", left = "0.35 m" }"#, "");
    let sc = parse(&text);
    let sys = sc.model.system.as_ref();
    let idx = |n: &str| sys.outputs().iter().position(|o| o.name == n).unwrap();
    let pitch = analyze_output(sys, &sc.excitation, idx("pitch"))
        .unwrap()
        .variance
        .unwrap();
    let roll = analyze_output(sys, &sc.excitation, idx("roll"))
        .unwrap()
        .variance
        .unwrap_or(0.0);
    assert!(roll.abs() <= ROUNDING * pitch, "roll {roll:e}, pitch {pitch:e}");
}

#[test]
fn full_vehicle_modes_match_the_decoupled_closed_forms() {
    // Closed form (derived here): with a = b, equal front and rear suspensions and unsprung masses, the
    // seven coordinates split into four uncoupled groups. Bounce: z with the mean wheel motion
    // w = Σz_i/4 is a quarter car of sprung mass m/4; pitch: s = aθ with (z_f − z_r)/2 is a quarter car of
    // sprung mass I_θ/(4a²); roll: r = (B/2)φ with (z_l − z_r)/2 is a quarter car of sprung mass
    // I_φ/B² (= I_φ/(4(B/2)²)); warp: the wheels alone in the pattern (+, −, −, +), ω² = (k + k_t)/m_u.
    // A quarter car (m_s, m_u, k, k_t) has ω² the roots of
    //   m_s m_u λ² − (m_s(k + k_t) + m_u k) λ + k k_t = 0.
    let car = FullVehicle {
        mass: 1200.0,
        pitch_inertia: 1900.0,
        roll_inertia: 420.0,
        front_distance: 1.3,
        rear_distance: 1.3,
        track_width: 1.6,
        suspension_stiffness: [24e3, 24e3],
        suspension_damping: [1500.0, 1500.0],
        unsprung_mass: [38.0, 38.0],
        tyre_stiffness: 190e3,
        seat: [0.0, 0.0],
    };
    let (k, kt, mu) = (24e3, 190e3, 38.0);
    let quarter = |ms: f64| {
        let (a, b, c) = (ms * mu, -(ms * (k + kt) + mu * k), k * kt);
        let d = (b * b - 4.0 * a * c).sqrt();
        [((-b - d) / (2.0 * a)).sqrt(), ((-b + d) / (2.0 * a)).sqrt()]
    };
    let mut expected: Vec<f64> = [
        quarter(1200.0 / 4.0),
        quarter(1900.0 / (4.0 * 1.3 * 1.3)),
        quarter(420.0 / (1.6 * 1.6)),
    ]
    .concat();
    expected.push(((k + kt) / mu).sqrt());
    expected.sort_by(f64::total_cmp);
    let (w, modes) = car.modes().unwrap();
    assert_eq!(w.len(), 7);
    for (a, b) in w.iter().zip(&expected) {
        // symmetric eigenproblem of a well-conditioned 7 × 7 pencil
        assert!(
            (a - b).abs() <= EXACT * b,
            "{a} vs {b} rad/s ({} vs {} Hz)",
            a / (2.0 * PI),
            b / (2.0 * PI)
        );
    }
    // the lowest mode is one of the three body modes: its wheel amplitudes are smaller than the body's
    let body = modes.column(0).rows(0, 3).norm();
    assert!(body > modes.column(0).rows(3, 4).norm());
}

#[test]
fn bad_input_tables_name_the_file_the_key_the_value_and_the_reason() {
    let model = format!(
        r#"[model]
kind = "mdof"
base_inputs = 1
forces = [[1, 0]]
{QUARTER_CAR}
[[model.element]]
name = "tyre"
point = [0, 1]
to = "base 0"
stiffness = "200 kN/m"
"#
    );
    let road = format!("[[input]]\nspectrum = {ROAD}\nspeed = \"20 m/s\"\ndrives = [0]\n");
    let force = format!("[[input]]\nspectrum = {FORCE}\ndrives = [1]\n");
    let cases: Vec<(String, &[&str])> = vec![
        // misspelt key
        (
            format!("{model}{road}[[input]]\nspectrum = {FORCE}\ndrive = [1]\n"),
            &["test-multi.toml", "input[1]", "drive", "unknown key"],
        ),
        // a model input driven twice
        (
            format!("{model}{road}[[input]]\nspectrum = {FORCE}\ndrives = [1, 0]\n"),
            &["input[1].drives[1]", "driven by input[0] already"],
        ),
        // a model input driven by none
        (
            format!("{model}{road}"),
            &["input", "model input 1", "driven by no [[input]] table"],
        ),
        // tracks on a single process
        (
            format!("{model}{force}{road}tracks = [\"left\"]\n"),
            &["input[1].tracks", "only a road of two tracks"],
        ),
        // a coherence kind that does not exist, and a misspelt coherence key
        (
            format!(
                "{model}{force}[[input]]\nroad = {{ spectrum = {ROAD}, track_width = \"1.5 m\", coherence = {{ kind = \"dodds\" }} }}\nspeed = \"20 m/s\"\ndrives = [0]\ntracks = [\"left\"]\n"
            ),
            &["input[1].road.coherence.kind", "dodds", "dodds-robson"],
        ),
        (
            format!(
                "{model}{force}[[input]]\nroad = {{ spectrum = {ROAD}, track_width = \"1.5 m\", coherence = {{ kind = \"dodds-robson\", wavines = 2 }} }}\nspeed = \"20 m/s\"\ndrives = [0]\ntracks = [\"left\"]\n"
            ),
            &["input[1].road.coherence.wavines", "unknown key"],
        ),
        // a track that is neither left nor right
        (
            format!(
                "{model}{force}[[input]]\nroad = {{ spectrum = {ROAD}, track_width = \"1.5 m\", coherence = {{ kind = \"constant\", coherence_amplitude = 0.5 }} }}\nspeed = \"20 m/s\"\ndrives = [0]\ntracks = [\"middle\"]\n"
            ),
            &["input[1].tracks[0]", "middle", "\"left\" or \"right\""],
        ),
        // coherence outside [0, 1]
        (
            format!(
                "{model}{force}[[input]]\nroad = {{ spectrum = {ROAD}, track_width = \"1.5 m\", coherence = {{ kind = \"tabulated\", n = [0, 1], squared_coherence = [1, 1.2] }} }}\nspeed = \"20 m/s\"\ndrives = [0]\ntracks = [\"left\"]\n"
            ),
            &["input[1].road.coherence.squared_coherence", "1.2", "[0, 1]"],
        ),
        // a temporal spectrum as a road
        (
            format!(
                "{model}{force}[[input]]\nroad = {{ spectrum = \"type1\", track_width = \"1.5 m\", coherence = {{ kind = \"dodds-robson\" }} }}\nspeed = \"20 m/s\"\ndrives = [0]\ntracks = [\"left\"]\n"
            ),
            &["input[1].road.spectrum", "type1", "spatial"],
        ),
        // two different speeds
        (
            format!("{model}{road}[[input]]\nspectrum = {FORCE}\ndrives = [1]\nspeed = \"10 m/s\"\n"),
            &["input[1].speed", "one speed"],
        ),
        // several tables without drives
        (
            format!("{model}[[input]]\nspectrum = {ROAD}\nspeed = \"20 m/s\"\n{force}"),
            &["input[0].drives", "<missing>", "several [[input]] tables"],
        ),
        // positions per driven input
        (
            format!("{model}{force}[[input]]\nspectrum = {ROAD}\nspeed = \"20 m/s\"\ndrives = [0]\npositions = [\"1 m\", \"2 m\"]\n"),
            &["input[1].positions", "one per driven input"],
        ),
    ];
    for (text, parts) in cases {
        let e = parse_err(&text);
        for p in parts {
            assert!(e.contains(p), "`{p}` not in: {e}");
        }
    }
    // a catalogue vehicle on two tracks under the single [input] table
    let single = std::fs::read_to_string(root().join("data/full-vehicle-two-tracks.toml"))
        .unwrap()
        .split("[[input]]")
        .next()
        .unwrap()
        .to_string()
        + "[input]\nspectrum = \"iso8608-c\"\nspeed = \"20 m/s\"\n";
    let e = parse_err(&single);
    assert!(
        e.contains("input.spectrum") && e.contains("two tracks") && e.contains("[[input]]"),
        "{e}"
    );
}

#[test]
fn raw_records_of_a_two_track_road_hold_the_tracks_themselves() {
    // The spectral route synthesises the right track as R = ρ L + √(1 − ρ²) W per frequency bin. The raw
    // record must hold L and R (not the generator W): with ρ = 1 (constant coherence amplitude 1) the
    // mixing row of R is (1, 0) exactly, so the recorded right track equals the left one up to the rounding
    // of one inverse FFT; with ρ = 0 it is the independent generator W, whose sample correlation with L
    // over 4 × 2048 samples is small (|r| ≤ 0.1 — the road's correlation length is ~1/α = 5 m = 0.33 s at
    // 15 m/s, i.e. ~33 samples, so ~250 effective samples per record: 0.1 is > 6 standard deviations of r,
    // false failure < 1e-9 for a Gaussian r, seed fixed).
    use stochvib::simulate::RunOptions;
    use stochvib::store::{RunFile, SignalGroup};
    let dir = std::env::temp_dir().join(format!("stochvib-raw-tracks-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    for rho in [1.0, 0.0] {
        let road = format!(
            r#"[[input]]
name = "road"
road = {{ spectrum = {ROAD}, track_width = "1.5 m", coherence = {{ kind = "constant", coherence_amplitude = {rho} }} }}
speed = "15 m/s"
"#
        );
        let sc = parse(&two_wheels(r#"tracks = ["left", "right"]"#, "[1, 1]", &road));
        let names: Vec<String> = sc.input_signals().iter().map(|s| s.name.clone()).collect();
        assert_eq!(names, ["road_left", "road_right"]);
        let mut opts = RunOptions::new(4, 20.48, 0.01, 17);
        opts.store_raw = true;
        let out = dir.join(format!("rho{rho}.h5"));
        let _ = std::fs::remove_file(&out);
        sc.simulate(&opts, &out, &|_, _| {}).unwrap();
        let f = RunFile::open(&out).unwrap();
        let l = f.read_signals(SignalGroup::Inputs, "road_left", 0..4).unwrap();
        let r = f.read_signals(SignalGroup::Inputs, "road_right", 0..4).unwrap();
        let scale = l.iter().fold(0.0f64, |a, x| a.max(x.abs()));
        let diff = l.iter().zip(r.iter()).fold(0.0f64, |a, (x, y)| a.max((x - y).abs()));
        if rho == 1.0 {
            assert!(diff <= EXACT * scale, "ρ = 1: max|R − L| = {diff:e} of {scale:e}");
        } else {
            let (sl, sr, slr) = l
                .iter()
                .zip(r.iter())
                .fold((0.0, 0.0, 0.0), |(a, b, c), (x, y)| (a + x * x, b + y * y, c + x * y));
            let corr: f64 = slr / (sl * sr).sqrt();
            assert!(corr.abs() <= 0.1, "ρ = 0: sample correlation {corr}");
            assert!(diff > 0.1 * scale);
        }
    }
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn the_input_coherence_chart_draws_the_squared_coherence_of_each_road() {
    // Constant coherence amplitude ρ = 0.5: γ² = ρ² = 0.25 at every n (closed form); a scenario without a
    // road of two tracks has no such chart.
    use stochvib::plot::scenario_plots::{input_coherence_chart, ScenarioPlotOptions};
    let road = format!(
        r#"[[input]]
name = "road"
road = {{ spectrum = {ROAD}, track_width = "1.5 m", coherence = {{ kind = "constant", coherence_amplitude = 0.5 }} }}
speed = "15 m/s"
"#
    );
    let sc = parse(&two_wheels(r#"tracks = ["left", "right"]"#, "[1, 1]", &road));
    let chart = input_coherence_chart(&sc, &ScenarioPlotOptions::default())
        .unwrap()
        .unwrap();
    assert_eq!(chart.series.len(), 1);
    assert_eq!(chart.series[0].name, "road: left and right");
    let pts = &chart.series[0].points;
    assert!((pts[0].0 - 1e-3).abs() <= ROUNDING && (pts[pts.len() - 1].0 - 10.0).abs() <= 1e-12);
    assert!(pts.iter().all(|p| (p.1 - 0.25).abs() <= ROUNDING), "{pts:?}");
    let single = parse(&two_wheels(
        "",
        "[1, 1]",
        &format!("[input]\nspectrum = {ROAD}\nspeed = \"15 m/s\"\n"),
    ));
    assert!(input_coherence_chart(&single, &ScenarioPlotOptions::default())
        .unwrap()
        .is_none());
}

/// A road of two tracks under the full vehicle: `track_width` is the distance between the wheel tracks,
/// which the vehicle fixes (its own `track_width`). A different value would give the coherence of tracks
/// that are not the ones the wheels run on: refused, naming the file, the key, the value and the model's
/// width. Left out, the model's width is used (the same analysis as writing it).
#[test]
fn a_road_track_width_other_than_the_vehicles_is_refused() {
    let text = std::fs::read_to_string(root().join("data/full-vehicle-two-tracks.toml")).unwrap();
    assert!(
        text.contains("track_width = \"1.5 m\", coherence"),
        "the file's road names its width"
    );
    // 1.6 m instead of the vehicle's 1.5 m
    let wrong = text.replace(
        "track_width = \"1.5 m\", coherence",
        "track_width = \"1.6 m\", coherence",
    );
    let err = parse_err(&wrong);
    for part in [
        "test-multi.toml",
        "input[0].road.track_width",
        "1.6 m",
        "1.5 m",
        "model.track_width",
    ] {
        assert!(err.contains(part), "missing `{part}` in: {err}");
    }
    // the same width in other units is the same width
    let same = text.replace(
        "track_width = \"1.5 m\", coherence",
        "track_width = \"150 cm\", coherence",
    );
    parse(&same);
    // left out: the vehicle's width, giving the same excitation as the file itself
    let omitted = text.replace("track_width = \"1.5 m\", coherence", "coherence");
    let (a, b) = (parse(&omitted), parse(&text));
    let sys = b.model.system.as_ref();
    let i = sys.outputs().iter().position(|o| o.name == "roll").unwrap();
    let va = analyze_output(sys, &a.excitation, i).unwrap().variance.unwrap();
    let vb = analyze_output(sys, &b.excitation, i).unwrap().variance.unwrap();
    assert_eq!(va.to_bits(), vb.to_bits(), "omitted width {va} vs written width {vb}");
    // a generic model has no width of its own: the key stays required
    let road = format!(
        "[[input]]\nroad = {{ spectrum = {ROAD}, coherence = {{ kind = \"constant\", coherence_amplitude = 0.5 }} }}\nspeed = \"15 m/s\"\n"
    );
    let err = parse_err(&two_wheels(r#"tracks = ["left", "right"]"#, "[1, 1]", &road));
    assert!(err.contains("track_width") && err.contains("required"), "{err}");
}
