//! Scenario files with several inputs (`[[input]]` tables): a road and a force on one generic model, a
//! generic machine whose wheels name their tracks, the full vehicle of the catalogue, the errors of the
//! format, and the natural frequencies of the seven-degree-of-freedom vehicle in a decoupled case.

use crate::common;
use common::tolerance::{EXACT, QUADRATURE, ROUNDING};
use std::f64::consts::PI;
use std::path::PathBuf;
use std::sync::Arc;
use stochvib::coherence::{IsotropicCoherence, TwoTracks};
use stochvib::models::full_vehicle::FullVehicle;
use stochvib::response::{analyze_output, Excitation};
use stochvib::scenario::{load_scenario, parse_scenario, Scenario};
use stochvib::spectrum::{IsoClass, PowerLaw};

fn root() -> PathBuf {
    crate::common::root()
}

/// `data/full-vehicle-two-tracks.toml` with the repository's spectrum catalogue.
fn full_vehicle_file() -> Scenario {
    load_scenario(
        &root().join("data/full-vehicle-two-tracks.toml"),
        &root().join("spectra"),
    )
    .unwrap()
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
    let both = common::quarter_car_scenario()
        .force()
        .then(&format!(
            r#"
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
        ))
        .text();
    let road_only = common::quarter_car_scenario()
        .then(&format!("\n[input]\nspectrum = {ROAD}\nspeed = \"20 m/s\"\n"))
        .text();
    let force_only = common::quarter_car_scenario()
        .force()
        .tyre_on_ground()
        .then(&format!("\n[input]\nspectrum = {FORCE}\n"))
        .text();
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
    let sc = parse(&common::two_wheels(r#"tracks = ["left", "right"]"#, "[1, 1]", &road));
    let single = |gains: &str| {
        parse(&common::two_wheels(
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
    let in_table = parse(&common::two_wheels(
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
    let sc = full_vehicle_file();
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
    let model = common::quarter_car_scenario().force().text();
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
    let dir = crate::common::scratch_path("multi-input", "raw-tracks");
    std::fs::create_dir_all(&dir).unwrap();
    for rho in [1.0, 0.0] {
        let road = format!(
            r#"[[input]]
name = "road"
road = {{ spectrum = {ROAD}, track_width = "1.5 m", coherence = {{ kind = "constant", coherence_amplitude = {rho} }} }}
speed = "15 m/s"
"#
        );
        let sc = parse(&common::two_wheels(r#"tracks = ["left", "right"]"#, "[1, 1]", &road));
        let names: Vec<String> = sc.input_signals().iter().map(|s| s.name.clone()).collect();
        assert_eq!(names, ["road_left", "road_right"]);
        let mut opts = RunOptions {
            realizations: 4,
            duration_s: 20.48,
            dt_s: 0.01,
            seed: 17,
            ..RunOptions::default()
        };
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

/// The `[[input]]` table of a road of two tracks (the exponential road `ROAD`, 1.5 m apart, at 15 m/s)
/// with a constant coherence amplitude ρ = 0.5.
fn constant_coherence_road() -> String {
    format!(
        r#"[[input]]
name = "road"
road = {{ spectrum = {ROAD}, track_width = "1.5 m", coherence = {{ kind = "constant", coherence_amplitude = 0.5 }} }}
speed = "15 m/s"
"#
    )
}

#[test]
fn the_input_coherence_chart_draws_the_squared_coherence_of_each_road() {
    // Constant coherence amplitude ρ = 0.5: γ² = ρ² = 0.25 at every n (closed form); a scenario without a
    // road of two tracks has no such chart.
    use stochvib::plot::scenario_plots::{input_coherence_chart, ScenarioPlotOptions};
    let sc = parse(&common::two_wheels(
        r#"tracks = ["left", "right"]"#,
        "[1, 1]",
        &constant_coherence_road(),
    ));
    let chart = input_coherence_chart(&sc, &ScenarioPlotOptions::default())
        .unwrap()
        .unwrap();
    assert_eq!(chart.series.len(), 1);
    assert_eq!(chart.series[0].name, "road: left and right");
    let pts = &chart.series[0].points;
    assert!((pts[0].0 - 1e-3).abs() <= ROUNDING && (pts[pts.len() - 1].0 - 10.0).abs() <= 1e-12);
    assert!(pts.iter().all(|p| (p.1 - 0.25).abs() <= ROUNDING), "{pts:?}");
    let single = parse(&common::two_wheels(
        "",
        "[1, 1]",
        &format!("[input]\nspectrum = {ROAD}\nspeed = \"15 m/s\"\n"),
    ));
    assert!(input_coherence_chart(&single, &ScenarioPlotOptions::default())
        .unwrap()
        .is_none());
}

/// A body on two wheels driven by two independent one-process roads (spatial, in m) `left`, `right`, with
/// `extra_left` added to the left table.
fn two_process_roads(extra_left: &str) -> String {
    let road2 = r#"{ kind = "exponential", domain = "spatial", variance = "4 cm^2", alpha = "0.5 1/m" }"#;
    common::two_wheels(
        "",
        "[1, 1]",
        &format!(
            r#"[[input]]
name = "left"
spectrum = {ROAD}
speed = "15 m/s"
drives = [0]
{extra_left}
[[input]]
name = "right"
spectrum = {road2}
drives = [1]
"#
        ),
    )
}

#[test]
fn the_input_pictures_draw_every_source_and_the_cross_spectrum_of_a_road() {
    use stochvib::plot::scenario_plots::{
        input_cross_spectrum_charts, input_density_chart, scenario_plots, ScenarioPlotOptions,
    };
    let opts = ScenarioPlotOptions::default();
    // Road of two tracks with a constant coherence amplitude ρ = 0.5 (closed forms): each track has the
    // exponential road's one-sided density G(n) = 4π S(2πn) = 4αD/(α² + 4π²n²) (S(Ω) = αD/(π(α² + Ω²)),
    // D = 1e-4 m², α = 0.2 1/m); the cross-spectrum is G_LR = ρ G (co-spectrum ρG, quad-spectrum 0: the
    // tracks are in phase) and γ² = ρ² = 0.25.
    let sc = parse(&common::two_wheels(
        r#"tracks = ["left", "right"]"#,
        "[1, 1]",
        &constant_coherence_road(),
    ));
    let charts = input_cross_spectrum_charts(&sc, &opts).unwrap();
    assert_eq!(charts.len(), 1);
    let (name, c) = &charts[0];
    assert_eq!(name, "road");
    assert_eq!(c.x_label, "spatial frequency n [cycles/m]");
    assert!(c.y_label.contains("(cross-)density"), "{}", c.y_label);
    assert_eq!(
        c.series.len(),
        2,
        "a real coherence draws no quad-spectrum on the log axis"
    );
    assert!(
        c.series[1].name.contains("quad-spectrum Q ≡ 0 (real coherence)"),
        "{}",
        c.series[1].name
    );
    let (alpha, d) = (0.2, 1e-4);
    let g = |n: f64| 4.0 * alpha * d / (alpha * alpha + 4.0 * PI * PI * n * n);
    for (auto, co) in c.series[0].points.iter().zip(&c.series[1].points) {
        assert_eq!(auto.0, co.0);
        assert!((auto.1 - g(auto.0)).abs() <= EXACT * g(auto.0), "G at n = {}", auto.0);
        assert!((co.1 - 0.5 * g(co.0)).abs() <= EXACT * g(co.0), "C at n = {}", co.0);
    }
    let coh = &c.secondary.as_ref().unwrap().series[0].points;
    assert_eq!(coh.len(), c.series[0].points.len());
    assert!(coh.iter().all(|p| (p.1 - 0.25).abs() <= ROUNDING), "{coh:?}");
    let dir = crate::common::scratch_path("multi-input", "input-pictures");
    let _ = std::fs::remove_dir_all(&dir);
    let files = scenario_plots(&sc, &dir).unwrap();
    for stem in ["input-density", "input-coherence", "input-cross-spectrum-road"] {
        for ext in ["svg", "png"] {
            assert!(
                files.contains(&dir.join(format!("{stem}.{ext}"))),
                "{stem}.{ext} missing"
            );
        }
    }
    let svg = std::fs::read_to_string(dir.join("input-cross-spectrum-road.svg")).unwrap();
    for text in [
        "Cross-spectrum of road",
        "co-spectrum C = Re G_left,right",
        "squared coherence γ²",
    ] {
        assert!(svg.contains(text), "missing `{text}`");
    }

    // Two independent one-process roads: both densities on one chart, each its own spectrum (4αD/(α² + 4π²n²)
    // with α = 0.2 1/m, D = 1 cm² and α = 0.5 1/m, D = 4 cm²); no cross-spectrum (independent sources)
    let sc = parse(&two_process_roads(""));
    let c = input_density_chart(&sc, &opts).unwrap();
    assert_eq!(c.series.len(), 2);
    assert!(c.series[0].name.starts_with("left: ") && c.series[1].name.starts_with("right: "));
    for (s, (alpha, d)) in c.series.iter().zip([(0.2, 1e-4), (0.5, 4e-4)]) {
        for p in &s.points {
            let want = 4.0 * alpha * d / (alpha * alpha + 4.0 * PI * PI * p.0 * p.0);
            assert!((p.1 - want).abs() <= EXACT * want, "{} at n = {}", s.name, p.0);
        }
    }
    assert!(input_cross_spectrum_charts(&sc, &opts).unwrap().is_empty());
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn kurtosis_of_an_input_table_makes_its_source_alone_non_gaussian() {
    use stochvib::simulate::{Route, RunOptions};
    // parse: the table's kurtosis, one entry per generator (the left road's; the right road Gaussian)
    let sc = parse(&two_process_roads("kurtosis = 6"));
    assert_eq!(sc.inputs[0].kurtosis, Some(6.0));
    assert_eq!(sc.inputs[1].kurtosis, None);
    let input = sc.run_input();
    assert_eq!(input.kurtosis, vec![Some(6.0), None]);
    let prov = input.provenance.iter().find(|p| p.name == "input_kurtosis").unwrap();
    assert!(format!("{prov:?}").contains("input[0] `left`: 6"), "{prov:?}");
    assert!(parse(&two_process_roads("")).run_input().kurtosis.is_empty());
    // The cumulants of independent sources add (Laplace moving average, Bogsjö, Podgórski & Rychlik 2012):
    // with y = y_L + y_R, y_R Gaussian, κ₄(y) = κ₄(y_L) and Var y = v_L + v_R on the same grid, so
    //     κ_y − 3 = (κ_{y_L} − 3)·v_L²/(v_L + v_R)².
    // The oracle is the pair of one-road runs (the right road's gain set to 0, and the left road's), each
    // planned alone: other excitations than the two-source run under test.
    let dir = crate::common::scratch_path("multi-input", "kurtosis-sources");
    std::fs::create_dir_all(&dir).unwrap();
    let mut opts = RunOptions {
        realizations: 2,
        duration_s: 10.24,
        dt_s: 0.01,
        seed: 3,
        ..RunOptions::default()
    };
    opts.route = Route::Spectral;
    opts.overwrite = true;
    let run = |text: &str, tag: &str| {
        let sc = parse(text);
        sc.simulate(&opts, &dir.join(format!("{tag}.h5")), &|_, _| {}).unwrap()
    };
    let kurtosis_of = |s: &stochvib::simulate::RunSummary, name: &str| -> f64 {
        let tag = format!("kurtosis of `{name}` (simulated process) = ");
        let note = s.notes.iter().find(|n| n.contains(&tag)).expect("kurtosis note");
        let rest = &note[note.find(&tag).unwrap() + tag.len()..];
        rest.split_whitespace().next().unwrap().parse().unwrap()
    };
    let var_of = |s: &stochvib::simulate::RunSummary, name: &str| {
        let o = s.outputs.iter().find(|o| o.output == name).unwrap();
        o.get("sigma_discrete").unwrap().analytic.unwrap().powi(2)
    };
    let both = run(&two_process_roads("kurtosis = 6"), "both");
    assert!(
        both.generator.contains("[6, 3 (Gaussian)] per input process"),
        "{}",
        both.generator
    );
    let left = run(
        &two_process_roads("kurtosis = 6").replace("gains = [1, 1]", "gains = [1, 0]"),
        "left",
    );
    let right = run(
        &two_process_roads("").replace("gains = [1, 1]", "gains = [0, 1]"),
        "right",
    );
    for name in ["bounce", "roll"] {
        let (vl, vr, v) = (var_of(&left, name), var_of(&right, name), var_of(&both, name));
        assert!((v - (vl + vr)).abs() <= EXACT * v, "{name}: {v:e} vs {vl:e} + {vr:e}");
        let want = 3.0 + (kurtosis_of(&left, name) - 3.0) * vl * vl / (v * v);
        let got = kurtosis_of(&both, name);
        // both printed to 6 decimals
        assert!(
            (got - want).abs() <= common::tolerance::PRINTED_6_DIGITS,
            "{name}: {got} vs {want}"
        );
        assert!(got > 3.0 && got < kurtosis_of(&left, name));
    }
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn kurtosis_of_a_road_of_two_tracks_is_refused_with_the_reason() {
    let road = format!(
        r#"[[input]]
name = "road"
road = {{ spectrum = {ROAD}, track_width = "1.5 m", coherence = {{ kind = "dodds-robson" }} }}
speed = "15 m/s"
kurtosis = 6
"#
    );
    let e = parse_err(&common::two_wheels(r#"tracks = ["left", "right"]"#, "[1, 1]", &road));
    for part in [
        "test-multi.toml",
        "input[0].kurtosis",
        "6",
        "road of two tracks",
        "coherence",
    ] {
        assert!(e.contains(part), "`{part}` missing from: {e}");
    }
    // a bad value in a one-process table: named like `[input] kurtosis`
    for (value, reason) in [("2.5", ">= 3"), ("\"six\"", "expected a number")] {
        let e = parse_err(&two_process_roads(&format!("kurtosis = {value}")));
        for part in ["test-multi.toml", "input[0].kurtosis", reason] {
            assert!(e.contains(part), "{value}: `{part}` missing from: {e}");
        }
    }
}

#[test]
fn a_two_track_run_says_what_its_inputs_are() {
    // The full vehicle on a road of two tracks with a coherence (wheelbase 2.7 m at 20 m/s: delay 0.135 s,
    // 27 steps of 5 ms): the route's reason and the variance methods name the two tracks, never "delayed
    // copies of one process" (the one-track reason).
    use stochvib::simulate::RunOptions;
    let sc = full_vehicle_file();
    let dir = crate::common::scratch_path("multi-input", "two-track-notes");
    std::fs::create_dir_all(&dir).unwrap();
    let mut opts = RunOptions {
        realizations: 2,
        duration_s: 2.56,
        dt_s: 0.005,
        seed: 1,
        ..RunOptions::default()
    };
    opts.overwrite = true;
    let s = sc.simulate(&opts, &dir.join("run.h5"), &|_, _| {}).unwrap();
    assert!(
        s.notes.iter().all(|n| !n.contains("delayed copies of one process")),
        "{:?}",
        s.notes
    );
    assert!(
        s.notes[0].contains("delayed tracks of a road of two tracks with a coherence"),
        "{}",
        s.notes[0]
    );
    let sys = sc.model.system.as_ref();
    let st = analyze_output(sys, &sc.excitation, 1).unwrap();
    let text = format!("{:?}", st.methods);
    assert!(!text.contains("delayed copies of one process"), "{text}");
    assert!(text.contains("road of two tracks"), "{text}");
    let _ = std::fs::remove_dir_all(&dir);
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
    let err = parse_err(&common::two_wheels(r#"tracks = ["left", "right"]"#, "[1, 1]", &road));
    assert!(err.contains("track_width") && err.contains("required"), "{err}");
}

/// `[road]`: the data file's `[[input]]` road written as its own section is the same scenario — every
/// output's analytic variance bit for bit (the section is rewritten into the one table it stands for) — and
/// its errors name `road.<key>` as written: a wrong track width, a bad speed, an unknown key, a kurtosis
/// (refused for a road of two tracks), and `[road]` beside `[[input]]`.
#[test]
fn a_road_section_is_the_one_input_table_it_stands_for() {
    let text = std::fs::read_to_string(root().join("data/full-vehicle-two-tracks.toml")).unwrap();
    let table = "[[input]]\nname = \"road\"\nroad = { spectrum = \"iso8608-c\", track_width = \"1.5 m\", coherence = { kind = \"dodds-robson\", waviness = 2 } }\nspeed = \"20 m/s\"\n";
    assert!(
        text.contains(table),
        "the data file's road table as this test expects it"
    );
    let section = "[road]\nspectrum = \"iso8608-c\"\ncoherence = { kind = \"dodds-robson\", waviness = 2 }\ntrack_width = \"1.5 m\"\nspeed = \"20 m/s\"\n";
    let (a, b) = (parse(&text), parse(&text.replace(table, section)));
    assert_eq!(b.inputs.len(), 1);
    assert_eq!(b.inputs[0].name, "road");
    let sys = a.model.system.as_ref();
    for (i, o) in sys.outputs().iter().enumerate() {
        let va = analyze_output(sys, &a.excitation, i).unwrap().variance;
        let vb = analyze_output(b.model.system.as_ref(), &b.excitation, i)
            .unwrap()
            .variance;
        assert_eq!(
            va.map(f64::to_bits),
            vb.map(f64::to_bits),
            "{}: {va:?} vs {vb:?}",
            o.name
        );
    }
    let check = |edit: &dyn Fn(&str) -> String, parts: &[&str]| {
        let err = parse_err(&text.replace(table, &edit(section)));
        for part in parts {
            assert!(err.contains(part), "missing `{part}` in: {err}");
        }
        assert!(!err.contains("input[0]"), "named as the [[input]] table: {err}");
    };
    check(
        &|s| s.replace("\"1.5 m\"", "\"1.6 m\""),
        &["test-multi.toml", "road.track_width", "1.6 m", "1.5 m"],
    );
    check(&|s| s.replace("\"20 m/s\"", "\"-3 m/s\""), &["road.speed", "-3", "> 0"]);
    check(&|s| format!("{s}coherense = 1\n"), &["road.coherense", "unknown key"]);
    check(&|s| format!("{s}kurtosis = 6\n"), &["road.kurtosis", "6"]);
    check(
        &|s| format!("{s}[[input]]\nspectrum = {FORCE}\n"),
        &["road", "[road]", "[[input]]"],
    );
}
