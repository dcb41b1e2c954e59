//! The International Roughness Index (IRI) of a longitudinal profile, by the standard quarter car
//! ("golden car") of ASTM E1926-08 and Sayers (1995).

use crate::error::{require_positive, Error, Result};
use crate::simulate::foh;
use nalgebra::DMatrix;

/// Golden-car tyre stiffness over sprung mass k₁ = k_t/m_s, s⁻².
pub const GOLDEN_K1: f64 = 653.0;
/// Golden-car suspension stiffness over sprung mass k₂ = k_s/m_s, s⁻².
pub const GOLDEN_K2: f64 = 63.3;
/// Golden-car unsprung over sprung mass μ = m_u/m_s.
pub const GOLDEN_MU: f64 = 0.15;
/// Golden-car damping over sprung mass c = c_s/m_s, s⁻¹.
pub const GOLDEN_C: f64 = 6.0;
/// Simulation speed of the IRI, 80 km/h in m/s.
pub const IRI_SPEED: f64 = 80.0 / 3.6;
/// Base length of the moving average applied to the profile first, m.
pub const IRI_MOVING_AVERAGE_BASE: f64 = 0.25;
/// Length over which the initial slope is taken, m (0.5 s at 80 km/h).
pub const IRI_INITIAL_SLOPE_LENGTH: f64 = 11.0;

/// The golden car's state matrices (A, B) for the state (z_s, ż_s, z_u, ż_u) driven by the road
/// elevation y: ẋ = A x + B y.
///
/// # Formula
/// ```text
/// z̈_s = −k₂(z_s − z_u) − c(ż_s − ż_u)
/// μ z̈_u = k₂(z_s − z_u) + c(ż_s − ż_u) − k₁(z_u − y)          k₁ = 653, k₂ = 63.3 s⁻², μ = 0.15, c = 6 s⁻¹
/// ```
/// (all per unit sprung mass; Sayers 1995, "On the calculation of International Roughness Index from
/// longitudinal road profile", Transp. Res. Rec. 1501, 1–12; ASTM E1926-08).
///
/// # Examples
/// ```
/// use stochvib::road::golden_car;
/// let (a, b) = golden_car();
/// assert_eq!(a.shape(), (4, 4));
/// assert_eq!(b[(3, 0)], 653.0 / 0.15);
/// ```
pub fn golden_car() -> (DMatrix<f64>, DMatrix<f64>) {
    let (k1, k2, mu, c) = (GOLDEN_K1, GOLDEN_K2, GOLDEN_MU, GOLDEN_C);
    #[rustfmt::skip]
    let a = DMatrix::from_row_slice(4, 4, &[
        0.0, 1.0, 0.0, 0.0,
        -k2, -c, k2, c,
        0.0, 0.0, 0.0, 1.0,
        k2 / mu, c / mu, -(k1 + k2) / mu, -c / mu,
    ]);
    let b = DMatrix::from_row_slice(4, 1, &[0.0, 0.0, 0.0, k1 / mu]);
    (a, b)
}

/// The IRI of one track and how it was computed.
#[derive(Debug, Clone, PartialEq)]
pub struct Iri {
    /// IRI in m/km (= mm/m).
    pub m_per_km: f64,
    /// Samples k of the moving average (base k·Δx).
    pub moving_average_samples: usize,
    /// The base length actually used, k·Δx in m (0.25 m when 0.25/Δx is an integer).
    pub moving_average_base_m: f64,
    /// Number of simulation steps averaged.
    pub steps: usize,
    /// Length over which the IRI is averaged, steps·Δx in m.
    pub length_m: f64,
}

