//! The text of the verdict tables of `stochvib analyze` ([`VerdictAnalysis`]): the comfort axes with the
//! purpose's factors (a_w by the Lyapunov and quadrature routes and their difference, k·a_w; A(8) and VDV for
//! health), a_v and the Annex C reactions; the Directive 2002/44/EC / ISO 2631-1 Annex B evaluation with the
//! health factors (per axis a_w, k·a_w, A(8), VDV; the verdict); per spectral method the fatigue damage rate
//! and life, with the moments used. The table builders serve the text (`Table::aligned`) and the markdown
//! (`Table::markdown`, [`super::markdown`]) alike.

use super::table::Table;
use crate::comfort::{Axis, ExposureVerdict, LimitCheck, Location, Purpose, Weighting, ZonePosition};
use crate::fields::EverydayUnit;
use crate::numbers::{num, sig4, sig_column};
use crate::study::{
    ComfortAxisResult, ComfortVerdict, FatigueVerdict, HealthAxisResult, HealthEvaluation, VerdictAnalysis,
};
use std::fmt;

fn opt(v: Option<f64>, prec: usize) -> String {
    v.map(|x| format!("{x:.prec$e}")).unwrap_or_else(|| "—".into())
}

/// The leading columns of an axis table: weighted output, location, axis, weighting, k (as given).
fn axis_columns<'a>(rows: impl Iterator<Item = (&'a str, Location, Axis, Weighting, f64)> + Clone) -> Table {
    Table::default()
        .text("weighted output", rows.clone().map(|r| r.0))
        .text("location", rows.clone().map(|r| r.1.label()))
        .text("axis", rows.clone().map(|r| r.2.label()))
        .text("W", rows.clone().map(|r| r.3.name()))
        .raw("k", rows.map(|r| num(r.4)))
}

/// The axes of `[analysis.comfort]` with the purpose's factors: a_w two ways, k, k·a_w (A(8) and VDV for
/// purpose health, where they are the standard's).
pub fn comfort_table(c: &ComfortVerdict) -> Table {
    let col = |f: &dyn Fn(&ComfortAxisResult) -> Option<f64>| c.axes.iter().map(f).collect::<Vec<_>>();
    let rows = c
        .axes
        .iter()
        .map(|a| (a.output.as_str(), a.location, a.axis, a.weighting, a.k));
    let t = axis_columns(rows)
        .num("a_w Lyapunov", &col(&|a| a.a_w_lyapunov))
        .num("a_w quadrature", &col(&|a| a.a_w_quadrature))
        .num("rel. diff", &col(&|a| a.rel_diff))
        .num("k·a_w", &col(&|a| Some(a.weighted)));
    match c.purpose {
        Purpose::Health => t.num("A(8)", &col(&|a| Some(a.a8))).num("VDV", &col(&|a| Some(a.vdv))),
        Purpose::Comfort => t,
    }
}

/// The axes of the Directive / health evaluation: health weighting and factor, a_w, k·a_w, A(8), VDV.
pub fn health_table(h: &HealthEvaluation) -> Table {
    let col = |f: &dyn Fn(&HealthAxisResult) -> f64| h.axes.iter().map(|a| Some(f(a))).collect::<Vec<_>>();
    let rows = (h.axes.iter()).map(|a| {
        (
            a.output.as_str(),
            a.term.location,
            a.term.axis,
            a.term.weighting,
            a.term.k,
        )
    });
    axis_columns(rows)
        .num("a_w", &col(&|a| a.term.a_w))
        .num("k·a_w", &col(&|a| a.term.weighted))
        .num("A(8)", &col(&|a| a.a8))
        .num("VDV", &col(&|a| a.vdv))
}

