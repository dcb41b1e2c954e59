//! The text of the road building blocks as numbers ([`crate::study::road_numbers`] computes them):
//! `stochvib coherence` (the coherence of a model and/or a measured two-track profile, per frequency) and
//! `stochvib iri` (the expected IRI of a road spectrum beside the IRI of a measured profile).

use super::table::{facts, Table, ToMarkdown};
use crate::numbers::sig4;
use crate::study::road_numbers::{CoherenceReport, CoherenceRow, IriReport};
use std::fmt;

impl CoherenceReport {
    fn table(&self) -> Table {
        let col = |f: fn(&CoherenceRow) -> Option<f64>| self.rows.iter().map(f).collect::<Vec<_>>();
        let mut t = Table::default().num("n [cycles/m]", &col(|r| Some(r.n)));
        if self.model.is_some() {
            t = t
                .num("ρ model", &col(|r| r.model_coherence_amplitude))
                .num("γ² model", &col(|r| r.model_squared_coherence));
        }
        if self.profile.is_some() {
            t = t
                .num("γ² measured", &col(|r| r.measured_squared_coherence))
                .num("lower", &col(|r| r.lower))
                .num("upper", &col(|r| r.upper));
        }
        t
    }

    fn lines(&self) -> Vec<String> {
        let mut out = Vec::new();
        if let Some(m) = &self.model {
            out.push(format!(
                "model: {m} (ρ the coherence amplitude, S_LR = ρS; γ² = ρ² the squared coherence)"
            ));
        }
        if let (Some(p), Some((l, r)), Some((k, nu))) = (&self.profile, &self.tracks, self.segments) {
            out.push(format!(
                "profile {p}: γ̂² of tracks {l} and {r} (linear trend removed; Welch, {k} segments, ν = {}), {} % \
                 Fisher-z interval",
                sig4(nu),
                sig4(self.confidence * 100.0)
            ));
        }
        out
    }
}

impl fmt::Display for CoherenceReport {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        for l in self.lines() {
            writeln!(f, "{l}")?;
        }
        write!(f, "{}", self.table().aligned("  "))
    }
}

impl ToMarkdown for CoherenceReport {
    fn markdown(&self) -> String {
        let mut s = "# Coherence of two tracks\n\n".to_string();
        s += &self.lines().iter().map(|l| format!("- {l}\n")).collect::<String>();
        s + "\n" + &self.table().markdown()
    }
}

/// A band edge: its value, or `unbounded` for the infinite edge of a spectrum without an upper limit.
fn edge(x: f64) -> String {
    if x.is_finite() {
        sig4(x)
    } else {
        "unbounded".to_string()
    }
}

impl IriReport {
    fn table(&self) -> Table {
        let mut what = vec![
            "expected, with the 250 mm moving average".to_string(),
            "expected, without the moving average".to_string(),
        ];
        let mut v = vec![
            Some(self.expected.m_per_km),
            Some(self.expected.without_moving_average_m_per_km),
        ];
        for m in &self.measured {
            what.push(format!("measured, track {}", m.track));
            v.push(Some(m.m_per_km));
        }
        Table::default().text("IRI", what).num("m/km", &v)
    }

    fn lines(&self) -> Vec<String> {
        vec![
            format!("spectrum {}", self.spectrum),
            format!(
                "E[IRI] = 1000 √(2/π) σ_rv / v: golden car (ASTM E1926) at 80 km/h, σ_rv of its relative velocity over \
                 {}–{} cycles/m (Gaussian profile: E|X| = √(2/π) σ)",
                edge(self.expected.band_cycles_per_m.0),
                edge(self.expected.band_cycles_per_m.1)
            ),
        ]
    }
}

impl fmt::Display for IriReport {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        for l in self.lines() {
            writeln!(f, "{l}")?;
        }
        write!(f, "{}", self.table().aligned("  "))
    }
}

impl ToMarkdown for IriReport {
    fn markdown(&self) -> String {
        let mut s = "# International Roughness Index\n\n".to_string();
        s += &facts(&[("spectrum", self.spectrum.clone())]);
        s += "\n";
        s += &self.lines()[1..].iter().map(|l| format!("- {l}\n")).collect::<String>();
        s + "\n" + &self.table().markdown()
    }
}
