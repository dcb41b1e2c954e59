//! Named tolerances of the test suite, in one place (test-only: not part of the library's API). Integration
//! tests use them through `mod common;`; unit tests, benches and examples include this file by path.
//!
//! Each constant says what it bounds and why the value is what it is. ε = `f64::EPSILON` = 2.2e-16; a
//! rounded operation errs by at most ε/2 relative. The constants are relative (to the magnitude of the
//! compared value) unless a test compares a value of order one absolutely.

// ---- rounding and exact methods, strictest first ----

/// A few rounded operations (a unit conversion, a convention round trip, one product or quotient, a sum of
/// a few exactly representable terms): each rounding is at most ε/2, so 4ε allows about eight of them.
pub const ULPS: f64 = 4.0 * f64::EPSILON;

/// A density evaluated on a grid by `density_into` (the vectorised `exp`/`ln` of `linalg::vmath`, each within
/// 2 ulp of libm, or a power by multiplications instead of `powf`) against its scalar oracle `density`: 2 ulp
/// from `exp`, 2 from `ln`, and up to 4 roundings placed differently by the two formulas (ε/2 each): 8ε
/// relative.
pub const SIMD_DENSITY: f64 = 8.0 * f64::EPSILON;

/// A tabulated density's law S_k (ω/ω_k)^p on a grid by `density_into` (`linalg::vpow::PowerFrom`, a
/// table-driven log₂/exp₂ of ω·fl(1/ω_k)) against its scalar oracle `density` (S_k·exp(p·ln(ω/ω_k)) by
/// libm), relative, for tables whose segments have |p| ≤ 8 and t = p ln(ω/ω_k) within |t| ≤ 1.5 (the tests
/// that use it check this of their tables, or show it in their docs). Ours: the power of the rounded ratio within
/// (1.5 + 0.5|p| + 2|t|/ln 2)ε (`vpow::POW_ERROR`), the ratio's rounding |p|ε/2, the product with S_k ε/2:
/// ≤ (2 + |p| + 2.9|t|)ε. The oracle: its ratio's rounding |p|ε/2, libm's ln and the product p·ln ε/2 each
/// amplified by |t|, its exp at most ε, the product with S_k ε/2: ≤ (1.5 + 0.5|p| + |t|)ε. In all
/// ≤ (3.5 + 1.5|p| + 3.9|t|)ε ≤ 21.4ε: 24ε.
pub const TABULATED_DENSITY: f64 = 24.0 * f64::EPSILON;

/// A short computation without cancellation (a closed form of a handful of operations, a quadrature rule
/// or polynomial sum of up to ~40 terms of one sign, a 16-point FFT, the factorisation of a quadratic,
/// the round-off floor of an integrator's error estimate, 25ε·∫|f|): n roundings of ≤ ε/2 add at worst
/// linearly, about 45ε for these sizes.
pub const ROUNDING: f64 = 1e-14;

/// Two FFT code paths of rustfft (AVX with FMA, SSE4.1, scalar) on one input, normwise: ‖y_a − y_b‖₂/‖y‖₂.
/// Each path errs by at most log₂n·η/(1 − log₂n·η) normwise with η = μ + γ₄(√2 + μ) ≈ 7ε for twiddle factors
/// accurate to μ ≈ ε (Higham, *Accuracy and Stability of Numerical Algorithms*, 2nd ed. 2002, Thm 24.2, for
/// Cooley–Tukey); two paths differ by at most twice that: 2·17·7ε ≈ 5.3e-14 for n ≤ 2¹⁷. Sizes with large
/// prime factors run Rader's or Bluestein's algorithm (an FFT of about 2n points and two twiddle products
/// more): 1e-13; measured ≤ 1.2e-15 over the sizes of `fft_paths.rs` (SSE4.1 and AVX paths against scalar, AMD EPYC).
pub const FFT_PATHS: f64 = 1e-13;

/// Closed form vs closed form (two algebraically equal expressions evaluated in f64): a few ulps, with
/// room for cancellation in sums of a handful of terms.
pub const EXACT: f64 = 1e-12;

