//! Two-track coherence models and the modified Bessel function K_ν behind the isotropic model.
//!
//! Expected values come from closed forms (half-integer orders, half-integer Matérn forms), published
//! tables (Abramowitz & Stegun 1964, Table 9.8) and slow oracles (the integral representation of K_ν, the
//! projection integrals that define the isotropic coherence), never from the code under test.

use std::f64::consts::PI;
use stochvib::coherence::bessel_k::{bessel_k, bessel_k_scaled, bessel_k_x_pow};
use stochvib::coherence::{
    AmmonBormann, AmmonBormannParameters, AmmonBormannRoad, Coherence, CoherenceKind, ConstantCoherence,
    IsotropicCoherence, TabulatedCoherence,
};

// ---- named tolerances -------------------------------------------------------------------------------
/// Closed form vs Temme/Steed + a few recurrence steps: a handful of ulps per operation.
const BESSEL_CLOSED_FORM: f64 = 1e-14;
/// Abramowitz & Stegun Table 9.8 prints 10 significant digits: half a unit of the last digit.
const AS_TABLE_10_DIGITS: f64 = 5e-10;
/// Trapezoid rule (step 1/200) on the integral representation of K_ν: the rule is geometrically
/// convergent for this even, entire, double-exponentially decaying integrand; 1e-12 leaves margin over
/// the summation rounding of ~2000 terms.
const BESSEL_INTEGRAL_ORACLE: f64 = 1e-12;
/// Simpson quadrature of the oscillatory projection integrals truncated at κ = 400 rad/m: the neglected
/// tail is bounded by (κ² + Ω²)^{−ν−½}/B at the cut (integration by parts), ≈ 2e-10 relative here, and
/// Simpson's error with step 2.5e-3 rad/m is below 1e-10.
const PROJECTION_QUADRATURE: f64 = 1e-8;
/// Two algebraically equal closed forms in f64.
const EXACT: f64 = 1e-13;

/// K_ν(x) = ∫₀^∞ e^{−x cosh t} cosh(νt) dt (A&S 9.6.24) by the trapezoid rule: an oracle independent of
/// the series and continued fractions of the code under test.
fn k_integral(nu: f64, x: f64) -> f64 {
    let h = 0.005;
    let mut sum = 0.5 * (-x).exp(); // t = 0 with weight ½
    let mut k = 1;
    loop {
        let t = k as f64 * h;
        let term = (-x * t.cosh() + nu * t).exp() * 0.5 * (1.0 + (-2.0 * nu * t).exp());
        sum += term;
        if x * t.cosh() - nu * t > 800.0 {
            break;
        }
        k += 1;
    }
    sum * h
}

#[test]
fn bessel_k_half_integer_orders_match_closed_forms() {
    // A&S 10.2.17: K_{1/2}(x) = √(π/(2x)) e^{−x}, K_{3/2} = K_{1/2}(1 + 1/x), K_{5/2} = K_{1/2}(1 + 3/x + 3/x²).
    // x spans Temme's series (x < 2) and Steed's continued fraction (x ≥ 2).
    for &x in &[0.01, 0.1, 0.5, 1.0, 1.999, 2.0, 3.7, 10.0, 55.0] {
        let k12 = (PI / (2.0 * x)).sqrt() * (-x).exp();
        let cases = [
            (0.5, k12),
            (1.5, k12 * (1.0 + 1.0 / x)),
            (2.5, k12 * (1.0 + 3.0 / x + 3.0 / (x * x))),
        ];
        for (nu, want) in cases {
            let got = bessel_k(nu, x).unwrap();
            assert!(
                (got - want).abs() <= BESSEL_CLOSED_FORM * want,
                "K_{nu}({x}) = {got:e}, closed form {want:e}"
            );
            // the scaled form is the same number times e^x
            let scaled = bessel_k_scaled(nu, x).unwrap();
            assert!((scaled - want * x.exp()).abs() <= BESSEL_CLOSED_FORM * want * x.exp());
        }
        // K_{−ν} = K_ν
        assert_eq!(bessel_k(-1.5, x).unwrap(), bessel_k(1.5, x).unwrap());
    }
}

#[test]
fn bessel_k_satisfies_the_recurrence() {
    // A&S 9.6.26: K_{ν+1}(x) = K_{ν−1}(x) + (2ν/x) K_ν(x), at non-half-integer orders in both branches.
    for &nu in &[1.0, 1.3, 1.77, 2.5, 3.2] {
        for &x in &[0.3, 1.5, 2.5, 8.0, 25.0] {
            let lhs = bessel_k_scaled(nu + 1.0, x).unwrap();
            let rhs = bessel_k_scaled(nu - 1.0, x).unwrap() + 2.0 * nu / x * bessel_k_scaled(nu, x).unwrap();
            assert!(
                (lhs - rhs).abs() <= BESSEL_CLOSED_FORM * lhs,
                "ν = {nu}, x = {x}: {lhs:e} vs {rhs:e}"
            );
        }
    }
}

