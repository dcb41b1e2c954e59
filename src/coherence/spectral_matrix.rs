//! A multi-component stationary process given by its cross-spectral density matrix S(ω), and the check
//! that such a matrix is a valid one (Hermitian, positive semi-definite).

use crate::error::{Error, Result};
use crate::spectrum::Spectrum;
use nalgebra::{Complex, DMatrix};
use std::fmt::Debug;
use std::sync::Arc;

/// A stationary process with `n_components()` correlated components (e.g. the left and right tracks of a
/// road) given by its two-sided cross-spectral density matrix in angular frequency.
///
/// # Formula
/// ```text
/// S_cd(ω) = (1/2π) ∫ E[x_c(t + τ) x_d(t)] e^{−iωτ} dτ,     S(ω) = S(ω)ᴴ ⪰ 0,   ω in rad/s
/// ```
/// so that an output y = Σ_c z_c x_c (z_c(ω) the complex gain of component c) has the density
/// S_y = Σ_{c,d} z_c S_cd conj(z_d). The diagonal S_cc are ordinary two-sided densities
/// ([`SpectralMatrix::component`]).
///
/// # Errors
/// Evaluation does not fail: implementations validate in their constructors, and
/// [`check_spectral_matrix`] checks a matrix at given frequencies.
///
/// # Examples
/// ```
/// use stochvib::coherence::{ConstantCoherence, SpectralMatrix, TwoTracks};
/// use stochvib::spectrum::{IsoClass, PowerLaw};
/// use std::sync::Arc;
/// let road = Arc::new(PowerLaw::iso_class(IsoClass::C).unwrap());
/// let tracks = TwoTracks::new(road, Arc::new(ConstantCoherence::new(0.5).unwrap()), 20.0).unwrap();
/// let s = tracks.matrix(3.0);
/// assert_eq!(tracks.n_components(), 2);
/// assert!((s[(0, 1)].re - 0.5 * s[(0, 0)].re).abs() < 1e-20);
/// ```
pub trait SpectralMatrix: Debug + Send + Sync {
    /// Short description with parameters and units.
    fn describe(&self) -> String;

    /// Number of components m.
    fn n_components(&self) -> usize;

    /// Name of component c (e.g. `left`, `right`).
    fn component_name(&self, c: usize) -> String;

    /// The auto-density S_cc of component c as a temporal spectrum (its asymptotes, support and
    /// breakpoints are those of the component).
    fn component(&self, c: usize) -> Arc<dyn Spectrum>;

    /// The m × m matrix S(ω), two-sided, ω in rad/s.
    fn matrix(&self, omega: f64) -> DMatrix<Complex<f64>>;

    /// An exact factorisation into independent processes with constant coefficients, when the matrix has
    /// one: parts (q_k, a_k) with
    ///
    /// ```text
    /// x_c(t) = Σ_k a_ck w_k(t),   w_k mutually uncorrelated with densities q_k S₀₀(ω),
    /// so that S_cd(ω) = Σ_k q_k a_ck a_dk S₀₀(ω)          (q_k ≥ 0, every component of density S₀₀)
    /// ```
    ///
    /// With it, an output driven by the components is a sum of outputs driven by independent single
    /// processes, each with the rational form of S₀₀ when that is rational: the exact (Lyapunov) routes
    /// apply. `None` (the default) when no such factorisation is known: a coherence that depends on the
    /// frequency makes the mixing depend on ω.
    fn independent_parts(&self) -> Option<Vec<(f64, Vec<f64>)>> {
        None
    }

    /// The normalised matrix C_cd(ω) = S_cd/√(S_cc S_dd) (the complex coherence; C_cc = 1), with C_cd = 0
    /// where a diagonal density vanishes.
    ///
    /// # Formula
    /// |C_cd|² = γ²_cd, the squared coherence of components c and d.
    fn coherence_matrix(&self, omega: f64) -> DMatrix<Complex<f64>> {
        let s = self.matrix(omega);
        let m = s.nrows();
        DMatrix::from_fn(m, m, |c, d| {
            if c == d {
                Complex::new(1.0, 0.0)
            } else {
                let q = (s[(c, c)].re * s[(d, d)].re).sqrt();
                if q > 0.0 {
                    s[(c, d)] / q
                } else {
                    Complex::new(0.0, 0.0)
                }
            }
        })
    }
}

/// Relative tolerance of [`check_spectral_matrix`]: Hermitian asymmetry and negative eigenvalues up to this
/// multiple of the largest diagonal entry are rounding.
pub const SPECTRAL_MATRIX_TOLERANCE: f64 = 1e-12;