/// An eigen-, Schur-, LU- or root-finding route on a small (n ≤ 10), well-conditioned matrix or
/// polynomial, against a closed form or a second such route (2×2 and 3×3 Lyapunov equations, oscillator
/// matrices, quadratic spectral factors, roots of unity, seeded random stable matrices of order ≤ 10):
/// backward-stable algorithms err by about κ·p(n)·ε with condition number κ ≤ 10² here; measured ≤ 1e-13 at
/// every use, so 1e-12 leaves a factor of ten.
pub const SMALL_DECOMPOSITION: f64 = 1e-12;

/// Normwise relative residual ‖A x − b‖ / (‖A‖‖x‖ + ‖b‖) of a backward-stable solver (Bartels–Stewart
/// for continuous and discrete Lyapunov equations up to n = 30, the O(n) sweep of a 10⁶-mass chain row by
/// row, spectral factorisation): O(n ε) with a modest constant whatever the conditioning. Measured: at most
/// 2.7e-13 (spectral factors of random stable polynomials of degree ≤ 4, 20 000 property-test cases); 1e-12.
pub const RESIDUAL: f64 = 1e-12;

/// Two exact (non-iterative) routes to the same quantity where the conditioning, not the operation count,
/// sets the error: a frequency response near a lightly damped resonance by Cramer's rule vs the system's
/// solve (the determinant cancels), the integral table Iₙ and spectral factors of random Hurwitz
/// polynomials in the property tests. Errors κ·ε with κ up to ~10³: measured ≤ 4.7e-13 (scraper with sprung
/// cab at ω = 9.4 rad/s) and ≤ 2.7e-13 over 20 000 property-test cases; 1e-11 leaves a factor of twenty.
pub const CONDITIONED: f64 = 1e-11;

/// Per unit of a condition number κ computed in the test: two backward-stable solves of an n ≤ 8 system
/// (an LU and a Schur back substitution) differ by ≤ 2·p(n)·κ·ε; p(n) ≤ 32 for these sizes, so 64ε.
pub const CONDITION_SCALED: f64 = 64.0 * f64::EPSILON;

/// Two exact routes on problems with condition numbers up to ~10⁵: the O(n) dynamic-stiffness sweep vs a
/// dense complex LU on the seeded random damped torsional chains (stiffness ratios up to 10³, light
/// damping, forcing frequencies near resonances). Measured: up to 1.1e-11; 1e-10.
pub const ILL_CONDITIONED: f64 = 1e-10;

/// Exact methods that go through an eigen- or Schur decomposition (Lyapunov, spectral factorisation,
/// integral table): conditioning of the randomised cases in the tests allows about 1e-9.
pub const FACTORISATION: f64 = 1e-9;

/// A double root of a polynomial (the spectral factor of (x − a)², two equal natural frequencies from a
/// discriminant that cancels): rounding the coefficients by ε moves a root of multiplicity two by about √ε
/// ≈ 1.5e-8 relative, so quantities that depend on it to first order agree to a few √ε; 1e-7 ≈ 7√ε.
pub const DOUBLE_ROOT: f64 = 1e-7;

/// Quantile of the χ² or Student t law by bisection to full precision on statrs's distribution functions
/// (regularised incomplete gamma and beta), against closed-form quantiles: the quantile inherits the
/// distribution function's relative error divided by x f(x)/F(x), measured ≤ 4.4e-15 for the tested
/// probabilities (1e-9 … 1 − 1e-8); 1e-9 leaves room for statrs's weaker regions (its own tests accept 1e-9
/// to 1e-13 depending on the argument).
pub const QUANTILE: f64 = 1e-9;

/// Variance of data with a large mean by two different one- or two-pass formulas (Welford's update and
/// its merge against the two-pass sum): every deviation x − mean carries the rounding of the data near the
/// mean, ulp(10⁶) ≈ 1.2e-10 on a spread σ ≈ 2.9, i.e. ≈ 4e-11 relative, partly averaging out over the sums;
/// measured 5.8e-12 for 100 values around 10⁶, so 1e-9 (σ/mean ≈ 3e-6) leaves two digits of margin.
pub const LARGE_MEAN_VARIANCE: f64 = 1e-9;

// ---- quadrature, Fourier and time-stepping ----

