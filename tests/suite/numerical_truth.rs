//! Every finite answer, every time: delayed inputs give their variance and moments exactly, the
//! integral table never prints a wrong number, every kind of non-answer says which it is, units of derived
//! outputs follow from the coordinates, and Welch estimates are compared with their own expectation.

use crate::common;
use crate::common::SpawnSerial;
use common::root;
use common::tolerance::{FACTORISATION, ROUNDING};
use std::path::Path;
use stochvib::response::{analyze_output, Outcome, VarianceMethod, TABLE_AGREEMENT};
use stochvib::scenario::{parse_scenario, Scenario};
use stochvib::simulate::{Route, RunOptions};

fn scenario(text: &str) -> Scenario {
    parse_scenario(text, Path::new("case.toml"), &root().join("spectra")).unwrap()
}

/// A half car (bounce z, pitch φ; wheels at a = 1.2 m ahead and b = 1.4 m behind the centre of mass: 2.6 m
/// apart) on the textbook's spatial type-1 road (8.45) at 11 m/s: the rear wheel feels the front's profile
/// 2.6/11 s later. Outputs: body velocity ż, pitch φ, and the point z − 1.2 φ … all finite.
fn half_car(extra_outputs: &str) -> String {
    format!(
        r#"
[model]
kind = "mdof"
base_inputs = 2
positions = ["0 m", "2.6 m"]
coordinates = [{{ name = "z", unit = "m", mass = "1200 kg" }}, {{ name = "phi", unit = "rad", mass = "1600 kg m^2" }}]
[[model.element]]
name = "front"
point = [1, 1.2]
to = "base 0"
stiffness = "40 kN/m"
damping = "3 kN*s/m"
[[model.element]]
name = "rear"
point = [1, -1.4]
to = "base 1"
stiffness = "45 kN/m"
damping = "3.2 kN*s/m"
[[model.output]]
name = "body_vel"
quantity = "velocity"
point = [1, 0]
[[model.output]]
name = "pitch"
quantity = "displacement"
point = [0, 1]
[[model.output]]
name = "seat"
quantity = "displacement"
point = [1, -1.2]
{extra_outputs}
[input]
spectrum = "book-8-45"
speed = "11 m/s"
"#
    )
}

fn method(st: &stochvib::response::ResponseStatistics, m: VarianceMethod) -> &Outcome {
    &st.methods.iter().find(|v| v.method == m).unwrap().outcome
}

/// Before: "sigma infinite/undefined: quadrature did not converge" (the density decays like ω⁻² with a
/// cos ωΔ tail). Now the exact covariance of the delayed augmented system and the Fourier-weighted
/// quadrature both give the variance, agreeing to FACTORISATION; λ₂ (and so ν₀⁺) is finite for the
/// displacements and reported; the velocity's λ₂ is infinite and says so.
#[test]
fn delayed_half_car_variances_and_moments_are_finite_and_agree() {
    let sc = scenario(&half_car(""));
    for i in 0..3 {
        let st = analyze_output(sc.model.system.as_ref(), &sc.excitation, i).unwrap();
        let exact = method(&st, VarianceMethod::LyapunovDelays)
            .value()
            .unwrap_or_else(|| panic!("{st:?}"));
        let quad = method(&st, VarianceMethod::Quadrature).value().unwrap();
        assert!(
            (exact - quad).abs() <= FACTORISATION * exact,
            "{}: {exact} vs {quad}",
            st.name
        );
        assert_eq!(st.variance, Some(exact));
        assert!(matches!(
            method(&st, VarianceMethod::Lyapunov),
            Outcome::NotApplicable { .. }
        ));
        if st.name == "body_vel" {
            // λ₂ of a velocity under a type-1 road (S ~ ω⁻²) through a damper: the acceleration is white
            assert!(st.lambda2_outcome.is_divergent(), "{:?}", st.lambda2_outcome);
            assert!(st.rate_note().unwrap().contains("infinite"));
        } else {
            let l2 = st
                .lambda2
                .unwrap_or_else(|| panic!("{}: {:?}", st.name, st.lambda2_outcome));
            assert!(l2 > 0.0 && st.zero_upcrossing_rate.is_some());
        }
    }
    // the report shows the row and a finite sigma for every output
    let r = stochvib::study::analysis_report(&sc).unwrap();
    let text = format!("{r}");
    assert!(
        text.contains("lyapunov (delays)") && !text.contains("sigma         infinite"),
        "{text}"
    );
}

