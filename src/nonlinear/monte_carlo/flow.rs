//! The linear flows of route 2 (the L_h of the splitting, see [`crate::nonlinear::integrator`]) and how the
//! inputs and the linear part of the outputs are read from their state.
//!
//! * [`ExactFlow`]: the linear part augmented with the inputs' shaping filters, z = [filter states; q̃; p̃],
//!   discretised by Van Loan's method (the draws and the arithmetic of a linear exact-route run, so that
//!   zero nonlinearity reproduces its samples); inputs and outputs are rows of z.
//! * [`FohFlow`]: the linear part's state x̃ = [q̃; p̃] stepped by the first-order hold of synthesised input
//!   samples; outputs are C x̃ + D ũ + E u̇.
//!
//! Both hold fluctuations about the linear part's static equilibrium under the input means; the plan adds
//! the equilibrium back where the elements need absolute deflections.

use crate::error::{Error, Result};
use crate::nonlinear::integrator::Lanes;
use crate::response::{augmented_system, Excitation};
use crate::simulate::{covariance_factor, foh, van_loan, GaussMarkov};
use crate::system::{FrequencyResponse, Mdof, Quantity};
use nalgebra::DMatrix;

pub(crate) fn row_major(m: &DMatrix<f64>) -> Vec<f64> {
    let mut v = Vec::with_capacity(m.len());
    for i in 0..m.nrows() {
        for j in 0..m.ncols() {
            v.push(m[(i, j)]);
        }
    }
    v
}

/// Φ and the noise factor L of one step.
#[derive(Debug, Clone)]
pub(crate) struct NoisyStep {
    pub phi: Vec<f64>,
    pub l: Vec<f64>,
}

impl NoisyStep {
    fn new(a: &DMatrix<f64>, g: &DMatrix<f64>, h: f64) -> Result<NoisyStep> {
        let d = van_loan(a, g, h)?;
        Ok(NoisyStep {
            phi: row_major(&d.phi),
            l: row_major(&covariance_factor(&d.qd)?),
        })
    }
}

/// The exact flow (see the module docs).
#[derive(Debug, Clone)]
pub(crate) struct ExactFlow {
    /// States of z.
    pub nz: usize,
    /// Offset of q̃ in z (the number of filter states).
    pub mech: usize,
    /// The step of h and of h/2 (for the Δt-halving check).
    pub coarse: NoisyStep,
    pub fine: NoisyStep,
    /// The stationary law of the starting point.
    pub start: GaussMarkov,
    /// Row of every base input's fluctuation ũ_j, and of its rate where needed.
    pub u_rows: Vec<Vec<f64>>,
    pub ud_rows: Vec<Option<Vec<f64>>>,
    /// Row of every simulated output's linear part.
    pub out_rows: Vec<Vec<f64>>,
}

/// An output that cannot be sampled on the exact route: it contains the driving white noise.
pub(crate) const WHITE: &str =
    "contains the driving white noise directly (infinite variance): its samples are not defined";

/// The augmented state matrix A, noise matrix G, output row h and whether the output contains the white
/// noise directly.
type Augmented = (DMatrix<f64>, DMatrix<f64>, Vec<f64>, bool);

/// The augmented (A, G, h, f) of output `i` of `sys` under `exc`.
fn row(sys: &Mdof, exc: &Excitation, i: usize) -> Result<Augmented> {
    let ss = sys.state_space().ok_or_else(|| Error::Numerical {
        what: "exact route".into(),
        reason: "no state space".into(),
    })?;
    let aug = augmented_system(ss, exc, i)?;
    let white = aug.f.amax() > 0.0;
    Ok((aug.a, aug.g, aug.h.row(0).iter().copied().collect(), white))
}

