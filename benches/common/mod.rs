//! Problem definitions shared by the criterion benches (`benches/*.rs`) and the comparison binary
//! (`examples/compare_rust.rs`), so that both time exactly the jobs `benches/compare/compare.py` does.
//!
//! The model is the sprung-cab scraper of `data/scraper-sprung-cab.toml` (Sukharev 8.7, eq. (8.65)):
//! m₁ = 30 t, ω₁ = 18.5 rad/s, ζ₁ = 0.1, m₂ = 2 t; the cab mount (c₂, b₂) is what the sweep varies. The
//! rational road is the graded dirt road (8.69), spatial type 1 (D = 32 cm², α = 0.16 1/m), at 10 m/s.
//! The non-rational input is a temporal type-4 process (`GaussCosine`).
#![allow(dead_code)] // every bench target uses a different subset

use nalgebra::DMatrix;
use std::f64::consts::PI;
use std::sync::Arc;
use stochvib::linalg::{h2_integral, solve_continuous_lyapunov};
use stochvib::models::scraper::{book_road_8_69, ScraperSprungCab};
use stochvib::response::{variance_lyapunov, Excitation};
use stochvib::spectrum::{AtSpeed, Domain, GaussCosine, GaussCosineParameters, Spectrum};

/// Front mass m₁, kg.
pub const M1: f64 = 3.0e4;
/// Tyre natural frequency √(c₁/m₁), rad/s.
pub const OMEGA1: f64 = 18.5;
/// Tyre damping ratio.
pub const ZETA1: f64 = 0.1;
/// Cab mass m₂, kg.
pub const M2: f64 = 2.0e3;
/// Nominal cab-mount frequency (1.5 Hz) and damping ratio (0.3) of the scenario file.
pub const OMEGA2: f64 = 2.0 * PI * 1.5;
/// Nominal cab-mount damping ratio.
pub const ZETA2: f64 = 0.3;
/// Road speed, m/s.
pub const SPEED: f64 = 10.0;
/// Output index of `x2_acc` (cab acceleration) in the sprung-cab instance.
pub const X2_ACC: usize = 3;

/// c₁ = m₁ ω₁², N/m.
pub fn c1() -> f64 {
    M1 * OMEGA1 * OMEGA1
}
/// b₁ = 2 ζ₁ √(c₁ m₁), N s/m.
pub fn b1() -> f64 {
    2.0 * ZETA1 * (c1() * M1).sqrt()
}
/// Nominal c₂, N/m.
pub fn c2_nominal() -> f64 {
    M2 * OMEGA2 * OMEGA2
}
/// Nominal b₂, N s/m.
pub fn b2_nominal() -> f64 {
    2.0 * ZETA2 * (c2_nominal() * M2).sqrt()
}

/// Sweep grid: c₂ over [m₂(2π·0.8 Hz)², m₂(2π·2.5 Hz)²] (N/m) × b₂ over [1, 30] kN s/m, linearly spaced,
/// `N_C2 × N_B2 = 10⁵` points (the same `numpy.linspace` grid in `compare.py`).
pub const N_C2: usize = 400;
/// Number of b₂ values.
pub const N_B2: usize = 250;

/// The c₂ and b₂ axes of the sweep grid.
pub fn grid() -> (Vec<f64>, Vec<f64>) {
    let lin = |lo: f64, hi: f64, n: usize| -> Vec<f64> {
        (0..n).map(|i| lo + (hi - lo) * i as f64 / (n - 1) as f64).collect()
    };
    let w = |f: f64| 2.0 * PI * f;
    (
        lin(M2 * w(0.8) * w(0.8), M2 * w(2.5) * w(2.5), N_C2),
        lin(1.0e3, 3.0e4, N_B2),
    )
}

/// The temporal road: (8.69) at 10 m/s.
pub fn road() -> Arc<dyn Spectrum> {
    Arc::new(AtSpeed::new(book_road_8_69(), SPEED).expect("valid speed"))
}

/// The type-4 input of the quadrature job: K(τ) = D e^{−ατ²} cos βτ with D = 1e-3 m², α = 20 1/s²,
/// β = 15 rad/s (a band around the tyre resonance).
pub const T4: (f64, f64, f64) = (1.0e-3, 20.0, 15.0);

/// The type-4 input as a spectrum.
pub fn type4() -> Arc<dyn Spectrum> {
    Arc::new(
        GaussCosineParameters {
            variance: T4.0,
            alpha: T4.1,
            beta: T4.2,
            domain: Domain::Temporal,
        }
        .build()
        .expect("valid constants"),
    )
}

/// Upper limit of the finite-interval quadrature job, rad/s: β + 40√α, where the type-4 density has
/// fallen by e^{−400} from its peak (both sides integrate [0, W] and double it).
pub fn type4_upper() -> f64 {
    T4.2 + 40.0 * T4.1.sqrt()
}