/// One line per check of the Directive / Annex B verdict, and the overall verdict.
pub fn health_lines(v: &ExposureVerdict) -> Vec<String> {
    let lim = |x: &LimitCheck, unit: &str| {
        format!(
            "{} {unit} (action {}, limit {}): {}",
            sig4(x.value),
            num(x.action),
            num(x.limit),
            if x.exceeds_limit {
                "ABOVE THE LIMIT VALUE"
            } else if x.exceeds_action {
                "above the action value"
            } else {
                "below the action value"
            }
        )
    };
    let zone = |p: ZonePosition| match p {
        ZonePosition::Below => "below the caution zone",
        ZonePosition::Within => "within the caution zone",
        ZonePosition::Above => "above the caution zone (health risks likely)",
    };
    let mut out = vec![format!("Directive 2002/44/EC  A(8) {}", lim(&v.directive_a8, "m/s²"))];
    if let Some(d) = &v.directive_vdv {
        out.push(format!("Directive 2002/44/EC  VDV  {}", lim(d, "m/s^1.75")));
    }
    out.push(format!("ISO 2631-1 Annex B    A(8) {}", zone(v.zone_a8.position)));
    if let Some(z) = &v.zone_vdv {
        out.push(format!("ISO 2631-1 Annex B    VDV  {}", zone(z.position)));
    }
    out.push(format!(
        "verdict: {}",
        if v.above_limit {
            "EXPOSURE LIMIT VALUE EXCEEDED"
        } else if !v.below_action {
            "exposure action value exceeded (limit respected)"
        } else {
            "below the exposure action values"
        }
    ));
    out
}

/// The lines under the comfort table: units, non-Gaussian warning, MSDV, a_v and the Annex C reactions.
pub fn comfort_lines(c: &ComfortVerdict) -> Vec<String> {
    let mut out = vec![match c.purpose {
        Purpose::Health => {
            "units: a_w, k·a_w, A(8) in m/s² (rad/s² before k for rotations); VDV in m/s^1.75 \
                            (stationary Gaussian: (3T)^(1/4)·k·a_w)"
        }
        Purpose::Comfort => "units: a_w, k·a_w, a_v in m/s² (rad/s² before k for rotations)",
    }
    .to_string()];
    if let Some(k) = &c.non_gaussian_input {
        out.push(format!(
            "non-Gaussian input ({k}): the VDV values and the VDV verdicts are those of a Gaussian input with the \
             same spectrum and do NOT hold (E a_w⁴ = κ_w σ_w⁴ with the weighted output's own kurtosis κ_w > 3, \
             not 3σ_w⁴); σ, a_w and A(8) hold. `stochvib simulate` prints the predicted VDV (κ_w T)^(1/4)·σ_w \
             beside the Monte Carlo VDV"
        ));
    }
    for a in &c.axes {
        if let Some(cov) = &a.input_coverage {
            out.push(format!("INPUT BAND: {}", cov.describe(&a.output)));
        }
    }
    for a in &c.axes {
        if let Some(m) = a.msdv {
            out.push(format!(
                "MSDV of {} (motion sickness, ISO 2631-1 9.2: (∫a_w² dt)^(1/2) = a_w·√T over the exposure) = {} \
                 m/s^1.5",
                a.output,
                sig4(m)
            ));
        }
    }
    out.push(format!(
        "a_v = √(Σ k²a_w²) = {} m/s² ({} factors); dominant axis {}",
        sig4(c.a_v),
        c.purpose.label(),
        c.dominant
    ));
    if !c.comfort_reactions.is_empty() {
        let r: Vec<&str> = c.comfort_reactions.iter().map(|r| r.label()).collect();
        out.push(format!(
            "ISO 2631-1 Annex C    a_v {} m/s²: {}",
            sig4(c.a_v),
            r.join(" / ")
        ));
    }
    out
}

/// The heading of the comfort section and of the health section.
pub fn comfort_headings(c: &ComfortVerdict) -> (String, String) {
    (
        format!(
            "comfort / exposure (ISO 2631-1:1997, purpose {}; daily exposure {})",
            c.purpose.label(),
            EverydayUnit::HOUR.show(c.exposure_s)
        ),
        format!(
            "Directive 2002/44/EC and ISO 2631-1 Annex B, health factors: {}",
            c.health
                .as_ref()
                .map_or("1.4·a_wx, 1.4·a_wy, a_wz", |h| h.factors.as_str())
        ),
    )
}

