//! In-process timing of the constrained quarter-car optimum of `benches/compare/optimize.py`: everything
//! `stochvib optimize` does after its start-up — read the scenario, parse the parameter, objective and
//! constraint, build the problem, search from 4 starts (`solve`) — repeated REPS times in one process.
//!
//! ```text
//! cargo bench --bench optimize -- SCENARIO [REPS [METHOD]]   (or the built bench binary: BIN SCENARIO [REPS [METHOD]])
//! ```
//!
//! METHOD is `auto` (the default: SLSQP with the analytic gradients here), `slsqp` or `cobyla`. Prints one
//! JSON line: the repetitions, the process CPU time (user + system, `CLOCK_PROCESS_CPUTIME_ID`) and the wall
//! time per repetition in seconds, the damping found, the evaluations and gradient evaluations of one
//! search and the method. The
//! Python side of the comparison times scipy the same way (`time.process_time`, `time.perf_counter`).

use std::path::Path;
use std::time::Instant;
use stochvib::optimize::{solve, Constraint, Goal, Method, Param, Problem, Quantity, Solution, SolveOptions};
use stochvib::scenario::load_scenario;

/// CPU time of this process, s.
fn cpu_seconds() -> f64 {
    let mut t = libc::timespec { tv_sec: 0, tv_nsec: 0 };
    // SAFETY: `t` is a valid, writable timespec and the clock id is a constant the kernel knows.
    let rc = unsafe { libc::clock_gettime(libc::CLOCK_PROCESS_CPUTIME_ID, &mut t) };
    assert_eq!(rc, 0, "clock_gettime(CLOCK_PROCESS_CPUTIME_ID) failed");
    t.tv_sec as f64 + t.tv_nsec as f64 * 1e-9
}

/// One search as the command makes it.
fn one(path: &Path, method: Method) -> Solution {
    let sc = load_scenario(path, Path::new("spectra")).expect("the scenario loads");
    let params = vec![Param::parse("model.suspension_damping=0.2:6 kN*s/m").expect("param")];
    let objective = Quantity::parse("--minimize", "sigma(body_acc)", &sc).expect("objective");
    let travel = Constraint::parse("3sigma(travel) <= 40 mm", &sc).expect("constraint");
    let problem = Problem::new(&sc, params, objective, Goal::Minimize, vec![travel]).expect("problem");
    let opts = SolveOptions {
        method,
        ..SolveOptions::default()
    };
    solve(&problem, &opts).expect("solve")
}

fn main() {
    // `cargo bench` passes `--bench`; the positional arguments are the scenario and the repetitions
    let args: Vec<String> = std::env::args().skip(1).filter(|a| !a.starts_with("--")).collect();
    let Some(path) = args.first() else {
        eprintln!("usage: optimize SCENARIO [REPS]  (the scenario of benches/compare/optimize.py)");
        return;
    };
    let reps: usize = args.get(1).and_then(|r| r.parse().ok()).unwrap_or(20).max(1);
    let method = Method::parse(args.get(2).map_or("auto", String::as_str)).expect("METHOD: auto, slsqp or cobyla");
    let path = Path::new(path);
    let (cpu0, wall0) = (cpu_seconds(), Instant::now());
    let mut last = one(path, method);
    for _ in 1..reps {
        last = one(std::hint::black_box(path), method);
    }
    let cpu = (cpu_seconds() - cpu0) / reps as f64;
    let wall = wall0.elapsed().as_secs_f64() / reps as f64;
    println!(
        "{{\"reps\": {reps}, \"cpu_s\": {cpu:e}, \"wall_s\": {wall:e}, \"c\": {}, \"evaluations\": {}, \
         \"gradient_evaluations\": {}, \"method\": \"{:?}\"}}",
        last.params[0].value, last.evaluations, last.gradient_evaluations, last.method
    );
}
