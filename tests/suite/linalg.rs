//! Cross-checks of the public `stochvib::linalg` API: the three routes to a variance (integral
//! table, Lyapunov equation, closed forms), the spectral-factorisation pipeline for rational spectra,
//! and scaling laws of Iₙ as property tests.

use crate::common;
use common::rel;
use common::tolerance::{CONDITIONED, EXACT, FACTORISATION, RESIDUAL, ROUNDING, SMALL_DECOMPOSITION, ULPS};
use nalgebra::{Complex, DMatrix};
use proptest::prelude::*;
use std::f64::consts::PI;
use stochvib::linalg::poly::{eval_complex, from_roots, mul, roots};
use stochvib::linalg::{
    h2_integral, integral_closed_form, integral_i_n, is_hurwitz, solve_continuous_lyapunov,
    solve_continuous_lyapunov_dense, spectral_factor,
};

/// m ẍ + c ẋ + k x = f(t), f white with two-sided density S₀ (E[f(t)f(t')] = 2π S₀ δ(t − t')).
/// Var x = S₀ ∫|H|² dω = π S₀/(kc) and Var ẋ = π S₀/(mc) (Newland); state-space route: A =
/// [[0, 1], [−k/m, −c/m]], noise on the velocity equation of intensity 2π S₀/m².
#[test]
fn sdof_variance_three_ways() {
    let (m, c, k, s0) = (3.0, 0.8, 120.0, 0.25);
    let var_x = PI * s0 / (k * c);
    let var_v = PI * s0 / (m * c);
    assert!(rel(s0 * h2_integral(&[1.0], &[k, c, m]).unwrap(), var_x) < ROUNDING);
    assert!(rel(s0 * h2_integral(&[0.0, 1.0], &[k, c, m]).unwrap(), var_v) < ROUNDING);
    assert!(rel(s0 * integral_closed_form(&[0.0, 1.0], &[k, c, m]).unwrap(), var_v) < ROUNDING);
    let a = DMatrix::from_row_slice(2, 2, &[0.0, 1.0, -k / m, -c / m]);
    let mut q = DMatrix::zeros(2, 2);
    q[(1, 1)] = 2.0 * PI * s0 / (m * m);
    let x = solve_continuous_lyapunov(&a, &q).unwrap();
    assert!(rel(x[(0, 0)], var_x) < SMALL_DECOMPOSITION);
    assert!(rel(x[(1, 1)], var_v) < SMALL_DECOMPOSITION);
    assert!(x[(0, 1)].abs() < SMALL_DECOMPOSITION * var_v);
}

/// A rational spectrum S(ω) = N(ω²)/D(ω²): factor numerator and denominator; the shaping filter
/// H = N_f/D_f (|H(iω)|² = S(ω)) gives ∫ S dω = h2_integral(N_f, D_f).
#[test]
fn rational_spectrum_pipeline() {
    // S(ω) = 1/(1 + ω²)²: ∫ S dω = π/2.
    let (nf, r1) = spectral_factor(&[1.0]).unwrap();
    let (df, r2) = spectral_factor(&[1.0, 2.0, 1.0]).unwrap();
    assert!(r1 < ULPS && r2 < RESIDUAL);
    assert!(rel(h2_integral(&nf, &df).unwrap(), PI / 2.0) < EXACT);
    // S(ω) = (1 + 4ω²) / ((4 − ω²)² + 0.16 ω²) (ζ = 0.1, ω₀ = 2) against the direct table value.
    let (nf, _) = spectral_factor(&[1.0, 4.0]).unwrap(); // 1 + 2s
    let (df, _) = spectral_factor(&[16.0, -8.0 + 0.16, 1.0]).unwrap(); // s² + 0.4 s + 4
    assert!((nf[0] - 1.0).abs() < ROUNDING && (nf[1] - 2.0).abs() < ROUNDING);
    assert!((df[1] - 0.4).abs() < SMALL_DECOMPOSITION && (df[0] - 4.0).abs() < SMALL_DECOMPOSITION);
    let v = h2_integral(&nf, &df).unwrap();
    // I₂ = π (A₀B₁² + A₂B₀²)/(A₀A₁A₂) = π (4·4 + 1)/(4·0.4·1)
    assert!(rel(v, PI * 17.0 / 1.6) < SMALL_DECOMPOSITION);
}

#[test]
fn higher_order_table_vs_lyapunov_physical_coordinates() {
    // Two-mass quarter-car-like chain: m1 x1'' = −k1 x1 − c1 x1' + k2 (x2 − x1) + c2 (x2' − x1') + f,
    // m2 x2'' = −k2 (x2 − x1) − c2 (x2' − x1'). Transfer f → x2 is c2 s + k2 over the 4th-order
    // characteristic polynomial det(M s² + C s + K).
    let (m1, m2, k1, k2, c1, c2) = (40.0, 300.0, 2.0e5, 2.0e4, 100.0, 1500.0);
    let d11 = [k1 + k2, c1 + c2, m1];
    let d22 = [k2, c2, m2];
    let off = [k2, c2];
    let den: Vec<f64> = {
        let p = mul(&d11, &d22);
        let q = mul(&off, &off);
        p.iter()
            .enumerate()
            .map(|(i, v)| v - q.get(i).copied().unwrap_or(0.0))
            .collect()
    };
    let num = [k2, c2];
    assert!(is_hurwitz(&den));
    let table = integral_i_n(&num, &den).unwrap();
    let closed = integral_closed_form(&num, &den).unwrap();
    assert!(rel(closed, table) < EXACT);
    // state x = (x1, x2, v1, v2), white force on mass 1 with E[f f'] = δ: ∫|H|² dω = 2π Var x2.
    let a = DMatrix::from_row_slice(
        4,
        4,
        &[
            0.0,
            0.0,
            1.0,
            0.0, //
            0.0,
            0.0,
            0.0,
            1.0, //
            -(k1 + k2) / m1,
            k2 / m1,
            -(c1 + c2) / m1,
            c2 / m1, //
            k2 / m2,
            -k2 / m2,
            c2 / m2,
            -c2 / m2,
        ],
    );
    let mut q = DMatrix::zeros(4, 4);
    q[(2, 2)] = 1.0 / (m1 * m1);
    let x = solve_continuous_lyapunov(&a, &q).unwrap();
    let xd = solve_continuous_lyapunov_dense(&a, &q).unwrap();
    assert!((&x - &xd).norm() < FACTORISATION * xd.norm());
    assert!(rel(2.0 * PI * x[(1, 1)], table) < FACTORISATION);
}

