//! Two road tracks with a coherence function and general sources: output statistics against oracles
//! built independently (closed forms of a symmetric vehicle, a dense direct evaluation of H S Hᴴ), the
//! limits γ = 1 (no roll) and γ = 0 (independent tracks), and the general form of the old excitations.

use crate::common;
use common::tolerance::{FACTORISATION, QUADRATURE, ROUNDING};
use nalgebra::{Complex, DMatrix};
use std::f64::consts::PI;
use std::sync::Arc;
use stochvib::coherence::{Coherence, ConstantCoherence, IsotropicCoherence, TwoTracks};
use stochvib::response::{analyze_output, variance_lyapunov, Excitation, InputMap, ResponseStatistics, Source};
use stochvib::spectrum::{Domain, Exponential, Spectrum};
use stochvib::system::{Attach, Element, FrequencyResponse, Mdof, Quantity};

use common::two_wheel_body::{body, C, H, K, V};

fn road() -> Arc<dyn Spectrum> {
    // type 1 in space (book (8.45) form): D = 1e-4 m², α = 0.2 rad/m
    Arc::new(Exponential::new(1e-4, 0.2, Domain::Spatial).unwrap())
}

fn output(sys: &Mdof, name: &str) -> usize {
    sys.output_index(name).unwrap()
}

fn tracks(coh: Arc<dyn Coherence>) -> Arc<TwoTracks> {
    Arc::new(TwoTracks::new(road(), coh, V).unwrap())
}

#[test]
fn symmetric_vehicle_matches_the_bounce_and_roll_closed_forms() {
    // Oracle: the closed forms of `common::two_wheel_body::closed_form_variances` (derived in its doc):
    // bounce and roll are single-input transfer functions driven by the road of variance D(1 ± ρ)/2, exact
    // Lyapunov variances on another model and another excitation than the two-track route under test.
    let rho = 0.4;
    let sys = body();
    let exc = Excitation::two_tracks(
        tracks(Arc::new(ConstantCoherence::new(rho).unwrap())),
        &[(0, 0.0), (1, 0.0)],
    )
    .unwrap();
    let (zb, zr) = common::two_wheel_body::closed_form_variances(rho);
    for (name, oracle) in [("bounce", zb), ("roll", zr)] {
        let st = analyze_output(&sys, &exc, output(&sys, name)).unwrap();
        let q = st.methods.iter().find(|m| m.method.name() == "quadrature").unwrap();
        let v = q.value().unwrap();
        assert!(
            (v - oracle).abs() <= QUADRATURE * oracle,
            "{name}: {v:e} vs closed form {oracle:e}"
        );
        // a constant coherence factors the tracks into the independent sum and difference processes of
        // densities S(1 ± ρ)/2: the exact route applies to the two-wheel model itself
        let ly = st.methods.iter().find(|m| m.method.name() == "lyapunov").unwrap();
        let x = ly.value().unwrap_or_else(|| panic!("{name}: {ly:?}"));
        assert!(
            (x - oracle).abs() <= FACTORISATION * oracle,
            "{name}: lyapunov {x:e} vs closed form {oracle:e}"
        );
        assert_eq!(st.variance, Some(x));
    }
}

/// A coherence that depends on the spatial frequency (the isotropic surface of Dodds & Robson) makes the
/// mixing of the tracks depend on ω: no factorisation into independent processes with constant
/// coefficients, so the exact route refuses and says why, and the quadrature is the answer.
#[test]
fn a_coherence_function_of_frequency_keeps_the_exact_route_refused() {
    let sys = body();
    let exc = Excitation::two_tracks(
        tracks(Arc::new(IsotropicCoherence::new(1.5, 2.0).unwrap())),
        &[(0, 0.0), (1, 0.0)],
    )
    .unwrap();
    let st = analyze_output(&sys, &exc, output(&sys, "roll")).unwrap();
    let ly = st.methods.iter().find(|m| m.method.name() == "lyapunov").unwrap();
    let stochvib::response::Outcome::NotApplicable { reason } = &ly.outcome else {
        panic!("{:?}", ly.outcome)
    };
    assert!(
        reason.contains("no rational factorisation (a coherence function of n)"),
        "{reason}"
    );
    let q = st.methods.iter().find(|m| m.method.name() == "quadrature").unwrap();
    assert_eq!(st.variance, q.value());
}

