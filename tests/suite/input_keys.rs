//! The `band` and `enveloping` keys of an input table: an explicit band on any spectrum (a catalogue ISO
//! 8608 class continued to the new edge, any other spectrum restricted), and a tyre's enveloping, the
//! contact-patch moving average |H(n)|² = (sin(πnL)/(πnL))² — checked at known wavenumbers, through a
//! variance against quadratures written here, against the expected IRI of the golden car (Sayers'
//! 250 mm moving average), with the exact route refusing it, and in a default Monte Carlo run; bad values
//! refused with file, key, value and reason.

use crate::common;

use common::tolerance::{PRINTED_7_DIGITS, QUADRATURE, ROUNDING};
use common::{rel, root, simpson_log};
use std::f64::consts::PI;
use stochvib::response::{analyze_output, Outcome, VarianceMethod};
use stochvib::scenario::{parse_scenario, Scenario};
use stochvib::simulate::{planned_memory, Route, RunOptions};
use stochvib::spectrum::{IsoBound, IsoClass, PowerLaw, Spectrum};
use stochvib::Error;

/// `data/quarter-car.toml` at `speed` with `keys` added to its `[input]` table (and without its levels).
fn quarter_car_text(speed: &str, keys: &str) -> String {
    let text = std::fs::read_to_string(root().join("data/quarter-car.toml")).unwrap();
    text.replace("speed = \"20 m/s\"", &format!("speed = \"{speed}\"\n{keys}"))
        .split("[analysis.levels]")
        .next()
        .unwrap()
        .to_string()
}

fn parse(text: &str) -> stochvib::Result<Scenario> {
    parse_scenario(text, &root().join("data/input-keys.toml"), &root().join("spectra"))
}

/// The error's key, value and reason (and that it names the file).
fn file_error(e: Error) -> (String, String, String) {
    match e {
        Error::File {
            file,
            key,
            value,
            reason,
        } => {
            assert!(file.ends_with("data/input-keys.toml"), "{}", file.display());
            (key, value, reason)
        }
        other => panic!("expected a file error, got {other}"),
    }
}

const ENVELOPED: &str = "band = [\"0.011 cycles/m\", \"30 cycles/m\"]\n\
                         enveloping = { kind = \"moving-average\", length = \"250 mm\" }";

/// |H(n)|² = (sin(πnL)/(πnL))² of the 250 mm moving average, read off the scenario's road as the ratio of
/// its density to the class C law's at n = 1/(4L), 1/(2L), 1/L, 3/(2L) = 1, 2, 4, 6 cycles/m:
/// (sin(π/4)/(π/4))² = 8/π², (1/(π/2))² = 4/π², 0 (the first zero), (1/(3π/2))² = 4/(9π²).
#[test]
fn moving_average_gain_at_known_wavenumbers() {
    let sc = parse(&quarter_car_text("20 m/s", ENVELOPED)).unwrap();
    let law = PowerLaw::iso8608(IsoClass::C, IsoBound::GeometricMean, Some((0.011, 30.0))).unwrap();
    let pi2 = PI * PI;
    for (n, expected) in [(1.0, 8.0 / pi2), (2.0, 4.0 / pi2), (4.0, 0.0), (6.0, 4.0 / (9.0 * pi2))] {
        let w = 2.0 * PI * n;
        let ratio = sc.input.spectrum.density(w) / law.density(w);
        assert!(
            (ratio - expected).abs() <= 10.0 * ROUNDING,
            "n = {n}: {ratio} vs {expected}"
        );
    }
    let text = stochvib::study::analysis_report(&sc).unwrap().to_string();
    assert!(text.contains("moving average of length 0.25 m"), "{text}");
}

