//! The text of the Monte Carlo verdict values of `stochvib analyze --monte-carlo N`
//! ([`crate::study::mc_verdicts`] computes them).

use crate::simulate::covers_word;
use crate::study::mc_verdicts::McVerdicts;
use std::fmt;

impl fmt::Display for McVerdicts {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        writeln!(f)?;
        writeln!(
            f,
            "Monte Carlo verdict values ({} realizations of T = {} s, Δt = {} s)",
            self.realizations, self.duration_s, self.dt_s
        )?;
        writeln!(
            f,
            "  {:<18} {:<12} {:>13} {:>13} {:>29}  covers",
            "output", "quantity", "analytic", "MC", "interval"
        )?;
        let e = |v: Option<f64>| v.map_or("—".to_string(), |x| format!("{x:.6e}"));
        for v in &self.values {
            let iv = &v.interval;
            writeln!(
                f,
                "  {:<18} {:<12} {:>13} {:>13.6e} [{:.6e}, {:.6e}]  {} ({} %) {}",
                v.output,
                v.quantity,
                e(v.analytic),
                iv.estimate,
                iv.lower,
                iv.upper,
                covers_word(v.covers),
                100.0 * iv.confidence,
                v.unit
            )?;
            if let Some(c) = &v.cause {
                writeln!(f, "    {c}")?;
            }
        }
        writeln!(
            f,
            "  (VDV over the record T; over a daily exposure T_e a stationary output gives VDV·(T_e/T)^(1/4); the \
             damage rate's analytic value is Dirlik's)"
        )?;
        for b in &self.basic_method {
            writeln!(f, "  basic method, {}: {}", b.output, b.describe())?;
        }
        Ok(())
    }
}
