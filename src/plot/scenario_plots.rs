//! Pictures of a loaded scenario: the input density, |H(iω)|² of each output and each output's density
//! with the cumulative variance curve (where the variance comes from).

use super::chart::{Legend, LineChart, Marker, SecondaryAxis, Series};
use crate::error::{Error, Result};
use crate::numbers::num;
use crate::scenario::Scenario;
use crate::spectrum::{Convention, Domain, Spectrum};
use crate::study::scenario_curves::{
    coherence_curves, cross_spectra, output_density_curves, spectra_curves, transfer_curves, CrossSpectrum,
    OutputDensityCurves, TransferCurves,
};
use std::path::{Path, PathBuf};

/// Options of [`scenario_plots_with`].
#[derive(Debug, Clone, PartialEq)]
pub struct ScenarioPlotOptions {
    /// Convention of the plotted densities and of the frequency axis. Default
    /// [`Convention::OneSidedCyclic`] (G(f) against f in Hz, or G_d(n) against n in cycles/m for a road).
    pub convention: Convention,
    /// SI unit of the input process (e.g. `m` for a road, `N` for a force); `None`: the scenario's input
    /// unit ([`ScenarioInput::unit`](crate::scenario::ScenarioInput::unit)).
    pub input_unit: Option<String>,
    /// Points per curve (at least 20). Default 400.
    pub points: usize,
}

impl Default for ScenarioPlotOptions {
    fn default() -> Self {
        ScenarioPlotOptions {
            convention: Convention::OneSidedCyclic,
            input_unit: None,
            points: 400,
        }
    }
}

/// Writes every scenario picture into `dir` with the default options ([`ScenarioPlotOptions::default`]):
/// `input-density` (every `[[input]]` source of the first one's domain and unit; `input-density-<name>` for
/// each other), for a road of two tracks `input-coherence` and `input-cross-spectrum-<name>`
/// ([`input_cross_spectrum_charts`]), then for each reported output `transfer-<output>` and
/// `output-density-<output>`, and
/// for each axis of `[analysis.comfort]` `weighted-density-<weighted output>`
/// ([`super::comfort_plots::weighted_density_chart`]), each as `.svg` and `.png`.
///
/// # Errors
/// As [`scenario_plots_with`].
///
/// # Examples
/// ```
/// use std::path::Path;
/// let root = Path::new(env!("CARGO_MANIFEST_DIR"));
/// let sc = stochvib::scenario::load_scenario(&root.join("data/quarter-car.toml"), &root.join("spectra")).unwrap();
/// let dir = std::env::temp_dir().join("stochvib-doc-scenario-plots");
/// let files = stochvib::plot::scenario_plots(&sc, &dir).unwrap();
/// assert_eq!(files.len(), 2 * (1 + 2 * 4)); // input + 2 per output, SVG and PNG each
/// ```
pub fn scenario_plots(sc: &Scenario, dir: &Path) -> Result<Vec<PathBuf>> {
    scenario_plots_with(sc, dir, &ScenarioPlotOptions::default())
}

/// Writes every scenario picture into `dir` (see [`scenario_plots`]) and returns the paths written.
///
/// # Errors
/// [`Error::Io`] if `dir` cannot be created; [`Error::Numerical`] (`plot …`) if a picture has nothing
/// drawable or the back end fails; errors of the response computations (e.g. an unstable system).
pub fn scenario_plots_with(sc: &Scenario, dir: &Path, opts: &ScenarioPlotOptions) -> Result<Vec<PathBuf>> {
    let mut files = input_density_chart(sc, opts)?.render(dir, "input-density")?;
    // `[[input]]` tables of another domain or unit than the first: one chart each
    for (i, inp) in sc.inputs.iter().enumerate().skip(1) {
        if !same_axes(&sc.inputs[0], inp, opts) {
            let c = source_density_chart(sc, i, opts)?;
            files.extend(c.render(dir, &format!("input-density-{}", super::chart::file_stem(&inp.name)))?);
        }
    }
    if let Some(c) = input_coherence_chart(sc, opts)? {
        files.extend(c.render(dir, "input-coherence")?);
    }
    for (name, c) in input_cross_spectrum_charts(sc, opts)? {
        files.extend(c.render(dir, &format!("input-cross-spectrum-{}", super::chart::file_stem(&name)))?);
    }
    for &i in &sc.analysis.outputs {
        let name = super::chart::file_stem(&sc.model.system.outputs()[i].name);
        files.extend(transfer_chart(sc, i, opts)?.render(dir, &format!("transfer-{name}"))?);
        files.extend(output_density_chart(sc, i, opts)?.render(dir, &format!("output-density-{name}"))?);
    }
    // every comfort axis of [analysis.comfort]: weighted density, band r.m.s., comfort scale
    let n_axes = sc.analysis.verdicts.comfort.as_ref().map_or(0, |c| c.axes.len());
    for j in 0..n_axes {
        let c = super::comfort_plots::weighted_density_chart(sc, j)?;
        let name = c.series[0].name.trim_start_matches("density of ").to_string();
        files.extend(c.render(dir, &format!("weighted-density-{}", super::chart::file_stem(&name)))?);
    }
    Ok(files)
}

