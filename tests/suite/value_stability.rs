//! Value stability: the Monte Carlo statistics of a seed are pinned to the last bit, so that a refactoring,
//! a dependency update or a change of thread count cannot change a stored result silently (the practice of
//! `rand`'s value-stability tests).
//!
//! Provenance: the pinned bit patterns were first printed by `stochvib simulate … --json` at commit 67bb861
//! (before the architecture rework) for the two runs below, one per route, and printed again by this test
//! when the time sums of a realization changed order (`simulate::TimeSums`: eight partial sums instead of
//! one running sum, for speed). That change moved every variance and σ by at most 6·10⁻¹⁶ relative (a few
//! ulp, a reordering's rounding), the exact route's means by at most 9·10⁻¹⁵ relative, and the spectral
//! route's means, which are zero up to rounding (≈ 10⁻²⁰; its records have no zero-frequency component),
//! to other rounding noise of the same size. They pin behaviour, not
//! correctness: that the statistics are right is tested against the analytic values in `mc_pipeline.rs`.
//! A deliberate change of the generators or of the route must update these pins in the same commit, with
//! the reason.

use crate::common;
use common::root;
use stochvib::scenario::load_scenario;
use stochvib::simulate::{Route, RunOptions};

/// Bits of (variance, sigma, mean) × (estimate, lower, upper) per output.
type Pins = &'static [(&'static str, [u64; 9])];

fn check(file: &str, opts: RunOptions, route: Route, pins: Pins) {
    let sc = load_scenario(&root().join("data").join(file), &root().join("spectra")).unwrap();
    let out = crate::common::scratch_kept("pin", file).join("run.h5");
    let _ = std::fs::remove_file(&out);
    let s = sc.simulate(&opts, &out, &|_, _| {}).unwrap();
    std::fs::remove_file(&out).unwrap();
    assert_eq!(s.route, route);
    assert_eq!(s.outputs.len(), pins.len());
    for (o, (name, bits)) in s.outputs.iter().zip(pins) {
        assert_eq!(&o.output, name);
        let mut got = Vec::new();
        for stat in ["variance", "sigma", "mean"] {
            let iv = o.get(stat).unwrap().interval;
            got.extend([iv.estimate, iv.lower, iv.upper].map(f64::to_bits));
        }
        assert_eq!(got, bits, "{file}/{name}: statistics changed");
    }
}

/// Exact route: conveyor idler, 30 realizations × 5 s at Δt = 0.01 s, seed 3.
#[test]
fn exact_route_statistics_are_pinned() {
    check(
        "conveyor-idler.toml",
        RunOptions {
            realizations: 30,
            duration_s: 5.0,
            dt_s: 0.01,
            seed: 3,
            ..RunOptions::default()
        },
        Route::Exact,
        &[
            (
                "y",
                [
                    0x3f4fa6101aeb5e31,
                    0x3f46a0701cd5d2ec,
                    0x3f5455d80c8074bb,
                    0x3f9fd2e848123e7d,
                    0x3f9ae8841372e2d1,
                    0x3fa209b2be0d43b5,
                    0x3f7573822d205fa2,
                    0xbf65f42cc90235a0,
                    0x3f8af08d5f60ed0a,
                ],
            ),
            (
                "y_vel",
                [
                    0x3f9af40dc3302600,
                    0x3f98faff0226a53f,
                    0x3f9ced1c8439a6c1,
                    0x3fc4c4428e32f7b0,
                    0x3fc3fdff80cf8879,
                    0x3fc58363a55ee774,
                    0xbf239aeefd6a8ba7,
                    0xbf69d5125ae79859,
                    0x3f6761b47b3a46e5,
                ],
            ),
        ],
    );
}

/// Whether this build and CPU run the FFT path that wrote the spectral route's pins: rustfft's AVX code, which
/// it takes on CPUs with AVX and FMA (`docs/cluster.md`, "Which numbers are identical on which machines").
/// Every number of the spectral route passes through an FFT, whose other paths differ in the last bits.
fn on_the_fft_path_of_the_pins() -> bool {
    #[cfg(all(feature = "simd-fft", target_arch = "x86_64"))]
    {
        std::arch::is_x86_feature_detected!("avx") && std::arch::is_x86_feature_detected!("fma")
    }
    #[cfg(not(all(feature = "simd-fft", target_arch = "x86_64")))]
    {
        false
    }
}

