//! Textbook chapter 8 models (Sukharev 2012, 8.5–8.7): balancer bogie, conveyor idler, scraper.
//!
//! Every expected value is an independent derivation (closed form vs numerical route vs Lyapunov, written
//! out in each test's comments and in the model's `# Formula` docs) or a value recomputed outside the crate
//! from the printed formulas (the comment says how); none is copied from running the code under test.

use crate::common;
use common::rel;
use common::tolerance::{
    CONDITIONED, EXACT, FACTORISATION, PRINTED_5_DIGITS, PRINTED_6_DIGITS, PRINTED_7_DIGITS, QUADRATURE, QUASI_STATIC,
};
use nalgebra::{Complex, DMatrix};
use std::f64::consts::PI;
use std::path::Path;
use std::sync::Arc;
use stochvib::fields::Fields;
use stochvib::linalg::solve_continuous_lyapunov;
use stochvib::models::balancer_bogie::{self, sweep, BalancerBogie};
use stochvib::models::conveyor_idler::{self, ConveyorIdler, LumpLoad};
use stochvib::models::scraper::{self, book_road_8_66, book_road_8_69, respond, ScraperRigidCab, ScraperSprungCab};
use stochvib::models::worked_example::{BookRow, EXPLAIN_ABOVE};
use stochvib::models::InputLayout;
use stochvib::response::{analyze_output, variance_integral_table, variance_lyapunov, variance_quadrature, Excitation};
use stochvib::scenario::load_spectrum;
use stochvib::spectrum::{two_pole_road::Form, AtSpeed, Domain, Exponential, RationalSpectrum, Spectrum, TwoPoleRoad};
use stochvib::Error;

// ------------------------------------------------------------------------------------------------
// Balancer bogie (8.5)

/// Book road (8.45): α = 0.035 1/cm = 3.5 1/m, D_x = 2.25 cm².
const ALPHA: f64 = 3.5;
const DX: f64 = 2.25e-4;

/// Closed form (8.47)–(8.49) (residues) against the general numerical route (2-input system in time,
/// road at speed, rear wheel delayed by ℓ/v, adaptive quadrature): different methods.
#[test]
fn bogie_closed_form_vs_quadrature_route() {
    let road: Arc<dyn Spectrum> = Arc::new(Exponential::new(DX, ALPHA, Domain::Spatial).unwrap());
    for (r, l, l1) in [
        (0.11, 0.6, 0.3),
        (0.15, 0.6, 0.3),
        (0.05, 1.2, 0.4),
        (0.3, 0.4, 0.1),
        (1.0 / 14.0, 0.6, 0.2),
    ] {
        let b = BalancerBogie { r, ell: l, ell1: l1 }.build().unwrap();
        let c = b.closed_form(DX, ALPHA).unwrap();
        let (dy, dx) = b.variance_numerical(road.clone(), 5.0).unwrap();
        assert!(rel(dx, DX) < EXACT);
        assert!(
            rel(dy, c.dy) < QUADRATURE,
            "r={r} l={l} l1={l1}: quad {dy} vs closed {}",
            c.dy
        );
    }
}

/// In time at speed v the wheel filter is 1/(1 + 4rs/v) and the delay ℓ/v; substituting ω = vλ in the
/// variance integral removes v entirely, so σ_y cannot depend on v.
#[test]
fn bogie_sigma_independent_of_speed() {
    let road: Arc<dyn Spectrum> = Arc::new(Exponential::new(DX, ALPHA, Domain::Spatial).unwrap());
    let b = BalancerBogie {
        r: 0.11,
        ell: 0.6,
        ell1: 0.3,
    }
    .build()
    .unwrap();
    let (d1, _) = b.variance_numerical(road.clone(), 1.0).unwrap();
    for v in [0.3, 7.0, 40.0] {
        let (dv, _) = b.variance_numerical(road.clone(), v).unwrap();
        assert!(rel(dv, d1) < QUADRATURE, "v = {v}: {dv} vs {d1}");
    }
}