/// The enveloped road's variance and the body acceleration's variance through the model against
/// quadratures written here: σ_z² = ∫_{n₁}^{n₂} G_d(n) (sin(πnL)/(πnL))² dn with the class C law
/// G_d(n) = 256·10⁻⁶ (n/0.1)⁻² m³ on [0.011, 30] cycles/m, L = 0.25 m; σ_a² = 2∫|H(iω)|² S_t(ω) dω with
/// S_t(ω) = G_d(ω/2πv) sinc²(ωL/2v)/(4πv) (one-sided G_d in cycles/m to the two-sided temporal density at
/// v = 20 m/s). Simpson's rule in ln n on 200 000 intervals resolves the sinc² oscillation (period 4
/// cycles/m, at least 2 000 points per period up to 30 cycles/m): its error is far below 10⁻⁸.
#[test]
fn enveloped_variances_against_quadratures_written_here() {
    let sc = parse(&quarter_car_text("20 m/s", ENVELOPED)).unwrap();
    let (l, v) = (0.25, 20.0);
    let g_d = |n: f64| 256e-6 * (n / 0.1).powi(-2);
    let sinc2 = |x: f64| (x.sin() / x).powi(2);
    let road = simpson_log(|n| g_d(n) * sinc2(PI * n * l), 0.011, 30.0, 200_000);
    let got = sc.input.spectrum.variance().unwrap();
    assert!(rel(got, road) < QUADRATURE, "{got} vs {road}");
    let sys = sc.model.system.as_ref();
    let i = sys.output_index("body_acc").unwrap();
    let s_t = |w: f64| g_d(w / (2.0 * PI * v)) * sinc2(0.5 * w * l / v) / (4.0 * PI * v);
    let h2 = |w: f64| sys.response(w)[(i, 0)].norm_sqr();
    let acc = 2.0 * simpson_log(|w| h2(w) * s_t(w), 2.0 * PI * 0.011 * v, 2.0 * PI * 30.0 * v, 200_000);
    let st = analyze_output(sys, &sc.excitation, i).unwrap();
    assert!(
        rel(st.variance.unwrap(), acc) < QUADRATURE,
        "{:?} vs {acc}",
        st.variance
    );
}

/// The exact route does not apply to an enveloped road (the sinc² density is not rational) and says so;
/// quadrature answers. On the textbook's rational graded road (8.69) (type 1, D = 32 cm², α = 0.16 m⁻¹)
/// the Lyapunov route gives the travel's variance without the key and refuses with it, naming the
/// moving average; the quadrature value with the key is checked against one written here (the type 1
/// density S(Ω) = Dα/(π(α² + Ω²)) times sinc², Simpson in ln ω on 200 000 intervals over 10⁻⁶…10⁴ rad/s;
/// the tails beyond hold < 10⁻¹⁰ of it: |H|² of the travel vanishes as ω² at 0 and the density as ω⁻⁴).
/// A Monte Carlo run asking for the exact route is refused.
#[test]
fn the_exact_route_refuses_an_enveloped_road_and_quadrature_answers() {
    let rational = quarter_car_text("20 m/s", "").replace("\"iso8608-c\"", "\"book-8-69\"");
    let sc = parse(&rational).unwrap();
    let sys = sc.model.system.as_ref();
    let i = sys.output_index("travel").unwrap();
    let lyapunov = |st: &stochvib::response::ResponseStatistics| {
        st.methods
            .iter()
            .find(|m| m.method == VarianceMethod::Lyapunov)
            .map(|m| m.outcome.clone())
    };
    assert!(lyapunov(&analyze_output(sys, &sc.excitation, i).unwrap()).is_some_and(|o| o.value().is_some()));
    let env = parse(&rational.replace(
        "speed = \"20 m/s\"",
        "speed = \"20 m/s\"\nenveloping = { kind = \"moving-average\", length = \"0.25 m\" }",
    ))
    .unwrap();
    let st = analyze_output(env.model.system.as_ref(), &env.excitation, i).unwrap();
    match lyapunov(&st) {
        Some(Outcome::NotApplicable { reason }) => {
            assert!(
                reason.contains("not rational") && reason.contains("moving average"),
                "{reason}"
            )
        }
        other => panic!("the Lyapunov route on an enveloped road: {other:?}"),
    }
    let (d, a, l, v) = (32e-4, 0.16, 0.25, 20.0);
    let s_t =
        |w: f64| d * a / (PI * (a * a + (w / v).powi(2))) / v * ((0.5 * w * l / v).sin() / (0.5 * w * l / v)).powi(2);
    let h2 = |w: f64| sys.response(w)[(i, 0)].norm_sqr();
    let expected = 2.0 * simpson_log(|w| h2(w) * s_t(w), 1e-6, 1e4, 200_000);
    assert!(
        rel(st.variance.unwrap(), expected) < QUADRATURE,
        "{:?} vs {expected}",
        st.variance
    );
    let exact = RunOptions {
        route: Route::Exact,
        realizations: 4,
        duration_s: 10.0,
        dt_s: 0.005,
        seed: 1,
        ..RunOptions::default()
    };
    let e = planned_memory(&env.run_input(), &exact).unwrap_err().to_string();
    assert!(e.contains("rational"), "{e}");
}

