//! Measured records: the readers (CSV, HDF5, WAV), the digital ISO 8041 weighting, the streamed ISO 2631-1
//! exposure, the record's Welch density and band values, rainflow fatigue of a record beside the spectral
//! methods, the expected IRI of a road spectrum, and the refusals of bad records.
//!
//! Every expected value is independent of the code under test: the analytic weighting is written out here
//! from ISO 2631-1:1997 Annex A (checked against the printed Table 3), the exposure values of sinusoids are
//! closed forms, the Welch band values of an AR(1) record are the closed-form integral of its spectrum, the
//! rainflow counts are those of ASTM E1049-85 Fig. 6, and the expected IRI values come from an independent
//! quadrature and Lyapunov solution (Python, scipy).

use crate::common::tolerance::{
    EXACT, IRI_EXPECTED, ISO8041_OWN_DB, ISO8041_OWN_PHASE_DEG, MINER_BLOCK_BOUNDARY, NOISE_WEIGHTING_REALISATION,
    PRINTED_3_DIGITS, RECORD_SINE_TRANSIENT, RECORD_START_OVERSHOOT, RUNNING_RMS_SAMPLED, WAV_FLOAT32,
    WELCH_WINDOW_BIAS,
};
use nalgebra::Complex;
use rand::{RngExt, SeedableRng};
use std::f64::consts::{PI, SQRT_2, TAU};
use std::path::{Path, PathBuf};
use stochvib::comfort::Weighting;
use stochvib::fatigue::SnReferencePoint;
use stochvib::record::{
    evaluate_exposure, evaluate_fatigue, open_record, AxisAssignment, BandAnalyzer, Channel, DigitalWeighting,
    ExposureOptions, FatigueOptions, MeanStressCorrection, RecordInfo, RecordOptions, RecordReader, TimeBase,
    MAX_BAND_ERROR_DB,
};
use stochvib::units::Dim;

/// A fresh directory for one test's files.
fn scratch(name: &str) -> PathBuf {
    crate::common::scratch_dir("records", name)
}

/// ISO 2631-1:1997 Annex A, written out independently of the crate: W = K·H_h·H_l·H_t·H_s with
/// s = i2πf, H_h = s²/(s² + ω₁s/Q₁ + ω₁²), H_l = ω₂²/(s² + ω₂s/Q₂ + ω₂²), Q₁ = Q₂ = 1/√2,
/// H_t = (1 + s/ω₃)/(1 + s/(Q₄ω₄) + s²/ω₄²), H_s = (s² + sω₅/Q₅ + ω₅²)/(s² + sω₆/Q₆ + ω₆²);
/// parameters of Table A.1 (f in Hz; `None` for a factor that is 1).
fn analytic(w: &str, f_hz: f64) -> Complex<f64> {
    #[allow(clippy::type_complexity)]
    let (f1, f2, f3, f4, q4, step): (f64, f64, Option<f64>, Option<f64>, f64, Option<(f64, f64, f64, f64)>) = match w {
        "Wk" => (0.4, 100.0, Some(12.5), Some(12.5), 0.63, Some((2.37, 0.91, 3.35, 0.91))),
        "Wd" => (0.4, 100.0, Some(2.0), Some(2.0), 0.63, None),
        "Wf" => (0.08, 0.63, None, Some(0.25), 0.86, Some((0.0625, 0.80, 0.10, 0.80))),
        _ => unreachable!(),
    };
    let s = Complex::new(0.0, TAU * f_hz);
    let (w1, w2) = (TAU * f1, TAU * f2);
    let q = 1.0 / SQRT_2;
    let hh = s * s / (s * s + s * w1 / q + w1 * w1);
    let hl = Complex::new(w2 * w2, 0.0) / (s * s + s * w2 / q + w2 * w2);
    let num_t = f3.map_or(Complex::new(1.0, 0.0), |f3| 1.0 + s / (TAU * f3));
    let ht = f4.map_or(Complex::new(1.0, 0.0), |f4| {
        let w4 = TAU * f4;
        num_t / (1.0 + s / (q4 * w4) + s * s / (w4 * w4))
    });
    let hs = step.map_or(Complex::new(1.0, 0.0), |(f5, q5, f6, q6)| {
        let (w5, w6) = (TAU * f5, TAU * f6);
        (s * s + s * w5 / q5 + w5 * w5) / (s * s + s * w6 / q6 + w6 * w6)
    });
    hh * hl * ht * hs
}

/// The analytic weighting above reproduces ISO 2631-1:1997 Table 3 (×1000, at the nominal band frequencies;
/// three printed digits): Wk 418, 482, 967, 1036, 769, 405, 186 at 0.5, 1, 4, 8, 16, 31.5, 63 Hz; Wd 1011,
/// 890, 512, 253 at 1, 2, 4, 8 Hz; Wf 695, 1006, 854, 224 at 0.1, 0.16, 0.25, 0.5 Hz.
#[test]
fn the_test_weighting_reproduces_the_printed_table() {
    let table: &[(&str, f64, f64)] = &[
        ("Wk", 0.5, 418.0),
        ("Wk", 1.0, 482.0),
        ("Wk", 4.0, 967.0),
        ("Wk", 8.0, 1036.0),
        ("Wk", 16.0, 769.0),
        ("Wk", 31.5, 405.0),
        ("Wk", 63.0, 186.0),
        ("Wd", 1.0, 1011.0),
        ("Wd", 2.0, 890.0),
        ("Wd", 4.0, 512.0),
        ("Wd", 8.0, 253.0),
        ("Wf", 0.1, 695.0),
        ("Wf", 0.16, 1006.0),
        ("Wf", 0.25, 854.0),
        ("Wf", 0.5, 224.0),
    ];
    for &(w, f, printed) in table {
        let v = 1000.0 * analytic(w, f).norm();
        // the printed value is rounded to the unit (×1000): |v − printed| ≤ 0.5 plus the last digit's rounding
        assert!(
            (v - printed).abs() <= 0.5 + PRINTED_3_DIGITS * printed,
            "{w} at {f} Hz: {v} vs {printed}"
        );
        let crate_value = 1000.0 * Weighting::parse(w).unwrap().magnitude(f);
        assert!(
            (crate_value - v).abs() < EXACT * 1e3 * v.max(1.0),
            "{w} at {f} Hz: crate {crate_value} vs {v}"
        );
    }
}

/// Amplitude and phase of the steady response of the digital weighting to a unit sine at `f_hz`: the sine is
/// filtered for 25 s (more than 40 decay times of the slowest pole, the 0.4 Hz high pass: e^{−ω₁t/(2Q₁)}
/// < 1e-18), then projected onto sin and cos over a whole number of periods of at least 2 s.
fn sine_response(filter: &DigitalWeighting, fs: f64, f_hz: f64) -> Complex<f64> {
    let settle = (25.0 * fs) as usize;
    let periods = (2.0 * f_hz).ceil().max(4.0);
    let n = (periods * fs / f_hz).round() as usize;
    let x: Vec<f64> = (0..settle + n).map(|i| (TAU * f_hz * i as f64 / fs).sin()).collect();
    let mut y = vec![0.0; x.len()];
    let mut state = filter.state();
    filter.filter(&mut state, &x, &mut y);
    // y ≈ Re(H e^{iωt})·(−i)… : for x = sin ωt, y = |H| sin(ωt + φ) = a sin ωt + b cos ωt, H = a + ib
    let (mut a, mut b) = (0.0, 0.0);
    for (i, yi) in y.iter().enumerate().skip(settle) {
        let t = TAU * f_hz * i as f64 / fs;
        a += yi * t.sin();
        b += yi * t.cos();
    }
    // a whole number of samples per sum only approximately spans whole periods: n samples span `periods`
    // periods to within one sample, so the projection error is O(1/n)
    Complex::new(2.0 * a / n as f64, 2.0 * b / n as f64)
}

/// The digital weighting (ISO 8041: bilinear sections prewarped at their poles), driven by sinusoids at the
/// exact one-third-octave centres 1000·10^{k/10} Hz from 0.5 to 80 Hz at f_s = 1 kHz, has the analytic
/// magnitude within `ISO8041_OWN_DB` (our own tolerance; the research computation of the same design gives at
/// most 0.12 dB, at 79.4 Hz) and within the 1 dB the toolkit accepts per band (`MAX_BAND_ERROR_DB`, inside
/// the ISO 8041 limits of about ±1 dB in the main range), and the analytic phase within
/// `ISO8041_OWN_PHASE_DEG`.
#[test]
fn digital_weighting_of_sinusoids_matches_the_analytic_weighting() {
    let fs = 1000.0;
    for name in ["Wk", "Wd"] {
        let filter = DigitalWeighting::new(Weighting::parse(name).unwrap(), fs).unwrap();
        for k in -33..=-11 {
            let f = 1000.0 * 10f64.powf(k as f64 / 10.0);
            let measured = sine_response(&filter, fs, f);
            let w = analytic(name, f);
            let db = 20.0 * (measured.norm() / w.norm()).log10();
            assert!(db.abs() < ISO8041_OWN_DB, "{name} at {f:.3} Hz: {db:+.4} dB");
            assert!(db.abs() < MAX_BAND_ERROR_DB);
            let phase = (measured / w).arg().to_degrees();
            assert!(
                phase.abs() < ISO8041_OWN_PHASE_DEG,
                "{name} at {f:.3} Hz: phase error {phase:.3}°"
            );
            // the filter's own error report agrees with the measured one
            let row = filter.error_at(f);
            assert!(
                (row.error_db - db).abs() < 0.01,
                "{name} at {f:.3} Hz: reported {} dB",
                row.error_db
            );
        }
    }
}

/// Writes a CSV record `time [s], <names with units>` of `n` samples at `fs`.
fn write_csv(path: &Path, header: &str, fs: f64, n: usize, row: impl Fn(f64) -> Vec<f64>) {
    use std::io::Write;
    let mut w = std::io::BufWriter::new(std::fs::File::create(path).unwrap());
    writeln!(w, "{header}").unwrap();
    for i in 0..n {
        let t = i as f64 / fs;
        let vals: Vec<String> = row(t).iter().map(|v| format!("{v:?}")).collect();
        writeln!(w, "{t:?},{}", vals.join(",")).unwrap();
    }
}

