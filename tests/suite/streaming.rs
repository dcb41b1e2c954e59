//! The streamed spectral route: white noise through FIR kernels designed from the
//! spectrum and the first-order-hold response, filtered by overlap-save with a fixed FFT size, so that a
//! statistics-only run of any (non-rational, delayed) input has memory independent of the duration.

use crate::common;
use common::root;
use common::tolerance::EXACT;
use common::{run_bits as bits, streamed};
use realfft::num_complex::Complex;
use std::path::PathBuf;
use stochvib::scenario::{parse_scenario, Scenario};
use stochvib::simulate::fir_stream::{GRID_TOLERANCE, TAIL_FRACTION};
use stochvib::simulate::resources::memory_bytes;
use stochvib::simulate::{planned_memory, stream, FirSynthesis, Route, RunOptions, RunSummary};

fn dir(tag: &str) -> PathBuf {
    crate::common::scratch_dir("stream", tag)
}

/// A shipped scenario with its `[analysis]` outputs replaced by `outputs`.
fn scenario(file: &str, outputs: &[&str]) -> Scenario {
    let path = root().join("data").join(file);
    let text = std::fs::read_to_string(&path).unwrap();
    let list = outputs
        .iter()
        .map(|o| format!("\"{o}\""))
        .collect::<Vec<_>>()
        .join(", ");
    let text = match text.find("outputs = [") {
        Some(start) => {
            let end = start + text[start..].find(']').unwrap() + 1;
            format!("{}outputs = [{list}]{}", &text[..start], &text[end..])
        }
        None => text.replacen("[analysis]\n", &format!("[analysis]\noutputs = [{list}]\n"), 1),
    };
    parse_scenario(&text, &path, &root().join("spectra")).unwrap()
}

/// The ISO 8608 class C quarter car at 20 m/s (road band 0.011–2.83 cycles/m, i.e. up to 356 rad/s).
fn quarter_car() -> Scenario {
    scenario("quarter-car.toml", &["travel", "tyre_force", "body_acc"])
}

/// The half car on the ISO class C road at 10 m/s: the rear wheel feels the front wheel's input delayed by
/// L/v = 2.7 m / 10 m/s = 0.27 s = 90 steps of 3 ms.
fn half_car() -> Scenario {
    scenario("half-car.toml", &["front_travel", "rear_travel", "body_acc"])
}

/// (a) The statistics and densities of a streamed run are bit-identical for any block size (1, 7 and 5000
/// steps, and one block for the whole realization): the draws come per overlap-save segment, whose size is
/// fixed by the kernels, and the running sums and Welch segments are fed in time order.
#[test]
fn streamed_statistics_are_bit_identical_for_any_block_size() {
    let d = dir("blocks");
    let sc = quarter_car();
    let mut all = Vec::new();
    for (k, block) in [1usize, 7, 5000, usize::MAX].into_iter().enumerate() {
        let mut o = streamed(5, 80.0, 0.004, 3);
        o.shard_size = 3;
        o.block_steps = block;
        let out = d.join(format!("b{k}.h5"));
        let s = sc.simulate(&o, &out, &|_, _| {}).unwrap();
        assert_eq!(s.route, Route::SpectralStream);
        all.push(bits(&s, &out));
    }
    assert!(all.windows(2).all(|w| w[0] == w[1]));
    let _ = std::fs::remove_dir_all(&d);
}

/// σ interval of `name` and its stated values: (lower, upper, analytic σ, exact σ of the simulated process).
fn sigma(s: &RunSummary, name: &str) -> (f64, f64, f64, f64) {
    let o = s.outputs.iter().find(|o| o.output == name).unwrap();
    let sg = o.get("sigma").unwrap();
    let sd = o.get("sigma_discrete").unwrap();
    (
        sg.interval.lower,
        sg.interval.upper,
        sg.analytic.unwrap(),
        sd.analytic.unwrap(),
    )
}

