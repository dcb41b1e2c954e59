//! The EN ISO 7096 input spectral classes of the catalogue and the SEAT value of `[analysis.seat_factor]`.
//!
//! Expected values: the class targets are the published r.m.s. values (EN ISO 7096:2000 as implemented in the
//! HVLab Human Response to Vibration toolbox, ISVR Southampton, C. Lewis 2009, `hvtestsignal.m`); the class
//! densities and the SEAT values are integrated here by composite Simpson rules from the defining formulas
//! (exact Butterworth magnitudes, the ISO 2631-1:1997 Annex A formula of Wk, the base-excited oscillator's
//! transmissibility), not by the library.

use crate::common;
use common::tolerance::{HIGH_ORDER_INPUT_LYAPUNOV, ISO7096_PRINTED_TARGET, QUADRATURE};
use common::{rel, root, simpson_log};
use nalgebra::Complex;
use std::f64::consts::PI;
use stochvib::scenario::{load_spectrum, parse_scenario};
use stochvib::study::verdict_analysis;

/// A class: (name, high-pass order, corner Hz, low-pass order, corner Hz, G_p, target r.m.s., band edge Hz).
type Class = (&'static str, i32, f64, i32, f64, f64, f64, f64);

/// (class, high-pass order, corner Hz, low-pass order, corner Hz, G_p (m/s²)²/Hz, target r.m.s. m/s², upper
/// band edge Hz), the table of the standard as the toolbox gives it.
const CLASSES: [Class; 9] = [
    ("em1", 4, 1.5, 4, 2.5, 2.82, 1.71, 11.22),
    ("em2", 4, 1.5, 4, 3.0, 2.72, 2.05, 11.22),
    ("em3", 4, 1.5, 4, 3.0, 1.93, 1.73, 11.22),
    ("em4", 4, 1.5, 4, 3.0, 0.60, 0.96, 11.22),
    ("em5", 4, 1.5, 1, 3.5, 1.11, 1.94, 17.78),
    ("em6", 2, 6.5, 2, 9.0, 0.79, 1.65, 17.78),
    ("em7", 8, 3.0, 8, 3.5, 9.25, 2.36, 11.22),
    ("em8", 4, 3.0, 2, 3.0, 1.45, 1.05, 17.78),
    ("em9", 4, 3.5, 2, 4.0, 2.10, 1.63, 17.78),
];

/// The one-sided class density G(f) in (m/s²)²/Hz: G_p |H_HP|² |H_LP|² with exact Butterworth magnitudes.
fn class_density(c: &Class, f: f64) -> f64 {
    let hp = (f / c.2).powi(2 * c.1);
    c.5 * hp / (1.0 + hp) / (1.0 + (f / c.4).powi(2 * c.3))
}

/// Simpson in ln f over 1e-3 … 1e3 Hz on 400 000 intervals (h = 3.5e-5: the h⁴ error term is below 1e-14 of
/// these integrands, whose steepest slopes are f^±32; the ends carry < 1e-20 of them).
fn integral(g: impl Fn(f64) -> f64) -> f64 {
    simpson_log(g, 1e-3, 1e3, 400_000)
}

/// Each class's r.m.s. in the band of the standard's target (0.89 Hz to 11.22 or 17.78 Hz, 8-pole Butterworth
/// band filters as the toolbox measures it) equals the published target to the rounding of the table and the
/// toolbox's own PSD/signal agreement (0.4 %), for every class but EM7: the catalogue file says why (its
/// density gives 2.25 m/s², the toolbox scales its signals to 2.36 m/s²), and that gap is asserted here so a
/// change of either shows.
#[test]
fn iso7096_classes_have_the_target_rms_in_band() {
    let dir = root().join("spectra");
    for c in &CLASSES {
        let s = load_spectrum(&dir.join(format!("iso7096-{}.toml", c.0)))
            .unwrap()
            .spectrum;
        let band = |f: f64| {
            let lo = (f / 0.89).powi(16);
            lo / (1.0 + lo) / (1.0 + (f / c.7).powi(16))
        };
        // the catalogue density, one-sided in Hz: G(f) = 4π S(2πf)
        let rms = integral(|f| 4.0 * PI * s.density(2.0 * PI * f) * band(f)).sqrt();
        if c.0 == "em7" {
            assert!((rms / c.6 - 0.955).abs() < 0.002, "EM7 band r.m.s. {rms}");
        } else {
            assert!(rel(rms, c.6) < ISO7096_PRINTED_TARGET, "{}: {rms} vs {}", c.0, c.6);
        }
    }
}

/// The catalogue density is the defining formula, and its variance (the library's route for a rational
/// density) is the integral of it.
#[test]
fn iso7096_class_density_and_variance_are_the_definition() {
    let dir = root().join("spectra");
    for c in &CLASSES {
        let s = load_spectrum(&dir.join(format!("iso7096-{}.toml", c.0)))
            .unwrap()
            .spectrum;
        for f in [0.5, 1.5, 2.0, 3.0, 7.0, 20.0] {
            let g = class_density(c, f);
            assert!(
                rel(4.0 * PI * s.density(2.0 * PI * f), g) < QUADRATURE,
                "{} at {f} Hz",
                c.0
            );
        }
        // the tail above 1 kHz: G_p/(1 + (f/f_l)²) exactly for a first-order low pass, else its leading term
        // G_p f_l^2m F^(1−2m)/(2m − 1) (the next is (f_l/F)^2m ≈ 1e-10 smaller; the high pass is 1 − 1e-23 there)
        let big_f = 1e3;
        let tail = if c.3 == 1 {
            c.5 * c.4 * (PI / 2.0 - (big_f / c.4).atan())
        } else {
            c.5 * c.4.powi(2 * c.3) * big_f.powi(1 - 2 * c.3) / (2 * c.3 - 1) as f64
        };
        let var = integral(|f| class_density(c, f)) + tail;
        assert!(rel(s.variance().unwrap(), var) < QUADRATURE, "{}", c.0);
    }
}

/// |Wk(f)| of ISO 2631-1:1997 Annex A (Table A.2: f1 = 0.4, f2 = 100, f3 = f4 = 12.5 Hz, Q4 = 0.63,
/// f5 = 2.37, Q5 = 0.91, f6 = 3.35 Hz, Q6 = 0.91), written out here.
fn wk(f: f64) -> f64 {
    let s = Complex::new(0.0, 2.0 * PI * f);
    let w = |x: f64| 2.0 * PI * x;
    let (w1, w2, w3, w4, w5, w6) = (w(0.4), w(100.0), w(12.5), w(12.5), w(2.37), w(3.35));
    let hh = 1.0 / (1.0 + 2f64.sqrt() * w1 / s + (w1 / s).powi(2));
    let hl = 1.0 / (1.0 + 2f64.sqrt() * s / w2 + (s / w2).powi(2));
    let ht = (1.0 + s / w3) / (1.0 + s / (0.63 * w4) + (s / w4).powi(2));
    let hs =
        (1.0 + s / (0.91 * w5) + (s / w5).powi(2)) / (1.0 + s / (0.91 * w6) + (s / w6).powi(2)) * (w5 / w6).powi(2);
    (hh * hl * ht * hs).norm()
}

/// A seat of natural frequency 1.5 Hz and damping ratio 0.3 (the textbook seat: m_pr = 5/7·70 + 25 = 75 kg)
/// on the platform, class `c` read as the platform displacement.
fn seat_scenario(c: &Class) -> String {
    let w = 2.0 * PI * 1.5;
    format!(
        r#"title = "seat test"
[model]
kind = "operator-seat"
operator_mass = "70 kg"
seat_mass = "25 kg"
stiffness = {:.17e}
damping_rate = "{:.17e} 1/s"
[input]
spectrum = {{ kind = "butterworth-band", unit = "m", convention = "one-sided-cyclic", level = {}, high_pass = {{ order = {}, corner = "{} Hz" }}, low_pass = {{ order = {}, corner = "{} Hz" }}, integrate = 2 }}
[analysis]
outputs = ["seat_acc"]
[analysis.seat_factor]
seat = "seat_acc"
floor = "base 0"
"#,
        75.0 * w * w,
        0.3 * w,
        c.5,
        c.1,
        c.2,
        c.3,
        c.4
    )
}

/// SEAT = √(∫G|T|²|Wk|² df / ∫G|Wk|² df) with T = (1 + 2iζr)/(1 − r² + 2iζr), r = f/f_n, the absolute
/// transmissibility of a base-excited oscillator; and a_w of the floor = √∫G|Wk|² df, by both routes.
#[test]
fn seat_factor_of_a_linear_seat_against_quadrature() {
    let spectra = root().join("spectra");
    for c in [&CLASSES[0], &CLASSES[2], &CLASSES[5]] {
        let path = root().join("data").join("seat-test.toml");
        let sc = parse_scenario(&seat_scenario(c), &path, &spectra).unwrap();
        let s = verdict_analysis(&sc).unwrap().seat_factor.unwrap();
        let t = |f: f64| {
            let r = f / 1.5;
            (Complex::new(1.0, 0.6 * r) / Complex::new(1.0 - r * r, 0.6 * r)).norm()
        };
        let floor = integral(|f| class_density(c, f) * wk(f).powi(2)).sqrt();
        let seat = integral(|f| class_density(c, f) * (t(f) * wk(f)).powi(2)).sqrt();
        // each route against the independent integral: quadrature tightly, the Lyapunov route (the one
        // reported) within the accuracy of its 16-state augmented system
        for (k, expected) in [(0, seat), (1, floor)] {
            let (l, q) = (s.a_w_lyapunov[k].unwrap(), s.a_w_quadrature[k].unwrap());
            assert!(rel(q, expected) < QUADRATURE, "{}: quadrature {q} vs {expected}", c.0);
            assert!(
                rel(l, expected) < HIGH_ORDER_INPUT_LYAPUNOV,
                "{}: Lyapunov {l} vs {expected}",
                c.0
            );
        }
        assert!(
            rel(s.floor_a_w, floor) < HIGH_ORDER_INPUT_LYAPUNOV,
            "{}: floor {} vs {floor}",
            c.0,
            s.floor_a_w
        );
        let expected = seat / floor;
        assert!(
            rel(s.seat_factor, expected) < HIGH_ORDER_INPUT_LYAPUNOV,
            "{}: SEAT {} vs {expected}",
            c.0,
            s.seat_factor
        );
    }
}

/// The catalogue scenario reads, its SEAT is below 1 (the seat isolates EM3), and bad keys are named.
#[test]
fn seat_factor_scenario_and_bad_keys() {
    let spectra = root().join("spectra");
    let path = root().join("data").join("operator-seat-iso7096.toml");
    let text = std::fs::read_to_string(&path).unwrap();
    let sc = parse_scenario(&text, &path, &spectra).unwrap();
    let s = verdict_analysis(&sc).unwrap().seat_factor.unwrap();
    assert!(s.seat_factor > 0.5 && s.seat_factor < 1.0, "{}", s.seat_factor);
    for (from, to, key) in [
        ("floor = \"base 0\"", "floor = \"base 1\"", "floor"),
        ("seat = \"seat_acc\"", "seat = \"travel\"", "seat"),
        ("seat = \"seat_acc\"", "seat = \"nothing\"", "seat"),
        ("weighting = \"Wk\"", "weighting = \"Wz\"", "weighting"),
    ] {
        let bad = text.replace(from, to);
        let e = parse_scenario(&bad, &path, &spectra).unwrap_err().to_string();
        assert!(e.contains(&format!("analysis.seat_factor.{key}")), "{e}");
    }
}