#[test]
fn identical_tracks_give_no_roll_and_independent_tracks_add() {
    let sys = body();
    let roll = output(&sys, "roll");
    let bounce = output(&sys, "bounce");
    // γ = 1: u_L = u_R, roll sees d = 0; its density is S|z|²(1 + 1 − 1 − 1), zero up to rounding of
    // terms of size S|z|² (bounded by the bounce variance scale times (H_roll/H_bounce)² ~ 1/h²).
    let same = Excitation::two_tracks(
        tracks(Arc::new(ConstantCoherence::new(1.0).unwrap())),
        &[(0, 0.0), (1, 0.0)],
    )
    .unwrap();
    let r1 = analyze_output(&sys, &same, roll).unwrap();
    let b1 = analyze_output(&sys, &same, bounce).unwrap().variance.unwrap();
    let v1 = r1.variance.unwrap_or(0.0);
    assert!(
        v1.abs() <= ROUNDING * b1 / (H * H),
        "roll variance {v1:e} with identical tracks"
    );
    // γ = 0: the tracks are independent processes: the exact Lyapunov value of the (old) independent
    // excitation, a different route (augmented state space) from the quadrature of the matrix source.
    let indep = Excitation::two_tracks(
        tracks(Arc::new(ConstantCoherence::new(0.0).unwrap())),
        &[(0, 0.0), (1, 0.0)],
    )
    .unwrap();
    let t: Arc<dyn Spectrum> = Arc::new(stochvib::spectrum::AtSpeed::new(road(), V).unwrap());
    let old = Excitation::independent(vec![t.clone(), t], vec![0.0, 0.0]).unwrap();
    for i in [bounce, roll] {
        let v = analyze_output(&sys, &indep, i).unwrap().variance.unwrap();
        let oracle = variance_lyapunov(&sys, &old, i).unwrap().variance;
        assert!(
            (v - oracle).abs() <= QUADRATURE * oracle,
            "output {i}: {v:e} vs {oracle:e}"
        );
    }
}

/// ∫_{-∞}^{∞} f dω = 2∫_0^∞ f by composite Simpson: on a logarithmic grid over [1e-9, 1] rad/s and a
/// uniform grid of step 0.01 rad/s over [1, 4000] rad/s (the integrands below decay like ω⁻⁴, so the tail
/// beyond 4000 rad/s is below 1e-10 of the total; below 1e-9 rad/s they are bounded by S(0)·|H(0)|², i.e.
/// below 1e-13 of the total).
fn dense_integral(f: impl Fn(f64) -> f64) -> f64 {
    let simpson = |g: &dyn Fn(f64) -> f64, a: f64, b: f64, n: usize| {
        let h = (b - a) / n as f64;
        let mut s = g(a) + g(b);
        for k in 1..n {
            s += g(a + k as f64 * h) * if k % 2 == 1 { 4.0 } else { 2.0 };
        }
        s * h / 3.0
    };
    let low = simpson(&|t: f64| f(t.exp()) * t.exp(), (1e-9f64).ln(), 0.0, 40_000);
    let high = simpson(&|w: f64| f(w), 1.0, 4000.0, 399_900);
    2.0 * (low + high)
}

#[test]
fn four_wheels_on_isotropic_tracks_match_a_dense_evaluation_of_h_s_h() {
    // Body with bounce, pitch and roll on four corners (axles at +1.2 m and −1.5 m, wheelbase 2.7 m),
    // wheels 0, 1 front left/right, 2, 3 rear left/right; the rear wheels feel the tracks delayed by 2.7/v.
    // Oracle: S_y(ω) = h S_uu hᴴ with S_uu built here entry by entry from its definition
    // S_jk = S(ω) ρ_jk(n) e^{−iω(τ_j − τ_k)} (ρ_jk = 1 on one track, the isotropic ρ(n) across), h the row
    // of the model's own frequency response, integrated by the dense Simpson rule above (no adaptivity,
    // no grouping, no oscillatory extrapolation). Outputs are body displacements, whose densities decay
    // like ω⁻⁴ (a suspension travel decays only like the road, ω⁻², and the rule's cut at 4000 rad/s would
    // miss ~1e-3 of it).
    let (a, b) = (1.2, 1.5);
    let el = |name: &str, x: f64, y: f64, j: usize| Element {
        name: name.into(),
        point: vec![1.0, -x, y],
        to: Attach::Base(j),
        stiffness: K,
        damping: C,
    };
    let sys = Mdof::from_elements(
        &[("z", "m"), ("theta", "rad"), ("phi", "rad")],
        &[1200.0, 1500.0, 400.0],
        vec![
            el("fl", a, H, 0),
            el("fr", a, -H, 1),
            el("rl", -b, H, 2),
            el("rr", -b, -H, 3),
        ],
        4,
        &[],
    )
    .unwrap()
    .with_output("roll", Quantity::Displacement(vec![0.0, 0.0, 1.0]))
    .unwrap()
    .with_output("pitch", Quantity::Displacement(vec![0.0, 1.0, 0.0]))
    .unwrap()
    .with_output("corner_rl", Quantity::Displacement(vec![1.0, b, H]))
    .unwrap();
    let coh = Arc::new(IsotropicCoherence::new(2.0 * H, 2.0).unwrap());
    let t = tracks(coh.clone());
    let wheels = [(0, 0.0), (1, 0.0), (0, a + b), (1, a + b)];
    let exc = Excitation::two_tracks(t, &wheels).unwrap();
    let s_t = stochvib::spectrum::AtSpeed::new(road(), V).unwrap();
    for name in ["roll", "pitch", "corner_rl"] {
        let i = output(&sys, name);
        let density = |w: f64| {
            let hm = sys.response(w);
            let rho = coh.coherence_amplitude(w / (2.0 * PI * V));
            let s = s_t.density(w);
            let suu = DMatrix::from_fn(4, 4, |j, k| {
                let r = if wheels[j].0 == wheels[k].0 { 1.0 } else { rho };
                Complex::from_polar(s * r, -w * (wheels[j].1 - wheels[k].1) / V)
            });
            let mut acc = Complex::new(0.0, 0.0);
            for j in 0..4 {
                for k in 0..4 {
                    acc += hm[(i, j)] * suu[(j, k)] * hm[(i, k)].conj();
                }
            }
            acc.re
        };
        let oracle = dense_integral(density);
        let v = analyze_output(&sys, &exc, i).unwrap().variance.unwrap();
        assert!(
            (v - oracle).abs() <= QUADRATURE * oracle,
            "{name}: {v:e} vs dense {oracle:e}"
        );
    }
}