/// (b) The streamed route is unbiased for the process it simulates and that process is the analytic one up
/// to the stated bias, for an ISO road quarter car and a delayed two-wheel (half-car) case.
///
/// * The σ interval covers the exact σ of the simulated FIR process (`sigma_discrete`, Σ k² of the taps).
///   Intervals at confidence 1 − 1e-7 (Student t on the per-realization mean squares: 40 realizations of
///   200 s, each hundreds of correlation times of the 1–10 Hz responses, so the mean squares are nearly
///   Gaussian and the t law is accurate): 6 intervals, false-failure probability
///   ≤ 6·1e-7 < 1e-6 (union bound).
/// * Hence it covers the analytic σ after allowing the stated bias |σ_discrete − σ_analytic|, and that bias
///   is checked against an independent method: the whole-record spectral route (periodic synthesis, one
///   inverse FFT of N = 2¹⁹ points, `sigma_discrete` = its exact grid σ) simulates the same first-order-hold
///   response of the same spectrum truncated at Nyquist. The streamed σ differs from it only by the window
///   tail (≤ TAIL_FRACTION of the variance, σ by half of it) and the grid of the kernel (variance change over
///   the last doubling ≤ GRID_TOLERANCE, and the error of a rectangle rule at a band edge halves per
///   doubling, so the remaining grid error is ≤ GRID_TOLERANCE of the variance); the 2¹⁹ grid has its own
///   error of the same kind, smaller. So |σ_stream/σ_periodic − 1| ≤ (TAIL_FRACTION + 2·GRID_TOLERANCE)/2.
#[test]
fn streamed_sigma_covers_the_simulated_and_the_analytic_sigma() {
    let d = dir("cover");
    let cases = [
        (quarter_car(), 0.004, ["travel", "tyre_force", "body_acc"]),
        (half_car(), 0.003, ["front_travel", "rear_travel", "body_acc"]),
    ];
    for (k, (sc, dt, names)) in cases.iter().enumerate() {
        let mut o = streamed(40, 200.0, *dt, 11 + k as u64);
        o.confidence = 1.0 - 1e-7;
        o.shard_size = 20;
        let s = sc.simulate(&o, &d.join(format!("s{k}.h5")), &|_, _| {}).unwrap();
        assert_eq!(s.route, Route::SpectralStream);
        let mut p = RunOptions {
            realizations: 2,
            duration_s: (1 << 19) as f64 * dt,
            dt_s: *dt,
            seed: 1,
            ..RunOptions::default()
        };
        p.route = Route::Spectral;
        let periodic = sc.simulate(&p, &d.join(format!("p{k}.h5")), &|_, _| {}).unwrap();
        for name in names {
            let (lo, hi, analytic, discrete) = sigma(&s, name);
            assert!(
                lo <= discrete && discrete <= hi,
                "{name}: [{lo}, {hi}] misses σ_d {discrete}"
            );
            let bias = (discrete - analytic).abs();
            assert!(lo - bias <= analytic && analytic <= hi + bias, "{name}");
            let (_, _, _, reference) = sigma(&periodic, name);
            let limit = (TAIL_FRACTION + 2.0 * GRID_TOLERANCE) / 2.0;
            assert!(
                (discrete / reference - 1.0).abs() <= limit,
                "{name}: streamed σ_d {discrete} vs periodic σ_d {reference} (analytic {analytic})"
            );
        }
    }
    let _ = std::fs::remove_dir_all(&d);
}

