//! Density evaluation of every spectrum type on a 10⁴-point grid (`cargo bench --bench spectra`).

mod common;

use common::{all_spectra, density_grid, N_DENSITY};
use criterion::{criterion_group, criterion_main, Criterion, Throughput};
use std::hint::black_box;

fn densities(c: &mut Criterion) {
    let grid = density_grid();
    let mut out = vec![0.0; grid.len()];
    let mut g = c.benchmark_group("density_1e4");
    g.throughput(Throughput::Elements(N_DENSITY as u64));
    for (name, s) in all_spectra() {
        g.bench_function(name, |b| {
            b.iter(|| {
                for (o, &w) in out.iter_mut().zip(&grid) {
                    *o = s.density(black_box(w));
                }
                black_box(&out);
            })
        });
        g.bench_function(format!("{name}/density_into"), |b| {
            b.iter(|| {
                s.density_into(black_box(&grid), &mut out);
                black_box(&out);
            })
        });
    }
    g.finish();
}

criterion_group!(benches, densities);
criterion_main!(benches);
