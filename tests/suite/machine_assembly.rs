//! `kind = "machine"`: a body on axles, a cab on mounts and a seat, against models built independently
//! (the `full-vehicle` model), closed forms (rigid-body frequencies, static deflections), symmetry (no roll on
//! identical tracks) and the stated kinematics of lateral and longitudinal motion.

use crate::common;
use common::tolerance::{CONDITIONED, EXACT, ROUNDING};
use common::{rel, root};
use nalgebra::Complex;
use stochvib::response::analyze_output;
use stochvib::scenario::{parse_scenario, Scenario};
use stochvib::study::verdict_analysis;

const G: f64 = 9.80665;

fn scenario(text: &str) -> Scenario {
    let path = root().join("data").join("machine-test.toml");
    parse_scenario(text, &path, &root().join("spectra")).unwrap_or_else(|e| panic!("{e}"))
}

fn road(coherence: &str, width: &str) -> String {
    format!(
        r#"
[[input]]
name = "road"
road = {{ spectrum = "iso8608-c", track_width = "{width}", coherence = {coherence} }}
speed = "20 m/s"
"#
    )
}

fn index(sc: &Scenario, name: &str) -> usize {
    sc.model.system.outputs().iter().position(|o| o.name == name).unwrap()
}

/// The row of H(iω) of output `name`.
fn row(sc: &Scenario, name: &str, w: f64) -> Vec<Complex<f64>> {
    let h = sc.model.system.response(w);
    let i = index(sc, name);
    (0..h.ncols()).map(|j| h[(i, j)]).collect()
}

/// With suspended wheels and no cab the assembly is the 7-DOF full vehicle (`src/models/full_vehicle.rs`,
/// built independently): the same frequency response of every shared output to the same four wheels at
/// every frequency, and the same variances on the same coherent road.
#[test]
fn machine_without_cab_is_the_full_vehicle() {
    let text = std::fs::read_to_string(root().join("data/full-vehicle-two-tracks.toml")).unwrap();
    let car = scenario(&text);
    let coherence = r#"{ kind = "dodds-robson", waviness = 2 }"#;
    let machine = scenario(&(common::CAR_AS_MACHINE.to_string() + &road(coherence, "1.5 m")));
    let pairs = [
        ("bounce", "bounce"),
        ("pitch", "pitch"),
        ("roll", "roll"),
        ("seat_acc", "seat_acc"),
        ("travel_fl", "travel_front_left"),
        ("tyre_force_rr", "tyre_force_rear_right"),
    ];
    for w in [0.5, 3.0, 8.0, 25.0, 70.0] {
        for (a, b) in pairs {
            for (x, y) in row(&car, a, w).iter().zip(row(&machine, b, w)) {
                assert!(
                    (x - y).norm() <= CONDITIONED * x.norm().max(1e-300),
                    "{a} at {w}: {x} vs {y}"
                );
            }
        }
    }
    for (a, b) in pairs {
        let va = analyze_output(car.model.system.as_ref(), &car.excitation, index(&car, a)).unwrap();
        let vb = analyze_output(machine.model.system.as_ref(), &machine.excitation, index(&machine, b)).unwrap();
        assert!(rel(va.variance.unwrap(), vb.variance.unwrap()) < CONDITIONED, "{a}");
        // a coherence that depends on n (Dodds–Robson) has no factorisation with constant coefficients
        let exact = vb
            .methods
            .iter()
            .find(|m| m.method.name() == "lyapunov (delays)")
            .unwrap();
        assert!(
            format!("{:?}", exact.outcome).contains("a coherence function of n"),
            "{b}: {:?}",
            exact.outcome
        );
    }
}