#[test]
fn bessel_k_matches_abramowitz_stegun_table_9_8() {
    // Abramowitz & Stegun (1964), Table 9.8, modified Bessel functions of orders 0 and 1:
    // for x ≤ 2 the table gives K₀(x), K₁(x); for x ≥ 2 it gives e^x K₀(x) and e^x K₁(x).
    let direct = [(1.0, 0.4210244382, 0.6019072302), (2.0, 0.1138938727, 0.1398658818)];
    for (x, k0, k1) in direct {
        assert!(
            (bessel_k(0.0, x).unwrap() / k0 - 1.0).abs() < AS_TABLE_10_DIGITS,
            "K0({x})"
        );
        assert!(
            (bessel_k(1.0, x).unwrap() / k1 - 1.0).abs() < AS_TABLE_10_DIGITS,
            "K1({x})"
        );
    }
    let scaled = [
        (5.0, 0.5478075643, 0.6002738588),
        (10.0, 0.3916319344, 0.4107665704),
        (20.0, 0.2785448766, 0.2854254970),
    ];
    for (x, e0, e1) in scaled {
        assert!(
            (bessel_k_scaled(0.0, x).unwrap() / e0 - 1.0).abs() < AS_TABLE_10_DIGITS,
            "e^x K0({x})"
        );
        assert!(
            (bessel_k_scaled(1.0, x).unwrap() / e1 - 1.0).abs() < AS_TABLE_10_DIGITS,
            "e^x K1({x})"
        );
    }
}

#[test]
fn bessel_k_matches_its_integral_representation() {
    for &nu in &[0.0, 0.3, 0.77, 1.25, 2.6, 4.1] {
        for &x in &[0.05, 0.7, 1.99, 2.01, 7.0, 30.0] {
            let want = k_integral(nu, x);
            let got = bessel_k(nu, x).unwrap();
            assert!(
                (got - want).abs() <= BESSEL_INTEGRAL_ORACLE * want,
                "K_{nu}({x}) = {got:e}, integral {want:e}"
            );
        }
    }
}

#[test]
fn x_pow_nu_k_nu_is_finite_at_small_x_and_consistent_elsewhere() {
    // limit x^ν K_ν(x) → 2^{ν−1} Γ(ν) (A&S 9.6.9); at x = 1e-200 the corrections are below 1e-100
    // (ν > 1: relative x²/(4(ν−1))) while K₅(1e-200) alone would overflow f64.
    let gamma5 = 24.0; // Γ(5)
    let v = bessel_k_x_pow(5.0, 1e-200).unwrap();
    assert!((v / (16.0 * gamma5) - 1.0).abs() < EXACT, "{v}");
    assert!(bessel_k(5.0, 1e-200).unwrap().is_infinite());
    // moderate x: the same number as x^ν · K_ν
    for &(nu, x) in &[(0.7, 0.3), (1.0, 1.0), (2.3, 4.0), (3.5, 40.0)] {
        let a = bessel_k_x_pow(nu, x).unwrap();
        let b = x.powf(nu) * bessel_k(nu, x).unwrap();
        assert!((a - b).abs() <= 1e-13 * b, "ν = {nu}, x = {x}: {a:e} vs {b:e}");
    }
    // bad arguments are named
    let e = bessel_k(1.0, 0.0).unwrap_err().to_string();
    assert!(e.contains('x') && e.contains("> 0"), "{e}");
    assert!(bessel_k(f64::NAN, 1.0).is_err());
}

#[test]
fn isotropic_coherence_half_integer_forms() {
    // The Matérn form 2^{1−ν}/Γ(ν) x^ν K_ν(x) is elementary at half-integer ν (from A&S 10.2.17):
    // w = 1 (ν = ½): ρ = e^{−x};  w = 3 (ν = 3/2): ρ = (1 + x) e^{−x};  w = 5: ρ = (1 + x + x²/3) e^{−x}.
    let b = 1.5;
    for &n in &[0.0, 1e-6, 0.01, 0.1, 0.3, 1.0, 3.0] {
        let x = 2.0 * PI * n * b;
        let cases = [
            (1.0, (-x).exp()),
            (3.0, (1.0 + x) * (-x).exp()),
            (5.0, (1.0 + x + x * x / 3.0) * (-x).exp()),
        ];
        for (w, want) in cases {
            let c = IsotropicCoherence::new(b, w).unwrap();
            let got = c.coherence_amplitude(n);
            assert!(
                (got - want).abs() <= 1e-13 * want.max(1e-300),
                "w = {w}, n = {n}: {got} vs {want}"
            );
            assert_eq!(c.coherence_amplitude(-n), got, "even in n");
            assert!((c.squared_coherence(n) - got * got).abs() <= EXACT);
        }
    }
}

