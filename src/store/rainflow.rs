//! The rainflow range histogram of a fatigue verdict channel, as stored under `/rainflow/<output>`
//! (an optional group: files without fatigue channels do not have it).

use super::checksum;

/// Rainflow cycles per range bin of one output, averaged over the realizations of a run.
///
/// # Formula
/// counts_b = (1/R) Σ_realizations Σ_cycles n_c [ΔS_c in bin b] (n_c = 1 or ½ for a half cycle);
/// `dirlik`_b = ν_p T ∫ over the bin's amplitudes of Dirlik's (1985) amplitude density (expected cycles
/// per realization of duration T).
///
/// # Errors
/// None (a plain record).
///
/// # Examples
/// ```
/// use stochvib::store::RainflowHistogram;
/// let h = RainflowHistogram { output: "s".into(), unit: "Pa".into(), edges: vec![0.0, 1.0], counts: vec![2.0],
///     overflow: 0.0, dirlik: None };
/// assert_ne!(h.checksum(), 0);
/// ```
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct RainflowHistogram {
    /// Run output.
    pub output: String,
    /// Stress unit (of the ranges).
    pub unit: String,
    /// The bins + 1 range edges (stress unit).
    pub edges: Vec<f64>,
    /// Cycles per bin per realization.
    pub counts: Vec<f64>,
    /// Cycles above the top edge per realization.
    pub overflow: f64,
    /// Expected cycles per bin per realization by Dirlik's method, if computed.
    pub dirlik: Option<Vec<f64>>,
}

impl RainflowHistogram {
    /// CRC-32 of the values and texts (stored as `@crc32`).
    pub fn checksum(&self) -> u32 {
        let mut c = checksum::Crc32::default();
        c.update_f64(&self.edges);
        c.update_f64(&self.counts);
        c.update_f64(&[self.overflow]);
        if let Some(d) = &self.dirlik {
            c.update(b"dirlik");
            c.update_f64(d);
        }
        for s in [&self.output, &self.unit] {
            c.update(s.as_bytes());
            c.update(&[0]);
        }
        c.finish()
    }
}