/// The expected International Roughness Index of ISO 8608 class C (G_d(n₀) = 256·10⁻⁶ m³, w = 2, no band)
/// through the golden car at 80 km/h with the 250 mm moving average (ASTM E1926; Sayers, "On the
/// calculation of International Roughness Index from longitudinal road profile", TRR 1501, 1995):
/// E[IRI] = √(2/π)·σ_rv/v for a Gaussian profile, σ_rv the suspension's relative velocity (here the damper
/// force over c). The golden car normalised by the sprung mass: k_t = 653, k_s = 63.3 N/m, c = 6 N s/m,
/// m_u = 0.15 kg, m_s = 1 kg. Expected 8.690343 m/km with the moving average and 8.875588 m/km without,
/// from an independent scipy quadrature of σ_rv² = ∫|H_rv(i2πnv)|² sinc²(πnL) G_d(n) dn (without the
/// average also from the Lyapunov equation of the golden car under white road velocity): IRI ∝ √G_d(n₀) with
/// K = 0.543146 and 0.554724 m/km per √(10⁻⁶ m³).
#[test]
fn golden_car_iri_of_class_c_with_the_250_mm_moving_average() {
    let golden = |keys: &str| {
        format!(
            "[model]\nkind = \"mdof\"\nbase_inputs = 1\ncoordinates = [{{ name = \"body\", unit = \"m\", mass = \"1 kg\" }}, \
             {{ name = \"wheel\", unit = \"m\", mass = \"0.15 kg\" }}]\n\
             [[model.element]]\nname = \"suspension\"\npoint = [1, 0]\nto = [0, 1]\nstiffness = \"63.3 N/m\"\ndamping = \"6 N*s/m\"\n\
             [[model.element]]\nname = \"tyre\"\npoint = [0, 1]\nto = \"base 0\"\nstiffness = \"653 N/m\"\n\
             [[model.output]]\nname = \"damper\"\nquantity = \"damper-force\"\nelement = \"suspension\"\n\
             [input]\nspectrum = {{ kind = \"iso8608\", class = \"C\", unbounded = true }}\nspeed = \"80 km/h\"\n{keys}\n"
        )
    };
    let iri = |keys: &str| {
        let sc = parse(&golden(keys)).unwrap();
        let st = analyze_output(sc.model.system.as_ref(), &sc.excitation, 0).unwrap();
        (2.0 / PI).sqrt() * st.sigma.unwrap() / 6.0 / (80.0 / 3.6) * 1000.0
    };
    let with = iri("enveloping = { kind = \"moving-average\", length = \"250 mm\" }");
    assert!(rel(with, 8.690343) < PRINTED_7_DIGITS, "{with}");
    let without = iri("");
    assert!(rel(without, 8.875588) < PRINTED_7_DIGITS, "{without}");
}