#[test]
fn isotropic_coherence_for_iso_waviness_is_x_k1() {
    // w = 2: ρ = x K₁(x). A&S Table 9.8: K₁(1) = 0.6019072302, K₁(2) = 0.1398658818; e^5 K₁(5) = 0.6002738588.
    let b = 2.0;
    let c = IsotropicCoherence::new(b, 2.0).unwrap();
    assert_eq!(c.coherence_amplitude(0.0), 1.0);
    for (x, want) in [
        (1.0, 0.6019072302),
        (2.0, 2.0 * 0.1398658818),
        (5.0, 5.0 * 0.6002738588 * (-5.0f64).exp()),
    ] {
        let n = x / (2.0 * PI * b);
        let got = c.coherence_amplitude(n);
        assert!(
            (got / want - 1.0).abs() < AS_TABLE_10_DIGITS,
            "x = {x}: {got} vs {want}"
        );
    }
    assert_eq!(c.track_width(), Some(2.0));
    // monotone decreasing from 1 to 0
    let mut prev = 1.0;
    for k in 1..200 {
        let r = c.coherence_amplitude(0.01 * k as f64);
        assert!(r < prev && r >= 0.0, "k = {k}");
        prev = r;
    }
    assert_eq!(c.coherence_amplitude(1e300), 0.0);
}

/// Composite Simpson rule of f on [0, upper] with `intervals` (even) subintervals.
fn simpson(f: impl Fn(f64) -> f64, upper: f64, intervals: usize) -> f64 {
    let h = upper / intervals as f64;
    let mut s = f(0.0) + f(upper);
    for k in 1..intervals {
        s += if k % 2 == 1 { 4.0 } else { 2.0 } * f(k as f64 * h);
    }
    s * h / 3.0
}

#[test]
fn isotropic_coherence_is_the_ratio_of_the_projection_integrals() {
    // The definition, independent of any Bessel function: for an isotropic surface with
    // S₂(k) ∝ k^{−(w+1)}, ρ(Ω) = ∫ (Ω² + κ²)^{−(w+1)/2} cos(κB) dκ / ∫ (Ω² + κ²)^{−(w+1)/2} dκ.
    // The denominator is known in closed form: ∫₀^∞ (Ω² + κ²)^{−ν−½} dκ = √π Γ(ν)/(2Γ(ν+½)) Ω^{−2ν}.
    let (b, w) = (1.5, 2.5);
    let nu = 0.5 * w;
    let c = IsotropicCoherence::new(b, w).unwrap();
    // Γ(1.25) = 0.906402477055477, Γ(1.75) = 0.919062526848883 (A&S Table 6.1)
    let denom_const = PI.sqrt() * 0.906402477055477 / (2.0 * 0.919062526848883);
    for &n in &[0.05, 0.1, 0.2] {
        let om = 2.0 * PI * n;
        let num = simpson(|k| (om * om + k * k).powf(-nu - 0.5) * (k * b).cos(), 400.0, 160_000);
        let den = denom_const * om.powf(-2.0 * nu);
        let want = num / den;
        let got = c.coherence_amplitude(n);
        assert!((got - want).abs() < PROJECTION_QUADRATURE, "n = {n}: {got} vs {want}");
    }
}

#[test]
fn isotropic_coherence_rejects_bad_parameters() {
    let e = IsotropicCoherence::new(0.0, 2.0).unwrap_err().to_string();
    assert!(e.contains("track_width"), "{e}");
    let e = IsotropicCoherence::new(1.5, -1.0).unwrap_err().to_string();
    assert!(e.contains("waviness") && e.contains("-1"), "{e}");
    assert!(IsotropicCoherence::new(1.5, f64::NAN).is_err());
    assert!(IsotropicCoherence::new(1.5, 101.0).is_err());
}

