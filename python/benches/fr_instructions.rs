//! The Rust side of `python/bench/fr_instructions.sh`: `K` frequency responses of the quarter car at 10⁴
//! points into a fresh (output, input, ω) array, exactly as the binding's `frequency_response` computes them.
//! Run under callgrind with K = 1 and K = 3: half the difference is the instruction count of one call,
//! whatever the machine's load (`python/bench/fr_instructions.py` is the Python side).

use nalgebra::Complex;
use stochvib::prelude::*;
use stochvib::system::FrequencyResponse;
fn main() {
    let k: usize = std::env::args().nth(1).unwrap().parse().unwrap();
    let n = 10_000;
    let w: Vec<f64> = (0..n)
        .map(|i| 0.01 + (100.0 - 0.01) * i as f64 / (n - 1) as f64)
        .collect();
    let sys = QuarterCar {
        sprung_mass: 300.0,
        unsprung_mass: 40.0,
        suspension_stiffness: 20e3,
        suspension_damping: 1.5e3,
        tyre_stiffness: 200e3,
        tyre_damping: 0.0,
    }
    .build()
    .unwrap()
    .system()
    .unwrap();
    let (p, m) = (sys.outputs().len(), sys.n_inputs());
    let mut acc = 0.0;
    for _ in 0..k {
        let mut out = vec![Complex::new(0.0, 0.0); p * m * n];
        for (kk, &x) in std::hint::black_box(&w).iter().enumerate() {
            let h = sys.response(x);
            for i in 0..p {
                for j in 0..m {
                    out[(i * m + j) * n + kk] = h[(i, j)];
                }
            }
        }
        acc += out[n / 2].re;
    }
    println!("{acc}");
}
