//! S–N (Wöhler) curve in stress amplitude, N·S_a^k = C, with an optional endurance limit, and the
//! Palmgren–Miner damage sum.

use crate::error::{Error, Result};
use crate::numbers::num;

/// A Basquin S–N curve in stress **amplitude** with an optional endurance limit.
///
/// # Formula
/// ```text
/// N(S_a) = C · S_a^{−k}            for S_a ≥ S_e   (cycles to failure at constant amplitude S_a)
/// N(S_a) = ∞                       for S_a < S_e   (endurance limit S_e; no damage)
/// D = Σ_i n_i / N(S_a,i) = Σ_{S_a,i ≥ S_e} n_i S_a,i^k / C        (Palmgren–Miner; failure at D = 1)
/// ```
/// S_a is the cycle amplitude (half the range ΔS = 2S_a) in the unit of the signal (Pa, MPa, …), k > 0 the
/// inverse slope (no unit), C > 0 in (signal unit)^k, and n_i the count of the cycle: 1 for a full cycle,
/// 0.5 for a half cycle. The endurance limit is a plain cut-off: a cycle whose amplitude is *strictly*
/// below S_e does no damage, one at or above it follows the Basquin line (no second slope, no Haibach
/// extension). A curve published in ranges, N·ΔS^k = C_Δ, is the same curve with C = C_Δ·2^{−k}.
///
/// # Errors
/// [`SnCurve::build`] rejects k ≤ 0, C ≤ 0 and a negative endurance limit (and non-finite values), naming
/// the parameter, its value and the reason.
///
/// # Examples
/// ```
/// use stochvib::fatigue::SnCurve;
/// // N·S_a^3 = 1e12 (MPa, amplitude), no endurance limit.
/// let sn = SnCurve { k: 3.0, c: 1e12, endurance_limit: None }.build().unwrap();
/// assert!((sn.cycles_to_failure(100.0).unwrap() - 1e6).abs() < 1e-3);
/// // 1000 full cycles at 100 MPa and one half cycle at 200 MPa: 1e-3 + 0.5·8e6/1e12.
/// let d = sn.damage([(100.0, 1000.0), (200.0, 0.5)]).unwrap();
/// assert!((d - (1e-3 + 4e-6)).abs() < 1e-15);
/// assert!(SnCurve { k: -3.0, c: 1e12, endurance_limit: None }.build().is_err());
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SnCurve {
    /// k, the inverse slope (no unit), > 0.
    pub k: f64,
    /// C of N·S_a^k = C, amplitude convention, (signal unit)^k, > 0.
    pub c: f64,
    /// S_e, the endurance limit (an amplitude, signal unit), if any.
    pub endurance_limit: Option<f64>,
}

/// An S–N curve given by one point of it: N₁ cycles to failure at amplitude S₁ and the inverse slope k;
/// [`SnReferencePoint::build`] gives the [`SnCurve`] with C = N₁·S₁^k.
///
/// # Formula
/// C = N₁ S₁^k.
///
/// # Errors
/// [`SnReferencePoint::build`]: as [`SnCurve::build`], and [`Error::InvalidParameter`] naming `amplitude`
/// or `cycles` unless both are finite and > 0.
///
/// # Examples
/// ```
/// use stochvib::fatigue::SnReferencePoint;
/// // 2e6 cycles at 50 MPa amplitude, k = 3 (an EN 1993-1-9-like detail, written in amplitudes).
/// let sn = SnReferencePoint { k: 3.0, amplitude: 50.0, cycles: 2e6, endurance_limit: None }.build().unwrap();
/// assert!((sn.c() - 2e6 * 125_000.0).abs() < 1e-3);
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SnReferencePoint {
    /// k, the inverse slope (no unit), > 0.
    pub k: f64,
    /// S₁, the amplitude of the point (signal unit), > 0.
    pub amplitude: f64,
    /// N₁, the cycles to failure at S₁, > 0.
    pub cycles: f64,
    /// S_e, the endurance limit (an amplitude, signal unit), if any.
    pub endurance_limit: Option<f64>,
}

/// An S–N curve published in **ranges**, N·ΔS^k = C_Δ, with an endurance limit given as a range ΔS_e (or
/// `None`); [`SnRangeCurve::build`] gives the amplitude curve [`SnCurve`].
///
/// # Formula
/// ΔS = 2S_a ⇒ N·(2S_a)^k = C_Δ ⇒ C = C_Δ·2^{−k};  S_e = ΔS_e/2.
///
/// # Errors
/// [`SnRangeCurve::build`]: as [`SnCurve::build`] (the parameter named `C` is then C_Δ·2^{−k});
/// `endurance_limit_range` must be finite and ≥ 0.
///
/// # Examples
/// ```
/// use stochvib::fatigue::SnRangeCurve;
/// let sn = SnRangeCurve { k: 3.0, c_range: 8e12, endurance_limit_range: Some(100.0) }.build().unwrap();
/// assert_eq!(sn.c(), 1e12);
/// assert_eq!(sn.endurance_limit(), Some(50.0));
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SnRangeCurve {
    /// k, the inverse slope (no unit), > 0.
    pub k: f64,
    /// C_Δ of N·ΔS^k = C_Δ, (signal unit)^k, > 0.
    pub c_range: f64,
    /// ΔS_e, the endurance limit as a range (signal unit), if any.
    pub endurance_limit_range: Option<f64>,
}

