//! Band tables of an output: IEC 61260-1 base-10 band r.m.s. by the band integral of
//! the output density, against a closed form, the whole-axis sum against the Lyapunov σ², and the
//! scenario key `[analysis] bands` with its validation and its place in the `analyze` report.

use crate::common;
use common::rel;
use common::tolerance::{EXACT, QUADRATURE};
use std::f64::consts::PI;
use std::path::Path;
use std::sync::Arc;
use stochvib::comfort::{bands_covering, output_band_row, output_band_table, BandFraction, BAND_COVERAGE};
use stochvib::response::{variance_lyapunov, Excitation};
use stochvib::scenario::parse_scenario;
use stochvib::spectrum::{Domain, Exponential};
use stochvib::study::analysis_report;
use stochvib::system::{OutputInfo, TransferFunction};

/// First-order filter H(s) = a/(s + a) on an exponentially correlated input (type 1) of variance D and
/// rate α: the case with a closed-form band integral.
const A: f64 = 6.0; // rad/s
const ALPHA: f64 = 2.0; // 1/s
const D: f64 = 1.0e-4; // m²

/// # Closed form
/// S_u(ω) = αD/(π(α² + ω²)) (type 1, docs/conventions.md), |H(iω)|² = a²/(a² + ω²), and by partial fractions
/// 1/((α² + ω²)(a² + ω²)) = [1/(α² + ω²) − 1/(a² + ω²)]/(a² − α²), with ∫ dω/(c² + ω²) = atan(ω/c)/c.
/// The band mean square over [f_1, f_2] (both signs of ω, so twice the positive-ω integral), ωₖ = 2πfₖ:
/// ```text
/// σ²_band = 2a²αD/(π(a² − α²)) · [ (atan(ω₂/α) − atan(ω₁/α))/α − (atan(ω₂/a) − atan(ω₁/a))/a ]
/// ```
/// Over [0, ∞) the bracket is (π/2)(1/α − 1/a), so σ² = aD/(a + α) (= 7.5e-5 m² here).
fn closed_band(f1: f64, f2: f64) -> f64 {
    let (w1, w2) = (2.0 * PI * f1, 2.0 * PI * f2);
    let at = |c: f64| ((w2 / c).atan() - (w1 / c).atan()) / c;
    2.0 * A * A * ALPHA * D / (PI * (A * A - ALPHA * ALPHA)) * (at(ALPHA) - at(A))
}

fn case() -> (TransferFunction, Excitation) {
    let h = TransferFunction::new(vec![A], vec![A, 1.0], OutputInfo::new("y", "m")).unwrap();
    let exc = Excitation::single(Arc::new(Exponential::new(D, ALPHA, Domain::Temporal).unwrap()), 0.0).unwrap();
    (h, exc)
}

#[test]
fn every_band_equals_the_arctan_closed_form() {
    let (h, exc) = case();
    let total = A * D / (A + ALPHA); // closed form above
    for fraction in [BandFraction::Octave, BandFraction::ThirdOctave] {
        let t = output_band_table(&h, &exc, 0, fraction, Some(total), None).unwrap();
        assert!(t.rows.len() >= 3, "{fraction:?}: {} bands", t.rows.len());
        for (k, r) in t.rows.iter().enumerate() {
            let want = closed_band(r.band.lower_hz, r.band.upper_hz);
            assert!(
                rel(r.mean_square, want) < QUADRATURE,
                "{}: {} vs {want}",
                r.band.label(),
                r.mean_square
            );
            assert!(rel(r.rms, want.sqrt()) < QUADRATURE);
            if k > 0 {
                assert_eq!(r.band.index, t.rows[k - 1].band.index + 1); // contiguous
            }
        }
        // the automatic choice holds at least BAND_COVERAGE of σ² and, the bands being disjoint, no more
        // than σ²
        let c = t.coverage().unwrap();
        assert!(
            (BAND_COVERAGE..=1.0 + QUADRATURE).contains(&c),
            "{fraction:?}: coverage {c}"
        );
        // ... and is the fewest such bands: dropping the smaller end band falls below the coverage
        let ends = t.rows[0].mean_square.min(t.rows[t.rows.len() - 1].mean_square);
        assert!(t.sum_mean_square - ends < BAND_COVERAGE * total);
    }
}

#[test]
fn contiguous_bands_over_the_whole_axis_sum_to_the_lyapunov_variance() {
    // One-third octaves from 10⁻⁴ Hz to 10⁴ Hz, plus the two tails [0, f_1) and [f_2, ∞) by the closed form
    // (the tails are ≈ 3e-4 and ≈ 1e-5 of σ² here, so the test sees the bands, not the tails): the sum is
    // the Lyapunov σ² (exact route, independent of the band quadrature) and the closed form aD/(a + α).
    let (h, exc) = case();
    let bands = bands_covering(BandFraction::ThirdOctave, 1e-4, 1e4).unwrap();
    for k in 1..bands.len() {
        assert!(rel(bands[k].lower_hz, bands[k - 1].upper_hz) < EXACT);
    }
    let sum: f64 = bands
        .iter()
        .map(|b| output_band_row(&h, &exc, 0, *b).unwrap().mean_square)
        .sum();
    let (f_lo, f_hi) = (bands[0].lower_hz, bands[bands.len() - 1].upper_hz);
    let tails = closed_band(0.0, f_lo) + closed_band(f_hi, f64::INFINITY);
    let lyapunov = variance_lyapunov(&h, &exc, 0).unwrap().variance;
    assert!(rel(lyapunov, A * D / (A + ALPHA)) < EXACT);
    assert!(rel(sum + tails, lyapunov) < QUADRATURE, "{} vs {lyapunov}", sum + tails);
}

