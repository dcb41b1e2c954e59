//! Spectral densities: every closed form against independent quadrature, conversions, files, bad input.
//!
//! Provenance of expected values: the closed forms derived in each type's doc comment (Fourier pairs of
//! docs/conventions.md), ISO 8608's class definition σ² = G_d(n₀) n₀² (1/n₁ − 1/n₂) for w = 2, and the SI
//! definitions of units. No expected value is taken from running the code under test.

use crate::common;
use common::rel;
use common::tolerance::{EXACT, FACTORISATION, FOURIER, QUADRATURE, TABULATED_DENSITY, ULPS};
use proptest::prelude::*;
use std::f64::consts::PI;
use std::path::Path;
use std::sync::Arc;
use stochvib::scenario::{load_spectrum, parse_spectrum, spectrum_catalogue};
use stochvib::spectrum::two_pole_road::Form;
use stochvib::spectrum::PowerLawParameters;
use stochvib::spectrum::{
    numeric, AtSpeed, BandWhiteParameters, Convention, Domain, ExpCosine, Exponential, GaussCosineParameters, Gaussian,
    IsoBound, IsoClass, PowerLaw, RationalSpectrum, Spectrum, Tabulated, TwoPoleRoad, ISO_BAND,
};
use stochvib::Error;

/// A spectrum with its variance and correlation known in closed form (independently of the code).
struct Case {
    s: Arc<dyn Spectrum>,
    d: f64,
    k: Box<dyn Fn(f64) -> f64>,
}

fn cases() -> Vec<Case> {
    let mut v: Vec<Case> = Vec::new();
    let (d, a, b) = (2.5, 0.7, 3.0);
    v.push(Case {
        s: Arc::new(Exponential::new(d, a, Domain::Temporal).unwrap()),
        d,
        k: Box::new(move |t: f64| d * (-a * t.abs()).exp()),
    });
    v.push(Case {
        s: Arc::new(Gaussian::new(d, a, Domain::Temporal).unwrap()),
        d,
        k: Box::new(move |t: f64| d * (-a * t * t).exp()),
    });
    v.push(Case {
        s: Arc::new(
            ExpCosine {
                variance: d,
                alpha: a,
                beta: b,
                domain: Domain::Temporal,
            }
            .build()
            .unwrap(),
        ),
        d,
        k: Box::new(move |t: f64| d * (-a * t.abs()).exp() * (b * t).cos()),
    });
    v.push(Case {
        s: Arc::new(
            GaussCosineParameters {
                variance: d,
                alpha: a,
                beta: b,
                domain: Domain::Temporal,
            }
            .build()
            .unwrap(),
        ),
        d,
        k: Box::new(move |t: f64| d * (-a * t * t).exp() * (b * t).cos()),
    });
    // (8.66) consistent: K = D_q (β e^{−α|x|} − α e^{−β|x|})/(β − α)
    let (dq, al, be) = (0.035f64.powi(2), 0.3, 12.0);
    v.push(Case {
        s: Arc::new(
            TwoPoleRoad {
                dq,
                alpha: al,
                beta: be,
                form: Form::Consistent,
            }
            .build()
            .unwrap(),
        ),
        d: dq,
        k: Box::new(move |x: f64| dq * (be * (-al * x.abs()).exp() - al * (-be * x.abs()).exp()) / (be - al)),
    });
    // (8.66) as printed: one pole, D = D_q β(α+β)/(α²+β²)
    let dp = dq * be * (al + be) / (al * al + be * be);
    v.push(Case {
        s: Arc::new(
            TwoPoleRoad {
                dq,
                alpha: al,
                beta: be,
                form: Form::AsPrinted,
            }
            .build()
            .unwrap(),
        ),
        d: dp,
        k: Box::new(move |x: f64| dp * (-al * x.abs()).exp()),
    });
    // band-limited white: K = 2 S0 (sin ω2τ − sin ω1τ)/τ
    let (s0, w1, w2) = (0.3, 2.0, 9.0);
    v.push(Case {
        s: Arc::new(
            BandWhiteParameters {
                convention: Convention::TwoSidedAngular,
                level: s0,
                lo: w1,
                hi: w2,
                domain: Domain::Temporal,
            }
            .build()
            .unwrap(),
        ),
        d: 2.0 * s0 * (w2 - w1),
        k: Box::new(move |t: f64| {
            if t == 0.0 {
                2.0 * s0 * (w2 - w1)
            } else {
                2.0 * s0 * ((w2 * t).sin() - (w1 * t).sin()) / t
            }
        }),
    });
    // rational S = 1/(π(1+ω²)) ⇒ type 1 with D = 1, α = 1
    v.push(Case {
        s: Arc::new(RationalSpectrum::new(vec![1.0 / PI], vec![1.0, 1.0], Domain::Temporal).unwrap()),
        d: 1.0,
        k: Box::new(|t: f64| (-t.abs()).exp()),
    });
    // (8.69) at 10 m/s: type 1 with α v
    let road = Arc::new(Exponential::new(32e-4, 0.16, Domain::Spatial).unwrap());
    v.push(Case {
        s: Arc::new(AtSpeed::new(road, 10.0).unwrap()),
        d: 32e-4,
        k: Box::new(|t: f64| 32e-4 * (-1.6 * t.abs()).exp()),
    });
    v
}