/// Closed form vs adaptive quadrature requested at relative 1e-10 (see
/// `stochvib::spectrum::numeric::REL_TOL`): the integrator's own error estimate
/// is usually far smaller; 1e-8 leaves two digits of margin. Also closed forms vs composite Simpson rules
/// whose h⁴ error term is below 1e-10 at each use (written out where they are used).
pub const QUADRATURE: f64 = 1e-8;

/// Closed form vs the oscillatory Fourier integral (Wynn-extrapolated tail), absolute, relative to the
/// variance K(0): the extrapolation stops at 1e-12 of the head's scale.
pub const FOURIER: f64 = 1e-7;

/// Fixed-step classical RK4 against an exact solution, relative to the response scale: with
/// ω_max·dt ≤ 0.01 the local error per step is ≈ (ω dt)⁵/120 ≈ 1e-12, so over ≤ 10⁴ steps the global
/// error stays near 1e-8; 1e-6 leaves two digits of margin.
pub const ODE_RK4: f64 = 1e-6;

// ---- agreement with printed values ----

/// Agreement with a value printed with 4 significant digits (in a source, or recomputed outside the crate
/// and quoted in the test's comment): rounding to n significant digits moves a value by at most half a unit
/// in the n-th digit, which is at most 5·10⁻ⁿ relative (the worst case, a leading digit of 1); the computed
/// value's own error is far smaller. Used as `rel(computed, printed) < PRINTED_4_DIGITS`.
pub const PRINTED_4_DIGITS: f64 = 5e-4;

/// As [`PRINTED_4_DIGITS`], for a value printed with 5 significant digits.
pub const PRINTED_5_DIGITS: f64 = 5e-5;

/// As [`PRINTED_4_DIGITS`], for a value printed with 6 significant digits.
pub const PRINTED_6_DIGITS: f64 = 5e-6;

/// As [`PRINTED_4_DIGITS`], for a value printed with 7 significant digits.
pub const PRINTED_7_DIGITS: f64 = 5e-7;

/// As [`PRINTED_4_DIGITS`], for a value printed with 8 significant digits.
pub const PRINTED_8_DIGITS: f64 = 5e-8;

// ---- discretisation, limits and statistical estimators (sanity bounds with their derivation) ----

/// Quasi-static limit of a base-excited system driven at a speed v where the road's temporal corner βv
/// lies far below the natural frequencies: the relative corrections are O((βv/ω)²). Scraper with sprung
/// cab (Sukharev (2012) 8.7) at v = 0.01 m/s: βv = 0.12 rad/s, lowest ω ≈ 9.5 rad/s, (βv/ω)² ≈ 1.6e-4;
/// measured 5e-6 for σ → √D_q and 6.2e-4 for the v^{3/2} law of σ_ẍ (the correction's constant ≈ 4); 1e-3.
pub const QUASI_STATIC: f64 = 1e-3;

/// Variance of the spectral generator's grid (Δt = 0.01 s, N = 2048) against its Poisson-summation value
/// D + 2Σ K(mT) − tail, relative to D: the tail is the integral 2∫_{ω_N}^∞ S dω up to the Euler–Maclaurin
/// term O(Δω² S′(ω_N)) ≈ 1e-9 (Δω = 0.31 rad/s, ω_N = 314 rad/s, S ∝ ω⁻² there); 1e-7 leaves two digits.
pub const POISSON_GRID_VARIANCE: f64 = 1e-7;

/// Exact mean of a Welch estimate (the window-smoothed density of the sampled process) against the analytic
/// density, relative: window smoothing ≈ (S″/2S)·4π²/(3L²) ≤ 0.8 % at ω → 0 (type 1, α = 1 s⁻¹, segments of
/// L = 40.96 s) plus aliasing ≈ (α² + ω²)[1/(2π/Δt − ω)² + 1/(2π/Δt + ω)²] ≤ 1.2e-3 up to ω = 15.3 rad/s
/// (Δt = 0.01 s): at most 0.92 %, bounded by 1 %.
pub const WELCH_WINDOW_BIAS: f64 = 1e-2;

/// Discrete variance of the spectral route (the input spectrum on the FFT grid, truncated at Nyquist,
/// piecewise constant between bins) against the analytic variance, relative, for the catalogue scenarios
/// simulated in `tests/mc_pipeline.rs` whose grids cover the input band: a sanity bound of 5 % (measured
/// with those grids: below 1 %, at most 0.94 % for the quarter car's body displacement).
pub const SPECTRAL_GRID_BIAS: f64 = 5e-2;

