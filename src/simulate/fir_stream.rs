//! Streamed spectral synthesis: stationary Gaussian outputs of any input spectrum and any linear system,
//! produced in time order with memory independent of the record length — white noise through finite
//! (FIR) kernels designed from the spectrum, filtered by overlap-save with a fixed FFT size.

use super::rng::fill_standard_normal;
use crate::error::{Error, Result};
use rand::rngs::Xoshiro256PlusPlus;
use realfft::num_complex::Complex;
use realfft::{ComplexToReal, RealFftPlanner, RealToComplex};
use std::sync::Arc;

/// Default bound of the kernel energy left outside the FIR window, as a fraction of each output's
/// variance on the kernel grid: the truncation lowers each output's variance by at most this fraction
/// (σ by at most half of it). Why 1e-4: the bias of σ it allows, ≤ 5·10⁻⁵ relative, is far below the
/// statistical half-width of a σ interval of any practical run (≈ z/√(2·R·N_eff) relative with R
/// realizations of N_eff independent samples: 1.96/√(2·10⁴·10⁵) ≈ 4·10⁻⁵ needs 10⁴ realizations of 10⁵
/// correlation times), so the streamed route is as good as unbiased; the run notes print each output's
/// actual fraction. A run may raise it (`RunOptions::stream_tail`, `--stream-tail`) for a spectrum with a
/// sharp edge, whose kernel decays only like 1/t (energy outside ±M lags ∝ 1/M): 10× the tolerance gives
/// 10× shorter kernels.
pub const TAIL_FRACTION: f64 = 1e-4;

/// Default bound of the relative change of each output's grid variance when the kernel grid is halved
/// (the estimate of the grid's rectangle-rule bias, which halves with every doubling for a spectrum with
/// jumps, e.g. a band edge).
pub const GRID_TOLERANCE: f64 = 1e-3;

/// Smallest kernel grid tried.
pub const MIN_GRID: usize = 1 << 12;

/// Largest kernel grid tried (2²⁴ points: the design's transient tables then take about
/// 72 bytes × 2²⁴ ≈ 1.2 GB per generator–output pair; the kernels then have up to 2²² taps).
pub const MAX_GRID: usize = 1 << 24;

/// The kernel spectra of a design on a grid of L points: `b[g][r][j]`, j = 0..=L/2, the DFT coefficients
/// of the circular kernel from generator g's white noise to output r (see [`FirSynthesis::design`]).
pub type KernelSpectra = Vec<Vec<Vec<Complex<f64>>>>;

/// How a [`FirSynthesis`] was designed: the kernel grid, the window and the two error measures.
#[derive(Debug, Clone, PartialEq)]
pub struct KernelDesign {
    /// Length L of the kernel grid (a power of two).
    pub grid_len: usize,
    /// Lag (in steps) of the first tap: the window is lags `first_lag .. first_lag + taps` (≤ 0).
    pub first_lag: i64,
    /// Per output: the fraction of its grid variance left outside the window (≤ the requested tail).
    pub tail_fraction: Vec<f64>,
    /// Per output: |σ²(L) − σ²(L/2)| / σ²(L), the change of the grid variance over the last doubling.
    pub grid_change: Vec<f64>,
    /// Per output: the variance Σ_g Σ_m h²\[m\] of the whole circular kernel on the grid.
    pub grid_variance: Vec<f64>,
}