/// The library's sprung-cab system for one (c₂, b₂): every output, names and description included.
pub fn scraper(c2: f64, b2: f64) -> stochvib::models::ModelInstance {
    ScraperSprungCab {
        m1: M1,
        c1: c1(),
        b1: b1(),
        m2: M2,
        c2,
        b2,
    }
    .build()
    .and_then(|s| s.instance())
    .expect("valid scraper parameters")
}

/// σ of the cab acceleration through the public API, as a user would write it per point: build the model
/// instance, then `variance_lyapunov` (which re-derives the road's shaping filter every call).
pub fn sigma_api(exc: &Excitation, c2: f64, b2: f64) -> f64 {
    let inst = scraper(c2, b2);
    variance_lyapunov(inst.system.as_ref(), exc, X2_ACC)
        .expect("stable model, rational road")
        .variance
        .sqrt()
}

/// Fastest exact method for the sweep: the closed-form transfer function of (8.65) times the road's
/// shaping filter (computed once), integrated by the table I_n (`h2_integral`). Nothing is allocated by
/// this code per point (the library call allocates a few small vectors).
///
/// # Formula
/// ```text
/// k₁ = c₁ + b₁s, k₂ = c₂ + b₂s,  Δ = (m₁s² + k₁ + k₂)(m₂s² + k₂) − k₂²,  H_ẍ₂ = s² k₁ k₂ / Δ
/// σ² = (1/2π) ∫ |H_ẍ₂(iω) B(iω)/A(iω)|² dω       (B/A: shaping filter of the road, unit white noise)
/// ```
pub struct SweepTable {
    fnum: Vec<f64>,
    fden: Vec<f64>,
    c1: f64,
    b1: f64,
}

/// Product of ascending-coefficient polynomials into a fixed buffer; returns the used length.
#[inline]
fn mul_into(p: &[f64], q: &[f64], out: &mut [f64]) -> usize {
    let n = p.len() + q.len() - 1;
    out[..n].fill(0.0);
    for (i, a) in p.iter().enumerate() {
        for (j, b) in q.iter().enumerate() {
            out[i + j] += a * b;
        }
    }
    n
}

impl SweepTable {
    /// Factors the road once.
    pub fn new(road: &dyn Spectrum) -> Self {
        let f = road
            .rational()
            .expect("rational road")
            .shaping_filter()
            .expect("proper filter");
        SweepTable {
            fnum: f.num,
            fden: f.den,
            c1: c1(),
            b1: b1(),
        }
    }

    /// Numerator and denominator (ascending powers of s) of H_ẍ₂(s) B(s)/A(s), with their lengths.
    #[inline]
    fn polys(&self, c2: f64, b2: f64) -> ([f64; 12], usize, [f64; 12], usize) {
        let (c1, b1) = (self.c1, self.b1);
        let p1 = [c1 + c2, b1 + b2, M1];
        let p2 = [c2, b2, M2];
        let k2 = [c2, b2];
        let mut delta = [0.0; 5];
        mul_into(&p1, &p2, &mut delta);
        let mut kk = [0.0; 3];
        mul_into(&k2, &k2, &mut kk);
        for (d, k) in delta.iter_mut().zip(kk) {
            *d -= k;
        }
        // s² k₁ k₂
        let mut n = [0.0; 5];
        mul_into(&[c1, b1], &k2, &mut n[2..]);
        let mut num = [0.0; 12];
        let mut den = [0.0; 12];
        let ln = mul_into(&n, &self.fnum, &mut num);
        let ld = mul_into(&delta, &self.fden, &mut den);
        (num, ln, den, ld)
    }

    /// σ of the cab acceleration, m/s², by the library's `h2_integral`.
    #[inline]
    pub fn sigma(&self, c2: f64, b2: f64) -> f64 {
        let (num, ln, den, ld) = self.polys(c2, b2);
        (h2_integral(&num[..ln], &den[..ld]).expect("stable, strictly proper") / (2.0 * PI)).sqrt()
    }
}

/// The same variance by the library's Lyapunov solver on the augmented state z = [x_F, x₁, x₂, v₁, v₂]
/// (the formulation `compare.py` hands to `scipy.linalg.solve_continuous_lyapunov`); the matrices are
/// reused across points, only the entries that depend on (c₂, b₂) change.
///
/// # Formula
/// ```text
/// ẋ_F = −a x_F + g w (road q = x_F),  m₁v̇₁ = −(c₁+c₂)x₁ + c₂x₂ − (b₁+b₂)v₁ + b₂v₂ + c₁q + b₁q̇,
/// m₂v̇₂ = c₂(x₁ − x₂) + b₂(v₁ − v₂),   ẍ₂ = h z,   F P + P Fᵀ + G Gᵀ = 0,   σ² = h P hᵀ
/// ```
pub struct SweepLyapunov {
    a: DMatrix<f64>,
    q: DMatrix<f64>,
}

