//! Non-Gaussian roads: the Laplace moving average (LMA) of K. Bogsjö, K. Podgórski and
//! I. Rychlik, "Models for road surface roughness", Vehicle System Dynamics 50(5), 2012, keeps the spectrum
//! and reaches the prescribed kurtosis; the responses of a quarter car to it keep the Gaussian σ while their
//! fourth moments and extremes grow; kurtosis 3 is the Gaussian case.
//!
//! Every statistical assertion is seeded and states the probability that it would fail for a correct
//! implementation under a fresh seed.

use crate::common;
use std::path::Path;
use stochvib::estimate::{mean_interval, Welch};
use stochvib::scenario::parse_scenario;
use stochvib::simulate::{run_batch, LaplaceGrid, LaplaceMovingAverage, Route, RunOptions};
use stochvib::spectrum::{Domain, Exponential, Spectrum};
use stochvib::store::{RunFile, SignalGroup};

/// The textbook road (8.45) in SI: type 1 in space, D = 2.25e-4 m², α = 3.5 1/m, sampled every 5 cm.
fn road() -> Exponential {
    Exponential::new(2.25e-4, 3.5, Domain::Spatial).unwrap()
}

/// The Laplace moving average of kurtosis 6 of the road `q` on `n` samples of [`DX`].
fn road_of_kurtosis_6(q: &dyn Spectrum, n: usize) -> LaplaceMovingAverage {
    LaplaceMovingAverage::new(
        q,
        LaplaceGrid {
            dt: DX,
            n,
            kurtosis: 6.0,
        },
    )
    .unwrap()
}
const DX: f64 = 0.05;

/// Extra relative variance of a Welch average over K segments (Hann window w of M samples, hop M/2) of an
/// LMA with kernel `f` (f[l] for l = −L..L, stored at l + L) and ν̃ steps, at ω (rad per sample), from the
/// fourth cumulant 3ν̃ of the increments:
/// one segment's periodogram is I = |Σ_m ε_m a_m|² with a_m = Σ_k w_k f_{k−m} e^{−iωk}, so the cumulant adds
/// 3ν̃ Σ_m |a_m|²|b_m|² to Cov(I_s, I_t) (b of the other segment); relative to (E I)² = (Σ|a|²)² and over
/// the K² pairs of the average, with only neighbouring segments overlapping, the added relative variance is
/// (δ₀ + 2δ₁)/K, δ_d = 3ν̃ Σ_m |a_m|²|a_{m−dM/2}|² / (Σ_m |a_m|²)². Evaluated here by direct sums.
fn cumulant_inflation(f: &[f64], nu_steps: f64, m: usize, omega: f64) -> (f64, f64) {
    let l = (f.len() - 1) / 2;
    let w: Vec<f64> = (0..m)
        .map(|k| 0.5 - 0.5 * (2.0 * std::f64::consts::PI * k as f64 / m as f64).cos())
        .collect();
    // a_m for m from −L to M + L
    let a2: Vec<f64> = (0..m + 2 * l + 1)
        .map(|idx| {
            let mm = idx as i64 - l as i64;
            let (mut re, mut im) = (0.0, 0.0);
            // the k with |k − mm| ≤ L only (f vanishes beyond), in increasing order
            let first = (mm - l as i64).max(0) as usize;
            let end = (mm + l as i64 + 1).clamp(0, m as i64) as usize;
            for (k, wk) in w.iter().enumerate().take(end).skip(first) {
                let lag = k as i64 - mm;
                let v = wk * f[(lag + l as i64) as usize];
                re += v * (omega * k as f64).cos();
                im -= v * (omega * k as f64).sin();
            }
            re * re + im * im
        })
        .collect();
    let total: f64 = a2.iter().sum();
    let d0: f64 = a2.iter().map(|v| v * v).sum::<f64>();
    let h = m / 2;
    let d1: f64 = (h..a2.len()).map(|i| a2[i] * a2[i - h]).sum();
    (
        3.0 * nu_steps * d0 / (total * total),
        3.0 * nu_steps * d1 / (total * total),
    )
}