/// Generators–outputs FIR synthesis by overlap-save, streaming one segment at a time.
///
/// # Formula
/// With w_g\[n\] independent standard normal white noise per generator g (one per independent input
/// process) and kernels k_{g,r}\[i\], i = 0..T (T taps, first lag a ≤ 0):
/// ```text
/// y_r[n] = Σ_g Σ_{i=0}^{T−1} k_{g,r}[i] w_g[n − i],     Var y_r = Σ_g Σ_i k_{g,r}[i]²,
/// K_r(ℓ) = E y_r[n] y_r[n+ℓ] = Σ_g Σ_i k_{g,r}[i] k_{g,r}[i+ℓ]
/// ```
/// exactly (a stationary moving-average process from its first sample: T − 1 noise samples are drawn
/// before the first output). Overlap-save with a fixed FFT size F (the smallest power of two ≥ 4T and
/// ≥ 1024): each segment draws H = F − T + 1 new samples per generator, in generator order, and yields H
/// outputs; the block size of a run only groups whole segments, so the draws, and hence the outputs, do
/// not depend on it.
///
/// Design from a spectrum ([`FirSynthesis::design`]): on a grid of L points, Δω = 2π/(LΔt),
/// ω_j = jΔω, the circular kernel
/// ```text
/// h_{g,r}[m] = Σ_{j=−L/2+1}^{L/2} b_{g,r,j} e^{iω_j mΔt},   b_{g,r,j} = G_{g,r}(ω_j) √(S_g(ω_j)Δω / L)
/// ```
/// (b_{−j} = conj b_j; one unnormalised inverse real FFT) has Σ_m h² = Σ_j w_j S_g(ω_j)Δω|G_{g,r}(ω_j)|²
/// (Parseval; w_j = 2, 1 at j = 0, L/2): the variance of the periodic spectral route on the same grid
/// ([`SpectralGenerator`](super::SpectralGenerator) with N = L), i.e. the white noise through h has the
/// grid density |b_j|²L/Δω = S_g|G|². The window is the lags −a..b around 0 grown greedily (by chunks of
/// 1/16 of its length, towards the side holding more normalised energy) until every output keeps at
/// least 1 − `tail` of its grid variance; L doubles from [`MIN_GRID`] until the window fits in L/4 (the
/// circular kernel is then a close approximation of the aperiodic one) and each output's grid variance
/// changed by at most `grid_tol` relative over the last doubling.
///
/// # Errors
/// [`FirSynthesis::from_taps`]: no generator or output, kernels of different lengths, non-finite taps.
/// [`FirSynthesis::design`]: the spectrum callback's errors; tables of the wrong shape; a kernel that
/// does not meet the bounds on a grid of [`MAX_GRID`] points (the message names the output and the numbers).
///
/// # Examples
/// ```
/// use stochvib::simulate::{FirSynthesis, stream};
/// // y[n] = w[n] + 0.5 w[n−1]: variance 1.25, lag-1 covariance 0.5
/// let fir = FirSynthesis::from_taps(vec![vec![vec![1.0, 0.5]]]).unwrap();
/// assert_eq!(fir.variance(0), 1.25);
/// assert_eq!(fir.autocovariance(0, 3), vec![1.25, 0.5, 0.0]);
/// let mut sc = fir.scratch();
/// let mut rng = stream(1, 0);
/// fir.start(&mut rng, &mut sc);
/// fir.next_segment(&mut rng, &mut sc).unwrap();
/// assert_eq!(fir.output(&sc, 0).len(), fir.hop());
/// ```
#[derive(Clone)]
pub struct FirSynthesis {
    taps: usize,
    fft_len: usize,
    /// kernels\[g\]\[r\]\[i\]
    kernels: Vec<Vec<Vec<f64>>>,
    /// spectra\[g\]\[r\]\[j\]: DFT of the zero-padded kernel, divided by F (the inverse FFT is unnormalised)
    spectra: KernelSpectra,
    forward: Arc<dyn RealToComplex<f64>>,
    inverse: Arc<dyn ComplexToReal<f64>>,
}

impl std::fmt::Debug for FirSynthesis {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("FirSynthesis")
            .field("generators", &self.kernels.len())
            .field("outputs", &self.kernels[0].len())
            .field("taps", &self.taps)
            .field("fft_len", &self.fft_len)
            .finish()
    }
}

/// Per-realization working memory of a [`FirSynthesis`]: O(F) per generator and output.
#[derive(Debug, Clone)]
pub struct FirScratch {
    /// history\[g\]: the last T − 1 noise samples, then the H new ones (the forward FFT's input, destroyed
    /// by it: the T − 1 samples the next segment keeps are saved in `kept` first)
    history: Vec<Vec<f64>>,
    /// the last T − 1 samples of a generator's segment, across its forward FFT
    kept: Vec<f64>,
    /// forward spectra of the current segment per generator
    x: Vec<Vec<Complex<f64>>>,
    y: Vec<Complex<f64>>,
    fft_scratch: Vec<Complex<f64>>,
    /// out\[r\]: the inverse FFT of output r's segment; its last H values are the segment's outputs
    out: Vec<Vec<f64>>,
}

