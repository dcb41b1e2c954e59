//! A symmetric body on two wheels (left at +h, right at −h): bounce z and roll φ, each wheel a spring and a
//! damper from the body to its base input (0 left, 1 right); the model of the two-track tests.

use stochvib::system::{Attach, Element, Mdof, Quantity};

/// Body mass, kg.
pub const M: f64 = 800.0;
/// Roll inertia, kg m².
pub const I: f64 = 300.0;
/// Half track width, m.
pub const H: f64 = 0.75;
/// Stiffness per wheel, N/m.
pub const K: f64 = 3.0e4;
/// Damping per wheel, N s/m.
pub const C: f64 = 2.0e3;
/// Speed, m/s.
pub const V: f64 = 15.0;

/// The body with the outputs `bounce` (z) and `roll` (φ).
pub fn body() -> Mdof {
    let el = |name: &str, y: f64, j: usize| Element {
        name: name.into(),
        point: vec![1.0, y],
        to: Attach::Base(j),
        stiffness: K,
        damping: C,
    };
    Mdof::from_elements(
        &[("z", "m"), ("phi", "rad")],
        &[M, I],
        vec![el("left", H, 0), el("right", -H, 1)],
        2,
        &[],
    )
    .unwrap()
    .with_output("bounce", Quantity::Displacement(vec![1.0, 0.0]))
    .unwrap()
    .with_output("roll", Quantity::Displacement(vec![0.0, 1.0]))
    .unwrap()
}

/// The road of the two-track tests: the type-1 spectrum in space (book (8.45) form) of variance
/// `scale`·D, D = 1e-4 m², α = 0.2 rad/m.
pub fn road(scale: f64) -> std::sync::Arc<dyn stochvib::spectrum::Spectrum> {
    use stochvib::spectrum::{Domain, Exponential};
    std::sync::Arc::new(Exponential::new(1e-4 * scale, 0.2, Domain::Spatial).unwrap())
}

/// The closed-form (bounce, roll) variances of [`body`] at [`V`] on two tracks of the [`road`] (scale 1)
/// with the constant coherence amplitude `rho`.
///
/// # Formula
/// With u_L, u_R under the wheels at ±h, the equations of motion are
///   M z̈ + 2C ż + 2K z = 2(C ḃ + K b),            b = (u_L + u_R)/2,
///   I φ̈ + 2Ch² φ̇ + 2Kh² φ = 2h(C ḋ + K d),       d = (u_L − u_R)/2,
/// and for S_LL = S_RR = S, S_LR = ρS: S_b = S(1 + ρ)/2, S_d = S(1 − ρ)/2, S_bd = 0. So bounce and roll are
/// single-input transfer functions driven by the road of variance D(1 ± ρ)/2: exact Lyapunov variances on
/// another model (transfer functions) and another excitation (one scaled process) than the two-track
/// routes under test.
pub fn closed_form_variances(rho: f64) -> (f64, f64) {
    use stochvib::response::{variance_lyapunov, Excitation};
    use stochvib::system::{OutputInfo, TransferFunction};
    let scaled = |f: f64| Excitation::road(road(f), V, &[0.0]).unwrap();
    let bounce_tf = TransferFunction::new(
        vec![2.0 * K, 2.0 * C],
        vec![2.0 * K, 2.0 * C, M],
        OutputInfo::new("z", "m"),
    )
    .unwrap();
    let roll_tf = TransferFunction::new(
        vec![2.0 * H * K, 2.0 * H * C],
        vec![2.0 * K * H * H, 2.0 * C * H * H, I],
        OutputInfo::new("phi", "rad"),
    )
    .unwrap();
    let variance = |tf: &TransferFunction, f: f64| variance_lyapunov(tf, &scaled(f), 0).unwrap().variance;
    (
        variance(&bounce_tf, (1.0 + rho) / 2.0),
        variance(&roll_tf, (1.0 - rho) / 2.0),
    )
}