/// The LMA's grid kernel f_l = N^{−1/2}[s₀ + 2Σ_{j=1}^{N/2−1} s_j cos(2πjl/N) + s_{N/2}(−1)^l] for |l| ≤ L,
/// by direct cosine sums.
fn kernel(lma: &LaplaceMovingAverage, l: usize) -> Vec<f64> {
    let s = lma.spectral().scales();
    let n = lma.len();
    // lags 0..=L; f(−lag) = f(lag) (cos is even)
    let half: Vec<f64> = (0..=l as i64)
        .map(|lag| {
            let mut v = s[0] + s[n / 2] * if lag % 2 == 0 { 1.0 } else { -1.0 };
            for (j, sj) in s.iter().enumerate().take(n / 2).skip(1) {
                v += 2.0 * sj * (2.0 * std::f64::consts::PI * (j as i64 * lag) as f64 / n as f64).cos();
            }
            v / (n as f64).sqrt()
        })
        .collect();
    half.iter().rev().chain(&half[1..]).copied().collect()
}

#[test]
fn laplace_road_has_the_prescribed_welch_density() {
    // One realization of 2²⁰ samples (52 km of road), kurtosis 6; Welch with M = 4096 (204.8 m), K = 511
    // segments. Expected: the analytic density S(Ω) = αD/(π(α² + Ω²)). The LMA has the Gaussian generator's
    // autocovariance by construction (E|c_j|² = S(ω_j)Δω, truncated at Nyquist, not folded), so the mean of
    // the estimate is S smoothed by the Hann window: relative bias ≈ (S″/2S)·4π²/(3L²) ≤ 4e-5 here
    // (L = 204.8 m, α = 3.5 1/m), against interval half-widths of ±25 %.
    // Interval: χ²_ν with Welch's ν for a Gaussian record, widened to ν_eff = 2/(2/ν + (δ₀ + 2δ₁)/K) for the
    // fourth cumulant of the Laplace increments (cumulant_inflation, direct sums over the kernel truncated at
    // |l| ≤ 400, where f has decayed by e^{−αΔx·400} ≈ e^{−70}). Five bins at 1 − 1e-8 each: union bound
    // 5e-8; the χ² law is the two-moment approximation, the factor 20 below 1e-6 is the margin for its tail.
    let q = road();
    let n = 1 << 20;
    let lma = road_of_kurtosis_6(&q, n);
    let mut sc = lma.scratch();
    let mut x = vec![0.0; n];
    lma.generate(&mut stochvib::simulate::stream(31, 0), &mut sc, &mut x)
        .unwrap();
    let m = 4096;
    let welch = Welch::new(m, DX).unwrap();
    let est = welch.estimate(&x).unwrap();
    assert_eq!(est.segments, 511);
    let f = kernel(&lma, 400);
    for j in [2usize, 10, 50, 200, 800] {
        let omega_sample = 2.0 * std::f64::consts::PI * j as f64 / m as f64;
        let (d0, d1) = cumulant_inflation(&f, lma.nu_steps(), m, omega_sample);
        let mut widened = est.clone();
        widened.dof = 2.0 / (2.0 / est.dof + (d0 + 2.0 * d1) / est.segments as f64);
        assert!(
            widened.dof < est.dof && widened.dof > 0.5 * est.dof,
            "bin {j}: ν_eff {}",
            widened.dof
        );
        let iv = widened.interval(j, 1.0 - 1e-8).unwrap();
        let analytic = q.density(est.omega[j]);
        assert!(
            iv.covers(analytic),
            "bin {j}: S = {analytic:e} not in [{:e}, {:e}] (ν_eff {})",
            iv.lower,
            iv.upper,
            widened.dof
        );
    }
}