#[test]
fn general_form_of_a_track_and_of_independent_inputs_gives_the_same_statistics() {
    // The old excitations in the general form go through the new code paths (per-source exact sums, the
    // general quadrature); the old variants through their own. Both are exact (Lyapunov with delays) or
    // converged quadrature, so they agree to those methods' accuracy.
    let sys = body();
    let t: Arc<dyn Spectrum> = Arc::new(stochvib::spectrum::AtSpeed::new(road(), V).unwrap());
    let track = Excitation::track(t.clone(), vec![0.0, 0.2], vec![1.0, 0.7], 0.01).unwrap();
    let force: Arc<dyn Spectrum> = Arc::new(Exponential::new(2e-4, 3.0, Domain::Temporal).unwrap());
    let indep = Excitation::independent(vec![t, force], vec![0.0, 0.02]).unwrap();
    for exc in [track, indep] {
        let generator = exc.to_sources();
        for i in 0..2 {
            let a = analyze_output(&sys, &exc, i).unwrap();
            let b = analyze_output(&sys, &generator, i).unwrap();
            let (va, vb) = (a.variance.unwrap(), b.variance.unwrap());
            assert!(
                (va - vb).abs() <= FACTORISATION * va,
                "output {i}: {va:e} vs general {vb:e}"
            );
            let (ma, mb) = (a.mean.unwrap(), b.mean.unwrap());
            assert!((ma - mb).abs() <= ROUNDING * ma.abs().max(1e-300), "mean {ma} vs {mb}");
            for m in &b.methods {
                if let (Some(x), "lyapunov" | "lyapunov (delays)" | "quadrature") = (m.value(), m.method.name()) {
                    assert!(
                        (x - va).abs() <= QUADRATURE * va,
                        "{}: {x:e} vs {va:e}",
                        m.method.name()
                    );
                }
            }
        }
    }
}

#[test]
fn a_road_and_an_independent_force_add() {
    // Two independent sources: the output variance is the sum of the variances under each source alone
    // (each computed through the old single-process excitations with the other input's gain 0).
    let sys = body();
    let t: Arc<dyn Spectrum> = Arc::new(stochvib::spectrum::AtSpeed::new(road(), V).unwrap());
    let f: Arc<dyn Spectrum> = Arc::new(Exponential::new(5e-5, 4.0, Domain::Temporal).unwrap());
    let exc = Excitation::sources(
        vec![Source::Process(t.clone()), Source::Process(f.clone())],
        vec![
            InputMap {
                source: 0,
                component: 0,
                delay: 0.0,
                gain: 1.0,
                mean: 0.0,
            },
            InputMap {
                source: 1,
                component: 0,
                delay: 0.0,
                gain: 1.0,
                mean: 0.0,
            },
        ],
    )
    .unwrap();
    for i in 0..2 {
        let alone0 = variance_lyapunov(
            &sys,
            &Excitation::track(t.clone(), vec![0.0, 0.0], vec![1.0, 0.0], 0.0).unwrap(),
            i,
        )
        .unwrap()
        .variance;
        let alone1 = variance_lyapunov(
            &sys,
            &Excitation::track(f.clone(), vec![0.0, 0.0], vec![0.0, 1.0], 0.0).unwrap(),
            i,
        )
        .unwrap()
        .variance;
        let st = analyze_output(&sys, &exc, i).unwrap();
        let v = st.variance.unwrap();
        assert!(
            (v - alone0 - alone1).abs() <= FACTORISATION * v,
            "output {i}: {v:e} vs {:e}",
            alone0 + alone1
        );
        let q = method_value(&st, "quadrature");
        assert!((q - v).abs() <= QUADRATURE * v);
    }
}