/// Peak of the N(M, σ) curve of a run's histogram picture (301 points over [min(M − 4σ, samples),
/// max(M + 4σ, samples)]) against 1/(σ√(2π)): the nearest grid point lies within half a step Δ/2 of M,
/// where the curve has dropped by at most ½(Δ/2σ)²; with Δ = 8σ/300 (samples inside M ± 4σ) that is 9e-5,
/// and the range of the 40 000 samples of the conveyor-idler run would have to exceed 27σ for the drop to
/// reach 1e-3.
pub const GAUSSIAN_CURVE_PEAK: f64 = 1e-3;

/// Model correlation of a run picture (FFT sum of the output density over |ω| ≤ π/Δt on a grid 8× finer than
/// the record) against the exact autocovariance of the discretised augmented system: the density beyond
/// Nyquist, which a sampled record aliases but the sum leaves out, dominates the difference. Conveyor idler at
/// Δt = 0.01 s: ~1e-8 relative for the displacement (density ∝ ω⁻⁶ beyond ω₀ ≈ 25 rad/s) and 5e-5 for the
/// velocity (∝ ω⁻⁴: tail ∝ (ω₀/ω_N)³ of the variance).
pub const PLOT_MODEL_CORRELATION: f64 = 2e-4;

/// A fast exact value (integral table or residue sum) that passed its error check, against the Lyapunov
/// reference: the checks admit an estimated relative error up to `INTEGRAL_TABLE_MAX_ERROR` = 1e-9 and the
/// estimates are order-of-magnitude bounds; the Lyapunov side of stiff cascades (poles from 0.05 to
/// 2400 rad/s) adds its own. Measured ≤ 2.1e-9 (the overdamped corner of the seat grid); 1e-8 leaves ×5.
pub const CONDITION_CHECKED: f64 = 1e-8;

/// The discrete variance of a spectral run planned with one Schur form of Φ for every FFT bin
/// (`planned_variances`) against the run's own LU solve per bin (`sigma_discrete`), relative in σ: both are
/// backward stable, but at Δt = 1 ms the low bins (a road band from 0.1 Hz) sit where |z − λ(Φ)| ≈ 10⁻³, and a
/// suspension travel's transfer cancels as ω² below the body mode, so rounding is amplified by up to ~10⁵.
/// Measured on the half car with a Wk axis (Δt = 1 ms): 4.6e-11 (pitch) to 3.4e-9 (front travel); 1e-8
/// leaves ×3 and is five orders below the 10⁻⁴…10⁻² bias targets the planned variance serves.
pub const SCHUR_GRID_VARIANCE: f64 = 1e-8;

/// A parameter study's numeric path on closed-form transfer polynomials (the integral table on Δ(s) and
/// N_i(s) written in the model's parameters, each value a dot product with the table's linear functional)
/// against the general path (the table on Faddeev–LeVerrier polynomials of the state space, or Lyapunov
/// where a check fails): each side is within `CONDITION_CHECKED` of the Lyapunov reference, so they may
/// differ by the sum, 2·CONDITION_CHECKED. Measured on the scraper grids of tests/fast_sweep.rs: ≤ 2.5e-9 at
/// every damped point; 1.0e-8 at an undamped cab mount (ζ₂ = 0, a 20 kg cab at 0.19 Hz: σ² ≈ 4e4 m², stable
/// only through the tyre damping acting on a cab that hardly moves m₁), where the two sides sit at −5e-9
/// and +3e-9 of Lyapunov: the value itself is that sensitive to the rounding of the coefficients.
pub const TRANSFER_POLYNOMIALS: f64 = 2.0 * CONDITION_CHECKED;

/// The steady-state amplitude of a replayed sinusoidal profile (first-order hold of the samples, an
/// input derivative by the central difference) against |H(iω)|·A: with p samples per period the linear
/// interpolation scales the fundamental by (sin(π/p)/(π/p))² ≈ 1 − (π/p)²/3 and the central difference the
/// derivative by sin(2π/p)/(2π/p) ≈ 1 − (2π/p)²/6; at p = 200 these are 8.2e-5 and 1.6e-4, and a residual
/// transient after a skip of 14 decay times is below 1e-6. 1e-3 leaves a factor of five.
pub const REPLAY_SINE_AMPLITUDE: f64 = 1e-3;