/// Log–log chart of the scenario's input density as given (a road in its spatial variable, before the
/// speed turns it into time), in `opts.convention`.
///
/// # Formula
/// The canonical S(ω) converted by [`Convention::from_canonical`]: G(f) = 4π S(2πf) by default.
///
/// # Errors
/// [`Error::Numerical`] "nothing to plot" when the density is zero everywhere on the grid.
pub fn input_density_chart(sc: &Scenario, opts: &ScenarioPlotOptions) -> Result<LineChart> {
    let unit = opts.input_unit.clone().unwrap_or_else(|| sc.input.unit.clone());
    if sc.inputs.len() <= 1 {
        let name = input_name(sc, &sc.input);
        let spectra = [(name.as_str(), sc.input.spectrum.as_ref())];
        return spectra_chart(
            &format!("Input density: {}", sc.title),
            &spectra,
            &unit,
            opts.convention,
            opts.points,
        );
    }
    // every `[[input]]` table drawn on the first one's axes (the others get their own chart)
    let names: Vec<String> = sc.inputs.iter().map(|i| source_label(sc, i)).collect();
    let spectra: Vec<(&str, &dyn Spectrum)> = sc
        .inputs
        .iter()
        .zip(&names)
        .filter(|(inp, _)| same_axes(&sc.inputs[0], inp, opts))
        .map(|(inp, n)| (n.as_str(), inp.spectrum.as_ref()))
        .collect();
    spectra_chart(
        &format!("Input densities: {}", sc.title),
        &spectra,
        &unit,
        opts.convention,
        opts.points,
    )
}

/// Legend text of an `[[input]]` source: its name and spectrum reference (`road: iso8608-c, each track`).
fn source_label(sc: &Scenario, inp: &crate::scenario::ScenarioInput) -> String {
    let reference = input_name(sc, inp);
    match &inp.coherence {
        Some(_) => format!("{}: {reference}, each track", inp.name),
        None => format!("{}: {reference}", inp.name),
    }
}

/// The spectrum of an input as the scenario names it: a measured profile by its CSV file and track
/// (`measured-profile.csv (measured profile, track left)`), a table written in the scenario by its `name`,
/// else by its kind (`gauss-cosine spectrum, written in the scenario`), any other spectrum by its reference
/// as written.
fn input_name(sc: &Scenario, inp: &crate::scenario::ScenarioInput) -> String {
    let table = toml::from_str::<toml::Table>(&inp.spectrum_text).unwrap_or_default();
    let key = |k: &str| table.get(k).and_then(|v| v.as_str());
    match (key("kind"), inp.origin == crate::scenario::SpectrumOrigin::Inline) {
        (Some("measured-profile"), _) => crate::scenario::input_as_written(inp, &sc.path),
        (Some(kind), true) => match (key("name"), key("class")) {
            (Some(name), _) => name.to_string(),
            (None, Some(class)) => format!("{kind} class {class}, written in the scenario"),
            (None, None) => format!("{kind} spectrum, written in the scenario"),
        },
        _ => inp.reference.clone(),
    }
}

/// Whether two inputs share the density chart's axes (domain, and unit unless `opts.input_unit` forces one).
fn same_axes(
    a: &crate::scenario::ScenarioInput,
    b: &crate::scenario::ScenarioInput,
    opts: &ScenarioPlotOptions,
) -> bool {
    a.spectrum.domain() == b.spectrum.domain() && (opts.input_unit.is_some() || a.unit == b.unit)
}

/// Log–log chart of the density of `[[input]]` source `i` alone, as given (in its own domain and unit).
///
/// # Errors
/// [`Error::InvalidParameter`] for an index out of range; as [`spectra_chart`].
pub fn source_density_chart(sc: &Scenario, i: usize, opts: &ScenarioPlotOptions) -> Result<LineChart> {
    let inp = sc
        .inputs
        .get(i)
        .ok_or_else(|| Error::invalid("input", i, format!("the scenario has {} inputs", sc.inputs.len())))?;
    let label = source_label(sc, inp);
    spectra_chart(
        &format!("Input density of {}: {}", inp.name, sc.title),
        &[(label.as_str(), inp.spectrum.as_ref())],
        opts.input_unit.as_deref().unwrap_or(&inp.unit),
        opts.convention,
        opts.points,
    )
}