/// ∫S dω by quadrature equals the closed-form D, and the model's own variance equals D.
#[test]
fn variance_by_quadrature_matches_closed_form() {
    for c in cases() {
        let q = numeric::variance(c.s.as_ref()).unwrap();
        assert!(
            rel(q.value, c.d) < QUADRATURE,
            "{}: quad {} vs {}",
            c.s.describe(),
            q.value,
            c.d
        );
        assert!(
            q.abs_error <= QUADRATURE * c.d,
            "{}: error estimate {}",
            c.s.describe(),
            q.abs_error
        );
        assert!(rel(c.s.variance().unwrap(), c.d) < EXACT, "{}", c.s.describe());
    }
}

/// The Fourier transform of S reproduces K(τ) at several lags, and the model's K matches the closed form.
#[test]
fn fourier_transform_of_density_reproduces_correlation() {
    for c in cases() {
        for &t in &[0.0, 0.05, 0.3, 1.0, 2.5, 7.0] {
            let expected = (c.k)(t);
            let q = numeric::correlation(c.s.as_ref(), t).unwrap();
            assert!(
                (q.value - expected).abs() < FOURIER * c.d,
                "{} at tau={t}: quad {} vs {}",
                c.s.describe(),
                q.value,
                expected
            );
            if let Ok(k) = c.s.correlation(t) {
                assert!(
                    (k - expected).abs() <= EXACT * c.d,
                    "{} at {t}: {k} vs {expected}",
                    c.s.describe()
                );
            }
        }
    }
}

/// Conversions: each convention integrates to the same variance (type 1, D = 1, α = 2):
/// ∫₀^∞ G(ω) dω = ∫₀^∞ G(f) df = (1/2π)∫Ŝ dω = D.
#[test]
fn every_convention_integrates_to_the_variance() {
    let s = Exponential::new(1.0, 2.0, Domain::Temporal).unwrap();
    let opts = stochvib::quad::QuadOptions {
        breakpoints: vec![2.0, 2.0 / (2.0 * PI)],
        ..Default::default()
    };
    for c in Convention::ALL {
        // integrate the convention's ordinate over its abscissa
        let f = |x: f64| {
            let (w, _) = c.to_canonical(x, 1.0);
            c.from_canonical(w, s.density(w)).1
        };
        let total = stochvib::quad::integrate(f, 0.0, f64::INFINITY, &opts).unwrap().value;
        let d = match c {
            Convention::TwoSidedAngular => 2.0 * total,
            Convention::OneSidedAngular | Convention::OneSidedCyclic => total,
            Convention::Engineering => 2.0 * total / (2.0 * PI),
        };
        assert!(rel(d, 1.0) < QUADRATURE, "{c}: {d}");
    }
}