fn fft_error(e: realfft::FftError) -> Error {
    Error::Numerical {
        what: "streamed spectral synthesis (FFT)".into(),
        reason: e.to_string(),
    }
}

/// The window of lags −a..b (b exclusive) around lag 0 of the circular energies `e[r][m]` (totals
/// `total[r]`) that keeps at least 1 − `tail` of every output's energy, grown greedily by chunks; returns
/// (a, b) and the fraction left outside per output.
fn window(e: &[Vec<f64>], total: &[f64], tail: f64) -> (usize, usize, Vec<f64>) {
    window_within(e, total, tail, e[0].len())
}

/// [`window`] with at most `limit` taps.
fn window_within(e: &[Vec<f64>], total: &[f64], tail: f64, limit: usize) -> (usize, usize, Vec<f64>) {
    let l = limit.min(e[0].len());
    let circ = e[0].len() as i64;
    let at = |r: usize, lag: i64| e[r][lag.rem_euclid(circ) as usize];
    let (mut a, mut b) = (0usize, 1usize);
    let mut inside: Vec<f64> = (0..e.len()).map(|r| at(r, 0)).collect();
    let outside = |inside: &[f64]| -> Vec<f64> {
        inside
            .iter()
            .zip(total)
            .map(|(i, t)| if *t > 0.0 { ((t - i) / t).max(0.0) } else { 0.0 })
            .collect()
    };
    while a + b < l && outside(&inside).iter().any(|f| *f > tail) {
        let chunk = ((a + b) / 16).max(8).min(l - a - b);
        let gain = |lags: std::ops::Range<i64>| -> (f64, Vec<f64>) {
            let per: Vec<f64> = (0..e.len()).map(|r| lags.clone().map(|m| at(r, m)).sum()).collect();
            let score = per
                .iter()
                .zip(total)
                .map(|(p, t)| if *t > 0.0 { p / t } else { 0.0 })
                .sum();
            (score, per)
        };
        let (left, lper) = gain(-((a + chunk) as i64)..-(a as i64));
        let (right, rper) = gain(b as i64..(b + chunk) as i64);
        if left > right {
            a += chunk;
            inside.iter_mut().zip(lper).for_each(|(i, p)| *i += p);
        } else {
            b += chunk;
            inside.iter_mut().zip(rper).for_each(|(i, p)| *i += p);
        }
    }
    let out = outside(&inside);
    (a, b, out)
}

/// The kernels h\[g\]\[r\] on a grid of `l` points: the inverse FFTs of the spectra `spectra(l)`
/// (checked: generators × outputs × (l/2 + 1) bins).
fn grid_kernels(
    spectra: &dyn Fn(usize) -> Result<KernelSpectra>,
    l: usize,
    planner: &mut RealFftPlanner<f64>,
) -> Result<Vec<Vec<Vec<f64>>>> {
    let b = spectra(l)?;
    let p = b.first().map_or(0, |x| x.len());
    if b.is_empty() || p == 0 || b.iter().any(|x| x.len() != p || x.iter().any(|y| y.len() != l / 2 + 1)) {
        return Err(Error::invalid(
            "kernel spectra",
            l,
            format!("need generators × outputs × {} bins", l / 2 + 1),
        ));
    }
    let inverse = planner.plan_fft_inverse(l);
    let mut h: Vec<Vec<Vec<f64>>> = Vec::with_capacity(b.len());
    for bg in b {
        let mut row = Vec::with_capacity(p);
        for mut br in bg {
            br[0].im = 0.0;
            br[l / 2].im = 0.0;
            let mut k = vec![0.0; l];
            inverse.process(&mut br, &mut k).map_err(fft_error)?;
            row.push(k);
        }
        h.push(row);
    }
    Ok(h)
}

/// The energy e\[r\]\[m\] = Σ_g h\[g\]\[r\]\[m\]² of every output's kernels at each lag, and its total (the
/// grid variance), which must be finite.
fn kernel_energies(h: &[Vec<Vec<f64>>], p: usize, l: usize) -> Result<(Vec<Vec<f64>>, Vec<f64>)> {
    let mut e = vec![vec![0.0; l]; p];
    for hg in h {
        for (er, k) in e.iter_mut().zip(hg) {
            er.iter_mut().zip(k).for_each(|(a, v)| *a += v * v);
        }
    }
    let total: Vec<f64> = e.iter().map(|er| er.iter().sum()).collect();
    if let Some(r) = total.iter().position(|t| !t.is_finite()) {
        return Err(Error::Numerical {
            what: "streamed spectral synthesis".into(),
            reason: format!("the kernel of output {r} is not finite on a grid of {} points", l),
        });
    }
    Ok((e, total))
}

