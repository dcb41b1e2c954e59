//! Rust side of `benches/compare/fatigue.py`: writes the seeded benchmark signal, times the streaming
//! rainflow count and the Dirlik life on the same inputs as the Python packages, and prints JSON.
//!
//! ```text
//! cargo run --release --example fatigue_compare -- --n 100000000 --reps 3 --dir /tmp/fatigue
//! ```
//! Files written in `--dir`: `signal.f64` (the resonant record, raw little-endian f64) and
//! `cycles_prefix.f64` (range, mean, count of every cycle of the first `--check` samples, row-major).

#[path = "../benches/common/fatigue_signal.rs"]
mod fatigue_signal;

use fatigue_signal::*;
use std::io::Write;
use std::path::PathBuf;
use std::time::Instant;
use stochvib::fatigue::{
    rainflow, Dirlik, OneSidedHzMoments, RainflowCounter, SnCurve, SpectralMethod, SpectralMoments,
};

fn arg<T: std::str::FromStr>(args: &[String], name: &str, default: T) -> T {
    args.iter()
        .position(|a| a == name)
        .and_then(|i| args.get(i + 1))
        .and_then(|v| v.parse().ok())
        .unwrap_or(default)
}

fn write_f64(path: &PathBuf, v: &[f64]) -> std::io::Result<()> {
    let mut f = std::io::BufWriter::new(std::fs::File::create(path)?);
    for x in v {
        f.write_all(&x.to_le_bytes())?;
    }
    f.flush()
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let args: Vec<String> = std::env::args().collect();
    let n: usize = arg(&args, "--n", N_RAINFLOW);
    let reps: usize = arg(&args, "--reps", 3);
    let check: usize = arg(&args, "--check", 1_000_000);
    let dir: PathBuf = arg(&args, "--dir", std::env::temp_dir().join("stochvib-fatigue"));
    std::fs::create_dir_all(&dir)?;

    let x = resonant_signal(n);
    write_f64(&dir.join("signal.f64"), &x)?;
    let prefix: Vec<f64> = rainflow(&x[..check.min(n)])?
        .iter()
        .flat_map(|c| [c.range, c.mean, c.count])
        .collect();
    write_f64(&dir.join("cycles_prefix.f64"), &prefix)?;

    // Rainflow + streaming Miner sum (k = 3), chunks of 1 Mi samples; best of `reps`.
    let mut best = f64::INFINITY;
    let (mut cycles, mut damage) = (0.0, 0.0);
    for _ in 0..reps {
        let t = Instant::now();
        let mut rc = RainflowCounter::new();
        let (mut d, mut c) = (0.0, 0.0);
        for chunk in x.chunks(1 << 20) {
            rc.push(chunk, |cy| {
                d += cy.count * cy.amplitude * cy.amplitude * cy.amplitude;
                c += cy.count;
            })?;
        }
        rc.finish(|cy| {
            d += cy.count * cy.amplitude * cy.amplitude * cy.amplitude;
            c += cy.count;
        });
        best = best.min(t.elapsed().as_secs_f64());
        cycles = c;
        damage = d;
    }

    // Dirlik life from the density (moments by adaptive quadrature) and from given moments.
    let sn = SnCurve {
        k: SN_K,
        c: SN_C,
        endurance_limit: None,
    }
    .build()?;
    let mut best_density = f64::INFINITY;
    let mut life = 0.0;
    let mut m = OneSidedHzMoments {
        m0: 1.0,
        m1: 1.0,
        m2: 1.0,
        m4: 1.0,
    }
    .build()?;
    for _ in 0..200 {
        let t = Instant::now();
        m = SpectralMoments::from_one_sided_hz(sdof_density, 0.0, SDOF_F_MAX, &[SDOF_FN])?;
        life = Dirlik.life(&m, &sn)?;
        best_density = best_density.min(t.elapsed().as_secs_f64());
    }
    let mut best_moments = f64::INFINITY;
    for _ in 0..200 {
        let t = Instant::now();
        let mut acc = 0.0;
        for _ in 0..1000 {
            acc += Dirlik.life(std::hint::black_box(&m), &sn)?;
        }
        std::hint::black_box(acc);
        best_moments = best_moments.min(t.elapsed().as_secs_f64() / 1000.0);
    }
    // Dirlik life from the density tabulated on the grids FLife is given (0.1 Hz and 0.01 Hz).
    let mut table = Vec::new();
    for step in [0.1, 0.01] {
        let npts = (SDOF_F_MAX / step).round() as usize + 1;
        let f: Vec<f64> = (0..npts).map(|i| i as f64 * SDOF_F_MAX / (npts - 1) as f64).collect();
        let g: Vec<f64> = f.iter().map(|&x| sdof_density(x)).collect();
        let mut best_table = f64::INFINITY;
        let mut life_table = 0.0;
        for _ in 0..50 {
            let t = Instant::now();
            let mt = SpectralMoments::from_tabulated_one_sided_hz(&f, &g, false)?;
            life_table = Dirlik.life(&mt, &sn)?;
            best_table = best_table.min(t.elapsed().as_secs_f64());
        }
        table.push(format!("\"{step}\": [{best_table:.6e}, {life_table:.17e}]"));
    }
    println!(
        "{{\"n\": {n}, \"rainflow_s\": {best:.6e}, \"cycles\": {cycles}, \"damage_k3\": {damage:.17e}, \
         \"dirlik_density_s\": {best_density:.6e}, \"dirlik_moments_s\": {best_moments:.6e}, \"dirlik_life_s\": {life:.17e}, \
         \"dirlik_table\": {{{}}}, \
         \"m0\": {:.17e}, \"m1\": {:.17e}, \"m2\": {:.17e}, \"m4\": {:.17e}, \"dir\": \"{}\"}}",
        table.join(", "),
        m.m0(),
        m.m1(),
        m.m2(),
        m.m4(),
        dir.display()
    );
    Ok(())
}