impl ExactFlow {
    /// The flow of `linear` (the linear part) under `exc` at step h, started from the stationary law of
    /// `start` (the route-1 equivalent, or the linear part); `outputs` the simulated outputs, `rates` whether
    /// the rate of each base input is needed.
    ///
    /// # Errors
    /// The exact route does not apply (delays, non-rational spectra, two tracks); a base input with white
    /// noise in it; an unstable starting law.
    pub(crate) fn new(
        linear: &Mdof,
        start: &Mdof,
        exc: &Excitation,
        outputs: &[usize],
        rates: &[bool],
        h: f64,
    ) -> Result<ExactFlow> {
        let nb = linear.n_base();
        let n = linear.n_coords();
        let mut probe = linear.clone();
        for j in 0..nb {
            probe = probe
                .with_output(
                    &format!("-u{j}"),
                    Quantity::RelativeDisplacement {
                        point: vec![0.0; n],
                        base: j,
                    },
                )?
                .with_output(
                    &format!("-du{j}"),
                    Quantity::RelativeVelocity {
                        point: vec![0.0; n],
                        base: j,
                    },
                )?;
        }
        let p = linear.outputs().len();
        let (a, g, _, _) = row(&probe, exc, 0)?;
        let nz = a.nrows();
        let mut u_rows = Vec::with_capacity(nb);
        let mut ud_rows = Vec::with_capacity(nb);
        for (j, &rate) in rates.iter().enumerate().take(nb) {
            let (_, _, hu, white) = row(&probe, exc, p + 2 * j)?;
            if white {
                return Err(Error::invalid(
                    "input",
                    j,
                    "a base input of white noise has no samples: an element or the linear part needs it",
                ));
            }
            u_rows.push(hu.iter().map(|v| -v).collect());
            let (_, _, hd, white) = row(&probe, exc, p + 2 * j + 1)?;
            ud_rows.push((rate && !white).then(|| hd.iter().map(|v| -v).collect()));
            if rate && white {
                return Err(Error::invalid(
                    "input",
                    j,
                    "a velocity-dependent element on this base input needs its rate, which contains white noise \
                     (infinite variance): give the input a spectrum decaying faster than ω⁻²",
                ));
            }
        }
        let out_rows = outputs
            .iter()
            .map(|&i| {
                let (_, _, hr, white) = row(&probe, exc, i)?;
                if white {
                    return Err(Error::Divergent {
                        quantity: format!("samples of `{}`", linear.outputs()[i].name),
                        reason: WHITE.into(),
                    });
                }
                Ok(hr)
            })
            .collect::<Result<Vec<_>>>()?;
        let (a0, g0, _, _) = row(start, exc, 0)?;
        let start = GaussMarkov::new(a0, g0, DMatrix::zeros(1, nz), h)?;
        Ok(ExactFlow {
            nz,
            mech: nz - 2 * n,
            coarse: NoisyStep::new(&a, &g, h)?,
            fine: NoisyStep::new(&a, &g, 0.5 * h)?,
            start,
            u_rows,
            ud_rows,
            out_rows,
        })
    }

    /// z ← Φz + Lw with fresh normals w (n of them, drawn first), in the order of a linear exact-route run
    /// (noise terms first for up to 8 states, the Φz terms first beyond).
    pub(crate) fn step(
        &self,
        s: &NoisyStep,
        z: &mut [f64],
        w: &mut [f64],
        next: &mut [f64],
        normals: &mut crate::simulate::StreamNormals<rand::rngs::Xoshiro256PlusPlus>,
    ) {
        normals.fill(w);
        self.step_with(s, z, w, next);
    }

    /// z ← Φz + Lw for given normals w.
    pub(crate) fn step_with(&self, s: &NoisyStep, z: &mut [f64], w: &[f64], next: &mut [f64]) {
        let n = self.nz;
        if n <= 8 {
            for (i, o) in next.iter_mut().enumerate() {
                let (l, ph) = (&s.l[i * n..(i + 1) * n], &s.phi[i * n..(i + 1) * n]);
                let mut acc = l[0] * w[0];
                for j in 1..n {
                    acc += l[j] * w[j];
                }
                for j in 0..n {
                    acc += ph[j] * z[j];
                }
                *o = acc;
            }
        } else {
            for (i, o) in next.iter_mut().enumerate() {
                let (l, ph) = (&s.l[i * n..(i + 1) * n], &s.phi[i * n..(i + 1) * n]);
                let mut acc = 0.0;
                for j in 0..n {
                    acc += ph[j] * z[j];
                }
                for j in 0..n {
                    acc += l[j] * w[j];
                }
                *o = acc;
            }
        }
        z.copy_from_slice(next);
    }