/// The general route with a non-type-1 road: the consistent two-pole road (8.66) has
/// K = D(βe^{−α|s|} − αe^{−β|s|})/(β − α), a linear combination of two type-1 roads, and D_y is linear in
/// the road spectrum: D_y = [β·D_y(type 1, α) − α·D_y(type 1, β)]/(β − α) from the closed form (8.49).
#[test]
fn bogie_general_road_by_superposition() {
    let (a, bb, d) = (3.5, 20.0, 1.0e-4);
    let road: Arc<dyn Spectrum> = Arc::new(
        TwoPoleRoad {
            dq: d,
            alpha: a,
            beta: bb,
            form: Form::Consistent,
        }
        .build()
        .unwrap(),
    );
    let b = BalancerBogie {
        r: 0.11,
        ell: 0.6,
        ell1: 0.25,
    }
    .build()
    .unwrap();
    let expected = (bb * b.closed_form(d, a).unwrap().dy - a * b.closed_form(d, bb).unwrap().dy) / (bb - a);
    let (dy, _) = b.variance_numerical(road, 3.0).unwrap();
    assert!(rel(dy, expected) < QUADRATURE, "{dy} vs {expected}");
}

/// Book example (ℓ = 60 cm, ℓ₁ = 30 cm, α = 3.5 1/m) recomputed outside the crate with numpy from (8.47),
/// (8.48), (8.40), and again by scipy.integrate.quad of 2∫₀^∞ S_x|W|²(1, cos λℓ)dλ (agree to 1e-6 relative);
/// to 7 digits (Python, the same formulas: D_Z/D_x = 1/(1 + 4αr), R_Z/D_x = (e^{−αℓ} − 4αr e^{−ℓ/(4r)})/(1 −
/// 16α²r²), D_y/D_x = (D_Z + R_Z)/(2D_x) for ℓ₁ = ℓ/2): D_Z/D_x = 0.3937008, R_Z/D_x = 0.1978467, D_y/D_x =
/// 0.2957737 (r = 11 cm); 0.3225806, 0.1906423, 0.2566115 (r = 15 cm); σ_y/σ_x = 0.5438508, 0.5065684 (both
/// fail).
#[test]
fn bogie_book_example_recomputed() {
    for (r, dz, rz, dy, s) in [
        (0.11, 0.3937008, 0.1978467, 0.2957737, 0.5438508),
        (0.15, 0.3225806, 0.1906423, 0.2566115, 0.5065684),
    ] {
        let c = BalancerBogie { r, ell: 0.6, ell1: 0.3 }
            .build()
            .unwrap()
            .closed_form(DX, ALPHA)
            .unwrap();
        assert!(rel(c.dz / DX, dz) < PRINTED_7_DIGITS);
        assert!(rel(c.rz / DX, rz) < PRINTED_7_DIGITS);
        assert!(rel(c.dy / DX, dy) < PRINTED_7_DIGITS);
        assert!(rel(c.sigma_ratio, s) < PRINTED_7_DIGITS);
        assert!(!c.passes);
    }
}

/// R_Z/D_x of the bogie of wheel radius `r` and base `l` (m) on the road of α = [`ALPHA`].
fn rz_ratio(r: f64, l: f64) -> f64 {
    BalancerBogie { r, ell: l, ell1: 0.0 }.rz_ratio(ALPHA)
}

/// The stable R_Z form equals the printed (8.48) away from 4αr = 1 (no cancellation there).
#[test]
fn bogie_rz_matches_printed_formula() {
    for (r, l) in [(0.11, 0.6), (0.15, 0.6), (0.02, 0.3), (0.5, 2.0)] {
        let q = 4.0 * ALPHA * r;
        let printed = ((-ALPHA * l).exp() - q * (-l / (4.0 * r)).exp()) / (1.0 - q * q);
        assert!(rel(rz_ratio(r, l), printed) < EXACT, "r = {r}");
    }
}

/// Removable singularity at 4αr = 1: limit R_Z → D_x(1 + αℓ)e^{−αℓ}/2 (L'Hôpital in b = 1/(4r) on (8.48)
/// written as D_x b(b e^{−αℓ} − α e^{−bℓ})/(b² − α²): d/db of numerator and denominator at b = α gives
/// D_x α(e^{−αℓ} + αℓ e^{−αℓ})/(2α)).
/// dR_Z/dε is bounded (R_Z is analytic in b), so at ε = ±1e-9 the distance to the limit is ≤ 10·ε·D_x.
#[test]
fn bogie_singularity_continuity() {
    let l = 0.6;
    let limit = (1.0 + ALPHA * l) * (-ALPHA * l).exp() / 2.0;
    let r0 = 1.0 / (4.0 * ALPHA);
    let eps_max = 1e-9;
    for eps in [-eps_max, 0.0, eps_max] {
        let r = r0 * (1.0 + eps);
        let v = rz_ratio(r, l);
        assert!(v.is_finite());
        assert!((v - limit).abs() <= 10.0 * eps_max, "eps {eps}: {v} vs {limit}");
    }
    // and the numerical route agrees at the singular point itself
    let road: Arc<dyn Spectrum> = Arc::new(Exponential::new(DX, ALPHA, Domain::Spatial).unwrap());
    let b = BalancerBogie {
        r: r0,
        ell: l,
        ell1: 0.3,
    }
    .build()
    .unwrap();
    let (dy, _) = b.variance_numerical(road, 2.0).unwrap();
    assert!(rel(dy, b.closed_form(DX, ALPHA).unwrap().dy) < QUADRATURE);
}