impl SnCurve {
    /// The curve of these fields, checked: N·S_a^k = C with inverse slope `k`, intercept `c` (amplitude
    /// convention, in (signal unit)^k) and an optional endurance limit `endurance_limit` = S_e (amplitude,
    /// signal unit).
    ///
    /// # Formula
    /// See the type: N(S_a) = C·S_a^{−k} for S_a ≥ S_e.
    ///
    /// # Errors
    /// [`Error::InvalidParameter`] naming `k`, `C` or `endurance_limit` when k is not finite and > 0, C is
    /// not finite and > 0, or S_e is negative or not finite.
    ///
    /// # Examples
    /// ```
    /// use stochvib::fatigue::SnCurve;
    /// let sn = SnCurve { k: 5.0, c: 2e15, endurance_limit: Some(40.0) }.build().unwrap();
    /// assert_eq!(sn.endurance_limit(), Some(40.0));
    /// let e = SnCurve { k: 5.0, c: 0.0, endurance_limit: None }.build().unwrap_err().to_string();
    /// assert!(e.contains("`C`") && e.contains("> 0"));
    /// ```
    pub fn build(self) -> Result<Self> {
        let SnCurve { k, c, endurance_limit } = self;
        if !(k.is_finite() && k > 0.0) {
            return Err(Error::invalid("k", k, "the S-N inverse slope must be finite and > 0"));
        }
        if !(c.is_finite() && c > 0.0) {
            return Err(Error::invalid(
                "C",
                c,
                "the S-N intercept N*S_a^k = C must be finite and > 0",
            ));
        }
        if let Some(se) = endurance_limit
            && !(se.is_finite() && se >= 0.0)
        {
            return Err(Error::invalid(
                "endurance_limit",
                se,
                "the endurance limit (an amplitude) must be finite and >= 0",
            ));
        }
        Ok(SnCurve { k, c, endurance_limit })
    }

    /// The inverse slope k.
    pub fn k(&self) -> f64 {
        self.k
    }

    /// The intercept C of N·S_a^k = C (amplitude convention).
    pub fn c(&self) -> f64 {
        self.c
    }

    /// The endurance limit S_e (an amplitude), if any.
    pub fn endurance_limit(&self) -> Option<f64> {
        self.endurance_limit
    }

    /// Whether a cycle of amplitude `amplitude` does damage: S_a ≥ S_e (always true without a limit).
    #[inline]
    pub fn damages(&self, amplitude: f64) -> bool {
        match self.endurance_limit {
            Some(se) => amplitude >= se,
            None => true,
        }
    }

    /// Cycles to failure N at constant amplitude S_a = `amplitude`.
    ///
    /// # Formula
    /// N = C·S_a^{−k} for S_a ≥ S_e; ∞ below the endurance limit (and at S_a = 0).
    ///
    /// # Errors
    /// [`Error::InvalidParameter`] naming `amplitude` unless it is finite and ≥ 0.
    ///
    /// # Examples
    /// ```
    /// use stochvib::fatigue::SnCurve;
    /// let sn = SnCurve { k: 4.0, c: 1e10, endurance_limit: Some(20.0) }.build().unwrap();
    /// assert_eq!(sn.cycles_to_failure(10.0).unwrap(), f64::INFINITY);
    /// assert!((sn.cycles_to_failure(100.0).unwrap() - 1e2).abs() < 1e-9);
    /// ```
    pub fn cycles_to_failure(&self, amplitude: f64) -> Result<f64> {
        if !(amplitude.is_finite() && amplitude >= 0.0) {
            return Err(Error::invalid(
                "amplitude",
                amplitude,
                "a cycle amplitude must be finite and >= 0",
            ));
        }
        if !self.damages(amplitude) || amplitude == 0.0 {
            return Ok(f64::INFINITY);
        }
        Ok(self.c * amplitude.powf(-self.k))
    }