/// The relative change |D_L − D_{L/2}|/D_L of every output's grid variance since the previous grid (0 for a
/// zero variance); infinite without a previous grid.
fn grid_change(total: &[f64], previous: Option<&[f64]>) -> Vec<f64> {
    match previous {
        Some(prev) => total
            .iter()
            .zip(prev)
            .map(|(t, q)| if *t > 0.0 { (t - q).abs() / t } else { 0.0 })
            .collect(),
        None => vec![f64::INFINITY; total.len()],
    }
}

/// The refusal at the largest grid: the output whose window does not fit, or whose grid variance still
/// changes the most.
fn largest_grid_error(fits: bool, taps: usize, outside: &[f64], change: &[f64], tail: f64, grid_tol: f64) -> Error {
    let p = outside.len();
    let (r, what) = if !fits {
        let r = (0..p).max_by(|x, y| outside[*x].total_cmp(&outside[*y])).unwrap_or(0);
        (
            r,
            format!(
                "its kernel needs {taps} taps to keep all but {tail:e} of the variance, more than a quarter of the \
                 largest grid"
            ),
        )
    } else {
        let r = (0..p).max_by(|x, y| change[*x].total_cmp(&change[*y])).unwrap_or(0);
        (
            r,
            format!(
                "its grid variance still changes by {:.3e} (> {grid_tol:e}) when the grid doubles",
                change[r]
            ),
        )
    };
    Error::Numerical {
        what: format!("streamed spectral synthesis of output {r}"),
        reason: format!(
            "{what} ({MAX_GRID} points): the spectrum has sharp edges or narrow peaks at this step; \
             use the whole-record spectral route (--route spectral), a longer time step, or a smoother \
             or band-limited output"
        ),
    }
}

/// The grid a window that does not fit needs: the energy outside the window extrapolated from the windows
/// of L/8 and L/4 taps (outside fraction ∝ M^−α, α ≥ 1/2; α = 1 for a jump of the spectrum), with the
/// numbers in the error when that grid is beyond the largest. `g` generators, L = the energies' length.
fn needed_grid(e: &[Vec<f64>], total: &[f64], tail: f64, g: usize) -> Result<usize> {
    let (l, p) = (e[0].len(), e.len());
    let (.., out4) = window_within(e, total, tail, l / 4);
    let (.., out8) = window_within(e, total, tail, l / 8);
    let need = |r: usize| -> f64 {
        if out4[r] <= tail {
            return (l / 4) as f64;
        }
        let alpha = if out8[r] > out4[r] {
            (out8[r] / out4[r]).log2().clamp(0.5, 8.0)
        } else {
            0.5
        };
        (l / 4) as f64 * (out4[r] / tail).powf(1.0 / alpha)
    };
    let r = (0..p).max_by(|x, y| need(*x).total_cmp(&need(*y))).unwrap_or(0);
    let taps = need(r);
    let grid = (4.0 * taps).min(1e30);
    if grid > MAX_GRID as f64 {
        let gf = g as f64;
        let f = (4.0 * taps).log2().ceil().exp2();
        // the design's tables (b, h, energies) and one thread's overlap-save buffers and the shared
        // kernel spectra at that size
        let design = super::resources::kernel_design_bytes(g, p, f as usize) as f64;
        let stream = gf * f * 8.0
            + (gf + 1.0) * f * 8.0
            + 4.0 * f * 8.0
            + 2.0 * p as f64 * f * 8.0
            + gf * p as f64 * (taps * 8.0 + f * 8.0);
        return Err(Error::Numerical {
            what: format!("streamed spectral synthesis of output {r}"),
            reason: format!(
                "its kernel leaves {:.3e} of the variance outside {} taps and {:.3e} outside {} (a decay \
                 like M^−{:.2}), so keeping all but the tolerated tail {tail:e} needs about {:.3e} taps: a \
                 kernel grid of {:.3e} points (largest {MAX_GRID}) and about {:.1} GiB to design plus {:.1} \
                 GiB to stream. The spectrum has a sharp edge or a narrow peak at this step: use the \
                 whole-record spectral route (--route spectral), a larger tail tolerance (--stream-tail; \
                 the variance is then biased low by at most that fraction), a longer time step, or a \
                 smoother or band-limited output",
                out8[r],
                l / 8,
                out4[r],
                l / 4,
                if out8[r] > out4[r] {
                    (out8[r] / out4[r]).log2()
                } else {
                    0.0
                },
                taps,
                grid,
                design / (1u64 << 30) as f64,
                stream / (1u64 << 30) as f64
            ),
        });
    }
    Ok((grid as usize).next_power_of_two())
}

