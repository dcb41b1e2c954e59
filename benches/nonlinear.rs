//! Nonlinear machines (`cargo bench --bench nonlinear`): route 2 (nonlinear Monte Carlo) of the quarter car
//! with bump stops, an asymmetric damper and tyre lift-off (`data/quarter-car-bump-stops.toml`, ISO 8608
//! class D at 15 m/s) per recorded sample, the linear run of the same model (its linear part: the damper at
//! the mean of its coefficients, no stop, a tyre that holds) per sample, and route 1 (statistical
//! linearization) per parameter point, what a sweep pays.
//!
//! Route 2 runs 16 realizations × 20 s at its suggested step with its computed burn-in, no Δt-halving check,
//! statistics only, into a temporary run file, on the global rayon pool; the linear run the same sizes on
//! the route `auto` takes (spectral: ISO 8608 has no shaping filter). The numpy comparison and the thread
//! scaling are `benches/compare/nonlinear.sh`.

use criterion::{criterion_group, criterion_main, Criterion, Throughput};
use std::hint::black_box;
use std::path::PathBuf;
use std::time::Duration;
use stochvib::nonlinear::monte_carlo::NonlinearRunOptions;
use stochvib::nonlinear::{linearize, Route1Options};
use stochvib::scenario::{load_scenario, parse_scenario};
use stochvib::simulate::RunOptions;

const R: usize = 16;
const DURATION_S: f64 = 20.0;

fn config() -> Criterion {
    Criterion::default()
        .sample_size(10)
        .warm_up_time(Duration::from_millis(500))
        .measurement_time(Duration::from_secs(5))
}

fn nonlinear(c: &mut Criterion) {
    let root = PathBuf::from(concat!(env!("CARGO_MANIFEST_DIR"), "/.."));
    let spectra = root.join("spectra");
    let path = root.join("data/quarter-car-bump-stops.toml");
    let sc = load_scenario(&path, &spectra).unwrap();
    let answers = sc.nonlinear_answers().unwrap().unwrap();
    let dt = sc.suggest_nonlinear_step(&answers).unwrap().dt_s;
    let run = RunOptions {
        overwrite: true,
        realizations: R,
        duration_s: DURATION_S,
        dt_s: dt,
        seed: 1,
        ..RunOptions::default()
    };
    let n = run.samples().unwrap();
    let out = std::env::temp_dir().join(format!("stochvib-bench-nonlinear-{}.h5", std::process::id()));
    let mut g = c.benchmark_group("nonlinear_quarter_car");
    g.throughput(Throughput::Elements((R * n) as u64));
    let opts = NonlinearRunOptions {
        run: run.clone(),
        burn_in_s: None,
        halving_checks: Some(0),
    };
    g.bench_function("route2_per_sample", |b| {
        b.iter(|| {
            let s = sc.simulate_nonlinear(&answers, &opts, &out, &|_, _| {}).unwrap();
            black_box(s.run.outputs.len())
        })
    });
    // the linear part as a scenario of its own
    let text = std::fs::read_to_string(&path).unwrap();
    let head = text.split("[[model.nonlinear]]").next().unwrap();
    let linear = head.replace("\"0 N*s/m\"", "\"1.5 kN*s/m\"") + &text[text.find("[input]").unwrap()..];
    let lin = parse_scenario(&linear, &path, &spectra).unwrap();
    g.bench_function("linear_run_per_sample", |b| {
        b.iter(|| black_box(lin.simulate(&run, &out, &|_, _| {}).unwrap().n_samples))
    });
    g.throughput(Throughput::Elements(1));
    let model = sc.nonlinear_model().unwrap();
    g.bench_function("route1_per_point", |b| {
        b.iter(|| black_box(linearize(model, &sc.excitation, &Route1Options::default()).unwrap()))
    });
    g.finish();
    let _ = std::fs::remove_file(&out);
}

criterion_group! {
    name = benches;
    config = config();
    targets = nonlinear
}
criterion_main!(benches);
