//! Monte Carlo defaults that agree with the analysis: the suggested Δt and duration of a scenario with a
//! Wk-weighted output make the default run's interval cover the analytic a_w; an interval that misses says
//! whether the discretisation bias or chance is the cause; `analyze --monte-carlo` reports the Monte Carlo
//! a_w, VDV and damage rate beside the analytic ones; and ISO 2631-1's basic-method check (crest factor,
//! MTVV/a_w, VDV/(a_w T^(1/4)) against 9, 1.5, 1.75) with the governing metric, on closed-form records and
//! on a run.

use crate::common;

use common::root;
use common::tolerance::{EXACT, ROUNDING, SCHUR_GRID_VARIANCE};
use common::SpawnSerial;
use std::f64::consts::PI;
use stochvib::comfort::{Governing, SignalMetrics};
use stochvib::scenario::{parse_scenario, Scenario};
use stochvib::simulate::{planned_variances, suggest_step, RunOptions};
use stochvib::study::with_verdict_input;

/// The half car of `data/half-car.toml` (ISO 8608 class C at 10 m/s, wheelbase delay 0.27 s: the spectral
/// route) with the driver's body acceleration judged as a Wk seat-surface z axis.
fn half_car_wk() -> Scenario {
    let mut text = std::fs::read_to_string(root().join("data/half-car.toml")).unwrap();
    text.push_str(
        "[analysis.comfort]\npurpose = \"health\"\nexposure = \"8 h\"\n[[analysis.comfort.axis]]\n\
         output = \"body_acc\"\nlocation = \"seat-surface\"\naxis = \"z\"\n",
    );
    parse_scenario(&text, &root().join("data/half-car-wk.toml"), &root().join("spectra")).unwrap()
}

/// A run file of this test process in the temporary directory.
fn scratch(name: &str) -> std::path::PathBuf {
    crate::common::scratch_kept("mc-defaults", name).join("run.h5")
}

/// |σ_d/σ − 1| of the weighted output for a run with `opts`.
fn weighted_bias(sc: &Scenario, opts: &RunOptions) -> f64 {
    with_verdict_input(sc, |input| {
        let v = planned_variances(input, opts)?;
        Ok(v.iter().find(|v| v.name == "body_acc_Wk").unwrap().bias())
    })
    .unwrap()
}

/// The default Monte Carlo run of a Wk output covers the analytic a_w.
///
/// Before: the step suggested from the model's poles and the input band alone (Δt = π/ω_hi with the band's
/// upper edge at 28.3 Hz, the Nyquist frequency) gave a simulated process whose weighted σ is more than 3 %
/// below the analytic a_w (the first-order hold attenuates the road near the Nyquist frequency), so the
/// interval missed it (the issue saw 5.6 % low). Asserted first, from the exact discrete-process variance
/// ([`planned_variances`]).
///
/// After: [`Scenario::suggest_step`] lowers that bias below 10⁻³; the run of 40 realizations at confidence
/// 1 − 10⁻⁶ must cover the analytic a_w. The bias is also asserted to be under a quarter of the interval's
/// half-width, so a miss would need a deviation beyond ≈ 3.7 of the 4.9 standard errors the interval spans:
/// the false-failure probability is at most that of the interval, 10⁻⁶ (the Student-t interval of the mean
/// of 40 per-realization mean squares, each an average over 10⁵ correlated samples, is close to its nominal
/// level).
#[test]
fn default_run_of_a_wk_output_covers_the_analytic_a_w() {
    let sc = half_car_wk();
    let old = suggest_step(&sc.run_input()).unwrap();
    let old_bias = weighted_bias(
        &sc,
        &RunOptions {
            realizations: 40,
            duration_s: old.duration_s,
            dt_s: old.dt_s,
            seed: 1,
            ..RunOptions::default()
        },
    );
    assert!(old_bias < -0.03, "the model-only default's bias {old_bias}");
    let s = sc.suggest_step(40).unwrap();
    let opts = RunOptions {
        confidence: 1.0 - 1e-6,
        realizations: 40,
        duration_s: s.duration_s,
        dt_s: s.dt_s,
        seed: 7,
        ..RunOptions::default()
    };
    let bias = weighted_bias(&sc, &opts);
    assert!(bias.abs() <= 1e-3, "suggested Δt = {} s: bias {bias}", s.dt_s);
    // a readable step m·10ᵏ (m from 1, 1.2, 1.25, 1.5, 2, 2.5, 3, 4, 5, 6, 8) that divides the wheelbase delay
    let steps = 0.27 / s.dt_s;
    let m = s.dt_s / 10f64.powf(s.dt_s.log10().floor());
    assert!((steps - steps.round()).abs() < 1e-9, "{}", s.dt_s);
    assert!(
        [1.0, 1.2, 1.25, 1.5, 2.0, 2.5, 3.0, 4.0, 5.0, 6.0, 8.0]
            .iter()
            .any(|r| (m - r).abs() < 1e-9),
        "{}",
        s.dt_s
    );
    let file = scratch("hc");
    let run = sc.simulate(&opts, &file, &|_, _| {}).unwrap();
    let _ = std::fs::remove_file(&file);
    let st = run.statistic("body_acc_Wk", "sigma").unwrap();
    let (a, iv) = (st.analytic.unwrap(), st.interval);
    assert!(
        bias.abs() * a < 0.25 * 0.5 * (iv.upper - iv.lower),
        "bias against the interval"
    );
    assert_eq!(st.covers, Some(true), "a_w {a} vs {iv:?} at Δt = {} s", s.dt_s);
}