fn rel(a: f64, b: f64) -> f64 {
    (a - b).abs() / b.abs()
}

/// Exposure of sinusoids through the weighting: a seat record of x = A_x sin(2π·2 Hz·t) and
/// z = A_z sin(2π·4 Hz·t), T = 120 s at 1 kHz, exposure 8 h. With B = |W(f)|·A the weighted amplitude
/// (|W| from the analytic weighting above) the closed forms are: a_w = B/√2, VDV = B·(3T/8)^{1/4}
/// (∫sin⁴ = 3T/8 over whole periods), crest factor √2, linear running r.m.s. with τ = 1 s: MTVV = B/√2
/// (a whole number of periods in τ), A(8) = k·a_w·√(8 h/8 h) with k = 1.4 (x) and 1 (z) (Directive
/// 2002/44/EC Annex B), daily VDV = k·VDV·(T_exp/T)^{1/4}, comfort vector sum √(a_wx² + a_wz²).
/// The filter starts at rest, so its start-up transient (decaying within a few seconds) is the only
/// departure: `RECORD_SINE_TRANSIENT` for the integrals. Maxima (peak, MTVV) see the transient itself: Wd
/// at 2 Hz overshoots the steady amplitude by 14 % in its first period, Wk at 4 Hz by 2.6 % (scipy, the same
/// analog weighting by the bilinear transform, started at rest), so crest factor and MTVV are checked on z
/// only, between the steady closed form and `RECORD_START_OVERSHOOT` above it.
#[test]
fn exposure_of_sinusoids_is_the_closed_form() {
    let dir = scratch("sine");
    let file = dir.join("seat.csv");
    let (fs, t, ax, az) = (1000.0, 120.0, 0.8, 1.2);
    write_csv(
        &file,
        "time [s],seat_x [m/s^2],seat_z [m/s^2]",
        fs,
        (t * fs) as usize,
        |t| vec![ax * (TAU * 2.0 * t).sin(), az * (TAU * 4.0 * t).sin()],
    );
    let mut reader = open_record(&file, &RecordOptions::default()).unwrap();
    let options = ExposureOptions {
        axes: vec![
            AxisAssignment::parse("seat_x=seat-surface:x").unwrap(),
            AxisAssignment::parse("seat_z=seat-surface:z").unwrap(),
        ],
        exposure_s: Some(8.0 * 3600.0),
        ..ExposureOptions::default()
    };
    let e = evaluate_exposure(reader.as_mut(), &options).unwrap();
    assert_eq!(e.samples, (t * fs) as usize);
    assert!(rel(e.duration_s, t) < EXACT);
    let bx = analytic("Wd", 2.0).norm() * ax;
    let bz = analytic("Wk", 4.0).norm() * az;
    for (axis, b, k) in [(&e.axes[0], bx, 1.4), (&e.axes[1], bz, 1.0)] {
        let m = &axis.metrics;
        let what = &axis.channel;
        assert!(
            rel(m.a_w, b / SQRT_2) < RECORD_SINE_TRANSIENT,
            "{what}: a_w {} vs {}",
            m.a_w,
            b / SQRT_2
        );
        let vdv = b * (3.0 * t / 8.0).powf(0.25);
        assert!(
            rel(m.vdv, vdv) < RECORD_SINE_TRANSIENT,
            "{what}: VDV {} vs {vdv}",
            m.vdv
        );
        if what == "seat_z" {
            // maxima see the start-up transient: between the steady value and RECORD_START_OVERSHOOT above
            let within = |v: f64, steady: f64| {
                v > steady * (1.0 - RECORD_SINE_TRANSIENT) && v < steady * (1.0 + RECORD_START_OVERSHOOT)
            };
            assert!(
                within(m.peak / m.a_w, SQRT_2),
                "{what}: crest factor {}",
                m.peak / m.a_w
            );
            assert!(
                within(m.mtvv.unwrap(), b / SQRT_2),
                "{what}: MTVV {:?} vs {}",
                m.mtvv,
                b / SQRT_2
            );
        }
        let h = axis.health.unwrap();
        assert_eq!(h.k, k);
        assert!(
            rel(h.a8, k * b / SQRT_2) < RECORD_SINE_TRANSIENT,
            "{what}: A(8) {}",
            h.a8
        );
        let daily = k * vdv * (8.0 * 3600.0 / t).powf(0.25);
        assert!(
            rel(h.daily_vdv, daily) < RECORD_SINE_TRANSIENT,
            "{what}: daily VDV {}",
            h.daily_vdv
        );
        assert!(axis.realisation.max_error_db < ISO8041_OWN_DB);
    }
    let comfort = e.comfort.as_ref().unwrap();
    let av = ((bx * bx + bz * bz) / 2.0).sqrt();
    assert!(
        rel(comfort.a_v, av) < RECORD_SINE_TRANSIENT,
        "vector sum {} vs {av}",
        comfort.a_v
    );
    // the verdict's A(8) is the larger of 1.4·a_wx and a_wz
    let verdict = e.verdict.as_ref().unwrap();
    let a8 = (1.4 * bx / SQRT_2).max(bz / SQRT_2);
    assert!(
        rel(verdict.a8, a8) < RECORD_SINE_TRANSIENT,
        "verdict A(8) {} vs {a8}",
        verdict.a8
    );
    // the band of the 4 Hz sine holds the z signal's mean square
    let bands = e.axes[1].bands.as_ref().unwrap();
    let b4 = bands.iter().find(|b| (b.band.centre_hz - 3.981).abs() < 0.01).unwrap();
    assert!(
        rel(b4.rms, bz / SQRT_2) < WELCH_WINDOW_BIAS,
        "4 Hz band {} vs {}",
        b4.rms,
        bz / SQRT_2
    );
    std::fs::remove_dir_all(&dir).unwrap();
}

/// Which metric governs a measured record (ISO 2631-1:1997 6.3.3, thresholds 9, 1.5, 1.75): a steady 4 Hz
/// sine of amplitude B through Wk has crest factor √2, MTVV/a_w = 1 and VDV/(a_w T^¼) = √2·(3/8)^¼ = 1.107
/// (∫sin⁴ = 3T/8), all below their thresholds: the r.m.s. governs, the basic method suffices. The same sine
/// as a 1 s burst in a 64 s record (a second axis: feet, z, also Wk): a_w = (B/√2)·√(1/64) = B/(8√2); the linear 1 s running r.m.s. reaches
/// B/√2, so MTVV/a_w = 8 (5.3 × its threshold); crest factor B/a_w = 8√2 = 11.3 (1.26 ×); VDV = B(3/8)^¼ over
/// T = 64 s, T^¼ = 2√2, so VDV/(a_w T^¼) = 4·(3/8)^¼ = 3.13 (1.79 ×): the MTVV governs. (B |W_k(4 Hz)| cancels
/// from every ratio; the weighting's start-up transient moves them by a few per cent, far from every threshold.)
#[test]
fn the_governing_metric_of_a_record_is_named() {
    let dir = scratch("governing");
    let file = dir.join("seat.csv");
    let fs = 1000.0;
    write_csv(
        &file,
        "time [s],steady [m/s^2],burst [m/s^2]",
        fs,
        (64.0 * fs) as usize,
        |t| {
            let s = (TAU * 4.0 * t).sin();
            vec![s, if (30.0..31.0).contains(&t) { s } else { 0.0 }]
        },
    );
    let mut reader = open_record(&file, &RecordOptions::default()).unwrap();
    let options = ExposureOptions {
        axes: vec![
            AxisAssignment::parse("steady=seat-surface:z").unwrap(),
            AxisAssignment::parse("burst=feet:z").unwrap(),
        ],
        ..ExposureOptions::default()
    };
    let e = evaluate_exposure(reader.as_mut(), &options).unwrap();
    let (steady, burst) = (&e.axes[0].metrics.check, &e.axes[1].metrics.check);
    assert!(steady.basic_method_sufficient, "{steady:?}");
    assert_eq!(steady.governing, stochvib::comfort::Governing::Rms);
    assert!(!burst.basic_method_sufficient, "{burst:?}");
    assert_eq!(burst.governing, stochvib::comfort::Governing::Mtvv, "{burst:?}");
    // the report names it
    let table = stochvib::report::record_report::axis_table(&e.axes).markdown();
    assert!(
        table.contains("governs") && table.contains("MTVV") && table.contains("r.m.s. (basic method)"),
        "{table}"
    );
    std::fs::remove_dir_all(&dir).unwrap();
}

/// Motion sickness: a vertical sine of amplitude A at 0.25 Hz, T = 800 s at 20 Hz, evaluated with Wf: a_w =
/// |Wf(0.25 Hz)|·A/√2 and MSDV = a_w·√T (ISO 2631-1 clause 9); the record has no time column, its rate is
/// stated.
#[test]
fn msdv_of_a_slow_sine_is_the_closed_form() {
    use std::io::Write;
    let dir = scratch("msdv");
    let file = dir.join("deck.csv");
    let (fs, t, a) = (20.0, 800.0, 0.5);
    let mut w = std::io::BufWriter::new(std::fs::File::create(&file).unwrap());
    writeln!(w, "# a ship's deck, vertical\nheave [m/s^2]").unwrap();
    for i in 0..(t * fs) as usize {
        writeln!(w, "{:?}", a * (TAU * 0.25 * i as f64 / fs).sin()).unwrap();
    }
    drop(w);
    let options = RecordOptions {
        sample_rate_hz: Some(fs),
        ..RecordOptions::default()
    };
    let mut reader = open_record(&file, &options).unwrap();
    let e = evaluate_exposure(
        reader.as_mut(),
        &ExposureOptions {
            motion_sickness: vec!["heave".into()],
            ..ExposureOptions::default()
        },
    )
    .unwrap();
    let m = &e.motion_sickness[0].metrics;
    let aw = analytic("Wf", 0.25).norm() * a / SQRT_2;
    assert!(rel(m.a_w, aw) < RECORD_SINE_TRANSIENT, "a_w {} vs {aw}", m.a_w);
    assert!(
        rel(m.msdv, aw * t.sqrt()) < RECORD_SINE_TRANSIENT,
        "MSDV {} vs {}",
        m.msdv,
        aw * t.sqrt()
    );
    assert_eq!(e.motion_sickness[0].weighting, Weighting::Wf);
    std::fs::remove_dir_all(&dir).unwrap();
}