/// Per-realization time averages of x² and x⁴ of R realizations of `lma` from `seed`.
fn moments(lma: &LaplaceMovingAverage, seed: u64, r: u64) -> (Vec<f64>, Vec<f64>) {
    let res = run_batch(
        seed,
        0..r,
        || (lma.scratch(), vec![0.0; lma.len()]),
        |(sc, x), _, rng| {
            lma.generate(rng, sc, x).unwrap();
            let n = x.len() as f64;
            (
                x.iter().map(|v| v * v).sum::<f64>() / n,
                x.iter().map(|v| v.powi(4)).sum::<f64>() / n,
            )
        },
    )
    .into_results();
    res.into_iter().unzip()
}

#[test]
fn laplace_road_reaches_the_prescribed_kurtosis() {
    // E x_k⁴ = κ D_N² exactly for the periodic LMA (the type's formula: cumulants of Σ f_m ε_{k−m}), and
    // E x_k² = D_N; by stationarity the per-realization time averages m₄,i = (1/N)Σ_k x_k⁴ have mean κD_N²
    // and are i.i.d. across realizations (independent streams). Interval: Student t of the mean of the
    // m₄,i at 1 − 2.5e-7 (CLT: each m₄,i already averages N/ℓ ≈ 60 correlation lengths, R = 400), so the
    // nominal false-failure probability of the four assertions together is ≤ 1e-6.
    // κ = 3 (ν = 0, point 4 of the tests): the same generator is the Gaussian process and reaches 3; κ = 6
    // and κ = 10 reach theirs, and their intervals exclude the Gaussian 3.
    let q = road();
    let n = 1 << 14;
    for (kappa, seed) in [(3.0, 41), (6.0, 42), (10.0, 43)] {
        let lma = LaplaceMovingAverage::new(
            &q,
            LaplaceGrid {
                dt: DX,
                n,
                kurtosis: kappa,
            },
        )
        .unwrap();
        let d = lma.grid_variance();
        let (m2, m4) = moments(&lma, seed, 400);
        let v = mean_interval(&m2, 1.0 - 2.5e-7).unwrap();
        assert!(
            v.covers(d),
            "κ = {kappa}: D_N = {d:e} not in [{:e}, {:e}]",
            v.lower,
            v.upper
        );
        let k = mean_interval(&m4, 1.0 - 2.5e-7).unwrap();
        let (lo, hi) = (k.lower / (d * d), k.upper / (d * d));
        assert!(lo <= kappa && kappa <= hi, "κ = {kappa} not in [{lo}, {hi}]");
        if kappa > 3.0 {
            assert!(
                lo > 3.0,
                "κ = {kappa}: the interval [{lo}, {hi}] does not exclude the Gaussian 3"
            );
        }
    }
}

/// The quarter car of `data/quarter-car-model.toml` (its ISO 8608 class C road at 20 m/s) with `[input]
/// kurtosis` set as given (None: the key absent).
fn quarter_car(kurtosis: Option<f64>) -> stochvib::scenario::Scenario {
    let root = common::root();
    let path = root.join("data/quarter-car-model.toml");
    let mut text = std::fs::read_to_string(&path).unwrap();
    if let Some(k) = kurtosis {
        text = text.replace("speed = \"20 m/s\"", &format!("speed = \"20 m/s\"\nkurtosis = {k}"));
    }
    parse_scenario(&text, &path, &root.join("spectra")).unwrap()
}

/// Per realization of output `name` of a stored run: (mean square, mean fourth power, max |y|, number of
/// up-crossings of `level`).
fn response_statistics(file: &Path, name: &str, r: usize, level: f64) -> Vec<[f64; 4]> {
    let run = RunFile::open(file).unwrap();
    let y = run.read_signals(SignalGroup::Outputs, name, 0..r).unwrap();
    y.rows()
        .into_iter()
        .map(|row| {
            let row = row.to_vec();
            let n = row.len() as f64;
            let m2 = row.iter().map(|v| v * v).sum::<f64>() / n;
            let m4 = row.iter().map(|v| v.powi(4)).sum::<f64>() / n;
            let max = row.iter().fold(0.0f64, |a, v| a.max(v.abs()));
            let up = row.windows(2).filter(|w| w[0] <= level && w[1] > level).count() as f64;
            [m2, m4, max, up]
        })
        .collect()
}

