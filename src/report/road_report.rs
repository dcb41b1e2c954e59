//! The text of the `stochvib road PROFILE.csv` report ([`crate::study::road_profile`] computes it): the
//! density with its intervals at about 16 bins per track, the ISO 8608 fits, the IRI and the coherence of
//! the first two tracks.

use crate::study::road_profile::RoadReport;
use std::fmt;

/// About 16 bins spread evenly in log n over `rows` (every bin when there are fewer).
fn log_rows(len: usize) -> Vec<usize> {
    if len <= 16 {
        return (0..len).collect();
    }
    let mut out: Vec<usize> = (0..16)
        .map(|k| ((len as f64).powf(k as f64 / 15.0) - 1.0).round() as usize)
        .map(|i| i.min(len - 1))
        .collect();
    out.dedup();
    out
}

impl fmt::Display for RoadReport {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let pc = self.confidence * 100.0;
        writeln!(f, "profile   {}", self.file)?;
        writeln!(
            f,
            "sampling  {} samples at {:.6} m ({:.3} m); Welch segments of {} samples (Δn = {:.4e} cycles/m), K = {}, ν = {:.1}; detrend {:?}",
            self.samples,
            self.step_m,
            self.length_m,
            self.segment_len,
            1.0 / (self.segment_len as f64 * self.step_m),
            self.segments,
            self.dof,
            self.detrend
        )?;
        for t in &self.tracks {
            writeln!(f)?;
            writeln!(f, "track {}", t.name)?;
            writeln!(f, "  sigma     {:.6e} m", t.sigma_m)?;
            writeln!(f, "  IRI       {:.4} m/km (golden car, 80 km/h)", t.iri_m_per_km)?;
            for fit in &t.fits {
                writeln!(
                    f,
                    "  ISO 8608 ({}): G_d(n0) = {:.4e} m^3 [{:.4e}, {:.4e}], w = {:.4} [{:.4}, {:.4}], class {}, band {:.4}..{:.4} cycles/m, reduced chi2 {:.3}",
                    fit.waviness_mode,
                    fit.g0_m3,
                    fit.g0_interval.0,
                    fit.g0_interval.1,
                    fit.waviness,
                    fit.waviness_interval.0,
                    fit.waviness_interval.1,
                    fit.class,
                    fit.band.0,
                    fit.band.1,
                    fit.reduced_chi2
                )?;
                if !fit.describes_the_road {
                    writeln!(
                        f,
                        "    not a power-law road: a fit this poor has probability {} (< {:.0e}) for a road that \
                         follows it; class {} is the level of G_d at n0 = 0.1 cycles/m only",
                        match fit.fit_p_value {
                            0.0 => "below 1e-300".to_string(),
                            p => format!("{p:.1e}"),
                        },
                        crate::study::road_profile::POWER_LAW_REJECT_P,
                        fit.class
                    )?;
                }
            }
            writeln!(
                f,
                "  {:>12}  {:>12}  {:>12}  {:>12}   ({pc} % interval; --json lists every bin)",
                "n [c/m]", "G_d [m^3]", "lower", "upper"
            )?;
            for i in log_rows(t.density.len()) {
                let r = &t.density[i];
                writeln!(
                    f,
                    "  {:>12.4e}  {:>12.4e}  {:>12.4e}  {:>12.4e}",
                    r.n, r.g_d, r.lower, r.upper
                )?;
            }
        }
        if let Some((l, r)) = &self.coherence_tracks {
            writeln!(f)?;
            writeln!(f, "squared coherence of {l} and {r} ({pc} % Fisher-z interval)")?;
            writeln!(
                f,
                "  {:>12}  {:>8}  {:>8}  {:>8}",
                "n [c/m]", "gamma^2", "lower", "upper"
            )?;
            for i in log_rows(self.coherence.len()) {
                let c = &self.coherence[i];
                writeln!(
                    f,
                    "  {:>12.4e}  {:>8.4}  {:>8.4}  {:>8.4}",
                    c.n, c.squared_coherence, c.lower, c.upper
                )?;
            }
        }
        Ok(())
    }
}
