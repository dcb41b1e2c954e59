//! Time-varying systems on a schedule and the refusal of bad transient input: the mine hoist winding its
//! rope (frozen coefficients at each rope length against the frequencies of the source's eigenproblem), an
//! unstable schedule named by its time, speed profiles that are not functions of time or negative,
//! envelopes that are not finite, and inputs without an exact route.

use crate::common;
use crate::common::rel;
use crate::common::tolerance::PRINTED_6_DIGITS;
use nalgebra::{DMatrix, DVector};
use std::sync::Arc;
use stochvib::models::mine_hoist::MineHoist;
use stochvib::spectrum::{IsoBound, IsoClass, PowerLaw};
use stochvib::system::{OutputInfo, StateSpace};
use stochvib::transient::{
    check_stability, input_model, ConstantAcceleration, Envelope, FamilyBuilder, PiecewiseLinear, Schedule,
    ScheduledSystem, SpeedProfile, SystemFamily,
};
use stochvib::Error;

/// ẋ = Ax + Bf of the hoist at rope length l₂: X = (R_bφ_b, R_sφ_s, y), A = [[0, I], [−M⁻¹C, −M⁻¹(2δC)]], a
/// force f on the load, output the hanging rope's stretch y − R_sφ_s.
fn hoist_state_space(h: &MineHoist, l2: f64, delta: f64) -> stochvib::Result<StateSpace> {
    let (m, c) = (h.mass_matrix(l2)?, h.stiffness_matrix(l2)?);
    let mi = m.try_inverse().expect("M is positive definite");
    let mut a = DMatrix::zeros(6, 6);
    a.view_mut((0, 3), (3, 3)).fill_with_identity();
    a.view_mut((3, 0), (3, 3)).copy_from(&(-&mi * &c));
    a.view_mut((3, 3), (3, 3)).copy_from(&(-&mi * &c * (2.0 * delta)));
    let mut b = DMatrix::zeros(6, 1);
    b.view_mut((3, 0), (3, 1)).copy_from(&mi.column(2));
    let cy = DMatrix::from_row_slice(1, 6, &[0.0, -1.0, 1.0, 0.0, 0.0, 0.0]);
    StateSpace::new(a, b, cy, None, None, vec![OutputInfo::new("rope_stretch", "m")])
}

/// The hoist winding at 10 m/s from l₂ = 700 m to 75 m (the source's data, Dvornikov, Kondrakhin & Velebnik
/// 2014, eqs. (3)–(5), (9), (14)) as a scheduled family. Frozen at each time, the undamped state matrix has
/// eigenvalues 0, 0, ±iω₁, ±iω₂ with ω from the generalized eigenproblem Cφ = ω²Mφ, solved independently
/// (scipy) at the rope lengths of the table: l₂ = 75 m: 11.51647, 30.60900 rad/s; 300 m: 6.51795, 25.86627;
/// 500 m: 5.06710, 24.87289; 700 m: 4.25501, 24.23537. The undamped schedule is accepted by the stability
/// check (eigenvalues on the imaginary axis: the rigid mode grows like a random walk, not exponentially).
#[test]
fn hoist_winding_frequencies_at_each_rope_length() {
    let hoist = MineHoist::printed();
    let h = hoist.clone();
    let build: Arc<FamilyBuilder> = Arc::new(move |v: &[f64]| Ok((hoist_state_space(&h, v[0], 0.0)?, None)));
    let schedule = Schedule {
        name: "hanging_length".into(),
        unit: "m".into(),
        profile: PiecewiseLinear::new(vec![0.0, 62.5], vec![700.0, 75.0]).unwrap(),
    };
    let fam = ScheduledSystem::new(vec![schedule], build, "mine hoist winding at 10 m/s");
    assert!(!fam.is_constant());
    assert_eq!(fam.knots(), vec![0.0, 62.5]);
    for (t, w1, w2) in [
        (62.5, 11.51647, 30.60900),
        (40.0, 6.51795, 25.86627),
        (20.0, 5.06710, 24.87289),
        (0.0, 4.25501, 24.23537),
    ] {
        let a = fam.at(t).unwrap().ss.a;
        let mut w: Vec<f64> = a
            .complex_eigenvalues()
            .iter()
            .map(|l| l.im)
            .filter(|im| *im > 1e-6)
            .collect();
        w.sort_by(f64::total_cmp);
        assert_eq!(w.len(), 2, "t = {t}: {w:?}");
        assert!(rel(w[0], w1) < PRINTED_6_DIGITS, "t = {t}: ω₁ = {}", w[0]);
        assert!(rel(w[1], w2) < PRINTED_6_DIGITS, "t = {t}: ω₂ = {}", w[1]);
    }
    let times: Vec<f64> = (0..=25).map(|k| k as f64 * 2.5).collect();
    assert!(check_stability(&fam, &times).is_ok());
}