impl SweepLyapunov {
    /// From a first-order road filter g/(s + a).
    pub fn new(road: &dyn Spectrum) -> Self {
        let f = road
            .rational()
            .expect("rational road")
            .shaping_filter()
            .expect("proper filter");
        assert!(f.num.len() == 1 && f.den.len() == 2, "first-order road filter expected");
        let (pole, gain) = (f.den[0] / f.den[1], f.num[0] / f.den[1]);
        let mut a = DMatrix::zeros(5, 5);
        a[(0, 0)] = -pole;
        a[(1, 3)] = 1.0;
        a[(2, 4)] = 1.0;
        a[(3, 0)] = (c1() - b1() * pole) / M1;
        let g = DMatrix::from_column_slice(5, 1, &[gain, 0.0, 0.0, b1() * gain / M1, 0.0]);
        let q = &g * g.transpose();
        SweepLyapunov { a, q }
    }

    /// σ of the cab acceleration, m/s².
    pub fn sigma(&mut self, c2: f64, b2: f64) -> f64 {
        let (c1, b1) = (c1(), b1());
        let a = &mut self.a;
        a[(3, 1)] = -(c1 + c2) / M1;
        a[(3, 2)] = c2 / M1;
        a[(3, 3)] = -(b1 + b2) / M1;
        a[(3, 4)] = b2 / M1;
        a[(4, 1)] = c2 / M2;
        a[(4, 2)] = -c2 / M2;
        a[(4, 3)] = b2 / M2;
        a[(4, 4)] = -b2 / M2;
        let p = solve_continuous_lyapunov(a, &self.q).expect("stable");
        let h = [0.0, c2 / M2, -c2 / M2, b2 / M2, -b2 / M2];
        let mut v = 0.0;
        for i in 0..5 {
            for j in 0..5 {
                v += h[i] * p[(i, j)] * h[j];
            }
        }
        v.sqrt()
    }
}

/// Closed-form two-sided density of `x2_acc` under the type-4 input, S(ω)|H_ẍ₂(iω)|² (a hand-written
/// integrand, to separate the library's per-evaluation overhead from the quadrature itself).
#[inline]
pub fn type4_density_closed(s4: &GaussCosine, c2: f64, b2: f64, w: f64) -> f64 {
    use nalgebra::Complex;
    let s = Complex::new(0.0, w);
    let k1 = Complex::new(c1(), b1() * w);
    let k2 = Complex::new(c2, b2 * w);
    let delta = (s * s * M1 + k1 + k2) * (s * s * M2 + k2) - k2 * k2;
    let h = s * s * k1 * k2 / delta;
    h.norm_sqr() * s4.density(w)
}

/// Number of points of the density-evaluation grid.
pub const N_DENSITY: usize = 10_000;

/// The density grid: 10⁴ points linearly spaced on [0.01, 100] (rad/s, or rad/m for spatial spectra).
pub fn density_grid() -> Vec<f64> {
    (0..N_DENSITY)
        .map(|i| 0.01 + (100.0 - 0.01) * i as f64 / (N_DENSITY - 1) as f64)
        .collect()
}

/// One spectrum of every type, with the parameters `compare.py` uses for its vectorised formulas.
pub fn all_spectra() -> Vec<(&'static str, Arc<dyn Spectrum>)> {
    use stochvib::spectrum::two_pole_road::Form;
    use stochvib::spectrum::{
        BandWhiteParameters, Convention, ExpCosine, Exponential, Gaussian, IsoBound, IsoClass, PowerLaw,
        RationalSpectrum, Tabulated, TwoPoleRoad, ISO_BAND,
    };
    let t = Domain::Temporal;
    let tab_x: Vec<f64> = (0..20).map(|k| 10f64.powf(-1.0 + 3.0 * k as f64 / 19.0)).collect();
    let tab_v: Vec<f64> = tab_x.iter().map(|x| 1.0 / (1.0 + x * x)).collect();
    vec![
        (
            "exponential",
            Arc::new(Exponential::new(1.0, 2.0, t).unwrap()) as Arc<dyn Spectrum>,
        ),
        ("gaussian", Arc::new(Gaussian::new(1.0, 2.0, t).unwrap())),
        (
            "exp_cosine",
            Arc::new(
                ExpCosine {
                    variance: 1.0,
                    alpha: 1.0,
                    beta: 5.0,
                    domain: t,
                }
                .build()
                .unwrap(),
            ),
        ),
        (
            "gauss_cosine",
            Arc::new(
                GaussCosineParameters {
                    variance: 1.0,
                    alpha: 2.0,
                    beta: 5.0,
                    domain: t,
                }
                .build()
                .unwrap(),
            ),
        ),
        (
            "rational",
            Arc::new(RationalSpectrum::new(vec![1.0, 0.5], vec![1.0, 0.3, 0.02], t).unwrap()),
        ),
        (
            "band_white",
            Arc::new(
                BandWhiteParameters {
                    convention: Convention::TwoSidedAngular,
                    level: 0.1,
                    lo: 1.0,
                    hi: 50.0,
                    domain: t,
                }
                .build()
                .unwrap(),
            ),
        ),
        (
            "tabulated",
            Arc::new(Tabulated::new(Convention::TwoSidedAngular, tab_x, tab_v, t).unwrap()),
        ),
        (
            "iso8608_c",
            Arc::new(PowerLaw::iso8608(IsoClass::C, IsoBound::GeometricMean, Some(ISO_BAND)).unwrap()),
        ),
        (
            "two_pole_road",
            Arc::new(
                TwoPoleRoad {
                    dq: 0.035 * 0.035,
                    alpha: 0.3,
                    beta: 12.0,
                    form: Form::Consistent,
                }
                .build()
                .unwrap(),
            ),
        ),
        ("at_speed", road()),
    ]
}