/// Limits: r → 0 gives D_Z → D_x, R_Z → D_x e^{−αℓ} (errors O(αr): set 4αr → 0 in (8.47), (8.48)); ℓ₁ ∈ {0, ℓ}
/// gives D_y = D_Z exactly (one wheel carries the pivot: (8.40) reduces to ℓ²D_Z/ℓ²).
#[test]
fn bogie_limits() {
    let r = 1e-9;
    let c = BalancerBogie { r, ell: 0.6, ell1: 0.3 }
        .build()
        .unwrap()
        .closed_form(DX, ALPHA)
        .unwrap();
    assert!((c.dz / DX - 1.0).abs() <= 4.0 * ALPHA * r);
    assert!((c.rz / DX - (-ALPHA * 0.6).exp()).abs() <= 8.0 * ALPHA * r);
    let road: Arc<dyn Spectrum> = Arc::new(Exponential::new(DX, ALPHA, Domain::Spatial).unwrap());
    for l1 in [0.0, 0.6] {
        let b = BalancerBogie {
            r: 0.11,
            ell: 0.6,
            ell1: l1,
        }
        .build()
        .unwrap();
        let c = b.closed_form(DX, ALPHA).unwrap();
        assert!(rel(c.dy, c.dz) < EXACT);
        assert!(rel(c.dz, DX / (1.0 + 4.0 * ALPHA * 0.11)) < EXACT);
        let (dy, _) = b.variance_numerical(road.clone(), 4.0).unwrap();
        assert!(rel(dy, c.dz) < QUADRATURE);
    }
}

#[test]
fn bogie_instance_layout_and_sweep() {
    let m = BalancerBogie {
        r: 0.11,
        ell: 0.6,
        ell1: 0.3,
    }
    .build()
    .unwrap()
    .instance(10.0)
    .unwrap();
    assert_eq!(
        m.layout,
        InputLayout::Track {
            positions: vec![0.0, 0.6],
            gains: vec![1.0, 1.0]
        }
    );
    // W(s) = 1/(1 + 4rs/v): |W|² = 1/2 at ω = v/(4r); y = ½(z₁ + z₂) → static gain ½ per wheel
    let h = m.system.response(10.0 / 0.44);
    assert!((h[(1, 0)].norm_sqr() - 0.5).abs() < EXACT);
    assert!((m.system.static_gain().unwrap()[(0, 1)] - 0.5).abs() < EXACT);
    let s = sweep(ALPHA, &[0.11, 0.15], &[0.6, 1.0], &[0.0, 0.5]).unwrap();
    assert_eq!(s.len(), 8);
    for p in &s {
        let c = BalancerBogie {
            r: p.r,
            ell: p.ell,
            ell1: p.ell1,
        }
        .build()
        .unwrap()
        .closed_form(1.0, ALPHA)
        .unwrap();
        assert!(rel(p.ratio, c.dy) < EXACT);
    }
    assert!(sweep(ALPHA, &[0.1], &[0.6], &[1.5]).is_err());
    assert!(BalancerBogie {
        r: 0.1,
        ell: 0.6,
        ell1: 0.7
    }
    .build()
    .is_err());
    assert!(BalancerBogie {
        r: -0.1,
        ell: 0.6,
        ell1: 0.3
    }
    .build()
    .is_err());
}

// ------------------------------------------------------------------------------------------------
// Conveyor idler (8.6, Example 8.1)

/// Exact σ_y² closed form (derived by hand with the I₃ entry of the integral table for
/// |H|²S_x = αD_x/(π|(iω)³ + (α + 2ζω₀)(iω)² + (ω₀² + 2αζω₀)iω + αω₀²|²)):
/// D_x(α + 2ζω₀)/(2ζω₀³(ω₀² + α² + 2αζω₀)).
fn idler_exact_variance(m: f64, c: f64, zeta: f64, df: f64, a: f64) -> f64 {
    let w0 = (c / m).sqrt();
    df / (m * m) * (a + 2.0 * zeta * w0) / (2.0 * zeta * w0.powi(3) * (w0 * w0 + a * a + 2.0 * a * zeta * w0))
}