/// The same system by Monte Carlo (spectral route; Δt = 2.6/11/20 makes the wheelbase delay 20 steps): the
/// σ intervals cover the exact σ of the simulated discretised process, which is within the grid bias of the
/// analytic σ. Per-output false-failure probability 1e-8 (interval confidence 1 − 1e-8), 3 outputs.
#[test]
fn delayed_half_car_monte_carlo_agrees() {
    let sc = scenario(&half_car(""));
    let dt = 2.6 / 11.0 / 20.0;
    let mut o = RunOptions {
        realizations: 400,
        duration_s: 60.0,
        dt_s: dt,
        seed: 15,
        ..RunOptions::default()
    };
    o.confidence = 1.0 - 1e-8;
    let out = crate::common::scratch_kept("truth", "mc").join("run.h5");
    let _ = std::fs::remove_file(&out);
    let s = sc.simulate(&o, &out, &|_, _| {}).unwrap();
    std::fs::remove_file(&out).unwrap();
    assert_eq!(s.route, Route::Spectral);
    for o in &s.outputs {
        let (sigma, disc) = (o.get("sigma").unwrap(), o.get("sigma_discrete").unwrap());
        let (sa, sd) = (sigma.analytic.unwrap(), disc.analytic.unwrap());
        assert!(
            sigma.interval.covers(sd),
            "{}: {:?} vs discrete {sd}",
            o.output,
            sigma.interval
        );
        // the grid (Δω = 2π/60 s, Nyquist 42 Hz) resolves the road's band: a few per cent at most
        assert!(
            (sd - sa).abs() < 0.05 * sa,
            "{}: discrete {sd} vs analytic {sa}",
            o.output
        );
    }
}

/// A point that weights a length and an angle (z − 1.2φ: the 1.2 is a lever arm in m/rad) is in metres,
/// not "mixed"; a pure angle in radians; its velocity in m/s.
#[test]
fn units_of_derived_outputs_follow_from_the_coordinates() {
    let sc = scenario(&half_car(
        "[[model.output]]\nname = \"tilt_rate\"\nquantity = \"velocity\"\npoint = [0, 2]\n[[model.output]]\nname = \
         \"front_travel\"\nquantity = \"deflection\"\nelement = \"front\"\n",
    ));
    let units: Vec<(&str, &str)> = sc
        .model
        .system
        .outputs()
        .iter()
        .map(|o| (o.name.as_str(), o.unit.as_str()))
        .collect();
    assert_eq!(
        units,
        [
            ("body_vel", "m/s"),
            ("pitch", "rad"),
            ("seat", "m"),
            ("tilt_rate", "rad/s"),
            ("front_travel", "m")
        ]
    );
}

/// The stiff chain of the report (masses 0.05, 5 and 2000 kg): the integral table printed 1.12e42 for a
/// variance of 2.49e4. Over a seeded family of stiff chains (mass ratios up to 10⁶, stiffness ratios up to
/// 10³), the table is either within TABLE_AGREEMENT of the Lyapunov value or reported unreliable or not
/// applicable — never a bare wrong number.
#[test]
fn the_integral_table_never_prints_a_wrong_number() {
    use rand::SeedableRng;
    let mut rng = rand::rngs::Xoshiro256PlusPlus::seed_from_u64(151);
    let mut values = 0;
    for case in 0..60 {
        let text = common::stiff_chain_text(&mut rng);
        let sc = scenario(&text);
        for i in 0..2 {
            let st = analyze_output(sc.model.system.as_ref(), &sc.excitation, i).unwrap();
            let lyap = method(&st, VarianceMethod::Lyapunov).value().unwrap();
            match method(&st, VarianceMethod::IntegralTable) {
                Outcome::Value { value, .. } => {
                    values += 1;
                    assert!(
                        (value - lyap).abs() <= TABLE_AGREEMENT * lyap,
                        "case {case}, output {i}: table {value} vs Lyapunov {lyap}"
                    );
                }
                Outcome::Unreliable { reason, .. } | Outcome::NotApplicable { reason } => assert!(!reason.is_empty()),
                other => panic!("case {case}: {other:?}"),
            }
        }
    }
    assert!(values > 60, "the table answered in only {values} of 120 cases");
}

