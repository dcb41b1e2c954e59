//! Value stability: the Monte Carlo statistics of a seed are pinned to the last bit, so that a refactoring,
//! a dependency update or a change of thread count cannot change a stored result silently (the practice of
//! `rand`'s value-stability tests).
//!
//! Provenance: the pinned bit patterns were printed by `stochvib simulate … --json` at commit 67bb861 (before
//! the architecture rework) for the two runs below, one per route. They pin behaviour, not
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
                    0x3f4fa6101aeb5e35,
                    0x3f46a0701cd5d2ef,
                    0x3f5455d80c8074be,
                    0x3f9fd2e848123e7f,
                    0x3f9ae8841372e2d3,
                    0x3fa209b2be0d43b6,
                    0x3f7573822d205f9b,
                    0xbf65f42cc90235b2,
                    0x3f8af08d5f60ed08,
                ],
            ),
            (
                "y_vel",
                [
                    0x3f9af40dc33025ff,
                    0x3f98faff0226a53e,
                    0x3f9ced1c8439a6c0,
                    0x3fc4c4428e32f7af,
                    0x3fc3fdff80cf8878,
                    0x3fc58363a55ee773,
                    0xbf239aeefd6a8bd6,
                    0xbf69d5125ae7985b,
                    0x3f6761b47b3a46e1,
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
                    0x3bf4d4e75224190e,
                    0xbc2c97e745c75626,
                    0x3c30e6908d282e35,
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
                    0xbbdb66c4b2477580,
                    0xbc0da8e72bd4b87d,
                    0x3c06cf35ff42db1d,
                ],
            ),
            (
                "front_travel",
                [
                    0x3f11663eed51584a,
                    0x3f0ebd4d46ccdb40,
                    0x3f136dd7373c42f4,
                    0x3f80af5e65202908,
                    0x3f7f5d07a65cece2,
                    0x3f81a1a128489f37,
                    0x3c10cbb1e9299f7e,
                    0x3bd2d8acffb8f040,
                    0x3c2034ec812bd7fc,
                ],
            ),
            (
                "rear_travel",
                [
                    0x3f15963a965b5f15,
                    0x3f12a2f0994eb914,
                    0x3f18898493680516,
                    0x3f8295abc7058062,
                    0x3f81449b7d0f5fc9,
                    0x3f83d062c09daf70,
                    0xbbeaec7a4a67df9a,
                    0xbc10f6d1904ba834,
                    0x3c047765fb63609c,
                ],
            ),
            (
                "body_acc",
                [
                    0x3fd560dbb2297a2b,
                    0x3fd456a8ea852d74,
                    0x3fd66b0e79cdc6e2,
                    0x3fe27ea42497a6c0,
                    0x3fe20a0f5faa24f7,
                    0x3fe2f06b7f25d50d,
                    0x3c27814a0993b4db,
                    0xbc62b3c7d6b4fccb,
                    0x3c65a3f117e77367,
                ],
            ),
        ],
    );
}
