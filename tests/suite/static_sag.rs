//! Static sag as a quantity: the compression of every spring under the weights it carries, reported by
//! `analyze`, a column of `sweep --verdicts` and a quantity of `optimize`, against closed forms written out
//! here from the catalogue files' parameters (g = 9.80665 m/s²):
//! * quarter car (`data/quarter-car-model.toml`): suspension m_s g/k_s = 300 g/20 000, tyre
//!   (m_s + m_u) g/k_t = 340 g/200 000;
//! * two-stage isolator (`data/isolator-two-stage.toml`): upper stage m₁ g/c₁ = 800 g/80 000, lower stage
//!   (m₁ + m₂) g/c₂ = 1000 g/400 000;
//! * the textbook seat (`data/operator-seat-verdicts.toml`): m_pr g/k with m_pr = (5/7)·80 + 26 kg (the
//!   model's reduced mass, Sukharev (2012) 7.6), at the stiffnesses swept.

use crate::common;
use crate::common::tolerance::{OPTIMUM_ON_CONSTRAINT, ROUNDING};
use std::path::Path;
use stochvib::optimize::{solve, Constraint, Goal, Param, Problem, Quantity, SolveOptions};
use stochvib::scenario::{load_scenario, parse_scenario, Scenario};

const G: f64 = 9.80665;

fn load(file: &str) -> Scenario {
    load_scenario(&common::root().join("data").join(file), &common::root().join("spectra")).unwrap()
}

fn sag(sc: &Scenario, element: &str) -> f64 {
    Quantity::parse("--minimize", &format!("static_sag({element})"), sc)
        .unwrap()
        .value(sc)
        .unwrap()
}

/// The closed forms of the module docs through the quantity and through `analyze`'s report; a kind whose
/// coordinates are not known to be vertical (`mdof`) and an element that is not there are refused by name.
#[test]
fn static_sag_against_closed_forms() {
    let cases: [(&str, &[(&str, f64)]); 3] = [
        (
            "quarter-car-model.toml",
            &[("suspension", 300.0 * G / 20e3), ("tyre", 340.0 * G / 200e3)],
        ),
        (
            "isolator-two-stage.toml",
            &[("upper", 800.0 * G / 80e3), ("lower", 1000.0 * G / 400e3)],
        ),
        (
            "operator-seat-verdicts.toml",
            &[("spring", (5.0 / 7.0 * 80.0 + 26.0) * G / 6500.0)],
        ),
    ];
    for (file, springs) in cases {
        let sc = load(file);
        let report = stochvib::study::analysis_report(&sc).unwrap();
        let listed = report
            .static_sag
            .as_ref()
            .unwrap_or_else(|| panic!("{file}: no static sag reported"));
        assert_eq!(listed.len(), springs.len(), "{file}: {listed:?}");
        for (element, want) in springs {
            let got = sag(&sc, element);
            assert!(common::rel(got, *want) < ROUNDING, "{file} {element}: {got} vs {want}");
            let shown = listed.iter().find(|s| s.element == *element).unwrap().deflection_m;
            assert_eq!(shown.to_bits(), got.to_bits());
        }
        assert!(report.to_string().contains("static compression under gravity"));
    }
    let qc = load("quarter-car-model.toml");
    let e = Quantity::parse("--minimize", "static_sag(spring)", &qc)
        .unwrap_err()
        .to_string();
    assert!(e.contains("suspension, tyre"), "{e}");
    let text = std::fs::read_to_string(common::root().join("data/quarter-car.toml")).unwrap();
    let generic = parse_scenario(
        &text,
        Path::new("data/quarter-car.toml"),
        &common::root().join("spectra"),
    )
    .unwrap();
    assert_eq!(generic.kind, "mdof");
    let e = Quantity::parse("--minimize", "static_sag(suspension)", &generic)
        .unwrap_err()
        .to_string();
    assert!(e.contains("vertical"), "{e}");
}

/// The seat's sag is a column of `sweep --verdicts` (m_pr g/k at k = 5000 and 8000 N/m), and a constraint
/// of `optimize`: the quarter car's body acceleration falls as the suspension softens (σ²_acc grows with
/// k_s for a road of white velocity; the classical closed form), so with `static_sag(suspension) <= 10 cm`
/// the optimum is where the constraint is active, k_s = m_s g/0.1 m = 29 419.95 N/m.
#[test]
fn static_sag_in_sweeps_and_as_an_optimize_constraint() {
    use stochvib::study::{Sweep, SweepMode, SweepParam, SweepSpec};
    let seat = load("operator-seat-verdicts.toml");
    let p = SweepParam::parse("model.stiffness=5000 N/m,8000 N/m").unwrap();
    let sweep = Sweep::new(&seat, SweepSpec::new(vec![p], SweepMode::Grid).unwrap()).unwrap();
    let t = stochvib::study::sweep_verdicts::sweep_verdicts(&sweep).unwrap();
    let col = t.columns.iter().position(|c| c == "static_sag(spring) [m]").unwrap() - 1;
    let m_pr = 5.0 / 7.0 * 80.0 + 26.0;
    for (row, k) in t.rows.iter().zip([5000.0, 8000.0]) {
        let got = row.values[col].unwrap();
        assert!(common::rel(got, m_pr * G / k) < ROUNDING, "{k}: {got}");
    }
    let qc = load("quarter-car-model.toml");
    let params = vec![Param::parse("model.suspension_stiffness=10:60 kN/m").unwrap()];
    let objective = Quantity::parse("--minimize", "sigma(body_acc)", &qc).unwrap();
    let limit = Constraint::parse("static_sag(suspension) <= 10 cm", &qc).unwrap();
    let problem = Problem::new(&qc, params, objective, Goal::Minimize, vec![limit]).unwrap();
    let answer = solve(&problem, &SolveOptions::default()).unwrap();
    assert!(answer.feasible);
    let k = answer.params[0].value;
    let want = 300.0 * G / 0.1;
    assert!(common::rel(k, want) < OPTIMUM_ON_CONSTRAINT, "k* = {k} vs {want}");
    assert!(answer.constraints[0].active, "{answer}");
}