fn hurwitz_from(real: &[f64], pairs: &[(f64, f64)], lead: f64) -> Vec<f64> {
    let mut rts: Vec<Complex<f64>> = real.iter().map(|&p| Complex::new(-p, 0.0)).collect();
    for &(w, z) in pairs {
        let re = -z * w;
        let im = w * (1.0 - z * z).sqrt();
        rts.push(Complex::new(re, im));
        rts.push(Complex::new(re, -im));
    }
    from_roots(&rts).unwrap().iter().map(|c| c * lead).collect()
}

proptest! {
    #![proptest_config(crate::common::proptest_config(200))]

    /// Iₙ(cB, A) = c² Iₙ(B, A), Iₙ(B, cA) = Iₙ/c², and frequency scaling
    /// Bₖ → Bₖ α⁻ᵏ, Aₖ → Aₖ α⁻ᵏ (H(s) → H(s/α)) gives α Iₙ.
    #[test]
    fn scaling_laws(
        real in prop::collection::vec(0.2f64..3.0, 0..3),
        pairs in prop::collection::vec((0.3f64..3.0, 0.05f64..0.95), 0..3),
        bseed in prop::collection::vec(-2.0f64..2.0, 6),
        c in 0.2f64..5.0,
        alpha in 0.1f64..10.0,
    ) {
        prop_assume!(!real.is_empty() || !pairs.is_empty());
        let a = hurwitz_from(&real, &pairs, 1.3);
        let n = a.len() - 1;
        let b: Vec<f64> = bseed[..n].to_vec();
        prop_assume!(b.iter().any(|v| v.abs() > 0.1));
        prop_assert!(is_hurwitz(&a));
        let i0 = integral_i_n(&b, &a).unwrap();
        prop_assert!(i0 > 0.0);
        let bc: Vec<f64> = b.iter().map(|v| v * c).collect();
        prop_assert!(rel(integral_i_n(&bc, &a).unwrap(), c * c * i0) < EXACT);
        let ac: Vec<f64> = a.iter().map(|v| v * c).collect();
        prop_assert!(rel(integral_i_n(&b, &ac).unwrap(), i0 / (c * c)) < CONDITIONED);
        let bs: Vec<f64> = b.iter().enumerate().map(|(k, v)| v * alpha.powi(-(k as i32))).collect();
        let as_: Vec<f64> = a.iter().enumerate().map(|(k, v)| v * alpha.powi(-(k as i32))).collect();
        prop_assert!(rel(integral_i_n(&bs, &as_).unwrap(), alpha * i0) < FACTORISATION);
        if n <= 4 {
            prop_assert!(rel(integral_closed_form(&b, &a).unwrap(), i0) < EXACT);
        }
    }

    /// Mirroring one real root into the right half plane leaves |A(iω)|² unchanged, but A is no
    /// longer Hurwitz (the table formulas would give a wrong value), so every API must refuse it.
    #[test]
    fn mirrored_root_rejected(
        real in prop::collection::vec(0.2f64..3.0, 1..4),
        pairs in prop::collection::vec((0.3f64..3.0, 0.05f64..0.95), 0..2),
    ) {
        let mut mirrored = real.clone();
        mirrored[0] = -mirrored[0];
        let a = hurwitz_from(&mirrored, &pairs, 1.0);
        prop_assert!(!is_hurwitz(&a));
        prop_assert!(integral_i_n(&[1.0], &a).is_err());
        prop_assert!(h2_integral(&[1.0], &a).is_err());
        let rts = roots(&a).unwrap();
        prop_assert!(rts.iter().any(|z| z.re > 0.0));
    }

    /// Spectral factor of |F(iω)|² for random stable F: residual and root location.
    #[test]
    fn spectral_factor_round_trip(
        real in prop::collection::vec(0.2f64..3.0, 0..3),
        pairs in prop::collection::vec((0.3f64..3.0, 0.02f64..0.95), 0..2),
        lead in 0.1f64..10.0,
    ) {
        let f = hurwitz_from(&real, &pairs, lead);
        let p: Vec<f64> = {
            let fneg: Vec<f64> = f.iter().enumerate().map(|(k, c)| if k % 2 == 0 { *c } else { -c }).collect();
            let g = mul(&f, &fneg);
            (0..f.len()).map(|k| if k % 2 == 0 { g[2 * k] } else { -g[2 * k] }).collect()
        };
        let (fr, resid) = spectral_factor(&p).unwrap();
        prop_assert!(resid < RESIDUAL);
        prop_assert_eq!(fr.len(), f.len());
        for w in [0.0, 0.37, 1.0, 2.9, 11.0] {
            let s = Complex::new(0.0, w);
            let a = eval_complex(&fr, s).norm_sqr();
            let b = eval_complex(&f, s).norm_sqr();
            prop_assert!((a - b).abs() <= CONDITIONED * b.max(1e-300));
        }
    }
}