/// Welch band values of a generated record against its known spectrum. The record is an AR(1) process
/// x_n = φx_{n−1} + e_n, e_n ~ N(0, σ²) at f_s, whose one-sided density is G(f) = (2σ²/f_s)/(1 − 2φ cos θ + φ²),
/// θ = 2πf/f_s, so a band's mean square is the closed form
/// ```text
/// ∫_{f₁}^{f₂} G df = (σ²/π)·[F(θ₂) − F(θ₁)],   F(θ) = 2/(1 − φ²)·atan((1 + φ)/(1 − φ)·tan(θ/2)).
/// ```
/// Bound: each bin's estimate is ≈ G·χ²_ν/ν with Welch's ν = 2K²/(K + 2(K−1)/36) (Hann, 50 % overlap);
/// a band value is a weighted mean of bins, whose relative s.d. is at most that of one bin, √(2/ν). With
/// K ≈ 4095 segments √(2/ν) = 0.0227; 6 s.d. (a one-sided Gaussian tail of 1e-9 per band, 3e-8 over the 15
/// bands with the χ² skewness √(8/ν) = 0.03 included generously) plus the leakage and proportional-bin bias
/// (`WELCH_WINDOW_BIAS`) make a false failure ≤ 1e-6. Seeded.
#[test]
fn welch_band_values_of_an_ar1_record_match_its_spectrum() {
    let (fs, phi, sigma, m) = (1000.0, 0.9, 1.0, 1024usize);
    let n = m / 2 * 4096;
    let mut rng = rand::rngs::Xoshiro256PlusPlus::seed_from_u64(32);
    let mut x = Vec::with_capacity(n);
    let mut prev = 0.0;
    for i in 0..n + 2000 {
        let e: f64 = rng.sample(rand_distr::StandardNormal);
        prev = phi * prev + sigma * e;
        if i >= 2000 {
            x.push(prev);
        }
    }
    let mut analyzer = BandAnalyzer::new(m, 1.0 / fs).unwrap();
    for block in x.chunks(10_000) {
        analyzer.push(block).unwrap();
    }
    let bands = stochvib::comfort::bands_covering(stochvib::comfort::BandFraction::ThirdOctave, 8.0, 200.0).unwrap();
    let values = analyzer.finish(&bands).unwrap().unwrap();
    let big_f = |theta: f64| 2.0 / (1.0 - phi * phi) * ((1.0 + phi) / (1.0 - phi) * (theta / 2.0).tan()).atan();
    let k = ((n - m) / (m / 2) + 1) as f64;
    let nu = 2.0 * k * k / (k + 2.0 * (k - 1.0) / 36.0);
    let bound = 6.0 * (2.0 / nu).sqrt() + WELCH_WINDOW_BIAS;
    assert_eq!(values.len(), 15); // 7.94 to 199.5 Hz
    for v in &values {
        let (t1, t2) = (TAU * v.band.lower_hz / fs, TAU * v.band.upper_hz / fs);
        let expected = sigma * sigma / PI * (big_f(t2) - big_f(t1));
        let got = v.rms * v.rms;
        assert!(
            rel(got, expected) < bound,
            "band {}: {got} vs {expected} (bound {bound})",
            v.band.label()
        );
        // IEC 61260-1 base-10 edges: f_m·10^{∓1/20}
        assert!(rel(v.band.upper_hz / v.band.lower_hz, 10f64.powf(0.1)) < EXACT);
    }
}

/// The three readers give back what was written: a CSV with a time column in ms and units mm/s², gn and
/// m/s²; a CSV with `;` and decimal commas, no time column, a stated rate and a unit given for a bare
/// column; HDF5 datasets with `unit` and `sample_rate` attributes; WAV float and 16-bit PCM with a stated
/// full scale. Values are converted to SI (mm/s² × 1e-3, gn × 9.80665 exactly by the CGPM's definition).
#[test]
fn readers_round_trip() {
    let dir = scratch("readers");
    let n = 300;
    let sig = |i: usize| ((i * 37 % 101) as f64 - 50.0) / 7.0;
    // CSV, comma, time column in ms
    let csv = dir.join("a.csv");
    write_csv(&csv, "time [ms],a [mm/s^2],b [gn],c [m/s^2]", 1.0, n, |t| {
        let i = t as usize;
        vec![sig(i), sig(i + 1), sig(i + 2)]
    });
    let all = read_all(&csv, &RecordOptions::default());
    assert_eq!(all.0.format, "CSV");
    assert!(
        rel(all.0.sample_rate_hz, 1000.0) < EXACT,
        "rate {}",
        all.0.sample_rate_hz
    );
    assert!(matches!(all.0.time_base, TimeBase::TimeColumn(_)));
    for i in 0..n {
        assert!((all.1[0][i] - sig(i) * 1e-3).abs() < EXACT);
        assert!((all.1[1][i] - sig(i + 1) * 9.80665).abs() < EXACT * 10.0);
        assert_eq!(all.1[2][i], sig(i + 2));
    }
    // CSV, semicolon, decimal comma, stated rate and unit
    let semi = dir.join("b.csv");
    let mut text = String::from("strain [ustrain];stress\n");
    for i in 0..n {
        text += &format!(
            "{};{}\n",
            format!("{:?}", sig(i)).replace('.', ","),
            format!("{:?}", sig(i + 5)).replace('.', ",")
        );
    }
    std::fs::write(&semi, text).unwrap();
    let opts = RecordOptions {
        sample_rate_hz: Some(512.0),
        units: vec![("stress".into(), "MPa".into())],
        decimal_comma: true,
        ..RecordOptions::default()
    };
    let b = read_all(&semi, &opts);
    assert_eq!(b.0.time_base, TimeBase::Stated);
    assert_eq!(b.0.channels[1].dim, Dim::new(-1, 1, -2));
    for i in 0..n {
        assert!((b.1[0][i] - sig(i) * 1e-6).abs() < EXACT * 1e-3);
        assert!((b.1[1][i] - sig(i + 5) * 1e6).abs() < EXACT * 1e6);
    }
    // HDF5
    let h5 = dir.join("c.h5");
    write_h5_acceleration(&h5, &(0..n).map(sig).collect::<Vec<_>>(), 250.0);
    let c = {
        let _serial = crate::common::hdf5_serial();
        read_all(&h5, &RecordOptions::default())
    };
    assert_eq!(
        (c.0.format, c.0.sample_rate_hz, c.0.samples_hint),
        ("HDF5", 250.0, Some(n))
    );
    assert_eq!(c.1[0], (0..n).map(sig).collect::<Vec<_>>());
    // WAV, float and 16-bit PCM, full scale 50 m/s^2
    for (bits, float) in [(32u16, true), (16, false)] {
        let wav = dir.join(format!("d{bits}.wav"));
        let spec = hound::WavSpec {
            channels: 2,
            sample_rate: 2000,
            bits_per_sample: bits,
            sample_format: if float {
                hound::SampleFormat::Float
            } else {
                hound::SampleFormat::Int
            },
        };
        let mut w = hound::WavWriter::create(&wav, spec).unwrap();
        for i in 0..n {
            for ch in 0..2 {
                let v = sig(i + ch) / 10.0;
                if float {
                    w.write_sample(v as f32).unwrap();
                } else {
                    w.write_sample((v * 32767.0 / 8.0) as i16).unwrap();
                }
            }
        }
        w.finalize().unwrap();
        let opts = RecordOptions {
            full_scale: Some("50 m/s^2".into()),
            channel_names: vec!["x".into(), "z".into()],
            ..RecordOptions::default()
        };
        let d = read_all(&wav, &opts);
        assert_eq!((d.0.format, d.0.sample_rate_hz), ("WAV", 2000.0));
        assert_eq!(d.0.channels[1].name, "z");
        for i in 0..n {
            for ch in 0..2 {
                let v = sig(i + ch) / 10.0;
                let expected = if float {
                    v as f32 as f64 * 50.0
                } else {
                    ((v * 32767.0 / 8.0) as i16) as f64 / 32768.0 * 50.0
                };
                let tol = if float { WAV_FLOAT32 * 50.0 } else { EXACT * 50.0 };
                assert!((d.1[ch][i] - expected).abs() <= tol, "{bits} bit, ch {ch}, frame {i}");
            }
        }
    }
    std::fs::remove_dir_all(&dir).unwrap();
}

/// An HDF5 record of one acceleration channel `z` in m/s² at `rate_hz` (the `unit` and `sample_rate`
/// attributes of the reader's layout).
fn write_h5_acceleration(path: &Path, data: &[f64], rate_hz: f64) {
    let _serial = crate::common::hdf5_serial();
    let f = hdf5::File::create(path).unwrap();
    let ds = f.new_dataset_builder().with_data(data).create("z").unwrap();
    let unit: hdf5::types::VarLenUnicode = "m/s^2".parse().unwrap();
    ds.new_attr::<hdf5::types::VarLenUnicode>()
        .create("unit")
        .unwrap()
        .write_scalar(&unit)
        .unwrap();
    ds.new_attr::<f64>()
        .create("sample_rate")
        .unwrap()
        .write_scalar(&rate_hz)
        .unwrap();
}

/// A dataset `z` at 1000 Hz whose `unit` attribute is written by `unit` (fixed-length ASCII, a one-element
/// array of variable-length strings, a number: as h5py's `bytes`, MATLAB's `h5writeatt` or a list writes it).
fn write_h5_with_unit(path: &Path, unit: impl FnOnce(&hdf5::Dataset)) {
    let _serial = crate::common::hdf5_serial();
    let f = hdf5::File::create(path).unwrap();
    let data: Vec<f64> = (0..4000).map(|i| (0.03 * i as f64).sin()).collect();
    let ds = f.new_dataset_builder().with_data(&data).create("z").unwrap();
    ds.new_attr::<f64>()
        .create("sample_rate")
        .unwrap()
        .write_scalar(&1000.0)
        .unwrap();
    unit(&ds);
}

