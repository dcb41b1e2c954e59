//! Band r.m.s. from Monte Carlo (`[analysis] bands` in `simulate`): the per-realization
//! band mean squares of the Welch estimates, their Student-t intervals against the expected band values of the
//! simulated process, the pipeline against a recomputation from the raw records, the bit-identical merge of a
//! two-shard run, and a band-less run left as it was.
//!
//! Every expected number is computed here from what the tests take as given elsewhere: the IEC 61260-1 band
//! edges and the analytic band table (tests/band_table.rs), the exact mean of the Welch estimate E Ŝ(ω_j)
//! stored with each density (tests/monte_carlo.rs), and `Welch::estimate` of a record; the band integral
//! with partial bins weighted by their overlap is written out again below ([`bin_weights`]).

use crate::common;
use crate::common::SpawnSerial;
use common::rel;
use common::tolerance::EXACT;
use std::f64::consts::PI;
use std::path::{Path, PathBuf};
use stochvib::comfort::{output_band_table, BandFraction, BandTable};
use stochvib::estimate::Welch;
use stochvib::scenario::{parse_scenario, Scenario};
use stochvib::simulate::RunOptions;
use stochvib::store::{tmp_path, OutputStatistics, Part, PsdEstimate, RunFile, SignalGroup};
use stochvib::study::{merge_runs, part_path, MergeOptions};

/// Per-band false-failure probability of the coverage test. At most 4 outputs × 22 bands = 88 intervals
/// are tested (asserted below), so by the union bound the test fails falsely with probability ≤ 88·2e-9 ≈
/// 1.8e-7 ≤ 1e-6. The level rests on the central limit theorem for the mean of the independent band mean
/// squares b_i (each a positive quadratic form of the Gaussian record, skewness ≈ √(8/ν) with ν ≥ 28
/// Welch degrees of freedom per bin, so ≤ 0.03 for the mean of 300); the factor 5 between 1.8e-7 and 1e-6
/// is the margin for the Edgeworth correction of the far tail.
const P_FALSE: f64 = 2e-9;

/// Bands holding less than this fraction of the output's total expected mean square are not tested: their
/// expected value E Ŝ is a signed sum over M lags whose rounding (≈ M·ε of the total, ≈ 1e-13) would be
/// comparable with the value itself (the 80 Hz band of the quarter car, above the road band's 56.6 Hz,
/// holds only window leakage, ≈ 1e-16 of the total).
const ENOUGH_ENERGY: f64 = 1e-6;

fn root() -> PathBuf {
    common::root()
}

/// The quarter car of the catalogue (ISO 8608 class C road at 20 m/s, band 0.5–80 Hz), with
/// `bands = "third-octave"` when `bands`.
fn quarter_car(bands: bool) -> Scenario {
    let path = root().join("data/quarter-car.toml");
    let text = std::fs::read_to_string(&path).unwrap();
    let text = if bands {
        text.replacen("[analysis]\n", "[analysis]\nbands = \"third-octave\"\n", 1)
    } else {
        text
    };
    parse_scenario(&text, &path, &root().join("spectra")).unwrap()
}

fn scratch(name: &str) -> PathBuf {
    crate::common::scratch_dir("band-mc", name)
}

fn fresh(path: &Path) -> &Path {
    let _ = std::fs::remove_file(path);
    let _ = std::fs::remove_file(tmp_path(path));
    path
}

/// The weights c_j of band [f_1, f_2] Hz on the Welch bins ω_j of `omega` (uniform, from 0 to the Nyquist
/// frequency ω_N): bin j stands for [ω_j − Δω/2, ω_j + Δω/2] ∩ [0, ω_N], and a one-sided band mean square
/// is 2∫S dω, so c_j = 2·(length of that bin inside [2πf_1, 2πf_2]).
fn bin_weights(omega: &[f64], f1: f64, f2: f64) -> Vec<f64> {
    let dw = omega[1] - omega[0];
    let wn = omega[omega.len() - 1];
    omega
        .iter()
        .map(|&w| {
            let lo = (w - dw / 2.0).max(0.0).max(2.0 * PI * f1);
            let hi = (w + dw / 2.0).min(wn).min(2.0 * PI * f2);
            2.0 * (hi - lo).max(0.0)
        })
        .collect()
}

fn dot(a: &[f64], b: &[f64]) -> f64 {
    a.iter().zip(b).map(|(x, y)| x * y).sum()
}

/// The analytic band table of output `name` of the scenario over its analysis band (what `analyze` shows).
fn analytic_table(sc: &Scenario, name: &str) -> BandTable {
    let i = sc
        .analysis
        .outputs
        .iter()
        .copied()
        .find(|&i| sc.model.system.outputs()[i].name == name)
        .unwrap();
    let (a, b) = sc.analysis.band.unwrap();
    output_band_table(
        sc.model.system.as_ref(),
        &sc.excitation,
        i,
        BandFraction::ThirdOctave,
        None,
        Some((a / (2.0 * PI), b / (2.0 * PI))),
    )
    .unwrap()
}