/// A catalogue ISO 8608 class given an explicit band: `iso8608-d` with band [0.011, 30] cycles/m has the
/// variance of the class D law over that band, G_d(n₀) n₀² (1/n₁ − 1/n₂) with G_d(n₀) = 1024·10⁻⁶ m³ and
/// n₀ = 0.1 cycles/m; in rad/m the same band gives the same variance; the input now reaches 30 cycles/m × v.
/// A rational catalogue spectrum (type 1 in time, D = 1 cm², α = 2 s⁻¹) is restricted: on [0, 2 rad/s] its
/// variance is D (2/π) atan(ω₂/α) = D/2.
#[test]
fn an_explicit_band_on_catalogue_spectra() {
    let sc = parse(
        &quarter_car_text("20 m/s", "band = [\"0.011 cycles/m\", \"30 cycles/m\"]").replace("iso8608-c", "iso8608-d"),
    )
    .unwrap();
    let expected = 1024e-6 * 0.01 * (1.0 / 0.011 - 1.0 / 30.0);
    assert!(rel(sc.input.spectrum.variance().unwrap(), expected) < 1e2 * ROUNDING);
    assert!(rel(sc.excitation.support().1, 2.0 * PI * 30.0 * 20.0) < ROUNDING);
    let rad = format!("band = [\"{} rad/m\", \"{} rad/m\"]", 2.0 * PI * 0.011, 2.0 * PI * 30.0);
    let sc = parse(&quarter_car_text("20 m/s", &rad).replace("iso8608-c", "iso8608-d")).unwrap();
    assert!(rel(sc.input.spectrum.variance().unwrap(), expected) < 1e2 * ROUNDING);
    let seat = std::fs::read_to_string(root().join("data/operator-seat.toml")).unwrap();
    let start = seat.find("spectrum =").unwrap();
    let end = start + seat[start..].find('\n').unwrap();
    let text = format!(
        "{}spectrum = \"type1\"\nband = [\"0 rad/s\", \"2 rad/s\"]{}",
        &seat[..start],
        &seat[end..]
    );
    let sc = parse(&text).unwrap();
    assert!(rel(sc.input.spectrum.variance().unwrap(), 0.5e-4) < QUADRATURE);
}

/// Bad `band` and `enveloping` values are refused with the file, the key, the value and the reason: a bare
/// `1/m` (read as rad/m, 2π times less than cycles/m), a frequency of the wrong variable, edges out of
/// order, a band past a tabulated spectrum's data, an enveloping of a process in time, an unknown kind, a
/// length ≤ 0, an unknown key; in a `[road]` section the key is named `road.band`.
#[test]
fn bad_band_and_enveloping_values_name_file_key_value_and_reason() {
    let cases: [(&str, &str, &str, &str); 7] = [
        (
            "band = [\"0.011 1/m\", \"30 1/m\"]",
            "input.band[0]",
            "0.011 1/m",
            "cycles/m",
        ),
        ("band = [\"1 Hz\", \"30 Hz\"]", "input.band[0]", "1 Hz", ""),
        (
            "band = [\"30 cycles/m\", \"1 cycles/m\"]",
            "input.band",
            "30 cycles/m",
            "low < high",
        ),
        (
            "enveloping = { kind = \"pneumatic\", length = \"0.25 m\" }",
            "input.enveloping.kind",
            "pneumatic",
            "moving-average",
        ),
        (
            "enveloping = { kind = \"moving-average\", length = \"-0.25 m\" }",
            "input.enveloping.length",
            "-0.25",
            "> 0",
        ),
        (
            "enveloping = { kind = \"moving-average\", length = \"4 s\" }",
            "input.enveloping.length",
            "4 s",
            "",
        ),
        (
            "enveloping = { kind = \"moving-average\", length = \"0.2 m\", width = \"0.2 m\" }",
            "input.enveloping.width",
            "0.2 m",
            "unknown key",
        ),
    ];
    for (keys, key, value, reason) in cases {
        let (k, v, r) = file_error(parse(&quarter_car_text("20 m/s", keys)).unwrap_err());
        assert_eq!(k, key, "{keys}: {r}");
        assert!(v.contains(value) && r.contains(reason), "{keys}: {v} / {r}");
    }
    // past the data of a tabulated spectrum
    let text = quarter_car_text("20 m/s", "band = [\"0.011 cycles/m\", \"30 cycles/m\"]")
        .replace("iso8608-c", "measured-road-example");
    let (k, _, r) = file_error(parse(&text).unwrap_err());
    assert!(
        k == "input.band" && r.contains("2.83") && r.contains("not") && r.contains("extend"),
        "{k}: {r}"
    );
    // a process in time
    let seat = std::fs::read_to_string(root().join("data/operator-seat.toml")).unwrap();
    let text = seat.replace(
        "[analysis]",
        "enveloping = { kind = \"moving-average\", length = \"0.25 m\" }\n[analysis]",
    );
    let (k, _, r) = file_error(parse(&text).unwrap_err());
    assert!(k == "input.enveloping" && r.contains("in time"), "{k}: {r}");
    // a [road] section
    let full = std::fs::read_to_string(root().join("data/full-vehicle-two-tracks.toml")).unwrap();
    let road = full
        .replace("[[input]]\nname = \"road\"\nroad = { spectrum = \"iso8608-c\", track_width = \"1.5 m\", coherence = { kind = \"dodds-robson\", waviness = 2 } }",
                 "[road]\nspectrum = \"iso8608-c\"\ncoherence = { kind = \"dodds-robson\" }\nband = [\"0.011 1/m\", \"5 1/m\"]");
    assert_ne!(road, full);
    let (k, _, _) = file_error(parse(&road).unwrap_err());
    assert_eq!(k, "road.band[0]");
}