/// The options of `exposure` follow the scenario's rules: a daily exposure from 1 min to 24 h (30 s and 10⁹⁰ h
/// were evaluated, the latter to A(8) = 2.4·10⁴⁴ m/s²), one channel per location and axis (two on the seat's
/// z read "invalid parameter `values` = SeatSurface Z"); each refused naming the flag.
#[test]
fn exposure_options_outside_a_day_or_repeating_an_axis_are_refused_by_flag() {
    let dir = scratch("options");
    let file = dir.join("seat.csv");
    write_csv(&file, "time [s],x [m/s^2],z [m/s^2]", 1000.0, 4000, |t| {
        vec![0.3 * (TAU * 2.0 * t).sin(), (TAU * 4.0 * t).sin()]
    });
    let run = |options: ExposureOptions| {
        let mut reader = open_record(&file, &RecordOptions::default()).unwrap();
        evaluate_exposure(reader.as_mut(), &options).map(|_| ())
    };
    for (t, why) in [(30.0, "less than 1 min"), (1e90 * 3600.0, "at most 24 h")] {
        let options = ExposureOptions {
            exposure_s: Some(t),
            ..ExposureOptions::default()
        };
        let e = run(options).unwrap_err();
        assert!(
            matches!(&e, stochvib::Error::InvalidParameter { name, .. } if name == "--exposure"),
            "{e}"
        );
        assert!(e.to_string().contains(why), "{e}");
    }
    for t in [60.0, 24.0 * 3600.0] {
        let options = ExposureOptions {
            exposure_s: Some(t),
            ..ExposureOptions::default()
        };
        run(options).unwrap();
    }
    let options = ExposureOptions {
        axes: vec![
            AxisAssignment::parse("z=seat-surface:z").unwrap(),
            AxisAssignment::parse("x=seat-surface:z").unwrap(),
        ],
        ..ExposureOptions::default()
    };
    let e = run(options).unwrap_err().to_string();
    assert!(
        e.contains("--axis") && e.contains("x=seat-surface:z") && e.contains("already given to channel `z`"),
        "{e}"
    );
    std::fs::remove_dir_all(&dir).unwrap();
}

/// A record's unit written as fixed-length ASCII (null-padded, 8 bytes for `m/s^2`) or as a one-element array
/// of variable-length UTF-8 is the unit (it read "no `unit` attribute"); a number is refused naming the
/// dataset's attribute. Expected: the written text, m/s² (dimension of an acceleration).
#[test]
fn hdf5_units_written_as_fixed_length_or_one_element_text_are_read() {
    use hdf5::types::{FixedAscii, VarLenUnicode};
    let dir = scratch("h5-units");
    let fixed = dir.join("fixed.h5");
    write_h5_with_unit(&fixed, |ds| {
        let u = FixedAscii::<8>::from_ascii(b"m/s^2").unwrap();
        ds.new_attr::<FixedAscii<8>>()
            .create("unit")
            .unwrap()
            .write_scalar(&u)
            .unwrap();
    });
    let one = dir.join("one.h5");
    write_h5_with_unit(&one, |ds| {
        let u: VarLenUnicode = "m/s^2".parse().unwrap();
        ds.new_attr::<VarLenUnicode>()
            .shape(1)
            .create("unit")
            .unwrap()
            .write(&[u])
            .unwrap();
    });
    for file in [&fixed, &one] {
        let (info, all) = read_all(file, &RecordOptions::default());
        assert_eq!(info.channels[0].dim, Dim::ACCELERATION, "{}", file.display());
        assert_eq!(all[0].len(), 4000);
        assert!(matches!(info.time_base, TimeBase::Attribute(_)));
    }
    let number = dir.join("number.h5");
    write_h5_with_unit(&number, |ds| {
        ds.new_attr::<i64>().create("unit").unwrap().write_scalar(&5).unwrap();
    });
    let e = open_record(&number, &RecordOptions::default())
        .map(|_| ())
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("number.h5") && e.contains("attribute unit") && e.contains("not text"),
        "{e}"
    );
    std::fs::remove_dir_all(&dir).unwrap();
}

/// Every sample of every channel, read in blocks of 64.
fn read_all(path: &Path, options: &RecordOptions) -> (RecordInfo, Vec<Vec<f64>>) {
    let mut r = open_record(path, options).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    let info = r.info().clone();
    let mut all = vec![Vec::new(); info.channels.len()];
    let mut block = vec![Vec::new(); info.channels.len()];
    while r.read_block(&mut block, 64).unwrap() > 0 {
        for (a, b) in all.iter_mut().zip(&block) {
            a.extend_from_slice(b);
        }
    }
    (info, all)
}

/// The error text of opening and evaluating `text` as a CSV record.
fn refusal(dir: &Path, name: &str, text: &str, options: &RecordOptions) -> String {
    let file = dir.join(name);
    std::fs::write(&file, text).unwrap();
    let result = open_record(&file, options).and_then(|mut r| {
        let opts = ExposureOptions::default();
        evaluate_exposure(r.as_mut(), &opts).map(|_| ())
    });
    let e = result.expect_err(name).to_string();
    assert!(e.contains(name), "{name}: the error does not name the file: {e}");
    e
}

/// Bad records are refused with the file, the line (or key) and the value: NaN, a blank field (missing
/// sample), non-monotone time, a skipped sample, a column without a unit, an ambiguous `g`, no time base,
/// an empty file, a header only, a value too large for the VDV's fourth powers, a rate too low for the
/// weighting's 80 Hz band, or so high (10⁹ Hz) that the rounded filter is no weighting; an unknown weighting
/// and axis by name.
#[test]
fn bad_records_are_refused_with_file_line_and_value() {
    let dir = scratch("bad");
    let none = RecordOptions::default();
    let rows = |f: &dyn Fn(usize) -> String| (0..40).map(f).collect::<Vec<_>>().join("\n");
    let good = |i: usize| format!("{:?},0.1,0.2,0.3", i as f64 / 1000.0);
    let head = "time [s],x [m/s^2],y [m/s^2],z [m/s^2]\n";
    let nan = format!(
        "{head}{}",
        rows(&|i| if i == 7 { "0.007,0.1,NaN,0.3".into() } else { good(i) })
    );
    let e = refusal(&dir, "nan.csv", &nan, &none);
    assert!(e.contains("line 9") && e.contains("NaN"), "{e}");
    let blank = format!(
        "{head}{}",
        rows(&|i| if i == 3 { "0.003,0.1,,0.3".into() } else { good(i) })
    );
    let e = refusal(&dir, "blank.csv", &blank, &none);
    assert!(e.contains("line 5"), "{e}");
    let back = format!(
        "{head}{}",
        rows(&|i| if i == 20 { "0.0185,0.1,0.2,0.3".into() } else { good(i) })
    );
    let e = refusal(&dir, "back.csv", &back, &none);
    assert!(e.contains("line 22") && e.contains("0.0185"), "{e}");
    let skipped = format!(
        "{head}{}",
        (0..40).filter(|&i| i != 30).map(good).collect::<Vec<_>>().join("\n")
    );
    let e = refusal(&dir, "skipped.csv", &skipped, &none);
    assert!(e.contains("line 31"), "{e}");
    let e = refusal(
        &dir,
        "nounit.csv",
        &format!("time [s],x,y [m/s^2]\n{}", rows(&|i| format!("{i}e-3,1,2"))),
        &none,
    );
    assert!(e.contains('x') && e.contains("unit"), "{e}");
    let e = refusal(
        &dir,
        "g.csv",
        &format!("time [s],z [g]\n{}", rows(&|i| format!("{i}e-3,1"))),
        &none,
    );
    assert!(e.contains("gn"), "{e}");
    let e = refusal(
        &dir,
        "notime.csv",
        &format!("z [m/s^2]\n{}", rows(&|_| "1".into())),
        &none,
    );
    assert!(e.contains("sample rate") || e.contains("sample-rate"), "{e}");
    let e = refusal(&dir, "empty.csv", "", &none);
    assert!(e.contains("empty") || e.contains("header"), "{e}");
    let e = refusal(&dir, "headonly.csv", head, &none);
    assert!(
        e.contains("no sample") || e.contains("empty") || e.contains("no row"),
        "{e}"
    );
    // 1e200 m/s²: its fourth power (1e800) is beyond f64, so the VDV could not be formed (it read
    // "invalid parameter `a_w` = NaN", no file); now the file, channel, sample, time and value
    let huge = format!(
        "{head}{}",
        rows(&|i| if i == 25 { "0.025,0.1,0.2,1e200".into() } else { good(i) })
    );
    let e = refusal(&dir, "huge.csv", &huge, &none);
    assert!(
        e.contains("`z`") && e.contains("sample 25") && e.contains("0.025 s") && e.contains("1e200"),
        "{e}"
    );
    let low = format!("{head}{}", rows(&|i| format!("{:?},0.1,0.2,0.3", i as f64 / 100.0)));
    let e = refusal(&dir, "low.csv", &low, &none);
    assert!(e.contains("80") && e.contains("lost"), "{e}");
    // 10⁹ Hz: Wk's rounded sections give no finite response at 0.5 Hz (its NaN error passed the 1 dB check
    // and the weighting table named the frequency as the sample rate); 10⁴ Hz is realised
    let e = DigitalWeighting::new(Weighting::Wk, 1e9).unwrap_err().to_string();
    assert!(e.contains("too high") && e.contains("1e9 Hz"), "{e}");
    assert!(DigitalWeighting::new(Weighting::Wk, 1e4).is_ok());
    assert!(Weighting::parse("Wq").unwrap_err().to_string().contains("Wq"));
    let e = AxisAssignment::parse("seat_z=seat-surface:up").unwrap_err().to_string();
    assert!(e.contains("--axis") && e.contains("up"), "{e}");
    std::fs::remove_dir_all(&dir).unwrap();
}