fn write_comfort(f: &mut fmt::Formatter<'_>, c: &ComfortVerdict) -> fmt::Result {
    let (head, health_head) = comfort_headings(c);
    writeln!(f)?;
    writeln!(f, "{head}")?;
    write!(f, "{}", comfort_table(c).aligned("  "))?;
    for l in comfort_lines(c) {
        writeln!(f, "  {l}")?;
    }
    writeln!(f)?;
    writeln!(f, "{health_head}")?;
    match &c.health {
        Some(h) => {
            write!(f, "{}", health_table(h).aligned("  "))?;
            writeln!(f, "  dominant axis {}", h.dominant)?;
            for l in h.notes.iter().chain(&health_lines(&h.verdict)) {
                writeln!(f, "  {l}")?;
            }
        }
        None => writeln!(f, "  {}", c.health_note.as_deref().unwrap_or("not applicable"))?,
    }
    Ok(())
}

impl fmt::Display for VerdictAnalysis {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        if let Some(c) = &self.comfort {
            write_comfort(f, c)?;
        }
        if let Some(x) = &self.fatigue {
            writeln!(f)?;
            writeln!(f, "{}", fatigue_heading(x))?;
            for l in fatigue_lines(x) {
                writeln!(f, "  {l}")?;
            }
            write!(f, "{}", fatigue_table(x).aligned("  "))?;
            if let Some(v) = fatigue_verdict_line(x) {
                writeln!(f, "  {v}")?;
            }
        }
        if let Some(s) = &self.seat_factor {
            writeln!(f)?;
            for l in s.lines() {
                writeln!(f, "{l}")?;
            }
        }
        Ok(())
    }
}

/// The heading of the fatigue section.
pub fn fatigue_heading(x: &FatigueVerdict) -> String {
    format!(
        "fatigue of {} (stress = {} × output, Pa)",
        x.output,
        sig4(x.stress_factor)
    )
}

/// The S–N curve, the moments two ways and the bandwidth parameters.
pub fn fatigue_lines(x: &FatigueVerdict) -> Vec<String> {
    let m = |v: [f64; 4]| {
        let c = sig_column(&v.map(Some));
        format!("m0 {}  m1 {}  m2 {}  m4 {}", c[0], c[1], c[2], c[3])
    };
    let mut out = vec![
        x.sn_curve.clone(),
        format!("moments (one-sided, Hz)  {}   ({})", m(x.moments), x.moments_method),
    ];
    if let Some(q) = x.moments_quadrature {
        out.push(format!(
            "moments by quadrature    {}   (largest rel. diff {})",
            m(q),
            opt(x.moments_rel_diff, 1)
        ));
    }
    out.push(format!(
        "α1 {}  α2 {}  peaks ν_p {} /s",
        sig4(x.alpha1),
        sig4(x.alpha2),
        sig4(x.nu_peak)
    ));
    out.push(format!("spread (longest/shortest life) {}", sig4(x.spread)));
    if let Some(cov) = &x.input_coverage {
        out.push(format!("INPUT BAND: {}", cov.describe(&x.output)));
    }
    out
}

/// Per spectral method: damage rate, life, life over the design life.
pub fn fatigue_table(x: &FatigueVerdict) -> Table {
    let life = |s: f64| s.is_finite().then_some(s / 3600.0);
    Table::default()
        .text("method", x.methods.iter().map(|m| m.method.clone()))
        .num(
            "damage [1/s]",
            &x.methods.iter().map(|m| Some(m.damage_rate)).collect::<Vec<_>>(),
        )
        .num(
            "life [h]",
            &x.methods.iter().map(|m| life(m.life_s)).collect::<Vec<_>>(),
        )
        .num(
            "life/design",
            &x.methods.iter().map(|m| m.safety_factor).collect::<Vec<_>>(),
        )
}

/// The fatigue verdict against the design life, if one is given.
pub fn fatigue_verdict_line(x: &FatigueVerdict) -> Option<String> {
    let (t, p) = (x.design_life_text.as_ref()?, x.passes?);
    Some(format!(
        "verdict: design life {t}: {}",
        if p {
            "every method's life is longer"
        } else {
            "SOME METHOD'S LIFE IS SHORTER"
        }
    ))
}