/// ISO 8608 classes over the standard band: σ² = G_d(n₀) n₀² (1/n₁ − 1/n₂) (w = 2), both by the closed
/// form and by quadrature of the density; class limits are ½ and 2 × the geometric mean 16·4ᵏ·10⁻⁶ m³
/// (ISO 8608:1995 Table 1), where the standard gives them.
#[test]
fn iso_classes_rms_over_standard_band() {
    let (n1, n2) = ISO_BAND;
    for (k, class) in IsoClass::ALL.into_iter().enumerate() {
        let g0 = 16e-6 * 4f64.powi(k as i32);
        for (bound, factor) in [
            (IsoBound::Lower, 0.5),
            (IsoBound::GeometricMean, 1.0),
            (IsoBound::Upper, 2.0),
        ] {
            // ISO 8608 Table 1 gives class A no lower and class H no upper limit
            if (class == IsoClass::A && bound == IsoBound::Lower) || (class == IsoClass::H && bound == IsoBound::Upper)
            {
                assert!(PowerLaw::iso8608(class, bound, Some(ISO_BAND)).is_err());
                continue;
            }
            let s = PowerLaw::iso8608(class, bound, Some(ISO_BAND)).unwrap();
            let expected = factor * g0 * 0.01 * (1.0 / n1 - 1.0 / n2);
            assert!(rel(s.variance().unwrap(), expected) < EXACT);
            assert!(rel(numeric::variance(&s).unwrap().value, expected) < QUADRATURE);
        }
    }
    // class C: σ ≈ 9.6 mm over the band (a well-known order of magnitude for class C roads)
    let c = PowerLaw::iso8608(IsoClass::C, IsoBound::GeometricMean, Some(ISO_BAND)).unwrap();
    let sigma = c.variance().unwrap().sqrt();
    assert!((sigma - (256e-6 * 0.01 * (1.0 / n1 - 1.0 / n2)).sqrt()).abs() < ULPS * sigma);
}

/// Without a band the power law has no finite variance and says so (never a finite number).
#[test]
fn unbounded_power_law_is_divergent() {
    let s = PowerLaw::iso8608(IsoClass::B, IsoBound::GeometricMean, None).unwrap();
    for r in [s.variance(), numeric::variance(&s).map(|q| q.value)] {
        match r {
            Err(Error::Divergent { reason, .. }) => assert!(reason.contains("band"), "{reason}"),
            other => panic!("expected divergence, got {other:?}"),
        }
    }
    // a temporal white tail (deg N = deg D) diverges too
    let w = RationalSpectrum::new(vec![1.0, 1.0], vec![1.0, 1.0], Domain::Temporal).unwrap();
    assert!(matches!(w.variance(), Err(Error::Divergent { .. })));
    assert!(matches!(numeric::variance(&w), Err(Error::Divergent { .. })));
}

/// The shaping filter reproduces the rational density on a grid: |B(iω)/A(iω)|²/(2π) = S(ω), and A is
/// Hurwitz. Types 1 and 3 have known filters: √(2αD)/(s+α) and (for type 3) a second-order denominator
/// s² + 2αs + α² + β².
#[test]
fn shaping_filters_reproduce_rational_spectra() {
    let t3 = ExpCosine {
        variance: 1.3,
        alpha: 0.4,
        beta: 5.0,
        domain: Domain::Temporal,
    }
    .build()
    .unwrap();
    let r3 = t3.rational().unwrap();
    let f3 = r3.shaping_filter().unwrap();
    let a = &f3.den;
    assert!(rel(a[0] / a[2], 0.16 + 25.0) < FACTORISATION && rel(a[1] / a[2], 0.8) < FACTORISATION);
    let t1 = Exponential::new(2.0, 3.0, Domain::Temporal).unwrap();
    let f1 = t1.rational().unwrap().shaping_filter().unwrap();
    assert!(rel(f1.num[0] / f1.den[1], (2.0 * 3.0 * 2.0f64).sqrt()) < FACTORISATION);
    assert!(rel(f1.den[0] / f1.den[1], 3.0) < FACTORISATION);
    for s in [
        &t3 as &dyn Spectrum,
        &t1,
        &TwoPoleRoad {
            dq: 1e-3,
            alpha: 0.3,
            beta: 12.0,
            form: Form::Consistent,
        }
        .build()
        .unwrap(),
    ] {
        let r = s.rational().unwrap();
        let f = r.shaping_filter().unwrap();
        for k in 0..200 {
            let w = 10f64.powf(-3.0 + 6.0 * k as f64 / 199.0);
            let h = eval(&f.num, w) / eval(&f.den, w);
            assert!(
                rel(h.norm_sqr() / (2.0 * PI), s.density(w)) < FACTORISATION,
                "{} at {w}",
                s.describe()
            );
        }
    }
}

