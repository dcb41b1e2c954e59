//! Ride comfort and whole-body vibration exposure (ISO 2631-1:1997, ISO 2631-4:2001, ISO 8041,
//! IEC 61260-1:2014, Directive 2002/44/EC).
//!
//! # Conventions
//! * Frequency weightings W(s) with s = iω, ω in rad/s, corner frequencies fᵢ in Hz (ωᵢ = 2πfᵢ)
//!   ([`Weighting`]); weighted accelerations a_w in m/s² (rad/s² for the rotational weighting We).
//! * Doses: VDV in m/s^1.75, MSDV in m/s^1.5, daily exposure A(8) in m/s² (T₀ = 8 h).
//! * Band mean squares take the **one-sided density in Hz**, G(f) = 4π S(2πf) of the crate's canonical
//!   two-sided angular density S(ω) ([`band_mean_square`]).
//! * The factors k multiply an axis' a_w ([`axis_factor`], [`vector_sum`]).
//!
//! # Pieces
//! * [`weighting`]: Wk, Wd, Wc, We, Wj, Wb, Wf — product form, polynomials, well-conditioned state space.
//! * [`weighted`]: the weighted output W(s)·H_i(s) of a state-space system (handles D and E).
//! * [`bands`]: base-10 octave and one-third-octave bands, band mean squares by quadrature.
//! * [`band_table`]: the band table of a system's output (band r.m.s. by the band integral of its density,
//!   the bands chosen from an analysis band or around the density's peak).
//! * [`exposure`]: VDV = (3T)^(1/4)·a_w of a stationary Gaussian signal, MSDV, A(8), total VDV.
//! * [`sampled`]: a_w, VDV, MSDV, running r.m.s. and MTVV, crest factor of a sampled weighted signal and
//!   the ISO 2631-1 rule for when the basic method is not sufficient.
//! * [`axes`]: axes, locations, purposes and their factors k; the vector sum.
//! * [`verdict`]: Directive 2002/44/EC action/limit values, the ISO 2631-1 health guidance caution zone
//!   and comfort reactions.

pub mod axes;
pub mod band_table;
pub mod bands;
pub mod exposure;
pub mod sampled;
pub mod verdict;
pub mod weighted;
pub mod weighted_sweep;
pub mod weighting;

pub use axes::{
    axis_factor, directive_factor, vector_sum, Axis, AxisFactor, AxisValue, Location, Purpose, VectorSum, VectorSumTerm,
};
pub use band_table::{output_band_row, output_band_table, BandRow, BandTable, BAND_COVERAGE, MAX_TABLE_THIRD_OCTAVES};
pub use bands::{band_mean_square, band_rms, bands_covering, Band, BandFraction};
pub use exposure::{
    daily_exposure_a8, daily_exposure_a8_periods, msdv, vdv_gaussian, vdv_total, ExposurePeriod, MAX_DAILY_EXPOSURE_S,
    MIN_DAILY_EXPOSURE_S, REFERENCE_DURATION_S,
};
pub use sampled::{
    running_rms, BasicMethodCheck, BasicMethodInputs, Governing, SignalMetrics, SignalMetricsStream,
    CREST_FACTOR_LIMIT, MTVV_INTEGRATION_TIME_S, MTVV_RATIO_LIMIT, VDV_RATIO_LIMIT,
};
pub use verdict::{
    comfort_reactions, ComfortReaction, DirectiveLimits, ExposureVerdict, HealthGuidanceZone, LimitCheck, ZoneCheck,
    ZonePosition,
};
pub use weighted::{check_weightable, weighted_output};
pub use weighted_sweep::{WeightedEvaluator, WeightedRoute, WeightedValue};
pub use weighting::{Motion, Weighting, WeightingParameters, WeightingUse, LARGE_OMEGA, Q_BAND_LIMITING};
