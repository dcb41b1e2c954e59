//! An input band that stops below the weighting band: the ISO 8608 class spectra stop at 2.83 cycles/m,
//! i.e. at 8.5 Hz at 3 m/s, while Wk weights up to its band-limiting corner f₂ = 100 Hz. The analysis says
//! so (the covered fraction and a_w with the road's power law continued to f₂), and the fix (an explicit
//! spatial band to 100/3 cycles/m) gives that same a_w; both are checked against a product-form integral
//! written in this file.

use crate::common;

use common::tolerance::{EXACT, QUADRATURE};
use common::{rel, root};
use std::f64::consts::PI;
use stochvib::comfort::Weighting;
use stochvib::scenario::{parse_scenario, Scenario};
use stochvib::study::verdict_analysis;

const SPEED: f64 = 3.0;

/// `data/quarter-car.toml` at 3 m/s with its body acceleration as a Wk seat-surface z axis; `spectrum`
/// replaces the road (`None`: the catalogue's `iso8608-c`, band 0.011–2.83 cycles/m).
fn quarter_car_wk(spectrum: Option<&str>) -> Scenario {
    let text = std::fs::read_to_string(root().join("data/quarter-car.toml")).unwrap();
    let mut text = text
        .replace("speed = \"20 m/s\"", "speed = \"3 m/s\"")
        .split("[analysis.levels]")
        .next()
        .unwrap()
        .to_string();
    if let Some(s) = spectrum {
        text = text.replace("spectrum = \"iso8608-c\"", &format!("spectrum = {s}"));
    }
    text.push_str(
        "[analysis.comfort]\npurpose = \"health\"\nexposure = \"8 h\"\n[[analysis.comfort.axis]]\n\
         output = \"body_acc\"\nlocation = \"seat-surface\"\naxis = \"z\"\n",
    );
    parse_scenario(&text, &root().join("data/quarter-car-wk.toml"), &root().join("spectra")).unwrap()
}

/// a_w of the body acceleration with the class C road's power law from 0.011 cycles/m up to f₂ = 100 Hz:
/// a_w² = 2∫_{ω_lo}^{ω₂} |W_k(iω)|² |H(iω)|² S(ω) dω, S(ω) = G_d(ω/(2πv))/(4πv) (ISO 8608's one-sided
/// spatial G_d in m³ to the two-sided temporal density: S_Ω(Ω) = G_d(Ω/2π)/(4π) and
/// S_t(ω) = S_Ω(ω/v)/v), G_d(n) = 256·10⁻⁶ (n/0.1)⁻² m³; Simpson's rule in ln ω on 40 000 intervals (the
/// integrand is smooth between the band's ends; its h⁴ error is below 1e-12 relative).
fn power_law_a_w(sc: &Scenario) -> f64 {
    let sys = sc.model.system.as_ref();
    let i = sys.outputs().iter().position(|o| o.name == "body_acc").unwrap();
    let g_d = |n: f64| 256e-6 * (n / 0.1).powi(-2);
    let s = |w: f64| g_d(w / (2.0 * PI * SPEED)) / (4.0 * PI * SPEED);
    let g = |w: f64| Weighting::Wk.response(w).norm_sqr() * sys.response(w)[(i, 0)].norm_sqr() * s(w);
    (2.0 * common::simpson_log(g, 2.0 * PI * 0.011 * SPEED, 2.0 * PI * 100.0, 40_000)).sqrt()
}

/// Before: a_w of the class C road at 3 m/s was reported without a word about the 91.5 % of the weighting
/// band (8.5 → 100 Hz) the road does not reach. After: the analysis states the input's edge (2.83 cycles/m
/// × 3 m/s = 8.49 Hz), the continued power law's exponent (2 for ISO 8608), a_w continued to 100 Hz (equal
/// to the product-form integral above), and the covered fraction (a_w/a_w,c)²; with the explicit band
/// ["0.011 cycles/m", "33.333333333333333 cycles/m"] (100 Hz at 3 m/s) the reported a_w is that value and
/// nothing is flagged; the text report prints the warning and offers both fixes (band, enveloping).
#[test]
fn an_input_band_below_the_weighting_band_is_flagged_and_continued() {
    let sc = quarter_car_wk(None);
    let oracle = power_law_a_w(&sc);
    let c = verdict_analysis(&sc).unwrap().comfort.unwrap();
    let ax = &c.axes[0];
    let cov = ax.input_coverage.as_ref().expect("the road stops at 8.5 Hz: flagged");
    assert!(rel(cov.input_edge_hz, 2.83 * SPEED) < EXACT, "{}", cov.input_edge_hz);
    assert_eq!(cov.weighting_edge_hz, 100.0);
    assert!((cov.exponent - 2.0).abs() < EXACT, "{}", cov.exponent);
    assert!(
        rel(cov.a_w_continued, oracle) < QUADRATURE,
        "{} vs {oracle}",
        cov.a_w_continued
    );
    assert!(rel(cov.covered_fraction, (ax.a_w / oracle).powi(2)) < QUADRATURE);
    assert!(cov.covered_fraction < 0.9, "{}", cov.covered_fraction);
    let text = stochvib::study::analysis_report(&sc).unwrap().to_string();
    assert!(
        text.contains("INPUT BAND: the input `road` stops at 8.490 Hz"),
        "{text}"
    );
    // the report offers both fixes: an explicit band and the tyre's enveloping
    assert!(
        text.contains("Fix: give the input an explicit band, e.g. band = [") && text.contains("enveloping = {"),
        "{text}"
    );
    // the fix: the band to 100 Hz at 3 m/s
    let band = "{ kind = \"iso8608\", class = \"C\", band = [\"0.011 cycles/m\", \"33.333333333333333 cycles/m\"] }";
    let fixed = quarter_car_wk(Some(band));
    let c = verdict_analysis(&fixed).unwrap().comfort.unwrap();
    assert!(rel(c.axes[0].a_w, oracle) < QUADRATURE, "{} vs {oracle}", c.axes[0].a_w);
    assert!(c.axes[0].input_coverage.is_none());
}