fn column(s: &[[f64; 4]], c: usize) -> Vec<f64> {
    s.iter().map(|v| v[c]).collect()
}

#[test]
fn quarter_car_on_a_laplace_road_keeps_sigma_not_extremes() {
    // Monte Carlo of the quarter car (R = 200 realizations of 40 s, Δt = 5 ms, spectral route, stored) on the
    // Gaussian road, on the LMA road of kurtosis 6 and on kurtosis 3; body acceleration and suspension travel.
    // * σ: the per-realization mean squares are i.i.d. with mean the exact variance of the simulated process
    //   (`sigma_discrete`, the same for every κ: the spectrum is the same), so the Student-t interval at
    //   1 − 2.5e-8 covers it (CLT).
    // * Response kurtosis: the closed form of the run's note (3 + κ₄/Var² of the filtered LMA, whose kernel sums
    //   are checked against direct convolution sums in the unit tests) is covered by the t interval of the
    //   fourth moments over σ⁴_discrete, and the Gaussian run's interval covers 3.
    // * Extremes (predicted direction: heavier tails than Gaussian, kurtosis > 3): the LMA run's t intervals of
    //   E[m₄], of the mean of the per-realization max |y| and of the mean number of up-crossings of 3σ lie
    //   entirely above the Gaussian run's (two disjoint intervals at 1 − 2.5e-8 each).
    // * κ = 3: covers 3 and the Gaussian σ like the Gaussian run.
    // The 26 intervals at 2.5e-8 each: union bound 6.5e-7 ≤ 1e-6.
    let conf = 1.0 - 2.5e-8;
    let dir = crate::common::scratch_dir("laplace", "extremes");
    let r = 200;
    let mut opts = RunOptions {
        realizations: r,
        duration_s: 40.0,
        dt_s: 0.005,
        seed: 17,
        ..RunOptions::default()
    };
    opts.store_raw = true;
    opts.route = Route::Spectral;
    opts.overwrite = true;
    let mut runs = Vec::new();
    for (label, k) in [("gauss", None), ("lma6", Some(6.0)), ("lma3", Some(3.0))] {
        let sc = quarter_car(k);
        let out = dir.join(format!("{label}.h5"));
        let s = stochvib::simulate::run(&sc.run_input(), &opts, &out, &|_, _| {}).unwrap();
        if let Some(k) = k {
            assert!(s.generator.contains("Laplace moving average"));
            let run = RunFile::open(&out).unwrap();
            assert!(run.metadata().generator.contains(&format!("kurtosis {k}")));
        }
        runs.push((label, k, out, s));
    }
    for name in ["body_acc", "travel"] {
        let var_d = runs[0]
            .3
            .outputs
            .iter()
            .find(|o| o.output == name)
            .unwrap()
            .get("sigma_discrete")
            .unwrap()
            .analytic
            .unwrap()
            .powi(2);
        let level = 3.0 * var_d.sqrt();
        let mut iv = Vec::new();
        for (label, k, out, s) in &runs {
            let st = response_statistics(out, name, r, level);
            let v = mean_interval(&column(&st, 0), conf).unwrap();
            assert!(
                v.covers(var_d),
                "{label} {name}: σ² = {var_d:e} not in [{:e}, {:e}]",
                v.lower,
                v.upper
            );
            let m4 = mean_interval(&column(&st, 1), conf).unwrap();
            let predicted = match k {
                None => 3.0,
                Some(_) => predicted_kurtosis(s, name),
            };
            let (lo, hi) = (m4.lower / (var_d * var_d), m4.upper / (var_d * var_d));
            assert!(
                lo <= predicted && predicted <= hi,
                "{label} {name}: kurtosis {predicted} not in [{lo}, {hi}]"
            );
            iv.push((
                m4,
                mean_interval(&column(&st, 2), conf).unwrap(),
                mean_interval(&column(&st, 3), conf).unwrap(),
            ));
        }
        let (g, l) = (&iv[0], &iv[1]);
        assert!(l.0.lower > g.0.upper, "{name}: E y⁴ not larger on the LMA road");
        assert!(
            l.1.lower > g.1.upper,
            "{name}: max |y| not larger: {:?} vs {:?}",
            l.1,
            g.1
        );
        assert!(
            l.2.lower > g.2.upper,
            "{name}: 3σ up-crossings not more: {:?} vs {:?}",
            l.2,
            g.2
        );
    }
    let _ = std::fs::remove_dir_all(&dir);
}