#[test]
fn ammon_bormann_formula_and_kind() {
    // f(Ω) = [1 + (Ω B^a/Ω_p)^w]^{−p} by hand: B = 1.6 m, a = 0.5, Ω_p = 2 rad·m^{−½}, w = 2, p = 0.75;
    // at Ω = 2/√1.6 rad/m the base is 1, f = 2^{−0.75}.
    let (b, a, omp, w, p): (f64, f64, f64, f64, f64) = (1.6, 0.5, 2.0, 2.0, 0.75);
    let om = omp / b.powf(a);
    let n = om / (2.0 * PI);
    let want = 2f64.powf(-0.75);
    let sq = AmmonBormannParameters {
        track_width_m: b,
        omega_p: omp,
        w,
        p,
        a,
        kind: CoherenceKind::SquaredCoherence,
    }
    .build()
    .unwrap();
    let amp = AmmonBormannParameters {
        track_width_m: b,
        omega_p: omp,
        w,
        p,
        a,
        kind: CoherenceKind::CoherenceAmplitude,
    }
    .build()
    .unwrap();
    assert!((sq.formula_value(n) - want).abs() < EXACT);
    assert!((sq.squared_coherence(n) - want).abs() < EXACT);
    assert!((sq.coherence_amplitude(n) - want.sqrt()).abs() < EXACT);
    assert!((amp.coherence_amplitude(n) - want).abs() < EXACT);
    assert!((amp.squared_coherence(n) - want * want).abs() < EXACT);
    assert_eq!(sq.coherence_amplitude(0.0), 1.0);
    assert!(sq.describe().contains("squared_coherence"));
    // invalid parameters name themselves
    let e = AmmonBormannParameters {
        track_width_m: b,
        omega_p: -2.0,
        w,
        p,
        a,
        kind: CoherenceKind::SquaredCoherence,
    }
    .build()
    .unwrap_err()
    .to_string();
    assert!(e.contains("omega_p"), "{e}");
    assert!(AmmonBormannParameters {
        track_width_m: b,
        omega_p: omp,
        w,
        p: 0.0,
        a,
        kind: CoherenceKind::SquaredCoherence
    }
    .build()
    .is_err());
}

#[test]
fn ammon_bormann_presets_reproduce_the_published_table() {
    // Parameter table of Project Chrono's RandomSurfaceTerrain (R. Gericke 2020; sources named there:
    // Löhe & Zehelein 2005, Mitschke & Wallentowitz 2014): (Ω_p, p, a, w).
    let table = [
        (AmmonBormannRoad::IsoA, 8.5, 3.5, 1.0, 2.0),
        (AmmonBormannRoad::IsoB, 5.3, 2.2, 1.0, 2.0),
        (AmmonBormannRoad::IsoC, 3.0, 1.3, 1.0, 2.0),
        (AmmonBormannRoad::IsoD, 1.6, 0.8, 1.0, 2.0),
        (AmmonBormannRoad::IsoE, 0.8, 0.5, 1.0, 2.0),
        (AmmonBormannRoad::MajorRoadConcrete, 0.96, 0.47, 0.96, 2.0),
        (AmmonBormannRoad::MajorRoadAsphalticConcrete, 0.73, 0.45, 0.6, 2.1),
        (
            AmmonBormannRoad::MainRoadAsphalticConcreteOnPavement,
            1.53,
            0.45,
            0.56,
            2.3,
        ),
        (AmmonBormannRoad::MainRoadAsphalticConcrete, 3.3, 0.88, 0.97, 2.2),
        (AmmonBormannRoad::TrackTiledConcretePavement, 0.99, 0.5, 0.94, 2.0),
    ];
    let b = 1.8;
    for (road, omp, p, a, w) in table {
        let m = AmmonBormann::preset(road, b).unwrap();
        assert_eq!(m.kind(), CoherenceKind::SquaredCoherence);
        for &n in &[0.02, 0.1, 0.5] {
            let om = 2.0 * PI * n;
            let want = (1.0 + (om * b.powf(a) / omp).powf(w)).powf(-p);
            assert!((m.formula_value(n) - want).abs() < EXACT, "{road:?} n = {n}");
        }
    }
    assert_eq!(AmmonBormannRoad::ALL.len(), table.len());
}