fn psd_of<'a>(psd: &'a [PsdEstimate], name: &str) -> &'a PsdEstimate {
    psd.iter().find(|p| p.output == name).unwrap()
}

#[test]
fn band_rms_intervals_cover_the_expected_band_values_of_the_simulated_process() {
    let _serial = common::hdf5_serial();
    let sc = quarter_car(true);
    // Spectral route (the road spectrum is not rational). Δt = 8 ms puts the Nyquist frequency (62.5 Hz)
    // above the road band (2.83 cycles/m · 20 m/s = 56.6 Hz); 80 s gives Welch segments of M = 1024 samples
    // (Δf = 0.122 Hz, K = 18 segments, ν ≈ 34 per bin and realization).
    let mut opts = RunOptions {
        realizations: 300,
        duration_s: 80.0,
        dt_s: 0.008,
        seed: 2026,
        ..RunOptions::default()
    };
    opts.confidence = 1.0 - P_FALSE;
    let dir = scratch("coverage");
    let out = dir.join("qc.h5");
    let s = sc.simulate(&opts, fresh(&out), &|_, _| {}).unwrap();
    // the 80 Hz band starts at 71 Hz, above the Nyquist frequency: left out, and said so
    assert!(
        s.notes.iter().any(|n| n.contains("above the Nyquist frequency")),
        "{:?}",
        s.notes
    );
    let run = RunFile::open(&out).unwrap();
    let psd = run.psd().unwrap();
    let mut tested = 0;
    let mut failures = Vec::new();
    for o in &s.outputs {
        let table = analytic_table(&sc, &o.output);
        let p = psd_of(&psd, &o.output);
        let expected_density = p.expected.as_ref().unwrap();
        let nyquist_hz = p.omega[p.omega.len() - 1] / (2.0 * PI);
        let rows: Vec<_> = table.rows.iter().filter(|r| r.band.lower_hz < nyquist_hz).collect();
        assert_eq!(rows.len(), 22, "{}: 0.5 … 63 Hz", o.output);
        let expected: Vec<f64> = rows
            .iter()
            .map(|r| {
                dot(
                    &bin_weights(&p.omega, r.band.lower_hz, r.band.upper_hz),
                    expected_density,
                )
            })
            .collect();
        let total: f64 = expected.iter().sum();
        for (r, e) in rows.iter().zip(&expected) {
            let label = r.band.label();
            let st = o.get(&format!("band_rms[{label}]")).unwrap();
            let se = o.get(&format!("band_rms_expected[{label}]")).unwrap();
            // the stored reference values are the analytic table's r.m.s. and the band integral of E Ŝ
            assert!(rel(st.analytic.unwrap(), r.rms) < EXACT, "{}/{label}", o.output);
            assert!(rel(se.analytic.unwrap(), e.sqrt()) < EXACT, "{}/{label}", o.output);
            assert_eq!(st.interval, se.interval);
            if *e < ENOUGH_ENERGY * total {
                continue;
            }
            tested += 1;
            if !st.interval.covers(e.sqrt()) {
                failures.push(format!("{}/{label}: {:e} not in {:?}", o.output, e.sqrt(), st.interval));
            }
        }
    }
    assert!(
        tested <= 88,
        "the union bound above counts at most 88 intervals, {tested} tested"
    );
    assert!(tested >= 4 * 20, "only {tested} bands with enough energy");
    assert!(failures.is_empty(), "{failures:#?}");
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn band_estimates_are_the_band_integrals_of_each_realizations_welch_estimate() {
    let _serial = common::hdf5_serial();
    let sc = quarter_car(true);
    let mut opts = RunOptions {
        realizations: 6,
        duration_s: 20.0,
        dt_s: 0.008,
        seed: 5,
        ..RunOptions::default()
    };
    opts.store_raw = true;
    let dir = scratch("raw");
    let out = dir.join("qc.h5");
    let s = sc.simulate(&opts, fresh(&out), &|_, _| {}).unwrap();
    let run = RunFile::open(&out).unwrap();
    let psd = run.psd().unwrap();
    for o in &s.outputs {
        let p = psd_of(&psd, &o.output);
        let m = 2 * (p.omega.len() - 1);
        let welch = Welch::new(m, opts.dt_s).unwrap();
        let raw = run.read_signals(SignalGroup::Outputs, &o.output, 0..6).unwrap();
        let densities: Vec<Vec<f64>> = raw
            .rows()
            .into_iter()
            .map(|x| welch.estimate(x.as_slice().unwrap()).unwrap().density)
            .collect();
        let table = analytic_table(&sc, &o.output);
        for r in table.rows.iter().filter(|r| r.band.lower_hz < 62.5) {
            let c = bin_weights(&p.omega, r.band.lower_hz, r.band.upper_hz);
            let mean = densities.iter().map(|d| dot(&c, d)).sum::<f64>() / 6.0;
            let st = o.get(&format!("band_rms[{}]", r.band.label())).unwrap();
            // a mean of 6 sums of ≤ 1024 positive terms, in another order: a few hundred roundings
            assert!(
                rel(st.interval.estimate, mean.sqrt()) < EXACT,
                "{}/{}: {} vs {}",
                o.output,
                r.band.label(),
                st.interval.estimate,
                mean.sqrt()
            );
        }
    }
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn a_two_shard_run_merged_is_bit_identical_and_a_band_less_run_is_unchanged() {
    let _serial = common::hdf5_serial();
    let sc = quarter_car(true);
    let dir = scratch("merge");
    let opts = |part| RunOptions {
        shard_size: 3,
        part,
        realizations: 10,
        duration_s: 10.0,
        dt_s: 0.008,
        seed: 77,
        ..RunOptions::default()
    };
    let single = dir.join("single.h5");
    sc.simulate(&opts(None), fresh(&single), &|_, _| {}).unwrap();
    let parts = dir.join("parts");
    std::fs::create_dir_all(&parts).unwrap();
    for i in 0..2 {
        let p = Part::new(i, 2).unwrap();
        sc.simulate(&opts(Some(p)), &part_path(&parts, p), &|_, _| {}).unwrap();
    }
    let merged = dir.join("merged.h5");
    merge_runs(&merged, &[parts], &MergeOptions::default(), &|_, _| {}).unwrap();
    let a = RunFile::open(&single).unwrap().statistics().unwrap();
    let b = RunFile::open(&merged).unwrap().statistics().unwrap();
    let bands_of = |s: &[OutputStatistics]| {
        s.iter()
            .flat_map(|o| &o.statistics)
            .filter(|st| st.name.starts_with("band_rms"))
            .count()
    };
    assert_eq!(bands_of(&a), 4 * 2 * 22, "4 outputs, 22 bands, two statistics each");
    assert_eq!(common::stored_statistic_bits(&a), common::stored_statistic_bits(&b));

    // the same run without `bands`: no band accumulator, no band statistic, and every other statistic and
    // density bit-identical to the run with bands
    let plain = dir.join("plain.h5");
    quarter_car(false)
        .simulate(&opts(None), fresh(&plain), &|_, _| {})
        .unwrap();
    let c = RunFile::open(&plain).unwrap();
    assert!(c.metadata().accumulators.iter().all(|(n, _)| !n.ends_with(":bands")));
    let with_bands = RunFile::open(&single).unwrap();
    assert!(with_bands
        .metadata()
        .accumulators
        .iter()
        .any(|(n, _)| n.ends_with(":bands")));
    let without: Vec<_> = common::stored_statistic_bits(&a)
        .into_iter()
        .filter(|(_, n, ..)| !n.starts_with("band_rms"))
        .collect();
    assert_eq!(common::stored_statistic_bits(&c.statistics().unwrap()), without);
    assert_eq!(common::psd_bits(&plain), common::psd_bits(&single));
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn simulate_prints_and_inspect_shows_the_band_table() {
    let dir = scratch("cli");
    let text = std::fs::read_to_string(root().join("data/quarter-car.toml"))
        .unwrap()
        .replacen("[analysis]\n", "[analysis]\nbands = \"octave\"\n", 1);
    let scenario = dir.join("qc.toml");
    std::fs::write(&scenario, text).unwrap();
    let out = dir.join("qc.h5");
    let exe = crate::common::cli_bin();
    let spectra = root().join("spectra");
    let run = |args: &[&str]| {
        let o = std::process::Command::new(exe).args(args).output_serial().unwrap();
        assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
        String::from_utf8(o.stdout).unwrap()
    };
    let summary = run(&[
        "simulate",
        scenario.to_str().unwrap(),
        "--realizations",
        "8",
        "--dt",
        "0.008",
        "--duration",
        "10",
        "--spectra-dir",
        spectra.to_str().unwrap(),
        "-o",
        out.to_str().unwrap(),
    ]);
    // per output: the band table with analytic, expected and Monte Carlo r.m.s.; the octaves covering
    // 0.5–80 Hz are nominal 0.5, 1, 2, …, 63 Hz
    assert!(summary.contains("bands     body [m]"), "{summary}");
    assert!(summary.contains("covers expected"), "{summary}");
    assert!(
        summary.lines().any(|l| l.trim_start().starts_with("31.5 Hz")),
        "{summary}"
    );
    let text = run(&["inspect", out.to_str().unwrap()]);
    assert!(
        text.contains("band_rms[31.5 Hz]") && text.contains("band_rms_expected[31.5 Hz]"),
        "{text}"
    );
    assert!(text.contains("body:bands"), "{text}");
    let json: serde_json::Value = serde_json::from_str(&run(&["inspect", "--json", out.to_str().unwrap()])).unwrap();
    let shown = json.to_string();
    assert!(shown.contains("band_rms[31.5 Hz]"), "{shown}");
    let _ = std::fs::remove_dir_all(&dir);
}