/// The response kurtosis the run notes state for output `name`.
fn predicted_kurtosis(s: &stochvib::simulate::RunSummary, name: &str) -> f64 {
    let tag = format!("kurtosis of `{name}` (simulated process) = ");
    let note = s.notes.iter().find(|n| n.contains(&tag)).expect("kurtosis note");
    let rest = &note[note.find(&tag).unwrap() + tag.len()..];
    rest.split_whitespace().next().unwrap().parse().unwrap()
}

#[test]
fn bad_kurtosis_values_name_file_key_value_and_reason() {
    let root = common::root();
    let path = root.join("data/quarter-car-model.toml");
    let text = std::fs::read_to_string(&path).unwrap();
    for (value, reason) in [("2.5", ">= 3"), ("\"six\"", "expected a number"), ("nan", ">= 3")] {
        let t = text.replace("speed = \"20 m/s\"", &format!("speed = \"20 m/s\"\nkurtosis = {value}"));
        let e = parse_scenario(&t, &path, &root.join("spectra"))
            .unwrap_err()
            .to_string();
        for part in ["quarter-car-model.toml", "input.kurtosis", reason] {
            assert!(e.contains(part), "{value}: `{part}` missing from: {e}");
        }
    }
    // a non-Gaussian input is simulated on the spectral route only
    let sc = quarter_car(Some(6.0));
    let mut opts = RunOptions {
        realizations: 2,
        duration_s: 4.0,
        dt_s: 0.005,
        seed: 1,
        ..RunOptions::default()
    };
    opts.route = Route::Exact;
    let out = crate::common::scratch_dir("laplace", "exact").join("exact.h5");
    let e = stochvib::simulate::run(&sc.run_input(), &opts, &out, &|_, _| {})
        .unwrap_err()
        .to_string();
    assert!(e.contains("spectral route"), "{e}");
    // the kurtosis is part of the run's identity
    assert!(sc.run_input().provenance.iter().any(|p| p.name == "input_kurtosis"));
}