/// The next grid's design tables (kernel spectra, kernels, energies) must fit in the available memory
/// before they are allocated.
fn check_design_memory(g: usize, p: usize, next: usize) -> Result<()> {
    let design = super::resources::kernel_design_bytes(g, p, next) as f64;
    if let Some(avail) = super::resources::available_memory()
        && design > avail as f64
    {
        return Err(Error::Numerical {
            what: "streamed spectral synthesis".into(),
            reason: format!(
                "designing its kernels on a grid of {next} points needs about {:.2} GiB, more than the \
                     {:.2} GiB available: use the whole-record spectral route (--route spectral), a larger \
                     tail tolerance (--stream-tail), a longer time step, or a smoother or band-limited output",
                design / (1u64 << 30) as f64,
                avail as f64 / (1u64 << 30) as f64
            ),
        });
    }
    Ok(())
}

impl FirSynthesis {
    /// A synthesis from explicit taps `kernels[g][r][i]` (every kernel of the same length T ≥ 1).
    ///
    /// # Errors
    /// See the type's `# Errors`.
    pub fn from_taps(kernels: Vec<Vec<Vec<f64>>>) -> Result<FirSynthesis> {
        let g = kernels.len();
        let p = kernels.first().map_or(0, |k| k.len());
        let taps = kernels.first().and_then(|k| k.first()).map_or(0, |k| k.len());
        if g == 0 || p == 0 || taps == 0 {
            return Err(Error::invalid(
                "kernels",
                format!("{g} generators × {p} outputs × {taps} taps"),
                "need at least one generator, one output and one tap",
            ));
        }
        if kernels
            .iter()
            .any(|k| k.len() != p || k.iter().any(|t| t.len() != taps))
        {
            return Err(Error::invalid(
                "kernels",
                "ragged",
                "every kernel needs the same number of taps",
            ));
        }
        if kernels.iter().flatten().flatten().any(|v| !v.is_finite()) {
            return Err(Error::invalid("kernels", "non-finite tap", "taps must be finite"));
        }
        let fft_len = (4 * taps).next_power_of_two().max(1024);
        let (forward, inverse) = super::fft_plans::real_fft_pair(fft_len);
        let mut buf = vec![0.0; fft_len];
        let mut spectra = Vec::with_capacity(g);
        for kg in &kernels {
            let mut row = Vec::with_capacity(p);
            for k in kg {
                buf.iter_mut().for_each(|v| *v = 0.0);
                buf[..taps].copy_from_slice(k);
                let mut s = forward.make_output_vec();
                forward.process(&mut buf, &mut s).map_err(fft_error)?;
                let scale = 1.0 / fft_len as f64;
                s.iter_mut().for_each(|c| *c *= scale);
                row.push(s);
            }
            spectra.push(row);
        }
        Ok(FirSynthesis {
            taps,
            fft_len,
            kernels,
            spectra,
            forward,
            inverse,
        })
    }