/// The instance through all three variance methods against the closed form; mean M_F/c (8.59);
/// velocity variance D_x α/(2ζω₀(ω₀² + α² + 2αζω₀)) (same I₃ entry with the numerator ω², derived by hand).
#[test]
fn idler_three_methods_vs_closed_form() {
    for (m, c, zeta, df, a, mf) in [
        (100.0, 7.0e4, 0.2, 4.0e6, 0.5, 1.0e4),
        (100.0, 7.0e4, 0.2, 4.0e6, 40.0, 0.0),
        (20.0, 5.0e3, 0.05, 1.0, 3.0, 2.0),
    ] {
        let idler = ConveyorIdler { m, c, b: 0.0 }.with_damping_ratio(zeta).unwrap();
        let inst = idler.instance().unwrap();
        assert_eq!(inst.layout, InputLayout::Single);
        let load: Arc<dyn Spectrum> = Arc::new(Exponential::new(df, a, Domain::Temporal).unwrap());
        let exc = Excitation::single(load, mf).unwrap();
        let sys = inst.system.as_ref();
        let expected = idler_exact_variance(m, c, zeta, df, a);
        let l = variance_lyapunov(sys, &exc, 0).unwrap();
        assert!(
            rel(l.variance, expected) < FACTORISATION,
            "lyap {} vs {expected}",
            l.variance
        );
        let t = variance_integral_table(sys, &exc, 0, 0).unwrap();
        assert!(rel(t, expected) < FACTORISATION, "table {t} vs {expected}");
        let q = variance_quadrature(sys, &exc, 0).unwrap();
        assert!(rel(q.value, expected) < QUADRATURE, "quad {} vs {expected}", q.value);
        let st = analyze_output(sys, &exc, 0).unwrap();
        assert!(rel(st.mean.unwrap(), mf / c) < EXACT || mf == 0.0);
        let w0 = (c / m).sqrt();
        let vel = df / (m * m) * a / (2.0 * zeta * w0 * (w0 * w0 + a * a + 2.0 * a * zeta * w0));
        let lv = variance_lyapunov(sys, &exc, 1).unwrap();
        assert!(rel(lv.variance, vel) < FACTORISATION);
        // the model's own closed form
        let r = idler.analyse(
            &LumpLoad {
                mean: mf,
                variance: df,
                alpha: a,
            }
            .build()
            .unwrap(),
        );
        assert!(rel(r.sigma_exact.powi(2), expected) < EXACT);
        assert!(rel(r.sigma_velocity_exact.powi(2), vel) < EXACT);
    }
}

/// Independent Lyapunov check of Example 8.1 on the hand-built state [y, ẏ, f]:
/// A = [[0,1,0],[−ω₀²,−2ζω₀,1],[0,0,−α]], B = [0,0,√(2αD_x)]ᵀ. Recomputed outside the crate with
/// scipy.linalg.solve_continuous_lyapunov(A, −BBᵀ) (m = 100, c = 7e4, ζ = 0.2, D_F = 4e6, α = 0.5):
/// σ_y² = 8.48180e−4 m² (= the closed form), σ_y = 0.0291235 m, white-noise σ_y = √(πS_x(ω₀)/(2ζω₀³)) =
/// 0.0062092 m, exact/white ratio 21.9998, a* = M_F/c + 3σ_y = 0.230228 m.
#[test]
fn idler_example_8_1() {
    let (m, c, zeta, df, a): (f64, f64, f64, f64, f64) = (100.0, 7.0e4, 0.2, 4.0e6, 0.5);
    let w0 = (c / m).sqrt();
    let dx = df / (m * m);
    let am = DMatrix::from_row_slice(3, 3, &[0.0, 1.0, 0.0, -w0 * w0, -2.0 * zeta * w0, 1.0, 0.0, 0.0, -a]);
    let b = DMatrix::from_row_slice(3, 1, &[0.0, 0.0, (2.0 * a * dx).sqrt()]);
    let p = solve_continuous_lyapunov(&am, &(&b * b.transpose())).unwrap();
    let r = ConveyorIdler { m, c, b: 0.0 }
        .with_damping_ratio(zeta)
        .unwrap()
        .analyse(
            &LumpLoad {
                mean: 1.0e4,
                variance: df,
                alpha: a,
            }
            .build()
            .unwrap(),
        );
    assert!(rel(r.sigma_exact.powi(2), p[(0, 0)]) < FACTORISATION);
    assert!(rel(r.sigma_exact.powi(2), 8.48180e-4) < PRINTED_6_DIGITS);
    assert!(rel(r.sigma_exact, 0.0291235) < PRINTED_6_DIGITS);
    assert!(rel(r.sigma_white_noise, 0.0062092) < PRINTED_5_DIGITS);
    assert!(rel(r.a_star_exact, 0.230228) < PRINTED_6_DIGITS);
    assert!((r.mean_y - 1.0e4 / 7.0e4).abs() < EXACT);
    assert!(rel(r.variance_ratio, 21.9998) < PRINTED_6_DIGITS);
    assert!(r.approximation_poor);
    let w = r.warning.unwrap();
    assert!(w.contains("invalid") && w.contains("α"), "{w}");
}