/// The cross-spectrum charts of every road of two tracks (`[[input]] road = { … }`), one per road with its
/// name: in `opts.convention` against the spatial frequency, log–log, the density of each track G_LL = G_RR,
/// the co-spectrum C = Re G_LR and the quad-spectrum Q = −Im G_LR (G_LR = C − iQ, J. S. Bendat and A. G.
/// Piersol, Random Data, 4th ed., 2010, eq. 5.66), and on a linear right-hand axis the squared coherence
/// γ² = |G_LR|²/(G_LL G_RR). Empty when the scenario has no road of two tracks.
///
/// # Formula
/// The source is the pair at the speed v (temporal, [`crate::coherence::TwoTracks`]); back in space,
/// S_x(Ω) = v·S_t(vΩ) for every entry of the matrix, then [`Convention::from_canonical`] (G(n) = 4π S_x(2πn)
/// by default), computed by [`cross_spectra`]. The Ω grid is that of the input density chart of the road's
/// spectrum. A real coherence
/// (every kind of [`crate::coherence`]) gives Q ≡ 0: the series is then left out of the log axis and its
/// legend says so.
///
/// # Errors
/// [`Error::InvalidParameter`] for fewer than 20 points.
pub fn input_cross_spectrum_charts(sc: &Scenario, opts: &ScenarioPlotOptions) -> Result<Vec<(String, LineChart)>> {
    let conv = opts.convention;
    let charts = cross_spectra(sc, conv, opts.points)?
        .into_iter()
        .map(|cs| {
            let real = cs.is_real();
            let CrossSpectrum {
                input,
                unit,
                tracks: (a, b),
                auto,
                co,
                quad,
                coherence,
            } = cs;
            let unit = opts.input_unit.clone().unwrap_or(unit);
            let mut chart = LineChart::new(
                format!("Cross-spectrum of {input}: {}", sc.title),
                frequency_label(conv, Domain::Spatial),
                density_label(conv, Domain::Spatial, &format!("{a} and {b}"), &unit).replacen(
                    "density",
                    "(cross-)density",
                    1,
                ),
            );
            chart.log_x = true;
            chart.log_y = true;
            chart.max_decades = Some(8.0);
            chart
                .series
                .push(Series::line(format!("density of each track, G_{a} = G_{b}"), auto));
            let co_name = if real {
                format!("co-spectrum C = Re G_{a},{b}; quad-spectrum Q ≡ 0 (real coherence)")
            } else {
                format!("co-spectrum C = Re G_{a},{b}")
            };
            chart.series.push(Series::dashed(co_name, co));
            if !real {
                chart
                    .series
                    .push(Series::dashed(format!("quad-spectrum Q = −Im G_{a},{b}"), quad));
            }
            chart.secondary = Some(SecondaryAxis {
                y_label: "squared coherence γ² [-]".into(),
                series: vec![Series::line(format!("γ² of {a} and {b} (right axis)"), coherence)],
                hlines: Vec::new(),
            });
            chart.legend = Legend::LowerLeft;
            (input, chart)
        })
        .collect();
    Ok(charts)
}

/// Chart of the squared coherence γ²(n) = |S_LR|²/(S_LL S_RR) of every multi-component input of the
/// scenario (a road of two tracks: one curve per `[[input]]` road, components 0 and 1) against the spatial
/// frequency n in cycles/m (log axis), or `None` when the scenario has no such input.
///
/// # Formula
/// ω = 2πnv with v the scenario's speed; γ² = |C_01(ω)|² with C the coherence matrix of the source
/// ([`crate::coherence::SpectralMatrix::coherence_matrix`]); n on a log grid over 1e-3 … 10 cycles/m.
///
/// # Errors
/// [`Error::InvalidParameter`] for fewer than 20 points.
pub fn input_coherence_chart(sc: &Scenario, opts: &ScenarioPlotOptions) -> Result<Option<LineChart>> {
    let Some(curves) = coherence_curves(sc, opts.points)? else {
        return Ok(None);
    };
    if curves.is_empty() {
        return Ok(None);
    }
    let mut chart = LineChart::new(
        format!("Input coherence: {}", sc.title),
        "spatial frequency n [cycles/m]",
        "squared coherence γ² [-]",
    );
    chart.log_x = true;
    chart.y_range = Some((0.0, 1.05));
    for c in curves {
        chart.series.push(Series::line(c.name, c.points));
    }
    chart.legend = Legend::LowerLeft;
    Ok(Some(chart))
}

