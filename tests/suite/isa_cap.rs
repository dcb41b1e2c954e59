//! The instruction-set cap `STOCHVIB_ISA`: a misspelt value is refused before any work, naming the
//! variable, the value and the names it takes; and a cap never changes a number — the transient Monte
//! Carlo (whose lockstep loop and output maps run through the dispatched kernels) prints the same text at
//! every cap this CPU has. Expected values: the names the user typed, and the run's own uncapped output
//! (the claim is equality across caps, not a value).

use crate::common::{cli_bin, root, scratch_dir};
use std::process::{Command, Output};
use stochvib::linalg::vmath::{Isa, ISA_ENV};

fn run(isa: &str, args: &[&str]) -> Output {
    Command::new(cli_bin())
        .current_dir(root())
        .env(ISA_ENV, isa)
        .env("STOCHVIB_SPECTRA", root().join("spectra"))
        .args(args)
        .output()
        .expect("stochvib runs")
}

#[test]
fn a_misspelt_cap_is_refused_with_its_name_and_value() {
    let o = run("avx-512", &["models"]);
    let e = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(1), "{e}");
    assert!(o.stdout.is_empty(), "nothing printed before the refusal");
    assert!(
        e.contains(ISA_ENV) && e.contains("avx-512") && e.contains("avx2") && e.contains("baseline"),
        "{e}"
    );
    assert!(!e.contains("panicked"), "{e}");
}

#[test]
fn every_cap_prints_the_same_transient_monte_carlo() {
    let d = scratch_dir("isa_cap", "transient");
    let scenario = root().join("data/quarter-car-accelerating.toml");
    let mut outputs = Vec::new();
    for isa in ["avx512", "avx2", "baseline"] {
        let out = d.join(format!("{isa}.h5"));
        let o = run(
            isa,
            &[
                "transient",
                scenario.to_str().unwrap(),
                "--monte-carlo",
                "24",
                "-o",
                out.to_str().unwrap(),
                "--json",
            ],
        );
        assert!(o.status.success(), "{isa}: {}", String::from_utf8_lossy(&o.stderr));
        // the run file's name is the only difference the cap may make
        let text = String::from_utf8(o.stdout)
            .unwrap()
            .replace(&format!("{isa}.h5"), "run.h5");
        outputs.push((isa, Isa::widest_up_to(Isa::parse(isa).unwrap()), text));
    }
    let (_, _, first) = &outputs[0];
    for (isa, used, text) in &outputs[1..] {
        assert!(text == first, "{isa} (runs {used:?}) printed another report");
    }
    let _ = std::fs::remove_dir_all(&d);
}
