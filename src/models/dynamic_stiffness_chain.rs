//! Harmonic response of an n-mass damped chain by the dynamic-stiffness (sweep) method
//! (Yurchenko (2011); full citation in [`crate::models`]).
//!
//! The article gives the method in matrix form, (1)–(10), and no numerical example. The printed recursion
//! is not implementable literally (see [`TorsionalChain`] `# Formula`); this module implements the corrected
//! scalar form, which is the Thomas algorithm for the tridiagonal dynamic-stiffness system, in O(n) time and
//! memory, and a dense complex LU solve as the slow independent oracle.

use crate::error::{require_non_negative, require_positive, Error, Result};
use crate::fields::Fields;
use crate::models::results::{DeterministicModel, ResultTable};
use crate::models::worked_example::BookRow;
use crate::numbers::num;
use crate::units::Dim;
use nalgebra::{Complex, DMatrix, DVector};

/// Largest n accepted by the dense oracle (an n × n complex matrix takes 16 n² bytes: 144 MB at 3000).
pub const DENSE_MAX_N: usize = 3000;

/// Relative size below which a pivot K_k + s_k (or the closure K_n) of the sweep counts as zero.
const PIVOT_EPS: f64 = 1e-14;

/// A damped chain of n masses, torsional (kg m², N m/rad, N m s/rad, torques N m, angles rad) or, with the
/// same equations, translational (kg, N/m, N s/m, forces N, displacements m).
///
/// Mass k (k = 1..n) has inertia I_k, a spring k_{g,k} and a damper β_k to ground (both may be 0); shaft k
/// (k = 1..n−1) joins masses k and k+1 with stiffness C_k and damping β_{k,k+1}.
///
/// # Formula
/// Equation of mass k under the harmonic torque M̄_k e^{ipt} (source: the unnumbered equation of mass k in the
/// gearbox example of Fig. 1, before (9); p = forcing frequency, rad/s), φ_k = Φ_k e^{ipt}:
/// ```text
/// d_k Φ_k + s_{k−1}(Φ_k − Φ_{k−1}) + s_k(Φ_k − Φ_{k+1}) = M̄_k,      s₀ = s_n = 0,
/// d_k = k_{g,k} − I_k p² + iβ_k p   (mass/ground dynamic stiffness),
/// s_k = C_k + iβ_{k,k+1} p          (shaft dynamic stiffness).
/// ```
/// Forward sweep from the free end k = 1: the sub-chain 1..k, cut in shaft k, obeys T_k = K_kΦ_k − F_k
/// (source (2)/(6): K_k ≙ H_k^{(1)}, the "stiffness at point k of the part 1..k", F_k ≙ P_k^{(1)}, the
/// "equivalent exciter"):
/// ```text
/// K₁ = d₁,  F₁ = M̄₁;   for k = 2..n, r = s_{k−1}/(K_{k−1} + s_{k−1}):
/// K_k = d_k + r K_{k−1}        (series combination of K_{k−1} and s_{k−1}, plus d_k)     ≙ (7)
/// F_k = M̄_k + r F_{k−1}                                                                ≙ (8)
/// ```
/// Closure Φ_n = F_n/K_n; back substitution Φ_k = (F_k + s_kΦ_{k+1})/(K_k + s_k), k = n−1..1 (≙ (4));
/// shaft torques M_{k,k+1} = s_k(Φ_k − Φ_{k+1}) (≙ (10) with its sign).
///
/// **Misprints in the source** ((4)–(9) and the unnumbered equations between them): (4) writes
/// q_{k−1} = (P − Bq_k − Cq_k)/H; from (2) and (3) it must be q_{k−1} = (H^{(1)}_{k−1} + C_{k−1,k})⁻¹(P^{(1)}_{k−1}
/// − B_{k−1,k}q_k). (7) adds C_{k,k+1} while (5) has C_{k,k−1}; with the sign convention of (3) the last term of
/// (5) enters (6) with a minus, so the minus in (8) needs B → −B; (9) defines H̄_k = I_kP² + iβ_kP although the
/// substituted equation has −I_kP²; that substituted equation (unnumbered, just before (9)) writes C_{k,k+1}
/// where C_{k−1,k} is meant. In scalar form, with B ≙ −s and H_k + C_{k,k+1} ≙ d_k + s_k, the printed (7)/(8)
/// become the recursion above.
///
/// Cost: O(n) complex operations and two length-n complex vectors (no n × n matrix). A pivot
/// K_{k−1} + s_{k−1} can vanish only at an undamped natural frequency of a sub-chain; it is then reported
/// as an error (use [`TorsionalChain::harmonic_response_dense`] for such small cases).
///
/// # Errors
/// [`TorsionalChain::new`]: n = 0, a non-positive or non-finite inertia, a negative or non-finite stiffness
/// or damping, or array lengths that do not match (n inertias and ground terms, n − 1 shafts).
///
/// # Examples
/// ```
/// use stochvib::models::dynamic_stiffness_chain::TorsionalChain;
/// use nalgebra::Complex;
/// // two masses, no damping: Φ₂/M̄₁ = s/(d₁d₂ + s(d₁ + d₂))
/// let ch = TorsionalChain::new(vec![1.0, 2.0], vec![0.0; 2], vec![0.0; 2], vec![100.0], vec![0.0]).unwrap();
/// let p = 3.0;
/// let r = ch.harmonic_response(p, &[Complex::new(1.0, 0.0), Complex::new(0.0, 0.0)]).unwrap();
/// let (d1, d2, s) = (-1.0 * p * p, -2.0 * p * p, 100.0);
/// assert!((r.angles[1].re - s / (d1 * d2 + s * (d1 + d2))).abs() < 1e-15);
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct TorsionalChain {
    inertia: Vec<f64>,
    ground_stiffness: Vec<f64>,
    ground_damping: Vec<f64>,
    shaft_stiffness: Vec<f64>,
    shaft_damping: Vec<f64>,
}