    /// Designs the kernels from their spectra on doubling grids (see the type's formula): `spectra(L)`
    /// returns b\[g\]\[r\]\[j\], j = 0..=L/2, for a grid of L points; `min_grid` is the first grid tried
    /// (raised to [`MIN_GRID`] and a power of two), `tail` and `grid_tol` the bounds of the window's
    /// truncation and of the grid change ([`TAIL_FRACTION`], [`GRID_TOLERANCE`] by default).
    ///
    /// # Errors
    /// See the type's `# Errors`.
    ///
    /// # Examples
    /// ```
    /// use stochvib::simulate::{FirSynthesis, fir_stream::{GRID_TOLERANCE, TAIL_FRACTION}};
    /// use realfft::num_complex::Complex;
    /// // unit white noise sampled at Δt = 1 (S = 1/(2π) on |ω| ≤ π): b_j = √(SΔω/L) = 1/L, kernel δ[m]
    /// let (fir, d) = FirSynthesis::design(
    ///     &|l| Ok(vec![vec![vec![Complex::new(1.0 / l as f64, 0.0); l / 2 + 1]]]),
    ///     0, TAIL_FRACTION, GRID_TOLERANCE,
    /// ).unwrap();
    /// assert_eq!((fir.taps(), d.first_lag), (1, 0));
    /// assert!((fir.variance(0) - 1.0).abs() < 1e-12);
    /// ```
    pub fn design(
        spectra: &dyn Fn(usize) -> Result<KernelSpectra>,
        min_grid: usize,
        tail: f64,
        grid_tol: f64,
    ) -> Result<(FirSynthesis, KernelDesign)> {
        if !(tail > 0.0 && tail < 1.0 && grid_tol > 0.0) {
            return Err(Error::invalid(
                "tail fraction",
                format!("{tail}, grid tolerance {grid_tol}"),
                "need 0 < tail < 1 and a positive grid tolerance",
            ));
        }
        let mut l = min_grid.max(MIN_GRID).next_power_of_two();
        let mut planner = RealFftPlanner::<f64>::new();
        let mut previous: Option<Vec<f64>> = None;
        loop {
            let h = grid_kernels(spectra, l, &mut planner)?;
            let p = h[0].len();
            let (e, total) = kernel_energies(&h, p, l)?;
            let (a, bb, outside) = window(&e, &total, tail);
            let fits = 4 * (a + bb) <= l;
            let change = grid_change(&total, previous.as_deref());
            if fits && change.iter().all(|c| *c <= grid_tol) {
                let taps = a + bb;
                let kernels = h
                    .iter()
                    .map(|hg| {
                        hg.iter()
                            .map(|k| (0..taps).map(|i| k[(l + i - a) % l]).collect())
                            .collect()
                    })
                    .collect();
                let fir = FirSynthesis::from_taps(kernels)?;
                return Ok((
                    fir,
                    KernelDesign {
                        grid_len: l,
                        first_lag: -(a as i64),
                        tail_fraction: outside,
                        grid_change: change,
                        grid_variance: total,
                    },
                ));
            }
            if 2 * l > MAX_GRID {
                return Err(largest_grid_error(fits, a + bb, &outside, &change, tail, grid_tol));
            }
            // a window that does not fit: jump to the grid it needs (or fail now with the numbers)
            let next = if fits {
                2 * l
            } else {
                (2 * l).max(needed_grid(&e, &total, tail, h.len())?)
            };
            check_design_memory(h.len(), p, next)?;
            previous = Some(total);
            l = next;
        }
    }

