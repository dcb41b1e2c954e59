//! The frequency-weighted output of a linear system: W(s)·H_i(s) as one state-space system.

use super::weighting::Weighting;
use crate::error::{Error, Result};
use crate::system::{FrequencyResponse, OutputInfo, StateSpace};
use nalgebra::DMatrix;

/// Whether output `output` of `ss` can be weighted by `w` ([`weighted_output`]): the index is in range and
/// the output is an acceleration of the weighting's unit. Builds nothing: a file reader checks its keys
/// with it, the study that evaluates builds the cascade.
///
/// # Errors
/// [`Error::InvalidParameter`] when `output` is out of range, or when the output's unit is not the
/// acceleration unit the weighting applies to (`m/s^2` for translational weightings, `rad/s^2` for We).
///
/// # Examples
/// ```
/// use stochvib::comfort::{check_weightable, Weighting};
/// use stochvib::system::{Attach, Element, FrequencyResponse, Mdof, Quantity};
/// let el = Element { name: "cushion".into(), point: vec![1.0], to: Attach::Base(0), stiffness: 5e4, damping: 1e3 };
/// let m = Mdof::from_elements(&[("z", "m")], &[80.0], vec![el], 1, &[]).unwrap()
///     .with_output("seat_acc", Quantity::Acceleration(vec![1.0])).unwrap()
///     .with_output("seat_z", Quantity::Displacement(vec![1.0])).unwrap();
/// let ss = m.state_space().unwrap();
/// assert!(check_weightable(ss, 0, &Weighting::Wk).is_ok());
/// assert!(check_weightable(ss, 1, &Weighting::Wk).is_err()); // a displacement
/// assert!(check_weightable(ss, 2, &Weighting::Wk).is_err()); // no such output
/// ```
pub fn check_weightable(ss: &StateSpace, output: usize, w: &Weighting) -> Result<()> {
    let p = ss.c.nrows();
    if output >= p {
        return Err(Error::invalid(
            "output",
            output,
            format!("the system has {p} output(s), indices 0..{}", p.saturating_sub(1)),
        ));
    }
    let info = &ss.outputs()[output];
    let expected_unit = w.quantity().unit;
    if !same_unit(&info.unit, expected_unit) {
        return Err(Error::invalid(
            &format!("unit of output `{}`", info.name),
            format!("\"{}\"", info.unit),
            format!(
                "the {} weighting applies to acceleration in {expected_unit}; weight an acceleration output",
                w.name()
            ),
        ));
    }
    Ok(())
}