/// A symmetric machine (body, cab and seat on the centre line, axles at ±1.5 m, a = 1.5 m, tyres k = 800
/// kN/m and 2 kN s/m, four mounts at (±0.5, ±0.6) m around the cab's centre of gravity), with a cab and a
/// seat.
fn symmetric(rear: &str) -> String {
    format!(
        r#"title = "symmetric machine"
[model]
kind = "machine"
body = {{ mass = "12000 kg", pitch_inertia = "24000 kg*m^2", roll_inertia = "7000 kg*m^2", height = "1.2 m" }}
[[model.axle]]
name = "front"
position = "1.5 m"
track_width = "2.0 m"
tyre_stiffness = "800 kN/m"
tyre_damping = "2 kN*s/m"
[[model.axle]]
name = "rear"
position = "-1.5 m"
track_width = "2.0 m"
tyre_stiffness = "800 kN/m"
tyre_damping = "2 kN*s/m"
{rear}
[model.cab]
mass = "1000 kg"
pitch_inertia = "800 kg*m^2"
roll_inertia = "700 kg*m^2"
position = ["0 m", "0 m", "2.4 m"]
mount_height = "1.7 m"
mount = [
  {{ position = ["0.5 m", "0.6 m"], stiffness = "200 kN/m", damping = "2 kN*s/m" }},
  {{ position = ["0.5 m", "-0.6 m"], stiffness = "200 kN/m", damping = "2 kN*s/m" }},
  {{ position = ["-0.5 m", "0.6 m"], stiffness = "200 kN/m", damping = "2 kN*s/m" }},
  {{ position = ["-0.5 m", "-0.6 m"], stiffness = "200 kN/m", damping = "2 kN*s/m" }},
]
[model.seat]
position = ["0 m", "0 m", "2.2 m"]
operator_mass = "70 kg"
seat_mass = "25 kg"
stiffness = "7000 N/m"
damping = "450 N*s/m"
[[model.output]]
name = "seat_y"
part = "seat"
direction = "y"
[[model.output]]
name = "seat_x"
part = "seat"
direction = "x"
[[model.output]]
name = "body_y"
part = "body"
point = ["1 m", "0.4 m", "3.1 m"]
direction = "y"
[[model.output]]
name = "roll_acc"
part = "body"
direction = "roll"
[[model.output]]
name = "pitch_acc"
part = "body"
direction = "pitch"
[[model.output]]
name = "cab_roll_acc"
part = "cab"
direction = "roll"
[[model.output]]
name = "cab_pitch_acc"
part = "cab"
direction = "pitch"
[analysis]
outputs = ["roll", "pitch", "seat_acc", "seat_y"]
"#
    )
}