/// Log–log chart of one or more spectra of the same domain and unit (e.g. ISO 8608 classes) in a
/// convention. The frequency range covers every spectrum's support and breakpoints.
///
/// # Errors
/// [`Error::InvalidParameter`] for no spectra, mixed domains or fewer than 20 points;
/// [`Error::Numerical`] "nothing to plot" from rendering when every density is zero.
///
/// # Examples
/// ```
/// use stochvib::spectrum::{Convention, Domain, Exponential, Spectrum};
/// let s = Exponential::new(1.0, 2.0, Domain::Temporal).unwrap();
/// let c = stochvib::plot::scenario_plots::spectra_chart("Type 1", &[("type 1", &s as &dyn Spectrum)], "m",
///     Convention::OneSidedCyclic, 100).unwrap();
/// assert!(c.log_x && c.log_y);
/// assert_eq!(c.x_label, "frequency f [Hz]");
/// ```
pub fn spectra_chart(
    title: &str,
    spectra: &[(&str, &dyn Spectrum)],
    unit: &str,
    convention: Convention,
    points: usize,
) -> Result<LineChart> {
    let (domain, curves) = spectra_curves(spectra, convention, points)?;
    let mut chart = LineChart::new(
        title,
        frequency_label(convention, domain),
        density_label(convention, domain, "input", unit),
    );
    chart.log_x = true;
    chart.log_y = true;
    // a density falling off exponentially (Gaussian-cosine) reaches 1e-300 within its support
    chart.max_decades = Some(INPUT_DECADES);
    for c in curves {
        chart.series.push(Series::line(c.name, c.points));
    }
    chart.legend = Legend::LowerLeft;
    Ok(chart)
}

/// Decades below its peak an input density chart shows.
const INPUT_DECADES: f64 = 30.0;

/// Log–log chart of |H_ij(iω)|² of output `output` for every input j, against frequency (Hz or rad/s per
/// `opts.convention`), with the system's natural frequencies marked.
///
/// # Formula
/// The ω grid spans the natural frequencies |λ| and the input's breakpoints and support edges, a decade
/// beyond each side, log-spaced, with the natural frequencies themselves included ([`transfer_curves`]).
///
/// # Errors
/// [`Error::InvalidParameter`] for an output index out of range.
pub fn transfer_chart(sc: &Scenario, output: usize, opts: &ScenarioPlotOptions) -> Result<LineChart> {
    let conv = opts.convention;
    let TransferCurves {
        output: info,
        per_input,
        natural,
    } = transfer_curves(sc, output, conv, opts.points)?;
    let in_unit = opts.input_unit.clone().unwrap_or_else(|| sc.input.unit.clone());
    let ratio = if info.unit == in_unit {
        "dimensionless".to_string()
    } else {
        format!("({}/{})²", unit_text(&info.unit), unit_text(&in_unit))
    };
    let mut chart = LineChart::new(
        format!("|H(iω)|² of {}: {}", info.name, sc.title),
        frequency_label(conv, Domain::Temporal),
        format!("|H(iω)|² [{ratio}]"),
    );
    chart.log_x = true;
    chart.log_y = true;
    chart.max_decades = Some(8.0);
    let m = per_input.len();
    for (j, c) in per_input.into_iter().enumerate() {
        let name = if m == 1 {
            format!("{} per unit input", info.name)
        } else {
            format!("{} per input {j}", info.name)
        };
        chart.series.push(Series::line(name, c));
    }
    chart.vlines = natural_frequency_markers(&natural, conv);
    chart.legend = Legend::LowerLeft;
    Ok(chart)
}