/// The discrete variance that [`planned_variances`] predicts (its FFT-grid transfer from one Schur form of
/// Φ for every bin) is the one the run simulates and stores as `sigma_discrete` (an LU solve per bin): two
/// evaluations of the same sum of positive terms that differ by rounding amplified by the conditioning of
/// zI − Φ near z = 1 ([`SCHUR_GRID_VARIANCE`]), for every simulated output: here the half car's outputs and
/// the Wk-weighted one (the augmented system, Δt of the default suggestion). `sigma_discrete` depends on Δt,
/// the duration and the spectra only, not on the realizations: two realizations suffice.
#[test]
fn planned_discrete_variance_is_the_runs_sigma_discrete() {
    let sc = half_car_wk();
    let s = sc.suggest_step(40).unwrap();
    let opts = RunOptions {
        realizations: 2,
        duration_s: s.duration_s,
        dt_s: s.dt_s,
        seed: 5,
        ..RunOptions::default()
    };
    let planned = with_verdict_input(&sc, |input| planned_variances(input, &opts)).unwrap();
    let file = scratch("planned");
    let run = sc.simulate(&opts, &file, &|_, _| {}).unwrap();
    let _ = std::fs::remove_file(&file);
    assert_eq!(planned.len(), run.outputs.len());
    for v in &planned {
        let d = run.statistic(&v.name, "sigma_discrete").unwrap().analytic.unwrap();
        let rel = (v.discrete.sqrt() / d - 1.0).abs();
        assert!(
            rel <= SCHUR_GRID_VARIANCE,
            "`{}`: planned {} vs run {d}: {rel:e}",
            v.name,
            v.discrete.sqrt()
        );
    }
}

/// An interval that misses is explained: with the old default step the weighted σ's interval (40
/// realizations, 95 %) misses the analytic a_w and covers the discrete-process σ_d, and the summary says
/// that the discretisation bias is the cause, with its size. The bias (> 3 %, asserted in
/// [`default_run_of_a_wk_output_covers_the_analytic_a_w`]) is over ten times the interval's half-width
/// (≈ 0.2 %), so the miss is certain; covering σ_d fails with probability 5 % (the interval's level) — the
/// assertion on the cause holds whichever of the two texts is printed once the miss is given, so only
/// `NOT covered` and the bias are asserted.
#[test]
fn a_miss_names_the_discretisation_bias() {
    let sc = half_car_wk();
    let old = suggest_step(&sc.run_input()).unwrap();
    let opts = RunOptions {
        realizations: 40,
        duration_s: old.duration_s,
        dt_s: old.dt_s,
        seed: 3,
        ..RunOptions::default()
    };
    let file = scratch("old");
    let run = sc.simulate(&opts, &file, &|_, _| {}).unwrap();
    let _ = std::fs::remove_file(&file);
    let o = run.outputs.iter().find(|o| o.output == "body_acc_Wk").unwrap();
    let cause = stochvib::simulate::coverage_cause(o).expect("the old default misses a_w");
    assert!(
        cause.contains("NOT covered") && cause.contains("σ_d/σ − 1 = -"),
        "{cause}"
    );
    let text = run.to_string();
    assert!(text.contains("covers    body_acc_Wk: NOT covered"), "{text}");
}

