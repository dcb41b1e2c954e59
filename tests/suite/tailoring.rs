//! Test tailoring (`stochvib tailor`, `study::tailoring`): the ERS and FDS of a spectrum file and of a
//! scenario output against integrals written here, and the refusals.

use crate::common::tolerance::{QUADRATURE, ULPS};
use crate::common::{cli_fails, cli_within, rel, root, simpson_log};
use std::f64::consts::PI;
use stochvib::extremes::{ErsFdsOptions, FdsMaterial};
use stochvib::scenario::{load_scenario, Catalogue};
use stochvib::study::tailoring::{tailoring_spectra, TailoringSource, TailoringTable};

/// |H|² of the relative displacement of a base-excited oscillator, f₀ Hz, quality factor Q, at ω rad/s.
fn h2(f0: f64, q: f64, w: f64) -> f64 {
    let w0 = 2.0 * PI * f0;
    1.0 / ((w0 * w0 - w * w).powi(2) + (w * w0 / q).powi(2))
}

fn options(frequencies_hz: Vec<f64>, duration_s: f64) -> ErsFdsOptions {
    ErsFdsOptions {
        frequencies_hz,
        q: 10.0,
        duration_s,
        material: FdsMaterial {
            b: 8.0,
            k: 2.0e9,
            c: 1.0e40,
        },
        rel_tol: 1e-11,
    }
}

/// (z_rms, n₀⁺, ERS, FDS) from the two moments ∫S|H|²dω and ∫ω²S|H|²dω over ω > 0 of a one-sided-in-ω
/// integrand, by Lalanne's definitions (docs/transients.md): z² = 2∫₀^∞ S|H|², n₀⁺ = ż/(2πz),
/// ERS = ω₀² z √(2 ln(n₀⁺T)), FDS = (K^b/C) n₀⁺T (√2 z)^b Γ(1 + b/2) (Γ(5) = 24 for b = 8).
fn expected(f0: f64, m0: f64, m2: f64, o: &ErsFdsOptions) -> [f64; 4] {
    let (z, v) = ((2.0 * m0).sqrt(), (2.0 * m2).sqrt());
    let n0 = v / (2.0 * PI * z);
    let nt = n0 * o.duration_s;
    let m = &o.material;
    let ers = (2.0 * PI * f0).powi(2) * z * (2.0 * nt.ln()).sqrt();
    let fds = m.k.powf(m.b) / m.c * nt * (2f64.sqrt() * z).powf(m.b) * 24.0;
    [z, n0, ers, fds]
}

/// Every point of `table` against [`expected`] from the moments (∫S|H|², ∫ω²S|H|²) that `moments` gives
/// at f₀; the FDS ∝ z⁸n₀ carries about eight times z's relative error.
fn check_points(table: &TailoringTable, o: &ErsFdsOptions, moments: impl Fn(f64) -> (f64, f64)) {
    for p in &table.points {
        let f0 = p.f0_hz;
        let (m0, m2) = moments(f0);
        let [z, n0, ers, fds] = expected(f0, m0, m2, o);
        let got = [p.z_rms, p.n0_plus, p.ers, p.fds];
        for (k, (name, want)) in [("z_rms", z), ("n0+", n0), ("ERS", ers), ("FDS", fds)]
            .into_iter()
            .enumerate()
        {
            let tol = if name == "FDS" { 10.0 * QUADRATURE } else { QUADRATURE };
            assert!(rel(got[k], want) < tol, "{f0} Hz: {name} {} against {want}", got[k]);
        }
    }
}

/// The catalogue's band-limited white acceleration (one-sided G₀ = 0.01 (m/s²)²/Hz on 1–80 Hz, so the
/// two-sided S = G₀/(4π) on 2π·1 ≤ |ω| ≤ 2π·80 rad/s), Q = 10, T = 1 h: the moments over the band by
/// Simpson's rule in ln ω (200 000 intervals: h = 2.2·10⁻⁵, against the resonance's relative half-width
/// 1/(2Q) = 0.05 the h⁴ error is below 10⁻¹²), at f₀ = 0.8 Hz (below the band), 10 Hz and 60 Hz.
#[test]
fn ers_and_fds_of_a_band_limited_white_spectrum_file() {
    let file = Catalogue::chosen(Some(&root().join("spectra")))
        .resolve("white-1-80hz", None)
        .unwrap();
    let o = options(vec![0.8, 10.0, 60.0], 3600.0);
    let table = tailoring_spectra(&TailoringSource::Spectrum(&file), &o).unwrap();
    let s = 0.01 / (4.0 * PI);
    let (lo, hi) = (2.0 * PI, 2.0 * PI * 80.0);
    check_points(&table, &o, |f0| {
        let m0 = simpson_log(|w| s * h2(f0, 10.0, w), lo, hi, 200_000);
        (m0, simpson_log(|w| w * w * s * h2(f0, 10.0, w), lo, hi, 200_000))
    });
    assert!(table.source.contains("white-1-80hz"), "{}", table.source);
}