/// A schedule that makes the system unstable is refused with the first time at which it is: an oscillator
/// whose damping ratio falls linearly from 0.1 at t = 0 to −0.1 at t = 4 s is undamped at 2 s (accepted)
/// and unstable at 3 s (named).
#[test]
fn unstable_schedule_is_refused_with_its_time() {
    let build: Arc<FamilyBuilder> = Arc::new(|v: &[f64]| {
        let w0 = 2.0 * std::f64::consts::PI;
        let ss = StateSpace::new(
            DMatrix::from_row_slice(2, 2, &[0.0, 1.0, -w0 * w0, -2.0 * v[0] * w0]),
            DMatrix::from_row_slice(2, 1, &[0.0, 1.0]),
            DMatrix::from_row_slice(1, 2, &[1.0, 0.0]),
            None,
            None,
            vec![OutputInfo::new("x", "m")],
        )?;
        Ok((ss, None::<DVector<f64>>))
    });
    let schedule = Schedule {
        name: "damping_ratio".into(),
        unit: "1".into(),
        profile: PiecewiseLinear::new(vec![0.0, 4.0], vec![0.1, -0.1]).unwrap(),
    };
    let fam = ScheduledSystem::new(vec![schedule], build, "oscillator losing its damping");
    assert!(check_stability(&fam, &[0.0, 1.0, 2.0]).is_ok());
    match check_stability(&fam, &[0.0, 1.0, 2.0, 3.0, 4.0]) {
        Err(Error::InvalidParameter { name, reason, .. }) => {
            assert!(name.contains("t = 3 s"), "{name}");
            assert!(reason.contains("unstable at t = 3 s"), "{reason}");
        }
        other => panic!("expected a refusal at t = 3 s, got {other:?}"),
    }
}

fn refused_name<T: std::fmt::Debug>(r: stochvib::Result<T>) -> String {
    match r {
        Err(Error::InvalidParameter { name, .. }) => name,
        other => panic!("expected an invalid-parameter error, got {other:?}"),
    }
}

/// A speed profile that is not a function of time (a repeated or decreasing time), a negative speed, an
/// acceleration that never reaches the target speed, and an envelope that is not finite or a negative
/// intensity are refused, naming the table element.
#[test]
fn bad_profiles_and_envelopes_are_refused_by_name() {
    assert_eq!(
        refused_name(SpeedProfile::table(vec![0.0, 5.0, 5.0], vec![1.0, 2.0, 3.0])),
        "time[2]"
    );
    assert_eq!(
        refused_name(SpeedProfile::table(vec![0.0, 5.0, 4.0], vec![1.0, 2.0, 3.0])),
        "time[2]"
    );
    assert_eq!(
        refused_name(SpeedProfile::table(vec![0.0, 5.0], vec![10.0, -1.0])),
        "speed[1]"
    );
    assert_eq!(
        refused_name(SpeedProfile::table(vec![0.0, 5.0], vec![10.0, f64::NAN])),
        "speed[1]"
    );
    assert_eq!(
        refused_name(
            ConstantAcceleration {
                from_m_s: 10.0,
                to_m_s: 0.0,
                acceleration_m_s2: 2.0,
                start_s: 0.0
            }
            .build()
        ),
        "acceleration"
    );
    assert_eq!(
        refused_name(Envelope::table(vec![0.0, 1.0], vec![0.0, f64::INFINITY])),
        "envelope[1]"
    );
    assert_eq!(
        refused_name(Envelope::intensity(vec![0.0, 1.0], vec![0.0, -0.5])),
        "envelope[1]"
    );
    assert_eq!(refused_name(Envelope::ramp(f64::NAN)), "time[1]");
}

/// The exact route exists for rational spectra and for w = 2 roads without a band; an ISO road with its band
/// edges under a speed profile has none and says "use Monte Carlo"; a road spectrum without a speed is
/// refused by name.
#[test]
fn inputs_without_an_exact_route_say_so() {
    let v = common::accelerating_5_to_15();
    let banded = PowerLaw::iso8608(IsoClass::C, IsoBound::GeometricMean, Some((0.011, 2.83))).unwrap();
    match input_model(&banded, Some(&v)) {
        Err(Error::NotApplicable { reason, .. }) => assert!(reason.contains("use Monte Carlo"), "{reason}"),
        other => panic!("expected not applicable, got {other:?}"),
    }
    let open = PowerLaw::iso8608(IsoClass::C, IsoBound::GeometricMean, None).unwrap();
    assert_eq!(refused_name(input_model(&open, None)), "speed");
}
