//! A precomputed, allocation-free evaluator of one output's density S_y(ω), for quadrature.

use super::Excitation;
use crate::error::Result;
use crate::spectrum::Spectrum;
use crate::system::{FrequencyResponse, StateSpace};
use nalgebra::{Complex, DMatrix};
use std::sync::Arc;

type C64 = Complex<f64>;

/// The two-sided density S_y(ω) of one output, set up once and then evaluated at many ω without heap
/// allocation (the Hessenberg route below allocates one workspace per ω above 16 states). It computes
/// what [`output_density`](super::output_density) computes, up to rounding; `output_density` stays the
/// plain dense reference (a full complex solve of (iωI − A) X = B per ω).
///
/// # Formula
/// For a state-space system the constructor first tries the **modal** form: the complex Schur form
/// A = Q T Qᴴ gives the eigenvalues λ_k = T_kk and the eigenvectors V = Q Y (Y unit upper triangular),
/// and then
/// ```text
/// H_ij(iω) = Σ_k r_kj / (iω − λ_k) + D_ij + iω E_ij,     r_kj = (c_i V)_k (V⁻¹ b_j)_k,
/// ```
/// O(n) per column and ω, one real division per term. It is used when the eigenvector condition number
/// ‖Y‖_F‖Y⁻¹‖_F ≤ 1e5 (error ≲ 1e5·ε relative to the terms summed). Otherwise (nearly defective A, e.g. a
/// critically damped mode) it reduces Aᵀ to upper **Hessenberg** form, Aᵀ = Q H Qᵀ (Householder), with
/// c̃ = Qᵀ c_iᵀ (c_i: row i of C) and B̃ = Qᵀ B:
/// ```text
/// H_ij(iω) = c_i (iωI − A)⁻¹ b_j + D_ij + iω E_ij = B̃_jᵀ x + D_ij + iω E_ij,   (iωI − H) x = c̃
/// ```
/// so one O(n²) Hessenberg solve (Gaussian elimination with partial pivoting, which only ever swaps
/// neighbouring rows) gives the whole row i; this is backward stable, like the dense solve.
/// The density is S_y = S(ω)|Σ_g e^{−iωτ_g} Σ_{j: τ_j = τ_g} g_j H_ij|² for a track (inputs with equal
/// delays are summed before the phase; a single delay group needs no phase at all), and
/// S_y = Σ_j |H_ij|² S_j(ω) for independent inputs. Systems without a state-space form use their own
/// [`FrequencyResponse::response`] per ω.
///
/// # Errors
/// [`OutputDensity::new`] rejects an excitation with the wrong number of inputs and an output index out
/// of range. Stability is not checked here (the variance functions check it); at an exact pole on the
/// imaginary axis the density is +∞.
///
/// # Examples
/// ```
/// use stochvib::response::{output_density, Excitation, OutputDensity};
/// use stochvib::spectrum::{Domain, Exponential};
/// use stochvib::system::{OutputInfo, StateSpace};
/// use nalgebra::DMatrix;
/// use std::sync::Arc;
/// // SDOF oscillator ẍ + 2ζω₀ẋ + ω₀²x = u, output x, under an exponentially correlated input
/// let (w0, z) = (10.0, 0.05);
/// let a = DMatrix::from_row_slice(2, 2, &[0.0, 1.0, -w0 * w0, -2.0 * z * w0]);
/// let b = DMatrix::from_row_slice(2, 1, &[0.0, 1.0]);
/// let c = DMatrix::from_row_slice(1, 2, &[1.0, 0.0]);
/// let ss = StateSpace::new(a, b, c, None, None, vec![OutputInfo::new("x", "m")]).unwrap();
/// let exc = Excitation::single(Arc::new(Exponential::new(1.0, 2.0, Domain::Temporal).unwrap()), 0.0).unwrap();
/// let fast = OutputDensity::new(&ss, &exc, 0).unwrap();
/// let w = 9.5;
/// // |H|² = 1/((ω₀² − ω²)² + (2ζω₀ω)²), S(ω) = Dα/(π(α² + ω²)) with D = 1, α = 2
/// let closed = 1.0 / ((w0 * w0 - w * w).powi(2) + (2.0 * z * w0 * w).powi(2)) * 2.0 / (std::f64::consts::PI * (4.0 + w * w));
/// assert!((fast.density(w) - closed).abs() < 1e-13 * closed);
/// assert!((fast.density(w) - output_density(&ss, &exc, 0, w)).abs() < 1e-13 * closed);
/// ```
#[derive(Debug, Clone)]
pub struct OutputDensity<'a> {
    row: Row<'a>,
    input: Input,
}