/// Every message class, in text and JSON: infinite (with the diagnosis), not converged (with the estimate
/// and the options that exist to raise the effort), not applicable (with the reason), unreliable.
#[test]
fn every_kind_of_non_answer_says_which_it_is() {
    // infinite: a damped base-excited mass's acceleration under a type-1 input (S ~ ω⁻², |H|² ~ ω²)
    let text = r#"
[model]
kind = "isolator-single"
mass = "100 kg"
stiffness = "10 kN/m"
damping_ratio = 0.2
[input]
spectrum = "type1"
"#;
    let sc = scenario(text);
    let acc = sc.model.system.output_index("x_acc").unwrap();
    let st = analyze_output(sc.model.system.as_ref(), &sc.excitation, acc).unwrap();
    assert!(st.variance_outcome.is_divergent() && st.variance_outcome.describe().starts_with("infinite: "));
    let json = serde_json::to_value(&st).unwrap();
    assert_eq!(json["variance_outcome"]["status"], "divergent");
    // not converged: the quadrature of a non-rational input with 3 subintervals allowed
    let sc = scenario(&std::fs::read_to_string(root().join("data/quarter-car.toml")).unwrap());
    let effort = stochvib::quad_oscillatory::OscillatoryOptions {
        max_subintervals: 3,
        ..Default::default()
    };
    let st = stochvib::response::analyze_output_with(sc.model.system.as_ref(), &sc.excitation, 0, &effort).unwrap();
    match &st.variance_outcome {
        Outcome::NotConverged { reason, estimate, .. } => {
            assert!(estimate.is_finite());
            assert!(
                reason.contains("max_subintervals (now 3)") && reason.contains("--max-subintervals"),
                "{reason}"
            );
        }
        other => panic!("{other:?}"),
    }
    let json = serde_json::to_value(&st).unwrap();
    assert_eq!(json["variance_outcome"]["status"], "not-converged");
    // the CLI flag exists and is honoured
    let o = std::process::Command::new(crate::common::cli_bin())
        .current_dir(root())
        .args(["analyze", "data/quarter-car.toml", "--max-subintervals", "3"])
        .output_serial()
        .unwrap();
    let out = String::from_utf8_lossy(&o.stdout);
    assert!(o.status.success() && out.contains("not converged"), "{out}");
    // not applicable: the integral table with delayed inputs
    let sc = scenario(&half_car(""));
    let st = analyze_output(sc.model.system.as_ref(), &sc.excitation, 1).unwrap();
    assert!(matches!(
        method(&st, VarianceMethod::IntegralTable),
        Outcome::NotApplicable { .. }
    ));
    // unreliable: the outcome of an Error::Inaccurate, in text and JSON
    let o = Outcome::from_error(
        &stochvib::Error::Inaccurate {
            method: "integral table".into(),
            value: 1.12e42,
            reason: "ill-conditioned".into(),
        },
        &Default::default(),
    );
    assert!(o.value().is_none() && o.describe().starts_with("unreliable (1.120000e42)"));
    assert_eq!(serde_json::to_value(&o).unwrap()["status"], "unreliable");
}

/// ISO 8608 defines no lower limit for class A and no upper limit for class H.
#[test]
fn iso_class_bounds_exist_only_where_the_standard_defines_them() {
    use stochvib::spectrum::{IsoBound, IsoClass};
    assert!(IsoClass::A.g0(IsoBound::Lower).is_err());
    assert!(IsoClass::H.g0(IsoBound::Upper).is_err());
    // ISO 8608:2016 Table 3: class B from 32 to 128 (×10⁻⁶ m³), class H from 131072
    assert_eq!(IsoClass::B.g0(IsoBound::Lower).unwrap(), 32e-6);
    assert_eq!(IsoClass::B.g0(IsoBound::Upper).unwrap(), 128e-6);
    assert_eq!(IsoClass::H.g0(IsoBound::Lower).unwrap(), 131072e-6);
}

