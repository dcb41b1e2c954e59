//! A quarter car on ISO 8608 roads: σ and 3σ bounds of the body acceleration, the suspension travel and
//! the dynamic tyre force for every road class at one speed, then a seeded Monte Carlo check of one case.
//!
//! ```sh
//! cargo run --release --example quarter_car [speed_m_per_s]
//! ```

use std::sync::Arc;
use stochvib::prelude::*;

fn main() -> Result<()> {
    let speed: f64 = std::env::args().nth(1).and_then(|a| a.parse().ok()).unwrap_or(20.0);
    // a passenger-car corner: body 300 kg, wheel 40 kg, spring 20 kN/m, damper 1.5 kN s/m, tyre 200 kN/m
    let car = QuarterCar {
        sprung_mass: 300.0,
        unsprung_mass: 40.0,
        suspension_stiffness: 20e3,
        suspension_damping: 1.5e3,
        tyre_stiffness: 200e3,
        tyre_damping: 0.0,
    }
    .build()?;
    let sys = car.system()?;
    let names = ["body_acc", "travel", "tyre_force"];
    let outputs = names.iter().map(|n| sys.output_index(n)).collect::<Result<Vec<_>>>()?;
    println!("quarter car at {speed} m/s on ISO 8608 roads (geometric mean of each class, 0.011-2.83 cycles/m)");
    println!(
        "{:<6} {:>22} {:>18} {:>20}",
        "class", "σ body_acc [m/s^2]", "σ travel [m]", "σ tyre_force [N]"
    );
    for class in IsoClass::ALL {
        let road = Excitation::road(Arc::new(PowerLaw::iso_class(class)?), speed, &[0.0])?;
        let sigmas = outputs
            .iter()
            .map(|&i| Ok(analyze_output(&sys, &road, i)?.sigma.unwrap_or(f64::INFINITY)))
            .collect::<Result<Vec<_>>>()?;
        println!(
            "{:<6} {:>22.4} {:>18.5} {:>20.1}",
            class.to_string(),
            sigmas[0],
            sigmas[1],
            sigmas[2]
        );
    }

    // class C in detail: every variance method, the 3σ bounds, and 200 realizations of 20 s
    let road = Excitation::road(Arc::new(PowerLaw::iso_class(IsoClass::C)?), speed, &[0.0])?;
    println!("\nclass C:");
    for &i in &outputs {
        let st = analyze_output(&sys, &road, i)?;
        let (lo, hi) = st.bounds(3.0).unwrap_or((f64::NAN, f64::NAN));
        println!(
            "  {:<11} σ = {:.5e} {u}, 3σ bounds [{lo:.4e}, {hi:.4e}] {u}",
            st.name,
            st.sigma.unwrap_or(f64::NAN),
            u = st.unit
        );
    }
    let input = RunInput::new(
        &sys,
        &road,
        outputs,
        vec![Signal::new("road", "m")],
        "examples/quarter_car.rs",
    );
    let step = suggest_step(&input)?;
    let file = std::env::temp_dir().join(format!("stochvib-quarter-car-{}.h5", std::process::id()));
    let _ = std::fs::remove_file(&file);
    let opts = RunOptions {
        realizations: 200,
        duration_s: 20.0,
        dt_s: step.dt_s,
        seed: 2026,
        ..RunOptions::default()
    };
    let mc = run(&input, &opts, &file, &|_, _| {})?;
    println!(
        "  Monte Carlo: {} realizations x {} samples, Δt = {:.4e} s ({} route)",
        mc.n_realizations,
        mc.n_samples,
        mc.dt_s,
        mc.route.name()
    );
    for o in &mc.outputs {
        let (s, d) = (o.get("sigma").unwrap(), o.get("sigma_discrete").unwrap());
        println!(
            "  {:<11} MC σ = {:.5e} in [{:.5e}, {:.5e}] (95 %); σ of the simulated grid process {:.5e}, covered: {}",
            o.output,
            s.interval.estimate,
            s.interval.lower,
            s.interval.upper,
            d.analytic.unwrap_or(f64::NAN),
            d.covers == Some(true)
        );
    }
    println!(
        "  run file {} (read it with h5py or `stochvib inspect`)",
        file.display()
    );
    Ok(())
}