fn eval(c: &[f64], w: f64) -> nalgebra::Complex<f64> {
    let z = nalgebra::Complex::new(0.0, w);
    c.iter()
        .rev()
        .fold(nalgebra::Complex::new(0.0, 0.0), |acc, &x| acc * z + x)
}

/// Tabulated spectra: the exact variance of the log–log interpolant equals quadrature; a table sampled
/// from a power law f^-2 reproduces it between the points.
#[test]
fn tabulated_log_log_interpolation() {
    let f: Vec<f64> = vec![0.5, 1.0, 2.0, 8.0, 20.0];
    let g: Vec<f64> = f.iter().map(|x| 3.0 / (x * x)).collect();
    let t = Tabulated::new(Convention::OneSidedCyclic, f.clone(), g, Domain::Temporal).unwrap();
    // ∫_{0.5}^{20} 3/f² df = 3 (2 − 0.05)
    assert!(rel(t.variance().unwrap(), 3.0 * (2.0 - 0.05)) < EXACT);
    assert!(rel(numeric::variance(&t).unwrap().value, 3.0 * 1.95) < QUADRATURE);
    let (_, s_at_5hz) = Convention::OneSidedCyclic.to_canonical(5.0, 3.0 / 25.0);
    assert!(rel(t.density(2.0 * PI * 5.0), s_at_5hz) < EXACT);
    assert_eq!(t.density(2.0 * PI * 30.0), 0.0);
}

/// `Tabulated::density_into` (segment found by walking an ascending grid, a table-driven power) against
/// its oracle, `density` point by point (binary search, libm): within [`TABULATED_DENSITY`] on ascending,
/// descending and shuffled grids with negative frequencies and points outside the table (0 exactly), and
/// exact at the nodes themselves (x^p = 1 at x = 1, and the last node's value); the nodes reproduce the
/// table exactly. The table's slopes p and the exponents t = p ln(ω/ω_k) of the grid are checked to lie
/// where the tolerance holds (|p| ≤ 8, |t| ≤ 1.5).
#[test]
fn tabulated_density_into_matches_density() {
    let f: Vec<f64> = (0..40).map(|i| 0.05 * 1.2f64.powi(i)).collect();
    let g: Vec<f64> = f
        .iter()
        .map(|x| 1e-3 / (1.0 + x * x) * (2.0 + (3.0 * x).sin()))
        .collect();
    let t = Tabulated::new(Convention::OneSidedCyclic, f.clone(), g, Domain::Temporal).unwrap();
    let nodes: Vec<(f64, f64)> = t.points().collect();
    for &(w, s) in &nodes {
        assert_eq!(t.density(w), s, "node ω = {w}");
    }
    let (lo, hi) = (nodes[0].0, nodes[nodes.len() - 1].0);
    for w in nodes.windows(2) {
        let p = (w[1].1 / w[0].1).ln() / (w[1].0 / w[0].0).ln();
        assert!(
            p.abs() <= 8.0 && (p * (w[1].0 / w[0].0).ln()).abs() <= 1.5,
            "segment at {}: p = {p}",
            w[0].0
        );
    }
    let mut asc: Vec<f64> = (0..5000).map(|i| 0.5 * lo + (1.1 * hi) * i as f64 / 4999.0).collect();
    asc.extend(nodes.iter().map(|p| p.0));
    asc.sort_by(f64::total_cmp);
    let desc: Vec<f64> = asc.iter().rev().cloned().collect();
    let mut mixed: Vec<f64> = asc
        .iter()
        .enumerate()
        .map(|(i, w)| if i % 3 == 0 { -w } else { *w })
        .collect();
    let n = mixed.len();
    for i in 0..n {
        mixed.swap(i, (i * 7919) % n);
    }
    for grid in [&asc, &desc, &mixed] {
        let mut out = vec![f64::NAN; grid.len()];
        t.density_into(grid, &mut out);
        for (w, o) in grid.iter().zip(&out) {
            let d = t.density(*w);
            let node = nodes.iter().any(|p| p.0 == w.abs());
            let ok = if node || d == 0.0 {
                *o == d
            } else {
                (o - d).abs() <= TABULATED_DENSITY * d
            };
            assert!(ok, "ω = {w}: {o:e} vs {d:e}");
        }
    }
}

