//! The Rust side of `benches/compare/run.sh`: times the jobs `benches/compare/compare.py` does with
//! numpy/scipy, with the same problem sizes, and prints JSON (seconds = best of several repetitions,
//! `check` = a value both sides must agree on).
//!
//! Run: `cargo run --release --example compare_rust [-- --reps N] [--smoke]`. With `--smoke` every job runs
//! once at a tiny size (seconds in all: the CI check that the harness still runs and its JSON parses).

#[path = "../benches/common/mod.rs"]
mod common;
#[path = "../benches/h5chain/mod.rs"]
mod h5chain;

use common::*;
use serde_json::{json, Map, Value};
use std::hint::black_box;
use std::time::Instant;
use stochvib::quad::{integrate, QuadOptions};
use stochvib::response::{
    output_density, variance_integral_table, variance_lyapunov, variance_quadrature, Excitation, OutputDensity,
};
use stochvib::spectrum::{Domain, GaussCosineParameters};
#[path = "../tests/common/tolerance.rs"]
#[allow(dead_code)]
mod tolerance;
use tolerance::QUADRATURE;

/// Best (smallest) wall time over `reps` runs of `f`, divided by `inner` calls per run; returns the
/// time per job and the last check value.
fn best(reps: usize, inner: usize, mut f: impl FnMut() -> f64) -> (f64, f64) {
    let mut t_best = f64::INFINITY;
    let mut check = 0.0;
    for _ in 0..reps {
        let t0 = Instant::now();
        for _ in 0..inner {
            check = black_box(f());
        }
        t_best = t_best.min(t0.elapsed().as_secs_f64() / inner as f64);
    }
    (t_best, check)
}