/// Monte Carlo pipeline job: realizations, samples per realization, time step (s), seed.
pub const MC_REAL: usize = 1000;
/// Samples per realization, 2¹⁶.
pub const MC_N: usize = 1 << 16;
/// Time step, s.
pub const MC_DT: f64 = 0.01;
/// Seed of the batch (realization i uses `stream(MC_SEED, i)`).
pub const MC_SEED: u64 = 2024;
/// Confidence level of the Monte Carlo intervals.
pub const MC_CONFIDENCE: f64 = 0.95;

/// The Monte Carlo pipeline model (as `examples/stream_memory.rs`): SDOF ẍ + 2ζωẋ + ω²x = u, ω = 10 rad/s,
/// ζ = 0.05, output x (m), under the exponential input K(τ) = D e^{−α|τ|}, D = 1, α = 3 s⁻¹ (shaping
/// filter √(2Dα)/(s + α) of unit white noise).
pub fn mc_sdof() -> (stochvib::system::StateSpace, Excitation) {
    let ss = stochvib::system::StateSpace::oscillator(10.0, 0.05).unwrap();
    let exc = Excitation::single(mc_input(), 0.0).unwrap();
    (ss, exc)
}

/// The input process of the Monte Carlo job: K(τ) = e^{−3|τ|} (type 1, D = 1, α = 3 s⁻¹).
pub fn mc_input() -> Arc<dyn Spectrum> {
    Arc::new(stochvib::spectrum::Exponential::new(1.0, 3.0, Domain::Temporal).unwrap())
}

/// Across-realization statistics of the pipeline (what `simulate::run` reports per output): the time
/// averages m_i = (1/N)Σy_k and v_i = (1/N)Σy_k² of each realization; Student-t intervals on their means
/// (σ² interval = interval of mean v_i; σ interval = its square root).
#[derive(Debug, Clone, Copy)]
pub struct McStats {
    /// Mean of the m_i with its interval.
    pub mean: stochvib::estimate::Interval,
    /// Mean of the v_i (σ² estimate) with its interval.
    pub var: stochvib::estimate::Interval,
    /// σ interval (lower, estimate, upper).
    pub sigma: (f64, f64, f64),
}

/// Folds per-realization (m_i, v_i), in realization order, into [`McStats`].
pub fn mc_stats(mv: &[(f64, f64)]) -> McStats {
    use stochvib::estimate::mean_interval;
    let m: Vec<f64> = mv.iter().map(|p| p.0).collect();
    let v: Vec<f64> = mv.iter().map(|p| p.1).collect();
    let mean = mean_interval(&m, MC_CONFIDENCE).unwrap();
    let var = mean_interval(&v, MC_CONFIDENCE).unwrap();
    McStats {
        mean,
        var,
        sigma: (var.lower.max(0.0).sqrt(), var.estimate.sqrt(), var.upper.sqrt()),
    }
}

/// Time averages (m, v) of a record, as a run computes them (`simulate::TimeSums`: eight partial sums,
/// the same bits for any cut of the record into blocks).
#[inline]
pub fn time_moments(y: &[f64]) -> (f64, f64) {
    let mut sums = stochvib::simulate::TimeSums::new();
    sums.push(y);
    sums.averages()
}

