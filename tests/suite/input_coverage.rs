//! Input coverage for every input form and every quantity that depends on the input's band: several
//! independent `[[input]]` tables, a road of two coherent tracks, a band table and fatigue moments. Each
//! reported "continued" value (the input's power law continued to the quantity's edge) is checked against
//! the same scenario with the band written out to that edge: for ISO 8608's w = 2 law the continuation
//! *is* the longer band, computed by another path (the power law's own band, not the continuation).

use crate::common;

use common::tolerance::{EXACT, QUADRATURE};
use common::{rel, root};
use std::f64::consts::PI;
use stochvib::scenario::{parse_scenario, Scenario};
use stochvib::study::verdict_analysis;

fn parse(text: &str) -> Scenario {
    parse_scenario(text, &root().join("data/input-coverage.toml"), &root().join("spectra")).unwrap()
}

const WK_AXIS: &str = "[analysis.comfort]\npurpose = \"health\"\nexposure = \"8 h\"\n[[analysis.comfort.axis]]\n\
                       output = \"{out}\"\nlocation = \"seat-surface\"\naxis = \"z\"\n";

/// The half car of `data/half-car.toml` at 3 m/s driven by two independent `[[input]]` tables, `front`
/// (class C) and `rear` (class B), with `front_band` and `rear_band` (cycles/m), and a Wk axis on the
/// driver's acceleration.
fn half_car(front_band: f64, rear_band: f64) -> Scenario {
    let text = std::fs::read_to_string(root().join("data/half-car.toml")).unwrap();
    let head = text.split("[input]").next().unwrap();
    let table = |name: &str, class: &str, drive: usize, top: f64| {
        format!(
            "[[input]]\nname = \"{name}\"\nspectrum = \"iso8608-{class}\"\nband = [\"0.011 cycles/m\", \"{top} cycles/m\"]\n\
             speed = \"3 m/s\"\ndrives = [{drive}]\n"
        )
    };
    parse(&format!(
        "{head}{}{}[analysis]\noutputs = [\"body_acc\"]\n{}",
        table("front", "c", 0, front_band),
        table("rear", "b", 1, rear_band),
        WK_AXIS.replace("{out}", "body_acc")
    ))
}

/// Two independent tables, front to 2.83 cycles/m (8.49 Hz at 3 m/s) and rear to 10 cycles/m (30 Hz): both
/// stop below Wk's f₂ = 100 Hz (100/3 cycles/m). The continued a_w equals a_w with both bands written to
/// 100/3 cycles/m; each source's own fraction equals a_w² over a_w² with that table's band alone written
/// out; the report names both inputs and their edges.
#[test]
fn several_independent_inputs_are_assessed_per_source() {
    let top = 100.0 / 3.0;
    let sc = half_car(2.83, 10.0);
    let c = verdict_analysis(&sc).unwrap().comfort.unwrap();
    let ax = &c.axes[0];
    let cov = ax.input_coverage.as_ref().expect("both inputs stop below 100 Hz");
    let a_w = |f: f64, r: f64| verdict_analysis(&half_car(f, r)).unwrap().comfort.unwrap().axes[0].a_w;
    let both = a_w(top, top);
    assert!(
        rel(cov.a_w_continued, both) < QUADRATURE,
        "{} vs {both}",
        cov.a_w_continued
    );
    assert!(rel(cov.covered_fraction, (ax.a_w / both).powi(2)) < QUADRATURE);
    let names: Vec<&str> = cov.sources.iter().map(|s| s.input.as_str()).collect();
    assert_eq!(names, ["front", "rear"]);
    assert!(rel(cov.sources[0].input_edge_hz, 2.83 * 3.0) < EXACT && rel(cov.sources[1].input_edge_hz, 30.0) < EXACT);
    let front_alone = (ax.a_w / a_w(top, 10.0)).powi(2);
    let rear_alone = (ax.a_w / a_w(2.83, top)).powi(2);
    assert!(rel(cov.sources[0].covered_fraction.unwrap(), front_alone) < QUADRATURE);
    assert!(rel(cov.sources[1].covered_fraction.unwrap(), rear_alone) < QUADRATURE);
    let text = stochvib::study::analysis_report(&sc).unwrap().to_string();
    assert!(
        text.contains("the inputs stop at `front` 8.490 Hz, `rear` 30.000 Hz"),
        "{text}"
    );
    // with both bands to f₂ nothing is flagged
    assert!(verdict_analysis(&half_car(top, top)).unwrap().comfort.unwrap().axes[0]
        .input_coverage
        .is_none());
}

/// The full vehicle of `data/full-vehicle-two-tracks.toml` (two coherent tracks, 20 m/s) with a Wk axis on
/// the seat: the road stops at 2.83 × 20 = 56.6 Hz; the continued a_w (both tracks continued, the
/// Dodds–Robson coherence kept) equals a_w with the road's band written to 100/20 = 5 cycles/m.
#[test]
fn two_coherent_tracks_are_continued_with_their_coherence() {
    let text = std::fs::read_to_string(root().join("data/full-vehicle-two-tracks.toml")).unwrap()
        + &WK_AXIS.replace("{out}", "seat_acc");
    let sc = parse(&text);
    let cov = verdict_analysis(&sc).unwrap().comfort.unwrap().axes[0]
        .input_coverage
        .clone()
        .expect("the road stops at 56.6 Hz");
    assert!(rel(cov.input_edge_hz, 2.83 * 20.0) < EXACT);
    let banded = parse(&text.replace(
        "speed = \"20 m/s\"",
        "speed = \"20 m/s\"\nband = [\"0.011 cycles/m\", \"5 cycles/m\"]",
    ));
    let c = verdict_analysis(&banded).unwrap().comfort.unwrap();
    assert!(c.axes[0].input_coverage.is_none());
    assert!(
        rel(cov.a_w_continued, c.axes[0].a_w) < QUADRATURE,
        "{} vs {}",
        cov.a_w_continued,
        c.axes[0].a_w
    );
}