    /// Number of taps T of every kernel.
    pub fn taps(&self) -> usize {
        self.taps
    }
    /// FFT size F of overlap-save (from T only, never from the record or block length).
    pub fn fft_len(&self) -> usize {
        self.fft_len
    }
    /// New samples per segment, H = F − T + 1.
    pub fn hop(&self) -> usize {
        self.fft_len - self.taps + 1
    }
    /// Number of generators (independent white noises).
    pub fn n_generators(&self) -> usize {
        self.kernels.len()
    }
    /// Number of outputs.
    pub fn n_outputs(&self) -> usize {
        self.kernels[0].len()
    }
    /// The taps k_{g,r}\[0..T\].
    ///
    /// # Panics
    /// g or r out of range (a programming error).
    pub fn kernel(&self, g: usize, r: usize) -> &[f64] {
        &self.kernels[g][r]
    }
    /// Exact variance of output r: Σ_g Σ_i k_{g,r}\[i\]².
    ///
    /// # Panics
    /// r out of range.
    pub fn variance(&self, r: usize) -> f64 {
        self.kernels
            .iter()
            .map(|kg| kg[r].iter().map(|v| v * v).sum::<f64>())
            .sum()
    }
    /// Exact autocovariance of output r at lags 0..`lags` (see the type's formula).
    ///
    /// # Panics
    /// r out of range.
    pub fn autocovariance(&self, r: usize, lags: usize) -> Vec<f64> {
        (0..lags)
            .map(|l| {
                self.kernels
                    .iter()
                    .map(|kg| {
                        let k = &kg[r];
                        if l >= k.len() {
                            0.0
                        } else {
                            k[..k.len() - l].iter().zip(&k[l..]).map(|(a, b)| a * b).sum::<f64>()
                        }
                    })
                    .sum()
            })
            .collect()
    }
    /// Bytes of the shared tables (taps and kernel spectra).
    pub fn table_bytes(&self) -> usize {
        let (g, p) = (self.n_generators(), self.n_outputs());
        g * p * (self.taps * 8 + (self.fft_len / 2 + 1) * 16)
    }
    /// Fresh working memory.
    pub fn scratch(&self) -> FirScratch {
        let f = self.fft_len;
        let g = self.n_generators();
        FirScratch {
            history: vec![vec![0.0; f]; g],
            kept: vec![0.0; self.taps - 1],
            x: vec![vec![Complex::new(0.0, 0.0); f / 2 + 1]; g],
            y: vec![Complex::new(0.0, 0.0); f / 2 + 1],
            fft_scratch: vec![
                Complex::new(0.0, 0.0);
                self.forward.get_scratch_len().max(self.inverse.get_scratch_len())
            ],
            out: vec![vec![0.0; f]; self.n_outputs()],
        }
    }
    /// Starts a realization: draws the T − 1 noise samples before the first output, per generator in
    /// order, from `rng`.
    pub fn start(&self, rng: &mut Xoshiro256PlusPlus, s: &mut FirScratch) {
        for h in &mut s.history {
            fill_standard_normal(rng, &mut h[..self.taps - 1]);
        }
    }
    /// The next segment: draws H samples per generator (in generator order) and computes H outputs of
    /// every output (read them with [`output`](Self::output)).
    ///
    /// # Errors
    /// A scratch of another synthesis; an FFT failure (never for a valid scratch).
    pub fn next_segment(&self, rng: &mut Xoshiro256PlusPlus, s: &mut FirScratch) -> Result<()> {
        let (f, t) = (self.fft_len, self.taps);
        let fits = s.history.iter().chain(&s.out).all(|v| v.len() == f) && s.kept.len() == t - 1;
        if s.history.len() != self.n_generators() || s.out.len() != self.n_outputs() || !fits {
            return Err(Error::invalid("scratch", s.kept.len(), "made by another synthesis"));
        }
        for (h, x) in s.history.iter_mut().zip(&mut s.x) {
            fill_standard_normal(rng, &mut h[t - 1..]);
            // the last T − 1 samples are the next segment's first ones: saved across the FFT, which uses its
            // input as scratch (the FFT reads the same values as from a copy: the same bits)
            s.kept.copy_from_slice(&h[f - (t - 1)..]);
            self.forward
                .process_with_scratch(h, x, &mut s.fft_scratch)
                .map_err(fft_error)?;
            h[..t - 1].copy_from_slice(&s.kept);
        }
        for (r, out) in s.out.iter_mut().enumerate() {
            // y_j = 0 + Σ_g x_g,j·K_g,r,j in generator order, every bin at once per generator, compiled for the
            // widest instruction set (the additions of a sum per bin, in the same order: the same bits)
            let mut terms = s.x.iter().zip(&self.spectra);
            match terms.next() {
                Some((x, k)) => crate::linalg::vmath::complex_mul_from_zero(&mut s.y, x, &k[r]),
                None => s.y.fill(Complex::new(0.0, 0.0)),
            }
            for (x, k) in terms {
                crate::linalg::vmath::complex_mul_add(&mut s.y, x, &k[r]);
            }
            s.y[0].im = 0.0;
            s.y[f / 2].im = 0.0;
            self.inverse
                .process_with_scratch(&mut s.y, out, &mut s.fft_scratch)
                .map_err(fft_error)?;
        }
        Ok(())
    }
    /// The H outputs of output r from the last [`next_segment`](Self::next_segment).
    ///
    /// # Panics
    /// r out of range.
    pub fn output<'a>(&self, s: &'a FirScratch, r: usize) -> &'a [f64] {
        &s.out[r][self.taps - 1..]
    }
}
