//! Response statistics of linear systems under stationary random inputs: mean, variance three ways,
//! band variance, spectral moments, crossing rates, peaks.
//!
//! # Formula
//! For inputs u with cross-spectral matrix S_u(ω) (m × m, two-sided angular) and a system H(iω):
//! ```text
//! S_y(ω) = H(iω) S_u(ω) H(iω)ᴴ,      D_y = ∫ S_y dω,      λ_k = ∫ |ω|^k S_y dω,      M_y = H(0) M_u
//! ```

mod continued;
mod cumulative;
mod delayed;
mod delayed_quadrature;
mod density;
mod exact_evaluator;
mod excitation;
mod outcome;
mod sources;
mod statistics;
mod variance;

pub use continued::{continue_excitation, Continued, ContinuedSource};
pub use cumulative::cumulative_variance;
pub use delayed::{delayed_augmented_system, variance_lyapunov_delayed, DelayedAugmentedSystem, DelayedCovariance};
pub use delayed_quadrature::{
    moments_oscillatory, spectral_moment_oscillatory, variance_oscillatory, OscillatoryMoments,
};
pub use density::OutputDensity;
pub use exact_evaluator::ExactEvaluator;
pub(crate) use exact_evaluator::{lyapunov_point, Leverrier, TransferBuilder, TransferPolynomials};
pub use excitation::Excitation;
pub use outcome::Outcome;
pub use sources::{InputMap, Source};
pub use statistics::{
    analyze_output, analyze_output_with, PointStatistics, ResponseStatistics, VarianceMethod, VarianceValue,
    TABLE_AGREEMENT,
};
pub use variance::{augmented_system, AugmentedSystem};
pub use variance::{
    band_variance, band_variance_with, output_density, output_high_frequency, output_low_frequency,
    spectral_moment_quadrature, spectral_moment_quadrature_with, variance_integral_table, variance_lyapunov,
    variance_quadrature, LyapunovMoments, INTEGRAL_TABLE_MAX_ERROR,
};