/// Harmonic response of a chain: complex amplitudes (φ = Re(Φ e^{ipt})).
#[derive(Debug, Clone, PartialEq)]
pub struct ChainResponse {
    /// Φ_k, rad (or m), k = 1..n.
    pub angles: Vec<Complex<f64>>,
    /// M_{k,k+1} = s_k(Φ_k − Φ_{k+1}), N m (or N), k = 1..n−1.
    pub shaft_torques: Vec<Complex<f64>>,
}

/// A harmonic load case: forcing frequency and torque amplitudes (all in phase).
#[derive(Debug, Clone, PartialEq)]
pub struct HarmonicLoad {
    /// p, rad/s.
    pub frequency: f64,
    /// M̄_k, N m, one per mass.
    pub torques: Vec<f64>,
}

/// A chain with an optional load case, as read from `data/dynamic-stiffness-chain.toml`.
#[derive(Debug, Clone, PartialEq)]
pub struct DynamicStiffnessChain {
    /// The chain.
    pub chain: TorsionalChain,
    /// The load case, when the file gives one.
    pub load: Option<HarmonicLoad>,
}

fn check_len(name: &str, len: usize, want: usize) -> Result<()> {
    if len != want {
        return Err(Error::invalid(
            name,
            format!("{len} values"),
            format!("need {want} values"),
        ));
    }
    Ok(())
}

impl TorsionalChain {
    /// Builds a chain: `inertia`, `ground_stiffness`, `ground_damping` (n each), `shaft_stiffness`,
    /// `shaft_damping` (n − 1 each).
    ///
    /// # Errors
    /// See the type's `# Errors`.
    pub fn new(
        inertia: Vec<f64>,
        ground_stiffness: Vec<f64>,
        ground_damping: Vec<f64>,
        shaft_stiffness: Vec<f64>,
        shaft_damping: Vec<f64>,
    ) -> Result<Self> {
        let n = inertia.len();
        if n == 0 {
            return Err(Error::invalid("inertia", "[]", "need at least one mass"));
        }
        check_len("ground_stiffness", ground_stiffness.len(), n)?;
        check_len("ground_damping", ground_damping.len(), n)?;
        check_len("shaft_stiffness", shaft_stiffness.len(), n - 1)?;
        check_len("shaft_damping", shaft_damping.len(), n - 1)?;
        for (k, &v) in inertia.iter().enumerate() {
            require_positive(&format!("inertia[{k}]"), v)?;
        }
        for (name, arr) in [
            ("ground_stiffness", &ground_stiffness),
            ("ground_damping", &ground_damping),
            ("shaft_stiffness", &shaft_stiffness),
            ("shaft_damping", &shaft_damping),
        ] {
            for (k, &v) in arr.iter().enumerate() {
                require_non_negative(&format!("{name}[{k}]"), v)?;
            }
        }
        Ok(TorsionalChain {
            inertia,
            ground_stiffness,
            ground_damping,
            shaft_stiffness,
            shaft_damping,
        })
    }

    /// Number of masses n.
    pub fn len(&self) -> usize {
        self.inertia.len()
    }

    /// Always false (a chain has at least one mass).
    pub fn is_empty(&self) -> bool {
        self.inertia.is_empty()
    }