/// `Tabulated::density_into` on an absurd table whose first segment rises by 2¹⁹⁹³ over one octave
/// (10⁻³⁰⁰ → 10³⁰⁰; the ratio of the values itself overflows): the prepared power law declines that segment
/// (the library's unit test `an_absurd_segment_is_declined`),
/// which then takes `density`'s own formula, bit for bit; and that formula keeps the density finite where
/// the power alone overflows: S(ω) = 10⁻³⁰⁰·ω^p with p = log₂(10⁶⁰⁰), against 2^(p log₂ω − 300 log₂10)
/// (the rounding of exponents near 2000 allows about 1600ε relative). The second segment (2⁻⁹⁹⁷ over an octave)
/// takes the prepared law, within [`TABULATED_DENSITY`]'s derivation for its p and t. A NaN frequency gives
/// NaN, as `density`.
#[test]
fn tabulated_density_into_absurd_segments_and_nan() {
    let t = Tabulated::new(
        Convention::TwoSidedAngular,
        vec![1.0, 2.0, 4.0],
        vec![1e-300, 1e300, 1.0],
        Domain::Temporal,
    )
    .unwrap();
    let p0 = 1e300f64.log2() - 1e-300f64.log2(); // the ratio itself overflows
    let p1 = (1.0f64 / 1e300).log2();
    let grid: Vec<f64> = (0..=300).map(|i| 1.0 + 3.0 * i as f64 / 300.0).collect();
    let mut out = vec![0.0; grid.len()];
    t.density_into(&grid, &mut out);
    for (&w, &o) in grid.iter().zip(&out) {
        let d = t.density(w);
        if w < 2.0 {
            assert_eq!(o.to_bits(), d.to_bits(), "ω = {w}: {o:e} vs {d:e}");
            // 10⁻³⁰⁰·ω^p = 2^(p log₂ω − 300 log₂10): the exponent to within its rounding (≤ 2300·ε/2 absolute),
            // so the value to within 2300·ln 2·ε relative
            let reference = (p0 * w.log2() - 300.0 * 10f64.log2()).exp2();
            let allowed = 2300.0 * std::f64::consts::LN_2 * f64::EPSILON;
            assert!(
                d.is_finite() && (d - reference).abs() <= allowed * reference,
                "ω = {w}: {d:e} vs {reference:e}"
            );
        } else {
            let t2 = (p1 * (w / 2.0).log2()).abs();
            let allowed = (3.5 + 1.5 * p1.abs() + 3.9 * t2 * std::f64::consts::LN_2) * f64::EPSILON;
            assert!((o - d).abs() <= allowed * d, "ω = {w}: {o:e} vs {d:e}");
        }
    }
    let mut nan = [0.0; 3];
    t.density_into(&[f64::NAN, 1.5, -f64::NAN], &mut nan);
    assert!(nan[0].is_nan() && nan[2].is_nan() && nan[1] > 0.0);
    assert!(t.density(f64::NAN).is_nan());
}

/// `Tabulated::density_into` evaluates the runs of points inside one segment together (SIMD) and points in no
/// order one by one: the order of the points cannot change a value, so the same 3000 frequencies (either
/// sign, both table ends, every node, points outside) give the same bits ascending, descending, shuffled
/// and one at a time.
#[test]
fn tabulated_density_into_does_not_depend_on_the_order() {
    let f: Vec<f64> = (0..25).map(|i| 0.1 * 1.3f64.powi(i)).collect();
    let g: Vec<f64> = f.iter().map(|x| 1.0 / (1.0 + x * x)).collect();
    let t = Tabulated::new(Convention::TwoSidedAngular, f.clone(), g, Domain::Temporal).unwrap();
    let mut asc: Vec<f64> = (0..3000).map(|i| 0.05 + 0.02 * i as f64).collect();
    asc.extend(&f);
    asc.extend(f.iter().map(|x| -x));
    asc.sort_by(f64::total_cmp);
    let eval = |grid: &[f64]| {
        let mut out = vec![f64::NAN; grid.len()];
        t.density_into(grid, &mut out);
        grid.iter()
            .zip(out)
            .map(|(w, o)| (w.to_bits(), o.to_bits()))
            .collect::<Vec<_>>()
    };
    let mut reference = eval(&asc);
    reference.sort();
    let n = asc.len();
    let mut shuffled = asc.clone();
    for i in 0..n {
        shuffled.swap(i, (i * 7919 + 13) % n);
    }
    let desc: Vec<f64> = asc.iter().rev().cloned().collect();
    for grid in [desc, shuffled] {
        let mut got = eval(&grid);
        got.sort();
        assert_eq!(got, reference);
    }
    let mut one_by_one: Vec<(u64, u64)> = asc.iter().flat_map(|w| eval(std::slice::from_ref(w))).collect();
    one_by_one.sort();
    assert_eq!(one_by_one, reference);
}

