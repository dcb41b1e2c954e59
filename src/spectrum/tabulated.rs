//! Tabulated (measured) spectra with log–log interpolation.

use super::{Asymptote, Convention, Domain, Spectrum};
use crate::error::{Error, Result};

/// A measured density given at points, interpolated linearly in log–log coordinates between them and
/// zero outside the tabulated range.
///
/// # Formula
/// Between canonical points (ωₖ, Sₖ) and (ωₖ₊₁, Sₖ₊₁) the density is the power law
/// S(ω) = Sₖ (ω/ωₖ)^{pₖ}, pₖ = ln(Sₖ₊₁/Sₖ)/ln(ωₖ₊₁/ωₖ), so the variance of the interpolant is exact:
/// ```text
/// D = 2 Σₖ Sₖ ωₖ [(ωₖ₊₁/ωₖ)^{pₖ+1} − 1]/(pₖ + 1)      (Sₖ ωₖ ln(ωₖ₊₁/ωₖ) when pₖ = −1)
/// ```
///
/// # Errors
/// [`Tabulated::new`] rejects fewer than two points, mismatched lengths, non-finite values, abscissae that
/// are not strictly increasing and positive, and non-positive densities (log–log needs S > 0).
///
/// # Examples
/// ```
/// use stochvib::spectrum::{Tabulated, Convention, Domain, Spectrum};
/// // G(f) ∝ f^-2 from 1 to 10 Hz, one-sided: variance ∫ 1/f² df = 0.9
/// let t = Tabulated::new(Convention::OneSidedCyclic, vec![1.0, 10.0], vec![1.0, 0.01], Domain::Temporal).unwrap();
/// assert!((t.variance().unwrap() - 0.9).abs() < 1e-12);
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct Tabulated {
    omega: Vec<f64>,
    density: Vec<f64>,
    convention: Convention,
    domain: Domain,
    /// Log-log slope of each segment, precomputed for `density`.
    slopes: Vec<f64>,
}

impl Tabulated {
    /// Builds a tabulated spectrum from abscissae `x` and ordinates `values` written in `convention`
    /// (x in Hz / cycles/m for `OneSidedCyclic`, rad/s / rad/m otherwise; one-sided tables give |ω|).
    ///
    /// # Errors
    /// See the type's `# Errors`.
    pub fn new(convention: Convention, x: Vec<f64>, values: Vec<f64>, domain: Domain) -> Result<Self> {
        if x.len() != values.len() {
            return Err(Error::invalid(
                "values",
                format!("{} values", values.len()),
                format!("must have as many entries as the {} frequencies", x.len()),
            ));
        }
        if x.len() < 2 {
            return Err(Error::invalid(
                "frequencies",
                format!("{x:?}"),
                "need at least two points",
            ));
        }
        for (i, (&xi, &vi)) in x.iter().zip(&values).enumerate() {
            if !(xi.is_finite() && xi > 0.0) {
                return Err(Error::invalid(
                    &format!("frequencies[{i}]"),
                    xi,
                    "must be finite and > 0 (log-log)",
                ));
            }
            if !(vi.is_finite() && vi > 0.0) {
                return Err(Error::invalid(
                    &format!("values[{i}]"),
                    vi,
                    "must be finite and > 0 (log-log)",
                ));
            }
            if i > 0 && xi <= x[i - 1] {
                return Err(Error::invalid(
                    &format!("frequencies[{i}]"),
                    xi,
                    "must be strictly increasing",
                ));
            }
        }
        let (omega, density) = x
            .iter()
            .zip(&values)
            .map(|(&xi, &vi)| convention.to_canonical(xi, vi))
            .unzip();
        let mut t = Tabulated {
            omega,
            density,
            convention,
            domain,
            slopes: Vec::new(),
        };
        t.slopes = (0..t.omega.len() - 1).map(|k| t.slope(k)).collect();
        Ok(t)
    }

    /// The canonical points (ω, S(ω)).
    pub fn points(&self) -> impl Iterator<Item = (f64, f64)> + '_ {
        self.omega.iter().cloned().zip(self.density.iter().cloned())
    }

    /// S on segment k: S_k (ω/ω_k)^{p_k}, evaluated as S_k exp(p_k ln(ω/ω_k)) (exact at the nodes, where
    /// the logarithm is 0; about 10 % faster than `powf` here).
    #[inline]
    fn segment(&self, k: usize, w: f64) -> f64 {
        self.density[k] * (self.slopes[k] * (w / self.omega[k]).ln()).exp()
    }

    /// The segment of `density` at w ≥ 0 (the last k ≤ n − 2 with ω_k ≤ w), None outside the table,
    /// found by walking from the segment `k` of the previous point (a binary search when w lies below it).
    #[inline]
    fn walk(&self, k: &mut usize, w: f64) -> Option<usize> {
        let n = self.omega.len();
        if w < self.omega[0] || w > self.omega[n - 1] {
            return None;
        }
        if w < self.omega[*k] {
            *k = self.omega.partition_point(|&x| x <= w).saturating_sub(1).min(n - 2);
        } else {
            while *k + 1 < n - 1 && self.omega[*k + 1] <= w {
                *k += 1;
            }
        }
        Some(*k)
    }

    fn slope(&self, k: usize) -> f64 {
        (self.density[k + 1] / self.density[k]).ln() / (self.omega[k + 1] / self.omega[k]).ln()
    }
}

