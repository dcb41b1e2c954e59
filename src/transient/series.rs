//! The statistics of every output over time from the exact route: mean(t), σ(t), the rates of the
//! derivative, crossing rates ν₀⁺(t), ν⁺(b, t) and the expected number of crossings over the mission.

use super::lyapunov_ode::{propagate, ExactOptions, StepReport};
use super::system::{Frozen, Start, TimeVaryingSystem};
use crate::error::Result;
use crate::extremes::{rice_rate, rice_rate_two_sided, Barrier, RiceState};
use nalgebra::{DMatrix, DVector};

/// One output over time (all vectors indexed like [`TransientSolution::times`]).
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct OutputSeries {
    /// Output name.
    pub name: String,
    /// SI unit.
    pub unit: String,
    /// m(t) = E y(t).
    pub mean: Vec<f64>,
    /// σ_y(t).
    pub sigma: Vec<f64>,
    /// ṁ(t) = E ẏ(t).
    pub mean_rate: Vec<f64>,
    /// σ_ẏ(t) (NaN when ẏ has a white component).
    pub sigma_rate: Vec<f64>,
    /// ρ(t), the correlation of y and ẏ at the same time (NaN as σ_ẏ, 0 where σ_y = 0).
    pub rho: Vec<f64>,
    /// Why the output has no finite σ (then the vectors are empty).
    pub unavailable: Option<String>,
    /// Why the crossing rates are missing, if they are.
    pub rate_note: Option<String>,
}

/// The expected number of crossings of a level over the mission and its quadrature error estimate.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct Crossings {
    /// ∫₀ᵀ ν(b, t) dt by the trapezoidal rule on the stored times.
    pub expected: f64,
    /// |T_h − T_2h|/3 (the trapezoidal rule on every other stored time), an estimate of its error.
    pub error_estimate: f64,
}

/// The exact route's answer: every output at every stored time.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct TransientSolution {
    /// Stored times, s.
    pub times: Vec<f64>,
    /// Per output.
    pub outputs: Vec<OutputSeries>,
    /// Accumulated relative error estimate of the state variances at each stored time.
    pub error_estimate: Vec<f64>,
    /// What the integrator did.
    pub report: StepReport,
    /// The start.
    pub start: Start,
}

impl OutputSeries {
    /// The Rice state at stored time k.
    pub fn state(&self, k: usize) -> RiceState {
        RiceState {
            mean: self.mean[k],
            mean_rate: self.mean_rate[k],
            sigma: self.sigma[k],
            sigma_rate: self.sigma_rate[k],
            rho: self.rho[k],
        }
    }

    /// ν₀⁺(t_k): up-crossings of the mean level by the fluctuation y − m, (1/2π)(σ_ẏ/σ_y)√(1 − ρ²), Hz.
    pub fn nu0_plus(&self, k: usize) -> f64 {
        if self.sigma[k] <= 0.0 {
            return 0.0;
        }
        let r = self.rho[k];
        self.sigma_rate[k] / self.sigma[k] * (1.0 - r * r).max(0.0).sqrt() / (2.0 * std::f64::consts::PI)
    }
}

impl TransientSolution {
    /// ν⁺(b, t_k) (one-sided) or the rate of leaving \[−b, b\] (two-sided), per stored time; NaN where the
    /// rates are missing ([`OutputSeries::rate_note`]).
    pub fn crossing_rates(&self, i: usize, level: f64, barrier: Barrier) -> Vec<f64> {
        let o = &self.outputs[i];
        (0..o.sigma.len())
            .map(|k| match barrier {
                Barrier::OneSided => rice_rate(level, &o.state(k)),
                Barrier::TwoSided => rice_rate_two_sided(level, &o.state(k)),
            })
            .collect()
    }

    /// [`Self::crossing_rates`] of both barriers at once, the two-sided rate from the one-sided one: ν⁺(b, t)
    /// of y plus that of −y (whose mean and mean rate change sign), as `rice_rate_two_sided` adds them (the
    /// same values; one Rice rate fewer per time). Where the mean and its rate are both zero, −y has the law
    /// of y and its rate is the same number, computed once (a zero mean and mean rate enter the rate only
    /// through b − m and ṁ + ρσ̇β, which ±0 leave unchanged unless they are zero themselves; then the rate
    /// may differ only in the sign of a zero).
    pub fn crossing_rates_both(&self, i: usize, level: f64) -> (Vec<f64>, Vec<f64>) {
        let o = &self.outputs[i];
        (0..o.sigma.len())
            .map(|k| {
                let s = o.state(k);
                let up = rice_rate(level, &s);
                if s.mean == 0.0 && s.mean_rate == 0.0 {
                    return (up, up + up);
                }
                let mirrored = RiceState {
                    mean: -s.mean,
                    mean_rate: -s.mean_rate,
                    ..s
                };
                (up, up + rice_rate(level, &mirrored))
            })
            .unzip()
    }