/// `RationalSpectrum::density_into` (eight Horner chains at once) against its oracle, `density` (one
/// chain per point): bit-identical for every grid length from 0 to 40 (whole blocks of eight and every
/// remainder), negative, zero and large frequencies. One value by hand: N(x) = 1 + 0.5x, D(x) = 1 + 0.3x
/// + 0.02x², at ω = 2 (x = 4): N = 3, D = 1 + 1.2 + 0.32 = 2.52, S = 3/2.52.
#[test]
fn rational_density_into_matches_density() {
    let r = RationalSpectrum::new(vec![1.0, 0.5], vec![1.0, 0.3, 0.02], Domain::Temporal).unwrap();
    let mut out = [0.0; 1];
    r.density_into(&[2.0], &mut out);
    assert!(rel(out[0], 3.0 / 2.52) < EXACT);
    // A higher degree as well: N(x) = 2 + x², D(x) = (1 + x)³ (poles of order 3 at ω = ±i).
    let r3 = RationalSpectrum::new(vec![2.0, 0.0, 1.0], vec![1.0, 3.0, 3.0, 1.0], Domain::Temporal).unwrap();
    for s in [&r, &r3] {
        for len in 0..=40usize {
            let grid: Vec<f64> = (0..len)
                .map(|i| {
                    let w = 0.37 * i as f64 * 1.3f64.powi(i as i32);
                    if i % 3 == 1 {
                        -w
                    } else {
                        w
                    }
                })
                .collect();
            let mut out = vec![f64::NAN; len];
            s.density_into(&grid, &mut out);
            for (w, o) in grid.iter().zip(&out) {
                assert_eq!(o.to_bits(), s.density(*w).to_bits(), "len {len}, ω = {w}");
            }
        }
    }
}

/// Spatial → temporal: S_t(ω) = S_Ω(ω/v)/v keeps the variance and maps K(τ) to K_Ω(vτ); the rational form
/// scales with it.
#[test]
fn spatial_to_temporal() {
    let road: Arc<dyn Spectrum> = Arc::new(
        TwoPoleRoad {
            dq: 1e-3,
            alpha: 0.3,
            beta: 12.0,
            form: Form::Consistent,
        }
        .build()
        .unwrap(),
    );
    for v in [1.0, 5.0, 15.0] {
        let t = AtSpeed::new(road.clone(), v).unwrap();
        assert!(rel(numeric::variance(&t).unwrap().value, 1e-3) < QUADRATURE);
        assert!(rel(t.correlation(0.2).unwrap(), road.correlation(0.2 * v).unwrap()) < EXACT);
        let r = t.rational().unwrap();
        for w in [0.1, 3.0, 100.0] {
            assert!(rel(r.density(w), road.density(w / v) / v) < EXACT);
        }
    }
    assert!(AtSpeed::new(road.clone(), 0.0).is_err());
    let temporal: Arc<dyn Spectrum> = Arc::new(Exponential::new(1.0, 1.0, Domain::Temporal).unwrap());
    assert!(AtSpeed::new(temporal, 3.0).is_err());
}

