//! A 10⁵-point (c₂, b₂) sweep of σ of the sprung-cab scraper's cab acceleration on the rational road
//! (8.69) at 10 m/s (`cargo bench --bench sweep`; throughput in points/s).
//!
//! The fast path factors the road once and, per point, forms the closed-form polynomials of (8.65) on the
//! stack and calls `h2_integral`; no model instance, output names or descriptions are built per point.
//! The slower variants (library Lyapunov per point, public model API per point) run on a 10³-point subgrid.

mod common;

use common::*;
use criterion::{criterion_group, criterion_main, Criterion, Throughput};
use stochvib::response::Excitation;

fn sweep(c: &mut Criterion) {
    let (c2s, b2s) = grid();
    let table = SweepTable::new(road().as_ref());
    let mut g = c.benchmark_group("sweep_scraper_x2_acc");
    g.sample_size(10);
    g.throughput(Throughput::Elements((c2s.len() * b2s.len()) as u64));
    g.bench_function("table_h2_integral_1e5", |b| {
        b.iter(|| {
            let mut acc = 0.0;
            for &c2 in &c2s {
                for &b2 in &b2s {
                    acc += table.sigma(c2, b2);
                }
            }
            acc
        })
    });
    // 10³-point subgrid (every 20th of the 400 c₂ values, every 5th of the 250 b₂ values: 20 × 50) for the
    // slow per-point variants. (Until 2026-11-25 this took every 40th and every 25th value, 10 × 10 = 100
    // points, while the throughput said 10³: the rows read 10× too fast.)
    let sub: Vec<(f64, f64)> = c2s
        .iter()
        .step_by(20)
        .flat_map(|&c2| b2s.iter().step_by(5).map(move |&b2| (c2, b2)))
        .collect();
    assert_eq!(sub.len(), 1000, "the subgrid of the 1e3 rows");
    g.throughput(Throughput::Elements(sub.len() as u64));
    let mut lyap = SweepLyapunov::new(road().as_ref());
    g.bench_function("lyapunov_per_point_1e3", |b| {
        b.iter(|| sub.iter().map(|&(c2, b2)| lyap.sigma(c2, b2)).sum::<f64>())
    });
    let exc = Excitation::single(road(), 0.0).unwrap();
    g.bench_function("public_api_per_point_1e3", |b| {
        b.iter(|| sub.iter().map(|&(c2, b2)| sigma_api(&exc, c2, b2)).sum::<f64>())
    });
    g.finish();
}

/// The path users take: `stochvib sweep`'s library calls on `data/scraper-sprung-cab.toml` over a
/// 100 × 100 (ω₂, ζ₂) grid (the scenario parsed once, every swept value read once; per point the numeric
/// builder writes the closed-form transfer polynomials of (8.65) and one Hurwitz elimination with its
/// linear functional covers the variance and λ₂ of the 4 outputs, each condition-checked), one
/// thread and all cores; the general path (model rebuilt from its table) for comparison; then the CSV of
/// the table.
fn scenario_sweep(c: &mut Criterion) {
    use std::path::Path;
    use stochvib::scenario::load_scenario;
    use stochvib::study::compute_sweep;
    use stochvib::study::{Sweep, SweepMode, SweepParam, SweepSpec};
    let sc = load_scenario(Path::new("data/scraper-sprung-cab.toml"), Path::new("spectra")).unwrap();
    let spec = SweepSpec::new(
        vec![
            SweepParam::parse("model.omega2=1 Hz..2.5 Hz:100").unwrap(),
            SweepParam::parse("model.zeta2=0.1..0.5:100").unwrap(),
        ],
        SweepMode::Grid,
    )
    .unwrap();
    let sweep = Sweep::new(&sc, spec).unwrap();
    let n = sweep.spec().n_points();
    let mut g = c.benchmark_group("scenario_sweep_scraper_4_outputs");
    g.sample_size(10);
    g.throughput(Throughput::Elements(n as u64));
    g.bench_function("evaluate_range_1e4_one_thread", |b| {
        b.iter(|| sweep.evaluate_range(0..n, false).len())
    });
    g.bench_function("evaluate_range_1e4_all_cores", |b| {
        b.iter(|| sweep.evaluate_range(0..n, true).len())
    });
    // the general path (model rebuilt from its substituted table per point) on the first 10³ points
    g.throughput(Throughput::Elements(1000));
    g.bench_function("evaluate_general_1e3_one_thread", |b| {
        b.iter(|| {
            (0..1000)
                .map(|p| sweep.evaluate_general(p).is_ok() as usize)
                .sum::<usize>()
        })
    });
    g.throughput(Throughput::Elements(n as u64));
    let table = compute_sweep(&sweep, 0..n, true, None, &|_, _| {}).unwrap();
    g.bench_function("to_csv_1e4", |b| b.iter(|| table.to_csv().len()));
    // rows into one flat buffer (nothing allocated per point), all cores
    let mut rows = vec![stochvib::study::FAILED_POINT; n * sweep.outputs().len()];
    g.bench_function("evaluate_into_1e4_all_cores", |b| {
        b.iter(|| sweep.evaluate_into(0..n, true, &mut rows).len())
    });
    // what `stochvib sweep -o table.h5` does after start-up: blocks evaluated on every core while a writer
    // thread puts the previous block into the file (2.4 MB), renamed when complete
    let dir = std::env::temp_dir().join(format!("stochvib-bench-sweep-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("table.h5");
    let opts = stochvib::study::StreamOptions::default();
    g.bench_function("write_sweep_table_h5_1e4", |b| {
        b.iter(|| {
            stochvib::study::write_sweep_table(&sweep, &path, true, None, opts, &|_, _| {})
                .unwrap()
                .n_points
        })
    });
    let _ = std::fs::remove_dir_all(&dir);
    g.finish();
}

criterion_group!(benches, sweep, scenario_sweep);
criterion_main!(benches);