// ---- nonlinear elements and their three routes ----

/// Route 1 (statistical linearization) against the fixed point of its own equations solved another way (a
/// root of 3εσ⁴ + σ² − σ₀² = 0, a scalar bisection): the iteration stops when no σ changes by more than
/// 1e-10 relative between iterations; under-relaxed by ½ with a contraction factor ≤ 0.9 the distance left to
/// the fixed point is at most ~10 times the last change, 1e-9 in σ, 2e-9 in σ²; 1e-8 leaves a factor of five.
pub const ROUTE1_ITERATION: f64 = 1e-8;

/// A trapezoid rule written in a test, on pieces whose ends are the integrand's kinks (so each piece is
/// smooth) with steps of σ/2000 over μ ± 12σ: the error per piece is ≈ h²/12·∫|f″| ≈ 2e-8 of the integral
/// for the Gaussian-weighted piecewise polynomials of the element laws (measured ≤ 3e-9); 1e-7.
pub const TRAPEZOID_PIECEWISE: f64 = 1e-7;

/// A stop of finite contact stiffness against the rigid (perfectly elastic) wall it tends to: the exact
/// variance converges as κ^{-1/2} (κ = k_c/k); at κ = 10⁶ and clearance d = σ₀ the gap is 6.3e-4 of σ₀² (the
/// closed forms of both, computed in tests/suite/nonlinear_routes.rs); 1e-3.
pub const RIGID_STOP: f64 = 1e-3;

/// The Gaussian closure's modelling error in the mean shift of an asymmetric damper (jacking): route 1's
/// E[F_d] assumes a Gaussian damper velocity, whose actual law is slightly non-Gaussian; seeded Monte Carlo
/// puts the exact mean 0.3 % (SDOF, c_r/c_c = 3) to 1 % (quarter car) from the closed form; 2 %.
pub const JACKING_CLOSURE: f64 = 2e-2;

/// A locked suspension's mode against √(k_t/(m_s + m_u)): the tyre contact's equivalent stiffness (about
/// 1 % of k_t at the catalogue quarter car's lift-off probability) and the stop's finite equivalent stiffness
/// move it by under 0.6 %; 1 %.
pub const LOCKED_MODE: f64 = 1e-2;

/// The quarter car with stops at 0.01 m/s against its quasi-static limit (the car follows the road: body
/// acceleration = road acceleration, tyre force = (m_s + m_u)·road acceleration): the neglected terms are of
/// relative order c·(ω₂/ω_b)² with the band's top ω₂ = 2π·0.01·2.83 = 0.178 rad/s and the body mode ω_b ≈
/// 7.7 rad/s, 5.3·10⁻⁴ times a constant of a few (4 for the scraper of [`QUASI_STATIC`]); measured 6.3·10⁻⁴
/// and 5.7·10⁻⁴; 3·10⁻³.
pub const CRAWL_QUASI_STATIC: f64 = 3e-3;

/// Observed order of the splitting integrator from the error envelope (the worst case over ten neighbouring
/// step counts, so that where the contact falls within a step averages out) at n and 8n steps per period:
/// second order gives log₂-ratios near 2 per halving; a kink in the force can make single steps erratic, so
/// the test requires at least 1.8 per halving on average (a first-order scheme would give 1).
pub const SPLITTING_MIN_ORDER: f64 = 1.8;

/// The false-failure probability of one statistical assertion of the route-2 tests: their intervals are
/// Student-t intervals across realizations at confidence 1 − MC_FALSE_FAILURE; with at most five such
/// assertions a test fails falsely with probability ≤ 10⁻⁶.
pub const MC_FALSE_FAILURE: f64 = 2e-7;

/// Up-crossings counted on the samples of a path miss the crossings that happen and reverse within one
/// step: an independent seeded computation (BAOAB, a two-sided stop at d = σ₀, κ = 100) measured the
/// sampled contact rate within 0.3 % of the exact one at h·ω_c = 0.6 and 0.3, +3 % only at h·ω_c = 1.2
/// (ω_c the contact frequency); the tests take h·ω_c ≤ 0.35, where 2 % leaves a margin.
pub const SAMPLED_CROSSINGS: f64 = 2e-2;

