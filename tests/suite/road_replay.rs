//! A road profile replayed through a model (`stochvib replay`, [`stochvib::road::replay()`],
//! [`stochvib::study::replay::replay_scenario`]): the steady-state response to a sinusoidal profile
//! against the closed-form transfer function of the quarter car, the delay between wheels on one track,
//! the synthetic class C profile against its own measured density and against a periodic FFT filtering,
//! and the errors.
//!
//! The quarter car of `data/quarter-car.toml`: body m_s = 300 kg, wheel m_u = 40 kg, suspension k = 20 kN/m,
//! c = 1.5 kN s/m, tyre k_t = 200 kN/m, road z_r under the tyre. With s = iω (derived here from the two
//! equations of motion m_s z̈_s = −c(ż_s − ż_u) − k(z_s − z_u), m_u z̈_u = c(ż_s − ż_u) + k(z_s − z_u) −
//! k_t(z_u − z_r)):
//! ```text
//! Δ(s) = (m_s s² + cs + k)(m_u s² + cs + k + k_t) − (cs + k)²
//! H_s = z_s/z_r = k_t (cs + k)/Δ,   H_u = z_u/z_r = k_t (m_s s² + cs + k)/Δ
//! body = H_s, body_acc = s² H_s, travel = ±(H_s − H_u), tyre_force = ±k_t (H_u − 1)
//! ```
//!
//! **The sampled (first-order-hold) response.** The replay steps the model exactly for an input linear
//! between samples. For a sampled sinusoid of angular frequency ω (θ = ωΔt) the linear interpolant is the
//! sinusoid convolved with the triangle of width 2Δt; its spectrum is the sampled sinusoid's times
//! sinc²(θ'/2) at every alias ω' = ω + m ω_s (ω_s = 2π/Δt). Hence the gain seen at the samples is
//! H_d(ω) = Σ_m H(i(ω + m ω_s)) sinc²((θ + 2πm)/2). Writing H = D + H_sp (feedthrough plus strictly proper
//! part) and using Σ_m sinc²(x + πm) = 1:
//! ```text
//! |H_d(ω) − H(iω)| ≤ (1 − sinc²(θ/2)) (|H_sp(iω)| + max_{m≠0} |H_sp(i(ω + m ω_s))|)
//!                  ≤ (1 − sinc²(θ/2)) (|H_sp(iω)| + |H_sp(i(ω_s − ω))|)
//! ```
//! for 0 ≤ ω ≤ ω_s/2, the last step because |H_sp| of every quarter-car output decreases beyond the
//! wheel-hop resonance (~11 Hz) and ω_s/2 is 200 Hz here. [`foh_bound`] evaluates it; the tests use it as
//! the tolerance, plus [`REPLAY_TRANSIENT`] for what is left of the start-up transient.

use crate::common;
use crate::common::SpawnSerial;
use common::tolerance::{EXACT, ROUNDING};
use nalgebra::{DMatrix, Matrix3, Vector3};
use realfft::num_complex::Complex;
use realfft::RealFftPlanner;
use std::f64::consts::PI;
use std::path::{Path, PathBuf};
use stochvib::road::replay::{replay, settling_length, ReplayOptions, Start, Wheel};
use stochvib::road::{CsvWriteOptions, Detrend, Profile, Track};
use stochvib::scenario::load_scenario;
use stochvib::study::replay::{replay_scenario, ScenarioReplayOptions};
use stochvib::system::{OutputInfo, StateSpace};

/// What is left of the start-up transient after the skipped length, relative to the output's amplitude:
/// the tests skip at least twice the settling length v·7/min|Re λ|, so the slowest mode has decayed by
/// e⁻¹⁴ = 8.3e-7 from an initial mismatch no larger than the response amplitude (the static start removes
/// the step onto the profile and leaves the slope mismatch, of the order of the response); 2e-6 allows a
/// factor of two for the mismatch.
const REPLAY_TRANSIENT: f64 = 2e-6;

