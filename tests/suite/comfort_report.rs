//! The comfort report: the motion sickness dose value (MSDV) of a Wf axis in `analyze`, and the
//! picture of a comfort axis (weighted density, one-third-octave band r.m.s., ISO 2631-1 Annex C scale).
//!
//! Provenance of the expected values:
//! * MSDV = (∫₀ᵀ a_w² dt)^{1/2} (ISO 2631-1:1997 clause 9.2) is a_w·√T for a stationary response (the
//!   integral of a_w² over T is T times the mean square). The report's MSDV comes from the Lyapunov a_w;
//!   it is compared with the quadrature a_w of the same weighted output (a different method, reported
//!   next to it) times √T.
//! * The band bars of the picture are compared with the whole-axis a_w: the band mean squares add up to
//!   the mean square over 0.5–80 Hz, which for Wk (band-limited to 0.4–100 Hz, ISO 2631-1 Annex A) holds
//!   nearly all of a_w² of this seat (the remainder is what lies outside the drawn bands).

use crate::common;

use stochvib::scenario::parse_scenario;

use stochvib::study::verdict_analysis;

const QUADRATURE: f64 = common::tolerance::QUADRATURE;

fn seat_with_wf_axis() -> stochvib::scenario::Scenario {
    let p = common::root().join("data/operator-seat-verdicts.toml");
    let text = std::fs::read_to_string(&p).unwrap().replace(
        "axis = \"z\"                         # Wk, k = 1 (ISO 2631-1 7.2.3)\n",
        "axis = \"z\"                         # Wk, k = 1 (ISO 2631-1 7.2.3)\n[[analysis.comfort.axis]]\noutput = \"seat_acc\"\nlocation = \"seat-surface\"\naxis = \"z\"\nweighting = \"Wf\"\n",
    );
    assert!(text.contains("\"Wf\""), "the scenario edit did not apply");
    parse_scenario(&text, &p, &common::root().join("spectra")).unwrap()
}

#[test]
fn msdv_of_a_wf_axis_is_reported() {
    let sc = seat_with_wf_axis();
    let v = verdict_analysis(&sc).unwrap();
    let c = v.comfort.as_ref().unwrap();
    let (wk, wf) = (&c.axes[0], &c.axes[1]);
    assert!(wk.msdv.is_none(), "MSDV is for Wf only");
    let quad = wf.a_w_quadrature.expect("the quadrature a_w of the Wf output");
    let expected = quad * c.exposure_s.sqrt();
    let got = wf.msdv.expect("MSDV of the Wf axis");
    assert!(
        common::rel(got, expected) < QUADRATURE,
        "MSDV {got} against a_w·√T {expected}"
    );
    // the text report prints it
    let text = v.to_string();
    assert!(text.contains("MSDV of ") && text.contains("m/s^1.5"), "{text}");
}

#[test]
fn weighted_density_picture_holds_density_bands_and_comfort_scale() {
    let sc = seat_with_wf_axis();
    let c = stochvib::plot::comfort_plots::weighted_density_chart(&sc, 0).unwrap();
    let sec = c.secondary.as_ref().unwrap();
    let bars = &sec.series[0].points;
    // 23 one-third octaves 0.5–80 Hz (IEC 61260-1 base-10 nominal centres 0.5, 0.63, …, 80), two points each
    assert_eq!(bars.len(), 46);
    let ms: f64 = bars.chunks(2).map(|p| p[0].1 * p[0].1).sum();
    let a_w = verdict_analysis(&sc).unwrap().comfort.unwrap().axes[0].a_w;
    // the bands miss only what the weighted seat acceleration has below 0.5 Hz and above 80 Hz
    assert!(
        ms.sqrt() <= a_w * (1.0 + QUADRATURE) && ms.sqrt() > 0.99 * a_w,
        "{} vs {a_w}",
        ms.sqrt()
    );
    // a_w ≈ 0.33 m/s², no band above it: the scale is drawn up to 2·a_w (0.315 and 0.5 m/s²)
    assert_eq!(sec.hlines.len(), 3, "a_w and two reactions");
    let dir = crate::common::scratch_path("comfort-report", "pic");
    let files = c.render(&dir, "weighted").unwrap();
    let svg = std::fs::read_to_string(files.iter().find(|f| f.extension().unwrap() == "svg").unwrap()).unwrap();
    for label in [
        "density of seat_acc_Wk",
        "band r.m.s. (one-third octaves)",
        "a little uncomfortable from 0.315",
        "fairly uncomfortable from 0.5",
        "a_w = ",
    ] {
        assert!(svg.contains(label), "the SVG lacks `{label}`");
    }
    // the Wf axis draws its own range, 0.1–0.5 Hz: 8 one-third octaves (0.1, 0.125, …, 0.5)
    let f = stochvib::plot::comfort_plots::weighted_density_chart(&sc, 1).unwrap();
    assert_eq!(f.secondary.unwrap().series[0].points.len(), 16);
    // `plot` of the scenario writes both pictures
    let all = stochvib::plot::scenario_plots(&sc, &dir).unwrap();
    assert_eq!(
        all.iter()
            .filter(|p| p.to_string_lossy().contains("weighted-density-"))
            .count(),
        4
    );
    std::fs::remove_dir_all(&dir).unwrap();
}
