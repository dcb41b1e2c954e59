//! Measured records: acceleration and stress (or strain) signals read from CSV, HDF5 and WAV files, and
//! their evaluation in the time domain — ISO 2631-1 exposure and comfort, rainflow fatigue beside the
//! spectral methods — streamed block by block, so memory stays flat in the record's length.
//!
//! # Conventions
//! * Sample rate f_s in Hz, time step dt = 1/f_s; samples are taken to hold over one step each (the
//!   rectangle rule of [`SignalMetrics`](crate::comfort::SignalMetrics)).
//! * Every channel carries a unit, read from the file or stated, never guessed ([`Channel`]); values are
//!   converted to SI on reading (m/s², rad/s², Pa, strain as a number).
//! * Weightings are realised as digital filters per ISO 8041 ([`DigitalWeighting`]: bilinear transform
//!   prewarped at each section's pole, with its error against the analytic weighting).
//! * One-third-octave bands of IEC 61260-1 as ideal bands of the streamed Welch density ([`bands`]).
//! * Fatigue: S–N curves in stress amplitude (N·S_a^k = C); rainflow per ASTM E1049 ([`fatigue_record`]).
//!
//! # Pieces
//! * [`source`]: channels, units, time bases, [`RecordReader`], [`open_record`].
//! * [`csv`](mod@csv), [`hdf5`](mod@hdf5), [`wav`]: the three readers.
//! * [`filter`] — [`DigitalWeighting`].
//! * [`running`]: the exponential running r.m.s. and the decimated envelope of a long signal.
//! * [`bands`]: band values from a streamed Welch density.
//! * [`exposure`] — [`evaluate_exposure`].
//! * [`fatigue_record`] — [`evaluate_fatigue`].

pub mod bands;
pub mod csv;
pub mod exposure;
pub mod fatigue_record;
pub mod filter;
pub mod hdf5;
pub mod running;
pub mod source;
pub mod wav;

pub use bands::{segment_for, BandAnalyzer, BandValue, MIN_BINS_PER_BAND};
pub use exposure::{
    evaluate_exposure, AxisAssignment, AxisEvaluation, ExposureEvaluation, ExposureOptions, HealthAxis,
    RealisationError,
};
pub use fatigue_record::{
    evaluate_fatigue, quantity_of_dim, sn_curve_from_flags, FatigueEvaluation, FatigueOptions, MeanStressCorrection,
    SnPoint,
};
pub use filter::{Biquad, DigitalWeighting, FilterState, WeightingErrorRow, MAX_BAND_ERROR_DB};
pub use running::{Envelope, EnvelopeBin, ExponentialRms, RunningRms};
pub use source::{open_record, parse_quantity, parse_unit, Channel, RecordInfo, RecordOptions, RecordReader, TimeBase};
