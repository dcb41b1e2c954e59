//! The text and markdown of the `stochvib tailor` table ([`crate::study::tailoring`] computes it): per
//! natural frequency the r.m.s. relative displacement, the up-crossing rate, the extreme response spectrum
//! and the fatigue damage spectrum.

use super::table::{Table, ToMarkdown};
use crate::numbers::num;
use crate::study::tailoring::TailoringTable;
use std::fmt;

impl TailoringTable {
    fn table(&self) -> Table {
        let col = |f: fn(&crate::extremes::ErsFdsPoint) -> f64| -> Vec<Option<f64>> {
            self.points
                .iter()
                .map(|p| Some(f(p)).filter(|v| v.is_finite()))
                .collect()
        };
        Table::default()
            .num("f0 [Hz]", &col(|p| p.f0_hz))
            .num("z_rms [m]", &col(|p| p.z_rms))
            .num("n0+ [1/s]", &col(|p| p.n0_plus))
            .num("ERS [m/s^2]", &col(|p| p.ers))
            .num("FDS [damage]", &col(|p| p.fds))
    }

    fn heading(&self) -> String {
        let o = &self.options;
        let m = &o.material;
        format!(
            "ERS and FDS of {}: Q = {}, T = {} s, Basquin b = {}, K = {} Pa/m, C = {} Pa^b \
             (Lalanne; n0+ counts up-crossings; ERS is — where n0+ T <= 1)",
            self.source,
            num(o.q),
            num(o.duration_s),
            num(m.b),
            num(m.k),
            num(m.c)
        )
    }
}

impl fmt::Display for TailoringTable {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        writeln!(f, "{}", self.heading())?;
        write!(f, "{}", self.table().aligned("  "))
    }
}

impl ToMarkdown for TailoringTable {
    fn markdown(&self) -> String {
        format!("{}\n\n{}", self.heading(), self.table().markdown())
    }
}