/// The spectral route of `simulate::run` for [`mc_sdof`], with the library's parts: the input by
/// [`SpectralGenerator`](stochvib::simulate::SpectralGenerator) (Rayleigh amplitudes, the default), the
/// response by the exact first-order hold [`SampledSystem::respond`](stochvib::simulate::SampledSystem)
/// driven through the periodic input for `warmup` periods and one recorded period (periodic steady state).
pub struct McSpectral {
    /// Input generator (N = [`MC_N`], Δt = [`MC_DT`]).
    pub generator: stochvib::simulate::SpectralGenerator,
    /// The SDOF discretised once (FOH).
    pub sys: stochvib::simulate::SampledSystem,
    /// Warm-up periods (σ_min·w·NΔt ≥ 36, as the spectral route of `simulate::run` did before it computed the steady state in the frequency domain).
    pub warmup: usize,
    /// H_d(ω_j) of the sampled system on the generator's grid (`SampledSystem::grid_response`).
    pub gain: Vec<realfft::num_complex::Complex<f64>>,
}

/// Working memory of one [`McSpectral`] task.
pub struct McScratch {
    spec: stochvib::simulate::SpectralScratch,
    u: Vec<f64>,
    y: Vec<f64>,
    x: Vec<f64>,
}

impl McSpectral {
    /// Builds the generator and the sampled system for `n` samples.
    pub fn new(n: usize) -> McSpectral {
        use stochvib::simulate::{Amplitudes, SampledSystem, SpectralGenerator};
        let (ss, _) = mc_sdof();
        let generator = SpectralGenerator::new(mc_input().as_ref(), MC_DT, n, Amplitudes::Rayleigh).unwrap();
        let sys = SampledSystem::new(&ss, MC_DT).unwrap();
        let sigma_min =
            ss.a.complex_eigenvalues()
                .iter()
                .map(|l| -l.re)
                .fold(f64::INFINITY, f64::min);
        let warmup = (stochvib::simulate::run::WARMUP_DECAY / (sigma_min * n as f64 * MC_DT))
            .ceil()
            .max(1.0) as usize;
        let gain = sys.grid_response(n, 0, 0).unwrap();
        McSpectral {
            generator,
            sys,
            warmup,
            gain,
        }
    }
    /// Fresh working memory.
    pub fn scratch(&self) -> McScratch {
        let n = self.generator.len();
        McScratch {
            spec: self.generator.scratch(),
            u: vec![0.0; n + 1],
            y: vec![0.0; n + 1],
            x: vec![0.0; self.sys.dims().0],
        }
    }
    /// One realization: generate → respond (warm-up + recorded period) → (m, v).
    pub fn realization(&self, s: &mut McScratch, rng: &mut rand::rngs::Xoshiro256PlusPlus) -> (f64, f64) {
        let n = self.generator.len();
        self.generator.generate(rng, &mut s.spec, &mut s.u[..n]).unwrap();
        s.u[n] = s.u[0]; // the first-order hold of the last step ramps to the next period's first sample
        s.x.iter_mut().for_each(|v| *v = 0.0);
        for _ in 0..=self.warmup {
            self.sys.respond(&s.u, &mut s.x, &mut s.y).unwrap();
        }
        time_moments(&s.y[..n])
    }
    /// One realization of the same periodic steady state in one FFT: generate_filtered with H_d on the
    /// grid (no time stepping, no warm-up) → (m, v).
    pub fn realization_fft(&self, s: &mut McScratch, rng: &mut rand::rngs::Xoshiro256PlusPlus) -> (f64, f64) {
        let n = self.generator.len();
        self.generator
            .generate_filtered(rng, &mut s.spec, &self.gain, &mut s.y[..n])
            .unwrap();
        time_moments(&s.y[..n])
    }
    /// `r` realizations of [`MC_SEED`] on the current rayon pool (`run_batch`), then the statistics;
    /// `fft` selects [`realization_fft`](Self::realization_fft) instead of time stepping.
    pub fn batch(&self, r: usize, fft: bool) -> McStats {
        let shard = stochvib::simulate::run_batch(
            MC_SEED,
            0..r as u64,
            || self.scratch(),
            |s, _, rng| {
                if fft {
                    self.realization_fft(s, rng)
                } else {
                    self.realization(s, rng)
                }
            },
        );
        mc_stats(shard.results())
    }
}

/// The exact route for [`mc_sdof`]: the SDOF augmented with the input's shaping filter, discretised by
/// Van Loan (`augmented_response`), each realization started from the stationary state.
pub struct McExact {
    /// The augmented Gauss–Markov model (3 states).
    pub gm: stochvib::simulate::GaussMarkov,
    /// Samples per realization.
    pub n: usize,
}