/// The International Roughness Index of a profile sampled at step Δx (ASTM E1926-08; Sayers 1995).
///
/// # Formula
/// 1. Moving average of base 250 mm: k = max(1, round(0.25/Δx)) samples,
///    ȳ_i = (1/k) Σ_{m=0}^{k−1} y_{i+m}, i = 0 … N − k. Its slope (ȳ_{i+1} − ȳ_i)/Δx = (y_{i+k} − y_i)/(kΔx)
///    is the slope of the continuous moving average of base kΔx, as in the reference algorithm.
/// 2. The golden car ([`golden_car`]) at v = 80 km/h over ȳ, linear between samples: exact discretisation
///    of each step Δt = Δx/v by the first-order hold ([`foh`], matrix exponential) — identical to the
///    reference algorithm's exact transition with the slope held constant over each step.
/// 3. Initial state from the slope over the first 11 m: s = (ȳ_{i₁₁} − ȳ₀)/(i₁₁Δx), i₁₁ = round(11/Δx),
///    x₀ = (ȳ₀, v s, ȳ₀, v s): both masses ride the initial grade, no relative motion.
/// 4. ```text
///    IRI = (1000/S) Σ_{i=1}^{S} |ż_s,i − ż_u,i| / v      m/km,   S = N − k steps (states at step ends)
///    ```
///    i.e. the mean absolute rectified relative slope, the rectangle rule of (1/L)∫|ż_s − ż_u| dt.
///
/// A flat or constant-slope profile gives 0 (the initial state is then the exact solution). For a
/// sinusoid y = A sin(2πx/λ) the IRI tends to (2/π)·ω|H_rel(iω)|·A·sinc(πB/λ)/v with ω = 2πv/λ, B the
/// moving-average base and H_rel the transfer function from y to z_s − z_u (see the tests).
///
/// # Errors
/// Δx not finite and > 0 or larger than 11 m; a profile shorter than 11 m plus the moving-average base;
/// non-finite elevations (naming the index).
///
/// # Examples
/// ```
/// use stochvib::road::iri;
/// // a constant grade of 2 % has no roughness
/// let y: Vec<f64> = (0..2000).map(|k| 0.02 * 0.05 * k as f64).collect();
/// assert!(iri(&y, 0.05).unwrap().m_per_km.abs() < 1e-9);
/// ```
pub fn iri(elevation_m: &[f64], step_m: f64) -> Result<Iri> {
    require_positive("step", step_m)?;
    if step_m > IRI_INITIAL_SLOPE_LENGTH {
        return Err(Error::invalid(
            "step",
            step_m,
            "longer than the 11 m initialisation length of the IRI; ASTM E1926 asks for ≤ 0.25 m",
        ));
    }
    if let Some(k) = elevation_m.iter().position(|v| !v.is_finite()) {
        return Err(Error::invalid(
            &format!("elevation[{k}]"),
            elevation_m[k],
            "must be finite",
        ));
    }
    let k = ((IRI_MOVING_AVERAGE_BASE / step_m).round() as usize).max(1);
    let i11 = ((IRI_INITIAL_SLOPE_LENGTH / step_m).round() as usize).max(1);
    let n = elevation_m.len();
    if n < k + i11 + 1 {
        return Err(Error::invalid(
            "profile length",
            format!("{} m ({n} samples)", n.saturating_sub(1) as f64 * step_m),
            format!(
                "the IRI needs at least 11 m plus the moving-average base ({} samples at {step_m} m)",
                k + i11 + 1
            ),
        ));
    }
    // moving average by a running sum
    let mut smooth = Vec::with_capacity(n - k + 1);
    let mut s: f64 = elevation_m[..k].iter().sum();
    smooth.push(s / k as f64);
    for i in 1..=n - k {
        s += elevation_m[i + k - 1] - elevation_m[i - 1];
        smooth.push(s / k as f64);
    }
    let v = IRI_SPEED;
    let (a, b) = golden_car();
    let d = foh(&a, &b, step_m / v)?;
    let slope = (smooth[i11] - smooth[0]) / (i11 as f64 * step_m);
    let mut x = [smooth[0], v * slope, smooth[0], v * slope];
    let phi = |r: usize, c: usize| d.phi[(r, c)];
    let mut sum = 0.0;
    let steps = smooth.len() - 1;
    for i in 0..steps {
        let (u0, u1) = (smooth[i], smooth[i + 1]);
        let mut next = [0.0; 4];
        for (r, nr) in next.iter_mut().enumerate() {
            *nr = phi(r, 0) * x[0]
                + phi(r, 1) * x[1]
                + phi(r, 2) * x[2]
                + phi(r, 3) * x[3]
                + d.gamma0[(r, 0)] * u0
                + d.gamma1[(r, 0)] * u1;
        }
        x = next;
        sum += (x[1] - x[3]).abs();
    }
    Ok(Iri {
        m_per_km: 1000.0 * sum / (steps as f64 * v),
        moving_average_samples: k,
        moving_average_base_m: k as f64 * step_m,
        steps,
        length_m: steps as f64 * step_m,
    })
}

/// The golden car's relative velocity ż_s − ż_u per unit road elevation, H_rv(s), at s = i2πnv for a
/// spatial frequency n (cycles/m) at the IRI speed v = 80 km/h.
///
/// # Formula
/// From the equations of [`golden_car`] with D = k₂ + cs:
/// ```text
/// Z_u = k₁ Y / (μs² + k₁ + s²D/(s² + D)),   Z_s − Z_u = −s² Z_u/(s² + D),   H_rv = s (Z_s − Z_u)/Y
/// ```
///
/// # Examples
/// ```
/// use stochvib::road::iri::golden_relative_velocity;
/// assert!(golden_relative_velocity(1e-6).norm() < 1e-9); // a long wave moves both masses alike
/// ```
pub fn golden_relative_velocity(n_cycles_per_m: f64) -> nalgebra::Complex<f64> {
    use nalgebra::Complex;
    let s = Complex::new(0.0, std::f64::consts::TAU * n_cycles_per_m * IRI_SPEED);
    let d = s * GOLDEN_C + GOLDEN_K2;
    let s2 = s * s;
    let zu = GOLDEN_K1 / (s2 * GOLDEN_MU + GOLDEN_K1 + s2 * d / (s2 + d));
    s * (-s2 * zu / (s2 + d))
}