    /// Palmgren–Miner damage of a set of cycles given as (amplitude S_a, count n) pairs; a half cycle has
    /// n = 0.5.
    ///
    /// # Formula
    /// D = Σ_{S_a,i ≥ S_e} n_i·S_a,i^k / C.
    ///
    /// # Errors
    /// [`Error::InvalidParameter`] naming `amplitude` (with the pair's position) unless every amplitude is
    /// finite and ≥ 0, or `count` unless every count is finite and ≥ 0.
    ///
    /// # Examples
    /// ```
    /// use stochvib::fatigue::SnCurve;
    /// let sn = SnCurve { k: 3.0, c: 1e9, endurance_limit: Some(5.0) }.build().unwrap();
    /// // The 4.0 cycle is below the endurance limit: only 10³·1 / 1e9 remains.
    /// assert_eq!(sn.damage([(10.0, 1.0), (4.0, 1e6)]).unwrap(), 1e-6);
    /// ```
    pub fn damage(&self, cycles: impl IntoIterator<Item = (f64, f64)>) -> Result<f64> {
        let mut sum = 0.0;
        for (i, (a, n)) in cycles.into_iter().enumerate() {
            if !(a.is_finite() && a >= 0.0) {
                return Err(Error::invalid(
                    "amplitude",
                    a,
                    format!("cycle {i}: a cycle amplitude must be finite and >= 0"),
                ));
            }
            if !(n.is_finite() && n >= 0.0) {
                return Err(Error::invalid(
                    "count",
                    n,
                    format!("cycle {i}: a cycle count must be finite and >= 0"),
                ));
            }
            if self.damages(a) {
                sum += n * a.powf(self.k);
            }
        }
        Ok(sum / self.c)
    }

    /// Palmgren–Miner damage of rainflow cycles ([`crate::fatigue::Cycle`]), using each cycle's
    /// amplitude and count.
    ///
    /// # Formula
    /// D = Σ_{S_a,i ≥ S_e} n_i·S_a,i^k / C, S_a,i = range_i/2, n_i ∈ {1, 0.5}.
    ///
    /// # Errors
    /// As [`SnCurve::damage`] (cycles counted from finite samples always pass, unless a range overflows).
    ///
    /// # Examples
    /// ```
    /// use stochvib::fatigue::{rainflow, SnCurve};
    /// let cycles = rainflow(&[0.0, 2.0, 0.0]).unwrap(); // two half cycles of range 2 (amplitude 1)
    /// let sn = SnCurve { k: 3.0, c: 10.0, endurance_limit: None }.build().unwrap();
    /// assert_eq!(sn.damage_of_cycles(&cycles).unwrap(), 0.1);
    /// ```
    pub fn damage_of_cycles(&self, cycles: &[crate::fatigue::Cycle]) -> Result<f64> {
        self.damage(cycles.iter().map(|c| (c.amplitude, c.count)))
    }

    /// One-line description with the parameters.
    pub fn describe(&self) -> String {
        match self.endurance_limit {
            Some(se) => format!(
                "S-N N*S_a^k = C (amplitude), k = {}, C = {}, endurance limit S_e = {} (amplitude)",
                num(self.k),
                num(self.c),
                num(se)
            ),
            None => format!(
                "S-N N*S_a^k = C (amplitude), k = {}, C = {}, no endurance limit",
                num(self.k),
                num(self.c)
            ),
        }
    }
}

impl SnReferencePoint {
    /// The [`SnCurve`] through this point (see the type).
    ///
    /// # Errors
    /// See the type's `# Errors`.
    pub fn build(self) -> Result<SnCurve> {
        let SnReferencePoint {
            k,
            amplitude,
            cycles,
            endurance_limit,
        } = self;
        if !(amplitude.is_finite() && amplitude > 0.0) {
            return Err(Error::invalid("amplitude", amplitude, "must be finite and > 0"));
        }
        if !(cycles.is_finite() && cycles > 0.0) {
            return Err(Error::invalid("cycles", cycles, "must be finite and > 0"));
        }
        if !(k.is_finite() && k > 0.0) {
            return Err(Error::invalid("k", k, "the S-N inverse slope must be finite and > 0"));
        }
        SnCurve {
            k,
            c: cycles * amplitude.powf(k),
            endurance_limit,
        }
        .build()
    }
}

impl SnRangeCurve {
    /// The amplitude [`SnCurve`] of this range curve (see the type).
    ///
    /// # Errors
    /// See the type's `# Errors`.
    pub fn build(self) -> Result<SnCurve> {
        let SnRangeCurve {
            k,
            c_range,
            endurance_limit_range,
        } = self;
        if !(k.is_finite() && k > 0.0) {
            return Err(Error::invalid("k", k, "the S-N inverse slope must be finite and > 0"));
        }
        if !(c_range.is_finite() && c_range > 0.0) {
            return Err(Error::invalid(
                "C_range",
                c_range,
                "the S-N intercept N*dS^k = C must be finite and > 0",
            ));
        }
        if let Some(se) = endurance_limit_range
            && !(se.is_finite() && se >= 0.0)
        {
            return Err(Error::invalid(
                "endurance_limit_range",
                se,
                "the endurance limit (a range) must be finite and >= 0",
            ));
        }
        SnCurve {
            k,
            c: c_range * 2f64.powf(-k),
            endurance_limit: endurance_limit_range.map(|s| 0.5 * s),
        }
        .build()
    }
}