/// Three printed digits of a table (ISO 2631-1:1997 Table 3 prints |W|×1000 to the unit): the rounding of
/// the last printed digit, relative, on top of the half unit.
pub const PRINTED_3_DIGITS: f64 = 5e-4;

/// Our own tolerance of the digital ISO 8041 weighting (bilinear sections prewarped at their poles) at
/// f_s = 1 kHz over the one-third-octave centres 0.5–80 Hz, dB. The same design computed independently
/// (scipy) errs by at most 0.12 dB, at 79.4 Hz, where the 100 Hz band limit nears the Nyquist frequency;
/// the projection of a 2 s steady sine adds O(1/n) ≈ 1e-4. ISO 8041 allows about ±1 dB in the main range.
pub const ISO8041_OWN_DB: f64 = 0.15;

/// Our own tolerance of the digital weighting's phase against the analytic phase at the same centres,
/// degrees: the bilinear frequency warping shifts the phase most at the top band (measured ≈ 1.2° at
/// 79.4 Hz); 2° leaves a margin.
pub const ISO8041_OWN_PHASE_DEG: f64 = 2.0;

/// Closed-form exposure values of a sinusoidal record through the digital weighting (a_w, VDV, MTVV, A(8),
/// MSDV): the filter starts at rest, so its start-up transient (the 0.4 Hz high pass decays as
/// e^{−1.78 t}; Wf's 0.08 Hz one as e^{−0.36 t}) perturbs the first seconds of a 120 s (800 s) record;
/// with the digital error at 2–4 Hz (≤ 0.01 dB ≈ 1e-3) 1 % bounds both.
pub const RECORD_SINE_TRANSIENT: f64 = 1e-2;

/// A WAV float sample is an f32: its rounding, relative to full scale (2⁻²⁴ of a value ≤ 1, doubled).
pub const WAV_FLOAT32: f64 = 1.2e-7;

/// Miner damage of constant-amplitude blocks counted by rainflow: at each of the two block junctions up to
/// two half cycles take a range spanning both blocks (≤ 150 MPa in place of 200 or 100), each at most
/// 1e-5 of damage against D = 0.0141: ≤ 4·1e-5/0.0141 = 2.8e-3; 3e-3.
pub const MINER_BLOCK_BOUNDARY: f64 = 3e-3;

/// The expected IRI by quadrature against an independent quadrature (scipy, printed to 7 digits); the
/// moving average's sinc² makes the integrand oscillate, which adaptive quadrature resolves to ≈ 1e-8.
pub const IRI_EXPECTED: f64 = 1e-5;

/// The digital weighting's |H|² against the analytic |W|² over 1–20 Hz at f_s = 1 kHz, relative: the same
/// design computed independently (scipy: each analog section by the bilinear transform prewarped at its pole,
/// `freqz` on 2000 frequencies) differs in magnitude by at most 0.0056 dB (Wk) and 0.0105 dB (Wd) there,
/// 0.021 dB = 0.49 % in |W|²; 0.6 %.
pub const NOISE_WEIGHTING_REALISATION: f64 = 6e-3;

/// Maxima of a sinusoidal record through a weighting started at rest (peak, crest factor, MTVV): the start-up
/// transient overshoots the steady amplitude — by 2.6 % for Wk at 4 Hz (scipy: the analog weighting by the
/// bilinear transform, started at rest, 120 s at 1 kHz); 4 % leaves a margin. Upper bound only.
pub const RECORD_START_OVERSHOOT: f64 = 4e-2;

/// The running r.m.s., VDV and MTVV of sampled sines and bursts (10 kHz, each sample held over its step)
/// against their continuous closed forms: the rectangle rule is exact for sin² and sin⁴ over whole periods,
/// the hold shifts the exponential form by O((ωdt)²) < 1e-5 and the window position of the linear form by
/// O(dt²); the closed forms are printed to 6 digits (5e-7). 1e-4.
pub const RUNNING_RMS_SAMPLED: f64 = 1e-4;