/// (c) The kernels against slow direct sums: (i) the designed taps equal the circular kernel
/// h[m] = b₀ + 2 Re Σ_{j=1}^{L/2−1} b_j e^{2πijm/L} + b_{L/2}(−1)^m summed term by term (no FFT) at the
/// window's lags; (ii) the streamed output equals the direct convolution Σ_g Σ_i k_{g,r}[i] w_g[n − i] of the
/// same white noise (regenerated in the documented order: T − 1 samples per generator, then H per generator
/// per segment). Rounding: the direct sums have ≤ L/2 terms of magnitude ≤ |b_j| (resp. ≤ T·G terms of
/// magnitude ≤ |k||w|), the FFTs O(log F) roundings per output, so the differences are far below
/// EXACT = 1e-12 (≈ 4500 ε) of the sum of magnitudes.
#[test]
fn kernels_and_streamed_output_match_direct_sums() {
    // (i) a causal first-order low-pass H = 1/(1 + iωτ), τ = 0.05 s, on a band-limited white input
    // S = 1 for |ω| ≤ 40 rad/s, Δt = 0.01 s: b_j = H(ω_j) √(S(ω_j)Δω/L)
    let (dt, tau) = (0.01, 0.05);
    let b = move |l: usize| -> Vec<Complex<f64>> {
        let dw = 2.0 * std::f64::consts::PI / (l as f64 * dt);
        (0..=l / 2)
            .map(|j| {
                let w = j as f64 * dw;
                let s = if w <= 40.0 { 1.0 } else { 0.0 };
                Complex::new(1.0, w * tau).inv() * (s * dw / l as f64).sqrt()
            })
            .collect()
    };
    let (fir, design) = FirSynthesis::design(&|l| Ok(vec![vec![b(l)]]), 0, TAIL_FRACTION, GRID_TOLERANCE).unwrap();
    let l = design.grid_len;
    let bj = b(l);
    let scale: f64 = bj.iter().map(|c| 2.0 * c.norm()).sum();
    for (i, tap) in fir.kernel(0, 0).iter().enumerate() {
        let m = design.first_lag + i as i64;
        let mut h = bj[0].re + bj[l / 2].re * if m.rem_euclid(2) == 0 { 1.0 } else { -1.0 };
        for (j, c) in bj.iter().enumerate().take(l / 2).skip(1) {
            let ph = 2.0 * std::f64::consts::PI * ((j as i64 * m).rem_euclid(l as i64)) as f64 / l as f64;
            h += 2.0 * (c * Complex::new(ph.cos(), ph.sin())).re;
        }
        assert!((h - tap).abs() <= EXACT * scale, "lag {m}: {h} vs {tap}");
    }
    assert!(design.tail_fraction[0] <= TAIL_FRACTION);

    // (ii) 2 generators, 2 outputs, 37 seeded taps; 3 segments against the direct convolution
    let t = 37;
    let mut rng = stream(99, 0);
    let kernels: Vec<Vec<Vec<f64>>> = (0..2)
        .map(|_| {
            (0..2)
                .map(|_| (0..t).map(|_| stochvib::simulate::standard_normal(&mut rng)).collect())
                .collect()
        })
        .collect();
    let fir = FirSynthesis::from_taps(kernels.clone()).unwrap();
    let h = fir.hop();
    let mut sc = fir.scratch();
    let mut rng = stream(5, 1);
    fir.start(&mut rng, &mut sc);
    let mut got = [Vec::new(), Vec::new()];
    for _ in 0..3 {
        fir.next_segment(&mut rng, &mut sc).unwrap();
        for (r, g) in got.iter_mut().enumerate() {
            g.extend_from_slice(fir.output(&sc, r));
        }
    }
    // the noise in the documented order
    let mut rng = stream(5, 1);
    let mut w = [Vec::new(), Vec::new()];
    for wg in w.iter_mut() {
        wg.extend((0..t - 1).map(|_| stochvib::simulate::standard_normal(&mut rng)));
    }
    for _ in 0..3 {
        for wg in w.iter_mut() {
            wg.extend((0..h).map(|_| stochvib::simulate::standard_normal(&mut rng)));
        }
    }
    for r in 0..2 {
        for n in 0..3 * h {
            let (mut y, mut mag) = (0.0, 0.0);
            for g in 0..2 {
                for i in 0..t {
                    // output n is at noise index n + T − 1
                    let v = kernels[g][r][i] * w[g][n + t - 1 - i];
                    y += v;
                    mag += v.abs();
                }
            }
            assert!(
                (y - got[r][n]).abs() <= EXACT * mag,
                "r {r} n {n}: {y} vs {}",
                got[r][n]
            );
        }
    }
}

/// (d) The planned memory of the streamed route does not grow with the duration (10⁵ … 10⁹ samples per
/// realization give the same estimate), while the whole-record estimate grows in proportion; the automatic
/// route takes the streamed route for a record whose whole-record buffers (≥ 8 bytes × 10¹¹ samples × 4
/// signals = 3.2 TB) exceed any machine's memory.
#[test]
fn planned_memory_does_not_grow_with_the_duration() {
    let sc = quarter_car();
    let input = sc.run_input();
    let dt = 0.004;
    let mut planned = Vec::new();
    for samples in [1e5, 1e7, 1e9] {
        let o = streamed(10, samples * dt, dt, 1);
        let m = planned_memory(&input, &o).unwrap();
        assert_eq!(m.route, Route::SpectralStream);
        planned.push(m.bytes);
        let whole = memory_bytes(samples as usize, 3, 1, &o, 2);
        assert!(whole as f64 >= samples * 8.0 * 4.0, "{whole}");
    }
    assert!(planned.windows(2).all(|w| w[0] == w[1]), "{planned:?}");
    // a few MB: kernels of a few thousand taps (not a bound of the design, a check that nothing of the
    // record's size is counted: 10⁹ samples would be 8 GB per signal)
    assert!(planned[0] < 1 << 30, "{}", planned[0]);
    let auto = RunOptions {
        realizations: 10,
        duration_s: 1e11 * dt,
        dt_s: dt,
        seed: 1,
        ..RunOptions::default()
    };
    let m = planned_memory(&input, &auto).unwrap();
    assert_eq!(m.route, Route::SpectralStream);
    assert_eq!(m.bytes, planned[0]);
}
