//! `stochvib transient` with several independent `[[input]]` sources: a rational road under a speed profile
//! and a force on the body, their shaping filters block-diagonal ahead of the quarter car (the exact route),
//! against the one-source routes (superposition), the stationary analysis and Monte Carlo; and the
//! refusals where no finite-dimensional route exists.

use crate::common::tolerance::{ADAPTIVE_ROUTE, QUADRATURE};
use crate::common::{quarter_car_scenario, rel, root, scratch_dir};
use std::path::Path;
use stochvib::response::analyze_output;
use stochvib::scenario::{parse_scenario, Scenario};
use stochvib::store::Compression;
use stochvib::study::transient_mc::{compare_sigma, simulate_transient, TransientMcOptions};
use stochvib::study::transient_run::{exact_solution, transient_setup};
use stochvib::transient::TransientSolution;

const ROAD: &str = r#"{ kind = "exponential", domain = "spatial", variance = "1 cm^2", alpha = "0.2 1/m" }"#;
const FORCE: &str = r#"{ kind = "exponential", unit = "N", variance = "1e4 N^2", alpha = "3 1/s" }"#;
const PROFILE: &str = "{ from = \"5 m/s\", to = \"15 m/s\", acceleration = \"1 m/s^2\", start = \"1 s\" }";
const WINDOW: &str = "\n[transient]\nduration = \"8 s\"\nstep = \"0.1 s\"\nstart = \"stationary\"\n";

fn scenario(text: &str) -> Scenario {
    parse_scenario(text, Path::new("t.toml"), &root().join("spectra")).unwrap()
}

fn exact(sc: &Scenario) -> TransientSolution {
    exact_solution(sc, &transient_setup(sc).unwrap()).unwrap()
}

/// The quarter car with a road (`speed`: the road table's speed key, e.g. `speed_profile = {…}`) on input 0
/// and a force on the body (input 1), as two `[[input]]` tables; means 1 cm and 100 N.
fn road_and_force(speed: &str) -> String {
    quarter_car_scenario()
        .force()
        .then(&format!(
            "\n[[input]]\nname = \"road\"\nspectrum = {ROAD}\n{speed}\nmean = \"1 cm\"\ndrives = [0]\n\n\
             [[input]]\nname = \"load\"\nspectrum = {FORCE}\nmean = \"100 N\"\ndrives = [1]\n{WINDOW}"
        ))
        .text()
}

/// Independent sources add their covariances, at every time of a manoeuvre too: the quarter car accelerating
/// from 5 to 15 m/s on a rational road (its spatial filter under v(t)) and loaded by a force of exponential
/// correlation on the body, both `[[input]]` tables at once, has σ²(t) = σ²_road(t) + σ²_force(t) at each of
/// the 81 times. The oracles are the one-source scenarios of the single `[input]` form (the road with its
/// `[input.speed_profile]`; the force with the tyre on the ground), each by the one-input route already
/// checked against closed forms (`transient_exact`): other code than the block-diagonal filters under test.
/// Each route is accurate to its error control (ADAPTIVE_ROUTE). The means are the statics (closed form):
/// body = μ_r + F(1/k + 1/k_t), travel = F/k at every time (a stationary start, constant means).
#[test]
fn a_road_under_a_speed_profile_and_a_force_add_their_variances_at_every_time() {
    let both = scenario(&road_and_force(&format!("speed_profile = {PROFILE}")));
    let road_only = scenario(
        &quarter_car_scenario()
            .then(&format!(
                "\n[input]\nspectrum = {ROAD}\nspeed_profile = {PROFILE}\n{WINDOW}"
            ))
            .text(),
    );
    let force_only = scenario(
        &quarter_car_scenario()
            .force()
            .tyre_on_ground()
            .then(&format!("\n[input]\nspectrum = {FORCE}\n{WINDOW}"))
            .text(),
    );
    let (sb, sr, sf) = (exact(&both), exact(&road_only), exact(&force_only));
    assert_eq!(sb.times.len(), 81);
    let (k, kt, f, mu) = (20e3, 200e3, 100.0, 0.01);
    for (i, name, mean) in [(0, "body", mu + f * (1.0 / k + 1.0 / kt)), (1, "travel", f / k)] {
        assert_eq!(sb.outputs[i].name, name);
        for j in 0..sb.times.len() {
            let v = sb.outputs[i].sigma[j].powi(2);
            let oracle = sr.outputs[i].sigma[j].powi(2) + sf.outputs[i].sigma[j].powi(2);
            assert!(
                rel(v, oracle) < ADAPTIVE_ROUTE,
                "{name} t = {}: {v:e} vs {oracle:e}",
                sb.times[j]
            );
            assert!(rel(sb.outputs[i].mean[j], mean) < ADAPTIVE_ROUTE, "{name} mean");
        }
    }
    // the road's variance grows with the speed: the sum is not constant
    assert!(sb.outputs[1].sigma[80] > 1.1 * sb.outputs[1].sigma[0]);
}

