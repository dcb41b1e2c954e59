//! Roads as data: two correlated synthetic tracks, measured profiles (CSV), their spatial spectra and
//! coherence, the ISO 8608 fit and class, and the International Roughness Index.
//!
//! Conventions: distances and elevations in m; spatial frequency n in cycles/m; ISO 8608's density
//! G_d(n) is one-sided in cycles/m (m³), with G_d(n) = 4π S(2πn) for the crate's canonical two-sided
//! S(Ω), Ω in rad/m ([`crate::spectrum`]); n₀ = 0.1 cycles/m. Two tracks L, R with the same density S have
//! S_LR = ρ S ([`crate::coherence`]).
//!
//! * [`TwoTrackGenerator`] ([`synthesis`]): left/right tracks with an exact cross-spectrum in expectation.
//! * [`Profile`], [`RawProfile`] ([`profile`]): measured profiles, CSV import/export, explicit resampling;
//!   [`Detrend`] ([`detrend`]).
//! * [`spatial_psd()`], [`spatial_cross_spectrum`] ([`spatial_psd`](mod@spatial_psd)): Welch estimates of
//!   G_d, G_LR and γ² with intervals.
//! * [`fit_iso8608`], [`iso8608_class`] ([`iso_fit`]): G_d(n₀), w, their standard errors, the class.
//! * [`replay()`](replay::replay) ([`replay`](mod@replay)): a profile replayed as a deterministic time-domain
//!   input through a model (wheels on tracks, delays by position/speed), each output's history and statistics.
//! * [`iri`](fn@iri) ([`iri`](mod@iri)): International Roughness Index (golden car, ASTM E1926).

pub mod detrend;
pub mod iri;
pub mod iso_fit;
pub mod profile;
pub mod replay;
pub mod spatial_psd;
pub mod synthesis;

pub use detrend::Detrend;
pub use iri::{expected_iri, golden_car, iri, ExpectedIri, Iri};
pub use iso_fit::{fit_iso8608, iso8608_class, IsoFit, Waviness, POWER_LAW_REJECT_P};
pub use profile::{CsvReadOptions, CsvWriteOptions, LengthUnit, Profile, RawProfile, Track};
pub use replay::{OutputStatistics, Replay, ReplayOptions, Start, Wheel};
pub use spatial_psd::{default_segment, spatial_cross_spectrum, spatial_psd, SpatialCrossSpectrum, SpatialPsd};
pub use synthesis::{TwoTrackGenerator, TwoTrackScratch};