impl McExact {
    /// Builds the model for `n` samples per realization.
    pub fn new(n: usize) -> McExact {
        let (ss, exc) = mc_sdof();
        McExact {
            gm: stochvib::simulate::augmented_response(&ss, &exc, &[0], MC_DT).unwrap(),
            n,
        }
    }
    /// `r` realizations of [`MC_SEED`] on the current rayon pool, then the statistics: as the exact route
    /// of `simulate::run`, [`LANES`](stochvib::simulate::LANES) consecutive realizations at a time in
    /// lockstep (`GaussMarkov::lanes`, blocks of [`EXACT_BLOCK`] steps; each lane has the bits of its
    /// realization alone), a short last group one at a time.
    pub fn batch(&self, r: usize) -> McStats {
        use stochvib::simulate::LANES;
        let nz = self.gm.n_states();
        let shard = stochvib::simulate::run_batch_groups(
            MC_SEED,
            0..r as u64,
            || (vec![0.0; nz], vec![0.0; self.n], vec![[0.0; LANES]; EXACT_BLOCK]),
            |(x, y, ys), group| {
                if group.end - group.start < LANES as u64 {
                    return Ok::<_, std::convert::Infallible>(
                        group
                            .map(|i| {
                                let mut rng = stochvib::simulate::stream(MC_SEED, i);
                                self.gm.initial_state(&mut rng, x);
                                self.gm.advance(x, &mut rng, y);
                                time_moments(y)
                            })
                            .collect(),
                    );
                }
                let mut lanes = self.gm.lanes(MC_SEED, group.start);
                let mut sums = stochvib::simulate::TimeSumLanes::new();
                let mut done = 0;
                while done < self.n {
                    let b = EXACT_BLOCK.min(self.n - done);
                    lanes.fill(&mut ys[..b]);
                    sums.push(ys[..b].iter().copied());
                    done += b;
                }
                Ok((0..LANES).map(|l| sums.lane(l).averages()).collect())
            },
        );
        let Ok(shard) = shard;
        mc_stats(shard.results())
    }
}

/// Steps per block of [`McExact::batch`]'s lockstep realizations (the exact route of `simulate::run` steps
/// in blocks as well).
pub const EXACT_BLOCK: usize = 4096;

/// The one-FFT route's floor: per realization of [`MC_SEED`], the N + 2 normals of its stream and one inverse
/// real FFT of length N (the route without its gains, response and sums); one thread. The plan is the
/// library's ([`stochvib::simulate::fft_plans`]): the machine code the route runs, not a second copy of
/// rustfft compiled into this crate.
pub struct OneFftFloor {
    fft: Arc<dyn realfft::ComplexToReal<f64>>,
    coef: Vec<realfft::num_complex::Complex<f64>>,
    out: Vec<f64>,
    scratch: Vec<realfft::num_complex::Complex<f64>>,
    normals: Vec<f64>,
}

impl OneFftFloor {
    /// The floor of realizations of `n` samples.
    pub fn new(n: usize) -> OneFftFloor {
        let fft = stochvib::simulate::fft_plans::inverse_real_fft(n);
        OneFftFloor {
            coef: fft.make_input_vec(),
            out: fft.make_output_vec(),
            scratch: fft.make_scratch_vec(),
            normals: vec![0.0; n + 2],
            fft,
        }
    }

    /// Realizations 0..r; returns a check value.
    pub fn run(&mut self, r: usize) -> f64 {
        let n = self.out.len();
        let mut acc = 0.0;
        for i in 0..r as u64 {
            stochvib::simulate::fill_standard_normal(&mut stochvib::simulate::stream(MC_SEED, i), &mut self.normals);
            for (c, p) in self.coef.iter_mut().zip(self.normals.chunks_exact(2)) {
                *c = realfft::num_complex::Complex::new(p[0], p[1]);
            }
            self.coef[0].im = 0.0;
            self.coef[n / 2].im = 0.0;
            self.fft
                .process_with_scratch(&mut self.coef, &mut self.out, &mut self.scratch)
                .unwrap();
            acc += self.out[1];
        }
        acc
    }
}

/// The exact route's floor: its normals alone (`draws` per realization of [`MC_SEED`]: one per state and
/// step, as `GaussMarkov::advance` draws them), drawn the way the route draws them: realizations 0..r in
/// groups of [`LANES`](stochvib::simulate::LANES) consecutive ones, side by side
/// (`fill_standard_normal_lanes`, `normals.len()` per lane at a time: the callers pass `LANE_DRAW_STEPS`
/// steps' worth, as the route draws them), a short last group one at a time
/// (`fill_standard_normal`); one thread; a check value.
pub fn exact_floor(normals: &mut [[f64; stochvib::simulate::LANES]], draws: usize, r: usize) -> f64 {
    use stochvib::simulate::{fill_standard_normal, fill_standard_normal_lanes, stream, NormalLanes, LANES};
    let mut acc = 0.0;
    let chunk = normals.len();
    let groups = r / LANES;
    for g in 0..groups {
        let mut lanes = NormalLanes::new(MC_SEED, (g * LANES) as u64);
        let mut done = 0;
        while done < draws {
            let b = chunk.min(draws - done);
            fill_standard_normal_lanes(&mut lanes, &mut normals[..b]);
            done += b;
        }
        acc += normals[0].iter().sum::<f64>();
    }
    let flat = normals.as_flattened_mut();
    for i in groups * LANES..r {
        let mut rng = stream(MC_SEED, i as u64);
        let mut done = 0;
        while done < draws {
            let b = flat.len().min(draws - done);
            fill_standard_normal(&mut rng, &mut flat[..b]);
            done += b;
        }
        acc += flat[0];
    }
    acc
}