/// How H_i·(iω) is obtained.
#[derive(Debug, Clone)]
enum Row<'a> {
    /// Partial fractions Σ_k r_k/(iω − λ_k) + d + iωe per (grouped) column, from a complex Schur form
    /// with well-conditioned eigenvectors.
    Modal { lambdas: Vec<C64>, cols: Vec<ModalColumn> },
    /// Hessenberg form of a state-space system; `cols` are the (grouped) columns of B̃ with their D, E
    /// entries.
    Hessenberg {
        n: usize,
        /// −H, row-major n × n (only the upper Hessenberg part is read).
        neg_h: Vec<f64>,
        /// c̃ = Qᵀ c_iᵀ.
        ct: Vec<f64>,
        cols: Vec<Column>,
    },
    /// No state-space form: the system's own response per ω.
    Dense { sys: &'a dyn FrequencyResponse, i: usize },
}

/// One (grouped) input column of the Hessenberg form.
#[derive(Debug, Clone)]
struct Column {
    b: Vec<f64>,
    d: f64,
    e: f64,
}

/// One (grouped) input column in modal form: residues r_k, D and E entries.
#[derive(Debug, Clone)]
struct ModalColumn {
    r: Vec<C64>,
    d: f64,
    e: f64,
}

/// Largest eigenvector condition number ‖Y‖_F ‖Y⁻¹‖_F for which the modal route is used: its error,
/// relative to the size of the terms summed, is about this times the unit roundoff (≈ 2e-11 at most);
/// beyond it (nearly defective A, e.g. a critically damped mode) the Hessenberg solve is used.
const MODAL_CONDITION_MAX: f64 = 1e5;

/// The input side.
#[derive(Debug, Clone)]
enum Input {
    /// One process: spectrum, groups of equal delay (τ_g, and for the dense row the (input, gain) pairs).
    Track {
        spectrum: Arc<dyn Spectrum>,
        delays: Vec<f64>,
        members: Vec<Vec<(usize, f64)>>,
    },
    /// Independent processes, one per input.
    Independent { spectra: Vec<Arc<dyn Spectrum>> },
    /// General sources: the row per input, combined by [`super::sources`]' density.
    Sources {
        sources: Vec<super::Source>,
        inputs: Vec<super::InputMap>,
    },
}

impl<'a> OutputDensity<'a> {
    /// Sets up the evaluator of S_y(ω) for output `i` of `sys` under `exc`.
    ///
    /// # Errors
    /// See the type's `# Errors`.
    pub fn new(sys: &'a dyn FrequencyResponse, exc: &Excitation, i: usize) -> Result<Self> {
        super::variance::check_shapes(sys, exc, i)?;
        let input = match exc {
            Excitation::Track {
                spectrum,
                delays,
                gains,
                ..
            } => {
                let mut groups: Vec<f64> = Vec::new();
                let mut members: Vec<Vec<(usize, f64)>> = Vec::new();
                for (j, (&t, &g)) in delays.iter().zip(gains).enumerate() {
                    match groups.iter().position(|&u| u == t) {
                        Some(k) => members[k].push((j, g)),
                        None => {
                            groups.push(t);
                            members.push(vec![(j, g)]);
                        }
                    }
                }
                Input::Track {
                    spectrum: spectrum.clone(),
                    delays: groups,
                    members,
                }
            }
            Excitation::Independent { spectra, .. } => Input::Independent {
                spectra: spectra.clone(),
            },
            Excitation::Sources { sources, inputs } => Input::Sources {
                sources: sources.clone(),
                inputs: inputs.clone(),
            },
        };
        let row = match sys.state_space() {
            None => Row::Dense { sys, i },
            Some(ss) => {
                let groups: Vec<Vec<(usize, f64)>> = match &input {
                    Input::Track { members, .. } => members.clone(),
                    Input::Independent { spectra } => (0..spectra.len()).map(|j| vec![(j, 1.0)]).collect(),
                    Input::Sources { inputs, .. } => (0..inputs.len()).map(|j| vec![(j, 1.0)]).collect(),
                };
                modal_row(ss, i, &groups).unwrap_or_else(|| hessenberg_row(ss, i, &groups))
            }
        };
        Ok(OutputDensity { row, input })
    }

