//! Named tolerances, in one place, used by the test-suite and by the reports' agreement flags.
//!
//! Each constant says what it bounds and why the value is what it is.

/// Closed form vs closed form (two algebraically equal expressions evaluated in f64): a few ulps, with
/// room for cancellation in sums of a handful of terms.
pub const EXACT: f64 = 1e-12;

/// Closed form vs adaptive quadrature requested at relative 1e-10 (see
/// [`spectrum::numeric::REL_TOL`](crate::spectrum::numeric::REL_TOL)): the integrator's own error estimate
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
