//! The band section of the `stochvib analyze` report: per output, the IEC 61260-1 octave or
//! one-third-octave band r.m.s. table asked for by `[analysis] bands` ([`crate::comfort::output_band_table`]),
//! printed by [`crate::report::band_text`].

use crate::comfort::{output_band_table, BandTable};
use crate::error::Result;
use crate::response::ResponseStatistics;
use crate::scenario::Scenario;
use serde::Serialize;
use std::f64::consts::PI;

/// One output's band table, or why there is none.
#[derive(Debug, Clone, Serialize)]
pub struct BandSection {
    /// The table, if it could be computed.
    pub table: Option<BandTable>,
    /// Why it could not.
    pub note: Option<String>,
    /// When the input stops below the table's top band: the bands above its edge with the input's power law
    /// continued ([`super::input_coverage::band_coverage`]).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub input_coverage: Option<super::input_coverage::BandCoverage>,
}

/// The band section of output `i` when the scenario asks for bands (`None` otherwise).
///
/// # Formula
/// [`output_band_table`] with σ² from the analysis' variance (its reference method) and the scenario's
/// `[analysis] band` (rad/s → Hz) as the range if given.
///
/// # Errors
/// None: a failing table becomes a note.
///
/// # Examples
/// ```no_run
/// use std::path::Path;
/// let sc = stochvib::scenario::load_scenario(Path::new("data/operator-seat.toml"), Path::new("spectra")).unwrap();
/// let st = stochvib::response::analyze_output(sc.model.system.as_ref(), &sc.excitation, 0).unwrap();
/// let s = stochvib::study::band_section::band_section(&sc, 0, &st);
/// assert!(s.is_none()); // the scenario has no `bands` key
/// ```
pub fn band_section(sc: &Scenario, i: usize, st: &ResponseStatistics) -> Option<BandSection> {
    let fraction = sc.analysis.bands?;
    let variance = st.sigma.map(|s| s * s);
    let range_hz = sc.analysis.band.map(|(a, b)| (a / (2.0 * PI), b / (2.0 * PI)));
    let r: Result<BandTable> = output_band_table(
        sc.model.system.as_ref(),
        &sc.excitation,
        i,
        fraction,
        variance,
        range_hz,
    );
    Some(match r {
        Ok(t) => {
            let names = super::input_coverage::source_names(sc);
            let (input_coverage, note) =
                match super::input_coverage::band_coverage(sc.model.system.as_ref(), &sc.excitation, i, &t, &names) {
                    Ok(c) => (c, None),
                    Err(e) => (None, Some(format!("input coverage not assessed: {e}"))),
                };
            BandSection {
                table: Some(t),
                note,
                input_coverage,
            }
        }
        Err(e) => BandSection {
            table: None,
            note: Some(e.to_string()),
            input_coverage: None,
        },
    })
}