    /// S_y(ω), two-sided, at angular frequency ω (rad/s).
    pub fn density(&self, omega: f64) -> f64 {
        match &self.row {
            Row::Modal { lambdas, cols } => {
                let h = |c: &ModalColumn| -> C64 {
                    let mut acc = C64::new(c.d, omega * c.e);
                    for (r, l) in c.r.iter().zip(lambdas) {
                        // r / (iω − λ) with one real division
                        let (re, im) = (-l.re, omega - l.im);
                        let inv = 1.0 / (re * re + im * im);
                        acc += C64::new(r.re * re + r.im * im, r.im * re - r.re * im) * inv;
                    }
                    acc
                };
                self.combine(omega, cols.iter().map(h))
            }
            Row::Hessenberg { n, .. } => match *n {
                0..=4 => self.hessenberg::<16, 4>(omega),
                5..=8 => self.hessenberg::<64, 8>(omega),
                9..=16 => self.hessenberg::<256, 16>(omega),
                n => {
                    let mut w = vec![C64::new(0.0, 0.0); n * n];
                    let mut x = vec![C64::new(0.0, 0.0); n];
                    self.hessenberg_with(omega, &mut w, &mut x)
                }
            },
            Row::Dense { sys, i } => {
                let h = sys.response(omega);
                let hij = |j: usize| h[(*i, j)];
                match &self.input {
                    Input::Track {
                        spectrum,
                        delays,
                        members,
                    } => {
                        let group = |m: &Vec<(usize, f64)>| m.iter().map(|&(j, g)| hij(j) * g).sum::<C64>();
                        let z = if delays.len() == 1 {
                            group(&members[0])
                        } else {
                            delays
                                .iter()
                                .zip(members)
                                .map(|(&t, m)| phase(t, omega) * group(m))
                                .sum()
                        };
                        spectrum.density(omega) * z.norm_sqr()
                    }
                    Input::Independent { spectra } => spectra
                        .iter()
                        .enumerate()
                        .map(|(j, s)| hij(j).norm_sqr() * s.density(omega))
                        .sum(),
                    Input::Sources { sources, inputs } => {
                        let row: Vec<C64> = (0..inputs.len()).map(hij).collect();
                        super::sources::density(sources, inputs, &row, omega)
                    }
                }
            }
        }
    }

    /// The Hessenberg route with stack workspaces of NN ≥ n² and N ≥ n entries.
    #[inline]
    fn hessenberg<const NN: usize, const N: usize>(&self, omega: f64) -> f64 {
        let mut w = [C64::new(0.0, 0.0); NN];
        let mut x = [C64::new(0.0, 0.0); N];
        self.hessenberg_with(omega, &mut w, &mut x)
    }