/// A stress record in MPa at a stated rate, one channel, evaluated with an S–N curve N·S_a^k = C.
fn fatigue_of(dir: &Path, name: &str, values: &[f64], k: f64, c_mpa: f64) -> stochvib::record::FatigueEvaluation {
    fatigue_with(dir, name, values, k, c_mpa, MeanStressCorrection::None, None)
}

/// As [`fatigue_of`], with a mean-stress correction and a hysteresis gate (Pa).
fn fatigue_with(
    dir: &Path,
    name: &str,
    values: &[f64],
    k: f64,
    c_mpa: f64,
    mean_stress: MeanStressCorrection,
    gate: Option<f64>,
) -> stochvib::record::FatigueEvaluation {
    let file = dir.join(name);
    let mut text = String::from("stress [MPa]\n");
    for v in values {
        text += &format!("{v:?}\n");
    }
    std::fs::write(&file, text).unwrap();
    let opts = RecordOptions {
        sample_rate_hz: Some(100.0),
        ..RecordOptions::default()
    };
    let mut r = open_record(&file, &opts).unwrap();
    // N·S_a^k = C with S_a in MPa: in Pa C·(1e6)^k; the reference point S_a = 1 MPa, N = C
    let sn = SnReferencePoint {
        k,
        amplitude: 1e6,
        cycles: c_mpa,
        endurance_limit: None,
    }
    .build()
    .unwrap();
    let options = FatigueOptions {
        channel: None,
        sn,
        sn_dim: Dim::new(-1, 1, -2),
        mean_stress,
        gate,
        segment_len: Some(8),
    };
    evaluate_fatigue(r.as_mut(), &options).unwrap()
}

/// A record shorter than the Welch segment: a `--segment` the user gave is refused naming it (with 10⁶ on a
/// 20 000-sample record the five spectral methods vanished from the table without a word); with the default
/// segment (256 samples at least) a 9-sample record is counted by rainflow and the report says why there
/// are no spectral methods.
#[test]
fn a_segment_longer_than_the_record_is_refused_or_explained() {
    let dir = scratch("fatigue-segment");
    let file = dir.join("short.csv");
    let history = [-2.0, 1.0, -3.0, 5.0, -1.0, 3.0, -4.0, 4.0, -2.0];
    let text: String = history.iter().map(|v| format!("{}\n", 10.0 * v)).collect();
    std::fs::write(&file, format!("stress [MPa]\n{text}")).unwrap();
    let evaluate = |segment_len: Option<usize>| {
        let opts = RecordOptions {
            sample_rate_hz: Some(100.0),
            ..RecordOptions::default()
        };
        let mut r = open_record(&file, &opts).unwrap();
        let sn = SnReferencePoint {
            k: 5.0,
            amplitude: 1e8,
            cycles: 2e6,
            endurance_limit: None,
        }
        .build()
        .unwrap();
        let options = FatigueOptions {
            channel: None,
            sn,
            sn_dim: Dim::new(-1, 1, -2),
            mean_stress: MeanStressCorrection::None,
            gate: None,
            segment_len,
        };
        evaluate_fatigue(r.as_mut(), &options)
    };
    let e = evaluate(Some(64)).unwrap_err().to_string();
    assert!(
        e.contains("--segment") && e.contains("64") && e.contains("9 samples"),
        "{e}"
    );
    let ev = evaluate(None).unwrap();
    assert!(ev.methods.is_empty() && ev.segments == 0);
    let text = stochvib::report::record_report::FatigueReport(ev).to_string();
    assert!(
        text.contains("no spectral methods: the record's 9 samples are fewer than one Welch segment"),
        "{text}"
    );
    std::fs::remove_dir_all(&dir).unwrap();
}

/// ASTM E1049-85 Fig. 6 (the history −2, 1, −3, 5, −1, 3, −4, 4, −2 in units of 10 MPa): ranges 3, 4, 6, 8, 9
/// with 0.5, 1.5, 0.5, 1.0, 0.5 cycles (one full cycle, six half cycles). With k = 3 and C = 1 (MPa
/// amplitudes) the Miner damage is Σ n·(10·r/2)³ = 125·(0.5·27 + 1.5·64 + 0.5·216 + 512 + 0.5·729).
#[test]
fn rainflow_of_the_astm_history_and_its_damage() {
    let dir = scratch("astm");
    let history: Vec<f64> = [-2.0, 1.0, -3.0, 5.0, -1.0, 3.0, -4.0, 4.0, -2.0]
        .iter()
        .map(|v| 10.0 * v)
        .collect();
    let e = fatigue_of(&dir, "astm.csv", &history, 3.0, 1.0);
    assert_eq!((e.full_cycles, e.half_cycles), (1, 6));
    let expected = 125.0 * (0.5 * 27.0 + 1.5 * 64.0 + 0.5 * 216.0 + 512.0 + 0.5 * 729.0);
    assert!(rel(e.damage, expected) < EXACT, "D {} vs {expected}", e.damage);
    let total: f64 = e.matrix.counts.iter().flatten().sum();
    assert_eq!(total, 4.0);
    std::fs::remove_dir_all(&dir).unwrap();
}

/// Palmgren–Miner of constant-amplitude blocks: 1e3 cycles at 100 MPa, 1e4 at 50, 1e5 at 25 (amplitudes),
/// k = 5, C = 1e15 MPa⁵: D = 1e3/1e5 + 1e4/3.2e6 + 1e5/1.024e8 = 0.0141015625 (hand formula). Where one block
/// meets the next, rainflow pairs the extremes across the junction, so up to two half cycles per junction
/// take a different range: `MINER_BLOCK_BOUNDARY`. Treating ranges as amplitudes would give 32·D.
#[test]
fn miner_damage_of_constant_amplitude_blocks() {
    let dir = scratch("miner");
    let mut v = Vec::new();
    for (n, s) in [(1000, 100.0), (10_000, 50.0), (100_000, 25.0)] {
        for _ in 0..n {
            v.push(s);
            v.push(-s);
        }
    }
    let e = fatigue_of(&dir, "blocks.csv", &v, 5.0, 1e15);
    assert!(rel(e.damage, 0.0141015625) < MINER_BLOCK_BOUNDARY, "D {}", e.damage);
    std::fs::remove_dir_all(&dir).unwrap();
}

/// A record held in memory, served in blocks at 1 kHz: one stress channel in MPa ([`MemoryRecord::new`]) or
/// acceleration channels in m/s² ([`MemoryRecord::accelerations`]).
struct MemoryRecord {
    info: RecordInfo,
    samples: Vec<Vec<f64>>,
    pos: usize,
}

impl MemoryRecord {
    fn new(samples: Vec<f64>) -> Self {
        let stress = Channel {
            name: "stress".into(),
            unit: "MPa".into(),
            to_si: 1e6,
            dim: Dim::new(-1, 1, -2),
        };
        Self::with(vec![(stress, samples)])
    }

    fn accelerations(channels: Vec<(&str, Vec<f64>)>) -> Self {
        let channel = |name: &str| Channel {
            name: name.into(),
            unit: "m/s^2".into(),
            to_si: 1.0,
            dim: Dim::ACCELERATION,
        };
        Self::with(channels.into_iter().map(|(n, x)| (channel(n), x)).collect())
    }

    fn with(channels: Vec<(Channel, Vec<f64>)>) -> Self {
        let (channels, samples): (Vec<Channel>, Vec<Vec<f64>>) = channels.into_iter().unzip();
        MemoryRecord {
            info: RecordInfo {
                source: PathBuf::from("generated"),
                format: "generated",
                sample_rate_hz: 1000.0,
                time_base: TimeBase::Stated,
                channels,
                samples_hint: Some(samples[0].len()),
            },
            samples,
            pos: 0,
        }
    }
}

impl RecordReader for MemoryRecord {
    fn info(&self) -> &RecordInfo {
        &self.info
    }

    fn read_block(&mut self, out: &mut [Vec<f64>], max: usize) -> stochvib::Result<usize> {
        let n = max.min(self.samples[0].len() - self.pos);
        for ((o, x), c) in out.iter_mut().zip(&self.samples).zip(&self.info.channels) {
            o.clear();
            o.extend(x[self.pos..self.pos + n].iter().map(|v| v * c.to_si));
        }
        self.pos += n;
        Ok(n)
    }
}

/// A stationary Gaussian record of 2²² samples at 1 kHz whose one-sided density is flat from 5 to 15 Hz and
/// zero elsewhere (spectral synthesis: independent Gaussian real and imaginary parts in every bin of the
/// band, one inverse FFT), scaled to σ = 40 MPa. Seeded.
fn band_limited_gaussian(seed: u64) -> Vec<f64> {
    let n = 1usize << 22;
    let df = 1000.0 / n as f64;
    let mut x = gaussian_lines(seed, n, (0..=n / 2).filter(|&j| (5.0..15.0).contains(&(j as f64 * df))));
    let sd = (x.iter().map(|v| v * v).sum::<f64>() / n as f64).sqrt();
    x.iter_mut().for_each(|v| *v *= 40.0 / sd);
    x
}

/// n samples of Σ_k X_k e^{i2πjk/n} + conjugate (the unnormalised inverse real FFT) with independent standard
/// normal real and imaginary parts of X_k in the bins `bins` (drawn in their order), zero elsewhere. Seeded.
fn gaussian_lines(seed: u64, n: usize, bins: impl Iterator<Item = usize>) -> Vec<f64> {
    use realfft::RealFftPlanner;
    let mut rng = rand::rngs::Xoshiro256PlusPlus::seed_from_u64(seed);
    let mut spectrum = vec![realfft::num_complex::Complex::new(0.0, 0.0); n / 2 + 1];
    for k in bins {
        spectrum[k] = realfft::num_complex::Complex::new(
            rng.sample(rand_distr::StandardNormal),
            rng.sample(rand_distr::StandardNormal),
        );
    }
    let mut x = vec![0.0; n];
    RealFftPlanner::<f64>::new()
        .plan_fft_inverse(n)
        .process(&mut spectrum, &mut x)
        .unwrap();
    x
}