/// A default Monte Carlo run of the quarter car on an enveloped class C road (band 0.1–30 cycles/m, 250 mm
/// moving average, 20 m/s) takes the spectral route; the body acceleration (which the enveloping shapes) has
/// a discretisation bias below a quarter of its interval's half-width and its interval covers the analytic
/// σ; every interval covers the exact σ of the simulated discrete process (the travel's grid bias at the
/// band's lower edge is left over its target by the suggestion, which says so). A miss needs a deviation
/// beyond ≈ 3.7 (body acceleration, shifted by its bias) or 5 (σ_d) standard errors of an interval at
/// confidence 1 − 2.5·10⁻⁷: the false-failure probability is at most 4 × 2.5·10⁻⁷ = 10⁻⁶ (union bound).
#[test]
fn default_monte_carlo_of_an_enveloped_road_covers_the_analytic_sigma() {
    let keys = ENVELOPED.replace("0.011 cycles/m", "0.1 cycles/m");
    let sc = parse(
        &quarter_car_text("20 m/s", &keys)
            .replace("band = [\"0.5 Hz\", \"80 Hz\"]", "outputs = [\"body_acc\", \"travel\"]"),
    )
    .unwrap();
    let s = sc.suggest_step(40).unwrap();
    assert!(
        s.reason.contains("still over its target") && s.reason.contains("`travel`"),
        "{}",
        s.reason
    );
    let opts = RunOptions {
        confidence: 1.0 - 2.5e-7,
        realizations: 40,
        duration_s: s.duration_s,
        dt_s: s.dt_s,
        seed: 5,
        ..RunOptions::default()
    };
    assert_eq!(planned_memory(&sc.run_input(), &opts).unwrap().route, Route::Spectral);
    let file = crate::common::scratch_kept("input-keys", "run").join("run.h5");
    let run = sc.simulate(&opts, &file, &|_, _| {}).unwrap();
    let _ = std::fs::remove_file(&file);
    for name in ["body_acc", "travel"] {
        let st = run.statistic(name, "sigma").unwrap();
        let d = run.statistic(name, "sigma_discrete").unwrap().analytic.unwrap();
        assert!(st.interval.covers(d), "{name}: σ_d {d} vs {:?}", st.interval);
    }
    let st = run.statistic("body_acc", "sigma").unwrap();
    let d = run.statistic("body_acc", "sigma_discrete").unwrap().analytic.unwrap();
    let (a, iv) = (st.analytic.unwrap(), st.interval);
    assert!(
        (d - a).abs() < 0.25 * 0.5 * (iv.upper - iv.lower),
        "bias {d} vs {a}, {iv:?}"
    );
    assert_eq!(st.covers, Some(true), "{a} vs {iv:?} at Δt = {} s", s.dt_s);
}
