//! ISO 2631-1 weighted r.m.s. a_w of the operator seat (`data/operator-seat-verdicts.toml`: rational
//! cab-floor input, W_k on the seat acceleration) over a sweep of seat stiffness × damping
//! (`cargo bench --bench weighting`; throughput in points/s). Per point: the model, its state space, the
//! weighted output W_k(s)·H(s) and the Lyapunov covariance of the system augmented with the input's
//! shaping filter (the public API, nothing cached). `benches/compare/weighting.py` does the same with
//! scipy's `solve_continuous_lyapunov` per point.

use criterion::{criterion_group, criterion_main, Criterion, Throughput};
use std::sync::Arc;
use stochvib::comfort::{weighted_output, WeightedEvaluator, Weighting};
use stochvib::models::operator_seat::OperatorSeat;
use stochvib::response::{variance_lyapunov, Excitation};
use stochvib::spectrum::{Domain, RationalSpectrum};
use stochvib::system::FrequencyResponse;

/// The cab-floor input of `data/operator-seat-verdicts.toml`.
fn input() -> Excitation {
    let s = RationalSpectrum::new(
        vec![9.978705857784458],
        vec![124596039.48735943, -448861.0914846832, 404.2589962686201, 1.0],
        Domain::Temporal,
    )
    .unwrap();
    Excitation::single(Arc::new(s), 0.0).unwrap()
}

/// a_w of one (stiffness N/m, damping N s/m) point.
fn a_w(exc: &Excitation, k: f64, b: f64) -> f64 {
    let seat = OperatorSeat {
        operator_mass: 80.0,
        seat_mass: 26.0,
        stiffness: k,
        damping: b,
    }
    .build()
    .unwrap();
    let m = seat.instance().unwrap();
    let ss = m.system.state_space().unwrap();
    let i = ss.outputs().iter().position(|o| o.name == "seat_acc").unwrap();
    let w = weighted_output(ss, i, &Weighting::Wk).unwrap();
    variance_lyapunov(&w, exc, 0).unwrap().variance.sqrt()
}

/// a_w of one point by the prepared [`WeightedEvaluator`] (the poles of W_k and of the input filter found
/// once; per point the model, its state space, Faddeev–LeVerrier and the checked residue sum).
fn a_w_fast(ev: &WeightedEvaluator, exc: &Excitation, k: f64, b: f64) -> f64 {
    let seat = OperatorSeat {
        operator_mass: 80.0,
        seat_mass: 26.0,
        stiffness: k,
        damping: b,
    }
    .build()
    .unwrap();
    let m = seat.instance().unwrap();
    let ss = m.system.state_space().unwrap();
    let i = ss.outputs().iter().position(|o| o.name == "seat_acc").unwrap();
    ev.a_w(ss, i, exc).unwrap().a_w
}

fn weighting(c: &mut Criterion) {
    let exc = input();
    // 10⁴-point subgrid of the 10⁵-point sweep of the comparison script (100 × 100 of 317 × 317)
    let ks: Vec<f64> = (0..100).map(|i| 3000.0 + 100.0 * i as f64).collect();
    let bs: Vec<f64> = (0..100).map(|j| 200.0 + 20.0 * j as f64).collect();
    let mut g = c.benchmark_group("weighting_a_w_sweep");
    g.sample_size(10);
    g.throughput(Throughput::Elements((ks.len() * bs.len()) as u64));
    g.bench_function("public_api_lyapunov_1e4", |bch| {
        bch.iter(|| {
            let mut acc = 0.0;
            for &k in &ks {
                for &b in &bs {
                    acc += a_w(&exc, k, b);
                }
            }
            acc
        })
    });
    let ev = WeightedEvaluator::new(&exc, Weighting::Wk).unwrap();
    g.bench_function("public_api_weighted_evaluator_1e4", |bch| {
        bch.iter(|| {
            let mut acc = 0.0;
            for &k in &ks {
                for &b in &bs {
                    acc += a_w_fast(&ev, &exc, k, b);
                }
            }
            acc
        })
    });
    // the seat's closed-form transfer function, no model or state space per point
    g.bench_function("public_api_a_w_rational_1e4", |bch| {
        bch.iter(|| {
            let mut acc = 0.0;
            for &k in &ks {
                for &b in &bs {
                    let (num, den) = OperatorSeat {
                        operator_mass: 80.0,
                        seat_mass: 26.0,
                        stiffness: k,
                        damping: b,
                    }
                    .build()
                    .unwrap()
                    .seat_acc_transfer();
                    acc += ev.a_w_rational(&num, &den, &exc).unwrap().a_w;
                }
            }
            acc
        })
    });
    g.finish();
}

criterion_group!(benches, weighting);
criterion_main!(benches);