/// The lump load of mean 0 and variance 1 whose correlation decays at the rate `alpha` (1/s).
fn unit_load(alpha: f64) -> LumpLoad {
    LumpLoad {
        mean: 0.0,
        variance: 1.0,
        alpha,
    }
    .build()
    .unwrap()
}

/// Ratio formula (exact closed form above divided by the white-noise πS_x(ω₀)/(2ζω₀³), S_x(ω₀) =
/// αD_x/(π(α² + ω₀²))): exact/white = (α + 2ζω₀)(α² + ω₀²)/(α(ω₀² + α² + 2αζω₀)); it equals the
/// quotient of the two variances (8.62 with two-sided S_x(ω₀)) and tends to 1 as α → ∞ (flat input) and
/// to the quasi-static D_x/ω₀⁴ as α → 0.
#[test]
fn idler_ratio_formula_and_limits() {
    let (m, c, zeta): (f64, f64, f64) = (100.0, 7.0e4, 0.2);
    let w0 = (c / m).sqrt();
    let idler = ConveyorIdler { m, c, b: 0.0 }.with_damping_ratio(zeta).unwrap();
    for a in [0.01, 0.5, 10.0, 1e3, 1e6] {
        let r = idler.analyse(&unit_load(a));
        let ratio = (a + 2.0 * zeta * w0) * (a * a + w0 * w0) / (a * (w0 * w0 + a * a + 2.0 * a * zeta * w0));
        assert!(rel(r.variance_ratio, ratio) < EXACT);
        assert!(rel(r.sigma_exact.powi(2) / r.sigma_white_noise.powi(2), ratio) < EXACT);
        assert_eq!(
            r.approximation_poor,
            (ratio - 1.0).abs() > conveyor_idler::APPROXIMATION_TOLERANCE
        );
    }
    // α → ∞: with x = 2ζω₀/α, y = ω₀²/α² the ratio is (1 + x)(1 + y)/(1 + x + y) = 1 + xy/(1 + x + y), so
    // 0 < ratio − 1 < xy = 2ζω₀³/α³ (≈ 7e-15 at α = 1e6), plus the rounding of the two variances
    let a = 1e6;
    let r = idler.analyse(&unit_load(a));
    assert!((r.variance_ratio - 1.0).abs() < 2.0 * zeta * w0.powi(3) / a.powi(3) + EXACT && !r.approximation_poor);
    // α → 0: σ_y² → D_x/ω₀⁴ with relative error O(α/(ζω₀))
    let a = 1e-6;
    let r = idler.analyse(&unit_load(a));
    let qs = 1.0 / (m * m) / w0.powi(4);
    assert!(rel(r.sigma_exact.powi(2), qs) < 10.0 * a / (zeta * w0));
}

// ------------------------------------------------------------------------------------------------
// Scraper (8.7)

/// The sprung-cab scraper (8.7) that three tests below share: m₁ = 30 t, c₁ = 10 MN/m, b₁ = 110 kN s/m,
/// m₂ = 2 t, c₂ = 180 kN/m, b₂ = 11 kN s/m.
fn sprung_cab() -> stochvib::models::ModelInstance {
    ScraperSprungCab {
        m1: 3.0e4,
        c1: 1.0e7,
        b1: 1.1e5,
        m2: 2.0e3,
        c2: 1.8e5,
        b2: 1.1e4,
    }
    .build()
    .unwrap()
    .instance()
    .unwrap()
}