/// How many standard errors of the segment spread the replayed and the analytic variance of the measured
/// profile may differ by. They are two estimates of one output variance from the same 500 m record: the
/// time average of the replay over the kept samples and the integral of |H|² against the Welch estimate
/// of the whole record (zero below its first bin). Each deviates from the road's true value by about the
/// standard error s/√J of the variance over J disjoint blocks of the history; their difference by at most
/// twice that. The record is fixed (seed 8608 of the synthesis), so the check is deterministic; 5 standard
/// errors (2.5 per estimate) is the margin of a normal deviate with two-sided probability 1.2e-2 each, kept
/// wide because the block estimate s is itself uncertain with J = 8.
const SEGMENT_SPREAD_SE: f64 = 5.0;

const M_S: f64 = 300.0;
const M_U: f64 = 40.0;
const K: f64 = 20e3;
const C: f64 = 1.5e3;
const K_T: f64 = 200e3;

fn root() -> PathBuf {
    crate::common::root()
}

fn tmp(name: &str) -> PathBuf {
    let d = crate::common::scratch_path("replay", name);
    std::fs::create_dir_all(&d).unwrap();
    d.join(name)
}

/// Closed-form responses of the quarter car at s = iω: (output name, H, feedthrough D up to sign).
fn quarter_car(omega: f64) -> [(&'static str, Complex<f64>, f64); 4] {
    let s = Complex::new(0.0, omega);
    let delta = (s * s * M_S + s * C + K) * (s * s * M_U + s * C + K + K_T) - (s * C + K) * (s * C + K);
    let hs = (s * C + K) * K_T / delta;
    let hu = (s * s * M_S + s * C + K) * K_T / delta;
    [
        ("body", hs, 0.0),
        ("body_acc", s * s * hs, 0.0),
        ("travel", hs - hu, 0.0),
        ("tyre_force", (hu - 1.0) * K_T, K_T),
    ]
}

/// The bound of the module docs on |H_d(ω) − H(iω)| for output `k` of [`quarter_car`] at step `dt`.
fn foh_bound(k: usize, omega: f64, dt: f64) -> f64 {
    let theta = omega * dt;
    let x = theta / 2.0;
    let sinc = if x == 0.0 { 1.0 } else { x.sin() / x };
    let sp = |w: f64| {
        let (_, h, d) = quarter_car(w)[k];
        // H_sp = H − D with D = −k_t for the tyre force (H → −k_t as ω → ∞)
        (h + d).norm()
    };
    (1.0 - sinc * sinc) * (sp(omega) + sp(2.0 * PI / dt - omega))
}

/// A one-track (`left`) profile of 4000 samples at `step_m`: z(x) = amp·sin(2πx/wavelength).
fn sine_track(amp: f64, wavelength_m: f64, step_m: f64) -> Profile {
    let th = 2.0 * PI / wavelength_m;
    let z: Vec<f64> = (0..4000).map(|i| amp * (th * i as f64 * step_m).sin()).collect();
    Profile::new(
        step_m,
        0.0,
        vec![Track {
            name: "left".into(),
            elevation_m: z,
        }],
    )
    .unwrap()
}

fn write_profile(name: &str, step: f64, tracks: Vec<(&str, Vec<f64>)>) -> PathBuf {
    let p = Profile::new(
        step,
        0.0,
        tracks
            .into_iter()
            .map(|(n, e)| Track {
                name: n.into(),
                elevation_m: e,
            })
            .collect(),
    )
    .unwrap();
    let path = tmp(name);
    p.write_csv(&path, &CsvWriteOptions::default()).unwrap();
    path
}

/// Least-squares fit y_k ≈ a sin φ_k + b cos φ_k + c: (amplitude √(a² + b²), phase atan2(b, a)).
fn fit_sine(y: &[f64], phase: impl Fn(usize) -> f64) -> (f64, f64) {
    let mut ata = Matrix3::zeros();
    let mut aty = Vector3::zeros();
    for (k, &v) in y.iter().enumerate() {
        let r = Vector3::new(phase(k).sin(), phase(k).cos(), 1.0);
        ata += r * r.transpose();
        aty += r * v;
    }
    let x = ata.lu().solve(&aty).unwrap();
    (x[0].hypot(x[1]), x[1].atan2(x[0]))
}

fn wrap(a: f64) -> f64 {
    (a + PI).rem_euclid(2.0 * PI) - PI
}

/// (a) A sinusoidal profile z(x) = A sin 2πnx through the quarter car at v = 20 m/s: after the transient
/// every output is |H(iω)| A sin(ωt + arg H), ω = 2πnv, with H the closed form of the module docs; the
/// fitted amplitude and phase agree within the first-order-hold bound. n = 0.06 cycles/m puts ω at the
/// body resonance (1.2 Hz), n = 0.55 cycles/m at the wheel hop (11 Hz).
#[test]
fn a_sinusoidal_profile_gives_the_closed_form_steady_state_amplitude_and_phase() {
    let scenario = load_scenario(&root().join("data/quarter-car.toml"), &root().join("spectra")).unwrap();
    let (step, v, amp) = (0.05, 20.0, 0.01);
    for n in [0.06, 0.55] {
        let z: Vec<f64> = (0..8000)
            .map(|i| amp * (2.0 * PI * n * i as f64 * step).sin())
            .collect();
        let path = write_profile(&format!("sine-{n}.csv"), step, vec![("left", z)]);
        let ss = scenario.model.system.state_space().unwrap();
        let skip = 2.0 * settling_length(ss, v).unwrap();
        let opts = ScenarioReplayOptions {
            speed_m_s: Some(v),
            skip_m: Some(skip),
            detrend: Detrend::Mean,
            ..Default::default()
        };
        let r = replay_scenario(&scenario, &path, &opts).unwrap();
        let rep = &r.replay;
        assert_eq!(rep.wheelbase_m, 0.0);
        let omega = 2.0 * PI * n * v;
        // the profile after removing its mean: the sinusoid plus a constant (the fit has a constant term)
        let x0 = rep.first_distance_m;
        for (k, (name, h, _)) in quarter_car(omega).iter().enumerate() {
            let i = rep.outputs.iter().position(|o| o.name == *name).unwrap();
            let (a_fit, ph_fit) = fit_sine(&rep.history[i], |j| 2.0 * PI * n * (x0 + j as f64 * step));
            let expected = h.norm() * amp;
            let tol = foh_bound(k, omega, rep.dt_s) / h.norm() + REPLAY_TRANSIENT;
            let err = (a_fit - expected).abs() / expected;
            eprintln!(
                "n = {n} {name}: amplitude rel error {err:.3e} (bound {tol:.3e}), phase error {:.3e}",
                wrap(ph_fit - h.arg())
            );
            assert!(
                err <= tol,
                "n = {n}, {name}: amplitude {a_fit:e} vs |H|A = {expected:e} (rel {err:e} > {tol:e})"
            );
            // travel and tyre force carry a sign convention of the model: their phase is checked modulo π
            let dph = if k < 2 {
                wrap(ph_fit - h.arg())
            } else {
                wrap(2.0 * (ph_fit - h.arg())) / 2.0
            };
            assert!(
                dph.abs() <= tol,
                "n = {n}, {name}: phase {ph_fit} vs arg H = {} (tol {tol:e})",
                h.arg()
            );
        }
    }
}

/// Two outputs that repeat the inputs (y = u: D = I, one idle state) show exactly what each wheel sees.
fn feedthrough(m: usize) -> StateSpace {
    StateSpace::new(
        DMatrix::from_element(1, 1, -1.0),
        DMatrix::zeros(1, m),
        DMatrix::zeros(m, 1),
        Some(DMatrix::identity(m, m)),
        None,
        (0..m).map(|j| OutputInfo::new(format!("u{j}"), "m")).collect(),
    )
    .unwrap()
}

/// Two identical first-order filters ẋ_j = a(u_j − x_j), outputs bounce (x₀ + x₁)/2 and pitch (x₀ − x₁)/2.
fn bounce_pitch() -> StateSpace {
    let a = 8.0;
    StateSpace::new(
        DMatrix::from_diagonal_element(2, 2, -a),
        DMatrix::from_diagonal_element(2, 2, a),
        DMatrix::from_row_slice(2, 2, &[0.5, 0.5, 0.5, -0.5]),
        None,
        None,
        vec![OutputInfo::new("bounce", "m"), OutputInfo::new("pitch", "m")],
    )
    .unwrap()
}

/// (b) Two wheels on one track, the rear one L = 2.7 m behind: it sees the front wheel's elevation L/v
/// later. With a wavelength L/k the two inputs are equal (in phase): no pitch; with 2L/(2k + 1) they are
/// opposite: no bounce. A position between samples (L = 2.725 m = 54.5 steps) gives the mean of the two
/// neighbouring samples, for a sinusoid z = A sin θx exactly A cos(θΔx/2) sin θ(x − L).
#[test]
fn wheels_on_one_track_see_it_delayed_by_the_wheelbase() {
    let (step, v, amp, l) = (0.05, 15.0, 0.02, 2.7);
    let wheels = |l: f64| {
        vec![
            Wheel {
                track: "left".into(),
                position_m: 0.0,
                gain: 1.0,
                offset: 0.0,
            },
            Wheel {
                track: "left".into(),
                position_m: l,
                gain: 1.0,
                offset: 0.0,
            },
        ]
    };
    let opts = ReplayOptions {
        speed_m_s: v,
        skip_m: Some(0.0),
        start: Start::Static,
    };
    for (wavelength, in_phase) in [(l / 3.0, true), (2.0 * l / 7.0, false), (l, true), (2.0 * l, false)] {
        let th = 2.0 * PI / wavelength;
        let p = sine_track(amp, wavelength, step);
        // what each wheel sees, against the closed form
        let r = replay(&feedthrough(2), &wheels(l), &p, Path::new("sine.csv"), &opts).unwrap();
        assert_eq!(r.wheelbase_m, l);
        assert!(!r.interpolated);
        for k in 0..r.history[0].len() {
            let x = r.first_distance_m + k as f64 * step;
            let (front, rear) = (amp * (th * x).sin(), amp * (th * (x - l)).sin());
            assert!((r.history[0][k] - front).abs() <= EXACT * amp, "front at {x} m");
            assert!((r.history[1][k] - rear).abs() <= EXACT * amp, "rear at {x} m");
        }
        // bounce and pitch: the one that should vanish is zero to rounding
        let r = replay(&bounce_pitch(), &wheels(l), &p, Path::new("sine.csv"), &opts).unwrap();
        let peak = |h: &[f64]| h.iter().fold(0.0f64, |m, y| m.max(y.abs()));
        let (b, ph) = (peak(&r.history[0]), peak(&r.history[1]));
        let (kept, gone) = if in_phase { (b, ph) } else { (ph, b) };
        assert!(kept > 0.1 * amp, "λ = {wavelength}: the excited motion {kept:e}");
        assert!(
            gone <= EXACT * amp,
            "λ = {wavelength}, in phase {in_phase}: {gone:e} should vanish"
        );
    }
    // a rear wheel half a step off the grid: linear interpolation, f = 1/2
    let (l2, wavelength) = (2.725, 1.3);
    let th = 2.0 * PI / wavelength;
    let p = sine_track(amp, wavelength, step);
    let r = replay(&feedthrough(2), &wheels(l2), &p, Path::new("sine.csv"), &opts).unwrap();
    assert!(r.interpolated);
    // the foremost wheel starts at the first whole step with the rear wheel on the profile: ⌈54.5⌉ = 55
    assert_eq!(r.first_distance_m, 55.0 * step);
    let atten = (th * step / 2.0).cos();
    for k in 0..r.history[0].len() {
        let x = r.first_distance_m + k as f64 * step;
        let rear = amp * atten * (th * (x - l2)).sin();
        assert!(
            (r.history[1][k] - rear).abs() <= EXACT * amp,
            "rear at {x} m: {} vs {rear}",
            r.history[1][k]
        );
    }
}

/// Σ (y_k − ȳ)² / K of `y`.
fn variance(y: &[f64]) -> f64 {
    let m = y.iter().sum::<f64>() / y.len() as f64;
    y.iter().map(|v| (v - m) * (v - m)).sum::<f64>() / y.len() as f64
}

/// (c) The synthetic class C profile (data/measured-profile.csv, 500 m at 0.05 m) through the quarter car at
/// 20 m/s. (i) The replayed σ² of each output against the analytic σ² with the profile's own Welch
/// density, within [`SEGMENT_SPREAD_SE`] standard errors of the spread over 8 disjoint blocks of the
/// history. (ii) The replay of the mean-removed track (one period of the FFT synthesis, so periodic)
/// against its periodic filtering computed here by FFT with the closed-form H: the r.m.s. difference over
/// the kept samples is bounded by the first-order-hold bound summed over the DFT bins (Parseval), scaled by
/// √(N/K) because only K of the N samples of the period are compared, plus [`REPLAY_TRANSIENT`].
#[test]
fn the_measured_profile_replayed_agrees_with_its_density_and_with_fft_filtering() {
    let scenario = load_scenario(&root().join("data/quarter-car.toml"), &root().join("spectra")).unwrap();
    let csv = root().join("data/measured-profile.csv");
    let r = replay_scenario(&scenario, &csv, &ScenarioReplayOptions::default()).unwrap();
    assert_eq!(r.analytic_track, "left");
    for o in &r.outputs {
        let h = &r.replay.history[o.index];
        let (vr, va) = (o.replayed.sigma.powi(2), o.analytic_sigma.unwrap().powi(2));
        assert!((variance(h) - vr).abs() <= ROUNDING * 1e3 * vr);
        let j = 8;
        let len = h.len() / j;
        let blocks: Vec<f64> = (0..j).map(|b| variance(&h[b * len..(b + 1) * len])).collect();
        let mean = blocks.iter().sum::<f64>() / j as f64;
        let s = (blocks.iter().map(|b| (b - mean).powi(2)).sum::<f64>() / (j - 1) as f64).sqrt();
        let se = s / (j as f64).sqrt();
        eprintln!(
            "{}: replayed σ² {vr:.4e}, analytic {va:.4e}, |Δ| = {:.2} standard errors ({se:.3e})",
            o.replayed.name,
            (vr - va).abs() / se
        );
        assert!(
            (vr - va).abs() <= SEGMENT_SPREAD_SE * se,
            "{}: replayed σ² {vr:e} vs analytic {va:e}: difference {:e} > {SEGMENT_SPREAD_SE} × {se:e}",
            o.replayed.name,
            (vr - va).abs()
        );
    }

    // (ii) periodic FFT filtering of the mean-removed left track
    let v = 20.0;
    let ss = scenario.model.system.state_space().unwrap();
    let opts = ScenarioReplayOptions {
        detrend: Detrend::Mean,
        skip_m: Some(2.0 * settling_length(ss, v).unwrap()),
        ..Default::default()
    };
    let r = replay_scenario(&scenario, &csv, &opts).unwrap();
    let profile = Profile::read_csv(&csv).unwrap();
    let z = Detrend::Mean.apply(&profile.track("left").unwrap().elevation_m);
    let n = z.len();
    let dt = profile.step_m / v;
    let mut planner = RealFftPlanner::<f64>::new();
    let fwd = planner.plan_fft_forward(n);
    let inv = planner.plan_fft_inverse(n);
    let mut zin = z.clone();
    let mut spec = fwd.make_output_vec();
    fwd.process(&mut zin, &mut spec).unwrap();
    let rep = &r.replay;
    let start = rep.skip_samples; // wheelbase 0: kept sample k is profile sample skip + k
    let kept = rep.history[0].len();
    for (k, (name, _, _)) in quarter_car(0.0).iter().enumerate() {
        let mut ys = spec.clone();
        let (mut err2, mut pow2) = (0.0, 0.0);
        for (b, c) in ys.iter_mut().enumerate() {
            let omega = 2.0 * PI * b as f64 / (n as f64 * dt);
            let h = quarter_car(omega)[k].1;
            let w = if b == 0 || b == n / 2 { 1.0 } else { 2.0 };
            err2 += w * c.norm_sqr() * foh_bound(k, omega, dt).powi(2);
            pow2 += w * c.norm_sqr() * h.norm_sqr();
            *c *= h / n as f64;
        }
        ys[0].im = 0.0;
        ys[n / 2].im = 0.0;
        let mut y = inv.make_output_vec();
        inv.process(&mut ys, &mut y).unwrap();
        let i = rep.outputs.iter().position(|o| o.name == *name).unwrap();
        // travel and tyre force: the model's sign convention is found from the data, then checked
        let dot: f64 = (0..kept).map(|q| rep.history[i][q] * y[start + q]).sum();
        let sign = dot.signum();
        let diff: Vec<f64> = (0..kept).map(|q| rep.history[i][q] - sign * y[start + q]).collect();
        let rms_diff = (diff.iter().map(|d| d * d).sum::<f64>() / kept as f64).sqrt();
        let rms_y = (pow2 / (n as f64 * n as f64)).sqrt();
        let bound = (err2 / pow2).sqrt() * (n as f64 / kept as f64).sqrt() + REPLAY_TRANSIENT;
        eprintln!(
            "{name}: FFT vs replay r.m.s. difference / σ = {:.3e} (bound {bound:.3e})",
            rms_diff / rms_y
        );
        assert!(
            rms_diff <= bound * rms_y,
            "{name}: r.m.s. difference {rms_diff:e} vs bound {:e} (σ {rms_y:e})",
            bound * rms_y
        );
        if k < 2 {
            assert_eq!(
                sign, 1.0,
                "{name}: body and its acceleration have the closed form's sign"
            );
        }
    }
}

/// (d) Bad input: a track the scenario needs that the CSV lacks, a profile shorter than the wheelbase plus
/// the skipped length, a speed ≤ 0, an input that is not a road, a missing history file directory.
#[test]
fn bad_replays_name_the_file_the_key_the_value_and_the_reason() {
    let spectra = root().join("spectra");
    let quarter = load_scenario(&root().join("data/quarter-car.toml"), &spectra).unwrap();
    let vehicle = load_scenario(&root().join("data/full-vehicle-two-tracks.toml"), &spectra).unwrap();
    let z: Vec<f64> = (0..400).map(|i| 0.01 * (i as f64 * 0.3).sin()).collect();
    let one = write_profile("left-only.csv", 0.05, vec![("left", z.clone())]);
    let err = |sc, p: &Path, o: ScenarioReplayOptions| replay_scenario(sc, p, &o).unwrap_err().to_string();
    let check = |e: String, parts: &[&str]| {
        for part in parts {
            assert!(e.contains(part), "missing `{part}` in: {e}");
        }
    };
    // the full vehicle needs `right`
    check(
        err(&vehicle, &one, ScenarioReplayOptions::default()),
        &["left-only.csv", "track", "right", "`left`"],
    );
    // --track naming no column
    check(
        err(
            &quarter,
            &one,
            ScenarioReplayOptions {
                track: Some("middle".into()),
                ..Default::default()
            },
        ),
        &["left-only.csv", "middle", "`left`"],
    );
    // 400 samples (399 × 0.05 = 19.95 m) cannot hold a 30 m skip (600 steps); nor the vehicle's 2.7 m
    // wheelbase plus 18 m; the lengths in a few digits (it wrote 19.950000000000003 m, steps of
    // 0.049999999999999996 m)
    check(
        err(
            &quarter,
            &one,
            ScenarioReplayOptions {
                skip_m: Some(30.0),
                ..Default::default()
            },
        ),
        &[
            "left-only.csv",
            "length` = 19.95 m",
            "skipped length 30 m (600 steps of 0.05 m)",
            "too short",
        ],
    );
    let two = write_profile("short.csv", 0.05, vec![("left", z.clone()), ("right", z.clone())]);
    check(
        err(
            &vehicle,
            &two,
            ScenarioReplayOptions {
                skip_m: Some(18.0),
                ..Default::default()
            },
        ),
        &["short.csv", "length", "wheelbase 2.7 m", "too short"],
    );
    // speed
    for bad in [0.0, -3.0, f64::NAN] {
        check(
            err(
                &quarter,
                &one,
                ScenarioReplayOptions {
                    speed_m_s: Some(bad),
                    ..Default::default()
                },
            ),
            &["speed", "> 0"],
        );
    }
    // an input that is a temporal process, not a road
    let iso = load_scenario(&root().join("data/isolator-single.toml"), &spectra).unwrap();
    check(
        err(
            &iso,
            &one,
            ScenarioReplayOptions {
                speed_m_s: Some(10.0),
                ..Default::default()
            },
        ),
        &["isolator-single.toml", "input.spectrum", "not a road"],
    );
    // a history file is never half-written and never silently replaced
    let r = replay_scenario(
        &quarter,
        &one,
        &ScenarioReplayOptions {
            skip_m: Some(1.0),
            ..Default::default()
        },
    )
    .unwrap();
    let out = tmp("history.csv");
    let _ = std::fs::remove_file(&out);
    r.replay.write_csv(&out, false).unwrap();
    let text = std::fs::read_to_string(&out).unwrap();
    assert!(
        text.starts_with("time [s], distance [m], body [m], body_acc [m/s^2]"),
        "{text}"
    );
    assert_eq!(text.lines().count(), 1 + r.replay.history[0].len());
    assert!(r
        .replay
        .write_csv(&out, false)
        .unwrap_err()
        .to_string()
        .contains("already exists"));
}

/// A Monte Carlo run of a scenario whose road spectrum is `measured-profile` records the CSV (name as
/// written, size, CRC-32) in its identifying provenance: after one elevation of the CSV changes, the
/// interrupted run is refused naming `measured_profile`; with the CSV restored it resumes.
#[test]
fn a_resume_after_the_measured_profile_changed_is_refused() {
    let _serial = common::hdf5_serial(); // no fork while a file is open
    let d = crate::common::scratch_path("replay", "identity");
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    let csv_text = std::fs::read_to_string(root().join("data/measured-profile.csv")).unwrap();
    std::fs::write(d.join("profile.csv"), &csv_text).unwrap();
    let scen_text = std::fs::read_to_string(root().join("data/quarter-car.toml"))
        .unwrap()
        .replace(
            "spectrum = \"iso8608-c\"",
            "spectrum = { kind = \"measured-profile\", file = \"profile.csv\", track = \"right\" }",
        );
    assert!(
        scen_text.contains("measured-profile"),
        "the scenario names its spectrum"
    );
    let scen = d.join("quarter.toml");
    std::fs::write(&scen, scen_text).unwrap();
    let load = || load_scenario(&scen, &root().join("spectra")).unwrap();
    let prov = load().run_input().provenance;
    let id = prov.iter().find(|p| p.name == "measured_profile").expect("recorded");
    assert!(id.identifies);
    let crc = stochvib::store::checksum::crc32(csv_text.as_bytes());
    assert_eq!(
        id.text,
        format!("profile.csv ({} bytes, CRC-32 {crc:08x})", csv_text.len())
    );
    let mut opts = stochvib::simulate::RunOptions {
        realizations: 8,
        duration_s: 2.0,
        dt_s: 0.01,
        seed: 11,
        ..Default::default()
    };
    opts.shard_size = 2;
    let out = d.join("run.h5");
    let r = std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| {
        let _ = load().simulate(&opts, &out, &|done, _| {
            if done >= 2 {
                panic!("interrupted");
            }
        });
    }));
    assert!(r.is_err() && stochvib::store::tmp_path(&out).exists());
    // one elevation of the right track, 0.001 mm higher: same size, other CRC
    let edited = csv_text.replace("0.05,-19.091,-9.676", "0.05,-19.091,-9.675");
    assert_ne!(edited, csv_text);
    std::fs::write(d.join("profile.csv"), &edited).unwrap();
    let err = load().simulate(&opts, &out, &|_, _| {}).unwrap_err().to_string();
    assert!(
        err.contains("measured_profile (changed since the interrupted run)"),
        "{err}"
    );
    // restored: the run resumes
    std::fs::write(d.join("profile.csv"), &csv_text).unwrap();
    let s = load().simulate(&opts, &out, &|_, _| {}).unwrap();
    assert_eq!(s.resumed_shards, 2);
    let _ = std::fs::remove_dir_all(&d);
}