/// Bad parameters are rejected by every constructor.
#[test]
fn bad_parameters_rejected() {
    for (d, a) in [
        (1.0, 0.0),
        (1.0, -1.0),
        (-1.0, 1.0),
        (f64::NAN, 1.0),
        (1.0, f64::NAN),
        (1.0, f64::INFINITY),
    ] {
        assert!(Exponential::new(d, a, Domain::Temporal).is_err(), "{d} {a}");
        assert!(Gaussian::new(d, a, Domain::Temporal).is_err());
        assert!(ExpCosine {
            variance: d,
            alpha: a,
            beta: 1.0,
            domain: Domain::Temporal
        }
        .build()
        .is_err());
        assert!(GaussCosineParameters {
            variance: d,
            alpha: a,
            beta: 1.0,
            domain: Domain::Temporal
        }
        .build()
        .is_err());
    }
    assert!(ExpCosine {
        variance: 1.0,
        alpha: 1.0,
        beta: -1.0,
        domain: Domain::Temporal
    }
    .build()
    .is_err());
    assert!(TwoPoleRoad {
        dq: 1.0,
        alpha: 0.0,
        beta: 1.0,
        form: Form::Consistent
    }
    .build()
    .is_err());
    assert!(PowerLawParameters {
        g0: 1.0,
        n0: 0.1,
        waviness: 2.0,
        band: Some((0.5, 0.1)),
        domain: Domain::Spatial
    }
    .build()
    .is_err());
    assert!(BandWhiteParameters {
        convention: Convention::OneSidedCyclic,
        level: 1.0,
        lo: 5.0,
        hi: 1.0,
        domain: Domain::Temporal
    }
    .build()
    .is_err());
    assert!(Tabulated::new(
        Convention::OneSidedCyclic,
        vec![1.0, 1.0],
        vec![1.0, 1.0],
        Domain::Temporal
    )
    .is_err());
    assert!(Tabulated::new(
        Convention::OneSidedCyclic,
        vec![1.0, 2.0],
        vec![1.0, 0.0],
        Domain::Temporal
    )
    .is_err());
    // S(ω) = (1 − ω²)/(1 + ω²)² is negative above ω = 1
    assert!(RationalSpectrum::new(vec![1.0, -1.0], vec![1.0, 2.0, 1.0], Domain::Temporal).is_err());
    // pole on the real axis: D(ω²) = 1 − ω²
    assert!(RationalSpectrum::new(vec![1.0], vec![-1.0, 1.0], Domain::Temporal).is_err());
}

fn file_error(text: &str) -> (String, String) {
    match parse_spectrum(text, Path::new("bad.toml")) {
        Err(Error::File { key, reason, .. }) => (key, reason),
        other => panic!("expected a file error, got {other:?}"),
    }
}

/// Bad files: errors name the key and the reason (and the file, via the Display of Error::File).
#[test]
fn bad_spectrum_files_name_key_and_reason() {
    let base = "kind = \"exponential\"\ndomain = \"spatial\"\n";
    let (k, r) = file_error(&format!("{base}variance = \"2.25 cm^2\"\n"));
    assert_eq!(k, "alpha");
    assert!(r.contains("missing"));
    let (k, _) = file_error(&format!(
        "{base}variance = \"2.25 cm^2\"\nalpha = \"0.035 1/furlong\"\n"
    ));
    assert_eq!(k, "alpha");
    let (k, r) = file_error(&format!("{base}variance = \"-2.25 cm^2\"\nalpha = \"0.035 1/cm\"\n"));
    assert_eq!(k, "variance");
    assert!(r.contains(">= 0"), "{r}");
    let (k, _) = file_error(&format!("{base}variance = \"2.25 cm\"\nalpha = \"0.035 1/cm\"\n"));
    assert_eq!(k, "variance");
    let (k, r) = file_error(&format!(
        "{base}variance = 2.25e-4\nalpah = \"0.035 1/cm\"\nalpha = 3.5\n"
    ));
    assert_eq!(k, "alpah");
    assert!(r.contains("unknown key"));
    let (k, _) = file_error("kind = \"pink\"\n");
    assert_eq!(k, "kind");
    let (k, r) = file_error("kind = \"iso8608\"\ndomain = \"spatial\"\nclass = \"C\"\nband = [0.011, 2.83]\n");
    assert_eq!(k, "band[0]");
    assert!(r.contains("unit"), "{r}");
    let msg = parse_spectrum(&format!("{base}variance = \"2.25 cm^2\"\n"), Path::new("x/bad.toml"))
        .unwrap_err()
        .to_string();
    assert!(msg.contains("x/bad.toml") && msg.contains("alpha"), "{msg}");
    assert!(matches!(
        parse_spectrum("kind = ", Path::new("p.toml")),
        Err(Error::Parse { .. })
    ));
}