/// The default step resolves a fatigue stress's rainflow peaks: `data/operator-seat-verdicts.toml`'s
/// spring stress has the rate of peaks ν_p = √(m₄/m₂) (one-sided Hz moments by quadrature of its density,
/// the verdict analysis' check, not the suggestion's closed form): its suggested Δt is at most 1/(32 ν_p)
/// (a sampled peak at frequency f misses at most 1 − cos(πfΔt) of its height, 0.5 % at fΔt = 1/32), where
/// the model's own suggestion (fastest pole only) is more than that.
#[test]
fn the_default_step_resolves_the_fatigue_stress_peaks() {
    let path = root().join("data/operator-seat-verdicts.toml");
    let sc = stochvib::scenario::load_scenario(&path, &root().join("spectra")).unwrap();
    let f = stochvib::study::verdict_analysis(&sc).unwrap().fatigue.unwrap();
    let m = f.moments_quadrature.expect("the stress's moments by quadrature");
    let nu_p = (m[3] / m[2]).sqrt();
    let limit = 1.0 / (32.0 * nu_p);
    assert!(suggest_step(&sc.run_input()).unwrap().dt_s > limit);
    let s = sc.suggest_step(30).unwrap();
    assert!(s.dt_s <= limit, "Δt = {} s vs 1/(32 ν_p) = {limit} s", s.dt_s);
    assert!(s.reason.contains("rate of peaks"), "{}", s.reason);
}

/// The default step resolves a band table: the quarter car of `data/quarter-car.toml` (20 m/s) with a
/// one-third-octave table over 0.5–200 Hz, whose top band (nominal 200 Hz) ends at 10^2.35 = 223.9 Hz
/// (IEC 61260-1, base 10). The model's own suggestion (Δt = π/(8|λ|max), the road's edge at 56.6 Hz) puts
/// the Nyquist frequency 1/(2Δt) below that edge; the scenario's suggestion puts it above the edge of the
/// report's top band.
#[test]
fn the_default_step_resolves_the_band_table() {
    let text = std::fs::read_to_string(root().join("data/quarter-car.toml")).unwrap();
    let text = text.replace(
        "band = [\"0.5 Hz\", \"80 Hz\"]",
        "band = [\"0.5 Hz\", \"200 Hz\"]\nbands = \"third-octave\"",
    );
    let sc = parse_scenario(
        &text,
        &root().join("data/quarter-car-bands.toml"),
        &root().join("spectra"),
    )
    .unwrap();
    let r = stochvib::study::analysis_report(&sc).unwrap();
    let table = r.outputs[0].bands.as_ref().unwrap().table.as_ref().unwrap();
    let top = table.rows.last().unwrap().band.upper_hz;
    assert!((top / 10f64.powf(2.35) - 1.0).abs() < EXACT, "{top}");
    let old = suggest_step(&sc.run_input()).unwrap();
    assert!(0.5 / old.dt_s < top, "{}", old.dt_s);
    let s = sc.suggest_step(40).unwrap();
    assert!(0.5 / s.dt_s >= top, "Δt = {} s: Nyquist below {top} Hz", s.dt_s);
    assert!(s.reason.contains("band table"), "{}", s.reason);
}

/// A 2 Hz sinusoid of amplitude A over whole periods: CF = √2, MTVV/a_w = 1 (τ = 1 s over whole periods),
/// VDV/(a_w T^(1/4)) = √2·(3/8)^(1/4) (a_w = A/√2, VDV = A(3T/8)^(1/4)): the basic method suffices and the
/// r.m.s. governs. A 1 s burst of it in a T = 64 s record (zeros elsewhere): a_w = (A/√2)/8, peak A,
/// MTVV = A/√2 (the window over the burst), VDV = A(3/8)^(1/4), so CF = 8√2 = 11.3 > 9, MTVV/a_w = 8 > 1.5,
/// VDV ratio = √2(3/8)^(1/4)·64^(1/4) = 3.13 > 1.75; the largest ratio to its threshold is the MTVV's
/// (8/1.5 = 5.3 against 1.26 and 1.79): the MTVV governs. Sums over whole periods are exact (discrete
/// orthogonality), so the ratios agree to rounding.
#[test]
fn basic_method_check_on_closed_form_records() {
    let (amp, dt) = (3.0, 1.0 / 256.0);
    let sine = |k: usize| amp * (2.0 * PI * 2.0 * k as f64 * dt).sin();
    let steady: Vec<f64> = (0..256 * 16).map(sine).collect();
    let c = SignalMetrics::from_samples(&steady, dt).unwrap().check;
    let close = |x: Option<f64>, y: f64| (x.unwrap() - y).abs() <= 10.0 * ROUNDING * y;
    assert!(close(c.crest_factor, 2f64.sqrt()));
    assert!(close(c.mtvv_ratio, 1.0));
    assert!(close(c.vdv_ratio, 2f64.sqrt() * (3.0f64 / 8.0).powf(0.25)));
    assert_eq!(c.governing, Governing::Rms);
    let burst: Vec<f64> = (0..256 * 64)
        .map(|k| {
            if (256 * 10..256 * 11).contains(&k) {
                sine(k)
            } else {
                0.0
            }
        })
        .collect();
    let c = SignalMetrics::from_samples(&burst, dt).unwrap().check;
    assert!(close(c.crest_factor, 8.0 * 2f64.sqrt()));
    assert!(close(c.mtvv_ratio, 8.0));
    assert!(close(
        c.vdv_ratio,
        2f64.sqrt() * (3.0f64 / 8.0).powf(0.25) * 64f64.powf(0.25)
    ));
    assert!(c.crest_factor_exceeded && c.mtvv_ratio_exceeded && c.vdv_ratio_exceeded);
    assert_eq!(c.governing, Governing::Mtvv);
}

