//! The Rust side of `benches/compare/nonlinear.sh`: route 2 (nonlinear Monte Carlo) of
//! `data/quarter-car-bump-stops.toml` on 1 and on 2 threads, the linear run of the same model (the linear
//! part: the damper at the mean of its two coefficients, no stop, a tyre that holds) and route 1 per
//! parameter point, and route 2 and the linear run of the same model on a rational road (where both take
//! their exact routes); prints JSON (seconds = best of several repetitions, wall and process CPU time).
//!
//! Run: `cargo run --release --example compare_nonlinear -- [--realizations R] [--duration T] [--reps K]
//! [--scaling]`; `--scaling` times only route 2 and the calibration spin loops on 1 and 2 threads (the
//! thread-scaling rows; `bash benches/compare/nonlinear.sh --scaling`); `--route2` times only route 2 on one
//! thread (for a profiler: `perf record -e cpu-clock -- compare_nonlinear --route2 --reps 1`).
//! The step is route 2's suggestion for the scenario and the burn-in route 2's default (both printed, so
//! that `benches/compare/nonlinear.py` runs the same steps); no Δt-halving check (the numpy peer has none),
//! statistics only (no raw samples), one temporary run file per run; routes 1 and 3 are computed once, before
//! the timing (route 1 is timed on its own).

use serde_json::json;
use std::path::{Path, PathBuf};
use std::time::Instant;
use stochvib::nonlinear::monte_carlo::{NonlinearRunOptions, NonlinearRunSummary};
use stochvib::nonlinear::{linearize, Route1Options};
use stochvib::scenario::{load_scenario, parse_scenario, Scenario};
use stochvib::simulate::RunOptions;
use stochvib::study::NonlinearAnswers;

/// Process CPU time, s (all threads).
fn cpu_seconds() -> f64 {
    let mut ts = libc::timespec { tv_sec: 0, tv_nsec: 0 };
    // SAFETY: clock_gettime writes one timespec into the valid pointer we pass.
    unsafe { libc::clock_gettime(libc::CLOCK_PROCESS_CPUTIME_ID, &mut ts) };
    ts.tv_sec as f64 + ts.tv_nsec as f64 * 1e-9
}

/// Best wall and best CPU time of `reps` calls of `f`, and its last result.
fn best<T>(reps: usize, mut f: impl FnMut() -> T) -> (f64, f64, T) {
    let (mut wall, mut cpu) = (f64::INFINITY, f64::INFINITY);
    let mut last = None;
    for _ in 0..reps {
        let (t0, c0) = (Instant::now(), cpu_seconds());
        last = Some(f());
        wall = wall.min(t0.elapsed().as_secs_f64());
        cpu = cpu.min(cpu_seconds() - c0);
    }
    (wall, cpu, last.expect("reps >= 1"))
}

fn arg(args: &[String], name: &str, default: f64) -> f64 {
    args.iter()
        .position(|a| a == name)
        .and_then(|i| args.get(i + 1))
        .map_or(default, |v| v.parse().expect("a number"))
}

/// 64 independent chains of 2·10⁷ dependent multiply-adds, spread over the pool.
fn spin() -> f64 {
    use rayon::prelude::*;
    (0..64u64)
        .into_par_iter()
        .map(|i| {
            let mut x = i as f64 * 1e-3;
            for _ in 0..20_000_000 / 64 {
                x = std::hint::black_box(x * 0.999_999 + 1e-9);
            }
            x
        })
        .sum()
}

/// CRC-32 of the bits of every statistic of the run (estimate and bounds): equal before and after a change
/// that must keep the results of a seed bit-identical.
fn statistics_crc(s: &NonlinearRunSummary) -> u32 {
    let mut h = crc32fast::Hasher::new();
    for o in &s.run.outputs {
        for st in &o.statistics {
            let iv = &st.interval;
            for v in [iv.estimate, iv.lower, iv.upper] {
                h.update(&v.to_bits().to_le_bytes());
            }
        }
    }
    h.finalize()
}

fn pool(threads: usize) -> rayon::ThreadPool {
    rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .expect("a thread pool")
}

/// The linear part of the scenario as a scenario of its own: no nonlinear tables, the damper's mean.
fn linear_text(text: &str) -> String {
    let head = text.split("[[model.nonlinear]]").next().expect("text");
    let tail = &text[text.find("[input]").expect("an [input] table")..];
    head.replace("\"0 N*s/m\"", "\"1.5 kN*s/m\"") + tail
}