/// The SDOF's impulse response h(kΔt)·√Δt, h(t) = e^{−ζωt} sin(ω_d t)/ω_d (ω = 10 rad/s, ζ = 0.05, Δt =
/// [`MC_DT`]) up to where its envelope falls below 10⁻⁴ of its start: the streamed route's kernel.
pub fn sdof_kernel() -> Vec<f64> {
    let (w, z, dt) = (10.0f64, 0.05f64, MC_DT);
    let wd = w * (1.0 - z * z).sqrt();
    let taps = ((1e4f64).ln() / (z * w) / dt).ceil() as usize;
    (0..taps)
        .map(|k| {
            let t = k as f64 * dt;
            (-z * w * t).exp() * (wd * t).sin() / wd * dt.sqrt()
        })
        .collect()
}

/// The streamed spectral route's job: per realization of [`MC_SEED`], [`sdof_kernel`] driven by white noise
/// through `simulate::FirSynthesis` (overlap-save, one forward and one inverse real FFT per segment), whole
/// segments covering `n` samples (a little more: 11 segments of 6350 = 69 850 samples for n = 2¹⁶), and the
/// time sums Σy, Σy² of every segment's output (`TimeSums`); one thread.
pub struct McStreamed {
    /// The synthesis of the one kernel.
    pub fir: stochvib::simulate::FirSynthesis,
    scratch: stochvib::simulate::FirScratch,
    segments: usize,
}

impl McStreamed {
    /// The job for realizations of (at least) `n` samples.
    pub fn new(n: usize) -> McStreamed {
        let fir = stochvib::simulate::FirSynthesis::from_taps(vec![vec![sdof_kernel()]]).expect("a valid kernel");
        McStreamed {
            scratch: fir.scratch(),
            segments: n.div_ceil(fir.hop()),
            fir,
        }
    }

    /// Realizations 0..r; returns a check value (the sum of their Σy² − (Σy)²/N).
    pub fn run(&mut self, r: usize) -> f64 {
        use stochvib::simulate::{stream, TimeSums};
        let mut acc = 0.0;
        for i in 0..r as u64 {
            let mut rng = stream(MC_SEED, i);
            self.fir.start(&mut rng, &mut self.scratch);
            let mut sums = TimeSums::new();
            for _ in 0..self.segments {
                self.fir
                    .next_segment(&mut rng, &mut self.scratch)
                    .expect("its own scratch");
                sums.push(self.fir.output(&self.scratch, 0));
            }
            let (s1, s2) = sums.totals();
            acc += s2 - s1 * s1 / (self.segments * self.fir.hop()) as f64;
        }
        acc
    }
}

/// The streamed route's floor: per realization of [`MC_SEED`], the normals [`McStreamed`] draws (taps − 1
/// to start, then one hop per segment) and one forward and one inverse real FFT of the segment length per
/// segment (the library's plans, [`stochvib::simulate::fft_plans`], as the route's); one thread.
pub struct StreamedFloor {
    fwd: Arc<dyn realfft::RealToComplex<f64>>,
    inv: Arc<dyn realfft::ComplexToReal<f64>>,
    buf: Vec<f64>,
    spec: Vec<realfft::num_complex::Complex<f64>>,
    back: Vec<f64>,
    scratch: Vec<realfft::num_complex::Complex<f64>>,
    taps: usize,
    segments: usize,
}

impl StreamedFloor {
    /// The floor of `job`.
    pub fn new(job: &McStreamed) -> StreamedFloor {
        let f = job.fir.fft_len();
        let (fwd, inv) = stochvib::simulate::fft_plans::real_fft_pair(f);
        StreamedFloor {
            buf: fwd.make_input_vec(),
            spec: fwd.make_output_vec(),
            back: inv.make_output_vec(),
            scratch: vec![Default::default(); fwd.get_scratch_len().max(inv.get_scratch_len())],
            taps: job.fir.taps(),
            segments: job.segments,
            fwd,
            inv,
        }
    }