/// `out[i] = level[i]·exp(slope[i]·ln(w[i]/node[i]))` by [`vmath`](crate::linalg::vmath)'s functions, as a
/// [`Task`](crate::linalg::vmath::Task) compiled for the CPU's widest SIMD unit.
struct Segments<'a> {
    level: &'a [f64],
    slope: &'a [f64],
    w: &'a [f64],
    node: &'a [f64],
    out: &'a mut [f64],
}

impl crate::linalg::vmath::Task for Segments<'_> {
    #[inline(always)]
    fn run(&mut self) {
        use crate::linalg::vmath::{exp, ln};
        let args = self.level.iter().zip(self.slope).zip(self.w.iter().zip(self.node));
        for (o, ((&l, &p), (&w, &wk))) in self.out.iter_mut().zip(args) {
            *o = l * exp(p * ln(w / wk));
        }
    }
}

impl Spectrum for Tabulated {
    fn describe(&self) -> String {
        format!(
            "tabulated ({} points, given as {}), {}..{} {}",
            self.omega.len(),
            self.convention,
            self.omega[0],
            self.omega[self.omega.len() - 1],
            self.domain.angular_unit()
        )
    }
    fn domain(&self) -> Domain {
        self.domain
    }
    fn density(&self, omega: f64) -> f64 {
        let w = omega.abs();
        let n = self.omega.len();
        if w < self.omega[0] || w > self.omega[n - 1] {
            return 0.0;
        }
        let k = self.omega.partition_point(|&x| x <= w).saturating_sub(1).min(n - 2);
        self.segment(k, w)
    }
    /// The formula of `density` with the vectorised [`vmath::exp`](crate::linalg::vmath::exp) and
    /// [`vmath::ln`](crate::linalg::vmath::ln) (within 4 ulp of `density` where |p_k ln(ω/ω_k)| ≤ 1, and
    /// exact at the nodes); the segments are found first, in blocks of 256 points, by walking from the
    /// previous point's segment instead of a binary search per point.
    fn density_into(&self, omega: &[f64], out: &mut [f64]) {
        use crate::linalg::vmath;
        const BLOCK: usize = 256;
        let mut k = 0;
        let (mut aw, mut node, mut slope, mut level) = ([1.0; BLOCK], [1.0; BLOCK], [0.0; BLOCK], [0.0; BLOCK]);
        for (w, o) in omega.chunks(BLOCK).zip(out.chunks_mut(BLOCK)) {
            let m = w.len().min(o.len());
            for i in 0..m {
                let a = w[i].abs();
                (aw[i], node[i], slope[i], level[i]) = match self.walk(&mut k, a) {
                    Some(k) => (a, self.omega[k], self.slopes[k], self.density[k]),
                    None => (1.0, 1.0, 0.0, 0.0),
                };
            }
            vmath::run(&mut Segments {
                level: &level[..m],
                slope: &slope[..m],
                w: &aw[..m],
                node: &node[..m],
                out: &mut o[..m],
            });
        }
    }
    fn high_frequency(&self) -> Asymptote {
        Asymptote::Vanishing
    }
    fn low_frequency(&self) -> Asymptote {
        Asymptote::Vanishing
    }
    fn support(&self) -> (f64, f64) {
        (self.omega[0], self.omega[self.omega.len() - 1])
    }
    fn breakpoints(&self) -> Vec<f64> {
        self.omega.clone()
    }
    fn variance(&self) -> Result<f64> {
        let mut total = 0.0;
        for k in 0..self.omega.len() - 1 {
            let p = self.slopes[k];
            let r = self.omega[k + 1] / self.omega[k];
            let seg = if (p + 1.0).abs() < 1e-12 {
                self.density[k] * self.omega[k] * r.ln()
            } else {
                self.density[k] * self.omega[k] * (r.powf(p + 1.0) - 1.0) / (p + 1.0)
            };
            total += seg;
        }
        Ok(2.0 * total)
    }
}