/// Rainflow life of a long Gaussian record against the five spectral methods computed from the record's own
/// Welch density: a band-limited Gaussian record (flat 5–15 Hz, α₂ = m₂/√(m₀m₄) = 0.881), 4.2·10⁶ samples
/// (≈ 5·10⁴ peaks), k = 3. Published accuracy on such wide-band Gaussian processes (Benasciutti & Tovo 2005,
/// Int. J. Fatigue 27; Mršnik, Slavič & Boltežar 2013, Int. J. Fatigue 47): Dirlik within ±15 %,
/// Tovo–Benasciutti within ±25 %, Zhao–Baker within ±30 %, Wirsching–Light within ±35 %, the narrow-band
/// formula conservative (damage at most +60 %). The rainflow damage itself has a sampling s.d.: the
/// amplitudes' c.v. of S_a³ is ≤ 1.24 per cycle (Rayleigh, √(Γ(4)/Γ(2.5)² − 1)), over ≈ 5·10⁴ cycles
/// correlated over a few cycles: ≤ 2 %; 6 s.d. = 12 % (a false failure ≤ 1e-8) is added to each band.
/// Peaks sampled at ≥ 66 samples per cycle bias the rainflow damage by ≤ 3·(1 − cos(π/66)) = 0.3 %.
#[test]
fn rainflow_life_of_a_gaussian_record_agrees_with_the_spectral_methods() {
    let mut r = MemoryRecord::new(band_limited_gaussian(2024));
    let sn = SnReferencePoint {
        k: 3.0,
        amplitude: 1e6,
        cycles: 1e12,
        endurance_limit: None,
    }
    .build()
    .unwrap();
    let options = FatigueOptions {
        channel: None,
        sn,
        sn_dim: Dim::new(-1, 1, -2),
        mean_stress: MeanStressCorrection::None,
        gate: None,
        segment_len: None,
    };
    let e = evaluate_fatigue(&mut r, &options).unwrap();
    assert_eq!(e.methods.len(), 5, "{:?}", e.methods);
    let alpha2 = e.spectral.unwrap().alpha2;
    assert!((alpha2 - 0.881).abs() < 0.02, "α₂ {alpha2}");
    let stat = 0.12;
    let ratios: Vec<(String, f64)> = e
        .methods
        .iter()
        .map(|m| (m.method.clone(), 1.0 / m.life_ratio))
        .collect();
    for (name, ratio) in &ratios {
        let lower = name.to_lowercase();
        let (lo, hi) = if lower.contains("narrow") {
            (1.0, 1.6)
        } else if lower.contains("dirlik") {
            (0.85, 1.15)
        } else if lower.contains("tovo") {
            (0.75, 1.25)
        } else if lower.contains("zhao") {
            (0.7, 1.3)
        } else {
            (0.65, 1.35)
        };
        assert!(
            *ratio > lo - stat && *ratio < hi + stat,
            "{name}: damage ratio {ratio}; all {ratios:?}"
        );
    }
    assert!(e.spread.unwrap() >= 1.0);
}

/// The expected IRI of ISO 8608 roads (waviness 2, the standard's band 0.011–2.83 cycles/m) from the
/// spectrum, golden car at 80 km/h, with and without the 250 mm moving average, against an independent
/// computation: scipy's adaptive quadrature of σ_rv² = ∫|H_rv(i2πnv)|²·sinc²(nb)·G_d(n)dn over the same band
/// (H_rv solved from the golden car's two equations of motion; E[IRI] = 1000·√(2/π)·σ_rv/v): class A
/// 2.172553 (no moving average 2.218210), C 8.690212 (8.872839), D 17.380424 (17.745678) m/km. Since the
/// slope of a w = 2 road is white, IRI ∝ √G_d(n₀): each class doubles the previous. (Without the band limits
/// the same quadrature gives 2.172586 / 8.690343 / 17.380685, and without the moving average the Lyapunov
/// solution 8.875588 for class C: the band's cut at 2.83 cycles/m matters at 1.5e-5 with the moving average,
/// 3e-4 without.)
#[test]
fn expected_iri_of_iso_classes_is_the_closed_form() {
    use stochvib::spectrum::{IsoClass, PowerLaw};
    for (class, with_ma, without) in [
        (IsoClass::A, 2.172553, 2.218210),
        (IsoClass::C, 8.690212, 8.872839),
        (IsoClass::D, 17.380424, 17.745678),
    ] {
        let road = PowerLaw::iso_class(class).unwrap();
        let e = stochvib::road::expected_iri(&road).unwrap();
        assert!(
            rel(e.m_per_km, with_ma) < IRI_EXPECTED,
            "{class:?}: {} vs {with_ma}",
            e.m_per_km
        );
        let no_ma = e.without_moving_average_m_per_km;
        assert!(rel(no_ma, without) < IRI_EXPECTED, "{class:?}: {no_ma} vs {without}");
    }
}

/// The command-line tool: `exposure` on a record prints a_w and the verdict; `weighting Wk` prints the
/// analytic magnitude at the asked frequency (Table 3: 0.967 at 4 Hz); a bad record exits non-zero naming the
/// file and the line, and writes nothing: not even the directory `--plots` names (for `exposure` and
/// `fatigue`).
#[test]
fn cli_exposure_weighting_and_refusal() {
    let dir = scratch("cli");
    let file = dir.join("seat.csv");
    write_csv(&file, "time [s],x [m/s^2],y [m/s^2],z [m/s^2]", 1000.0, 20_000, |t| {
        vec![0.3 * (TAU * 2.0 * t).sin(), 0.0, (TAU * 4.0 * t).sin()]
    });
    let limit = std::time::Duration::from_secs(300);
    let out = crate::common::cli_within(&["exposure", "seat.csv", "--exposure", "8 h"], &dir, limit);
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    assert!(text.contains("A(8)") && text.contains("VDV"), "{text}");
    // the y channel is zero: a_w = MTVV = 0, and MTVV/a_w is no number ("—", as the crest factor), not NaN
    assert!(!text.contains("NaN"), "{text}");
    let out = crate::common::cli_within(&["weighting", "Wk", "--frequency", "4"], &dir, limit);
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(out.status.success() && text.contains("0.967"), "{text}");
    std::fs::write(dir.join("bad.csv"), "time [s],z [m/s^2]\n0,1\n0.001,x\n").unwrap();
    let plots = dir.join("pictures");
    let out = crate::common::cli_within(&["exposure", "bad.csv", "--plots", "pictures"], &dir, limit);
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(
        !out.status.success() && err.contains("bad.csv") && err.contains("line 3"),
        "{err}"
    );
    assert!(
        !plots.exists(),
        "the refused record left the directory of the pictures behind"
    );
    std::fs::write(dir.join("bad-stress.csv"), "time [s],s [MPa]\n0,1\n0.001,x\n").unwrap();
    let fatigue = [
        "fatigue",
        "bad-stress.csv",
        "--sn-slope",
        "5",
        "--sn-amplitude",
        "100 MPa",
        "--plots",
        "pictures",
    ];
    let out = crate::common::cli_within(&fatigue, &dir, limit);
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(!out.status.success() && err.contains("bad-stress.csv"), "{err}");
    assert!(
        !plots.exists(),
        "the refused stress record left the directory of the pictures behind"
    );
    std::fs::remove_dir_all(&dir).unwrap();
}

/// `coherence` and `iri` as numbers: a constant coherence model of amplitude 0.5 has γ² = 0.25 at every
/// frequency (definition); the measured two-track profile's γ̂² lies in its own interval within [0, 1]; the
/// expected IRI of ISO 8608 class C is 8.690212 m/km (independent quadrature, see
/// `expected_iri_of_iso_classes_is_the_closed_form`), and the IRI of the class C profile in `data/` (a
/// synthetic class C road) lies within the class's IRI limits, the IRI of G_d(n₀)/2 and 2·G_d(n₀):
/// 8.690343/√2 = 6.145 and 8.690343·√2 = 12.290 m/km.
#[test]
fn cli_coherence_and_iri_as_numbers() {
    let root = crate::common::root();
    let limit = std::time::Duration::from_secs(300);
    let json = |args: &[&str]| -> serde_json::Value {
        let out = crate::common::cli_within(args, &root, limit);
        assert!(
            out.status.success(),
            "{args:?}: {}",
            String::from_utf8_lossy(&out.stderr)
        );
        serde_json::from_slice(&out.stdout).unwrap()
    };
    let model = r#"{ kind = "constant", coherence_amplitude = 0.5 }"#;
    let c = json(&[
        "coherence",
        "--model",
        model,
        "--frequency",
        "0.1,1,3",
        "--format",
        "json",
    ]);
    let rows = c["rows"].as_array().unwrap();
    assert_eq!(rows.len(), 3);
    for r in rows {
        assert!(
            (r["model_squared_coherence"].as_f64().unwrap() - 0.25).abs() < EXACT,
            "{r}"
        );
    }
    let c = json(&[
        "coherence",
        "--profile",
        "data/measured-profile.csv",
        "--segment",
        "128", // 65 rows: the helper reads the output after the exit, so it must fit a pipe's 64 KiB
        "--format",
        "json",
    ]);
    let rows = c["rows"].as_array().unwrap();
    assert!(rows.len() > 10);
    for r in rows {
        let (g, lo, hi) = (
            r["measured_squared_coherence"].as_f64(),
            r["lower"].as_f64(),
            r["upper"].as_f64(),
        );
        if let (Some(g), Some(lo), Some(hi)) = (g, lo, hi) {
            assert!((0.0..=1.0).contains(&g) && lo <= g && g <= hi, "{r}");
        }
    }
    let i = json(&[
        "iri",
        "iso8608-c",
        "--profile",
        "data/measured-profile.csv",
        "--format",
        "json",
    ]);
    let expected = i["expected"]["m_per_km"].as_f64().unwrap();
    assert!(rel(expected, 8.690212) < IRI_EXPECTED, "{expected}");
    let measured = i["measured"].as_array().unwrap();
    assert!(!measured.is_empty());
    for m in measured {
        let v = m["m_per_km"].as_f64().unwrap();
        assert!(v > 8.690343 / SQRT_2 && v < 8.690343 * SQRT_2, "{m}");
    }
}