#[test]
fn kurtosis_of_a_filtered_laplace_moving_average_follows_its_kernel_ratio() {
    // Derivation: x_k = Σ_m f_m ε_{k−m} with i.i.d. ε of variance 1 and fourth cumulant 3ν̃; cumulants of a
    // sum of independent terms add, so κ₄(x) = 3ν̃ Σf⁴ and Var x = Σf²: κ_x − 3 = 3ν̃ Σf⁴/(Σf²)². A linear
    // filter gives y = h * x = Σ_m g_m ε_{k−m}, g = h * f, the same ε: κ_y − 3 = 3ν̃ Σg⁴/(Σg²)², hence
    //     κ_y − 3 = (κ_x − 3) · [Σg⁴/(Σg²)²] / [Σf⁴/(Σf²)²].
    // Here h is the two-tap mean y_k = (x_k + x_{k−1})/2 (gain G_j = (1 + e^{−iω_jΔt})/2): g_l = (f_l + f_{l−1})/2
    // computed by direct cosine sums of the kernel (no FFT), against `filtered_cumulants` (FFT of s_j G_j).
    // A pure delay (G_j = e^{−iω_j 3Δt}) only shifts g: κ_y = κ_x exactly.
    use realfft::num_complex::Complex;
    let q = road();
    let n = 256;
    let lma = road_of_kurtosis_6(&q, n);
    let f = kernel(&lma, n / 2);
    let ratio = |k: &[f64]| k.iter().map(|v| v.powi(4)).sum::<f64>() / k.iter().map(|v| v * v).sum::<f64>().powi(2);
    // periodic kernel over one period (lags −N/2..N/2 − 1), then g_l = (f_l + f_{l−1})/2 circularly
    let per: Vec<f64> = f[..n].to_vec();
    let g: Vec<f64> = (0..n).map(|l| 0.5 * (per[l] + per[(l + n - 1) % n])).collect();
    let want = 3.0 + (6.0 - 3.0) * ratio(&g) / ratio(&per);
    let dw = 2.0 * std::f64::consts::PI / (n as f64 * DX);
    let mean: Vec<Complex<f64>> = (0..=n / 2)
        .map(|j| (Complex::new(1.0, 0.0) + Complex::from_polar(1.0, -(j as f64) * dw * DX)) * 0.5)
        .collect();
    let (k4, var) = lma.filtered_cumulants(&mean).unwrap();
    let got = 3.0 + k4 / (var * var);
    assert!((got - want).abs() <= common::tolerance::EXACT, "{got} vs {want}");
    assert!(got < 6.0, "the mean of two samples is smoother: {got}");
    let delay: Vec<Complex<f64>> = (0..=n / 2)
        .map(|j| Complex::from_polar(1.0, -3.0 * j as f64 * dw * DX))
        .collect();
    let (k4, var) = lma.filtered_cumulants(&delay).unwrap();
    // the Nyquist bin's gain e^{−iπ·3} = −1 is real: the delay is exact on the grid
    assert!((3.0 + k4 / (var * var) - 6.0).abs() <= common::tolerance::EXACT);
}

/// The operator seat of `data/operator-seat-verdicts.toml` (ISO 2631-1 Wk comfort axis on the seat) with
/// `[input] kurtosis` set as given.
fn operator_seat(kurtosis: Option<f64>) -> stochvib::scenario::Scenario {
    let root = common::root();
    let path = root.join("data/operator-seat-verdicts.toml");
    let mut text = std::fs::read_to_string(&path).unwrap();
    if let Some(k) = kurtosis {
        text = text.replacen("[input]\n", &format!("[input]\nkurtosis = {k}\n"), 1);
    }
    parse_scenario(&text, &path, &root.join("spectra")).unwrap()
}

