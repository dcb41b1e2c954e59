//! The reports of the measured-record commands: `stochvib exposure RECORD` ([`ExposureReport`]),
//! `stochvib fatigue RECORD` ([`FatigueReport`]) and `stochvib weighting NAME` ([`WeightingReport`], computed
//! by [`crate::study::weighting_table`]), as text, markdown (four significant figures per column,
//! [`super::table`]) and JSON (every field).

use super::table::{facts, Table, ToMarkdown};
use super::verdict_report::health_lines;
use crate::numbers::{num, sig4};
use crate::record::{AxisEvaluation, ExposureEvaluation, FatigueEvaluation, WeightingErrorRow};
use crate::study::weighting_table::WeightingReport;
use serde::Serialize;
use std::fmt;

/// The report of `stochvib exposure` (text, markdown, JSON: the [`ExposureEvaluation`] itself).
#[derive(Debug, Clone, Serialize)]
#[serde(transparent)]
pub struct ExposureReport(pub ExposureEvaluation);

fn opt(v: Option<f64>) -> Option<f64> {
    v.filter(|x| x.is_finite())
}

/// The per-axis table: a_w, MTVV, VDV, crest factor, the basic-method ratios, which metric governs (ISO
/// 2631-1 6.3.3: none above its threshold, the r.m.s.; else the one furthest above), and the health values.
pub fn axis_table(axes: &[AxisEvaluation]) -> Table {
    let col = |f: &dyn Fn(&AxisEvaluation) -> Option<f64>| axes.iter().map(f).collect::<Vec<_>>();
    Table::default()
        .text("channel", axes.iter().map(|a| a.channel.clone()))
        .text("location", axes.iter().map(|a| a.location.label()))
        .text("axis", axes.iter().map(|a| a.axis.label()))
        .text("W", axes.iter().map(|a| a.weighting.name()))
        .num("a_w [m/s²]", &col(&|a| Some(a.metrics.a_w)))
        .num("MTVV [m/s²]", &col(&|a| a.mtvv))
        .num("VDV [m/s^1.75]", &col(&|a| Some(a.metrics.vdv)))
        .num("crest factor", &col(&|a| opt(a.metrics.check.crest_factor)))
        .num("MTVV/a_w", &col(&|a| opt(a.mtvv.map(|m| m / a.metrics.a_w))))
        .num("VDV/(a_w T^¼)", &col(&|a| opt(a.metrics.check.vdv_ratio)))
        .text(
            "basic method",
            axes.iter().map(|a| {
                if a.metrics.check.basic_method_sufficient {
                    "sufficient"
                } else {
                    "NOT sufficient"
                }
            }),
        )
        .text("governs", axes.iter().map(|a| a.metrics.check.governing.label()))
        .num("k (health)", &col(&|a| a.health.map(|h| h.k)))
        .num("A(8) [m/s²]", &col(&|a| a.health.map(|h| h.a8)))
        .num("VDV day [m/s^1.75]", &col(&|a| a.health.map(|h| h.daily_vdv)))
}

/// The motion-sickness table: a_w (Wf), MSDV of the record and of the exposure.
pub fn sickness_table(axes: &[AxisEvaluation]) -> Table {
    Table::default()
        .text("channel", axes.iter().map(|a| a.channel.clone()))
        .num(
            "a_w (Wf) [m/s²]",
            &axes.iter().map(|a| Some(a.metrics.a_w)).collect::<Vec<_>>(),
        )
        .num(
            "MSDV record [m/s^1.5]",
            &axes.iter().map(|a| Some(a.metrics.msdv)).collect::<Vec<_>>(),
        )
        .num(
            "MSDV exposure [m/s^1.5]",
            &axes.iter().map(|a| a.msdv_exposure).collect::<Vec<_>>(),
        )
}

/// The band table: one row per one-third-octave band, one column per axis (band r.m.s. of the weighted
/// signal; `*` marks a band narrower than the bins resolve).
pub fn band_table(axes: &[AxisEvaluation]) -> Option<Table> {
    let first = axes.iter().find_map(|a| a.bands.as_ref())?;
    let mut t = Table::default().text("band", first.iter().map(|b| b.band.label()));
    for a in axes {
        let cells: Vec<String> = match &a.bands {
            Some(b) => {
                let v: Vec<Option<f64>> = b.iter().map(|x| Some(x.rms)).collect();
                crate::numbers::sig_column(&v)
                    .into_iter()
                    .zip(b)
                    .map(|(s, x)| if x.resolved { s } else { format!("{s}*") })
                    .collect()
            }
            None => vec!["—".into(); first.len()],
        };
        t = t.raw(&format!("{} ({}) [m/s²]", a.channel, a.weighting), cells);
    }
    Some(t)
}