/// The running r.m.s. of ISO 2631-1 6.3.1 (τ = 1 s) against closed forms, streamed in uneven blocks:
/// * exponential form, a steady sine of amplitude A: max a_w(t₀) = (A/√2)·√(1 + 1/√(1 + 4ω²τ²)) (the mean
///   square's response to sin² = (1 − cos 2ωt)/2 through the first-order low pass 1/(1 + iωτ) at 2ω):
///   0.760650 (0.5 Hz), 0.734618 (1 Hz), 0.714104 (4 Hz) for A = 1;
/// * a burst of 4 Hz, amplitude A = 1, D = 0.5 s (two periods) inside 10 s of silence: VDV = A(3D/8)^{1/4} =
///   0.658037, linear MTVV (τ ≥ D) = A√(D/(2τ)) = 0.5, a_w = A√(D/(2T)) = 0.158114;
/// * linear form, a steady sine: max = (A/√2)·√(1 + |sin ωτ|/(ωτ)) = 0.778526 at 0.75 Hz.
///
/// Sampled at 10 kHz with each sample held over its step; the rectangle rule of sin² and sin⁴ over whole
/// periods is exact, the hold shifts the exponential form by O((ωdt)²) < 1e-5: `RUNNING_RMS_SAMPLED`.
#[test]
fn running_rms_vdv_and_mtvv_of_sines_and_bursts_are_closed_forms() {
    use stochvib::comfort::SignalMetricsStream;
    use stochvib::record::ExponentialRms;
    let dt = 1e-4;
    let sine = |f: f64, t: f64| -> Vec<f64> {
        (0..(t / dt) as usize)
            .map(|i| (TAU * f * i as f64 * dt).sin())
            .collect()
    };
    for (f, expected) in [(0.5, 0.760650), (1.0, 0.734618), (4.0, 0.714104)] {
        let x = sine(f, 30.0);
        let mut r = ExponentialRms::new(dt, 1.0).unwrap();
        let (mut rest, mut k) = (&x[..], 1);
        while !rest.is_empty() {
            let n = (k * 7919 % 50_000 + 1).min(rest.len()); // uneven blocks
            r.push(&rest[..n]);
            rest = &rest[n..];
            k += 1;
        }
        let got = r.mtvv();
        assert!(
            rel(got, expected) < RUNNING_RMS_SAMPLED,
            "exponential MTVV at {f} Hz: {got} vs {expected}"
        );
    }
    let mut burst = vec![0.0; (10.0 / dt) as usize];
    let start = (4.0 / dt) as usize;
    for (i, v) in sine(4.0, 0.5).into_iter().enumerate() {
        burst[start + i] = v;
    }
    let mut s = SignalMetricsStream::new(dt, 1.0).unwrap();
    for b in burst.chunks(33_333) {
        s.push(b).unwrap();
    }
    let m = s.finish().unwrap();
    assert!(
        rel(m.vdv, (3.0 * 0.5f64 / 8.0).powf(0.25)) < RUNNING_RMS_SAMPLED,
        "burst VDV {}",
        m.vdv
    );
    assert!(
        rel(m.mtvv.unwrap(), 0.5) < RUNNING_RMS_SAMPLED,
        "burst MTVV {:?}",
        m.mtvv
    );
    assert!(
        rel(m.a_w, (0.5f64 / 20.0).sqrt()) < RUNNING_RMS_SAMPLED,
        "burst a_w {}",
        m.a_w
    );
    let mut s = SignalMetricsStream::new(dt, 1.0).unwrap();
    s.push(&sine(0.75, 20.0)).unwrap();
    let m = s.finish().unwrap();
    assert!(
        rel(m.mtvv.unwrap(), 0.778526) < RUNNING_RMS_SAMPLED,
        "linear MTVV {:?}",
        m.mtvv
    );
}

/// The mean-stress correction and the hysteresis gate of `fatigue`:
/// * Goodman: 2000 reversals between 150 and 50 MPa (mean 100, amplitude 50) are 999.5 cycles of range
///   100; with S_u = 400 MPa the equivalent amplitude is 50/(1 − 100/400) = 66.667 MPa, so with k = 5,
///   C = 1e15 MPa⁵: D = 999.5·66.667⁵/1e15, and uncorrected 999.5·50⁵/1e15.
/// * Gate: ±100 MPa reversals with a 3 MPa ripple at every extreme (100, 97, 100 / −100, −97, −100): with a
///   gate of 10 MPa the ripples are removed and the count is that of the clean ±100 sequence, 999 ranges of
///   200 = 499.5 cycles, D = 499.5·100⁵/1e15; without the gate the ripples add at least 999 full cycles (the first ripple holds the start: a half cycle).
#[test]
fn goodman_correction_and_hysteresis_gate() {
    let dir = scratch("goodman");
    let v: Vec<f64> = (0..2000).map(|i| if i % 2 == 0 { 150.0 } else { 50.0 }).collect();
    let goodman = MeanStressCorrection::Goodman { ultimate: 400e6 };
    let e = fatigue_with(&dir, "mean.csv", &v, 5.0, 1e15, goodman, None);
    let eq: f64 = 50.0 / (1.0 - 100.0 / 400.0);
    assert!(
        rel(e.damage, 999.5 * eq.powi(5) / 1e15) < EXACT,
        "Goodman D {}",
        e.damage
    );
    assert!(
        rel(e.damage_uncorrected, 999.5 * 50f64.powi(5) / 1e15) < EXACT,
        "D {}",
        e.damage_uncorrected
    );
    let mut rippled = Vec::new();
    for _ in 0..500 {
        rippled.extend_from_slice(&[-100.0, -97.0, -100.0, 100.0, 97.0, 100.0]);
    }
    let gated = fatigue_with(
        &dir,
        "ripple.csv",
        &rippled,
        5.0,
        1e15,
        MeanStressCorrection::None,
        Some(10e6),
    );
    assert!(
        rel(gated.damage, 499.5 * 100f64.powi(5) / 1e15) < EXACT,
        "gated D {}",
        gated.damage
    );
    let raw = fatigue_with(
        &dir,
        "ripple2.csv",
        &rippled,
        5.0,
        1e15,
        MeanStressCorrection::None,
        None,
    );
    assert!(
        raw.full_cycles >= gated.full_cycles + 999,
        "{} vs {}",
        raw.full_cycles,
        gated.full_cycles
    );
    assert!(raw.damage > gated.damage);
    std::fs::remove_dir_all(&dir).unwrap();
}

/// The pictures: `exposure --plots` writes the weighted time history with its running r.m.s. and the band
/// spectrum against the comfort scale, `fatigue --plots` the range histogram against Dirlik's density and
/// the rainflow matrix, each as SVG and PNG (non-empty files; the PNG with its signature).
#[test]
fn cli_pictures_are_written() {
    let dir = scratch("pictures");
    write_csv(&dir.join("seat.csv"), "time [s],z [m/s^2]", 1000.0, 20_000, |t| {
        vec![(TAU * 4.0 * t).sin()]
    });
    write_csv(&dir.join("axle.csv"), "time [s],stress [MPa]", 100.0, 20_000, |t| {
        vec![50.0 * (TAU * 3.0 * t).sin() + 20.0 * (TAU * 7.3 * t).sin()]
    });
    let limit = std::time::Duration::from_secs(300);
    for args in [
        vec!["exposure", "seat.csv", "--plots", "e"],
        vec![
            "fatigue",
            "axle.csv",
            "--sn-slope",
            "5",
            "--sn-amplitude",
            "100 MPa",
            "--sn-cycles",
            "1e6",
            "--plots",
            "f",
        ],
    ] {
        let out = crate::common::cli_within(&args, &dir, limit);
        assert!(
            out.status.success(),
            "{args:?}: {}",
            String::from_utf8_lossy(&out.stderr)
        );
        let sub = dir.join(args[args.len() - 1]);
        let names = crate::common::listing(&sub);
        assert!(
            names.iter().filter(|n| n.ends_with(".svg")).count() >= 2,
            "{args:?}: {names:?}"
        );
        assert!(
            names.iter().filter(|n| n.ends_with(".png")).count() >= 2,
            "{args:?}: {names:?}"
        );
        for n in names.iter().filter(|n| n.ends_with(".png")) {
            let bytes = std::fs::read(sub.join(n)).unwrap();
            assert!(bytes.starts_with(b"\x89PNG"), "{n}");
        }
    }
    // a zero record: every band r.m.s. is 0, which a logarithmic axis cannot hold; the band picture is left
    // out and the time history drawn (it failed with "nothing to plot" after printing the report, exit 1,
    // the time history already written)
    write_csv(&dir.join("still.csv"), "time [s],z [m/s^2]", 1000.0, 4000, |_| {
        vec![0.0]
    });
    let out = crate::common::cli_within(&["exposure", "still.csv", "--plots", "s"], &dir, limit);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let names = crate::common::listing(&dir.join("s"));
    assert_eq!(names, ["exposure-time-z.png", "exposure-time-z.svg"], "{names:?}");
    std::fs::remove_dir_all(&dir).unwrap();
}

/// Band-limited Gaussian white noise of n samples at 1 kHz, periodic with T = n/f_s: in every bin f_k = k/T
/// with `lo` ≤ f_k ≤ `hi` independent standard normal real and imaginary parts X_k, zero elsewhere, one
/// inverse FFT, scaled by the fixed c = 1/√(4M) (M bins) so that the expected mean square is 1 (m/s²)²: a
/// bin contributes 2c²|X_k|² = 4c²E_k to the mean square, E_k = |X_k|²/2 ~ Exp(1). Seeded.
fn white_band(seed: u64, n: usize, lo: f64, hi: f64) -> Vec<f64> {
    let t = n as f64 / 1000.0;
    assert!(lo * t > 1.0 && hi * t < n as f64 / 2.0);
    let bins = white_band_bins(n, lo, hi);
    let c = 1.0 / (4.0 * bins.clone().count() as f64).sqrt();
    let mut x = gaussian_lines(seed, n, bins);
    x.iter_mut().for_each(|v| *v *= c);
    x
}