/// Spectral route: half car with the wheelbase delay, 20 realizations × 10 s at Δt = 0.009 s, seed 7. Pinned
/// on the FFT path of AVX with FMA only (see [`on_the_fft_path_of_the_pins`]); elsewhere the test says that
/// it did not check.
#[test]
fn spectral_route_statistics_are_pinned() {
    if !on_the_fft_path_of_the_pins() {
        eprintln!("value_stability: the spectral route's pins were NOT checked: they hold on rustfft's AVX+FMA path");
        return;
    }
    check(
        "half-car.toml",
        RunOptions {
            realizations: 20,
            duration_s: 10.0,
            dt_s: 0.009,
            seed: 7,
            ..RunOptions::default()
        },
        Route::Spectral,
        &[
            (
                "bounce",
                [
                    0x3f27c399118ad72c,
                    0x3f23e7a632aafc99,
                    0x3f2b9f8bf06ab1bf,
                    0x3f8b938554638d27,
                    0x3f893ceceda766c1,
                    0x3f8dbb2ee7b1aa45,
                    0x3bfa401792f843c6,
                    0xbc0b5fb6288e5e03,
                    0x3c1acfe6ddc350e4,
                ],
            ),
            (
                "pitch",
                [
                    0x3eff2699fd2592dd,
                    0x3efb49e91a505c6e,
                    0x3f0181a56ffd64a6,
                    0x3f76533d6e2400ed,
                    0x3f74e53b8d1e1700,
                    0x3f77ab2dbc78dada,
                    0xbbc9064309f200bf,
                    0xbbfdc6304ecebf9a,
                    0x3bf7849f8c523f6a,
                ],
            ),
            (
                "front_travel",
                [
                    0x3f11663eed51584a,
                    0x3f0ebd4d46ccdb42,
                    0x3f136dd7373c42f3,
                    0x3f80af5e65202908,
                    0x3f7f5d07a65cece3,
                    0x3f81a1a128489f37,
                    0x3bf725f0878d1386,
                    0xbbf3e530ae85529a,
                    0x3c108c446f67de6a,
                ],
            ),
            (
                "rear_travel",
                [
                    0x3f15963a965b5f18,
                    0x3f12a2f0994eb916,
                    0x3f1889849368051a,
                    0x3f8295abc7058063,
                    0x3f81449b7d0f5fca,
                    0x3f83d062c09daf72,
                    0xbbd6e229fdca38b8,
                    0xbc09841df5671c13,
                    0x3c03cb9375f48de5,
                ],
            ),
            (
                "body_acc",
                [
                    0x3fd560dbb2297a28,
                    0x3fd456a8ea852d71,
                    0x3fd66b0e79cdc6df,
                    0x3fe27ea42497a6bf,
                    0x3fe20a0f5faa24f5,
                    0x3fe2f06b7f25d50c,
                    0xbc184f9005e4be1d,
                    0xbc62d19a05ab02de,
                    0x3c614ca1054cb6fc,
                ],
            ),
        ],
    );
}

/// A linear run file of generator version 1 (left-to-right time sums; files that record no version) is
/// never continued by this build, whose time sums differ in the last bits: the fixture
/// `tests/data/run-written-with-table-crc.h5`, written before the versions (its command in
/// `checksum_stability.rs`), left as the `.tmp` of an interrupted run of the same command, is refused with
/// both versions named and left in place; the same run into a new file records version 2.
#[test]
fn a_linear_run_of_generator_version_1_is_not_resumed() {
    let _serial = common::hdf5_serial();
    let sc = load_scenario(&root().join("data/isolator-single.toml"), &root().join("spectra")).unwrap();
    let opts = RunOptions {
        realizations: 4,
        shard_size: 2,
        store_raw: true,
        duration_s: 1.0,
        dt_s: 0.01,
        seed: 3,
        ..RunOptions::default()
    };
    let dir = common::scratch_dir("pin", "version-1");
    let out = dir.join("run.h5");
    let tmp = stochvib::store::tmp_path(&out);
    std::fs::copy(root().join("tests/data/run-written-with-table-crc.h5"), &tmp).unwrap();
    let e = sc.simulate(&opts, &out, &|_, _| {}).unwrap_err().to_string();
    for part in [
        "generator version (1 (not recorded",
        "against 2 (linear routes: every realization's time sums in eight partial sums)",
    ] {
        assert!(e.contains(part), "`{part}` not in: {e}");
    }
    assert!(tmp.exists() && !out.exists());
    std::fs::remove_file(&tmp).unwrap();
    sc.simulate(&opts, &out, &|_, _| {}).unwrap();
    let run = stochvib::store::RunFile::open(&out).unwrap();
    let meta = run.metadata();
    let version = meta.provenance.iter().find(|p| p.name == "generator_version").unwrap();
    assert!(
        version.identifies && version.text.starts_with("2 (linear routes"),
        "{version:?}"
    );
    std::fs::remove_dir_all(&dir).unwrap();
}