/// The lines under the tables: the time base, the realisation, the sums and the verdict.
pub fn exposure_lines(e: &ExposureEvaluation) -> Vec<String> {
    let mut out = Vec::new();
    for a in e.axes.iter().chain(&e.motion_sickness) {
        out.push(format!(
            "{}: {} as a digital filter at {} Hz (bilinear, prewarped per section): largest error {:.3} dB (at {} Hz), \
             {:.2}° of phase over {}–{} Hz; bands from Welch segments of {} samples",
            a.channel,
            a.weighting,
            num(e.record.sample_rate_hz),
            a.realisation.max_error_db,
            sig4(a.realisation.at_hz),
            a.realisation.max_phase_error_deg,
            num(a.weighting.evaluation_range_hz().0),
            num(a.weighting.evaluation_range_hz().1),
            a.segment_len
        ));
    }
    out.push(format!(
        "MTVV from the {:?} running r.m.s., τ = {} s; the basic-method ratios use the linear one (ISO 2631-1 6.3)",
        e.running,
        num(e.tau_s)
    ));
    if let Some(c) = &e.comfort {
        out.push(format!(
            "comfort: vibration total value a_v = √(Σ k² a_w²) = {} m/s² (ISO 2631-1 8.2, comfort factors k)",
            sig4(c.a_v)
        ));
    }
    if let Some(h) = &e.health_vector {
        out.push(format!(
            "health vector sum of the seat axes √(Σ (k a_w)²) = {} m/s² (an additional indicator, ISO 2631-1 7.2.2)",
            sig4(h.a_v)
        ));
    }
    if let Some(v) = &e.verdict {
        out.push(format!(
            "daily exposure {} h: A(8) = k a_w √(T_exp/8 h) on axis {}, VDV_day = k VDV (T_exp/T)^¼ on axis {} (k = 1.4, \
             1.4, 1 for x, y, z: Directive 2002/44/EC Annex B)",
            sig4(e.exposure_s / 3600.0),
            e.dominant_a8.as_deref().unwrap_or("—"),
            e.dominant_vdv.as_deref().unwrap_or("—")
        ));
        out.extend(health_lines(v));
    }
    out
}

fn exposure_facts(e: &ExposureEvaluation) -> Vec<(&'static str, String)> {
    vec![
        ("record", format!("{} ({})", e.record.source.display(), e.record.format)),
        (
            "sampling",
            format!(
                "{} samples at {} Hz ({})",
                e.samples,
                num(e.record.sample_rate_hz),
                e.record.time_base
            ),
        ),
        ("duration", format!("{} s", sig4(e.duration_s))),
        ("exposure", format!("{} h", sig4(e.exposure_s / 3600.0))),
    ]
}

impl fmt::Display for ExposureReport {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let e = &self.0;
        for (k, v) in exposure_facts(e) {
            writeln!(f, "{k:<10} {v}")?;
        }
        if !e.axes.is_empty() {
            writeln!(f)?;
            write!(f, "{}", axis_table(&e.axes).aligned("  "))?;
        }
        if !e.motion_sickness.is_empty() {
            writeln!(f)?;
            write!(f, "{}", sickness_table(&e.motion_sickness).aligned("  "))?;
        }
        let all: Vec<AxisEvaluation> = e.axes.iter().chain(&e.motion_sickness).cloned().collect();
        if let Some(t) = band_table(&all) {
            writeln!(f)?;
            writeln!(
                f,
                "  one-third-octave band r.m.s. of the weighted signals (* fewer bins than resolve the band)"
            )?;
            write!(f, "{}", t.aligned("  "))?;
        }
        writeln!(f)?;
        for l in exposure_lines(e) {
            writeln!(f, "  {l}")?;
        }
        Ok(())
    }
}