/// Log–log chart of the density of output `output` in `opts.convention`, with the cumulative variance on
/// a linear right-hand axis and the whole-axis variance as a horizontal line.
///
/// # Formula
/// S_y(ω) = H S_u Hᴴ, computed by [`output_density_curves`]. The cumulative variance at grid point ω_k is
/// σ²(ω_k) = 2∫_0^{ω_k} S_y dω = ∫_0^{f_k} G_y df ([`cumulative_variance`](crate::response::cumulative_variance): accumulated segment by segment
/// with [`band_variance`](crate::response::band_variance), adaptive Gauss–Kronrod quadrature per segment; no
/// trapezoid). When S_y is not integrable at ω = 0 the curve starts at the first grid point (and its label
/// says so). The horizontal line is
/// [`variance_quadrature`](crate::response::variance_quadrature) over the whole axis, so the gap between the
/// curve's end and the line is the variance beyond the plotted range.
///
/// # Errors
/// [`Error::InvalidParameter`] for an output index out of range; quadrature errors.
pub fn output_density_chart(sc: &Scenario, output: usize, opts: &ScenarioPlotOptions) -> Result<LineChart> {
    let conv = opts.convention;
    let OutputDensityCurves {
        output: info,
        density,
        cumulative,
        from_zero,
        whole,
        natural,
    } = output_density_curves(sc, output, conv, opts.points)?;
    let var_unit = squared(&info.unit);
    let fsym = if conv.is_cyclic() { "f" } else { "ω" };
    let mut hlines = Vec::new();
    if let Some(v) = whole {
        hlines.push(Marker::new(v, format!("σ² (whole axis) = {} {var_unit}", num(v))));
    }
    let cum_name = if from_zero {
        format!("cumulative variance σ²({fsym})")
    } else {
        format!(
            "cumulative variance from {fsym} = {} (not integrable at 0)",
            num(cumulative[0].0)
        )
    };
    let mut chart = LineChart::new(
        format!("Output density of {}: {}", info.name, sc.title),
        frequency_label(conv, Domain::Temporal),
        density_label(conv, Domain::Temporal, &info.name.clone(), &info.unit),
    );
    chart.log_x = true;
    chart.log_y = true;
    chart.max_decades = Some(8.0);
    chart
        .series
        .push(Series::line(format!("density of {}", info.name), density));
    chart.secondary = Some(SecondaryAxis {
        y_label: format!("cumulative variance σ²({fsym}) [{var_unit}]"),
        series: vec![Series::dashed(cum_name, cumulative)],
        hlines,
    });
    chart.vlines = natural_frequency_markers(&natural, conv);
    chart.legend = Legend::LowerLeft;
    Ok(chart)
}

fn frequency_label(conv: Convention, domain: Domain) -> String {
    match (conv.is_cyclic(), domain) {
        (true, Domain::Temporal) => "frequency f [Hz]".into(),
        (true, Domain::Spatial) => "spatial frequency n [cycles/m]".into(),
        (false, Domain::Temporal) => "angular frequency ω [rad/s]".into(),
        (false, Domain::Spatial) => "wavenumber Ω [rad/m]".into(),
    }
}

/// A unit for display: `m/s^2` → `m/s²`, `N*s/m` → `N·s/m`.
pub fn unit_text(unit: &str) -> String {
    unit.replace("^-1", "⁻¹")
        .replace("^-2", "⁻²")
        .replace("^2", "²")
        .replace("^3", "³")
        .replace("^4", "⁴")
        .replace('*', "·")
}

/// `u²`, or `(u)²` for a compound unit.
fn squared(unit: &str) -> String {
    let unit = &unit_text(unit);
    if unit.chars().all(|c| c.is_alphanumeric()) {
        format!("{unit}²")
    } else {
        format!("({unit})²")
    }
}

fn density_label(conv: Convention, domain: Domain, what: &str, unit: &str) -> String {
    let x = match (conv.is_cyclic(), domain) {
        (true, Domain::Temporal) => "f",
        (true, Domain::Spatial) => "n",
        (false, Domain::Temporal) => "ω",
        (false, Domain::Spatial) => "Ω",
    };
    let sym = match conv {
        Convention::TwoSidedAngular => format!("S({x}), two-sided"),
        Convention::OneSidedAngular => format!("G({x}), one-sided"),
        Convention::OneSidedCyclic => format!("G({x}), one-sided"),
        Convention::Engineering => format!("Ŝ({x}) = 2πS"),
    };
    let per = match (conv.is_cyclic(), domain) {
        (true, Domain::Temporal) => "Hz",
        (true, Domain::Spatial) => "(cycles/m)",
        (false, Domain::Temporal) => "(rad/s)",
        (false, Domain::Spatial) => "(rad/m)",
    };
    format!("density {sym} of {what} [{}/{per}]", squared(unit))
}

/// Vertical markers at the natural frequencies (already in the convention's frequency), the first one
/// labelled with the whole list.
fn natural_frequency_markers(nat: &[f64], conv: Convention) -> Vec<Marker> {
    let unit = if conv.is_cyclic() { "Hz" } else { "rad/s" };
    let list = nat.iter().map(|f| num(*f)).collect::<Vec<_>>().join(", ");
    nat.iter()
        .enumerate()
        .map(|(k, f)| {
            let label = if k == 0 {
                format!("natural frequencies |λ|: {list} {unit}")
            } else {
                String::new()
            };
            Marker::new(*f, label)
        })
        .collect()
}
