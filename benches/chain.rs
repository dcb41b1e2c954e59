//! The dynamic-stiffness chain (`cargo bench --bench chain`; throughput in masses/s): the O(n) sweep
//! `TorsionalChain::harmonic_response` at n = 10, 10², …, 10⁶ against the dense O(n³) LU oracle
//! `harmonic_response_dense` at n = 10 … 400, one forcing frequency (40 rad/s). The chain is
//! `benches/h5chain/mod.rs::chain(n)` (varying inertias and shafts, a unit torque on every mass).

#[path = "h5chain/mod.rs"]
mod h5chain;

use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion, Throughput};
use h5chain::{chain, chain_check, CHAIN_P};
use std::time::Duration;

fn chain_bench(c: &mut Criterion) {
    let mut g = c.benchmark_group("dynamic_stiffness_chain");
    g.sample_size(10);
    g.warm_up_time(Duration::from_millis(500));
    g.measurement_time(Duration::from_secs(2));
    for n in [10, 100, 1_000, 10_000, 100_000, 1_000_000] {
        let (ch, torques) = chain(n);
        g.throughput(Throughput::Elements(n as u64));
        g.bench_with_input(BenchmarkId::new("sweep", n), &n, |b, _| {
            b.iter(|| chain_check(&ch.harmonic_response(CHAIN_P, &torques).unwrap()))
        });
    }
    for n in [10, 50, 100, 200, 400] {
        let (ch, torques) = chain(n);
        g.throughput(Throughput::Elements(n as u64));
        g.bench_with_input(BenchmarkId::new("dense_lu", n), &n, |b, _| {
            b.iter(|| chain_check(&ch.harmonic_response_dense(CHAIN_P, &torques).unwrap()))
        });
    }
    g.finish();
}

criterion_group!(benches, chain_bench);
criterion_main!(benches);
