//! The text and markdown of the `stochvib analyze` report of a scenario with nonlinear elements
//! ([`crate::study::nonlinear_report()`] computes it): route 1, route 3 and, with `--monte-carlo N`, route 2
//! beside them with the verdicts.

use super::table::{facts, Table, ToMarkdown};
use crate::study::nonlinear_report::NonlinearReport;
use std::fmt;

fn opt(v: Option<f64>) -> String {
    v.map(|x| format!("{x:.5e}")).unwrap_or_else(|| "—".into())
}

impl fmt::Display for NonlinearReport {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        writeln!(f, "scenario  {}  ({})", self.title, self.scenario)?;
        writeln!(f, "model     {}", self.model)?;
        writeln!(f, "input     {}", self.input)?;
        writeln!(f, "route 1   statistical linearization: {}", self.route1)?;
        writeln!(f, "route 3   {}", self.route3)?;
        if let Some(m) = &self.monte_carlo {
            writeln!(f, "route 2   nonlinear Monte Carlo: {m}")?;
        }
        for e in &self.elements {
            write!(f, "element   {}: {}", e.name, e.description)?;
            if let (Some(q), Some(m)) = (&e.equivalent, &e.moments) {
                write!(
                    f,
                    "; route 1 (remainder beyond the linear part): F₀ = {:.4e}, k_eq = {:.4e}, c_eq = {:.4e}; μ_x = {:.4e}, \
                     σ_x = {:.4e}, σ_v = {:.4e}",
                    q.mean_force, q.stiffness, q.damping, m.mean_x, m.sigma_x, m.sigma_v
                )?;
            }
            writeln!(f)?;
        }
        for k in &self.skipped {
            writeln!(f)?;
            writeln!(f, "output {}: no statistics: {}", k.name, k.reason)?;
        }
        for o in &self.outputs {
            writeln!(f)?;
            writeln!(f, "output {} [{}]", o.name, o.unit)?;
            if !o.route1_methods.is_empty() {
                let m: Vec<String> = o
                    .route1_methods
                    .iter()
                    .map(|(n, v, d)| {
                        format!(
                            "{n} {} (rel. diff {})",
                            opt(*v),
                            d.map_or("—".into(), |d| format!("{d:.1e}"))
                        )
                    })
                    .collect();
                writeln!(f, "  route 1 variance of the equivalent system: {}", m.join(", "))?;
                writeln!(
                    f,
                    "  route 1 ν₀⁺ {} /s{}",
                    opt(o.route1_nu0),
                    o.route1_a_w
                        .map_or(String::new(), |a| format!(", a_w (W_k) {a:.5e} m/s²"))
                )?;
            }
            writeln!(
                f,
                "  {:<30} {:>12} {:>12} {:>12} {:>27} {:>10}",
                "statistic", "route 1", "exact", "route 2 MC", "interval", "r1/MC−1"
            )?;
            for r in &o.rows {
                let (mc, iv) = match &r.monte_carlo {
                    Some(iv) => (
                        format!("{:.5e}", iv.estimate),
                        format!("[{:.4e}, {:.4e}]", iv.lower, iv.upper),
                    ),
                    None => ("—".into(), String::new()),
                };
                let flag = if r.route1_covered == Some(false) {
                    "  << route 1 outside"
                } else {
                    ""
                };
                writeln!(
                    f,
                    "  {:<30} {:>12} {:>12} {:>12} {:>27} {:>10}{flag}",
                    r.statistic,
                    opt(r.route1),
                    opt(r.exact),
                    mc,
                    iv,
                    r.route1_rel_diff.map_or("—".into(), |d| format!("{d:+.2e}"))
                )?;
            }
            for (name, iv) in &o.dt_halving {
                writeln!(
                    f,
                    "  {name}: {:.3e} [{:.3e}, {:.3e}] (Δt minus Δt/2, same noise path)",
                    iv.estimate, iv.lower, iv.upper
                )?;
            }
        }
        if !self.verdicts.is_empty() {
            writeln!(f)?;
        }
        for v in &self.verdicts {
            writeln!(f, "verdict   {v}")?;
        }
        Ok(())
    }
}

impl ToMarkdown for NonlinearReport {
    fn markdown(&self) -> String {
        let mut s = format!("## {}\n\n", self.title);
        s.push_str(&facts(&[
            ("scenario", self.scenario.clone()),
            ("model", self.model.clone()),
            ("input", self.input.clone()),
            ("route 1 (statistical linearization)", self.route1.clone()),
            ("route 3 (exact)", self.route3.clone()),
            (
                "route 2 (Monte Carlo)",
                self.monte_carlo
                    .clone()
                    .unwrap_or_else(|| "not run (--monte-carlo N)".into()),
            ),
        ]));
        for k in &self.skipped {
            s.push_str(&format!("\n### {}\n\nno statistics: {}\n", k.name, k.reason));
        }
        for o in &self.outputs {
            s.push_str(&format!("\n### {} [{}]\n\n", o.name, o.unit));
            s.push_str(
                &Table::default()
                    .text("statistic", o.rows.iter().map(|r| r.statistic.clone()))
                    .text("route 1", o.rows.iter().map(|r| opt(r.route1)))
                    .text("exact", o.rows.iter().map(|r| opt(r.exact)))
                    .text(
                        "route 2",
                        o.rows.iter().map(|r| {
                            r.monte_carlo.map_or("—".into(), |iv| {
                                format!("{:.5e} [{:.4e}, {:.4e}]", iv.estimate, iv.lower, iv.upper)
                            })
                        }),
                    )
                    .text(
                        "route 1 covered",
                        o.rows.iter().map(|r| match r.route1_covered {
                            Some(true) => "yes".into(),
                            Some(false) => "**NO**".into(),
                            None => "—".to_string(),
                        }),
                    )
                    .markdown(),
            );
        }
        if !self.verdicts.is_empty() {
            s.push('\n');
            for v in &self.verdicts {
                s.push_str(&format!("- **{v}**\n"));
            }
        }
        s
    }
}
