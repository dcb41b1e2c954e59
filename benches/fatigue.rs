//! Fatigue benchmarks (`cargo bench --bench fatigue`): streaming rainflow + Miner sum of 10⁸ samples
//! (a resonant record and white noise), and a Dirlik life from a density (moments by adaptive quadrature
//! plus the damage), from the density tabulated at 50 001 points, and from given moments.

#[path = "common/fatigue_signal.rs"]
mod fatigue_signal;

use criterion::{criterion_group, criterion_main, Criterion, Throughput};
use fatigue_signal::*;
use std::hint::black_box;
use stochvib::fatigue::{Dirlik, RainflowCounter, SnCurve, SpectralMethod, SpectralMoments};

/// Rainflow count of the whole record in 1 Mi-sample chunks with a streaming Miner sum (k = 3).
fn count(x: &[f64]) -> (f64, usize) {
    let mut rc = RainflowCounter::new();
    let mut d = 0.0;
    for chunk in x.chunks(1 << 20) {
        rc.push(chunk, |c| d += c.count * c.amplitude * c.amplitude * c.amplitude)
            .unwrap();
    }
    let full = rc.full_cycles();
    rc.finish(|c| d += c.count * c.amplitude * c.amplitude * c.amplitude);
    (d, full)
}

fn rainflow_1e8(c: &mut Criterion) {
    let mut g = c.benchmark_group("rainflow_1e8");
    g.sample_size(10);
    g.throughput(Throughput::Elements(N_RAINFLOW as u64));
    for (name, x) in [
        ("resonant", resonant_signal(N_RAINFLOW)),
        ("white", white_signal(N_RAINFLOW)),
    ] {
        g.bench_function(name, |b| b.iter(|| black_box(count(black_box(&x)))));
    }
    g.finish();
}

fn dirlik(c: &mut Criterion) {
    let sn = SnCurve {
        k: SN_K,
        c: SN_C,
        endurance_limit: None,
    }
    .build()
    .unwrap();
    let mut g = c.benchmark_group("dirlik");
    g.bench_function("life_from_density", |b| {
        b.iter(|| {
            let m = SpectralMoments::from_one_sided_hz(sdof_density, 0.0, SDOF_F_MAX, &[SDOF_FN]).unwrap();
            black_box(Dirlik.life(&m, &sn).unwrap())
        })
    });
    let npts = 50_001;
    let f: Vec<f64> = (0..npts).map(|i| i as f64 * SDOF_F_MAX / (npts - 1) as f64).collect();
    let gv: Vec<f64> = f.iter().map(|&x| sdof_density(x)).collect();
    g.bench_function("life_from_table_50001", |b| {
        b.iter(|| {
            let m = SpectralMoments::from_tabulated_one_sided_hz(black_box(&f), black_box(&gv), false).unwrap();
            black_box(Dirlik.life(&m, &sn).unwrap())
        })
    });
    let m = SpectralMoments::from_one_sided_hz(sdof_density, 0.0, SDOF_F_MAX, &[SDOF_FN]).unwrap();
    g.bench_function("life_from_moments", |b| {
        b.iter(|| black_box(Dirlik.life(black_box(&m), &sn).unwrap()))
    });
    g.finish();
}

criterion_group!(benches, rainflow_1e8, dirlik);
criterion_main!(benches);