/// `stochvib spectrum NAME --omega …` / `--frequency …`: the density at the user's points. Type 1
/// (D = 1 cm², α = 2 1/s): S(ω) = αD/(π(α² + ω²)); one-sided cyclic G(f) = 4π S(2πf).
#[test]
fn spectrum_density_at_chosen_points() {
    let run = |args: &[&str]| -> serde_json::Value {
        let o = std::process::Command::new(crate::common::cli_bin())
            .current_dir(root())
            .args(args)
            .output_serial()
            .unwrap();
        assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
        serde_json::from_slice(&o.stdout).unwrap()
    };
    let (d, a) = (1e-4, 2.0);
    let s = |w: f64| a * d / (std::f64::consts::PI * (a * a + w * w));
    let j = run(&["spectrum", "type1", "--omega", "0,1,5", "--json"]);
    for (k, w) in [0.0, 1.0, 5.0].iter().enumerate() {
        let (x, v) = (
            j["density"][k][0].as_f64().unwrap(),
            j["density"][k][1].as_f64().unwrap(),
        );
        assert_eq!(x, *w);
        assert!((v - s(*w)).abs() <= ROUNDING * s(*w));
    }
    let j = run(&[
        "spectrum",
        "type1",
        "--frequency",
        "0.5,2",
        "--convention",
        "one-sided-cyclic",
        "--json",
    ]);
    for (k, f) in [0.5, 2.0].iter().enumerate() {
        let g = 4.0 * std::f64::consts::PI * s(2.0 * std::f64::consts::PI * f);
        let (x, v) = (
            j["density"][k][0].as_f64().unwrap(),
            j["density"][k][1].as_f64().unwrap(),
        );
        assert!(
            (x - f).abs() <= ROUNDING * f && (v - g).abs() <= ROUNDING * g,
            "{x} {v} {g}"
        );
    }
}

/// The Welch estimate's χ² band is compared with the estimate's own expectation — the window kernel over
/// the density of the simulated, sampled process — and covers it at the nominal rate on the bins where the
/// estimate measures the density (`PsdEstimate::resolved`: expected estimate within 25 % of the density).
/// Over 60 seeds × 2 outputs × every 8th resolved bin (Hann bins further apart than two are nearly
/// uncorrelated), 95 % bands: the count of covered bins is Binomial(n, 0.95) to the χ² approximation; the
/// test accepts [0.95 n − 5σ, 0.95 n + 5σ], σ = √(n·0.95·0.05), false-failure probability below 1e-6 for
/// independent bins (the χ² approximation is fine at ν > 1000).
///
/// The half car's road (ISO 8608, n ≤ 2.83 cycles/m) has no power above 2π·2.83·10 = 178 rad/s: there the
/// estimate is the window's leakage of a few strong lines far away, its scatter about 3 times the χ²
/// variance (measured while writing this test), and those bins must be flagged unresolved.
#[test]
fn welch_bands_cover_their_expectation_at_the_nominal_rate() {
    for (file, dt) in [("conveyor-idler.toml", 0.01), ("half-car.toml", 0.01)] {
        let sc = stochvib::scenario::load_scenario(&root().join("data").join(file), &root().join("spectra")).unwrap();
        let (mut covered, mut n) = (0usize, 0usize);
        for seed in 0..60u64 {
            let out = crate::common::scratch_kept("truth", "welch").join(format!("run-{seed}.h5"));
            let _ = std::fs::remove_file(&out);
            let s = sc
                .simulate(
                    &RunOptions {
                        realizations: 20,
                        duration_s: 20.0,
                        dt_s: dt,
                        seed: 1000 + seed,
                        ..RunOptions::default()
                    },
                    &out,
                    &|_, _| {},
                )
                .unwrap();
            let run = stochvib::store::RunFile::open(&s.path).unwrap();
            for p in run.psd().unwrap().iter().take(2) {
                let (e, resolved) = (p.expected.as_ref().unwrap(), p.resolved().unwrap());
                if file == "half-car.toml" {
                    for (w, r) in p.omega.iter().zip(&resolved) {
                        assert!(
                            *w < 2.0 * std::f64::consts::PI * 2.83 * 10.0 || !r,
                            "{}: bin {w} resolved",
                            p.output
                        );
                    }
                }
                for j in (1..e.len() - 1).step_by(8).filter(|j| resolved[*j]) {
                    n += 1;
                    covered += usize::from(p.lower[j] <= e[j] && e[j] <= p.upper[j]);
                }
            }
            drop(run);
            std::fs::remove_file(&out).unwrap();
        }
        let (mean, sd) = (0.95 * n as f64, (n as f64 * 0.95 * 0.05).sqrt());
        println!("{file}: the band covers the expectation at {covered} of {n} resolved bins");
        assert!(n > 400, "{file}: only {n} resolved bins");
        assert!(
            (covered as f64 - mean).abs() <= 5.0 * sd,
            "{file}: {covered} of {n} bins covered (expected {mean:.0} ± {:.0})",
            5.0 * sd
        );
    }
}