/// `stochvib replay SCENARIO PROFILE --json -o history.csv`: the report as JSON (every reported output with
/// its replayed and analytic σ) and the history file; `--speed 0` fails naming the option.
#[test]
fn the_replay_command_prints_the_report_and_writes_the_history() {
    let out = tmp("cli-history.csv");
    let _ = std::fs::remove_file(&out);
    let run = |args: &[&str]| {
        std::process::Command::new(crate::common::cli_bin())
            .current_dir(root())
            .env("STOCHVIB_SPECTRA", root().join("spectra"))
            .args(args)
            .output_serial()
            .unwrap()
    };
    let o = run(&[
        "replay",
        "data/quarter-car.toml",
        "data/measured-profile.csv",
        "--speed",
        "15",
        "--json",
        "-o",
        out.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let j: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    assert_eq!(j["replay"]["speed_m_s"], 15.0);
    let outputs = j["outputs"].as_array().unwrap();
    assert_eq!(outputs.len(), 4);
    // the same numbers as the library call (JSON round-trips f64 exactly)
    let sc = load_scenario(&root().join("data/quarter-car.toml"), &root().join("spectra")).unwrap();
    let opts = ScenarioReplayOptions {
        speed_m_s: Some(15.0),
        ..Default::default()
    };
    let lib = replay_scenario(&sc, &root().join("data/measured-profile.csv"), &opts).unwrap();
    for (x, l) in outputs.iter().zip(&lib.outputs) {
        assert_eq!(x["name"], l.replayed.name.as_str());
        assert_eq!(
            x["sigma"].as_f64().unwrap().to_bits(),
            l.replayed.sigma.to_bits(),
            "{x}"
        );
        assert_eq!(x["analytic_sigma"].as_f64(), l.analytic_sigma, "{x}");
    }
    let text = std::fs::read_to_string(&out).unwrap();
    assert!(text.starts_with("time [s], distance [m], body [m]"));
    let o = run(&[
        "replay",
        "data/quarter-car.toml",
        "data/measured-profile.csv",
        "--speed",
        "0",
    ]);
    assert!(!o.status.success());
    let e = String::from_utf8_lossy(&o.stderr);
    assert!(e.contains("speed") && e.contains("> 0"), "{e}");
}
