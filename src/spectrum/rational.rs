//! General rational spectra S(ω) = N(ω²)/D(ω²) and their spectral factorisation into a stable,
//! minimum-phase shaping filter.

use super::{Asymptote, Domain, Spectrum};
use crate::error::{Error, Result};
use crate::linalg::poly;
use std::f64::consts::PI;

/// A rational two-sided density S(ω) = Σ nₖ ω^{2k} / Σ dₖ ω^{2k} (coefficients in ascending powers of ω²).
///
/// Types 1 and 3, the textbook roads (8.66) and (8.69) and any output of a rational-spectrum input through a
/// rational system are of this form.
///
/// # Formula
/// ```text
/// S(ω) = N(ω²) / D(ω²),     N(x) = Σ nₖ xᵏ,  D(x) = Σ dₖ xᵏ
/// ```
/// Spectral factorisation: S(ω) = |B(iω)/A(iω)|² / (2π) with A Hurwitz (all roots in Re s < 0) and B with
/// all roots in Re s ≤ 0 (minimum phase), so that x = (B/A)·w with unit-intensity white noise w
/// (E[w(t)w(t+τ)] = δ(τ), two-sided density 1/(2π)) has exactly this spectrum ([`ShapingFilter`]).
///
/// # Errors
/// [`RationalSpectrum::new`] rejects empty or non-finite coefficients, a zero leading coefficient, a
/// denominator with a root on the real ω axis (a pole at real frequency), and numerators that make S
/// negative somewhere.
///
/// # Examples
/// ```
/// use stochvib::spectrum::{RationalSpectrum, Domain, Spectrum};
/// // S(ω) = 1/(π(1 + ω²)) is type 1 with D = 1, α = 1.
/// let s = RationalSpectrum::new(vec![1.0 / std::f64::consts::PI], vec![1.0, 1.0], Domain::Temporal).unwrap();
/// assert!((s.variance().unwrap() - 1.0).abs() < 1e-12);
/// let f = s.shaping_filter().unwrap();
/// assert!((f.den[0] - 1.0).abs() < 1e-12 && (f.den[1] - 1.0).abs() < 1e-12);
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct RationalSpectrum {
    num: Vec<f64>,
    den: Vec<f64>,
    domain: Domain,
    filter: ShapingFilter,
    corners: Vec<f64>,
}

/// A stable minimum-phase filter B(s)/A(s) (real coefficients, ascending powers of s) that turns
/// unit-intensity white noise (E[w(t)w(t+τ)] = δ(τ)) into a process with a given rational spectrum:
/// S(ω) = |B(iω)/A(iω)|² / (2π).
#[derive(Debug, Clone, PartialEq)]
pub struct ShapingFilter {
    /// B(s), ascending powers of s.
    pub num: Vec<f64>,
    /// A(s), ascending powers of s, Hurwitz, positive leading coefficient.
    pub den: Vec<f64>,
    /// Largest relative residual of |B/A|²/(2π) against S seen on a check grid.
    pub residual: f64,
}

impl RationalSpectrum {
    /// Builds S(ω) = N(ω²)/D(ω²) from coefficients in ascending powers of ω².
    ///
    /// # Errors
    /// See the type's `# Errors`.
    pub fn new(num: Vec<f64>, den: Vec<f64>, domain: Domain) -> Result<Self> {
        let num = poly::trim(&num);
        let den = poly::trim(&den);
        for (name, c) in [("numerator", &num), ("denominator", &den)] {
            // coefficients of ω²: the spectral factor has twice the degree
            if 2 * c.len().saturating_sub(1) > poly::MAX_DEGREE {
                return Err(Error::invalid(
                    name,
                    format!("{} coefficients", c.len()),
                    format!(
                        "degree {} in ω is above the {} whose roots are computed: use a spectrum of lower order",
                        2 * (c.len() - 1),
                        poly::MAX_DEGREE
                    ),
                ));
            }
            if c.is_empty() || c.iter().all(|v| *v == 0.0) {
                return Err(Error::invalid(
                    name,
                    format!("{c:?}"),
                    "must have a non-zero coefficient",
                ));
            }
            if c.iter().any(|v| !v.is_finite()) {
                return Err(Error::invalid(name, format!("{c:?}"), "coefficients must be finite"));
            }
        }
        let (given_num, given_den) = (format!("{num:?}"), format!("{den:?}"));
        let flipped = *den.last().unwrap() < 0.0;
        let (num, den) = if flipped {
            (num.iter().map(|v| -v).collect(), den.iter().map(|v| -v).collect())
        } else {
            (num, den)
        };
        let sign = if flipped {
            " (N and D taken with the sign of D's leading coefficient)"
        } else {
            ""
        };
        // Factorise both, the denominator first (a real pole is a fault of D whatever N is); this also checks
        // D > 0 and N ≥ 0 on the real ω axis.
        let (a, _) = poly::spectral_factor(&den).map_err(|e| {
            Error::invalid(
                "denominator",
                &given_den,
                format!("D(ω²) must be > 0 for all real ω: S has a pole on the real axis{sign} ({e})"),
            )
        })?;
        let scaled: Vec<f64> = num.iter().map(|v| v * 2.0 * PI).collect();
        let (b, _) = poly::spectral_factor(&scaled).map_err(|e| {
            Error::invalid(
                "numerator",
                &given_num,
                format!("N(ω²) must be ≥ 0 for all real ω{sign} ({e})"),
            )
        })?;
        let poles = poly::roots(&a)?;
        if poles.iter().any(|p| p.re >= 0.0) {
            return Err(Error::invalid(
                "denominator",
                &given_den,
                "D(ω²) vanishes at a real frequency: S has a pole on the real axis",
            ));
        }
        let mut corners: Vec<f64> = poles.iter().map(|p| p.norm()).filter(|w| *w > 0.0).collect();
        corners.sort_by(f64::total_cmp);
        corners.dedup_by(|x, y| (*x - *y).abs() <= 1e-9 * y.abs());
        let mut s = RationalSpectrum {
            num,
            den,
            domain,
            filter: ShapingFilter {
                num: b,
                den: a,
                residual: 0.0,
            },
            corners,
        };
        s.filter.residual = s.filter_residual();
        Ok(s)
    }