/// The FFT bins k of `white_band`: lo ≤ k/T ≤ hi.
fn white_band_bins(n: usize, lo: f64, hi: f64) -> std::ops::RangeInclusive<usize> {
    let t = n as f64 / 1000.0;
    (lo * t).ceil() as usize..=(hi * t).floor() as usize
}

/// a_w of band-limited white noise records against the analytic value of the same spectrum.
///
/// The record's spectrum is flat over the lines f_k = k/T, 1 ≤ f_k ≤ 20 Hz (`white_band`, σ² = 1 (m/s²)²,
/// T = 2²⁰/1 kHz = 1048.6 s), so the analytic weighted mean square is
/// μ = Σ_k 4c²|W(f_k)|² = σ²·mean_k |W(f_k)|², with W the analytic ISO 2631-1 weighting written out in this
/// file (Wd for the x channel, Wk for z); it equals ∫|W|²G df of the flat density G = σ²/(19 Hz) up to the
/// Riemann error O(Δf²), Δf = 1/T.
///
/// What the record gives: the weighted signal of a periodic record is, after the filter's start-up, periodic,
/// and its mean square over one period is S = Σ_k 4c²|H(f_k)|²E_k (Parseval) with H the digital weighting.
/// The start-up is removed exactly by evaluating the record of one period (a₁) and of two periods (a₂): the
/// first periods are identical, the second is in steady state (the slowest pole decays as e^{−1.78 t/s}), so
/// S = 2a₂² − a₁².
///
/// Tolerance: the digital |H|² differs from |W|² over 1–20 Hz by at most `NOISE_WEIGHTING_REALISATION`; and
/// S − E[S] = Σ c_k(E_k − 1), c_k = 4c²|H_k|², a sum of independent centred exponentials, which satisfies
/// Bernstein's moment condition with variance v = Σc_k² and scale b = 2·max c_k, so
/// P(|S − E S| ≥ t) ≤ 2exp(−t²/(2(v + bt))). With t = bL + √(b²L² + 2Lv), L = ln(2/5e-7), each channel fails
/// falsely with probability ≤ 5e-7, the test ≤ 1e-6 (about 5.5 s.d.: 8.9 % of μ for Wd, whose weight lies mostly
/// at 1–2 Hz, so that few lines carry the mean square; a longer record narrows it as 1/√T).
#[test]
fn a_w_of_band_limited_white_noise_is_the_analytic_value() {
    let n = 1usize << 20;
    let (lo, hi) = (1.0, 20.0);
    let x = white_band(31, n, lo, hi);
    let z = white_band(32, n, lo, hi);
    let twice = |v: &[f64]| [v, v].concat();
    let options = ExposureOptions::default();
    let one = evaluate_exposure(
        &mut MemoryRecord::accelerations(vec![("x", x.clone()), ("z", z.clone())]),
        &options,
    )
    .unwrap();
    let two = evaluate_exposure(
        &mut MemoryRecord::accelerations(vec![("x", twice(&x)), ("z", twice(&z))]),
        &options,
    )
    .unwrap();
    let bins = white_band_bins(n, lo, hi);
    let c2 = 1.0 / (4.0 * bins.clone().count() as f64);
    let t = n as f64 / 1000.0;
    let l = (2.0f64 / 5e-7).ln();
    for (i, (channel, w)) in [("x", "Wd"), ("z", "Wk")].into_iter().enumerate() {
        assert_eq!(one.axes[i].channel, channel);
        assert_eq!(one.axes[i].weighting, Weighting::parse(w).unwrap());
        let ck: Vec<f64> = bins
            .clone()
            .map(|k| 4.0 * c2 * analytic(w, k as f64 / t).norm_sqr())
            .collect();
        let mu: f64 = ck.iter().sum();
        // the digital c_k are at most (1 + NOISE_WEIGHTING_REALISATION)·c_k: v and b from that upper bound
        let up = 1.0 + NOISE_WEIGHTING_REALISATION;
        let v: f64 = ck.iter().map(|c| c * c * up * up).sum();
        let b = 2.0 * up * ck.iter().fold(0.0f64, |m, c| m.max(*c));
        let stat = b * l + (b * b * l * l + 2.0 * l * v).sqrt();
        let (a1, a2) = (one.axes[i].metrics.a_w, two.axes[i].metrics.a_w);
        let s = 2.0 * a2 * a2 - a1 * a1;
        let allowed = stat + mu * NOISE_WEIGHTING_REALISATION;
        assert!(
            (s - mu).abs() <= allowed,
            "{channel} ({w}): steady a_w² {s} against the analytic {mu} (allowed ±{allowed}, of which {stat} \
             statistical); a_w of one period {a1}"
        );
        assert!(stat < 0.1 * mu, "{channel}: the test is too weak: ±{stat} of {mu}");
    }
}

/// Gerber and SWT mean-stress corrections against their closed forms (k = 5, C = 1e15 MPa⁵, the record of
/// 2000 reversals is 999.5 cycles of one range and mean, half cycles counted 0.5):
/// * tensile mean: reversals between 150 and 50 MPa (S_m = 100, S_a = 50), S_u = 400 MPa:
///   Gerber S_a,eq = 50/(1 − (100/400)²) = 53.333 MPa; SWT S_a,eq = √(S_max·S_a) = √(150·50) = 86.603 MPa;
/// * compressive mean: between −50 and −150 MPa (S_m = −100): Gerber credits no compressive mean
///   (S_a,eq = S_a = 50); SWT has S_max = −50 ≤ 0, no damage;
/// * mean −25, amplitude 50 (between 25 and −75): SWT √(25·50) = 35.355 MPa.
///
/// D = 999.5·S_a,eq⁵/1e15 (Smith, Watson & Topper 1970; Gerber 1874; as in Dowling, "Mechanical Behavior of
/// Materials", 4th ed. 2013, eqs. 10.14 and 10.23).
#[test]
fn gerber_and_swt_corrections_are_the_closed_forms() {
    let dir = scratch("gerber-swt");
    let reversals = |hi: f64, lo: f64| -> Vec<f64> { (0..2000).map(|i| if i % 2 == 0 { hi } else { lo }).collect() };
    let gerber = MeanStressCorrection::Gerber { ultimate: 400e6 };
    let swt = MeanStressCorrection::Swt;
    let damage = |eq: f64| 999.5 * eq.powi(5) / 1e15;
    let cases = [
        (
            "gerber-tension.csv",
            (150.0, 50.0),
            gerber,
            damage(50.0 / (1.0 - 0.25f64.powi(2))),
        ),
        ("swt-tension.csv", (150.0, 50.0), swt, damage((150.0f64 * 50.0).sqrt())),
        ("gerber-compression.csv", (-50.0, -150.0), gerber, damage(50.0)),
        ("swt-compression.csv", (-50.0, -150.0), swt, 0.0),
        ("swt-crossing.csv", (25.0, -75.0), swt, damage((25.0f64 * 50.0).sqrt())),
    ];
    for (name, (hi, lo), correction, expected) in cases {
        let e = fatigue_with(&dir, name, &reversals(hi, lo), 5.0, 1e15, correction, None);
        let cycles = e.full_cycles as f64 + 0.5 * e.half_cycles as f64;
        assert_eq!(
            cycles, 999.5,
            "{name}: {} full and {} half cycles",
            e.full_cycles, e.half_cycles
        );
        let ok = if expected == 0.0 {
            e.damage == 0.0
        } else {
            rel(e.damage, expected) < EXACT
        };
        assert!(ok, "{name}: D {} against {expected}", e.damage);
        assert!(
            rel(e.damage_uncorrected, damage(50.0)) < EXACT,
            "{name}: uncorrected D {}",
            e.damage_uncorrected
        );
    }
    std::fs::remove_dir_all(&dir).unwrap();
}

/// Truncated binary records are refused with the file and the reason, and nothing is written (the directory
/// `--plots` names is not made): an HDF5 record cut to half its length, a WAV record whose data chunk ends
/// early (the header promises 4000 frames, the file holds about 1500).
#[test]
fn truncated_hdf5_and_wav_records_are_refused() {
    let dir = scratch("truncated");
    let n = 4000;
    let h5 = dir.join("cut.h5");
    write_h5_acceleration(
        &h5,
        &(0..n).map(|i| (0.03 * i as f64).sin()).collect::<Vec<_>>(),
        1000.0,
    );
    let wav = dir.join("cut.wav");
    let spec = hound::WavSpec {
        channels: 2,
        sample_rate: 1000,
        bits_per_sample: 16,
        sample_format: hound::SampleFormat::Int,
    };
    let mut w = hound::WavWriter::create(&wav, spec).unwrap();
    for i in 0..2 * n {
        w.write_sample(((0.03 * i as f64).sin() * 10_000.0) as i16).unwrap();
    }
    w.finalize().unwrap();
    for file in [&h5, &wav] {
        let len = std::fs::metadata(file).unwrap().len();
        let cut = if file == &wav { 44 + 6000 } else { len / 2 };
        let f = std::fs::OpenOptions::new().write(true).open(file).unwrap();
        f.set_len(cut).unwrap();
    }
    let limit = std::time::Duration::from_secs(300);
    let cases: [(&str, &[&str], &[&str]); 2] = [
        ("cut.h5", &[], &["truncat", "HDF5"]),
        (
            "cut.wav",
            &["--full-scale", "50 m/s^2", "--channels", "x,z"],
            &["truncated", "frame"],
        ),
    ];
    for (name, extra, reasons) in cases {
        let mut args = vec!["exposure", name, "--plots", "pictures"];
        args.extend_from_slice(extra);
        let out = crate::common::cli_within(&args, &dir, limit);
        let err = String::from_utf8_lossy(&out.stderr);
        assert!(!out.status.success(), "{name}: accepted");
        assert!(err.contains(name), "{name}: the error does not name the file: {err}");
        assert!(
            reasons.iter().any(|r| err.contains(r)),
            "{name}: the error gives no reason ({reasons:?}): {err}"
        );
        assert_eq!(
            crate::common::listing(&dir),
            ["cut.h5", "cut.wav"],
            "{name}: something was written"
        );
    }
    std::fs::remove_dir_all(&dir).unwrap();
}