fn rigid(w0: f64, zeta: f64) -> ScraperRigidCab {
    let m1 = 3.0e4;
    let c1 = m1 * w0 * w0;
    ScraperRigidCab {
        m1,
        c1,
        b1: 2.0 * zeta * (c1 * m1).sqrt(),
    }
    .build()
    .unwrap()
}

/// Rigid cab with b₁ > 0 under (8.69) (type 1, density ∝ ω⁻²): |H_ẍ1|² ∝ ω², so the acceleration variance
/// is infinite (|H_ẍ1|²S ∝ ω²·ω⁻² → const as ω → ∞, so ∫dω diverges): the model's outputs must route into
/// Error::Divergent. The printed (8.66) form (also ∝ ω⁻²) diverges the same way.
#[test]
fn scraper_rigid_acceleration_divergence() {
    let inst = rigid(18.5, 0.1).instance().unwrap();
    let stats = respond(&inst, book_road_8_69(), 10.0).unwrap();
    let acc = stats.iter().find(|s| s.name == "x1_acc").unwrap();
    assert!(acc.sigma.is_none());
    assert!(acc.variance_outcome.is_divergent() && acc.variance_outcome.describe().contains("infinite"));
    let x1 = stats.iter().find(|s| s.name == "x1").unwrap();
    assert!(x1.sigma.is_some());
    let exc = Excitation::single(Arc::new(AtSpeed::new(book_road_8_69(), 10.0).unwrap()), 0.0).unwrap();
    assert!(matches!(
        variance_quadrature(inst.system.as_ref(), &exc, 1),
        Err(Error::Divergent { .. })
    ));
    let printed = respond(&inst, book_road_8_66(Form::AsPrinted).unwrap(), 10.0).unwrap();
    assert!(printed[1].sigma.is_none());
    // the sprung cab's acceleration stays finite under (8.69) (|H_ẍ2|² → const, road ∝ ω⁻²) while x1_acc
    // diverges as for the rigid cab
    let s = sprung_cab();
    let st = respond(&s, book_road_8_69(), 10.0).unwrap();
    assert!(st[2].sigma.is_none() && st[3].sigma.is_some());
}

/// White road into the rigid cab (derived by hand with the I₂ entry of the integral table for
/// H = (b₁iω + c₁)/(m₁(iω)² + b₁iω + c₁)): σ_x1² = πS₀(b₁² + c₁m₁)/(b₁m₁) for two-sided
/// white level S₀; Lyapunov, integral table and (for this ω⁻² integrand) quadrature all agree.
#[test]
fn scraper_rigid_white_road_closed_form() {
    let s = rigid(17.0, 0.15);
    let (m1, w0, z): (f64, f64, f64) = (3.0e4, 17.0, 0.15);
    let c1 = m1 * w0 * w0;
    let b1 = 2.0 * z * (c1 * m1).sqrt();
    let s0 = 2.5e-5;
    let inst = s.instance().unwrap();
    let white: Arc<dyn Spectrum> = Arc::new(RationalSpectrum::new(vec![s0], vec![1.0], Domain::Temporal).unwrap());
    let exc = Excitation::single(white, 0.0).unwrap();
    let expected = PI * s0 * (b1 * b1 + c1 * m1) / (b1 * m1);
    let sys = inst.system.as_ref();
    assert!(rel(variance_lyapunov(sys, &exc, 0).unwrap().variance, expected) < FACTORISATION);
    assert!(rel(variance_integral_table(sys, &exc, 0, 0).unwrap(), expected) < FACTORISATION);
    assert!(rel(variance_quadrature(sys, &exc, 0).unwrap().value, expected) < QUADRATURE);
}

/// Consistent (8.66) road at 10 m/s: Lyapunov (exact, 4 states) vs quadrature, displacement and
/// acceleration of the rigid cab and the sprung cab's outputs (all finite for the ω⁻⁴ road).
#[test]
fn scraper_consistent_road_methods_agree() {
    let road = AtSpeed::new(book_road_8_66(Form::Consistent).unwrap(), 10.0).unwrap();
    let exc = Excitation::single(Arc::new(road), 0.0).unwrap();
    let r = rigid(18.5, 0.1).instance().unwrap();
    let s = sprung_cab();
    for inst in [&r, &s] {
        let sys = inst.system.as_ref();
        for i in 0..sys.outputs().len() {
            let l = variance_lyapunov(sys, &exc, i).unwrap().variance;
            let q = variance_quadrature(sys, &exc, i).unwrap().value;
            assert!(rel(l, q) < QUADRATURE, "{}: lyap {l} quad {q}", sys.outputs()[i].name);
        }
    }
}