/// Σ a in 8 partial sums (vectorised like numpy's pairwise sum; a serial sum of 10⁴ values is a chain of
/// 10⁴ dependent additions, ~11 µs, which would time the check instead of the density).
fn sum8(a: &[f64]) -> f64 {
    let mut s = [0.0; 8];
    let mut chunks = a.chunks_exact(8);
    for c in &mut chunks {
        for j in 0..8 {
            s[j] += c[j];
        }
    }
    s.iter().sum::<f64>() + chunks.remainder().iter().sum::<f64>()
}

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let reps: usize = args
        .iter()
        .position(|a| a == "--reps")
        .and_then(|i| args.get(i + 1))
        .and_then(|s| s.parse().ok())
        .unwrap_or(5);
    let smoke = args.iter().any(|a| a == "--smoke");
    // `--only density`: the density jobs alone (run.sh alternates them with numpy's, round after round)
    let only_density = args.windows(2).any(|w| w[0] == "--only" && w[1] == "density");
    let reps = if smoke { 1 } else { reps };
    // sizes: the comparison's, or tiny ones for the smoke run (the same list in compare.py)
    let (mc_real, mc_n) = if smoke { (4, 1 << 12) } else { (MC_REAL, MC_N) };
    let mut jobs = Map::new();
    let mut put = |key: &str, n: usize, (t, check): (f64, f64)| {
        eprintln!("{key:32} {t:12.6e} s   check {check:.12e}");
        jobs.insert(key.to_string(), json!({"seconds": t, "n": n, "check": check}));
    };

    // `--only floors`: the three Monte Carlo routes and their floors alone, in alternating rounds (run.sh runs
    // several such processes: a job's best differs between processes more than between rounds)
    if args.windows(2).any(|w| w[0] == "--only" && w[1] == "floors") {
        let (r, n) = if smoke { (4, 1 << 12) } else { (200, MC_N) };
        let rounds = if smoke { 1 } else { 5 };
        let timings = floor_rounds(r, n, rounds);
        let jobs: Map<String, Value> = timings
            .iter()
            .map(|t| {
                let v = json!({"name": t.name, "cpu_seconds": t.cpu_s, "wall_seconds": t.wall_s, "check": t.check});
                (t.key.to_string(), v)
            })
            .collect();
        let doc =
            json!({"side": "rust", "realizations": r, "samples": n, "rounds": rounds, "jobs": Value::Object(jobs)});
        println!("{}", serde_json::to_string_pretty(&doc).unwrap());
        return;
    }

    // `--only h5`: the HDF5 write and chain jobs alone (to time them, and the process's CPU, by themselves)
    if args.windows(2).any(|w| w[0] == "--only" && w[1] == "h5") {
        let jobs: Map<String, Value> = hdf5_and_chain_jobs(reps, smoke).into_iter().collect();
        let doc = json!({"side": "rust", "jobs": Value::Object(jobs)});
        println!("{}", serde_json::to_string_pretty(&doc).unwrap());
        return;
    }

    // 1. density of every spectrum type on 10⁴ points
    let wgrid = density_grid();
    let mut out = vec![0.0; wgrid.len()];
    for (name, s) in all_spectra() {
        let r = best(reps, 20, || {
            s.density_into(&wgrid, &mut out);
            sum8(&out)
        });
        put(&format!("density_{name}"), N_DENSITY, r);
    }
    if only_density {
        // the instruction set the kernels ran (`STOCHVIB_ISA` caps it; a misspelt cap is refused)
        let isa = match stochvib::linalg::vmath::Isa::cap_from_env() {
            Ok(_) => format!("{:?}", stochvib::linalg::vmath::Isa::detected()),
            Err(e) => {
                eprintln!("compare_rust: {e}");
                std::process::exit(2);
            }
        };
        let doc = json!({"side": "rust", "isa": isa, "jobs": Value::Object(jobs)});
        println!("{}", serde_json::to_string_pretty(&doc).unwrap());
        return;
    }

    // 2. one variance of the 2-DOF scraper (cab acceleration) under the rational road, three ways
    let exc = Excitation::single(road(), 0.0).expect("temporal road");
    let inst = scraper(c2_nominal(), b2_nominal());
    let sys = inst.system.as_ref();
    put(
        "variance_lyapunov",
        1,
        best(reps, 200, || variance_lyapunov(sys, &exc, X2_ACC).unwrap().variance),
    );
    put(
        "variance_table",
        1,
        best(reps, 200, || variance_integral_table(sys, &exc, X2_ACC, 0).unwrap()),
    );
    put(
        "variance_quadrature",
        1,
        best(reps, 5, || variance_quadrature(sys, &exc, X2_ACC).unwrap().value),
    );

    // 3. the 10⁵-point (c₂, b₂) sweep of σ of the cab acceleration
    let (mut c2s, mut b2s) = grid();
    if smoke {
        (c2s, b2s) = (
            c2s.iter().step_by(20).copied().collect(),
            b2s.iter().step_by(25).copied().collect(),
        );
    }
    let n_sweep = c2s.len() * b2s.len();
    let table = SweepTable::new(road().as_ref());
    put(
        "sweep_table",
        n_sweep,
        best(reps, 1, || {
            let mut acc = 0.0;
            for &c2 in &c2s {
                for &b2 in &b2s {
                    acc += table.sigma(c2, b2);
                }
            }
            acc
        }),
    );
    // every core (rayon's pool; the machine may be shared, so this row is noisy)
    put(
        "sweep_table_par",
        n_sweep,
        best(reps, 1, || {
            use rayon::prelude::*;
            c2s.par_iter()
                .map(|&c2| b2s.iter().map(|&b2| table.sigma(c2, b2)).sum::<f64>())
                .sum()
        }),
    );
    let mut lyap = SweepLyapunov::new(road().as_ref());
    put(
        "sweep_lyapunov",
        n_sweep,
        best(reps.min(2), 1, || {
            let mut acc = 0.0;
            for &c2 in &c2s {
                for &b2 in &b2s {
                    acc += lyap.sigma(c2, b2);
                }
            }
            acc
        }),
    );
    // the public API per point is slow (see RESULTS.md): time every 10th c₂ column and scale to 10⁵
    let step = 10;
    let (t_api, check_api) = best(1, 1, || {
        let mut acc = 0.0;
        for &c2 in c2s.iter().step_by(step) {
            for &b2 in &b2s {
                acc += sigma_api(&exc, c2, b2);
            }
        }
        acc
    });
    put("sweep_api", n_sweep, (t_api * step as f64, check_api));

    // 4. type-4 (GaussCosine) input through the 2-DOF model: σ² of the cab acceleration by quadrature
    let s4 = GaussCosineParameters {
        variance: T4.0,
        alpha: T4.1,
        beta: T4.2,
        domain: Domain::Temporal,
    }
    .build()
    .unwrap();
    let exc4 = Excitation::single(type4(), 0.0).unwrap();
    let mut points = sys.natural_frequencies();
    points.push(T4.2);
    let w_hi = type4_upper();
    points.retain(|w| *w > 0.0 && *w < w_hi);
    let opts = QuadOptions {
        rel_tol: QUADRATURE,
        breakpoints: points.clone(),
        ..QuadOptions::default()
    };
    // the library's integrand: the evaluator is set up inside the timed job (once per integral)
    put(
        "quad4_library",
        1,
        best(reps, 20, || {
            let density = OutputDensity::new(sys, &exc4, X2_ACC).unwrap();
            2.0 * integrate(|w| density.density(w), 0.0, w_hi, &opts).unwrap().value
        }),
    );
    // the dense reference integrand (a full complex solve per ω), the library integrand before the fast path
    put(
        "quad4_library_dense",
        1,
        best(reps, 20, || {
            2.0 * integrate(|w| output_density(sys, &exc4, X2_ACC, w), 0.0, w_hi, &opts)
                .unwrap()
                .value
        }),
    );
    let (c2n, b2n) = (c2_nominal(), b2_nominal());
    put(
        "quad4_closed",
        1,
        best(reps, 20, || {
            2.0 * integrate(|w| type4_density_closed(&s4, c2n, b2n, w), 0.0, w_hi, &opts)
                .unwrap()
                .value
        }),
    );
    put(
        "quad4_variance_quadrature",
        1,
        best(reps, 5, || variance_quadrature(sys, &exc4, X2_ACC).unwrap().value),
    );
    let evals = integrate(|w| output_density(sys, &exc4, X2_ACC, w), 0.0, w_hi, &opts)
        .unwrap()
        .evaluations;

    for (key, job) in hdf5_and_chain_jobs(reps, smoke) {
        jobs.insert(key, job);
    }

    // 5. Monte Carlo pipeline: MC_REAL = 1000 realizations × MC_N = 2¹⁶ samples of the SDOF
    //    (ω = 10 rad/s, ζ = 0.05) under K(τ) = e^{−3|τ|}, Δt = 0.01 s: generate → respond → statistics
    //    (per realization m_i, v_i; Student-t intervals of mean, σ², σ). Spectral route (the library default
    //    generator): SpectralGenerator (Rayleigh) + SampledSystem::respond (FOH), 1 warm-up period, through
    //    run_batch on a 1- and a 2-thread rayon pool; and the same periodic steady state in one FFT
    //    (`_fft`: SpectralGenerator::generate_filtered with SampledSystem::grid_response). Exact route
    //    (augmented Gauss–Markov) for reference. The check is the σ² estimate (statistical agreement with
    //    numpy: its standard error is in `check_se`).
    let mc_reps = reps.min(3);
    let mut mc_info = Map::new();
    {
        let pipe = McSpectral::new(mc_n);
        let exact = McExact::new(mc_n);
        let (ss, exc) = mc_sdof();
        let analytic = variance_lyapunov(&ss, &exc, 0).unwrap().variance;
        let mut put_mc = |key: &str, t: f64, st: &McStats| {
            eprintln!(
                "{key:32} {t:12.6e} s   σ² {:.6e} ∈ [{:.6e}, {:.6e}]",
                st.var.estimate, st.var.lower, st.var.upper
            );
            let q = stochvib::estimate::student_t_quantile(mc_real as f64 - 1.0, 0.975).unwrap();
            let se = (st.var.upper - st.var.estimate) / q;
            jobs.insert(
                key.to_string(),
                json!({"seconds": t, "n": mc_real * mc_n, "check": st.var.estimate, "check_se": se,
                       "mean": [st.mean.lower, st.mean.estimate, st.mean.upper],
                       "var": [st.var.lower, st.var.estimate, st.var.upper],
                       "sigma": [st.sigma.0, st.sigma.1, st.sigma.2]}),
            );
        };
        for threads in [1usize, 2] {
            let pool = rayon::ThreadPoolBuilder::new().num_threads(threads).build().unwrap();
            for (fft, tag) in [(false, ""), (true, "_fft")] {
                let mut st = None;
                let (t, _) = best(mc_reps, 1, || {
                    let s = pool.install(|| pipe.batch(mc_real, fft));
                    st = Some(s);
                    s.var.estimate
                });
                put_mc(&format!("mc_pipeline{tag}_{threads}t"), t, &st.unwrap());
            }
            let mut st = None;
            let (t, _) = best(mc_reps, 1, || {
                let s = pool.install(|| exact.batch(mc_real));
                st = Some(s);
                s.var.estimate
            });
            put_mc(&format!("mc_exact_{threads}t"), t, &st.unwrap());
        }
        // calibration of the machine's parallelism at this moment: 8 independent scalar spin loops on the
        // same 1- and 2-thread pools (ideal speed-up 2; on a shared machine it shows the CPU actually
        // available, against which the pipeline's 1 vs 2 thread ratio is read)
        for threads in [1usize, 2] {
            use rayon::prelude::*;
            let pool = rayon::ThreadPoolBuilder::new().num_threads(threads).build().unwrap();
            let r = best(mc_reps, 1, || {
                pool.install(|| {
                    (0..8u64)
                        .into_par_iter()
                        .map(|i| {
                            let mut x = black_box(i as f64);
                            for _ in 0..25_000_000u64 {
                                x = x * 1.000_000_1 + 1e-9;
                            }
                            x
                        })
                        .sum::<f64>()
                })
            });
            eprintln!("{:32} {:12.6e} s", format!("mc_spin_{threads}t"), r.0);
            jobs.insert(
                format!("mc_spin_{threads}t"),
                json!({"seconds": r.0, "n": 8, "check": r.1}),
            );
        }
        let mut put_floor = |key: &str, (t, check): (f64, f64)| {
            eprintln!("{key:32} {t:12.6e} s");
            jobs.insert(key.into(), json!({"seconds": t, "n": mc_real * mc_n, "check": check}));
        };
        // floor: draw the N normals of a realization + one inverse real FFT of length N, per realization
        // (1 thread; the same work as numpy's floor job)
        let mut floor = OneFftFloor::new(mc_n);
        let r = best(mc_reps, 1, || floor.run(mc_real));
        put_floor("mc_floor_1t", r);
        // (the routes against their floors: `--only floors`, in several processes)
        mc_info.insert("analytic_variance".into(), json!(analytic));
        mc_info.insert("input_grid_variance".into(), json!(pipe.generator.grid_variance()));
        mc_info.insert("warmup_periods".into(), json!(pipe.warmup));
        mc_info.insert("realizations".into(), json!(mc_real));
        mc_info.insert("samples".into(), json!(mc_n));
    }

    let doc = json!({
        "side": "rust",
        "mc": Value::Object(mc_info),
        "glibc_tunables": std::env::var("GLIBC_TUNABLES").unwrap_or_default(),
        "threads": rayon::current_num_threads(),
        "quad4_points": points,
        "quad4_evaluations": evals,
        "jobs": Value::Object(jobs),
    });
    println!("{}", serde_json::to_string_pretty(&doc).unwrap());
}

