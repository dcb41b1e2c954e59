//! The text of the band section of the `stochvib analyze` report: per output, the IEC 61260-1 octave or
//! one-third-octave band r.m.s. table ([`crate::study::band_section`] computes it).

use crate::study::band_section::BandSection;
use std::fmt;

impl fmt::Display for BandSection {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let t = match (&self.table, &self.note) {
            (Some(t), _) => t,
            (None, n) => return writeln!(f, "  bands         — {}", n.as_deref().unwrap_or("")),
        };
        let kind = match t.fraction {
            crate::comfort::BandFraction::Octave => "octave",
            crate::comfort::BandFraction::ThirdOctave => "one-third-octave",
        };
        writeln!(f, "  {kind} bands (IEC 61260-1 base 10): {}", t.chosen_by)?;
        writeln!(
            f,
            "    {:>9} {:>12} {:>12} {:>12} {:>14} {:>14}",
            "band", "f_m [Hz]", "f_1 [Hz]", "f_2 [Hz]", "r.m.s.", "mean square"
        )?;
        for r in &t.rows {
            writeln!(
                f,
                "    {:>9} {:>12.6} {:>12.6} {:>12.6} {:>14.6e} {:>14.6e}",
                r.band.label(),
                r.band.centre_hz,
                r.band.lower_hz,
                r.band.upper_hz,
                r.rms,
                r.mean_square
            )?;
        }
        match (t.total_variance, t.coverage()) {
            (Some(v), Some(c)) => writeln!(
                f,
                "    Σ band mean squares {:.6e} = {:.4} % of σ² = {v:.6e}",
                t.sum_mean_square,
                100.0 * c
            ),
            _ => writeln!(f, "    Σ band mean squares {:.6e} (σ² not finite)", t.sum_mean_square),
        }?;
        if let Some(n) = &self.note {
            writeln!(f, "    {n}")?;
        }
        match &self.input_coverage {
            Some(c) => writeln!(f, "    INPUT BAND: {}", c.describe()),
            None => Ok(()),
        }
    }
}