/// The value of the variance method `name` (`quadrature`, `lyapunov (delays)`, …) in `st`.
fn method_value(st: &ResponseStatistics, name: &str) -> f64 {
    st.methods
        .iter()
        .find(|m| m.method.name() == name)
        .unwrap()
        .value()
        .unwrap()
}

#[test]
fn invalid_sources_are_refused_with_the_entry_named() {
    let t: Arc<dyn Spectrum> = Arc::new(stochvib::spectrum::AtSpeed::new(road(), V).unwrap());
    let bad = |inp: InputMap| {
        Excitation::sources(vec![Source::Process(t.clone())], vec![inp])
            .unwrap_err()
            .to_string()
    };
    let ok = InputMap {
        source: 0,
        component: 0,
        delay: 0.0,
        gain: 1.0,
        mean: 0.0,
    };
    assert!(bad(InputMap { source: 1, ..ok }).contains("inputs[0].source"));
    assert!(bad(InputMap { component: 1, ..ok }).contains("inputs[0].component"));
    assert!(bad(InputMap { delay: -1.0, ..ok }).contains("inputs[0].delay"));
    assert!(bad(InputMap { gain: f64::NAN, ..ok }).contains("inputs[0].gain"));
    // a spatial spectrum is not a temporal input
    let e = Excitation::sources(vec![Source::Process(road())], vec![ok])
        .unwrap_err()
        .to_string();
    assert!(e.contains("sources[0]"), "{e}");
}

#[test]
fn seven_dof_vehicle_does_not_roll_on_identical_tracks_and_adds_independent_ones() {
    use stochvib::models::full_vehicle::FullVehicle;
    let car = FullVehicle::passenger_car();
    let sys = car.mdof().unwrap();
    let l = car.wheelbase();
    // γ = 1: the left–right symmetric car sees u_fl = u_fr and u_rl = u_rr; roll and the left–right
    // difference of the travels are zero up to rounding of terms of the size of the bounce response.
    let same = Excitation::two_tracks(tracks(Arc::new(ConstantCoherence::new(1.0).unwrap())), &car.wheels()).unwrap();
    let roll = analyze_output(&sys, &same, output(&sys, "roll")).unwrap();
    let pitch = analyze_output(&sys, &same, output(&sys, "pitch"))
        .unwrap()
        .variance
        .unwrap();
    let v = roll.variance.unwrap_or(0.0);
    assert!(
        v.abs() <= ROUNDING * pitch,
        "roll variance {v:e} on identical tracks (pitch {pitch:e})"
    );
    // γ = 0: two independent tracks, each a single process felt by its front and rear wheel with the
    // delay L/v: the exact sum over sources of Lyapunov-with-delays values (augmented state space with the
    // delays' exact covariance), against the quadrature of the two-track matrix with ρ = 0.
    let indep = Excitation::two_tracks(tracks(Arc::new(ConstantCoherence::new(0.0).unwrap())), &car.wheels()).unwrap();
    let t: Arc<dyn Spectrum> = Arc::new(stochvib::spectrum::AtSpeed::new(road(), V).unwrap());
    let w = |s: usize, x: f64| InputMap {
        source: s,
        component: 0,
        delay: x / V,
        gain: 1.0,
        mean: 0.0,
    };
    let two_sources = Excitation::sources(
        vec![Source::Process(t.clone()), Source::Process(t)],
        vec![w(0, 0.0), w(1, 0.0), w(0, l), w(1, l)],
    )
    .unwrap();
    for name in ["seat_acc", "roll", "pitch", "travel_rl", "tyre_force_fr"] {
        let i = output(&sys, name);
        let q = method_value(&analyze_output(&sys, &indep, i).unwrap(), "quadrature");
        let exact = method_value(&analyze_output(&sys, &two_sources, i).unwrap(), "lyapunov (delays)");
        assert!(
            (q - exact).abs() <= QUADRATURE * exact,
            "{name}: quadrature {q:e} vs exact {exact:e}"
        );
    }
}