impl ToMarkdown for ExposureReport {
    fn markdown(&self) -> String {
        let e = &self.0;
        let mut s = format!("# ISO 2631-1 evaluation of {}\n\n", e.record.source.display());
        s += &facts(&exposure_facts(e));
        if !e.axes.is_empty() {
            s += &format!("\n## Axes\n\n{}", axis_table(&e.axes).markdown());
        }
        if !e.motion_sickness.is_empty() {
            s += &format!(
                "\n## Motion sickness\n\n{}",
                sickness_table(&e.motion_sickness).markdown()
            );
        }
        let all: Vec<AxisEvaluation> = e.axes.iter().chain(&e.motion_sickness).cloned().collect();
        if let Some(t) = band_table(&all) {
            s += &format!("\n## One-third-octave bands\n\n{}", t.markdown());
        }
        s += "\n";
        s += &exposure_lines(e).iter().map(|l| format!("- {l}\n")).collect::<String>();
        s
    }
}

/// The report of `stochvib fatigue` (text, markdown, JSON: the [`FatigueEvaluation`] itself).
#[derive(Debug, Clone, Serialize)]
#[serde(transparent)]
pub struct FatigueReport(pub FatigueEvaluation);

/// Rainflow against each spectral method.
pub fn method_table(e: &FatigueEvaluation) -> Table {
    let mut names = vec!["rainflow (ASTM E1049, Miner)".to_string()];
    let mut rate = vec![Some(e.damage_uncorrected / e.duration_s)];
    let mut life = vec![Some(e.life_uncorrected_s / 3600.0)];
    let mut ratio = vec![Some(1.0)];
    for m in &e.methods {
        names.push(m.method.clone());
        rate.push(Some(m.damage_rate));
        life.push(Some(m.life_s / 3600.0));
        ratio.push(Some(m.life_ratio));
    }
    Table::default()
        .text("method", names)
        .num("damage rate [1/s]", &rate)
        .num("life [h]", &life)
        .num("life / rainflow life", &ratio)
}

/// A life in hours, or "unlimited" when no cycle does damage (a corrected damage of 0: e.g. SWT with every
/// cycle's peak in compression).
fn life_hours(life_s: f64) -> String {
    if life_s.is_finite() {
        format!("{} h", sig4(life_s / 3600.0))
    } else {
        "unlimited (no cycle does damage)".to_string()
    }
}

/// The range–mean matrix as a table (rows: range bins; columns: mean bins with any count).
pub fn matrix_table(e: &FatigueEvaluation) -> Table {
    let m = &e.matrix;
    let n = m.counts.len();
    let used: Vec<usize> = (0..n).filter(|&j| m.counts.iter().any(|r| r[j] > 0.0)).collect();
    let rows: Vec<usize> = (0..n).filter(|&i| m.counts[i].iter().any(|v| *v > 0.0)).collect();
    let mut t = Table::default().text(
        "range \\ mean",
        rows.iter().map(|&i| {
            format!(
                "{}–{}",
                sig4(i as f64 * m.range_width),
                sig4((i + 1) as f64 * m.range_width)
            )
        }),
    );
    for &j in &used {
        let centre = m.mean_origin + (j as f64 + 0.5) * m.mean_width;
        t = t.raw(&sig4(centre), rows.iter().map(|&i| num(m.counts[i][j])));
    }
    t
}

fn fatigue_lines(e: &FatigueEvaluation) -> Vec<String> {
    let mut out = vec![
        format!(
            "S–N curve {} (amplitudes, SI); mean-stress correction {}",
            e.sn,
            e.mean_stress.label()
        ),
        format!(
            "rainflow: {} full and {} half cycles (residue) {}; Miner damage {} with the correction, {} without",
            e.full_cycles,
            e.half_cycles,
            e.gate.map_or_else(
                || "without a gate".to_string(),
                |g| format!("after a hysteresis gate of {}", sig4(g))
            ),
            sig4(e.damage),
            sig4(e.damage_uncorrected)
        ),
        format!(
            "life with the correction {}, without {} h",
            life_hours(e.life_s),
            sig4(e.life_uncorrected_s / 3600.0)
        ),
    ];
    if let Some(m) = &e.spectral {
        out.push(format!(
            "Welch density ({} segments of {} samples, each segment's mean removed) up to {} Hz: σ = {}, ν₀⁺ = {} Hz, \
             ν_p = {} Hz, α₁ = {}, α₂ = {}",
            e.segments,
            e.segment_len,
            num(e.record.sample_rate_hz / 2.0),
            sig4(m.m0.sqrt()),
            sig4(m.nu0_plus_hz),
            sig4(m.nu_peak_hz),
            sig4(m.alpha1),
            sig4(m.alpha2)
        ));
    } else if e.segments == 0 {
        out.push(format!(
            "no spectral methods: the record's {} samples are fewer than one Welch segment of {} (--segment)",
            e.samples, e.segment_len
        ));
    } else {
        out.push("no spectral methods: the record does not fluctuate (its Welch density is zero)".into());
    }
    if let Some(s) = e.spread {
        out.push(format!("spread of the spectral lives (longest/shortest): {}", sig4(s)));
    }
    if let Some(p) = e.samples_per_peak
        && p < 20.0
    {
        out.push(format!(
            "only {} samples per peak (f_s/ν_p): sampled peaks fall short of the true ones by up to 1 − cos(π ν_p/f_s) = \
             {}, so the rainflow damage is biased low",
            sig4(p),
            sig4(1.0 - (std::f64::consts::PI / p).cos())
        ));
    }
    out
}