/// `data/quarter-car.toml` at 3 m/s with `extra` appended (the levels dropped) and `band` on its input.
fn quarter_car(band: Option<f64>, extra: &str) -> Scenario {
    let text = std::fs::read_to_string(root().join("data/quarter-car.toml")).unwrap();
    let keys = band.map_or(String::new(), |b| {
        format!("\nband = [\"0.011 cycles/m\", \"{b} cycles/m\"]")
    });
    let text = text.replace("speed = \"20 m/s\"", &format!("speed = \"3 m/s\"{keys}"));
    parse(&(text.split("[analysis.levels]").next().unwrap().to_string() + extra))
}

/// A one-third-octave table of the quarter car's outputs over 0.5–80 Hz at 3 m/s: the road stops at
/// 8.49 Hz, inside the 8 Hz band; every band from there up is flagged, each with the band r.m.s. the road
/// continued to the table's top (89.1 Hz) gives — equal to the table of the same scenario with the band
/// written to 89.1/3 cycles/m — and the covered fraction of the table's mean square.
#[test]
fn a_band_table_above_the_input_band_is_flagged_and_continued() {
    let with_bands = |band| quarter_car(band, "bands = \"third-octave\"\n");
    let sc = with_bands(None);
    let r = stochvib::study::analysis_report(&sc).unwrap();
    let o = r.outputs.iter().find(|o| o.statistics.name == "body_acc").unwrap();
    let section = o.bands.as_ref().unwrap();
    let table = section.table.as_ref().unwrap();
    let cov = section.input_coverage.as_ref().expect("the road stops at 8.49 Hz");
    let top = table.rows.last().unwrap().band.upper_hz;
    assert!(rel(cov.table_edge_hz, top) < EXACT && top > 80.0);
    assert_eq!(cov.bands.first().unwrap().band, "8 Hz");
    assert_eq!(
        cov.bands.len(),
        table.rows.iter().filter(|r| r.band.upper_hz > 8.49).count()
    );
    let fixed = with_bands(Some(top / 3.0));
    let rf = stochvib::study::analysis_report(&fixed).unwrap();
    let of = rf.outputs.iter().find(|o| o.statistics.name == "body_acc").unwrap();
    let tf = of.bands.as_ref().unwrap().table.as_ref().unwrap();
    for b in &cov.bands {
        let row = tf.rows.iter().find(|r| r.band.label() == b.band).unwrap();
        assert!(
            rel(b.rms_continued, row.rms) < QUADRATURE,
            "{}: {} vs {}",
            b.band,
            b.rms_continued,
            row.rms
        );
    }
    assert!(rel(cov.covered_fraction, table.sum_mean_square / tf.sum_mean_square) < QUADRATURE);
    assert!(r
        .to_string()
        .contains("INPUT BAND: the input `road` stops at 8.490 Hz, below the top of `body_acc`'s band table"));
    assert!(of.bands.as_ref().unwrap().input_coverage.is_none());
}

/// Fatigue moments of the quarter car's suspension travel at 3 m/s: the continuation edge is 10 × the
/// fastest natural frequency (the wheel hop, close to √((k_s + k_t)/m_u) = 74.2 rad/s: 118 Hz within 5 %);
/// the continued m₀, m₂, m₄ equal the moments with the band written to that edge; the report says so.
#[test]
fn fatigue_moments_above_the_input_band_are_flagged_and_continued() {
    let fatigue = "[analysis.fatigue]\noutput = \"travel\"\nstress_factor = \"1e9 Pa/m\"\nk = 5\n\
                   reference_amplitude = \"120 MPa\"\nreference_cycles = 2e6\n";
    let sc = quarter_car(None, fatigue);
    let v = verdict_analysis(&sc).unwrap().fatigue.unwrap();
    let cov = v.input_coverage.as_ref().expect("the road stops at 8.49 Hz");
    let hop = 10.0 * (220e3f64 / 40.0).sqrt() / (2.0 * PI);
    assert!(rel(cov.model_edge_hz, hop) < 0.05, "{} vs {hop}", cov.model_edge_hz);
    let fixed = verdict_analysis(&quarter_car(Some(cov.model_edge_hz / 3.0), fatigue))
        .unwrap()
        .fatigue
        .unwrap();
    assert!(fixed.input_coverage.is_none());
    for (k, j) in [(0, 0), (1, 2), (2, 3)] {
        assert!(rel(cov.moments_continued[j], fixed.moments[j]) < QUADRATURE, "m{j}");
        assert!(
            rel(cov.covered_fractions[k], v.moments[j] / fixed.moments[j]) < QUADRATURE,
            "m{j}"
        );
    }
    assert!(cov.covered_fractions[2] < cov.covered_fractions[0]);
    let text = stochvib::study::analysis_report(&sc).unwrap().to_string();
    assert!(
        text.contains("below 10 × the model's fastest natural frequency"),
        "{text}"
    );
}
