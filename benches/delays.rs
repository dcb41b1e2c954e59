//! Time per call of the two delayed-input routes on a 3-DOF, 2-input vehicle (`cargo bench --bench delays`):
//! the exact delayed covariance (`variance_lyapunov_delayed`: variance, λ₂, λ₄ at once) and the oscillatory
//! quadrature (`spectral_moment_oscillatory`, per moment), next to the plain adaptive quadrature where it
//! converges.
//!
//! Model: a body (bounce z, pitch φ; 1500 kg, radius of gyration 1.2 m) on two spring–damper wheels 2.6 m
//! apart (4e4 N/m, 2.5e3 N s/m) with a 90 kg seat (1.5e4 N/m, 600 N s/m) 0.5 m ahead of the centre; road
//! type 1 in space (D = 1e-4 m², α = 0.1 1/m) at 11 m/s, rear delay 2.6/11 s. Outputs: seat displacement
//! (variance, λ₂, λ₄ finite) and body velocity (variance finite, the plain quadrature stalls).

use criterion::{criterion_group, criterion_main, Criterion};
use std::hint::black_box;
use std::sync::Arc;
use stochvib::quad_oscillatory::OscillatoryOptions;
use stochvib::response::{spectral_moment_oscillatory, variance_lyapunov_delayed, variance_quadrature, Excitation};
use stochvib::spectrum::{AtSpeed, Domain, Exponential, Spectrum};
use stochvib::system::{Attach, Element, Mdof, Quantity};

fn model() -> (Mdof, Excitation) {
    let wheel = |name: &str, x: f64, j: usize| Element {
        name: name.into(),
        point: vec![1.0, x, 0.0],
        to: Attach::Base(j),
        stiffness: 4e4,
        damping: 2.5e3,
    };
    let seat = Element {
        name: "seat".into(),
        point: vec![0.0, 0.0, 1.0],
        to: Attach::Point(vec![1.0, 0.5, 0.0]),
        stiffness: 1.5e4,
        damping: 600.0,
    };
    let m = Mdof::from_elements(
        &[("z", "m"), ("phi", "rad"), ("s", "m")],
        &[1500.0, 1500.0 * 1.2f64.powi(2), 90.0],
        vec![wheel("front", 1.3, 0), wheel("rear", -1.3, 1), seat],
        2,
        &[],
    )
    .unwrap()
    .with_output("seat", Quantity::Displacement(vec![0.0, 0.0, 1.0]))
    .unwrap()
    .with_output("body_vel", Quantity::Velocity(vec![1.0, 0.0, 0.0]))
    .unwrap();
    let v = 11.0;
    let spatial = Arc::new(Exponential::new(1e-4, 0.1, Domain::Spatial).unwrap());
    let road: Arc<dyn Spectrum> = Arc::new(AtSpeed::new(spatial, v).unwrap());
    let exc = Excitation::track(road, vec![0.0, 2.6 / v], vec![1.0, 1.0], 0.0).unwrap();
    (m, exc)
}

fn delays(c: &mut Criterion) {
    let (m, exc) = model();
    let opts = OscillatoryOptions::default();
    let mut g = c.benchmark_group("delays_3dof_2inputs");
    for (i, name) in [(0usize, "seat"), (1, "body_vel")] {
        g.bench_function(format!("{name}/lyapunov_delayed_all_moments"), |b| {
            b.iter(|| variance_lyapunov_delayed(&m, black_box(&exc), i).unwrap().variance)
        });
        g.bench_function(format!("{name}/oscillatory_variance"), |b| {
            b.iter(|| {
                spectral_moment_oscillatory(&m, black_box(&exc), i, 0, &opts)
                    .unwrap()
                    .value
            })
        });
    }
    g.bench_function("seat/oscillatory_lambda2", |b| {
        b.iter(|| {
            spectral_moment_oscillatory(&m, black_box(&exc), 0, 2, &opts)
                .unwrap()
                .value
        })
    });
    g.bench_function("seat/oscillatory_lambda4", |b| {
        b.iter(|| {
            spectral_moment_oscillatory(&m, black_box(&exc), 0, 4, &opts)
                .unwrap()
                .value
        })
    });
    g.bench_function("seat/plain_quadrature_variance", |b| {
        b.iter(|| variance_quadrature(&m, black_box(&exc), 0).unwrap().value)
    });
    g.finish();
}

criterion_group!(benches, delays);
criterion_main!(benches);
