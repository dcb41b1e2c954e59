//! The streamed spectral route with several independent input sources (`[[input]]` tables):
//! one white noise per component of every source through its own kernels, summed per output (a
//! multi-component source's coherence mixing is part of its kernels). Statistics bit-identical for any
//! block size; σ intervals cover the simulated and the analytic σ.

use crate::common;
use common::{run_bits as bits, streamed};
use std::path::PathBuf;
use stochvib::scenario::{parse_scenario, Scenario};
use stochvib::simulate::Route;

fn root() -> PathBuf {
    crate::common::root()
}

fn dir(tag: &str) -> PathBuf {
    crate::common::scratch_dir("stream-src", tag)
}

fn parse(text: &str) -> Scenario {
    parse_scenario(
        text,
        &root().join("data/test-stream-sources.toml"),
        &root().join("spectra"),
    )
    .unwrap()
}

const ROAD: &str = r#"{ kind = "exponential", domain = "spatial", variance = "1 cm^2", alpha = "0.2 1/m" }"#;
const FORCE: &str = r#"{ kind = "exponential", unit = "N", variance = "1e4 N^2", alpha = "3 1/s" }"#;

/// A quarter car (body 300 kg, wheel 40 kg, suspension 20 kN/m and 1.5 kN s/m, tyre 200 kN/m) on a road
/// (20 m/s) with an independent force on the body: two sources.
fn road_and_force() -> Scenario {
    parse(
        &common::quarter_car_scenario()
            .force()
            .then(&format!(
                r#"
[[input]]
name = "road"
spectrum = {ROAD}
speed = "20 m/s"
drives = [0]

[[input]]
name = "load"
spectrum = {FORCE}
drives = [1]
"#
            ))
            .text(),
    )
}

/// A body in bounce and roll on two wheels on two road tracks of constant coherence 0.4 (one
/// two-component source: its kernels carry the coherence mixing).
fn two_tracks() -> Scenario {
    parse(&common::two_wheels(
        r#"tracks = ["left", "right"]"#,
        "[1, 1]",
        &format!(
            r#"
[[input]]
road = {{ spectrum = {ROAD}, track_width = "1.5 m", coherence = {{ kind = "constant", coherence_amplitude = 0.4 }} }}
speed = "15 m/s"
"#
        ),
    ))
}

/// (a) Bit-identical statistics and densities for blocks of 1, 7 and 5000 steps and whole realizations:
/// the draws come per overlap-save segment (fixed by the kernels), generator after generator, and the
/// running sums and Welch segments are fed in time order.
#[test]
fn several_sources_stream_bit_identically_for_any_block_size() {
    let d = dir("blocks");
    for (c, sc) in [road_and_force(), two_tracks()].iter().enumerate() {
        let mut all = Vec::new();
        for (k, block) in [1usize, 7, 5000, usize::MAX].into_iter().enumerate() {
            let mut o = streamed(5, 40.0, 0.004, 3);
            o.shard_size = 3;
            o.block_steps = block;
            let out = d.join(format!("c{c}-b{k}.h5"));
            let s = sc.simulate(&o, &out, &|_, _| {}).unwrap();
            assert_eq!(s.route, Route::SpectralStream);
            all.push(bits(&s, &out));
        }
        assert!(all.windows(2).all(|w| w[0] == w[1]), "case {c}");
    }
    let _ = std::fs::remove_dir_all(&d);
}

/// (b) The σ interval of each output covers the exact σ of the simulated FIR process (`sigma_discrete`,
/// Σ_g Σ_i k² over every source's generators) and the analytic σ of the sources' summed response (the
/// run's analytic value: the Lyapunov/quadrature route of `analyze_output`, another method) after allowing
/// the stated bias |σ_discrete − σ_analytic|. Intervals at confidence 1 − 1e-7 (Student t on 40
/// per-realization mean squares of 200 s, hundreds of correlation times of the ≤ 1.5 Hz body modes, so
/// nearly Gaussian): 4 intervals, false-failure probability ≤ 4·1e-7 < 1e-6 (union bound). The bias itself
/// is bounded by the design (window tail ≤ 1e-4 of the variance, grid change ≤ 1e-3): |σ_d/σ_a − 1| ≤ 1e-3
/// for these smooth (exponential) spectra.
#[test]
fn several_sources_cover_the_simulated_and_the_analytic_sigma() {
    let d = dir("cover");
    let cases = [
        (road_and_force(), ["body", "travel"]),
        (two_tracks(), ["bounce", "roll"]),
    ];
    for (k, (sc, names)) in cases.iter().enumerate() {
        let mut o = streamed(40, 200.0, 0.004, 21 + k as u64);
        o.confidence = 1.0 - 1e-7;
        o.shard_size = 20;
        let s = sc.simulate(&o, &d.join(format!("s{k}.h5")), &|_, _| {}).unwrap();
        assert_eq!(s.route, Route::SpectralStream);
        for name in names {
            let o = s.outputs.iter().find(|o| o.output == *name).unwrap();
            let sg = o.get("sigma").unwrap();
            let (lo, hi) = (sg.interval.lower, sg.interval.upper);
            let analytic = sg.analytic.unwrap();
            let discrete = o.get("sigma_discrete").unwrap().analytic.unwrap();
            assert!(
                lo <= discrete && discrete <= hi,
                "{name}: [{lo}, {hi}] misses σ_d {discrete}"
            );
            let bias = (discrete - analytic).abs();
            assert!(bias <= 1e-3 * analytic, "{name}: σ_d {discrete} vs analytic {analytic}");
            assert!(lo - bias <= analytic && analytic <= hi + bias, "{name}");
        }
    }
    let _ = std::fs::remove_dir_all(&d);
}