    /// Inertias I_k, kg m².
    pub fn inertia(&self) -> &[f64] {
        &self.inertia
    }

    /// Shaft stiffnesses C_k, N m/rad.
    pub fn shaft_stiffness(&self) -> &[f64] {
        &self.shaft_stiffness
    }

    /// The illustrative chain of `data/dynamic-stiffness-chain.toml` (the source prints no example): a
    /// five-mass drive (motor, coupling, gear stages, drum) with 2 % shaft damping at 40 rad/s, the first mass
    /// grounded through a soft mount. Not from the source.
    pub fn illustrative() -> Self {
        TorsionalChain {
            inertia: vec![12.0, 0.8, 3.5, 1.2, 60.0],
            ground_stiffness: vec![2.0e3, 0.0, 0.0, 0.0, 0.0],
            ground_damping: vec![5.0, 0.0, 0.0, 0.0, 20.0],
            shaft_stiffness: vec![4.0e5, 2.5e5, 1.5e5, 8.0e4],
            shaft_damping: vec![200.0, 125.0, 75.0, 40.0],
        }
    }

    #[inline]
    fn d(&self, k: usize, p: f64) -> Complex<f64> {
        Complex::new(
            self.ground_stiffness[k] - self.inertia[k] * p * p,
            self.ground_damping[k] * p,
        )
    }

    #[inline]
    fn s(&self, k: usize, p: f64) -> Complex<f64> {
        Complex::new(self.shaft_stiffness[k], self.shaft_damping[k] * p)
    }

    fn check_load(&self, p: f64, torques: &[Complex<f64>]) -> Result<()> {
        if !p.is_finite() {
            return Err(Error::invalid("p", p, "forcing frequency must be finite"));
        }
        check_len("torques", torques.len(), self.len())?;
        if torques.iter().any(|t| !(t.re.is_finite() && t.im.is_finite())) {
            return Err(Error::invalid("torques", "array", "amplitudes must be finite"));
        }
        Ok(())
    }

    /// Harmonic response at forcing frequency `p` (rad/s) to torque amplitudes `torques` (N m, one per
    /// mass) by the O(n) sweep (see the type's `# Formula`).
    ///
    /// # Errors
    /// Non-finite `p` or torques, wrong number of torques; [`Error::Numerical`] when a pivot vanishes (an
    /// undamped sub-chain or the whole chain is at resonance at `p`, e.g. a free chain at p = 0).
    pub fn harmonic_response(&self, p: f64, torques: &[Complex<f64>]) -> Result<ChainResponse> {
        self.check_load(p, torques)?;
        let n = self.len();
        // phi holds F_k during the sweep and Φ_k after back substitution; piv holds K_k + s_k
        let mut phi: Vec<Complex<f64>> = Vec::with_capacity(n);
        let mut piv: Vec<Complex<f64>> = Vec::with_capacity(n.saturating_sub(1));
        let mut kk = self.d(0, p);
        let mut ff = torques[0];
        for (k, &tk) in torques.iter().enumerate().skip(1) {
            let s = self.s(k - 1, p);
            let den = kk + s;
            if den.l1_norm() <= PIVOT_EPS * (kk.l1_norm() + s.l1_norm()) || den.l1_norm() == 0.0 {
                return Err(Error::Numerical {
                    what: "dynamic-stiffness sweep".into(),
                    reason: format!(
                        "pivot K+s vanishes at shaft {k} for p = {p} rad/s (undamped sub-chain 1..{k} at \
                         resonance); use harmonic_response_dense for small chains or add damping"
                    ),
                });
            }
            phi.push(ff);
            piv.push(den);
            let r = s / den;
            kk = self.d(k, p) + r * kk;
            ff = tk + r * ff;
        }
        let scale = self.d(n - 1, p).norm() + if n > 1 { self.s(n - 2, p).norm() } else { 0.0 };
        if kk.norm() <= PIVOT_EPS * scale || kk.norm() == 0.0 {
            return Err(Error::Numerical {
                what: "dynamic-stiffness sweep".into(),
                reason: format!(
                    "the chain's dynamic stiffness is singular at p = {p} rad/s (a natural frequency, or a free \
                     chain at p = 0)"
                ),
            });
        }
        let mut next = ff / kk;
        phi.push(next);
        for k in (0..n - 1).rev() {
            next = (phi[k] + self.s(k, p) * next) / piv[k];
            phi[k] = next;
        }
        drop(piv);
        let shaft_torques = (0..n - 1).map(|k| self.s(k, p) * (phi[k] - phi[k + 1])).collect();
        Ok(ChainResponse {
            angles: phi,
            shaft_torques,
        })
    }