/// σ² of the first method that gave a value, and the value of `m`.
fn exact_and_quadrature(st: &stochvib::response::ResponseStatistics, exact: VarianceMethod) -> (f64, f64) {
    let e = method(st, exact).value().unwrap_or_else(|| panic!("{st:?}"));
    let q = method(st, VarianceMethod::Quadrature)
        .value()
        .unwrap_or_else(|| panic!("{st:?}"));
    (e, q)
}

/// Force inputs in the generic MDOF format (`forces = [[1]]`): a mass m on a spring k and damper b to the
/// ground, driven by a force of type-1 correlation K_F(τ) = D e^{−α|τ|}, S_F(ω) = Dα/(π(α² + ω²)).
///
/// # Closed form
/// x = F/(ms² + bs + k), so σ_x² = (Dα/π)·2π·I₃ with the table integral (James, Nichols & Phillips,
/// *Theory of Servomechanisms*, 1947, table of I_n) I₃ = a₁/(2a₃(a₁a₂ − a₀a₃)) for the numerator 1 and
/// a(s) = (s + α)(ms² + bs + k): a₀ = m, a₁ = b + αm, a₂ = k + αb, a₃ = αk. Hence
/// σ_x² = D a₁/(k(a₁a₂ − mαk)); limits: α → 0 gives D/k² (quasi-static), α → ∞ gives D/(αkb) (white).
/// The relative displacement of the base-excited oscillator (matrix form, `relative-displacement`) has the
/// numerator −ms²: I₃ = b₀²a₂a₃/(2a₀a₃(a₁a₂ − a₀a₃)) with b₀ = m, σ_z² = Dα m a₂/(a₁a₂ − mαk) (→ 0 as α → 0:
/// a slow base carries the mass along). The element form's `deflection` is the same quantity written
/// another way.
#[test]
fn force_inputs_and_relative_outputs_match_closed_forms() {
    let (m, k, b, d, alpha) = (100.0, 1e4, 200.0, 100.0, 2.0);
    let (a1, a2) = (b + alpha * m, k + alpha * b);
    let det = a1 * a2 - m * alpha * k;
    let force_var = d * a1 / (k * det);
    let rel_var = d * alpha * m * a2 / det;
    let force = format!(
        r#"
[model]
kind = "mdof"
coordinates = [{{ name = "x", unit = "m" }}]
mass_matrix = [[{m}]]
damping_matrix = [[{b}]]
stiffness_matrix = [[{k}]]
forces = [[1]]
[[model.output]]
name = "x"
quantity = "displacement"
point = [1]
[input]
spectrum = {{ kind = "exponential", domain = "temporal", unit = "N", variance = "{d} N^2", alpha = "{alpha} 1/s" }}
"#
    );
    let sc = scenario(&force);
    let st = analyze_output(sc.model.system.as_ref(), &sc.excitation, 0).unwrap();
    let (e, q) = exact_and_quadrature(&st, VarianceMethod::Lyapunov);
    for v in [e, q] {
        assert!((v - force_var).abs() <= FACTORISATION * force_var, "{v} vs {force_var}");
    }
    // the same oscillator on a moving base, written with matrices and with an element
    let base = |model: &str| {
        format!(
            r#"
[model]
kind = "mdof"
base_inputs = 1
{model}
[input]
spectrum = {{ kind = "exponential", domain = "temporal", unit = "m", variance = "{d} m^2", alpha = "{alpha} 1/s" }}
"#
        )
    };
    let matrix = base(&format!(
        "coordinates = [{{ name = \"x\", unit = \"m\" }}]\nmass_matrix = [[{m}]]\ndamping_matrix = [[{b}]]\n\
         stiffness_matrix = [[{k}]]\nbase_stiffness = [[{k}]]\nbase_damping = [[{b}]]\n[[model.output]]\nname = \
         \"travel\"\nquantity = \"relative-displacement\"\npoint = [1]\nbase = 0\n[[model.output]]\nname = \
         \"travel_rate\"\nquantity = \"relative-velocity\"\npoint = [1]\nbase = 0"
    ));
    let elements = base(&format!(
        "coordinates = [{{ name = \"x\", unit = \"m\", mass = {m} }}]\n[[model.element]]\nname = \"s\"\npoint = [1]\n\
         to = \"base 0\"\nstiffness = {k}\ndamping = {b}\n[[model.output]]\nname = \"travel\"\nquantity = \
         \"deflection\"\nelement = \"s\""
    ));
    let (scm, sce) = (scenario(&matrix), scenario(&elements));
    assert_eq!(scm.model.system.outputs()[0].unit, "m");
    assert_eq!(scm.model.system.outputs()[1].unit, "m/s");
    let stm = analyze_output(scm.model.system.as_ref(), &scm.excitation, 0).unwrap();
    let ste = analyze_output(sce.model.system.as_ref(), &sce.excitation, 0).unwrap();
    let (e, q) = exact_and_quadrature(&stm, VarianceMethod::Lyapunov);
    let el = ste.variance.unwrap();
    for v in [e, q, el] {
        assert!((v - rel_var).abs() <= FACTORISATION * rel_var, "{v} vs {rel_var}");
    }
    // a relative output needs a base input that exists, and a force with a base input is refused
    let bad = matrix.replace("base = 0", "base = 3");
    let err = parse_scenario(&bad, Path::new("case.toml"), &root().join("spectra")).unwrap_err();
    assert!(err.to_string().contains("base"), "{err}");
    let both = matrix.replace("base_damping = [[", "forces = [[1]]\nbase_damping = [[");
    let err = parse_scenario(&both, Path::new("case.toml"), &root().join("spectra")).unwrap_err();
    assert!(err.to_string().contains("forces"), "{err}");
}