fn fatigue_facts(e: &FatigueEvaluation) -> Vec<(&'static str, String)> {
    vec![
        ("record", format!("{} ({})", e.record.source.display(), e.record.format)),
        ("channel", e.channel.clone()),
        (
            "sampling",
            format!(
                "{} samples at {} Hz, {} s",
                e.samples,
                num(e.record.sample_rate_hz),
                sig4(e.duration_s)
            ),
        ),
        (
            "values",
            format!("mean {}, min {}, max {} (SI)", sig4(e.mean), sig4(e.min), sig4(e.max)),
        ),
    ]
}

impl fmt::Display for FatigueReport {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let e = &self.0;
        for (k, v) in fatigue_facts(e) {
            writeln!(f, "{k:<9} {v}")?;
        }
        writeln!(f)?;
        write!(f, "{}", method_table(e).aligned("  "))?;
        writeln!(f)?;
        for l in fatigue_lines(e) {
            writeln!(f, "  {l}")?;
        }
        writeln!(f)?;
        writeln!(f, "  range–mean matrix (cycles; half cycles count 0.5; SI)")?;
        write!(f, "{}", matrix_table(e).aligned("  "))
    }
}

impl ToMarkdown for FatigueReport {
    fn markdown(&self) -> String {
        let e = &self.0;
        let mut s = format!("# Fatigue of {}\n\n", e.channel);
        s += &facts(&fatigue_facts(e));
        s += &format!(
            "\n## Life by rainflow and by the spectral methods\n\n{}\n",
            method_table(e).markdown()
        );
        s += &fatigue_lines(e).iter().map(|l| format!("- {l}\n")).collect::<String>();
        s += &format!("\n## Range–mean matrix\n\n{}", matrix_table(e).markdown());
        s
    }
}

impl WeightingReport {
    fn table(&self) -> Table {
        let col = |f: fn(&WeightingErrorRow) -> f64| self.rows.iter().map(|r| Some(f(r))).collect::<Vec<_>>();
        let t = Table::default()
            .num("f [Hz]", &col(|r| r.frequency_hz))
            .num("|W|", &col(|r| r.analytic_magnitude))
            .num("|W| ×1000", &col(|r| 1000.0 * r.analytic_magnitude))
            .num("phase [°]", &col(|r| r.analytic_phase_deg));
        if self.sample_rate_hz.is_none() {
            return t;
        }
        t.num("|H| digital", &col(|r| r.digital_magnitude))
            .num("phase H [°]", &col(|r| r.digital_phase_deg))
            .num("error [dB]", &col(|r| r.error_db))
            .num("phase error [°]", &col(|r| r.phase_error_deg))
    }

    fn title(&self) -> String {
        match self.sample_rate_hz {
            Some(r) => format!(
                "{} ({}) and its digital realisation at {} Hz (bilinear, prewarped at each section's pole)",
                self.weighting,
                self.standard,
                num(r)
            ),
            None => format!(
                "{} ({}), analytic: K·H_h·H_l·H_t·H_s at s = i2πf",
                self.weighting, self.standard
            ),
        }
    }
}

impl fmt::Display for WeightingReport {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        writeln!(f, "{}", self.title())?;
        write!(f, "{}", self.table().aligned("  "))
    }
}

impl ToMarkdown for WeightingReport {
    fn markdown(&self) -> String {
        format!("# {}\n\n{}", self.title(), self.table().markdown())
    }
}