/// The state-space system whose single output is output `output` of `ss` passed through the weighting
/// `w` (series connection), so that its frequency response is W(iω)·H_output(iω).
///
/// # Formula
/// The system is ẋ = Ax + Bu, y_i = C_i x + D_i u + E_i u̇ (row i = `output`), and the weighting's
/// cascade realisation ([`Weighting::state_space`]) is ẋ_w = A_w x_w + b_w v, z = c_w x_w + d_w v with
/// input v = y_i. Because y_i contains u̇, x_w would be driven by u̇; the change of variable
/// ξ = x_w − b_w E_i u removes it:
///
/// ```text
/// ξ̇ = A_w x_w + b_w (C_i x + D_i u + E_i u̇) − b_w E_i u̇
///   = A_w ξ + b_w C_i x + (b_w D_i + A_w b_w E_i) u
/// z  = c_w ξ + d_w C_i x + (c_w b_w E_i + d_w D_i) u + d_w E_i u̇
/// ```
/// so that, with the state X = [x; ξ],
///
/// ```text
/// A_c = [[A, 0], [b_w C_i, A_w]],   B_c = [[B], [b_w D_i + A_w b_w E_i]],
/// C_c = [d_w C_i, c_w],             D_c = c_w b_w E_i + d_w D_i,          E_c = d_w E_i.
/// ```
/// Check (Laplace domain, zero initial state):
///
/// ```text
/// Z = c_w(sI − A_w)⁻¹b_w [C_i(sI − A)⁻¹B + D_i] U + [c_w(sI − A_w)⁻¹A_w b_w + c_w b_w] E_i U + d_w Y_i,
/// (sI − A_w)⁻¹A_w + I = s(sI − A_w)⁻¹   ⇒   the E_i term is c_w s(sI − A_w)⁻¹b_w E_i U = (W(s) − d_w)·s·E_i U,
/// Z = W(s)·[C_i(sI − A)⁻¹B + D_i + sE_i]·U = W(s)·Y_i.
/// ```
///
/// Every ISO weighting is strictly proper with relative degree ≥ 2 (d_w = 0 and c_w b_w = 0), so
/// W(s)·s·E_i is strictly proper: the weighted output has **no** feedthrough, D_c = E_c = 0, even when
/// the unweighted output (an acceleration of a base-excited damped mass) has D ≠ 0 and E ≠ 0. Its
/// high-frequency density therefore decays and its variance is finite.
///
/// The output is named `<name>_<W>` (e.g. `seat_acc_Wk`) with the unit of the unweighted output.
///
/// # Errors
/// [`Error::InvalidParameter`] when `output` is out of range, or when the output's unit is not the
/// acceleration unit the weighting applies to (`m/s^2` for translational weightings, `rad/s^2` for We).
///
/// # Examples
/// ```
/// use stochvib::comfort::{weighted_output, Weighting};
/// use stochvib::system::{Attach, Element, FrequencyResponse, Mdof, Quantity};
/// // seat on a base: m = 80 kg, k = 5e4 N/m, b = 1e3 N s/m; output: absolute acceleration of the mass
/// let el = Element { name: "cushion".into(), point: vec![1.0], to: Attach::Base(0), stiffness: 5e4, damping: 1e3 };
/// let m = Mdof::from_elements(&[("z", "m")], &[80.0], vec![el], 1, &[]).unwrap()
///     .with_output("seat_acc", Quantity::Acceleration(vec![1.0])).unwrap();
/// let ss = m.state_space().unwrap();
/// let w = weighted_output(ss, 0, &Weighting::Wk).unwrap();
/// assert_eq!(w.outputs()[0].name, "seat_acc_Wk");
/// let omega = 2.0 * std::f64::consts::PI * 4.0;
/// let expected = Weighting::Wk.response(omega) * m.response(omega)[(0, 0)];
/// assert!((w.response(omega)[(0, 0)] - expected).norm() < 1e-9 * expected.norm());
/// assert!(w.e.iter().all(|v| *v == 0.0) && w.d.iter().all(|v| *v == 0.0));
/// ```
pub fn weighted_output(ss: &StateSpace, output: usize, w: &Weighting) -> Result<StateSpace> {
    check_weightable(ss, output, w)?;
    let info = &ss.outputs()[output];
    let (aw, bw, cw, dw) = w.cascade();
    let (n, m, nw) = (ss.n_states(), ss.b.ncols(), aw.nrows());
    let ci = ss.c.rows(output, 1).into_owned();
    let di = ss.d.rows(output, 1).into_owned();
    let ei = ss.e.rows(output, 1).into_owned();

    let mut a = DMatrix::zeros(n + nw, n + nw);
    a.view_mut((0, 0), (n, n)).copy_from(&ss.a);
    a.view_mut((n, 0), (nw, n)).copy_from(&(&bw * &ci));
    a.view_mut((n, n), (nw, nw)).copy_from(&aw);

    let mut b = DMatrix::zeros(n + nw, m);
    b.view_mut((0, 0), (n, m)).copy_from(&ss.b);
    let aw_bw = &aw * &bw;
    b.view_mut((n, 0), (nw, m)).copy_from(&(&bw * &di + &aw_bw * &ei));

    let mut c = DMatrix::zeros(1, n + nw);
    c.view_mut((0, 0), (1, n)).copy_from(&(&ci * dw));
    c.view_mut((0, n), (1, nw)).copy_from(&cw);

    let cw_bw = (&cw * &bw)[(0, 0)];
    let d = &ei * cw_bw + &di * dw;
    let e = &ei * dw;
    StateSpace::new(
        a,
        b,
        c,
        Some(d),
        Some(e),
        vec![OutputInfo::new(
            format!("{}_{}", info.name, w.name()),
            info.unit.clone(),
        )],
    )
}

/// `m/s^2` and `m/s²` are the same unit (and likewise for rad).
pub(crate) fn same_unit(unit: &str, expected: &str) -> bool {
    let norm = |u: &str| u.trim().replace('²', "^2").replace(' ', "");
    norm(unit) == norm(expected)
}