    /// The slow public oracle: the same response by assembling the dense n × n complex dynamic-stiffness
    /// matrix Z = K − p²M + ipB and solving Z Φ = M̄ with nalgebra's LU (partial pivoting). O(n³).
    ///
    /// # Errors
    /// As [`TorsionalChain::harmonic_response`]; n > [`DENSE_MAX_N`]; a singular matrix.
    pub fn harmonic_response_dense(&self, p: f64, torques: &[Complex<f64>]) -> Result<ChainResponse> {
        self.check_load(p, torques)?;
        let n = self.len();
        if n > DENSE_MAX_N {
            return Err(Error::invalid(
                "n",
                n,
                format!("the dense oracle is limited to n <= {DENSE_MAX_N}"),
            ));
        }
        let mut z = DMatrix::<Complex<f64>>::zeros(n, n);
        for k in 0..n {
            z[(k, k)] += self.d(k, p);
        }
        for k in 0..n - 1 {
            let s = self.s(k, p);
            z[(k, k)] += s;
            z[(k + 1, k + 1)] += s;
            z[(k, k + 1)] -= s;
            z[(k + 1, k)] -= s;
        }
        let rhs = DVector::from_column_slice(torques);
        let phi = z.lu().solve(&rhs).ok_or_else(|| Error::Numerical {
            what: "dense dynamic-stiffness solve".into(),
            reason: format!("singular matrix at p = {p} rad/s"),
        })?;
        let angles: Vec<Complex<f64>> = phi.iter().copied().collect();
        let shaft_torques = (0..n - 1).map(|k| self.s(k, p) * (angles[k] - angles[k + 1])).collect();
        Ok(ChainResponse { angles, shaft_torques })
    }
}

impl DynamicStiffnessChain {
    /// Reads the `[model]` table: arrays `inertia` (kg m²), `shaft_stiffness` (N m/rad), optional
    /// `shaft_damping` (N m s/rad), `ground_stiffness` (N m/rad), `ground_damping` (N m s/rad) as plain SI
    /// numbers (missing damping/ground arrays are zeros); optional load case `frequency` (with its unit,
    /// e.g. `"40 rad/s"`) and `torques` (array, N m).
    ///
    /// # Errors
    /// Missing keys, wrong types or lengths, invalid values (named by file and key).
    pub fn from_fields(f: &Fields) -> Result<Self> {
        let inertia = f.numbers("inertia")?;
        let n = inertia.len();
        let shaft_stiffness = f.numbers("shaft_stiffness")?;
        let opt = |k: &str, len: usize| -> Result<Vec<f64>> {
            match f.get(k) {
                None => Ok(vec![0.0; len]),
                Some(_) => f.numbers(k),
            }
        };
        let shaft_damping = opt("shaft_damping", n.saturating_sub(1))?;
        let ground_stiffness = opt("ground_stiffness", n)?;
        let ground_damping = opt("ground_damping", n)?;
        let chain = TorsionalChain::new(
            inertia,
            ground_stiffness,
            ground_damping,
            shaft_stiffness,
            shaft_damping,
        )
        .map_err(|e| f.wrap("inertia", e))?;
        let load = match f.get("frequency") {
            None => None,
            Some(v) => {
                let frequency = f.angular_frequency(v, "frequency", Dim::FREQUENCY)?;
                let torques = f.numbers("torques")?;
                if torques.len() != n {
                    return Err(f.error(
                        "torques",
                        format!("{} values", torques.len()),
                        format!("need {n} values"),
                    ));
                }
                Some(HarmonicLoad { frequency, torques })
            }
        };
        Ok(DynamicStiffnessChain { chain, load })
    }

    /// The illustrative case of `data/dynamic-stiffness-chain.toml`: [`TorsionalChain::illustrative`] driven
    /// by 1000 N m on the motor at 40 rad/s.
    pub fn illustrative() -> Self {
        DynamicStiffnessChain {
            chain: TorsionalChain::illustrative(),
            load: Some(HarmonicLoad {
                frequency: 40.0,
                torques: vec![1000.0, 0.0, 0.0, 0.0, 0.0],
            }),
        }
    }
}

impl DeterministicModel for DynamicStiffnessChain {
    fn description(&self) -> String {
        format!(
            "torsional chain of {} masses by dynamic stiffness (Yurchenko, Calculation of linear vibrations of \
             mechanical systems by the dynamic-stiffness method, 2011)",
            self.chain.len()
        )
    }