/// Delays for the transfer-function kind: `numerator = [[0.5], [0.5]]` over D(s) = 1 + τs with the two
/// inputs Δ = ℓ/v apart on a type-1 track, y = W(s)·(u(t) + u(t − Δ))/2 with W = 1/(1 + τs) (the balancer
/// bogie's pivot through the wheel filter, Sukharev 2012 (8.46)).
///
/// # Closed form
/// σ_y² = ∫ S(ω)|W|²·|1 + e^{−iωΔ}|²/4 dω = (Dα/π)·(J(0) + J(Δ))/2 with
/// J(Δ) = ∫ cos(ωΔ)/((α² + ω²)(1 + τ²ω²)) dω = π(e^{−αΔ}/α − τe^{−Δ/τ})/(1 − α²τ²)
/// (partial fractions and ∫ cos(ωΔ)/(a² + ω²) dω = πe^{−aΔ}/a).
#[test]
fn transfer_function_with_delayed_inputs_matches_closed_form() {
    let (d, alpha, tau, len, v) = (1e-4, 2.0, 0.05, 1.3, 4.0);
    let delta = len / v;
    let j = |dl: f64| {
        std::f64::consts::PI * ((-alpha * dl).exp() / alpha - tau * (-dl / tau).exp())
            / (1.0 - alpha * alpha * tau * tau)
    };
    let want = d * alpha / std::f64::consts::PI * (j(0.0) + j(delta)) / 2.0;
    let text = format!(
        r#"
[model]
kind = "transfer-function"
numerator = [[0.5], [0.5]]
denominator = [1, {tau}]
positions = ["0 m", "{len} m"]
output = {{ name = "pivot", unit = "m" }}
[input]
spectrum = {{ kind = "exponential", domain = "temporal", unit = "m", variance = "{d} m^2", alpha = "{alpha} 1/s" }}
speed = "{v} m/s"
"#
    );
    let sc = scenario(&text);
    let st = analyze_output(sc.model.system.as_ref(), &sc.excitation, 0).unwrap();
    let (e, q) = exact_and_quadrature(&st, VarianceMethod::LyapunovDelays);
    for x in [e, q] {
        assert!((x - want).abs() <= FACTORISATION * want, "{x} vs {want}");
    }
    // positions with a single numerator are refused: one input has no delay
    let single = text.replace("[[0.5], [0.5]]", "[1]");
    let err = parse_scenario(&single, Path::new("case.toml"), &root().join("spectra")).unwrap_err();
    assert!(err.to_string().contains("positions"), "{err}");
}

