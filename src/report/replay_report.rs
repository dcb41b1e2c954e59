//! `stochvib replay SCENARIO PROFILE.csv`: a measured road profile replayed through a scenario's model
//! ([`crate::study::replay::replay_scenario`]), each reported output's replayed statistics beside the
//! analytic σ from the profile's own measured density.

use crate::study::replay::ScenarioReplay;
use std::fmt;

impl fmt::Display for ScenarioReplay {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let r = &self.replay;
        writeln!(f, "scenario  {} ({})", self.scenario.display(), self.title)?;
        writeln!(f, "profile   {} (detrend {:?})", self.profile.display(), self.detrend)?;
        writeln!(
            f,
            "replay    v = {} m/s, Δx = {:.6} m, Δt = Δx/v = {:.6e} s (first-order hold, exact between samples); {} samples, \
             start {:?}",
            r.speed_m_s, r.step_m, r.dt_s, r.n_samples, r.start
        )?;
        writeln!(
            f,
            "          first {:.3} m ({} samples) skipped for settling; statistics over {} samples from {:.3} m along \
             the profile (foremost wheel)",
            r.skip_m,
            r.skip_samples,
            r.n_samples - r.skip_samples,
            r.first_distance_m
        )?;
        for w in &self.wheels {
            writeln!(
                f,
                "  input {}: track {} at {} m behind the first contact, gain {}{}",
                w.input,
                w.track,
                w.position_m,
                w.gain,
                if w.offset != 0.0 {
                    format!(", offset {}", w.offset)
                } else {
                    String::new()
                }
            )?;
        }
        if r.interpolated {
            writeln!(
                f,
                "  (a wheel falls between profile samples: its track is linearly interpolated, which attenuates \
                 wavelengths of a few steps)"
            )?;
        }
        writeln!(f)?;
        writeln!(
            f,
            "{:<16} {:>6}  {:>12} {:>12} {:>12} {:>8}  {:>12} {:>12}  {:>12}",
            "output", "unit", "mean", "sigma", "analytic", "ratio", "min", "max", "crest"
        )?;
        for o in &self.outputs {
            let s = &o.replayed;
            let (a, ratio) = match o.analytic_sigma {
                Some(a) => (format!("{a:.4e}"), format!("{:.4}", s.sigma / a)),
                None => ("-".into(), "-".into()),
            };
            writeln!(
                f,
                "{:<16} {:>6}  {:>12.4e} {:>12.4e} {:>12} {:>8}  {:>12.4e} {:>12.4e}  {:>12.3}",
                s.name, s.unit, s.mean, s.sigma, a, ratio, s.min, s.max, s.crest_factor
            )?;
        }
        writeln!(f)?;
        writeln!(
            f,
            "sigma: replayed, about the mean; analytic: the same scenario with the Welch density of track `{}` \
             (measured-profile, zero outside its bins) as its road spectrum at v; crest = max|y − mean|/sigma",
            self.analytic_track
        )?;
        Ok(())
    }
}
