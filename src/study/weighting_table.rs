//! What `stochvib weighting NAME` reports, as computed: an ISO 2631 / ISO 8041 frequency weighting at given
//! frequencies, analytic and (with a sample rate) as its digital realisation with the errors of the latter;
//! [`crate::report::record_report`] prints it.

use crate::comfort::Weighting;
use crate::error::Result;
use crate::numbers::num;
use crate::record::{DigitalWeighting, WeightingErrorRow};
use serde::Serialize;

/// The report of `stochvib weighting NAME`: the analytic weighting (and its digital realisation at a sample
/// rate) at the given frequencies.
#[derive(Debug, Clone, Serialize)]
pub struct WeightingReport {
    /// The weighting.
    pub weighting: Weighting,
    /// Its standard and use.
    pub standard: &'static str,
    /// The sample rate of the digital realisation, if asked for.
    pub sample_rate_hz: Option<f64>,
    /// One row per frequency (digital columns equal to the analytic ones without a sample rate).
    pub rows: Vec<WeightingErrorRow>,
    /// The digital realisation (its second-order sections and gain, e.g. for `scipy.signal.sosfilt`).
    pub digital: Option<DigitalWeighting>,
}

/// Refuses a row with a value that is not finite (a frequency so high that 2πf or its powers overflow),
/// naming `--frequency` (or `--sample-rate` when the frequencies are the default ones, up to the Nyquist
/// frequency) with the row's frequency.
fn require_finite_rows(rows: &[WeightingErrorRow], default_frequencies: bool) -> Result<()> {
    let finite = |v: &[f64]| v.iter().all(|x| x.is_finite());
    for r in rows {
        let analytic = finite(&[r.frequency_hz, r.analytic_magnitude, r.analytic_phase_deg]);
        let digital = finite(&[r.digital_magnitude, r.digital_phase_deg, r.error_db, r.phase_error_deg]);
        // the analytic weighting depends on the frequency alone, the digital one on the sample rate too
        let flag = match (analytic, digital) {
            (true, true) => continue,
            (false, _) if !default_frequencies => "--frequency",
            _ => "--sample-rate",
        };
        return Err(crate::Error::invalid(
            flag,
            num(r.frequency_hz),
            format!(
                "the weighting at {} Hz is not a finite number in f64 arithmetic (2πf, its powers or the \
                 sampled filter overflow): give frequencies and a sample rate of the weighting's range",
                num(r.frequency_hz)
            ),
        ));
    }
    Ok(())
}

impl WeightingReport {
    /// The weighting at `frequencies_hz` (default: the one-third-octave centres of its evaluation range, or up
    /// to the Nyquist frequency).
    ///
    /// # Errors
    /// A frequency that is not finite and > 0; the errors of [`DigitalWeighting::new`].
    pub fn new(weighting: Weighting, frequencies_hz: &[f64], sample_rate_hz: Option<f64>) -> Result<Self> {
        if let Some(f) = frequencies_hz.iter().find(|f| !(f.is_finite() && **f > 0.0)) {
            return Err(crate::Error::invalid(
                "--frequency",
                f,
                "frequencies must be finite and > 0 Hz",
            ));
        }
        // the sample rate is the flag's: name it so
        let digital = match sample_rate_hz {
            Some(r) => {
                Some(DigitalWeighting::new(weighting, r).map_err(|e| e.renamed("sample rate", "--sample-rate"))?)
            }
            None => None,
        };
        let rows = if frequencies_hz.is_empty() {
            let (lo, hi) = weighting.evaluation_range_hz();
            match &digital {
                Some(d) => d.error_table(lo, hi)?,
                None => crate::comfort::bands_covering(crate::comfort::BandFraction::ThirdOctave, lo, hi)?
                    .iter()
                    .map(|b| analytic_row(weighting, b.centre_hz))
                    .collect(),
            }
        } else {
            frequencies_hz
                .iter()
                .map(|&f| match &digital {
                    Some(d) => d.error_at(f),
                    None => analytic_row(weighting, f),
                })
                .collect()
        };
        require_finite_rows(&rows, frequencies_hz.is_empty())?;
        Ok(WeightingReport {
            weighting,
            standard: weighting.quantity().standard,
            sample_rate_hz,
            rows,
            digital,
        })
    }
}

/// The analytic weighting at f as a row whose digital columns repeat it.
fn analytic_row(w: Weighting, f_hz: f64) -> WeightingErrorRow {
    let h = w.response(std::f64::consts::TAU * f_hz);
    WeightingErrorRow {
        frequency_hz: f_hz,
        analytic_magnitude: h.norm(),
        analytic_phase_deg: h.arg().to_degrees(),
        digital_magnitude: h.norm(),
        digital_phase_deg: h.arg().to_degrees(),
        error_db: 0.0,
        phase_error_deg: 0.0,
    }
}