#[test]
fn non_gaussian_vdv_is_predicted_from_the_weighted_output_kurtosis() {
    // VDV⁴ of a realization of T = NΔt is Σ a_k⁴ Δt, so for any stationary a_w(t) E[VDV⁴] = T·E a⁴ = T κ_w σ_w⁴
    // (κ_w = E a⁴/σ_w⁴): 3Tσ_w⁴ for a Gaussian weighted output, more for the Laplace road of kurtosis 6. The run
    // states κ_w of the simulated weighted output (the note, from the cumulants: see the test above) and uses
    // (κ_w T)^{1/4}σ_d as the analytic VDV.
    // Monte Carlo (R = 300 realizations of 20 s at Δt = 5 ms, spectral route): the run's Student-t interval of
    // E[VDV⁴] (raised to 1/4) at 1 − 2.5e-7 covers (κ_w T)^{1/4}σ_d and lies above the Gaussian (3T)^{1/4}σ_d
    // (κ_w ≈ 5.9 here: the Gaussian value is ≈ 15 % lower in VDV, the interval's half-width ≈ 6 %); the σ
    // interval at the same confidence covers σ_d, the σ of the Gaussian run (same spectrum). Two intervals:
    // nominal false-failure probability ≤ 5e-7 ≤ 1e-6 (CLT for the mean of VDV_i⁴).
    let dir = crate::common::scratch_dir("laplace", "vdv");
    let w = "seat_acc_Wk";
    let (dt, duration) = (0.005, 20.0);
    let mut opts = RunOptions {
        realizations: 300,
        duration_s: duration,
        dt_s: dt,
        seed: 23,
        ..RunOptions::default()
    };
    opts.route = Route::Spectral;
    opts.overwrite = true;
    opts.confidence = 1.0 - 2.5e-7;
    let sc = operator_seat(Some(6.0));
    let s = sc.simulate(&opts, &dir.join("seat6.h5"), &|_, _| {}).unwrap();
    let kappa = predicted_kurtosis(&s, w);
    assert!(kappa > 5.0 && kappa < 6.5, "κ_w = {kappa}");
    let o = s.outputs.iter().find(|o| o.output == w).unwrap();
    let sd = o.get("sigma_discrete").unwrap().analytic.unwrap();
    let t = duration;
    let vdv = o.get("vdv").unwrap();
    let predicted = (kappa * t).powf(0.25) * sd;
    let gaussian = (3.0 * t).powf(0.25) * sd;
    // the analytic column is the non-Gaussian prediction (κ_w printed to 6 decimals in the note)
    let a = vdv.analytic.unwrap();
    assert!(
        (a - predicted).abs() <= common::tolerance::PRINTED_6_DIGITS * a,
        "{a} vs {predicted}"
    );
    assert!(
        vdv.method.contains("non-Gaussian") && vdv.method.contains("κ_w"),
        "{}",
        vdv.method
    );
    assert!(!vdv.method.contains("E a⁴ = 3σ⁴)"), "{}", vdv.method);
    let iv = &vdv.interval;
    assert!(
        iv.lower <= a && a <= iv.upper,
        "VDV {a} not in [{}, {}]",
        iv.lower,
        iv.upper
    );
    assert_eq!(vdv.covers, Some(true));
    // E[VDV⁴]/T against κ_w σ⁴ and 3σ⁴
    let (lo, hi) = (iv.lower.powi(4) / t, iv.upper.powi(4) / t);
    assert!(lo <= kappa * sd.powi(4) && kappa * sd.powi(4) <= hi);
    assert!(
        lo > 3.0 * sd.powi(4),
        "E[VDV⁴]/T interval [{lo:e}, {hi:e}] does not exclude 3σ⁴ = {:e}",
        3.0 * sd.powi(4)
    );
    assert!(iv.lower > gaussian);
    // σ unchanged: the Gaussian run (same grid) has the same discrete σ, which the interval covers
    let mut g_opts = opts.clone();
    g_opts.realizations = 2;
    let g = operator_seat(None)
        .simulate(&g_opts, &dir.join("seat-gauss.h5"), &|_, _| {})
        .unwrap();
    let go = g.outputs.iter().find(|o| o.output == w).unwrap();
    assert_eq!(go.get("sigma_discrete").unwrap().analytic.unwrap(), sd);
    let gv = go.get("vdv").unwrap();
    assert!((gv.analytic.unwrap() - gaussian).abs() <= common::tolerance::ROUNDING * gaussian);
    assert!(!gv.method.contains("non-Gaussian"));
    let sigma = o.get("sigma").unwrap();
    assert!(sigma.interval.covers(sd), "σ_d = {sd} not in {:?}", sigma.interval);
    // the seat spring's damage rate: Dirlik's rate holds for a Gaussian output only, so for this non-Gaussian
    // run it is withdrawn as the analytic value (no `covers`), named in the method, while the Gaussian run
    // keeps it as its analytic value
    let damage = damage_rate(&s.outputs);
    assert!(damage.analytic.is_none() && damage.covers.is_none(), "{damage:?}");
    assert!(
        damage.method.contains("NOT compared") && damage.method.contains("non-Gaussian"),
        "{}",
        damage.method
    );
    let g_damage = damage_rate(&g.outputs);
    assert!(g_damage.analytic.is_some() && !g_damage.method.contains("NOT compared"));
    // the text summary prints the prediction beside the Monte Carlo VDV
    let text = format!("{s}");
    assert!(text.contains("(κ_w T)^(1/4)·σ_w, κ_w = "), "{text}");
    assert!(format!("{g}").contains("(3T)^(1/4)·σ_w (Gaussian)"));
    // `analyze` (no Monte Carlo) says that its Gaussian VDV does not hold for this input
    let v = stochvib::study::verdict_analysis(&sc).unwrap();
    let c = v.comfort.as_ref().unwrap();
    assert_eq!(c.non_gaussian_input.as_deref(), Some("input kurtosis 6")); // a temporal `[input]` is `input`
    assert!(format!("{v}").contains("do NOT hold"), "{v}");
    let vg = stochvib::study::verdict_analysis(&operator_seat(None)).unwrap();
    assert!(vg.comfort.as_ref().unwrap().non_gaussian_input.is_none());
    assert!(!format!("{vg}").contains("do NOT hold"));
    let _ = std::fs::remove_dir_all(&dir);
}