/// On two identical tracks (coherence 1) the symmetric machine neither rolls nor moves sideways at the seat:
/// its left and right wheels see the same road. On partly coherent tracks it does (the check can fail).
#[test]
fn symmetric_machine_on_identical_tracks_does_not_roll() {
    let same = scenario(&(symmetric("") + &road(r#"{ kind = "constant", coherence_amplitude = 1.0 }"#, "2.0 m")));
    let var = |sc: &Scenario, name: &str| {
        analyze_output(sc.model.system.as_ref(), &sc.excitation, index(sc, name))
            .unwrap()
            .variance
            .unwrap_or(0.0)
    };
    let pitch = var(&same, "pitch");
    for name in ["roll", "cab_roll", "seat_y"] {
        let v = var(&same, name);
        let scale = if name == "seat_y" { var(&same, "seat_x") } else { pitch };
        assert!(v.abs() <= ROUNDING * scale, "{name}: {v:e} against {scale:e}");
    }
    let partly = scenario(&(symmetric("") + &road(r#"{ kind = "dodds-robson", waviness = 2 }"#, "2.0 m")));
    assert!(var(&partly, "roll") > 1e-3 * var(&partly, "pitch"));
}

/// The lateral and longitudinal motion at height h is the stated kinematics of small angles: on the body
/// −(h − h_b)·φ̈ (and −(h − h_b)·θ̈), at the seat −(h_m − h_b)·φ̈ − (h_s − h_m)·φ̈_c, with h_b = 1.2 m,
/// h_m = 1.7 m, h_s = 2.2 m: compared output by output at several frequencies.
#[test]
fn horizontal_acceleration_at_height_is_lever_times_angular_acceleration() {
    let sc = scenario(&(symmetric("") + &road(r#"{ kind = "dodds-robson", waviness = 2 }"#, "2.0 m")));
    for w in [1.0, 6.0, 20.0] {
        let (roll, croll) = (row(&sc, "roll_acc", w), row(&sc, "cab_roll_acc", w));
        let (pitch, cpitch) = (row(&sc, "pitch_acc", w), row(&sc, "cab_pitch_acc", w));
        // (expected, the size of its terms: the scale of the rounding)
        let lever = |a: &[Complex<f64>], b: &[Complex<f64>], la: f64, lb: f64| -> Vec<(Complex<f64>, f64)> {
            a.iter()
                .zip(b)
                .map(|(x, y)| (-la * x - lb * y, (la * x).norm() + (lb * y).norm()))
                .collect()
        };
        let checks = [
            ("body_y", lever(&roll, &croll, 3.1 - 1.2, 0.0)),
            ("seat_y", lever(&roll, &croll, 1.7 - 1.2, 2.2 - 1.7)),
            ("seat_x", lever(&pitch, &cpitch, 1.7 - 1.2, 2.2 - 1.7)),
        ];
        for (name, expected) in checks {
            for (x, (y, scale)) in row(&sc, name, w).iter().zip(&expected) {
                assert!((x - y).norm() <= EXACT * scale, "{name} at {w}: {x} vs {y}");
            }
        }
    }
}

/// Natural frequencies of the rigid body on its tyres against closed forms, the cab and seat removed: bounce
/// 4k/m, pitch 4k a²/J_y, roll 4k (w/2)²/J_x; with an oscillating rear axle (free pin) the body's roll is held
/// by the front axle alone, 2k (w/2)²/J_x, and the axle rolls at 2k (w/2)²/J_a.
#[test]
fn rigid_body_frequencies_against_closed_forms() {
    let (k, m, jy, jx, a, h): (f64, f64, f64, f64, f64, f64) = (800e3, 12000.0, 24000.0, 7000.0, 1.5, 1.0);
    let without_cab = |rear: &str| {
        let text = symmetric(rear);
        let cut = text.find("[model.cab]").unwrap();
        let end = text.find("[analysis]").unwrap();
        format!(
            "{}{}",
            &text[..cut],
            &text[end..].replace("\"seat_acc\", \"seat_y\"", "\"bounce\"")
        ) + &road(r#"{ kind = "dodds-robson", waviness = 2 }"#, "2.0 m")
    };
    let freqs = |text: &str| {
        let mut f = scenario(text).model.system.as_mdof().unwrap().modes().unwrap().0;
        f.sort_by(f64::total_cmp);
        f
    };
    let mut expected = vec![
        (4.0 * k / m).sqrt(),
        (4.0 * k * a * a / jy).sqrt(),
        (4.0 * k * h * h / jx).sqrt(),
    ];
    expected.sort_by(f64::total_cmp);
    for (x, y) in freqs(&without_cab("")).iter().zip(&expected) {
        assert!(rel(*x, *y) < CONDITIONED, "{x} vs {y}");
    }
    let ja: f64 = 300.0;
    let osc = format!("oscillating = {{ roll_inertia = \"{ja} kg*m^2\" }}");
    let mut expected = vec![
        (4.0 * k / m).sqrt(),
        (4.0 * k * a * a / jy).sqrt(),
        (2.0 * k * h * h / jx).sqrt(),
        (2.0 * k * h * h / ja).sqrt(),
    ];
    expected.sort_by(f64::total_cmp);
    let got = freqs(&without_cab(&osc));
    assert_eq!(got.len(), 4);
    for (x, y) in got.iter().zip(&expected) {
        assert!(rel(*x, *y) < CONDITIONED, "{x} vs {y}");
    }
}

/// Static deflections of the symmetric machine under gravity: the seat spring carries m_pr g
/// (m_pr = 5/7·70 + 25 = 75 kg), each of the four mounts (m_cab + m_pr) g / 4, each tyre the whole machine's
/// weight over four (every centre of gravity on the axes of symmetry).
#[test]
fn static_deflections_against_the_weights() {
    let sc = scenario(&(symmetric("") + &road(r#"{ kind = "dodds-robson", waviness = 2 }"#, "2.0 m")));
    let d = &sc.model.description;
    let value = |name: &str| -> f64 {
        let at = d.find(&format!("{name} ")).unwrap_or_else(|| panic!("{name} in {d}"));
        d[at + name.len() + 1..]
            .split([',', ' '])
            .next()
            .unwrap()
            .parse()
            .unwrap()
    };
    let m_pr = 5.0 / 7.0 * 70.0 + 25.0;
    let total = 12000.0 + 1000.0 + m_pr;
    // the description prints 4 significant digits
    let four = 5e-4;
    assert!(rel(value("seat"), m_pr * G / 7000.0) < four);
    assert!(rel(value("mount_0"), (1000.0 + m_pr) * G / 4.0 / 200e3) < four);
    assert!(rel(value("tyre_front_left"), total * G / 4.0 / 800e3) < four);
    assert!(rel(value("tyre_rear_right"), total * G / 4.0 / 800e3) < four);
}

/// The catalogue wheel loader: every axis of the seat has a finite a_w, SEAT is reported, the static sag is
/// in the description, and bad keys are named.
#[test]
fn wheel_loader_scenario_and_bad_keys() {
    let path = root().join("data/wheel-loader-cab-seat.toml");
    let text = std::fs::read_to_string(&path).unwrap();
    let sc = scenario(&text);
    let v = verdict_analysis(&sc).unwrap();
    let c = v.comfort.unwrap();
    assert_eq!(c.axes.len(), 3);
    assert!(c.axes.iter().all(|a| a.a_w.is_finite() && a.a_w > 0.0));
    let s = v.seat_factor.unwrap();
    assert!(s.seat_factor > 0.0 && s.seat_factor < 3.0, "{}", s.seat_factor);
    assert!(sc.model.description.contains("static deflection"));
    let spectra = root().join("spectra");
    for (from, to, key) in [
        (
            "track_width = \"2.0 m\"\ntyre_stiffness = \"900 kN/m\"\ntyre_damping = \"4 kN*s/m\"\noscillating",
            "track_width = \"2.2 m\"\ntyre_stiffness = \"900 kN/m\"\ntyre_damping = \"4 kN*s/m\"\noscillating",
            "model.axle[1].track_width",
        ),
        (
            "part = \"seat\"\ndirection = \"x\"",
            "part = \"wing\"\ndirection = \"x\"",
            "model.output[0].part",
        ),
        (
            "damping = \"470 N*s/m\"",
            "damping = \"-470 N*s/m\"",
            "model.seat.damping",
        ),
    ] {
        assert!(text.contains(from), "{from}");
        let e = parse_scenario(&text.replace(from, to), &path, &spectra)
            .unwrap_err()
            .to_string();
        assert!(e.contains(key), "{key}: {e}");
    }
}

/// The analytic σ of a whole machine, exact and by quadrature, against Monte Carlo: the symmetric machine with cab and seat (tyre
/// damping raised to 8 kN s/m per tyre, a bounce damping ratio near 0.1) on the textbook type-1 road
/// (eq. 8.45, rational: D = 2.25 cm², α = 3.5 1/m) at 5 m/s on two tracks of constant coherence 0.5,
/// wheelbase 3 m (delays).
///
/// * analytic, two ways: the exact `lyapunov (delays)` route on the sum and difference processes of the
///   constant coherence (each felt by the four wheels with their delays and gains ±1; the symmetric machine
///   feels the difference process not at all in bounce and the sum process not at all in roll, parts that
///   come out at the rounding level of either sign and are taken as 0) against the Fourier-weighted
///   adaptive quadrature of S_y, whose own error estimate is within `QUADRATURE` of its value: the two
///   agree within `QUADRATURE` (the delay-free `lyapunov` route says it does not apply);
/// * Monte Carlo: 40 realizations of 200 s at Δt = 0.02 s (spectral route, the only one for delayed
///   inputs), seed 20261127. The Student-t interval of σ across realizations (each a time average over
///   200 s, ≫ the slowest mode's correlation time 1/(ζω) ≈ 0.6 s, so near-normal) at confidence
///   1 − `MC_FALSE_FAILURE` covers the exact σ of the simulated grid process (`sigma_discrete`) for each of
///   four outputs: false failure ≤ 4 × 2e-7 < 1e-6 (union bound). That grid process's σ lies within
///   `SPECTRAL_GRID_BIAS` of the analytic one (the road on the record's frequency grid up to Nyquist,
///   157 rad/s, far above the 2.6–3.4 Hz rigid-body modes and the 1.4 Hz seat).
#[test]
fn machine_quadrature_agrees_with_monte_carlo() {
    use common::tolerance::{MC_FALSE_FAILURE, QUADRATURE, SPECTRAL_GRID_BIAS};
    use stochvib::response::{Outcome, VarianceMethod};
    use stochvib::simulate::{run, RunOptions};
    let text = symmetric("")
        .replace("tyre_damping = \"2 kN*s/m\"", "tyre_damping = \"8 kN*s/m\"")
        .replace(
            "outputs = [\"roll\", \"pitch\", \"seat_acc\", \"seat_y\"]",
            "outputs = [\"bounce\", \"roll\", \"cab_pitch\", \"seat_travel\"]",
        )
        + r#"
[[input]]
name = "road"
road = { spectrum = "book-8-45", track_width = "2.0 m", coherence = { kind = "constant", coherence_amplitude = 0.5 } }
speed = "5 m/s"
"#;
    let sc = scenario(&text);
    let names = ["bounce", "roll", "cab_pitch", "seat_travel"];
    let mut exact = Vec::new();
    for name in names {
        let st = analyze_output(sc.model.system.as_ref(), &sc.excitation, index(&sc, name)).unwrap();
        let outcome = |m: VarianceMethod| &st.methods.iter().find(|v| v.method == m).unwrap().outcome;
        let lyapunov = outcome(VarianceMethod::Lyapunov);
        assert!(
            matches!(lyapunov, Outcome::NotApplicable { .. }),
            "{name}: {lyapunov:?}"
        );
        let Outcome::Value { value, error_estimate } = outcome(VarianceMethod::Quadrature) else {
            panic!("{name}: {st:?}")
        };
        assert!(
            error_estimate.unwrap() <= QUADRATURE * value,
            "{name}: {value:e} ± {error_estimate:?}"
        );
        let Outcome::Value { value: delayed, .. } = outcome(VarianceMethod::LyapunovDelays) else {
            panic!("{name}: {:?}", outcome(VarianceMethod::LyapunovDelays))
        };
        assert!(
            rel(*delayed, *value) <= QUADRATURE,
            "{name}: {delayed:e} vs quadrature {value:e}"
        );
        exact.push(delayed.sqrt());
    }
    let mut opts = RunOptions {
        realizations: 40,
        duration_s: 200.0,
        dt_s: 0.02,
        seed: 20261127,
        ..RunOptions::default()
    };
    opts.confidence = 1.0 - MC_FALSE_FAILURE;
    let file = common::scratch_dir("machine-assembly", "mc").join("run.h5");
    let mc = run(&sc.run_input(), &opts, &file, &|_, _| {}).unwrap();
    for (name, sigma) in names.iter().zip(exact) {
        let o = mc.outputs.iter().find(|o| o.output == *name).unwrap();
        let s = o.get("sigma_discrete").unwrap();
        let grid = s.analytic.unwrap();
        assert!(
            s.covers == Some(true),
            "{name}: σ_d = {grid:e} not in [{:e}, {:e}]",
            s.interval.lower,
            s.interval.upper
        );
        assert!(
            rel(grid, sigma) <= SPECTRAL_GRID_BIAS,
            "{name}: grid σ {grid:e} vs analytic {sigma:e}"
        );
    }
}

/// The machine of `machine_quadrature_agrees_with_monte_carlo` (tyre damping 8 kN s/m, the type-1 road at
/// 5 m/s on two tracks of coherence 0.5) with `extra` (nonlinear elements) before its input and the seat
/// damping `seat_damping` N s/m.
fn machine_on_type1_road(extra: &str, seat_damping: f64) -> Scenario {
    let text = symmetric("")
        .replace("tyre_damping = \"2 kN*s/m\"", "tyre_damping = \"8 kN*s/m\"")
        .replace(
            "damping = \"450 N*s/m\"",
            &format!("damping = \"{seat_damping} N*s/m\""),
        )
        .replace(
            "outputs = [\"roll\", \"pitch\", \"seat_acc\", \"seat_y\"]",
            "outputs = [\"bounce\", \"roll\", \"seat_travel\"]",
        );
    let at = text.find("[analysis]").unwrap();
    scenario(&format!(
        "{}{extra}\n{}\n[[input]]\nname = \"road\"\nroad = {{ spectrum = \"book-8-45\", track_width = \"2.0 m\", \
         coherence = {{ kind = \"constant\", coherence_amplitude = 0.5 }} }}\nspeed = \"5 m/s\"\n",
        &text[..at],
        &text[at..]
    ))
}

/// σ of `name` and of its rate (√λ₂) in the linear scenario `sc`.
fn sigma_and_rate(sc: &Scenario, name: &str) -> (f64, f64) {
    let st = analyze_output(sc.model.system.as_ref(), &sc.excitation, index(sc, name)).unwrap();
    (st.sigma.unwrap(), st.lambda2.unwrap().sqrt())
}

/// A friction seat in a whole machine, route 1: Coulomb friction F_c = 120 N across the seat (450 N s/m) has
/// the Gaussian equivalent damping c_eq = E[dF/dv] = F_c √(2/π)/σ_v for a zero-mean Gaussian seat velocity
/// (Caughey 1963; F = F_c sgn v). So route 1's answer is the linear machine with seat damping 450 + c_eq where
/// c_eq solves c_eq = F_c √(2/π)/σ_v(450 + c_eq), σ_v the seat travel's rate √λ₂ of that linear machine.
/// The test solves this scalar equation by bisection on linear scenarios it writes itself (c_eq ↦ c_eq −
/// F_c√(2/π)/σ_v(450 + c_eq) increases: more damping, slower seat), and route 1's σ of every output equals
/// that machine's within `ROUTE1_ITERATION`.
#[test]
fn friction_seat_in_a_machine_route1_is_the_equivalent_damping_fixed_point() {
    use common::tolerance::ROUTE1_ITERATION;
    let (f_c, c) = (120.0, 450.0);
    let friction = format!(
        "\n[[model.nonlinear]]\nkind = \"coulomb-friction\"\nname = \"guide\"\nacross = \"seat\"\nforce = \"{f_c} N\"\n"
    );
    let sc = machine_on_type1_road(&friction, c);
    let answers = sc.nonlinear_answers().unwrap().unwrap();
    let route1 = answers.route1_statistics.expect("route 1 converges");
    let gap = |c_eq: f64| {
        let (_, rate) = sigma_and_rate(&machine_on_type1_road("", c + c_eq), "seat_travel");
        c_eq - f_c * (2.0 / std::f64::consts::PI).sqrt() / rate
    };
    let (mut lo, mut hi) = (0.0, 1.0e5);
    assert!(gap(lo) < 0.0 && gap(hi) > 0.0);
    for _ in 0..60 {
        let mid = 0.5 * (lo + hi);
        if gap(mid) < 0.0 {
            lo = mid
        } else {
            hi = mid
        }
    }
    let equivalent = machine_on_type1_road("", c + 0.5 * (lo + hi));
    for name in ["bounce", "roll", "seat_travel"] {
        let want = sigma_and_rate(&equivalent, name).0;
        let got = route1.iter().find(|s| s.name == name).unwrap().sigma.unwrap();
        assert!(
            rel(got, want) < ROUTE1_ITERATION,
            "{name}: route 1 {got:e} vs the fixed point {want:e}"
        );
    }
    // the friction is felt: the seat moves less than on its linear damper alone
    let frictionless = sigma_and_rate(&machine_on_type1_road("", c), "seat_travel").0;
    assert!(sigma_and_rate(&equivalent, "seat_travel").0 < 0.9 * frictionless);
}

/// A friction seat in a whole machine, route 2 (nonlinear Monte Carlo on the spectral route: the two tracks
/// and the wheelbase delay). Zero nonlinearity first: a stop 10 m away across the seat (never reached) must
/// give the linear machine's σ of the seat travel and of the roll, inside route 2's Student-t intervals at
/// 1 − `MC_FALSE_FAILURE`. Then the Coulomb friction of 120 N across the seat: route 2's whole interval of the
/// seat travel's σ lies below the frictionless σ (friction only dissipates: the predicted direction; route 1
/// puts it 27 % below). Three intervals: false failure ≤ 6e-7. 16 realizations × 100 s each.
#[test]
fn friction_seat_in_a_machine_route2() {
    use common::tolerance::MC_FALSE_FAILURE;
    use stochvib::nonlinear::monte_carlo::NonlinearRunOptions;
    use stochvib::simulate::RunOptions;
    let run = |sc: &Scenario, tag: &str| {
        let answers = sc.nonlinear_answers().unwrap().unwrap();
        let dt = sc.suggest_nonlinear_step(&answers).unwrap().dt_s;
        let opts = NonlinearRunOptions {
            run: RunOptions {
                confidence: 1.0 - MC_FALSE_FAILURE,
                overwrite: true,
                realizations: 16,
                duration_s: 100.0,
                dt_s: dt,
                seed: 30,
                ..RunOptions::default()
            },
            burn_in_s: None,
            halving_checks: None,
        };
        let file = common::scratch_dir("machine-assembly", tag).join("run.h5");
        let _serial = common::hdf5_serial();
        let s = sc.simulate_nonlinear(&answers, &opts, &file, &|_, _| {}).unwrap();
        move |name: &str| {
            let o = s.run.outputs.iter().find(|o| o.output == name).unwrap();
            let i = &o.get("sigma_response").unwrap().interval;
            (i.lower, i.upper)
        }
    };
    let linear = machine_on_type1_road("", 450.0);
    let far = "\n[[model.nonlinear]]\nkind = \"bump-stop\"\nname = \"far_stop\"\nacross = \"seat\"\n\
               upper_clearance = \"10 m\"\nlower_clearance = \"10 m\"\nstiffness = \"1 kN/m\"\n";
    let iv = run(&machine_on_type1_road(far, 450.0), "far-stop");
    for name in ["seat_travel", "roll"] {
        let exact = sigma_and_rate(&linear, name).0;
        let (lower, upper) = iv(name);
        assert!(
            lower <= exact && exact <= upper,
            "{name}: linear σ {exact:e} outside [{lower:e}, {upper:e}]"
        );
    }
    let friction = "\n[[model.nonlinear]]\nkind = \"coulomb-friction\"\nname = \"guide\"\nacross = \"seat\"\n\
                    force = \"120 N\"\n";
    let iv = run(&machine_on_type1_road(friction, 450.0), "friction");
    let frictionless = sigma_and_rate(&linear, "seat_travel").0;
    let (lower, upper) = iv("seat_travel");
    assert!(
        upper < frictionless,
        "friction seat σ in [{lower:e}, {upper:e}], frictionless {frictionless:e}"
    );
}