fn scenario_text(bands: &str, band: &str) -> String {
    format!(
        r#"
title = "first-order filter"
source = "test"
[model]
kind = "transfer-function"
numerator = [{A}]
denominator = [{A}, 1]
output = {{ name = "y", unit = "m" }}
[input]
spectrum = {{ kind = "exponential", domain = "temporal", unit = "m", variance = "{D} m^2", alpha = "{ALPHA} 1/s" }}
[analysis]
{bands}
{band}
"#
    )
}

fn spectra() -> std::path::PathBuf {
    crate::common::root().join("spectra")
}

#[test]
fn analyze_reports_the_band_table_in_text_and_json() {
    let text = scenario_text("bands = \"octave\"", "");
    let sc = parse_scenario(&text, Path::new("case.toml"), &spectra()).unwrap();
    let report = analysis_report(&sc).unwrap();
    let section = report.outputs[0].bands.as_ref().unwrap();
    let t = section.table.as_ref().unwrap();
    for r in &t.rows {
        let want = closed_band(r.band.lower_hz, r.band.upper_hz); // closed form of the first test
        assert!(rel(r.mean_square, want) < QUADRATURE);
    }
    // σ² of the table is the analysis' σ² (closed form aD/(a + α))
    assert!(rel(t.total_variance.unwrap(), A * D / (A + ALPHA)) < QUADRATURE);
    let shown = report.to_string();
    assert!(shown.contains("octave bands (IEC 61260-1 base 10)"), "{shown}");
    assert!(shown.contains("1 Hz") && shown.contains("% of σ²"), "{shown}");
    let json = serde_json::to_value(&report).unwrap();
    let rows = &json["outputs"][0]["bands"]["table"]["rows"];
    assert_eq!(rows.as_array().unwrap().len(), t.rows.len());
    assert!(rows[0]["band"]["centre_hz"].is_number() && rows[0]["rms"].is_number());
    // without the key: no band section, and none in the JSON
    let plain = parse_scenario(&scenario_text("", ""), Path::new("case.toml"), &spectra()).unwrap();
    let report = analysis_report(&plain).unwrap();
    assert!(report.outputs[0].bands.is_none());
    assert!(serde_json::to_value(&report).unwrap()["outputs"][0]
        .get("bands")
        .is_none());
}

#[test]
fn an_analysis_band_chooses_the_bands_it_covers() {
    // [analysis] band = 0.5 … 80 Hz: the 23 one-third octaves 0.5 … 80 Hz (ISO 2631-1's range; the same
    // count as the `bands_covering` doc example), each the closed form
    let text = scenario_text("bands = \"third-octave\"", "band = [\"0.5 Hz\", \"80 Hz\"]");
    let sc = parse_scenario(&text, Path::new("case.toml"), &spectra()).unwrap();
    let report = analysis_report(&sc).unwrap();
    let t = report.outputs[0].bands.as_ref().unwrap().table.as_ref().unwrap();
    assert_eq!(t.rows.len(), 23);
    assert_eq!((t.rows[0].band.nominal_hz, t.rows[22].band.nominal_hz), (0.5, 80.0));
    for r in &t.rows {
        assert!(rel(r.mean_square, closed_band(r.band.lower_hz, r.band.upper_hz)) < QUADRATURE);
    }
}

#[test]
fn an_unknown_band_kind_is_an_error_naming_file_key_value_and_reason() {
    for bad in ["bands = \"1/3-octave\"", "bands = 3"] {
        let text = scenario_text(bad, "");
        let err = parse_scenario(&text, Path::new("case.toml"), &spectra())
            .unwrap_err()
            .to_string();
        let value = bad.trim_start_matches("bands = ").trim_matches('"');
        for part in ["case.toml", "bands", value, "third-octave"] {
            assert!(err.contains(part), "`{part}` missing in: {err}");
        }
    }
}

#[test]
fn a_divergent_variance_without_a_band_gives_a_note_not_an_error() {
    // H(s) = s (the input's rate of change): S_y = ω²·αD/(π(α² + ω²)) → αD/π as ω → ∞, so σ² = ∞ and
    // the automatic choice has nothing to cover; the section says to give a band.
    let text = scenario_text("bands = \"octave\"", "").replace(
        &format!("numerator = [{A}]\ndenominator = [{A}, 1]"),
        "numerator = [0, 1]\ndenominator = [1]",
    );
    let sc = parse_scenario(&text, Path::new("case.toml"), &spectra()).unwrap();
    let report = analysis_report(&sc).unwrap();
    let section = report.outputs[0].bands.as_ref().unwrap();
    assert!(section.table.is_none());
    assert!(
        section.note.as_ref().unwrap().contains("[analysis] band"),
        "{:?}",
        section.note
    );
}