    #[inline]
    fn hessenberg_with(&self, omega: f64, w: &mut [C64], x: &mut [C64]) -> f64 {
        let Row::Hessenberg { n, neg_h, ct, cols } = &self.row else {
            unreachable!("only called for the Hessenberg row")
        };
        let n = *n;
        let s = C64::new(0.0, omega);
        if !hessenberg_solve(n, neg_h, ct, s, &mut w[..n * n], &mut x[..n]) {
            return f64::INFINITY;
        }
        let x = &x[..n];
        let h = |c: &Column| -> C64 {
            let mut acc = C64::new(c.d, omega * c.e);
            for (b, xk) in c.b.iter().zip(x) {
                acc += xk * *b;
            }
            acc
        };
        self.combine(omega, cols.iter().map(h))
    }

    /// S_y from the row values of the (grouped) columns, in the order of the delay groups (track) or of
    /// the inputs (independent).
    #[inline]
    fn combine(&self, omega: f64, mut h: impl Iterator<Item = C64>) -> f64 {
        match &self.input {
            Input::Track { spectrum, delays, .. } => {
                let z = if delays.len() == 1 {
                    h.next().unwrap_or_default()
                } else {
                    delays.iter().zip(h).map(|(&t, v)| phase(t, omega) * v).sum()
                };
                spectrum.density(omega) * z.norm_sqr()
            }
            Input::Independent { spectra } => spectra
                .iter()
                .zip(h)
                .map(|(sp, v)| v.norm_sqr() * sp.density(omega))
                .sum(),
            Input::Sources { sources, inputs } => {
                let row: Vec<C64> = h.collect();
                super::sources::density(sources, inputs, &row, omega)
            }
        }
    }
}

/// Σ_{(j, g) ∈ group} g·M[(r, j)] for one row r of a matrix M.
fn group_sum(m: &DMatrix<f64>, r: usize, group: &[(usize, f64)]) -> f64 {
    group.iter().map(|&(j, g)| g * m[(r, j)]).sum()
}

/// The Hessenberg form of output `i`: Aᵀ = Q H Qᵀ, c̃ = Qᵀ c_iᵀ, B̃ = Qᵀ B with the columns of each group
/// summed with their gains.
fn hessenberg_row<'a>(ss: &StateSpace, i: usize, groups: &[Vec<(usize, f64)>]) -> Row<'a> {
    let n = ss.n_states();
    let (q, h) = if n >= 2 {
        nalgebra::linalg::Hessenberg::new(ss.a.transpose()).unpack()
    } else {
        (DMatrix::identity(n, n), ss.a.transpose())
    };
    let ct: Vec<f64> = (0..n).map(|k| (0..n).map(|l| q[(l, k)] * ss.c[(i, l)]).sum()).collect();
    let bt = q.transpose() * &ss.b;
    let cols = groups
        .iter()
        .map(|g| Column {
            b: (0..n).map(|k| group_sum(&bt, k, g)).collect(),
            d: group_sum(&ss.d, i, g),
            e: group_sum(&ss.e, i, g),
        })
        .collect();
    Row::Hessenberg {
        n,
        neg_h: (0..n * n).map(|r| -h[(r / n, r % n)]).collect(),
        ct,
        cols,
    }
}