/// Sprung-cab frequency response against the explicit 2×2 solve of (8.65) (Cramer's rule on
/// [[k₁ + k₂ − m₁ω², −k₂], [−k₂, k₂ − m₂ω²]]·(x₁, x₂) = (k₁, 0), k_i = c_i + iωb_i, Δ its determinant):
/// H_x1 = k₁(k₂ − m₂ω²)/Δ, H_x2 = H_x1 k₂/(k₂ − m₂ω²), H_ẍ = −ω²H, travel = H_x2 − H_x1.
#[test]
fn scraper_sprung_response_explicit() {
    let (m1, c1, b1, m2, c2, b2) = (3.0e4, 1.0e7, 1.1e5, 2.0e3, 1.8e5, 1.1e4);
    let inst = ScraperSprungCab { m1, c1, b1, m2, c2, b2 }
        .build()
        .unwrap()
        .instance()
        .unwrap();
    for w in [0.3, 5.0, 9.4, 18.0, 120.0] {
        let k1 = Complex::new(c1, b1 * w);
        let k2 = Complex::new(c2, b2 * w);
        let d22 = k2 - m2 * w * w;
        let det = (k1 + k2 - m1 * w * w) * d22 - k2 * k2;
        let x1 = k1 * d22 / det;
        let x2 = x1 * k2 / d22;
        let h = inst.system.response(w);
        let expect = [x1, x2, x1 * (-w * w), x2 * (-w * w), x2 - x1];
        for (i, e) in expect.iter().enumerate() {
            assert!(
                (h[(i, 0)] - e).norm() <= CONDITIONED * e.norm().max(1e-300),
                "w={w} output {i}"
            );
        }
    }
}

/// Quasi-static limit: as v → 0 all road power lies far below ω₀, where H_x1, H_x2 → 1 (the static gain of
/// base motion), so σ_x1², σ_x2² → ∫S_q = D_q, i.e. σ → √D_q
/// = 3.5 cm and σ_ẍ → 0 like v^{3/2}; at v = 0.01 m/s the temporal corner β v = 0.12 rad/s gives errors O((βv/ω₀)²).
#[test]
fn scraper_quasi_static_limit() {
    let s = sprung_cab();
    let stats = respond(&s, book_road_8_66(Form::Consistent).unwrap(), 0.01).unwrap();
    assert!(rel(stats[0].sigma.unwrap(), 0.035) < QUASI_STATIC);
    assert!(rel(stats[1].sigma.unwrap(), 0.035) < QUASI_STATIC);
    // σ_ẍ2 → 0: for ω ≫ βv the road density is D_q αβ(α+β)v³/(πω⁴), so σ_ẍ2² = v³·D_q αβ(α+β)/π ·
    // ∫|H_x2|²dω (1 + O((βv/ω₂)²)): halving v divides σ_ẍ2 by 2^{3/2}
    let half = respond(&s, book_road_8_66(Form::Consistent).unwrap(), 0.005).unwrap();
    let ratio = stats[3].sigma.unwrap() / half[3].sigma.unwrap();
    assert!(rel(ratio, 2f64.powf(1.5)) < QUASI_STATIC, "{ratio}");
}

/// data/reference/table-8-1.toml holds the printed values of Sukharev (2012) 8.7, Table 8.1 exactly.
#[test]
fn scraper_table_8_1_transcription() {
    let (speeds, rows) = scraper::table_8_1().unwrap();
    assert_eq!(speeds, vec![5.0, 10.0, 15.0]);
    let got: Vec<(&str, &str, &str, Vec<f64>)> = rows
        .iter()
        .map(|r| (r.cab.as_str(), r.output.as_str(), r.unit.as_str(), r.values.clone()))
        .collect();
    assert_eq!(
        got,
        vec![
            ("rigid", "x1", "cm", vec![3.0, 4.0, 4.6]),
            ("rigid", "x1_acc", "m/s^2", vec![6.0, 8.0, 10.0]),
            ("sprung", "x2", "cm", vec![1.0, 2.0, 2.5]),
            ("sprung", "x2_acc", "m/s^2", vec![3.0, 4.5, 5.6]),
        ]
    );
    // every printed cell has a row (plus the cab-travel reading of σ_x2)
    assert_eq!(scraper::book_rows().len(), 12 + 3);
}