/// The `damage_rate` statistic of the operator seat's fatigue output `travel`.
fn damage_rate(outputs: &[stochvib::store::OutputStatistics]) -> &stochvib::store::Statistic {
    outputs
        .iter()
        .find(|o| o.output == "travel")
        .unwrap()
        .get("damage_rate")
        .unwrap()
}

#[test]
fn merged_shards_of_a_non_gaussian_verdict_run_keep_its_vdv_prediction() {
    // A cluster run (2 shard files of 4 realizations) merged equals the single-process run bit for bit, the
    // non-Gaussian analytic VDV and its method text included (the merge takes them from the shard files).
    use stochvib::store::Part;
    use stochvib::study::part_path;
    use stochvib::study::{merge_runs, MergeOptions};
    let dir = crate::common::scratch_dir("laplace", "merge");
    std::fs::create_dir_all(&dir).unwrap();
    let sc = operator_seat(Some(6.0));
    let mut opts = RunOptions {
        realizations: 8,
        duration_s: 4.0,
        dt_s: 0.005,
        seed: 5,
        ..RunOptions::default()
    };
    opts.shard_size = 4;
    opts.overwrite = true;
    let whole = sc.simulate(&opts, &dir.join("whole.h5"), &|_, _| {}).unwrap();
    let files: Vec<_> = (0..2)
        .map(|i| {
            let p = Part::new(i, 2).unwrap();
            let path = part_path(&dir, p);
            let mut o = opts.clone();
            o.part = Some(p);
            sc.simulate(&o, &path, &|_, _| {}).unwrap();
            path
        })
        .collect();
    let merged = dir.join("merged.h5");
    let _ = std::fs::remove_file(&merged);
    merge_runs(&merged, &files, &MergeOptions::default(), &|_, _| {}).unwrap();
    let w = "seat_acc_Wk";
    let a = whole
        .outputs
        .iter()
        .find(|o| o.output == w)
        .unwrap()
        .get("vdv")
        .unwrap()
        .clone();
    let m = RunFile::open(&merged).unwrap().statistics().unwrap();
    let b = m.iter().find(|o| o.output == w).unwrap().get("vdv").unwrap().clone();
    assert!(a.method.contains("non-Gaussian"), "{}", a.method);
    assert_eq!(a.method, b.method);
    assert_eq!(a.analytic.map(f64::to_bits), b.analytic.map(f64::to_bits));
    assert_eq!(a.interval.estimate.to_bits(), b.interval.estimate.to_bits());
    // the withdrawn Dirlik comparison of the damage rate survives the merge
    let da = damage_rate(&whole.outputs);
    let db = damage_rate(&m);
    assert!(da.method.contains("NOT compared"), "{}", da.method);
    assert_eq!(da.method, db.method);
    assert!(db.analytic.is_none() && db.covers.is_none());
    assert_eq!(da.interval.estimate.to_bits(), db.interval.estimate.to_bits());
    let _ = std::fs::remove_dir_all(&dir);
}