/// The modal (partial-fraction) form of output `i`, or `None` when the eigenvectors are ill-conditioned
/// (or the Schur iteration fails).
///
/// A = Q T Qᴴ (complex Schur, T upper triangular, λ_k = T_kk); the eigenvectors of T are the columns of
/// the unit upper triangular Y, (T − λ_k I) y_k = 0, so A = V Λ V⁻¹ with V = Q Y and
/// c_i (sI − A)⁻¹ b = Σ_k (c_i V)_k (V⁻¹ b)_k / (s − λ_k).
fn modal_row<'a>(ss: &StateSpace, i: usize, groups: &[Vec<(usize, f64)>]) -> Option<Row<'a>> {
    let n = ss.n_states();
    let zero = C64::new(0.0, 0.0);
    let (q, t) = if n == 0 {
        (DMatrix::zeros(0, 0), DMatrix::zeros(0, 0))
    } else {
        let ac = ss.a.map(|v| C64::new(v, 0.0));
        nalgebra::linalg::Schur::try_new(ac, f64::EPSILON, 10_000)?.unpack()
    };
    let lambdas: Vec<C64> = (0..n).map(|k| t[(k, k)]).collect();
    let scale = t.iter().map(|v| v.norm()).fold(0.0, f64::max);
    // Y: unit upper triangular eigenvectors of T
    let mut y = DMatrix::<C64>::identity(n, n);
    for k in 0..n {
        for j in (0..k).rev() {
            let mut acc = zero;
            for l in j + 1..=k {
                acc += t[(j, l)] * y[(l, k)];
            }
            let gap = t[(j, j)] - lambdas[k];
            if gap.norm() <= 1e-8 * scale {
                return None;
            }
            y[(j, k)] = -acc / gap;
        }
    }
    // Y⁻¹ (unit upper triangular) by back substitution, column by column
    let mut yi = DMatrix::<C64>::identity(n, n);
    for k in 0..n {
        for j in (0..k).rev() {
            let mut acc = zero;
            for l in j + 1..=k {
                acc += y[(j, l)] * yi[(l, k)];
            }
            yi[(j, k)] = -acc;
        }
    }
    let cond = y.norm() * yi.norm();
    if cond.is_nan() || cond > MODAL_CONDITION_MAX {
        return None;
    }
    let cv = ss.c.row(i).map(|v| C64::new(v, 0.0)) * (&q * &y);
    let qh_b = q.adjoint() * ss.b.map(|v| C64::new(v, 0.0));
    let w = &yi * qh_b; // V⁻¹ B
    let cols = groups
        .iter()
        .map(|g| ModalColumn {
            r: (0..n)
                .map(|k| cv[k] * g.iter().map(|&(j, gain)| w[(k, j)] * gain).sum::<C64>())
                .collect(),
            d: group_sum(&ss.d, i, g),
            e: group_sum(&ss.e, i, g),
        })
        .collect();
    Some(Row::Modal { lambdas, cols })
}

/// e^{−iωτ}, exactly 1 for τ = 0.
#[inline]
fn phase(tau: f64, omega: f64) -> C64 {
    if tau == 0.0 {
        C64::new(1.0, 0.0)
    } else {
        C64::from_polar(1.0, -omega * tau)
    }
}

/// Solves (sI + N) x = r for an upper Hessenberg N (`neg_h`, row-major n × n) and a real right-hand side,
/// by Gaussian elimination with partial pivoting in the workspace `w` (n²). Returns false for an exactly
/// singular matrix.
#[inline]
fn hessenberg_solve(n: usize, neg_h: &[f64], r: &[f64], s: C64, w: &mut [C64], x: &mut [C64]) -> bool {
    if n == 0 {
        return true;
    }
    for i in 0..n {
        let lo = i.saturating_sub(1);
        for j in lo..n {
            w[i * n + j] = C64::new(neg_h[i * n + j], 0.0);
        }
        w[i * n + i] += s;
        x[i] = C64::new(r[i], 0.0);
    }
    for k in 0..n - 1 {
        let (top, rest) = w.split_at_mut((k + 1) * n);
        let (rk, rk1) = (&mut top[k * n..], &mut rest[..n]);
        if rk1[k].norm_sqr() > rk[k].norm_sqr() {
            for j in k..n {
                std::mem::swap(&mut rk[j], &mut rk1[j]);
            }
            x.swap(k, k + 1);
        }
        if rk[k] == C64::new(0.0, 0.0) {
            return false;
        }
        let l = rk1[k] / rk[k];
        for j in k + 1..n {
            rk1[j] -= l * rk[j];
        }
        let xk = x[k];
        x[k + 1] -= l * xk;
    }
    for k in (0..n).rev() {
        let row = &w[k * n..(k + 1) * n];
        let mut acc = x[k];
        for j in k + 1..n {
            acc -= row[j] * x[j];
        }
        if row[k] == C64::new(0.0, 0.0) {
            return false;
        }
        x[k] = acc / row[k];
    }
    true
}
