//! Statistical estimators for Monte Carlo results, each with a confidence interval to compare with the
//! analytic value ([`Interval::covers`], [`Comparison`]).
//!
//! * [`interval`]: the one interval type of the crate, [`Interval`], and [`Comparison`].
//! * [`moments`]: mean (Student-t), variance and σ (χ²) across independent realizations; streaming
//!   [`RunningMoments`] (Welford).
//! * [`welch`]: Welch density estimate (Hann, 50 % overlap) in the canonical two-sided angular convention,
//!   χ² intervals with Welch's equivalent degrees of freedom.
//! * [`correlation`]: textbook (8.11) across-realization correlation K̂(t₁, t₂) with an exact interval, and
//!   the time-average K̂(τ) of one record.

pub mod correlation;
pub mod cross_spectrum;
pub mod interval;
pub mod moments;
pub mod welch;

pub use correlation::{ensemble_correlation, time_correlation};
pub use cross_spectrum::{cross_spectrum, CrossSpectrum};
pub use interval::{Comparison, Interval};
pub use moments::{
    chi_squared_quantile, mean_interval, poisson_rate_interval, std_interval, student_t_quantile, variance_interval,
    variance_interval_known_mean, ChiSquaredInterval, RunningMoments, VarianceEstimate,
};
pub use welch::{Welch, WelchEstimate, WelchScratch, WelchStream, WelchSums};
