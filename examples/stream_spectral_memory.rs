//! Peak resident memory of a statistics-only run of the streamed spectral route (`--route
//! spectral-stream`) for a given number of samples per realization: the ISO 8608 class C quarter car of
//! `data/quarter-car.toml` (suspension travel and tyre force, Δt = 4 ms), 2 realizations (one per thread),
//! written to a temporary run file. Run one size per process, so that VmHWM is that size's peak:
//!
//! `for n in 1e5 1e6 1e7 1e8 1e9; do cargo run --release --example stream_spectral_memory -- $n; done`

use std::path::Path;
use std::time::Instant;
use stochvib::scenario::parse_scenario;
use stochvib::simulate::{planned_memory, run, Route, RunOptions};

fn status_kib(key: &str) -> Option<u64> {
    let s = std::fs::read_to_string("/proc/self/status").ok()?;
    let line = s.lines().find(|l| l.starts_with(key))?;
    line.split_whitespace().nth(1)?.parse().ok()
}

fn main() -> stochvib::Result<()> {
    let samples = std::env::args()
        .nth(1)
        .and_then(|a| a.parse::<f64>().ok())
        .unwrap_or(1e6);
    let path = Path::new("data/quarter-car.toml");
    let text = std::fs::read_to_string(path)
        .map_err(|e| stochvib::Error::invalid("scenario", path.display(), e.to_string()))?
        .replacen(
            "[analysis]\n",
            "[analysis]\noutputs = [\"travel\", \"tyre_force\"]\n",
            1,
        );
    let sc = parse_scenario(&text, path, Path::new("spectra"))?;
    let dt = 0.004;
    let mut opts = RunOptions {
        realizations: 2,
        duration_s: samples * dt,
        dt_s: dt,
        seed: 7,
        ..RunOptions::default()
    };
    opts.route = Route::SpectralStream;
    opts.overwrite = true;
    let input = sc.run_input();
    let before = status_kib("VmHWM:");
    let planned = planned_memory(&input, &opts)?;
    let out = std::env::temp_dir().join(format!("stochvib-stream-memory-{}.h5", std::process::id()));
    let t0 = Instant::now();
    let s = run(&input, &opts, &out, &|_, _| {})?;
    let secs = t0.elapsed().as_secs_f64();
    let _ = std::fs::remove_file(&out);
    let n = s.n_samples as f64;
    println!("samples per realization  {}", s.n_samples);
    println!("record size if held      {:.1} MiB per signal", n * 8.0 / 1048576.0);
    println!("route                    {}: {}", s.route.name(), s.generator);
    println!(
        "planned memory           {:.1} MiB (estimate)",
        planned.bytes as f64 / 1048576.0
    );
    for o in &s.outputs {
        let sg = o.get("sigma").and_then(|x| x.analytic);
        let sd = o.get("sigma_discrete");
        if let (Some(a), Some(d)) = (sg, sd) {
            println!(
                "{:<10} σ est {:.6e} [{:.6e}, {:.6e}], exact σ of the simulated process {:.6e}, analytic {:.6e}",
                o.output,
                d.interval.estimate,
                d.interval.lower,
                d.interval.upper,
                d.analytic.unwrap_or(f64::NAN),
                a
            );
        }
    }
    println!(
        "elapsed                  {secs:.2} s ({:.2} M samples/s per realization, 2 realizations in parallel)",
        n / secs / 1e6
    );
    println!(
        "peak RSS (VmHWM)         {} KiB ({} KiB before planning)",
        status_kib("VmHWM:").map_or("?".into(), |v| v.to_string()),
        before.map_or("?".into(), |v| v.to_string())
    );
    Ok(())
}
