//! The text of the verdict tables of `stochvib analyze` ([`VerdictAnalysis`]): per axis a_w by the
//! Lyapunov and quadrature routes and their difference, k·a_w, A(8), VDV; a_v; the verdict against
//! Directive 2002/44/EC and ISO 2631-1; per spectral method the fatigue damage rate and life, with the
//! moments used.

use crate::comfort::ZonePosition;
use crate::scenario::VerdictAnalysis;
use std::fmt;

fn opt(v: Option<f64>, prec: usize) -> String {
    v.map(|x| format!("{x:.prec$e}")).unwrap_or_else(|| "—".into())
}

fn hours(s: f64) -> String {
    if s.is_infinite() {
        "∞".into()
    } else {
        format!("{:.4e} h", s / 3600.0)
    }
}

impl fmt::Display for VerdictAnalysis {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        if let Some(c) = &self.comfort {
            writeln!(f)?;
            writeln!(
                f,
                "comfort / exposure (ISO 2631-1:1997, {:?}; daily exposure {} h)",
                c.purpose,
                c.exposure_s / 3600.0
            )?;
            writeln!(
                f,
                "  {:<18} {:<12} {:<4} {:<3} {:>5} {:>13} {:>13} {:>9} {:>11} {:>11} {:>11}",
                "weighted output",
                "location",
                "axis",
                "W",
                "k",
                "a_w Lyapunov",
                "a_w quadrat.",
                "rel.diff",
                "k·a_w",
                "A(8)",
                "VDV"
            )?;
            for a in &c.axes {
                writeln!(
                    f,
                    "  {:<18} {:<12} {:<4} {:<3} {:>5} {:>13} {:>13} {:>9} {:>11.4e} {:>11.4e} {:>11.4e}",
                    a.output,
                    format!("{:?}", a.location),
                    format!("{:?}", a.axis),
                    a.weighting.name(),
                    a.k,
                    opt(a.a_w_lyapunov, 6),
                    opt(a.a_w_quadrature, 6),
                    opt(a.rel_diff, 1),
                    a.weighted,
                    a.a8,
                    a.vdv
                )?;
            }
            writeln!(f, "  units: a_w, k·a_w, A(8) in m/s² (rad/s² before k for rotations); VDV in m/s^1.75 (stationary Gaussian: (3T)^(1/4)·k·a_w)")?;
            if let Some(k) = &c.non_gaussian_input {
                writeln!(
                    f,
                    "  non-Gaussian input ({k}): the VDV column and the VDV verdicts below are those of a Gaussian \
                     input with the same spectrum and do NOT hold (E a_w⁴ = κ_w σ_w⁴ with the weighted output's own \
                     kurtosis κ_w > 3, not 3σ_w⁴); σ, a_w and A(8) hold. `stochvib simulate` prints the predicted \
                     VDV (κ_w T)^(1/4)·σ_w beside the Monte Carlo VDV"
                )?;
            }
            for a in &c.axes {
                if let Some(cov) = &a.input_coverage {
                    writeln!(f, "  INPUT BAND: {}", cov.describe(&a.output))?;
                }
            }
            for a in &c.axes {
                if let Some(m) = a.msdv {
                    writeln!(
                        f,
                        "  MSDV of {} (motion sickness, ISO 2631-1 9.2: (∫a_w² dt)^(1/2) = a_w·√T over the exposure) = \
                         {m:.4e} m/s^1.5",
                        a.output
                    )?;
                }
            }
            writeln!(
                f,
                "  a_v = √(Σ k²a_w²) = {:.4e} m/s²; dominant axis {}",
                c.a_v, c.dominant
            )?;
            let v = &c.verdict;
            let lim = |x: &crate::comfort::LimitCheck| {
                format!(
                    "{:.3} (action {}, limit {}): {}",
                    x.value,
                    x.action,
                    x.limit,
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
            writeln!(f, "  Directive 2002/44/EC  A(8) {}", lim(&v.directive_a8))?;
            if let Some(d) = &v.directive_vdv {
                writeln!(f, "  Directive 2002/44/EC  VDV  {}", lim(d))?;
            }
            writeln!(f, "  ISO 2631-1 Annex B    A(8) {}", zone(v.zone_a8.position))?;
            if let Some(z) = &v.zone_vdv {
                writeln!(f, "  ISO 2631-1 Annex B    VDV  {}", zone(z.position))?;
            }
            if !v.comfort_reactions.is_empty() {
                let r: Vec<&str> = v.comfort_reactions.iter().map(|r| r.label()).collect();
                writeln!(f, "  ISO 2631-1 Annex C    a_v {:.3} m/s²: {}", c.a_v, r.join(" / "))?;
            }
            writeln!(
                f,
                "  verdict: {}",
                if v.above_limit {
                    "EXPOSURE LIMIT VALUE EXCEEDED"
                } else if !v.below_action {
                    "exposure action value exceeded (limit respected)"
                } else {
                    "below the exposure action values"
                }
            )?;
        }
        if let Some(x) = &self.fatigue {
            writeln!(f)?;
            writeln!(
                f,
                "fatigue of {} (stress = {:e} × output, Pa)",
                x.output, x.stress_factor
            )?;
            writeln!(f, "  {}", x.sn_curve)?;
            let [m0, m1, m2, m4] = x.moments;
            writeln!(
                f,
                "  moments (one-sided, Hz)  m0 {m0:.6e}  m1 {m1:.6e}  m2 {m2:.6e}  m4 {m4:.6e}   ({})",
                x.moments_method
            )?;
            if let Some([q0, q1, q2, q4]) = x.moments_quadrature {
                writeln!(
                    f,
                    "  moments by quadrature    m0 {q0:.6e}  m1 {q1:.6e}  m2 {q2:.6e}  m4 {q4:.6e}   (largest rel. diff {})",
                    opt(x.moments_rel_diff, 1)
                )?;
            }
            writeln!(
                f,
                "  α1 {:.4}  α2 {:.4}  peaks ν_p {:.4e} /s",
                x.alpha1, x.alpha2, x.nu_peak
            )?;
            writeln!(
                f,
                "  {:<34} {:>13} {:>15} {:>10}",
                "method", "damage /s", "life", "life/design"
            )?;
            for m in &x.methods {
                writeln!(
                    f,
                    "  {:<34} {:>13.4e} {:>15} {:>10}",
                    m.method,
                    m.damage_rate,
                    hours(m.life_s),
                    m.safety_factor.map(|s| format!("{s:.3}")).unwrap_or_else(|| "—".into())
                )?;
            }
            writeln!(f, "  spread (longest/shortest life) {:.3}", x.spread)?;
            if let Some(cov) = &x.input_coverage {
                writeln!(f, "  INPUT BAND: {}", cov.describe(&x.output))?;
            }
            if let (Some(t), Some(p)) = (&x.design_life_text, x.passes) {
                writeln!(
                    f,
                    "  verdict: design life {t}: {}",
                    if p {
                        "every method's life is longer"
                    } else {
                        "SOME METHOD'S LIFE IS SHORTER"
                    }
                )?;
            }
        }
        Ok(())
    }
}