/// Checks that S(ω) is Hermitian and positive semi-definite at every given frequency.
///
/// # Formula
/// |S_cd − conj(S_dc)| ≤ ε·max_c S_cc and λ_min(S) ≥ −ε·max_c S_cc, ε = [`SPECTRAL_MATRIX_TOLERANCE`].
///
/// # Errors
/// [`Error::InvalidParameter`] naming the matrix, the frequency, the entry or eigenvalue and the reason.
///
/// # Examples
/// ```
/// use stochvib::coherence::{check_spectral_matrix, ConstantCoherence, TwoTracks};
/// use stochvib::spectrum::{IsoClass, PowerLaw};
/// use std::sync::Arc;
/// let road = Arc::new(PowerLaw::iso_class(IsoClass::B).unwrap());
/// let t = TwoTracks::new(road, Arc::new(ConstantCoherence::new(1.0).unwrap()), 10.0).unwrap();
/// check_spectral_matrix(&t, &[0.5, 5.0, 50.0]).unwrap();
/// ```
pub fn check_spectral_matrix(m: &dyn SpectralMatrix, omegas: &[f64]) -> Result<()> {
    for &w in omegas {
        let s = m.matrix(w);
        let k = s.nrows();
        if s.ncols() != k || k != m.n_components() {
            return Err(Error::invalid(
                "spectral matrix",
                m.describe(),
                format!(
                    "is {}×{} at ω = {w:e} rad/s, expected {}×{}",
                    s.nrows(),
                    s.ncols(),
                    m.n_components(),
                    m.n_components()
                ),
            ));
        }
        let scale = (0..k).map(|c| s[(c, c)].re.abs()).fold(0.0, f64::max);
        for c in 0..k {
            for d in 0..k {
                let v = s[(c, d)];
                if !(v.re.is_finite() && v.im.is_finite()) {
                    return Err(Error::invalid(
                        &format!("S[{c},{d}]"),
                        format!("{v} at ω = {w:e} rad/s"),
                        format!("{}: entries must be finite", m.describe()),
                    ));
                }
                if (v - s[(d, c)].conj()).norm() > SPECTRAL_MATRIX_TOLERANCE * scale {
                    return Err(Error::invalid(
                        &format!("S[{c},{d}]"),
                        format!("{v} at ω = {w:e} rad/s"),
                        format!("{}: not Hermitian (S[{d},{c}] = {})", m.describe(), s[(d, c)]),
                    ));
                }
            }
        }
        let herm = (&s + s.adjoint()) * Complex::new(0.5, 0.0);
        let lmin = herm
            .symmetric_eigenvalues()
            .iter()
            .copied()
            .fold(f64::INFINITY, f64::min);
        if lmin < -SPECTRAL_MATRIX_TOLERANCE * scale {
            return Err(Error::invalid(
                "spectral matrix",
                format!("smallest eigenvalue {lmin:e} at ω = {w:e} rad/s"),
                format!(
                    "{}: not positive semi-definite (a coherence above 1 or a negative density)",
                    m.describe()
                ),
            ));
        }
    }
    Ok(())
}

/// The lower-triangular factor L of a positive semi-definite Hermitian matrix C = L Lᴴ, with the columns
/// of zero pivots set to zero (so C of rank < m, e.g. identical tracks with γ = 1, is factored too).
///
/// # Formula
/// Cholesky–Banachiewicz: L_kk = √(C_kk − Σ_{l<k} |L_kl|²), L_ck = (C_ck − Σ_{l<k} L_cl conj(L_kl))/L_kk;
/// a pivot C_kk − Σ|L_kl|² ≤ ε·max C_cc (ε = [`SPECTRAL_MATRIX_TOLERANCE`]) gives a zero column.
/// For the 2 × 2 coherence matrix [[1, ρ], [ρ̄, 1]]: L = [[1, 0], [ρ̄, √(1 − |ρ|²)]], i.e. per frequency
/// Z_R = ρ̄ Z_L + √(1 − |ρ|²) W with W independent of Z_L.
///
/// # Errors
/// None: a matrix that is not semi-definite gives a factor of a nearby one (check it first with
/// [`check_spectral_matrix`]).
///
/// # Examples
/// ```
/// use stochvib::coherence::semidefinite_cholesky;
/// use nalgebra::{Complex, DMatrix};
/// let c = DMatrix::from_row_slice(2, 2, &[1.0, 0.6, 0.6, 1.0]).map(|v| Complex::new(v, 0.0));
/// let l = semidefinite_cholesky(&c);
/// assert!((l[(1, 1)].re - 0.8).abs() < 1e-15);
/// ```
pub fn semidefinite_cholesky(c: &DMatrix<Complex<f64>>) -> DMatrix<Complex<f64>> {
    let m = c.nrows();
    let scale = (0..m).map(|k| c[(k, k)].re.abs()).fold(0.0, f64::max);
    let mut l = DMatrix::from_element(m, m, Complex::new(0.0, 0.0));
    for k in 0..m {
        let pivot = c[(k, k)].re - (0..k).map(|j| l[(k, j)].norm_sqr()).sum::<f64>();
        if pivot <= SPECTRAL_MATRIX_TOLERANCE * scale {
            continue;
        }
        let d = pivot.sqrt();
        l[(k, k)] = Complex::new(d, 0.0);
        for r in k + 1..m {
            let mut acc = c[(r, k)];
            for j in 0..k {
                acc -= l[(r, j)] * l[(k, j)].conj();
            }
            l[(r, k)] = acc / d;
        }
    }
    l
}