    /// Realizations 0..r; returns a check value.
    pub fn run(&mut self, r: usize) -> f64 {
        use stochvib::simulate::{fill_standard_normal, stream};
        let (t, f) = (self.taps, self.buf.len());
        let mut acc = 0.0;
        for i in 0..r as u64 {
            let mut rng = stream(MC_SEED, i);
            fill_standard_normal(&mut rng, &mut self.buf[..t - 1]);
            for _ in 0..self.segments {
                fill_standard_normal(&mut rng, &mut self.buf[t - 1..]);
                self.fwd
                    .process_with_scratch(&mut self.buf, &mut self.spec, &mut self.scratch)
                    .unwrap();
                self.spec[0].im = 0.0;
                self.spec[f / 2].im = 0.0;
                self.inv
                    .process_with_scratch(&mut self.spec, &mut self.back, &mut self.scratch)
                    .unwrap();
                acc += self.back[t];
            }
        }
        acc
    }
}

/// CPU time of this process (user + sys), s.
pub fn cpu_seconds() -> f64 {
    let mut ts = libc::timespec { tv_sec: 0, tv_nsec: 0 };
    // SAFETY: a valid pointer to a timespec; CLOCK_PROCESS_CPUTIME_ID exists on Linux.
    unsafe { libc::clock_gettime(libc::CLOCK_PROCESS_CPUTIME_ID, &mut ts) };
    ts.tv_sec as f64 + ts.tv_nsec as f64 * 1e-9
}

/// One job of [`floor_rounds`]: its key and name, its best CPU and wall time over the rounds (s), its last
/// check value.
pub struct FloorTiming {
    /// A short key (`mc_pipeline_fft`, `mc_floor`, `mc_exact`, `mc_exact_floor`, `mc_streamed`,
    /// `mc_streamed_floor`).
    pub key: &'static str,
    /// What the job does.
    pub name: &'static str,
    /// The least CPU time of this process over the rounds, s.
    pub cpu_s: f64,
    /// The least wall time over the rounds, s.
    pub wall_s: f64,
    /// The job's check value.
    pub check: f64,
}

/// One job: key, name and a closure doing it once (returning a check value).
type FloorJob<'a> = (&'static str, &'static str, Box<dyn FnMut() -> f64 + 'a>);

/// The three Monte Carlo routes, each followed by its floor — the one-FFT route ([`McSpectral::batch`]) and
/// [`OneFftFloor`], the exact route ([`McExact::batch`]) and [`exact_floor`] (drawn as the route draws), the
/// streamed route ([`McStreamed`]) and [`StreamedFloor`] — on `r` realizations of `n` samples, one thread,
/// in `rounds` alternating rounds (a change of load hits both sides of a ratio alike); each job's best round.
pub fn floor_rounds(r: usize, n: usize, rounds: usize) -> Vec<FloorTiming> {
    use stochvib::simulate::{LANES, LANE_DRAW_STEPS};
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(1)
        .build()
        .expect("a pool of one thread");
    let pipe = McSpectral::new(n);
    let exact = McExact::new(n);
    let mut streamed = McStreamed::new(n);
    let mut streamed_floor = StreamedFloor::new(&streamed);
    let mut floor = OneFftFloor::new(n);
    let nz = exact.gm.n_states();
    let mut exact_normals = vec![[0.0; LANES]; LANE_DRAW_STEPS * nz];
    let mut jobs: Vec<FloorJob> = vec![
        (
            "mc_pipeline_fft",
            "one FFT route",
            Box::new(|| pool.install(|| pipe.batch(r, true)).var.estimate),
        ),
        (
            "mc_floor",
            "one FFT floor: N + 2 normals + 1 inverse real FFT",
            Box::new(|| floor.run(r)),
        ),
        (
            "mc_exact",
            "exact route",
            Box::new(|| pool.install(|| exact.batch(r)).var.estimate),
        ),
        (
            "mc_exact_floor",
            "exact floor: its normals (8 streams side by side)",
            Box::new(|| exact_floor(&mut exact_normals, nz * n, r)),
        ),
        (
            "mc_streamed",
            "streamed spectral route (FIR overlap-save + Σy, Σy²)",
            Box::new(|| streamed.run(r)),
        ),
        (
            "mc_streamed_floor",
            "streamed floor: its normals + forward and inverse real FFT per segment",
            Box::new(|| streamed_floor.run(r)),
        ),
    ];
    let mut best = vec![(f64::INFINITY, f64::INFINITY, 0.0); jobs.len()];
    for _ in 0..rounds {
        for (b, (_, _, job)) in best.iter_mut().zip(&mut jobs) {
            let (c0, w0) = (cpu_seconds(), std::time::Instant::now());
            let check = std::hint::black_box(job());
            let (c, w) = (cpu_seconds() - c0, w0.elapsed().as_secs_f64());
            *b = (b.0.min(c), b.1.min(w), check);
        }
    }
    jobs.iter()
        .zip(best)
        .map(|((key, name, _), (cpu_s, wall_s, check))| FloorTiming {
            key,
            name,
            cpu_s,
            wall_s,
            check,
        })
        .collect()
}