/// The exact route of a time-invariant system (every step one Van Loan transition, P ← ΦPΦᵀ + Q_d) against a
/// closed form (Caughey–Stumpf, a first-order system from rest): the transitions are exact, the error is the
/// rounding of the Padé exponential (≈ 1e-15 relative per step) accumulated over up to ~2000 steps with
/// the slight shift of the grid by the reuse of one transition for steps equal within 1e-12; measured ≤ 3e-12
/// at every stored time; 1e-10 leaves a factor of thirty.
pub const EXACT_TRANSITIONS: f64 = 1e-10;

/// The exact route with time-varying coefficients (midpoint transitions with step doubling and Richardson
/// extrapolation, local tolerance rel_tol = 1e-9 per step) against a closed form: the accumulated error is
/// bounded by the sum of the local estimates the route reports, which stays below 1e-7 over the ramps of
/// the tests (a few hundred steps); 1e-7.
pub const ADAPTIVE_ROUTE: f64 = 1e-7;

/// The exact route's accumulated error estimate (relative to the largest variance of each state over the
/// window) after a start from rest with time-varying coefficients: at most the local tolerance rel_tol = 1e-9
/// per step times the steps (measured: 1.1e-6 over the ≈ 10³ steps of an amplitude ramp, 1.6e-5 over the
/// 2.3·10⁴ steps of the winding hoist); 1e-4 leaves a factor of six. An estimate relative to each step's own
/// variance reports O(0.1) there.
pub const ERROR_ESTIMATE_FROM_REST: f64 = 1e-4;

/// A variance that is zero by a cancellation (the roll of a symmetric body on one track) as the exact route
/// computes it, as a σ relative to the σ the same state has without the cancellation: the variance is a sum
/// of terms of that size that cancel, with a rounding error of a few ε of them, so σ/σ_scale ≈ √(few ε)
/// ≈ 10⁻⁷ at most; 10⁻⁶ leaves a factor of ten (a real coupling of the state would give O(1)).
pub const ZERO_BY_CANCELLATION: f64 = 1e-6;

/// Coulomb friction with a weak spring against the exact Laplace law of its spring-free limit (σ_v and the
/// kurtosis 6, `route2_coulomb_friction_matches_the_spring_free_laplace_law`): the spring's slow force
/// ω²x biases the velocity's law by α = ω²x/F_c, which raises σ_v by 2.5E[α²] and the kurtosis by
/// 4E[α²] to first order in the quasi-static (adiabatic) expansion, E[α²] = 2.5D²ω²/F_c⁴ = 3.1e-3 in the
/// test: 0.8 % and 1.3 %; the corrections to the expansion are of the same order in ω² but not bounded
/// here, so three times the larger: 3 %, an estimate, not a bound.
pub const COULOMB_SPRING_FREE: f64 = 0.03;

/// A tyre that cannot pull changes the rare lift-offs of a linear quarter car only while they last: over an
/// excursion of the tyre deflection beyond the level u = L/σ_F (L the static load, σ_F the linear σ of the
/// dynamic tyre force) the missing pull k_t(x − δ) is of order σ_F/u (the mean overshoot of a Gaussian
/// process beyond a high level) against the restoring force of order uσ_F that shapes the excursion, so the
/// excursion's curvature changes by about 1/u², its duration by about 1/(2u²), the fraction of time lifted
/// by about 1/u² and the entries (decided before each lift-off, changed only through the next one) by
/// less: 11 % at u = 3, an order-of-magnitude argument, not a bound: twice that, relative.
pub const RARE_LIFT_OFF: f64 = 0.25;

// ---- optimisation (COBYLA, src/optimize) ----

/// The location of an interior optimum found by COBYLA against its closed form. Near a smooth minimum
/// f(x*) + ½f''δ², so an objective known to relative rounding ε_f ≈ 1e-15 locates x* only to
/// δ/x* ≈ √(2ε_f f/(f''x*²)) ≈ 3e-8 for the problems here, and COBYLA stops when its trust region has
/// shrunk to ρ_end = 1e-9 of the range, a few ρ from the minimum of its linear models. Measured: 5.0e-8
/// (quarter-car c_opt and the margin of the inactive constraint 8.3e-8), 2.6e-9 (ζ = ½), 3.2e-9 to 4.2e-8
/// (Warburton f, ζ); 1e-6. The objective's value there is within (1e-6)² = 1e-12 of its minimum (measured
/// 1.6e-13).
pub const OPTIMUM_INTERIOR: f64 = 1e-6;