/// The shipped catalogue: every file parses, and the book values come out in SI as derived by hand.
#[test]
fn catalogue_files_parse_with_book_values() {
    let dir = crate::common::root().join("spectra");
    let entries = spectrum_catalogue(&dir).unwrap();
    assert!(entries.len() >= 17);
    for e in &entries {
        assert!(
            e.spectrum.is_ok(),
            "{}: {:?}",
            e.path.display(),
            e.spectrum.as_ref().err()
        );
    }
    // (8.45): D = 2.25 cm² = 2.25e-4 m², α = 0.035 1/cm = 3.5 1/m ⇒ K(1 m) = 2.25e-4 e^{−3.5}
    let s = load_spectrum(&dir.join("book-8-45.toml")).unwrap().spectrum;
    assert!(rel(s.variance().unwrap(), 2.25e-4) < EXACT);
    assert!(rel(s.correlation(1.0).unwrap(), 2.25e-4 * (-3.5f64).exp()) < EXACT);
    // (8.69): D = 32 cm² = 3.2e-3 m², α = 0.16e-2 1/cm = 0.16 1/m
    let s = load_spectrum(&dir.join("book-8-69.toml")).unwrap().spectrum;
    assert!(rel(s.correlation(10.0).unwrap(), 3.2e-3 * (-1.6f64).exp()) < EXACT);
    // (8.66) printed: D = D_q β(α+β)/(α²+β²) with √D_q = 3.5 cm
    let s = load_spectrum(&dir.join("book-8-66-printed.toml")).unwrap().spectrum;
    assert!(rel(s.variance().unwrap(), 0.035f64.powi(2) * 12.0 * 12.3 / 144.09) < EXACT);
    // ISO class D over the standard band
    let s = load_spectrum(&dir.join("iso8608-d.toml")).unwrap().spectrum;
    assert!(rel(s.variance().unwrap(), 1024e-6 * 0.01 * (1.0 / 0.011 - 1.0 / 2.83)) < EXACT);
    // white 1–80 Hz, one-sided 0.01 (m/s²)²/Hz ⇒ D = 0.79 (m/s²)²
    let s = load_spectrum(&dir.join("white-1-80hz.toml")).unwrap().spectrum;
    assert!(rel(s.variance().unwrap(), 0.79) < EXACT);
}

proptest! {
    #![proptest_config(crate::common::proptest_config(64))]

    /// For random parameters, quadrature of every standard type's density gives D.
    #[test]
    fn prop_standard_types_integrate_to_d(d in 1e-6f64..1e3, a in 1e-2f64..1e2, b in 0.0f64..50.0) {
        let list: Vec<Box<dyn Spectrum>> = vec![
            Box::new(Exponential::new(d, a, Domain::Temporal).unwrap()),
            Box::new(Gaussian::new(d, a, Domain::Temporal).unwrap()),
            Box::new(ExpCosine { variance: d, alpha: a, beta: b, domain: Domain::Temporal }.build().unwrap()),
            Box::new(
                GaussCosineParameters { variance: d, alpha: a, beta: b, domain: Domain::Temporal }.build().unwrap(),
            ),
        ];
        for s in list {
            let q = numeric::variance(s.as_ref()).unwrap().value;
            prop_assert!(rel(q, d) < QUADRATURE, "{}: {} vs {}", s.describe(), q, d);
        }
    }

    /// Convention round trips are exact up to rounding for any point.
    #[test]
    fn prop_convention_round_trip(w in 0.0f64..1e4, s in 0.0f64..1e3) {
        for c in Convention::ALL {
            let (x, v) = c.from_canonical(w, s);
            let (w2, s2) = c.to_canonical(x, v);
            prop_assert!((w2 - w).abs() <= ULPS * w.max(1.0));
            prop_assert!((s2 - s).abs() <= ULPS * s);
        }
    }

    /// Type 3's rational form and shaping filter reproduce its density for random parameters.
    #[test]
    fn prop_type3_factorisation(d in 1e-3f64..10.0, a in 0.05f64..5.0, b in 0.0f64..20.0) {
        let s = ExpCosine { variance: d, alpha: a, beta: b, domain: Domain::Temporal }.build().unwrap();
        let r = s.rational().unwrap();
        let f = r.shaping_filter().unwrap();
        prop_assert!(f.residual < FACTORISATION, "residual {}", f.residual);
        prop_assert!(rel(r.variance().unwrap(), d) < FACTORISATION);
    }
}