    /// [`RationalSpectrum::new`] with the spectral factor B(s)/A(s) given in closed form (Butterworth poles,
    /// say): for densities of high order whose poles the factorisation of D(ω²) from its coefficients cannot
    /// resolve (coefficients spanning 40 decades); `corners` are the pole magnitudes |p| (rad per lag unit).
    ///
    /// # Errors
    /// [`Error::InvalidParameter`] for empty or non-finite coefficients, or a factor whose |B/A|²/(2π) differs
    /// from N/D by more than 1e-9 (relative) on the check grid.
    pub fn with_factor(
        num: Vec<f64>,
        den: Vec<f64>,
        domain: Domain,
        filter: (Vec<f64>, Vec<f64>),
        corners: Vec<f64>,
    ) -> Result<Self> {
        for (name, c) in [("numerator", &num), ("denominator", &den), ("factor", &filter.1)] {
            if c.iter().all(|v| *v == 0.0) || c.iter().any(|v| !v.is_finite()) {
                return Err(Error::invalid(
                    name,
                    format!("{c:?}"),
                    "coefficients must be finite, not all zero",
                ));
            }
        }
        let mut s = RationalSpectrum {
            num: poly::trim(&num),
            den: poly::trim(&den),
            domain,
            filter: ShapingFilter {
                num: filter.0,
                den: filter.1,
                residual: 0.0,
            },
            corners,
        };
        s.filter.residual = s.filter_residual();
        if s.filter.residual.is_nan() || s.filter.residual > 1e-9 {
            return Err(Error::invalid(
                "factor",
                s.filter.residual,
                "the given spectral factor does not reproduce N(ω²)/D(ω²)",
            ));
        }
        Ok(s)
    }

    /// Numerator coefficients in ascending powers of ω².
    pub fn numerator(&self) -> &[f64] {
        &self.num
    }
    /// Denominator coefficients in ascending powers of ω².
    pub fn denominator(&self) -> &[f64] {
        &self.den
    }

    /// The stable minimum-phase shaping filter (see the type docs).
    ///
    /// When deg N = deg D the filter is proper but not strictly proper: the process contains a white-noise
    /// component (ideal white noise is N = S₀, D = 1, filter √(2πS₀)) and has infinite variance, yet it
    /// can still drive a system whose output variance is finite.
    ///
    /// # Errors
    /// [`Error::Divergent`] when deg N > deg D: S grows without bound and no filter driven by white
    /// noise produces it.
    pub fn shaping_filter(&self) -> Result<ShapingFilter> {
        if self.num.len() > self.den.len() {
            return Err(self.improper());
        }
        Ok(self.filter.clone())
    }

    /// The density q·S(ω), q > 0: the same poles, the numerator scaled by q and the shaping filter's numerator
    /// by √q (so the factor is not recomputed and stays exact).
    ///
    /// # Errors
    /// `q` must be finite and > 0.
    ///
    /// # Examples
    /// ```
    /// use stochvib::spectrum::{Domain, RationalSpectrum, Spectrum};
    /// let s = RationalSpectrum::new(vec![1.0], vec![1.0, 1.0], Domain::Temporal).unwrap();
    /// let h = s.scaled(0.25).unwrap();
    /// assert!((h.density(2.0) - 0.25 * s.density(2.0)).abs() < 1e-15);
    /// ```
    pub fn scaled(&self, q: f64) -> Result<RationalSpectrum> {
        crate::error::require_positive("scale", q)?;
        let mut s = self.clone();
        s.num.iter_mut().for_each(|c| *c *= q);
        s.filter.num.iter_mut().for_each(|c| *c *= q.sqrt());
        Ok(s)
    }