/// An optimum on an active constraint or a bound against its closed form: COBYLA linearises the constraint
/// and meets it to about ρ_end = 1e-9 of the range; the value at a bound is exact up to the rounding of
/// the model. Measured: 7.9e-10 (c* on 3σ_travel = 40 mm), 3.9e-10 (3σ_travel there), 1.3e-12 (at a bound);
/// 1e-8.
pub const OPTIMUM_ON_CONSTRAINT: f64 = 1e-8;

/// A σ from the optimiser's affine model of the state space against the same σ from the scenario reader's
/// model: the matrices agree to the rounding of their entries (the model is called affine only when they do
/// within 1e-12 of each matrix's largest entry), and σ² = h P hᵀ of a 4-state Lyapunov solution amplifies a
/// relative perturbation of the matrices by its condition (≈ 10² for the quarter car's spread of
/// stiffnesses and masses); 1e-10.
pub const AFFINE_MODEL: f64 = 1e-10;

/// `stochvib sweep --verdicts` against `stochvib analyze --json` of the same scenario written by hand: the
/// verdicts run the same code on the same matrices (equal bit for bit); σ is the exact route of the sweep
/// evaluator against the exact column of `analyze` (integral table or Lyapunov on the same model, a few
/// hundred roundings); 1e-12.
pub const SWEEP_AGAINST_ANALYZE: f64 = 1e-12;

/// A class of EN ISO 7096 against its published r.m.s. target: the targets are printed to two decimals (half a
/// unit of the last digit is ≤ 0.52 % of 0.96 m/s²) and the toolbox that publishes them measures its own
/// signals against its own densities within 0.4 %; 5e-3 (measured: ≤ 3.9e-3, EM6).
pub const ISO7096_PRINTED_TARGET: f64 = 5e-3;

/// The Lyapunov route of a weighted output under an input of high order (a seat-test class: an 8-state
/// Butterworth pair as the input's shaping filter, 8 states of Wk, the model's) against an independent
/// integral: the filter's polynomial coefficients span nine decades, and the augmented Lyapunov solution keeps
/// about seven digits (measured: 2.0e-7 on EM1); 1e-6.
pub const HIGH_ORDER_INPUT_LYAPUNOV: f64 = 1e-6;

/// An analytic sensitivity of a σ against its closed-form derivative. The Lyapunov sensitivity is exact for
/// the derivative of the model's matrices, which are differenced centrally with a step 10⁻⁵ of the value:
/// exact for the damping (A is affine in c) up to the rounding of the difference, ε·|c|/δ ≈ 1e-11, plus the
/// solves' relative accuracy ≈ 1e-13; 1e-8.
pub const GRADIENT_CLOSED_FORM: f64 = 1e-8;

/// An analytic sensitivity against a central finite difference of the evaluated σ with step h = 10⁻⁴x: the
/// difference's truncation |σ'''|h²/(6|σ'|) ≈ (h/x)² = 1e-8 for these smooth, rational-in-x variances, its
/// rounding ε·σ/(h·σ') ≈ 1e-12; 1e-6.
pub const GRADIENT_FINITE_DIFFERENCE: f64 = 1e-6;

/// The mean of Welch estimates at route 2's segment length against the exact mean of the estimate
/// (`Welch::expected_all` of the known autocovariance), summed over the interior bins, relative: the sum is a
/// windowed energy whose relative standard deviation per segment is √(2·Σρ²·Σw⁴M/(Σw²)²/M) ≈ 0.085 for an
/// AR(1) of coefficient ½ (Σρ² = 5/3, Hann's 35/18, M = 900), over ≈ 256 × 14 effective segments 1.4e-3;
/// 1e-2 is 7 standard deviations (false failure < 10⁻¹¹) and is exceeded by a normalisation off by the
/// ratio of version 1's to version 2's segment, 922/900 = 1.024.
pub const WELCH_SEGMENT_NORMALISATION: f64 = 1e-2;