/// Jobs of the HDF5 write and chain comparison (HDF5 write through the library's `store` writer; the dynamic-stiffness chain), timed
/// like the rest (best of `reps`); see `benches/h5chain/mod.rs` for the problems.
fn hdf5_and_chain_jobs(reps: usize, smoke: bool) -> Vec<(String, Value)> {
    use h5chain::*;
    use stochvib::store::Compression;
    let mut out = Vec::new();
    let mut put = |key: &str, n: usize, (t, check): (f64, f64), extra: Value| {
        eprintln!("{key:32} {t:12.6e} s   check {check:.12e}");
        let mut job = json!({"seconds": t, "n": n, "check": check});
        if let (Value::Object(j), Value::Object(e)) = (&mut job, extra) {
            j.extend(e);
        }
        out.push((key.to_string(), job));
    };

    // HDF5: write 1000 × 2¹⁶ f64 (524 MB) through RunWriter, timed from create to finish (fsync + rename
    // included) or to drop (close, no fsync); the data are read back afterwards (not timed) for the check.
    let dir = h5_tmpdir("compare");
    let (rows, deflate_rows, cols) = if smoke {
        (4, 2, 1 << 12)
    } else {
        (H5_ROWS, H5_DEFLATE_ROWS, H5_COLS)
    };
    let cases: [(&str, usize, Compression, bool, usize); 3] = [
        ("h5_write_none", rows, Compression::None, true, reps),
        ("h5_write_none_nosync", rows, Compression::None, false, reps),
        (
            "h5_write_deflate1",
            deflate_rows,
            Compression::DEFLATE_FAST,
            true,
            reps.min(2),
        ),
    ];
    let mut data = h5_data(rows, cols);
    for (key, rows, comp, finish, r) in cases {
        if data.nrows() != rows {
            data = h5_data(rows, cols);
        }
        let path = dir.join(format!("{key}.h5"));
        let mut t_best = f64::INFINITY;
        let mut written = path.clone();
        for _ in 0..r.max(1) {
            let _ = std::fs::remove_file(&path);
            let _ = std::fs::remove_file(stochvib::store::tmp_path(&path));
            let t0 = Instant::now();
            written = h5_write_library(&path, &data, comp, finish);
            t_best = t_best.min(t0.elapsed().as_secs_f64());
        }
        let check = h5_read_check(&written);
        let bytes = rows * cols * 8;
        let size = std::fs::metadata(&written).map(|m| m.len()).unwrap_or(0);
        let _ = std::fs::remove_file(&written);
        put(
            key,
            bytes,
            (t_best, check),
            json!({"mb_per_s": bytes as f64 / t_best / 1e6, "file_bytes": size}),
        );
    }
    drop(data);
    let _ = std::fs::remove_dir_all(&dir);

    // the chain: the O(n) sweep at n = 10⁴, 10⁵, 10⁶ and 400, the library's dense LU oracle at n = 400
    for (key, n) in [
        ("chain_sweep_400", 400),
        ("chain_sweep_1e4", 10_000),
        ("chain_sweep_1e5", 100_000),
        ("chain_sweep_1e6", 1_000_000),
    ] {
        let n = if smoke { n.min(10_000) } else { n };
        let (ch, torques) = chain(n);
        let inner = (1_000_000 / n).clamp(1, 100);
        let r = best(reps, inner, || {
            chain_check(&ch.harmonic_response(CHAIN_P, &torques).expect("damped chain"))
        });
        put(key, n, r, json!({"seconds_per_mass": r.0 / n as f64}));
    }
    let (ch, torques) = chain(400);
    let r = best(reps.min(3), 1, || {
        chain_check(&ch.harmonic_response_dense(CHAIN_P, &torques).expect("damped chain"))
    });
    put("chain_dense_400", 400, r, json!({}));
    out
}