/// Monte Carlo of seeded random delayed rational cases (the exact-vs-quadrature agreement of the same
/// family is `tests/delays.rs::random_delayed_rational_cases_routes_agree`): a random stable denominator
/// (a real pole and a damped pair), 2–3 inputs with random numerators at random positions on a type-1 or
/// type-3 track, written as a `transfer-function` scenario. The σ interval of the spectral route covers the
/// exact σ of the simulated discretised process (positions are multiples of vΔt = 0.05 m: exact delays), which is within SPECTRAL_GRID_BIAS of the analytic σ.
/// Interval confidence 1 − 2.5e-7 per case, 4 cases: false-failure probability ≤ 1e-6.
#[test]
fn random_delayed_cases_monte_carlo_agrees() {
    use common::tolerance::SPECTRAL_GRID_BIAS;
    use rand::{RngExt, SeedableRng};
    let mut rng = rand::rngs::Xoshiro256PlusPlus::seed_from_u64(2026);
    for case in 0..4 {
        let p = 1.0 + 4.0 * rng.random::<f64>();
        let (w, z) = (3.0 + 10.0 * rng.random::<f64>(), 0.1 + 0.4 * rng.random::<f64>());
        // D(s) = (s + p)(s² + 2ζωs + ω²)
        let den = [p * w * w, w * w + 2.0 * z * w * p, 2.0 * z * w + p, 1.0];
        let n_in = 2 + (case % 2);
        let nums: Vec<String> = (0..n_in)
            .map(|_| {
                let c: Vec<String> = (0..3)
                    .map(|_| format!("{:.4}", 40.0 * (rng.random::<f64>() - 0.3)))
                    .collect();
                format!("[{}]", c.join(", "))
            })
            .collect();
        let positions: Vec<String> = (0..n_in)
            .map(|i| {
                if i == 0 {
                    "\"0 m\"".to_string()
                } else {
                    format!("\"{:.2} m\"", 0.05 * (10 + rng.random_range(0..50)) as f64)
                }
            })
            .collect();
        let spectrum = if case < 2 {
            "{ kind = \"exponential\", domain = \"spatial\", unit = \"m\", variance = \"1 cm^2\", alpha = \"0.2 1/m\" }"
        } else {
            "{ kind = \"exp-cosine\", domain = \"spatial\", unit = \"m\", variance = \"1 cm^2\", alpha = \"0.1 1/m\", beta = \"0.8 1/m\" }"
        };
        let text = format!(
            "[model]\nkind = \"transfer-function\"\nnumerator = [{}]\ndenominator = [{}]\npositions = [{}]\noutput = \
             {{ name = \"y\", unit = \"m\" }}\n[input]\nspectrum = {spectrum}\nspeed = \"5 m/s\"\n",
            nums.join(", "),
            den.iter().map(|x| format!("{x:e}")).collect::<Vec<_>>().join(", "),
            positions.join(", ")
        );
        let sc = scenario(&text);
        let mut o = RunOptions {
            realizations: 200,
            duration_s: 60.0,
            dt_s: 0.01,
            seed: 31 + case as u64,
            ..RunOptions::default()
        };
        o.confidence = 1.0 - 2.5e-7;
        let out = crate::common::scratch_kept("truth", "rand").join(format!("run-{case}.h5"));
        let _ = std::fs::remove_file(&out);
        let s = sc
            .simulate(&o, &out, &|_, _| {})
            .unwrap_or_else(|e| panic!("case {case}: {e}\n{text}"));
        std::fs::remove_file(&out).unwrap();
        let o = &s.outputs[0];
        let (sigma, disc) = (o.get("sigma").unwrap(), o.get("sigma_discrete").unwrap());
        let (sa, sd) = (sigma.analytic.unwrap(), disc.analytic.unwrap());
        assert!(
            sigma.interval.covers(sd),
            "case {case}: {:?} vs discrete {sd}\n{text}",
            sigma.interval
        );
        assert!(
            (sd - sa).abs() < SPECTRAL_GRID_BIAS * sa,
            "case {case}: discrete {sd} vs analytic {sa}\n{text}"
        );
    }
}