fn nonlinear_run(sc: &Scenario, answers: &NonlinearAnswers, opts: &RunOptions, out: &Path) -> NonlinearRunSummary {
    let o = NonlinearRunOptions {
        run: RunOptions {
            overwrite: true,
            ..opts.clone()
        },
        burn_in_s: None,
        halving_checks: Some(0),
    };
    sc.simulate_nonlinear(answers, &o, out, &|_, _| {}).unwrap()
}

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let r = arg(&args, "--realizations", 512.0) as usize;
    let duration = arg(&args, "--duration", 30.0);
    let reps = arg(&args, "--reps", 3.0) as usize;
    let scaling_only = args.iter().any(|a| a == "--scaling");
    let route2_only = args.iter().any(|a| a == "--route2");
    let threads: &[usize] = if route2_only { &[1] } else { &[1, 2] };
    let root = PathBuf::from(env!("CARGO_MANIFEST_DIR"));
    let spectra = root.join("spectra");
    let path = root.join("data/quarter-car-bump-stops.toml");
    let sc = load_scenario(&path, &spectra).unwrap();
    let answers = sc.nonlinear_answers().unwrap().unwrap();
    let step = sc.suggest_nonlinear_step(&answers).unwrap();
    let dir = std::env::temp_dir().join(format!("stochvib-compare-nonlinear-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let opts = RunOptions {
        realizations: r,
        duration_s: duration,
        dt_s: step.dt_s,
        seed: 1,
        ..RunOptions::default()
    };
    let out = dir.join("run.h5");
    let mut rows = serde_json::Map::new();
    let mut summary = None;
    for &threads in threads {
        let p = pool(threads);
        let (wall, cpu, s) = best(reps, || p.install(|| nonlinear_run(&sc, &answers, &opts, &out)));
        rows.insert(
            format!("route2_{threads}_threads"),
            json!({"seconds": wall, "cpu_seconds": cpu}),
        );
        summary = Some(s);
    }
    // what a second core gives at all on this machine now: the same fixed arithmetic on 1 and 2 threads
    for &threads in if route2_only { &[][..] } else { threads } {
        let p = pool(threads);
        let (wall, cpu, _) = best(reps, || p.install(spin));
        rows.insert(
            format!("spin_{threads}_threads"),
            json!({"seconds": wall, "cpu_seconds": cpu}),
        );
    }
    let s = summary.unwrap();
    if !scaling_only && !route2_only {
        single_thread_jobs(&sc, &path, &spectra, &opts, &out, reps, &mut rows);
    }
    std::fs::remove_dir_all(&dir).unwrap();
    let travel = s.run.outputs.iter().find(|o| o.output == "travel").unwrap();
    let stat = |name: &str| travel.get(name).map(|x| x.interval.estimate);
    let burn = (s.burn_in_s / s.run.dt_s).round() as usize;
    let doc = json!({
        "scenario": "data/quarter-car-bump-stops.toml",
        "realizations": r, "samples": s.run.n_samples, "burn": burn, "dt": s.run.dt_s,
        "step_reason": step.reason,
        "sigma_travel_m": stat("sigma_response"),
        "statistics_crc32": statistics_crc(&s),
        "stop_contact_fraction": travel.statistics.iter().find(|x| x.name.contains("fraction")).map(|x| x.interval.estimate),
        "jobs": rows,
    });
    println!("{}", serde_json::to_string_pretty(&doc).unwrap());
}

/// The linear run of the same model and route 1 per parameter point, on one thread.
fn single_thread_jobs(
    sc: &Scenario,
    path: &Path,
    spectra: &Path,
    opts: &RunOptions,
    out: &Path,
    reps: usize,
    rows: &mut serde_json::Map<String, serde_json::Value>,
) {
    // the linear run of the same model, same sizes, the route `auto` takes (ISO 8608 has no shaping filter)
    let lin = parse_scenario(&linear_text(&std::fs::read_to_string(path).unwrap()), path, spectra).unwrap();
    let lin_opts = RunOptions {
        overwrite: true,
        ..opts.clone()
    };
    let p1 = pool(1);
    let (lw, lc, ls) = best(reps, || {
        p1.install(|| lin.simulate(&lin_opts, out, &|_, _| {}).unwrap())
    });
    rows.insert(
        "linear_1_thread".into(),
        json!({"seconds": lw, "cpu_seconds": lc, "route": ls.route.name(), "samples": ls.n_samples}),
    );
    // route 1 per parameter point (what a sweep of the scenario pays per point)
    let model = sc.nonlinear_model().unwrap();
    let exc = sc.excitation.clone();
    let (w1, c1, _) = best(reps.max(5), || {
        p1.install(|| linearize(model, &exc, &Route1Options::default()).unwrap())
    });
    rows.insert("route1_point".into(), json!({"seconds": w1, "cpu_seconds": c1}));
    // the same on two threads (the distinct element rows' variances side by side)
    let p2 = pool(2);
    let (w2, c2, _) = best(reps.max(5), || {
        p2.install(|| linearize(model, &exc, &Route1Options::default()).unwrap())
    });
    rows.insert(
        "route1_point_2_threads".into(),
        json!({"seconds": w2, "cpu_seconds": c2}),
    );
    // the same model on a rational road (an exponential spatial spectrum, which has a shaping filter): the
    // linear run takes its exact route, route 2 its exact flow (one realization at a time, no lockstep)
    let text = std::fs::read_to_string(path)
        .unwrap()
        .replace("\"iso8608-d\"", "\"book-8-45\"");
    let rational = parse_scenario(&text, path, spectra).unwrap();
    let ra = rational.nonlinear_answers().unwrap().unwrap();
    let (ew, ec, es) = best(reps, || p1.install(|| nonlinear_run(&rational, &ra, opts, out)));
    rows.insert(
        "route2_exact_1_thread".into(),
        json!({"seconds": ew, "cpu_seconds": ec, "samples": es.run.n_samples, "route": es.run.route.name()}),
    );
    let lin = parse_scenario(&linear_text(&text), path, spectra).unwrap();
    let (lw, lc, ls) = best(reps, || {
        p1.install(|| lin.simulate(&lin_opts, out, &|_, _| {}).unwrap())
    });
    rows.insert(
        "linear_exact_1_thread".into(),
        json!({"seconds": lw, "cpu_seconds": lc, "route": ls.route.name(), "samples": ls.n_samples}),
    );
}