/// The body acceleration of data/quarter-car.toml (ISO 8608 class C at 20 m/s, band-limited in ω to the
/// road's band at that speed) as the base: the moments of S_y|H|² with S_y from the dense reference
/// `response::output_density` (not the evaluator the route uses) by Simpson's rule in ln ω over the band
/// (400 000 intervals), at f₀ = 1.5 Hz (near the body mode) and 10 Hz (near wheel hop).
#[test]
fn ers_and_fds_of_a_scenario_output() {
    let root = root();
    let sc = load_scenario(&root.join("data/quarter-car.toml"), &root.join("spectra")).unwrap();
    let sys = sc.model.system.as_ref();
    let acc = sys.output_index("body_acc").unwrap();
    let o = options(vec![1.5, 10.0], 8.0 * 3600.0);
    let table = tailoring_spectra(
        &TailoringSource::Output {
            scenario: &sc,
            output: acc,
        },
        &o,
    )
    .unwrap();
    let (lo, hi) = sc.excitation.spectra()[0].support();
    assert!(
        lo > 0.0 && hi.is_finite(),
        "the road of this scenario is band-limited: {lo} {hi}"
    );
    let sy = |w: f64| stochvib::response::output_density(sys, &sc.excitation, acc, w);
    check_points(&table, &o, |f0| {
        let m0 = simpson_log(|w| sy(w) * h2(f0, 10.0, w), lo, hi, 400_000);
        (m0, simpson_log(|w| w * w * sy(w) * h2(f0, 10.0, w), lo, hi, 400_000))
    });
}

/// The command prints the library's table (JSON at full precision), with units on the command line; the
/// grid is logarithmic.
#[test]
fn the_command_prints_the_table_of_the_library() {
    let root = root();
    let args = [
        "tailor",
        "white-1-80hz",
        "--duration",
        "60 min",
        "--f-min",
        "10 Hz",
        "--f-max",
        "1000 Hz",
        "--points",
        "3",
        "--json",
    ];
    let o = cli_within(&args, &root, std::time::Duration::from_secs(120));
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let v: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    let pts = v["points"].as_array().unwrap();
    let f: Vec<f64> = pts.iter().map(|p| p["f0_hz"].as_f64().unwrap()).collect();
    // "10 Hz" reads as 2π·10 rad/s and back: the grid's ends within rounding
    for (got, want) in f.iter().zip([10.0, 100.0, 1000.0]) {
        assert!(rel(*got, want) < ULPS, "{f:?}");
    }
    assert_eq!(v["options"]["duration_s"].as_f64(), Some(3600.0));
    // at 10 Hz, inside the band: the same moments as the library test above
    let s = 0.01 / (4.0 * PI);
    let (lo, hi) = (2.0 * PI, 2.0 * PI * 80.0);
    let m0 = simpson_log(|w| s * h2(10.0, 10.0, w), lo, hi, 200_000);
    let z = pts[0]["z_rms"].as_f64().unwrap();
    assert!(rel(z, (2.0 * m0).sqrt()) < QUADRATURE, "{z}");
    let text = cli_within(&args[..args.len() - 1], &root, std::time::Duration::from_secs(120));
    let text = String::from_utf8_lossy(&text.stdout);
    assert!(text.contains("ERS [m/s^2]") && text.contains("Q = 10"), "{text}");
}

/// What is not a base acceleration, and options out of range, are refused with the flag, value and reason.
#[test]
fn the_command_refuses_what_is_not_a_base_acceleration() {
    let root = root();
    let road = cli_fails(1, &["tailor", "iso8608-c", "--duration", "1 h"], &root);
    assert!(road.contains("spatial"), "{road}");
    let body = cli_fails(
        1,
        &[
            "tailor",
            "--scenario",
            "data/quarter-car.toml",
            "--output-name",
            "body",
            "--duration",
            "1 h",
        ],
        &root,
    );
    assert!(body.contains("body") && body.contains("its unit is m"), "{body}");
    let unknown = cli_fails(
        1,
        &[
            "tailor",
            "--scenario",
            "data/quarter-car.toml",
            "--output-name",
            "cab",
            "--duration",
            "1 h",
        ],
        &root,
    );
    assert!(unknown.contains("cab"), "{unknown}");
    let length = cli_fails(1, &["tailor", "white-1-80hz", "--duration", "5 m"], &root);
    assert!(
        length.contains("--duration 5 m") && length.contains("expected s"),
        "{length}"
    );
    let order = cli_fails(
        1,
        &[
            "tailor",
            "white-1-80hz",
            "--duration",
            "1 h",
            "--f-min",
            "50 Hz",
            "--f-max",
            "5 Hz",
        ],
        &root,
    );
    assert!(order.contains("f-min") && order.contains("below f-max"), "{order}");
    let q = cli_fails(1, &["tailor", "white-1-80hz", "--duration", "1 h", "--q", "0.4"], &root);
    assert!(q.contains("quality factor"), "{q}");
    // 10⁸ frequencies would run ~17 minutes (10 µs a point) before printing; the grid holds at most 10⁶
    let many = cli_fails(
        1,
        &["tailor", "white-1-80hz", "--duration", "1 h", "--points", "100000000"],
        &root,
    );
    assert!(
        many.contains("points") && many.contains("100000000") && many.contains("at most 1000000"),
        "{many}"
    );
}

/// The heading writes the options as numbers, not every digit of a large one: Basquin b = 1e300 (it printed
/// 301 digits) reads `b = 1e300`.
#[test]
fn the_heading_writes_large_options_briefly() {
    let out = cli_within(
        &[
            "tailor",
            "white-1-80hz",
            "--duration",
            "1 h",
            "--b",
            "1e300",
            "--points",
            "2",
        ],
        &root(),
        std::time::Duration::from_secs(120),
    );
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    assert!(text.contains("Basquin b = 1e300,"), "{text}");
}
