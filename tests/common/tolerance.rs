//! Named tolerances of the test suite, in one place (test-only: not part of the library's API). Integration
//! tests use them through `mod common;`; unit tests, benches and examples include this file by path.
//!
//! Each constant says what it bounds and why the value is what it is.

/// Closed form vs closed form (two algebraically equal expressions evaluated in f64): a few ulps, with
/// room for cancellation in sums of a handful of terms.
pub const EXACT: f64 = 1e-12;

/// Closed form vs adaptive quadrature requested at relative 1e-10 (see
/// `stochvib::spectrum::numeric::REL_TOL`): the integrator's own error estimate
/// is usually far smaller; 1e-8 leaves two digits of margin.
pub const QUADRATURE: f64 = 1e-8;

/// Closed form vs the oscillatory Fourier integral (Wynn-extrapolated tail), absolute, relative to the
/// variance K(0): the extrapolation stops at 1e-12 of the head's scale.
pub const FOURIER: f64 = 1e-7;

/// Exact methods that go through an eigen- or Schur decomposition (Lyapunov, spectral factorisation,
/// integral table): conditioning of the randomised cases in the tests allows about 1e-9.
pub const FACTORISATION: f64 = 1e-9;

/// Fixed-step classical RK4 against an exact solution, relative to the response scale: with
/// ω_max·dt ≤ 0.01 the local error per step is ≈ (ω dt)⁵/120 ≈ 1e-12, so over ≤ 10⁴ steps the global
/// error stays near 1e-8; 1e-6 leaves two digits of margin.
pub const ODE_RK4: f64 = 1e-6;

/// Model correlation of a run picture (FFT sum of the output density over |ω| ≤ π/Δt on a grid 8× finer than
/// the record) against the exact autocovariance of the discretised augmented system: the density beyond
/// Nyquist, which a sampled record aliases but the sum leaves out, dominates the difference. Conveyor idler at
/// Δt = 0.01 s: ~1e-8 relative for the displacement (density ∝ ω⁻⁶ beyond ω₀ ≈ 25 rad/s) and 5e-5 for the
/// velocity (∝ ω⁻⁴: tail ∝ (ω₀/ω_N)³ of the variance).
pub const PLOT_MODEL_CORRELATION: f64 = 2e-4;
