//! Variance of a 2-DOF model three ways under a rational road, and under a type-4 input by quadrature
//! (`cargo bench --bench variance`).
//!
//! Models: the sprung-cab scraper (`x2_acc`) and the quarter car of `data/quarter-car.toml` (`body_acc`,
//! built by `load_scenario`), both under the graded dirt road (8.69) at 10 m/s.

mod common;

use common::*;
use criterion::{criterion_group, criterion_main, Criterion};
use std::hint::black_box;
use std::path::Path;
use stochvib::quad::{integrate, QuadOptions};
use stochvib::response::{
    output_density, variance_integral_table, variance_lyapunov, variance_quadrature, Excitation, OutputDensity,
};
use stochvib::scenario::load_scenario;
use stochvib::system::FrequencyResponse;
#[path = "../tests/common/tolerance.rs"]
#[allow(dead_code)]
mod tolerance;
use tolerance::QUADRATURE;

fn rational_road(c: &mut Criterion) {
    let exc = Excitation::single(road(), 0.0).unwrap();
    let scr = scraper(c2_nominal(), b2_nominal());
    let root = Path::new(concat!(env!("CARGO_MANIFEST_DIR"), "/.."));
    let qc = load_scenario(&root.join("data/quarter-car.toml"), &root.join("spectra")).expect("quarter car");
    let qsys = qc.model.system.clone();
    let body_acc = qsys.outputs().iter().position(|o| o.name == "body_acc").unwrap();
    let models: [(&str, &dyn FrequencyResponse, usize); 2] = [
        ("scraper_x2_acc", scr.system.as_ref(), X2_ACC),
        ("quarter_car_body_acc", qsys.as_ref(), body_acc),
    ];
    let mut g = c.benchmark_group("variance_rational_road");
    for (name, sys, i) in models {
        g.bench_function(format!("{name}/lyapunov"), |b| {
            b.iter(|| variance_lyapunov(sys, black_box(&exc), i).unwrap().variance)
        });
        g.bench_function(format!("{name}/integral_table"), |b| {
            b.iter(|| variance_integral_table(sys, black_box(&exc), i, 0).unwrap())
        });
        g.bench_function(format!("{name}/quadrature"), |b| {
            b.iter(|| variance_quadrature(sys, black_box(&exc), i).unwrap().value)
        });
    }
    g.finish();
}

fn type4_input(c: &mut Criterion) {
    let exc4 = Excitation::single(type4(), 0.0).unwrap();
    let scr = scraper(c2_nominal(), b2_nominal());
    let sys = scr.system.as_ref();
    let mut points = sys.natural_frequencies();
    points.push(T4.2);
    let w_hi = type4_upper();
    let opts = QuadOptions {
        rel_tol: QUADRATURE,
        breakpoints: points,
        ..QuadOptions::default()
    };
    let mut g = c.benchmark_group("variance_type4_scraper_x2_acc");
    g.bench_function("integrate_output_density_rel1e-8", |b| {
        b.iter(|| {
            let density = OutputDensity::new(sys, &exc4, X2_ACC).unwrap();
            integrate(|w| density.density(w), 0.0, w_hi, black_box(&opts)).unwrap()
        })
    });
    g.bench_function("integrate_dense_output_density_rel1e-8", |b| {
        b.iter(|| integrate(|w| output_density(sys, &exc4, X2_ACC, w), 0.0, w_hi, black_box(&opts)).unwrap())
    });
    g.bench_function("variance_quadrature_rel1e-10", |b| {
        b.iter(|| variance_quadrature(sys, black_box(&exc4), X2_ACC).unwrap().value)
    });
    g.finish();
}

criterion_group!(benches, rational_road, type4_input);
criterion_main!(benches);