    /// The noise of one coarse step built from the two fine steps' normals: η = Φ_f L_f w₁ + L_f w₂ (the
    /// same Brownian path as the fine steps; N(0, Q_d(h)) exactly).
    pub(crate) fn coupled_noise(&self, w1: &[f64], w2: &[f64], out: &mut [f64]) {
        let n = self.nz;
        let f = &self.fine;
        let lw1: Vec<f64> = (0..n).map(|i| (0..n).map(|j| f.l[i * n + j] * w1[j]).sum()).collect();
        for (i, o) in out.iter_mut().enumerate() {
            let mut acc = 0.0;
            for j in 0..n {
                acc += f.phi[i * n + j] * lw1[j] + f.l[i * n + j] * w2[j];
            }
            *o = acc;
        }
    }

    /// z ← Φz + η for a given noise vector η.
    #[allow(clippy::needless_range_loop)] // row-major matrix products read clearest with indices
    pub(crate) fn step_noise(&self, s: &NoisyStep, z: &mut [f64], eta: &[f64], next: &mut [f64]) {
        let n = self.nz;
        for (i, o) in next.iter_mut().enumerate() {
            let mut acc = eta[i];
            for j in 0..n {
                acc += s.phi[i * n + j] * z[j];
            }
            *o = acc;
        }
        z.copy_from_slice(next);
    }
}

/// A first-order-hold step: x ← Φx + Γ₀u_k + Γ₁u_{k+1}.
#[derive(Debug, Clone)]
pub(crate) struct HoldStep {
    pub phi: Vec<f64>,
    pub g0: Vec<f64>,
    pub g1: Vec<f64>,
}

/// The first-order-hold flow (see the module docs).
#[derive(Debug, Clone)]
pub(crate) struct FohFlow {
    /// States (2n).
    pub nx: usize,
    /// Inputs (base, then force).
    pub m: usize,
    pub coarse: HoldStep,
    pub fine: HoldStep,
    /// C, D, E rows of every simulated output.
    pub c_rows: Vec<Vec<f64>>,
    pub d_rows: Vec<Vec<f64>>,
    pub e_rows: Vec<Vec<f64>>,
}

impl FohFlow {
    pub(crate) fn new(linear: &Mdof, outputs: &[usize], h: f64) -> Result<FohFlow> {
        let ss = linear.state_space().ok_or_else(|| Error::Numerical {
            what: "spectral route".into(),
            reason: "no state space".into(),
        })?;
        let hold = |dt: f64| -> Result<HoldStep> {
            let f = foh(&ss.a, &ss.b, dt)?;
            Ok(HoldStep {
                phi: row_major(&f.phi),
                g0: row_major(&f.gamma0),
                g1: row_major(&f.gamma1),
            })
        };
        let pick = |m: &DMatrix<f64>| outputs.iter().map(|&i| m.row(i).iter().copied().collect()).collect();
        Ok(FohFlow {
            nx: ss.a.nrows(),
            m: ss.b.ncols(),
            coarse: hold(h)?,
            fine: hold(0.5 * h)?,
            c_rows: pick(&ss.c),
            d_rows: pick(&ss.d),
            e_rows: pick(&ss.e),
        })
    }

    /// x ← Φx + Γ₀u₀ + Γ₁u₁ lane by lane (every row's sum from 0, Φ_ij x_j over j, then Γ₀u₀ + Γ₁u₁ per
    /// input, in a lane's order whatever the number of lanes).
    #[inline(always)]
    #[allow(clippy::needless_range_loop)] // row-major matrix products read clearest with indices
    pub(crate) fn step<const L: usize>(
        &self,
        s: &HoldStep,
        x: &mut [Lanes<L>],
        u0: &[Lanes<L>],
        u1: &[Lanes<L>],
        next: &mut [Lanes<L>],
    ) {
        // rows as slices zipped with the vectors: no bounds check per term (a step costs a few dozen terms)
        let (n, m) = (self.nx, self.m);
        for (i, (o, phi)) in next.iter_mut().zip(s.phi.chunks_exact(n)).enumerate() {
            let (g0, g1) = (&s.g0[i * m..(i + 1) * m], &s.g1[i * m..(i + 1) * m]);
            let mut acc = [0.0; L];
            for (a, xj) in phi.iter().zip(&*x) {
                for l in 0..L {
                    acc[l] += a * xj[l];
                }
            }
            for (((a, b), u0), u1) in g0.iter().zip(g1).zip(&u0[..m]).zip(&u1[..m]) {
                for l in 0..L {
                    acc[l] += a * u0[l] + b * u1[l];
                }
            }
            *o = acc;
        }
        x.copy_from_slice(next);
    }
}