    /// The expected number of crossings ∫ν dt over the stored times.
    pub fn expected_crossings(&self, i: usize, level: f64, barrier: Barrier) -> Crossings {
        self.crossings(&self.crossing_rates(i, level, barrier))
    }

    /// The expected number of crossings ∫ν dt over the stored times from the rates ν at the stored times.
    pub fn crossings(&self, rates: &[f64]) -> Crossings {
        let fine = trapezoid(&self.times, rates, 1);
        let coarse = trapezoid(&self.times, rates, 2);
        Crossings {
            expected: fine.unwrap_or(f64::NAN),
            error_estimate: match (fine, coarse) {
                (Some(f), Some(c)) => (f - c).abs() / 3.0,
                _ => f64::NAN,
            },
        }
    }

    /// P(the level is crossed at least once over the stored times) with Poisson crossings at the
    /// integrated rate: 1 − exp(−∫ν dt).
    pub fn exceedance_probability(&self, i: usize, level: f64, barrier: Barrier) -> f64 {
        -(-self.expected_crossings(i, level, barrier).expected).exp_m1()
    }
}

/// Trapezoidal rule over every `stride`-th point (None when that leaves no interval or the grid does not
/// end on a used point).
fn trapezoid(t: &[f64], y: &[f64], stride: usize) -> Option<f64> {
    let n = t.len();
    if n < 2 || !(n - 1).is_multiple_of(stride) || (n - 1) / stride == 0 {
        return None;
    }
    Some(
        (0..(n - 1) / stride)
            .map(|j| {
                let (a, b) = (j * stride, (j + 1) * stride);
                0.5 * (y[a] + y[b]) * (t[b] - t[a])
            })
            .sum(),
    )
}

/// The derivative rows D = Ḣ + HF and the rate ẏ₀ at t (Ḣ, ẏ₀ by a one-sided difference for
/// time-varying coefficients).
fn derivative_rows(sys: &TimeVaryingSystem, t: f64, fr: &Frozen) -> Result<(DMatrix<f64>, DVector<f64>)> {
    let mut d = &fr.h * &fr.f;
    let mut y0_rate = DVector::zeros(fr.y0.len());
    if !sys.is_invariant() {
        let dt = 1e-7 * t.abs().max(1.0);
        let next = sys.frozen(t + dt)?;
        d += (&next.h - &fr.h) / dt;
        y0_rate = (&next.y0 - &fr.y0) / dt;
    }
    Ok((d, y0_rate))
}

/// The statistics of every output from the states' mean m and covariance P at t.
fn output_point(
    sys: &TimeVaryingSystem,
    t: f64,
    p: &DMatrix<f64>,
    m: &DVector<f64>,
    out: &mut [OutputSeries],
) -> Result<()> {
    let fr = sys.frozen(t)?;
    let (d, y0_rate) = derivative_rows(sys, t, &fr)?;
    for (i, o) in out.iter_mut().enumerate() {
        if o.unavailable.is_some() {
            continue;
        }
        let h = fr.h.row(i);
        let dr = d.row(i);
        let var = (h * p * h.transpose())[(0, 0)].max(0.0);
        o.mean.push((h * m)[(0, 0)] + fr.y0[i]);
        o.sigma.push(var.sqrt());
        let hg = h * &fr.g;
        let white = hg.amax() > 1e-12 * h.amax() * fr.g.amax();
        if white {
            o.rate_note = Some(
                "ẏ has a white-noise component (the output's density decays only like ω⁻²): no crossing rate".into(),
            );
            o.mean_rate.push(f64::NAN);
            o.sigma_rate.push(f64::NAN);
            o.rho.push(f64::NAN);
            continue;
        }
        let vd = (dr * p * dr.transpose())[(0, 0)].max(0.0);
        let c = (h * p * dr.transpose())[(0, 0)];
        o.mean_rate.push((dr * m)[(0, 0)] + (h * &fr.b)[(0, 0)] + y0_rate[i]);
        o.sigma_rate.push(vd.sqrt());
        let rho = if var > 0.0 && vd > 0.0 {
            (c / (var * vd).sqrt()).clamp(-1.0, 1.0)
        } else {
            0.0
        };
        o.rho.push(rho);
    }
    Ok(())
}

