//! Numerical linear algebra for stochastic vibration analysis.
//!
//! * [`lyapunov`] — continuous and discrete Lyapunov equations (state covariance of a linear system
//!   driven by white noise), by the Bartels–Stewart real-Schur method, with dense Kronecker oracles.
//! * [`integral_table`] — the closed-form integral table Iₙ = ∫|Hₙ(ω)|² dω of James, Nichols &
//!   Phillips / Newland (Appendix 1) for rational transfer functions, exact for any order.
//! * [`small_lyapunov`] — the continuous Lyapunov equation of a system of at most 8 states by one LU of
//!   its vectorised symmetric form, reused for many right-hand sides (value and sensitivities).
//! * [`expm`](mod@expm) — the matrix exponential with overflow and shape checks.
//! * [`transfer`] — numerator and denominator of a state-space transfer function in a frequency-scaled
//!   variable (stiff systems keep their digits).
//! * [`vmath`] — vectorised `exp` and `ln` with run-time CPU dispatch (AVX-512, AVX2, SSE2), for grids.
//! * [`poly`] — real polynomials with ascending coefficients: evaluation, products, roots, the Hurwitz
//!   test and spectral factorisation of non-negative polynomials in ω².
//!
//! Everything works in `f64` with [`nalgebra`] dense matrices; bad input is reported as
//! [`Error`](crate::Error), never by a panic.

pub mod expm;
pub mod integral_table;
pub mod lyapunov;
pub mod poly;
pub mod shifted_lu;
pub mod small_lyapunov;
pub mod transfer;
pub mod vmath;
pub mod vpow;

pub use expm::expm;
pub use integral_table::{h2_integral, integral_closed_form, integral_i_n};
pub use lyapunov::{
    is_stable, solve_continuous_lyapunov, solve_continuous_lyapunov_dense, solve_discrete_lyapunov,
    solve_discrete_lyapunov_dense, spectral_abscissa, spectral_radius, LyapunovSolver,
};
pub use poly::{is_hurwitz, spectral_factor};
pub use small_lyapunov::{SmallLyapunov, SMALL_LYAPUNOV_MAX_CONDITION, SMALL_LYAPUNOV_MAX_STATES};