    /// The harmonic response of the load case by the O(n) recursion (6)–(8), checked against the dense
    /// complex solve: amplitude and phase of every angle and shaft torque.
    fn results(&self) -> Result<Vec<ResultTable>> {
        let Some(load) = &self.load else {
            return Ok(vec![ResultTable::new("Harmonic response", &[("note", "-")]).with_note(
                "the file gives no load case (`frequency`, `torques`): nothing to compute",
            )]);
        };
        let torques: Vec<Complex<f64>> = load.torques.iter().map(|&m| Complex::new(m, 0.0)).collect();
        let fast = self.chain.harmonic_response(load.frequency, &torques)?;
        let dense = self.chain.harmonic_response_dense(load.frequency, &torques)?;
        let note = format!(
            "forcing frequency p = {} rad/s; phase relative to the torques; the dense solve agrees to {:.1e} relative",
            num(load.frequency),
            max_rel_diff(&fast, &dense)
        );
        let mut angles = ResultTable::new(
            "Angle amplitudes (6)-(8)",
            &[("mass", "-"), ("|phi|", "rad"), ("phase", "rad")],
        )
        .with_note(note.clone());
        for (k, a) in fast.angles.iter().enumerate() {
            angles.push(vec![(k + 1).to_string().into(), a.norm().into(), a.arg().into()]);
        }
        let mut shafts = ResultTable::new(
            "Shaft torque amplitudes M(k,k+1) = s_k (phi_k - phi_(k+1))",
            &[("shaft", "-"), ("|M|", "N m"), ("phase", "rad")],
        )
        .with_note(note);
        for (k, m) in fast.shaft_torques.iter().enumerate() {
            shafts.push(vec![
                format!("{}-{}", k + 1, k + 2).into(),
                m.norm().into(),
                m.arg().into(),
            ]);
        }
        Ok(vec![angles, shafts])
    }
}

/// Largest relative difference between two responses, |a − b| / max|b| over angles and torques.
fn max_rel_diff(a: &ChainResponse, b: &ChainResponse) -> f64 {
    let pairs = a
        .angles
        .iter()
        .zip(&b.angles)
        .chain(a.shaft_torques.iter().zip(&b.shaft_torques));
    let scale = b
        .angles
        .iter()
        .chain(&b.shaft_torques)
        .map(|z| z.norm())
        .fold(0.0, f64::max);
    pairs.map(|(x, y)| (x - y).norm()).fold(0.0, f64::max) / scale.max(f64::MIN_POSITIVE)
}

/// Rows of the `book` report for Yurchenko (2011). The article prints no numerical example:
/// every row has `printed = None`; values are for the illustrative chain and load of
/// [`DynamicStiffnessChain::illustrative`].
pub fn book_rows() -> Vec<BookRow> {
    let case = DynamicStiffnessChain::illustrative();
    let load = case.load.as_ref().expect("illustrative case has a load");
    let torques: Vec<Complex<f64>> = load.torques.iter().map(|&t| Complex::new(t, 0.0)).collect();
    let fast = case.chain.harmonic_response(load.frequency, &torques).ok();
    let dense = case.chain.harmonic_response_dense(load.frequency, &torques).ok();
    let ex = "Yurchenko (2011), dynamic-stiffness chain (illustrative 5-mass drive, 1000 N m on mass 1 at 40 rad/s)";
    let note = "article prints no numerical example; value for the illustrative case";
    let mut rows = Vec::new();
    let mut push = |q: String, u: &str, c: Option<f64>, e: &str| {
        rows.push(BookRow {
            example: ex.to_string(),
            quantity: q,
            unit: u.to_string(),
            printed: None,
            computed: c,
            explanation: e.to_string(),
        })
    };
    let n = case.chain.len();
    push(
        "|Phi_1| (sweep)".into(),
        "rad",
        fast.as_ref().map(|r| r.angles[0].norm()),
        note,
    );
    push(
        format!("|Phi_{n}| (sweep)"),
        "rad",
        fast.as_ref().map(|r| r.angles[n - 1].norm()),
        note,
    );
    push(
        format!("|M_{},{}| (sweep)", n - 1, n),
        "N m",
        fast.as_ref().map(|r| r.shaft_torques[n - 2].norm()),
        note,
    );
    let diff = match (&fast, &dense) {
        (Some(a), Some(b)) => Some(
            a.angles
                .iter()
                .zip(&b.angles)
                .map(|(x, y)| (x - y).norm())
                .fold(0.0, f64::max)
                / b.angles.iter().map(|y| y.norm()).fold(0.0, f64::max),
        ),
        _ => None,
    };
    push(
        "max |Phi_sweep - Phi_dense| / max |Phi|".into(),
        "-",
        diff,
        "corrected recursion (6)-(8) vs dense LU solve; no printed value",
    );
    rows
}