/// Solves the exact route for `sys` started as `start`, with the statistics of every output at `times`.
///
/// # Errors
/// The errors of [`TimeVaryingSystem::start`] and [`propagate`].
///
/// # Examples
/// ```
/// use stochvib::transient::{solve, Envelope, ExactOptions, FixedSystem, InputModel, Start, TimeVaryingSystem,
///     TransientInput};
/// use stochvib::system::{OutputInfo, StateSpace};
/// use nalgebra::DMatrix;
/// use std::sync::Arc;
/// // ẏ = −a y + w from rest, white w of density S₀: σ²(t) = πS₀(1 − e^{−2at})/a
/// let (a, s0) = (2.0, 0.5);
/// let ss = StateSpace::new(DMatrix::from_element(1, 1, -a), DMatrix::from_element(1, 1, 1.0),
///     DMatrix::from_element(1, 1, 1.0), None, None, vec![OutputInfo::new("y", "m")]).unwrap();
/// let fam = Arc::new(FixedSystem::new(ss, None, "first order").unwrap());
/// let input = TransientInput { model: InputModel::White { density: s0 }, envelope: Envelope::unit(), mean: 0.0,
///     gains: vec![1.0] };
/// let sys = TimeVaryingSystem::new(fam, input).unwrap();
/// let sol = solve(&sys, &Start::Rest, &[0.5, 1.0], &ExactOptions::default()).unwrap();
/// let exact = (std::f64::consts::PI * s0 * (1.0 - (-2.0 * a).exp()) / a).sqrt();
/// assert!((sol.outputs[0].sigma[1] - exact).abs() < 1e-12 * exact);
/// ```
pub fn solve(sys: &TimeVaryingSystem, start: &Start, times: &[f64], opts: &ExactOptions) -> Result<TransientSolution> {
    let (p0, m0) = sys.start(start)?;
    let mut outputs: Vec<OutputSeries> = sys
        .outputs()
        .iter()
        .enumerate()
        .map(|(i, o)| OutputSeries {
            name: o.name.clone(),
            unit: o.unit.clone(),
            mean: Vec::new(),
            sigma: Vec::new(),
            mean_rate: Vec::new(),
            sigma_rate: Vec::new(),
            rho: Vec::new(),
            unavailable: sys.unavailable(i).map(str::to_string),
            rate_note: None,
        })
        .collect();
    let mut error_estimate = Vec::with_capacity(times.len());
    let report = propagate(sys, p0, m0, times, opts, &mut |_, t, p, m, err| {
        error_estimate.push(err);
        output_point(sys, t, p, m, &mut outputs)
    })?;
    Ok(TransientSolution {
        times: times.to_vec(),
        outputs,
        error_estimate,
        report,
        start: start.clone(),
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// An output with a mean, a mean rate and a correlation of y and ẏ at every time (the mirrored process
    /// differs from y), and one time at rest (σ = 0).
    fn solution() -> TransientSolution {
        let k = 5;
        let output = OutputSeries {
            name: "y".into(),
            unit: "m".into(),
            mean: vec![0.0, 0.3, -0.2, 1.1, 0.05],
            sigma: vec![0.0, 0.5, 0.8, 1.2, 0.9],
            mean_rate: vec![0.0, 2.0, -1.5, 0.4, -0.1],
            sigma_rate: vec![0.0, 3.0, 5.0, 7.5, 6.0],
            rho: vec![0.0, 0.2, -0.35, 0.6, 0.0],
            unavailable: None,
            rate_note: None,
        };
        TransientSolution {
            times: (0..k).map(|j| j as f64 * 0.25).collect(),
            outputs: vec![output],
            error_estimate: vec![0.0; k],
            report: StepReport {
                steps: k,
                exact_steps: k,
                rejected: 0,
                exponentials: 1,
                max_error_estimate: 0.0,
            },
            start: Start::Rest,
        }
    }

    /// A zero-mean output (every mean and mean rate +0 or −0, σ > 0 after the start): the two-sided rates,
    /// whose mirrored half is then not computed again, have the bits of `rice_rate_two_sided`'s sum of both
    /// halves, at levels 0, ±0.3, 1.5 and 4.
    #[test]
    fn a_zero_mean_output_gives_the_two_sided_bits() {
        let mut sol = solution();
        sol.outputs[0].mean = vec![0.0, -0.0, 0.0, -0.0, 0.0];
        sol.outputs[0].mean_rate = vec![0.0, 0.0, -0.0, -0.0, 0.0];
        let bits = |v: &[f64]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
        for b in [0.0, 0.3, -0.3, 1.5, 4.0] {
            let (_, both) = sol.crossing_rates_both(0, b);
            let want = sol.crossing_rates(0, b, Barrier::TwoSided);
            assert!(
                want.iter().skip(1).all(|&v| v > 0.0),
                "b = {b}: every rate after the start is positive"
            );
            assert_eq!(bits(&both), bits(&want), "b = {b}");
        }
    }

    /// Both barriers' rates from one pass have the bits of each barrier's own rates, at levels below,
    /// at and above the means.
    #[test]
    fn both_barriers_at_once_give_the_bits_of_each() {
        let sol = solution();
        let bits = |v: &[f64]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
        for b in [-1.0, 0.0, 0.3, 1.5, 4.0] {
            let (up, both) = sol.crossing_rates_both(0, b);
            assert_eq!(bits(&up), bits(&sol.crossing_rates(0, b, Barrier::OneSided)), "b = {b}");
            assert_eq!(
                bits(&both),
                bits(&sol.crossing_rates(0, b, Barrier::TwoSided)),
                "b = {b}"
            );
        }
    }
}