/// At a constant 20 m/s the exact route of the two sources is their stationary answer at every time: the
/// variances of the stationary analysis of the same scenario (the `[[input]]` sources' cross-spectral
/// matrix, integrated by the crate's stationary route, not the transient code) within ADAPTIVE_ROUTE.
#[test]
fn two_sources_at_constant_speed_are_the_stationary_answer() {
    let sc = scenario(&road_and_force("speed = \"20 m/s\""));
    let sol = exact(&sc);
    let sys = sc.model.system.as_ref();
    for i in 0..2 {
        let st = analyze_output(sys, &sc.excitation, i).unwrap();
        let var = st.variance.unwrap();
        for j in [0, 40, 80] {
            assert!(
                rel(sol.outputs[i].sigma[j].powi(2), var) < ADAPTIVE_ROUTE.max(QUADRATURE),
                "{} t = {}",
                sol.outputs[i].name,
                sol.times[j]
            );
        }
    }
}

/// Monte Carlo of the two sources (the exact transitions of the frozen block-diagonal form, 300
/// realizations, seed 5) against the exact σ(t) at the 81 times: for Gaussian responses
/// (R − 1)s²/σ² ~ χ²_{R−1}, and `compare_sigma` at α = 5·10⁻⁷ per output (Bonferroni over the times) fails
/// with probability ≤ 10⁻⁶ for the two outputs when both routes are right.
#[test]
fn two_sources_monte_carlo_against_the_exact_route() {
    let sc = scenario(&road_and_force(&format!("speed_profile = {PROFILE}")));
    let setup = transient_setup(&sc).unwrap();
    let sol = exact_solution(&sc, &setup).unwrap();
    let dir = scratch_dir("transient-sources", "mc");
    let out = dir.join("two.h5");
    let opts = TransientMcOptions {
        realizations: 300,
        substeps: 2,
        seed: 5,
        shard_size: 100,
        confidence: 0.95,
        store_raw: false,
        compression: Compression::default(),
        part: None,
        overwrite: false,
        max_hours: stochvib::simulate::resources::DEFAULT_MAX_HOURS,
    };
    simulate_transient(&sc, &setup, &sol, &opts, &out, &|_, _| {}).unwrap();
    let series = stochvib::transient::monte_carlo::read_transient_run(&out).unwrap().1;
    assert_eq!(series.outputs.len(), 2);
    for c in compare_sigma(&series, 5e-7).unwrap() {
        assert!(c.outside.is_empty(), "{}: {}", c.output, c.verdict());
    }
    let _ = std::fs::remove_dir_all(&dir);
}

/// What has no finite-dimensional exact route is refused with the reason and what to use instead: two
/// tables giving a speed profile (one machine, one profile: file, key, reason); a road of waviness 2 without
/// a band beside another source; a non-rational road beside another source (no evolutionary route for
/// several sources either).
#[test]
fn several_sources_refusals() {
    let twice = road_and_force(&format!("speed_profile = {PROFILE}"))
        .replace("drives = [1]\n", &format!("drives = [1]\nspeed_profile = {PROFILE}\n"));
    let e = parse_scenario(&twice, Path::new("t.toml"), &root().join("spectra"))
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("input[1]") && e.contains("speed_profile") && e.contains("one speed profile"),
        "{e}"
    );
    let w2 = scenario(&road_and_force(&format!("speed_profile = {PROFILE}")).replace(
        ROAD,
        r#"{ kind = "iso8608", class = "C", bound = "mean", unbounded = true }"#,
    ));
    let e = transient_setup(&w2).unwrap_err().to_string();
    assert!(e.contains("w = 2") && e.contains("Monte Carlo"), "{e}");
    let iso = scenario(&road_and_force(&format!("speed_profile = {PROFILE}")).replace(ROAD, r#""iso8608-c""#));
    let e = stochvib::study::transient_run::evolutionary_setup(&iso)
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("several [[input]] sources") && e.contains("not available"),
        "{e}"
    );
}