/// The expected IRI of a stationary Gaussian road profile, from its spectrum.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct ExpectedIri {
    /// E\[IRI\] with the 250 mm moving average of ASTM E1926, m/km.
    pub m_per_km: f64,
    /// E\[IRI\] without the moving average, m/km.
    pub without_moving_average_m_per_km: f64,
    /// σ of the golden car's relative velocity with the moving average, m/s.
    pub sigma_relative_velocity_m_s: f64,
    /// The band of the spectrum integrated over, cycles/m (an infinite upper edge for a spectrum without
    /// one; `null` in JSON).
    #[serde(serialize_with = "finite_or_null")]
    pub band_cycles_per_m: (f64, f64),
}

/// A pair of band edges with a non-finite edge as `None` (JSON has no infinity).
fn finite_or_null<S: serde::Serializer>(band: &(f64, f64), s: S) -> std::result::Result<S::Ok, S::Error> {
    use serde::Serialize;
    let f = |x: f64| x.is_finite().then_some(x);
    (f(band.0), f(band.1)).serialize(s)
}

/// The expected IRI of a road of spatial spectrum S(Ω) (the crate's two-sided density in rad/m).
///
/// # Formula
/// The IRI is the golden car's mean rectified relative slope, the time mean of |ż_s − ż_u|/v at v = 80 km/h
/// (ASTM E1926; Sayers 1995).
/// For a stationary Gaussian profile ż_s − ż_u is Gaussian with zero mean, and E|X| = √(2/π)σ_X exactly, so
/// ```text
/// E[IRI] = 1000·√(2/π)·σ_rv / v  m/km,   σ_rv² = ∫₀^∞ |H_rv(i2πnv)|² · sinc²(nb) · G_d(n) dn,
/// ```
/// with G_d(n) = 4π S(2πn) the one-sided density in cycles/m, b = 0.25 m, sinc(x) = sin(πx)/(πx) the moving
/// average's transfer function and H_rv from [`golden_relative_velocity`]; by adaptive quadrature over the
/// spectrum's support, split at the golden car's resonances (≈ 1 and 10 Hz at 80 km/h) and at the zeros of
/// the sinc (n = 4, 8, … cycles/m). For ISO 8608 roads of waviness w = 2 the IRI is proportional to
/// √G_d(n₀) (the slope of such a road is white): E\[IRI\] = K·√(G_d(n₀)/10⁻⁶ m³) with one constant K.
///
/// # Errors
/// [`Error::NotApplicable`] for a temporal spectrum; the quadrature's errors.
///
/// # Examples
/// ```
/// use stochvib::road::iri::expected_iri;
/// use stochvib::spectrum::{IsoClass, PowerLaw};
/// let road = PowerLaw::iso_class(IsoClass::C).unwrap();
/// let e = expected_iri(&road).unwrap();
/// assert!(e.m_per_km > 6.0 && e.m_per_km < 12.3); // within the class limits of C
/// ```
pub fn expected_iri(road: &dyn crate::spectrum::Spectrum) -> Result<ExpectedIri> {
    use crate::quad::{integrate, QuadOptions};
    use std::f64::consts::{PI, TAU};
    if road.domain() != crate::spectrum::Domain::Spatial {
        return Err(Error::NotApplicable {
            method: "expected IRI".into(),
            reason: "the IRI needs a spatial road spectrum (rad/m); this one is temporal".into(),
        });
    }
    let (lo, hi) = road.support();
    let (lo, hi) = (lo.max(0.0) / TAU, hi / TAU);
    let b = IRI_MOVING_AVERAGE_BASE;
    let variance = |ma: bool| -> Result<f64> {
        let integrand = |n: f64| {
            let h = golden_relative_velocity(n).norm_sqr();
            let s = if ma && n > 0.0 {
                (PI * n * b).sin() / (PI * n * b)
            } else {
                1.0
            };
            h * s * s * 4.0 * PI * road.density(TAU * n)
        };
        let mut breaks = vec![0.045, 0.45];
        breaks.extend((1..=25).map(|k| k as f64 / b));
        let opts = QuadOptions {
            breakpoints: breaks.into_iter().filter(|x| *x > lo && *x < hi).collect(),
            ..QuadOptions::default()
        };
        Ok(integrate(integrand, lo, hi, &opts)?.value)
    };
    let to_iri = |var: f64| 1000.0 * (2.0 / PI).sqrt() * var.max(0.0).sqrt() / IRI_SPEED;
    let (with, without) = (variance(true)?, variance(false)?);
    Ok(ExpectedIri {
        m_per_km: to_iri(with),
        without_moving_average_m_per_km: to_iri(without),
        sigma_relative_velocity_m_s: with.max(0.0).sqrt(),
        band_cycles_per_m: (lo, hi),
    })
}