#[test]
fn ammon_bormann_road_spectra_convert_the_german_unevenness() {
    // Φ_h(Ω₀ = 1 rad/m) one-sided in Ω ⇒ G_d(n) = 2π Φ_h(2πn). Check of the convention: the ISO class limits
    // that Chrono tabulates in Φ_h(Ω₀) (A/B boundary 2e-6 m³, B/C 8e-6 m³) must map onto ISO 8608's
    // G_d(n₀) limits 32e-6 and 128e-6 m³ (ISO 8608 class table) within the 1 % of their rounding:
    // 2π · 2e-6 · (0.2π)^{−2} = 31.8e-6.
    let conv = |phi0: f64, w: f64| 2.0 * PI * phi0 * (0.2 * PI).powf(-w);
    assert!((conv(2e-6, 2.0) / 32e-6 - 1.0).abs() < 0.01);
    assert!((conv(8e-6, 2.0) / 128e-6 - 1.0).abs() < 0.01);
    let s = AmmonBormannRoad::MainRoadAsphalticConcrete
        .profile_spectrum(None)
        .unwrap();
    assert!((s.one_sided_cyclic(0.1) / conv(5e-6, 2.2) - 1.0).abs() < EXACT);
    // slope w = 2.2: G(1)/G(0.1) = 10^{−2.2}
    assert!((s.one_sided_cyclic(1.0) / s.one_sided_cyclic(0.1) - 10f64.powf(-2.2)).abs() < EXACT);
    // ISO presets: the class's geometric mean (ISO 8608: class C 256e-6 m³)
    let c = AmmonBormannRoad::IsoC.profile_spectrum(None).unwrap();
    assert!((c.one_sided_cyclic(0.1) - 256e-6).abs() < 1e-18);
}

#[test]
fn tabulated_coherence_interpolates_and_validates() {
    let n = vec![0.0, 0.1, 0.4, 1.0];
    let rho = vec![1.0, 0.8, 0.2, 0.1];
    let t = TabulatedCoherence::new(n.clone(), rho.clone(), CoherenceKind::CoherenceAmplitude).unwrap();
    // nodes exact, midpoints linear in ρ, ends held
    for (nk, rk) in n.iter().zip(&rho) {
        assert_eq!(t.coherence_amplitude(*nk), *rk);
    }
    assert!((t.coherence_amplitude(0.25) - 0.5).abs() < EXACT);
    assert!((t.squared_coherence(0.25) - 0.25).abs() < EXACT);
    assert_eq!(t.coherence_amplitude(5.0), 0.1);
    assert_eq!(t.coherence_amplitude(-0.1), 0.8);
    // a γ² table is interpolated in γ², and ρ = √γ²
    let g = TabulatedCoherence::new(vec![0.2, 0.6], vec![0.81, 0.01], CoherenceKind::SquaredCoherence).unwrap();
    assert!((g.squared_coherence(0.4) - 0.41).abs() < EXACT);
    assert!((g.coherence_amplitude(0.4) - 0.41f64.sqrt()).abs() < EXACT);
    assert_eq!(g.squared_coherence(0.0), 0.81, "held below the table");
    // errors name the entry, the value and the reason
    let e = TabulatedCoherence::new(
        vec![0.0, 0.2, 0.1],
        vec![1.0, 0.5, 0.4],
        CoherenceKind::SquaredCoherence,
    )
    .unwrap_err()
    .to_string();
    assert!(
        e.contains("n[2]") && e.contains("0.1") && e.contains("ascending"),
        "{e}"
    );
    let e = TabulatedCoherence::new(vec![0.0, 0.2], vec![1.0, f64::NAN], CoherenceKind::SquaredCoherence)
        .unwrap_err()
        .to_string();
    assert!(e.contains("squared_coherence[1]") && e.contains("NaN"), "{e}");
    let e = TabulatedCoherence::new(vec![0.0, 0.2], vec![1.0, -0.1], CoherenceKind::CoherenceAmplitude)
        .unwrap_err()
        .to_string();
    assert!(e.contains("coherence_amplitude[1]") && e.contains("[0, 1]"), "{e}");
    assert!(TabulatedCoherence::new(vec![0.0], vec![1.0], CoherenceKind::SquaredCoherence).is_err());
    assert!(TabulatedCoherence::new(vec![0.0, 1.0], vec![1.0], CoherenceKind::SquaredCoherence).is_err());
}

#[test]
fn coherence_kind_keys_and_constant_model() {
    assert_eq!(
        "squared_coherence".parse::<CoherenceKind>().unwrap(),
        CoherenceKind::SquaredCoherence
    );
    assert_eq!(
        "coherence_amplitude".parse::<CoherenceKind>().unwrap(),
        CoherenceKind::CoherenceAmplitude
    );
    let e = "coherence".parse::<CoherenceKind>().unwrap_err().to_string();
    assert!(e.contains("ambiguous"), "{e}");
    let c = ConstantCoherence::new(0.3).unwrap();
    assert_eq!(c.coherence_amplitude(0.7), 0.3);
    assert!((c.squared_coherence(0.7) - 0.09).abs() < EXACT);
    assert!(ConstantCoherence::new(-0.1).is_err());
    assert!(ConstantCoherence::new(f64::NAN).is_err());
}