/// The basic-method check of a run (`data/operator-seat-verdicts.toml`, a stationary Gaussian weighted
/// output, default step): VDV/(a_w T^(1/4)) → 3^(1/4) for a Gaussian (E a⁴ = 3σ⁴, so E VDV⁴ = 3Tσ⁴); its
/// bounds from the VDV and σ intervals, each at confidence 1 − 5·10⁻⁷, must contain 3^(1/4) (false-failure
/// probability ≤ 10⁻⁶ by the union bound). A Gaussian record's crest factor is near √(2 ln(ν₀T)) ≈ 3–4.5:
/// far below 9; the r.m.s. governs. The summary prints the check; `analyze --monte-carlo` reports a_w, VDV
/// and the damage rate beside the analytic values, and the same check.
#[test]
fn basic_method_check_of_a_run_and_analyze_monte_carlo() {
    let path = root().join("data/operator-seat-verdicts.toml");
    let sc = stochvib::scenario::load_scenario(&path, &root().join("spectra")).unwrap();
    let s = sc.suggest_step(30).unwrap();
    let opts = RunOptions {
        confidence: 1.0 - 5e-7,
        realizations: 30,
        duration_s: s.duration_s,
        dt_s: s.dt_s,
        seed: 11,
        ..RunOptions::default()
    };
    let file = scratch("seat");
    let run = sc.simulate(&opts, &file, &|_, _| {}).unwrap();
    let _ = std::fs::remove_file(&file);
    let b = &run.basic_method[0];
    assert_eq!(b.output, "seat_acc_Wk");
    assert_eq!(b.governing(), Governing::Rms);
    assert!(b.check.crest_factor.unwrap() < 6.0);
    let (v, sg) = (
        run.statistic("seat_acc_Wk", "vdv").unwrap().interval,
        run.statistic("seat_acc_Wk", "sigma").unwrap().interval,
    );
    let t4 = b.duration_s.powf(0.25);
    let g = 3f64.powf(0.25);
    assert!(
        v.lower / (sg.upper * t4) <= g && g <= v.upper / (sg.lower * t4),
        "{v:?} {sg:?}"
    );
    assert!(run.to_string().contains("basic     seat_acc_Wk: crest factor"));
    // the command line: Monte Carlo a_w, VDV and damage rate beside the analytic values
    let out = std::process::Command::new(crate::common::cli_bin())
        .args(["analyze", path.to_str().unwrap(), "--monte-carlo", "10", "--json"])
        .output_serial()
        .unwrap();
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let j: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    let mc = &j["monte_carlo_verdicts"];
    let quantities: Vec<&str> = mc["values"]
        .as_array()
        .unwrap()
        .iter()
        .map(|v| v["quantity"].as_str().unwrap())
        .collect();
    assert_eq!(quantities, ["damage rate", "a_w", "VDV over T"], "{mc}");
    for v in mc["values"].as_array().unwrap() {
        assert!(
            v["analytic"].as_f64().unwrap() > 0.0 && v["estimate"].as_f64().unwrap() > 0.0,
            "{v}"
        );
    }
    assert_eq!(mc["basic_method"][0]["check"]["governing"], "rms");
}