// ------------------------------------------------------------------------------------------------
// Book rows and scenario reading

fn check_rows(rows: &[BookRow], n_min: usize) {
    assert!(rows.len() >= n_min);
    for r in rows {
        if let Some(d) = r.rel_diff()
            && d.abs() > EXPLAIN_ABOVE
        {
            assert!(!r.explanation.trim().is_empty(), "{} lacks an explanation", r.quantity);
        }
        if r.computed.is_none() {
            assert!(!r.explanation.trim().is_empty());
        }
    }
}

#[test]
fn book_rows_explained() {
    check_rows(&balancer_bogie::book_rows(), 2);
    check_rows(&conveyor_idler::book_rows(), 7);
    check_rows(&scraper::book_rows(), 12);
    // the computed values come from the code: Example 8.1 exact σ is the closed form above
    let rows = conveyor_idler::book_rows();
    let exact = rows.iter().find(|r| r.quantity == "sigma_y exact").unwrap();
    assert!(
        rel(
            exact.computed.unwrap(),
            idler_exact_variance(100.0, 7.0e4, 0.2, 4.0e6, 0.5).sqrt()
        ) < EXACT
    );
    assert!(exact.explanation.starts_with("white-noise approximation invalid"));
}

fn model_table(path: &str) -> toml::Table {
    let text = std::fs::read_to_string(crate::common::root().join(path)).unwrap();
    let t: toml::Table = toml::from_str(&text).unwrap();
    t["model"].as_table().unwrap().clone()
}

/// The `[model]` tables of the four scenario files build their instances, every key is consumed, and
/// the values are the documented ones.
#[test]
fn scenario_model_tables() {
    let read = |file: &str, f: &dyn Fn(&Fields) -> stochvib::Result<stochvib::models::ModelInstance>| {
        let mut t = model_table(file);
        t.remove("kind");
        let fields = Fields::new(Path::new(file), "model", &t);
        let inst = f(&fields).unwrap();
        fields.finish().unwrap();
        inst
    };
    let b = read("data/balancer-bogie.toml", &|f| {
        balancer_bogie::from_fields(f, Some(5.0))
    });
    assert_eq!(b.system.n_inputs(), 2);
    let c = read("data/conveyor-idler.toml", &conveyor_idler::from_fields);
    // static compliance 1/c = 1/70 kN/m
    assert!(rel(c.system.static_gain().unwrap()[(0, 0)], 1.0 / 7.0e4) < EXACT);
    let r = read("data/scraper-rigid-cab.toml", &scraper::rigid_from_fields);
    // underdamped poles have modulus ω₀ = √(c₁/m₁) = 18.5 rad/s (omega1 in the file)
    assert!(rel(r.system.natural_frequencies()[0], 18.5) < FACTORISATION);
    let s = read("data/scraper-sprung-cab.toml", &scraper::sprung_from_fields);
    assert_eq!(s.system.outputs().len(), 5);
    // bad input: missing key and conflicting keys name the key
    let mut t = model_table("data/conveyor-idler.toml");
    t.remove("kind");
    t.remove("m");
    let e = conveyor_idler::from_fields(&Fields::new(Path::new("x.toml"), "model", &t)).unwrap_err();
    assert!(e.to_string().contains("model.m"), "{e}");
    let mut t = model_table("data/conveyor-idler.toml");
    t.insert("b".into(), toml::Value::String("1 kN s/m".into()));
    let e = conveyor_idler::from_fields(&Fields::new(Path::new("x.toml"), "model", &t)).unwrap_err();
    assert!(e.to_string().contains("not both"), "{e}");
}

/// spectra/conveyor-lump-load.toml: σ_F = 2 kN (D_F = 4e6 N²), α = 0.5 1/s, temporal, unit N
/// (Sukharev (2012) 8.6, Example 8.1, problem data).
#[test]
fn conveyor_lump_load_spectrum_file() {
    let s = load_spectrum(&crate::common::root().join("spectra/conveyor-lump-load.toml")).unwrap();
    assert_eq!(s.unit, "N");
    assert_eq!(s.spectrum.domain(), Domain::Temporal);
    assert!(rel(s.spectrum.variance().unwrap(), 4.0e6) < EXACT);
    // type 1: S(0) = D/(πα)
    assert!(rel(s.spectrum.density(0.0), 4.0e6 / (PI * 0.5)) < EXACT);
}