    /// The spectrum of the same profile seen at speed `v` (for a spatial spectrum): S_t(ω) = S(ω/v)/v.
    ///
    /// # Errors
    /// `v` must be finite and > 0.
    pub fn at_speed(&self, v: f64) -> Result<RationalSpectrum> {
        crate::error::require_positive("speed", v)?;
        let scale = |c: &[f64], extra: f64| -> Vec<f64> {
            c.iter()
                .enumerate()
                .map(|(k, x)| x * extra / v.powi(2 * k as i32))
                .collect()
        };
        RationalSpectrum::new(scale(&self.num, 1.0 / v), scale(&self.den, 1.0), Domain::Temporal)
    }

    fn improper(&self) -> Error {
        Error::Divergent {
            quantity: "variance of the rational spectrum".into(),
            reason: format!(
                "deg N = {} ≥ deg D = {} in ω²: S(ω) does not decay faster than 1/ω²·… it tends to a \
                 non-zero constant or grows, so ∫S dω is infinite; use a band",
                self.num.len() - 1,
                self.den.len() - 1
            ),
        }
    }

    fn filter_residual(&self) -> f64 {
        let mut worst: f64 = 0.0;
        let scale = self.corners.iter().cloned().fold(1.0, f64::max);
        for k in 0..=60 {
            let w = scale * 10f64.powf(-3.0 + 6.0 * k as f64 / 60.0);
            let s = self.density(w);
            let h = poly::eval_complex(&self.filter.num, nalgebra::Complex::new(0.0, w))
                / poly::eval_complex(&self.filter.den, nalgebra::Complex::new(0.0, w));
            let f = h.norm_sqr() / (2.0 * PI);
            if s > 0.0 {
                worst = worst.max((f - s).abs() / s);
            }
        }
        worst
    }
}

impl Spectrum for RationalSpectrum {
    fn describe(&self) -> String {
        format!(
            "rational: N(w^2) = {:?}, D(w^2) = {:?} (ascending powers of w^2)",
            self.num, self.den
        )
    }
    fn domain(&self) -> Domain {
        self.domain
    }
    fn density(&self, omega: f64) -> f64 {
        let x = omega * omega;
        poly::eval(&self.num, x) / poly::eval(&self.den, x)
    }
    /// Eight points at a time ([`poly::eval_lanes`]): the same operations as [`density`](Self::density),
    /// so bit-identical to it; 55.6 → 9.0 µs for 10⁴ points against one Horner chain per point (criterion
    /// `density_1e4/rational/density_into`, 2-core AMD EPYC, 2026-11-23).
    fn density_into(&self, omega: &[f64], out: &mut [f64]) {
        const L: usize = 8;
        let n = omega.len().min(out.len());
        let (omega, out) = (&omega[..n], &mut out[..n]);
        let mut w_blocks = omega.chunks_exact(L);
        let mut o_blocks = out.chunks_exact_mut(L);
        for (w, o) in (&mut w_blocks).zip(&mut o_blocks) {
            let x: [f64; L] = std::array::from_fn(|j| w[j] * w[j]);
            let num = poly::eval_lanes(&self.num, &x);
            let den = poly::eval_lanes(&self.den, &x);
            for j in 0..L {
                o[j] = num[j] / den[j];
            }
        }
        for (o, &w) in o_blocks.into_remainder().iter_mut().zip(w_blocks.remainder()) {
            *o = self.density(w);
        }
    }
    fn high_frequency(&self) -> Asymptote {
        let (n, d) = (self.num.len() - 1, self.den.len() - 1);
        Asymptote::Power {
            exponent: 2.0 * (n as f64 - d as f64),
            coefficient: self.num[n] / self.den[d],
        }
    }
    fn low_frequency(&self) -> Asymptote {
        let n = self.num.iter().position(|v| *v != 0.0).unwrap_or(0);
        let d = self.den.iter().position(|v| *v != 0.0).unwrap_or(0);
        Asymptote::Power {
            exponent: 2.0 * (n as f64 - d as f64),
            coefficient: self.num[n] / self.den[d],
        }
    }
    fn breakpoints(&self) -> Vec<f64> {
        self.corners.clone()
    }
    /// Closed form by the integral table: D = (1/2π) ∫ |B(iω)/A(iω)|² dω.
    fn variance(&self) -> Result<f64> {
        if self.num.len() >= self.den.len() {
            return Err(self.improper());
        }
        let f = self.shaping_filter()?;
        match crate::linalg::h2_integral(&f.num, &f.den) {
            Ok(v) => Ok(v / (2.0 * PI)),
            // a filter of high order whose Hurwitz system is numerically singular (an 8th-order Butterworth
            // pair): the density itself is still exact, so integrate it
            Err(Error::Numerical { .. }) => super::numeric::variance(self).map(|r| r.value),
            Err(e) => Err(e),
        }
    }
    fn rational(&self) -> Option<RationalSpectrum> {
        Some(self.clone())
    }
}
