//! Pictures of a Monte Carlo run file (`.h5` written by [`run`](crate::simulate::run())):
//! per output, the Welch estimate with its interval band against the analytic density, and — when the file
//! stores raw realizations — realization excerpts, the histogram of the samples against N(M, σ) and the
//! correlation estimate against the model. Everything is read from the file; the charts are built with
//! [`mc_plots`](super::mc_plots).

use super::chart::{Histogram, LineChart, Series};
use super::mc_plots::{correlation_chart, histogram_chart, realizations_chart, welch_chart};
use crate::error::{Error, Result};
use crate::estimate::time_correlation;
use crate::store::{PsdEstimate, RunFile, SignalGroup};
use std::f64::consts::PI;
use std::path::{Path, PathBuf};

/// Realizations drawn in the excerpt picture.
pub const EXCERPT_REALIZATIONS: usize = 3;
/// Samples per realization drawn in the excerpt picture.
pub const EXCERPT_SAMPLES: usize = 2000;
/// Upper bound on the samples in a histogram: whole realizations are read while their total stays within
/// it (at least one), so a large run does not exhaust memory. The legend-free count is `data.len()`.
pub const MAX_HISTOGRAM_SAMPLES: usize = 4_000_000;
/// Realizations averaged in the correlation estimate (at most).
pub const MAX_CORRELATION_REALIZATIONS: usize = 100;

/// The charts of one output of a run file.
#[derive(Debug, Clone)]
pub struct OutputCharts {
    /// Output name (as in the file).
    pub output: String,
    /// Welch estimate G(f) with its interval band against the analytic density (log–log).
    pub welch: LineChart,
    /// Excerpts of the first realizations (raw data only).
    pub realizations: Option<LineChart>,
    /// Histogram of the samples against N(M, σ) with M ± 3σ (raw data only).
    pub histogram: Option<Histogram>,
    /// Correlation estimate against the model K(τ) from the stored analytic density (raw data only).
    pub correlation: Option<LineChart>,
    /// A nonlinear run's response histogram against route 1's Gaussian and the exact density (linear and
    /// logarithmic density axis; [`super::nonlinear_plots`]); the raw histogram and correlation, whose
    /// references are those of a linear model, are then not drawn.
    pub response_density: Option<(LineChart, LineChart)>,
}

/// The `title` key of the scenario text stored in the file, or `None` if absent or unparsable.
fn scenario_title(text: &str) -> Option<String> {
    let t: toml::Table = toml::from_str(text).ok()?;
    t.get("title")?.as_str().map(|s| s.to_string())
}

/// Model correlation from a two-sided density S(ω) stored on a uniform grid ω_j = jΔω, j ≥ 0.
///
/// # Formula
/// K(τ) = 2 Σ_j w_j S(ω_j) cos(ω_j τ) Δω with w_0 = 1/2 (ω = 0 appears once on the two-sided grid), w_j = 1
/// otherwise: the Riemann sum of K(τ) = ∫ S(ω) e^{iωτ} dω over |ω| ≤ ω_max.
fn cosine_sum(omega: &[f64], s: &[f64], tau: f64) -> f64 {
    let dw = omega[1] - omega[0];
    let mut k = 0.0;
    for (j, (&w, &sv)) in omega.iter().zip(s).enumerate() {
        let wt = if j == 0 && w == 0.0 { 0.5 } else { 1.0 };
        k += wt * sv * (w * tau).cos();
    }
    2.0 * k * dw
}

/// Model correlation K(mΔt), m = 0..=max_lag, of the scenario output `name`, and the frequency step used.
///
/// # Formula
/// K(mΔt) = Σ_{j=0}^{L/2} w_j S_y(ω_j) Δω cos(ω_j mΔt), ω_j = jΔω, Δω = 2π/(LΔt), w_j = 2 except
/// w_0 = w_{L/2} = 1: the two-sided integral ∫ S_y(ω) e^{iωτ} dω over |ω| ≤ π/Δt (the band a record sampled
/// at Δt resolves), evaluated by one inverse real FFT of length L = 2^⌈log₂ max(8N, 2¹⁶)⌉ ≤ 2¹⁸, so the grid
/// is 8× finer than the record's own and resolves narrow density peaks. S_y is the library's analytic output
/// density ([`output_density`](crate::response::output_density)).
fn scenario_correlation(
    sc: &crate::scenario::Scenario,
    name: &str,
    dt: f64,
    n: usize,
    max_lag: usize,
) -> Result<(Vec<f64>, f64)> {
    // a weighted output of `[analysis.comfort]` (`<output>_<W>`) is an output of the system the run
    // simulated: the scenario's system extended by the weighting filters
    let extended;
    let mut sys = sc.model.system.as_ref();
    if !sys.outputs().iter().any(|o| o.name == name) && !sc.analysis.verdicts.is_empty() {
        extended = crate::study::verdict_system(sc)?.0;
        sys = &extended;
    }
    let i = sys
        .outputs()
        .iter()
        .position(|o| o.name == name)
        .ok_or_else(|| Error::invalid("output", name, "not an output of the stored scenario"))?;
    let l = (8 * n)
        .max(1 << 16)
        .next_power_of_two()
        .min(1 << 18)
        .max(2 * (max_lag + 1));
    let dw = 2.0 * PI / (l as f64 * dt);
    let mut spec: Vec<realfft::num_complex::Complex<f64>> = (0..=l / 2)
        .map(|j| {
            let s = crate::response::output_density(sys, &sc.excitation, i, j as f64 * dw);
            realfft::num_complex::Complex::new(s * dw, 0.0)
        })
        .collect();
    let c2r = realfft::RealFftPlanner::<f64>::new().plan_fft_inverse(l);
    let mut k = vec![0.0; l];
    c2r.process(&mut spec, &mut k)
        .map_err(|e| Error::invalid("correlation FFT", l, e.to_string()))?;
    k.truncate(max_lag + 1);
    Ok((k, dw))
}

/// Builds the charts of every output of a run file without rendering them (see [`run_plots`]).
///
/// # Formula
/// Welch picture: one-sided cyclic G(f) = 4π S(ω) at f = ω/(2π) from the stored two-sided S(ω) (estimate,
/// interval and analytic). Histogram: N(M, σ) with M = `@analytic` of `mean` and σ = `@analytic` of `sigma`.
/// Correlation: K̂(mΔt) averaged over realizations ([`time_correlation`] with the known zero mean) against
/// the model K(τ) of the scenario rebuilt from the text stored in the file (see `scenario_correlation`: one
/// inverse FFT of the analytic output density on a grid 8× finer than the record), up to
/// τ_max = min(T/4, 2π/(4Δω_W)) with T the record length and Δω_W the Welch grid step, with the analytic
/// σ² = K(0) marked and, for the spectral route, the variance σ²_d of the simulated FFT-grid process (the
/// `sigma_discrete` statistic) when it differs by more than 0.1 %. If the scenario cannot be rebuilt (a named
/// spectrum missing from the catalogue), the model falls back to K(τ) = 2 Σ S(ω_j) cos(ω_j τ) Δω_W of the
/// stored analytic density (ω = 0 weighted ½), which under-resolves density peaks narrower than Δω_W.
///
/// # Errors
/// Errors of [`RunFile::open`] and its readers; [`RunFile::verify`]'s error naming the damaged dataset of a
/// file whose checksums do not match; [`Error::InvalidParameter`] when an output lacks its density
/// estimate, the analytic density, or the analytic σ, or when the density grid is not uniform.
///
/// # Examples
/// ```no_run
/// use std::path::Path;
/// let charts = stochvib::plot::run_plots::run_charts(Path::new("run.h5"), Path::new("spectra")).unwrap();
/// println!("{}", charts[0].welch.title);
/// ```
pub fn run_charts(path: &Path, spectra_dir: &Path) -> Result<Vec<OutputCharts>> {
    let run = RunFile::open(path)?;
    // every checksum, as `inspect` checks them: a damaged file is an error naming the damaged part
    run.verify()?;
    let meta = run.metadata().clone();
    let scenario = scenario_title(&meta.scenario_text).unwrap_or_else(|| {
        path.file_stem()
            .map(|s| s.to_string_lossy().into_owned())
            .unwrap_or_default()
    });
    // the scenario rebuilt from the stored text gives the model correlation at full resolution; a file whose
    // named spectra are not in the catalogue falls back to the stored (Welch-grid) analytic density
    let model_sc = if meta.store_raw {
        crate::scenario::parse_scenario(&meta.scenario_text, path, spectra_dir).ok()
    } else {
        None
    };
    let psds = run.psd()?;
    let stats = run.statistics()?;
    let response = run.response_histograms()?;
    let mut out = Vec::new();
    for sig in &meta.outputs {
        let name = &sig.name;
        let unit = &sig.unit;
        let title = format!("{scenario}: {name}");
        let quantity = format!("output {name}");
        let psd: &PsdEstimate = psds
            .iter()
            .find(|p| &p.output == name)
            .ok_or_else(|| Error::invalid("output", name, "no density estimate in /psd"))?;
        let analytic = psd
            .analytic
            .as_ref()
            .ok_or_else(|| Error::invalid("output", name, "no analytic density in /psd"))?;
        if psd.omega.len() < 2 || analytic.len() != psd.omega.len() {
            return Err(Error::invalid(
                "psd",
                name,
                "need at least two frequencies and one analytic value per frequency",
            ));
        }
        let f: Vec<f64> = psd.omega.iter().map(|w| w / (2.0 * PI)).collect();
        let g = |v: &[f64]| v.iter().map(|s| 4.0 * PI * s).collect::<Vec<f64>>();
        let ga: Vec<(f64, f64)> = f.iter().cloned().zip(g(analytic)).collect();
        let mut welch = welch_chart(
            &title,
            &f,
            &g(&psd.density),
            &g(&psd.lower),
            &g(&psd.upper),
            psd.confidence,
            &ga,
            &quantity,
            unit,
        )?;
        welch.series[0].name = format!("Welch estimate (ν = {})", crate::numbers::num(psd.dof));
        welch.series[1].name = if response.is_empty() {
            "continuous-time analytic density".into()
        } else {
            "route 1: density of the equivalent linear system (an approximation)".into()
        };
        let response_density = response
            .iter()
            .find(|h| &h.output == name)
            .map(|h| super::nonlinear_plots::histogram_charts(&scenario, h));
        if let Some(e) = &psd.expected {
            let coverage = psd
                .coverage()
                .map(|c| format!(", covered at {} of {} resolved bins", c.covered_resolved, c.resolved))
                .unwrap_or_default();
            welch.series.push(
                Series::line(
                    format!("expected estimate (window ⊛ sampled density{coverage})"),
                    f.iter().cloned().zip(g(e)).collect(),
                )
                .with_color(2)
                .analytic(),
            );
        }
        let (mut realizations, mut histogram, mut correlation) = (None, None, None);
        if meta.store_raw && response.is_empty() {
            let n = meta.n_samples;
            let nr = meta.n_realizations;
            // excerpts
            let ne = EXCERPT_REALIZATIONS.min(nr);
            let m = EXCERPT_SAMPLES.min(n);
            let first = run.read_signals(SignalGroup::Outputs, name, 0..ne)?;
            let t: Vec<f64> = (0..m).map(|k| k as f64 * meta.dt).collect();
            let rows: Vec<(String, Vec<f64>)> = (0..ne)
                .map(|i| {
                    (
                        format!("realization {i}"),
                        first.row(i).iter().take(m).cloned().collect(),
                    )
                })
                .collect();
            let refs: Vec<(&str, &[f64])> = rows.iter().map(|(s, v)| (s.as_str(), &v[..])).collect();
            realizations = Some(realizations_chart(&title, &t, &refs, &quantity, unit)?);
            // histogram
            let st = stats
                .iter()
                .find(|s| &s.output == name)
                .ok_or_else(|| Error::invalid("output", name, "no statistics in /statistics"))?;
            let an = |key: &str| {
                st.statistics
                    .iter()
                    .find(|s| s.name == key)
                    .and_then(|s| s.analytic)
                    .ok_or_else(|| Error::invalid("statistic", key, format!("no @analytic for output {name}")))
            };
            let (mean, sigma) = (an("mean")?, an("sigma")?);
            let nh = (MAX_HISTOGRAM_SAMPLES / n.max(1)).clamp(1, nr);
            let all = run.read_signals(SignalGroup::Outputs, name, 0..nh)?;
            let (data, _) = all.into_raw_vec_and_offset();
            let mut h = histogram_chart(&title, &data, mean, sigma, &quantity, unit, None)?;
            h.x_label = format!("{quantity} [{unit}]");
            h.curves[0].name = format!(
                "{} (analytic σ); {} samples of {nh} realizations",
                h.curves[0].name,
                data.len()
            );
            histogram = Some(h);
            // correlation
            let dw = psd.omega[1] - psd.omega[0];
            let uniform = psd
                .omega
                .windows(2)
                .all(|w| ((w[1] - w[0]) - dw).abs() <= 1e-9 * dw.abs().max(f64::MIN_POSITIVE));
            if dw.is_nan() || dw <= 0.0 || !uniform {
                return Err(Error::invalid("psd", name, "density grid is not uniform in ω"));
            }
            let tau_max = (n as f64 * meta.dt / 4.0).min(2.0 * PI / (4.0 * dw));
            let max_lag = ((tau_max / meta.dt).floor() as usize).clamp(1, n.saturating_sub(1).max(1));
            let nc = MAX_CORRELATION_REALIZATIONS.min(nr);
            let rows = if nc <= nh {
                None
            } else {
                Some(run.read_signals(SignalGroup::Outputs, name, 0..nc)?)
            };
            let mut k = vec![0.0; max_lag + 1];
            for i in 0..nc {
                let x: &[f64] = match &rows {
                    Some(r) => r.row(i).to_slice().unwrap_or(&[]),
                    None => &data[i * n..(i + 1) * n],
                };
                for (a, b) in k.iter_mut().zip(time_correlation(x, max_lag, Some(mean))?) {
                    *a += b / nc as f64;
                }
            }
            let lags: Vec<f64> = (0..=max_lag).map(|m| m as f64 * meta.dt).collect();
            let (model, model_name) = match &model_sc {
                Some(sc) => {
                    let (k, dw_f) = scenario_correlation(sc, name, meta.dt, n, max_lag)?;
                    let label = format!(
                        "model K(τ) = ∫ S_y(ω) cos ωτ dω of the scenario, |ω| ≤ π/Δt, Δω = {} rad/s",
                        crate::numbers::num(dw_f)
                    );
                    (k, label)
                }
                None => (
                    lags.iter().map(|&tau| cosine_sum(&psd.omega, analytic, tau)).collect(),
                    format!(
                        "model K(τ) = 2Σ S(ω_j) cos(ω_j τ) Δω of the stored analytic S(ω), Δω = {} rad/s (scenario \
                         not rebuilt: coarse)",
                        crate::numbers::num(dw)
                    ),
                ),
            };
            let mut c = correlation_chart(&title, &lags, &k, &model, None, &quantity, unit)?;
            c.series[0].name = format!("estimate K̂(τ), mean of {nc} realizations");
            c.series[1].name = model_name;
            c.hlines
                .push(super::chart::Marker::new(sigma * sigma, "analytic σ² = K(0)"));
            // the spectral route simulates the spectrum sampled on its FFT grid: its exact variance (stored as the
            // `sigma_discrete` statistic) is what the estimate converges to; mark it when it differs visibly
            if let Some(sd) = st
                .statistics
                .iter()
                .find(|s| s.name == "sigma_discrete")
                .and_then(|s| s.analytic)
                && (sd * sd - sigma * sigma).abs() > 1e-3 * sigma * sigma
            {
                c.hlines.push(super::chart::Marker::new(
                    sd * sd,
                    "σ²_d of the simulated (FFT-grid) process: what the estimate converges to",
                ));
            }
            correlation = Some(c);
        }
        out.push(OutputCharts {
            output: name.clone(),
            welch,
            realizations,
            histogram,
            correlation,
            response_density,
        });
    }
    Ok(out)
}

/// Writes the pictures of a Monte Carlo run file into `dir` (created if missing), SVG and PNG each:
/// `<output>-welch` always, and `<output>-realizations`, `<output>-histogram`, `<output>-correlation` when
/// the file stores raw realizations, and `<output>-rainflow` for a fatigue channel ([`rainflow_charts`]).
/// Titles name the scenario (its `title`) and the output.
///
/// # Formula
/// As [`run_charts`].
///
/// # Errors
/// As [`run_charts`]; [`Error::Io`] if the directory or a file cannot be written.
///
/// # Examples
/// ```no_run
/// use std::path::Path;
/// let files = stochvib::plot::run_plots(Path::new("run.h5"), Path::new("pictures"), Path::new("spectra")).unwrap();
/// assert!(!files.is_empty());
/// ```
pub fn run_plots(path: &Path, dir: &Path, spectra_dir: &Path) -> Result<Vec<PathBuf>> {
    // a transient run: σ(t) against the exact curve, and the maxima of the mission
    if let Some(files) = super::transient_plots::transient_plots(path, dir)? {
        return Ok(files);
    }
    let mut files = Vec::new();
    for oc in run_charts(path, spectra_dir)? {
        let s = super::chart::file_stem(&oc.output);
        files.extend(oc.welch.render(dir, &format!("{s}-welch"))?);
        if let Some(c) = &oc.realizations {
            files.extend(c.render(dir, &format!("{s}-realizations"))?);
        }
        if let Some(h) = &oc.histogram {
            files.extend(h.render(dir, &format!("{s}-histogram"))?);
        }
        if let Some(c) = &oc.correlation {
            files.extend(c.render(dir, &format!("{s}-correlation"))?);
        }
        if let Some((lin, log)) = &oc.response_density {
            files.extend(lin.render(dir, &format!("{s}-histogram"))?);
            files.extend(log.render(dir, &format!("{s}-histogram-log"))?);
        }
    }
    for c in rainflow_charts(path)? {
        files.extend(c.1.render(dir, &format!("{}-rainflow", super::chart::file_stem(&c.0)))?);
    }
    Ok(files)
}

/// The rainflow range histograms of a run with a fatigue channel (`[analysis.fatigue]`): the Monte Carlo
/// count per realization in each range bin (markers at the bin centres) against Dirlik's expected count from
/// the analytic spectral moments (line), log–log; empty bins are not drawn. One chart per histogram, with
/// the output's name.
///
/// # Formula
/// Dirlik's expected count in bin [r₀, r₁] is ν_p T ∫ p_D(r) dr with p_D Dirlik's range density
/// (Dirlik 1985), as stored in `/rainflow/<output>/dirlik` by the run.
///
/// # Errors
/// As [`RunFile::open`] and [`RunFile::rainflow`] (a damaged histogram fails its checksum).
pub fn rainflow_charts(path: &Path) -> Result<Vec<(String, LineChart)>> {
    let run = RunFile::open(path)?;
    let mut out = Vec::new();
    for h in run.rainflow()? {
        let centre = |j: usize| 0.5 * (h.edges[j] + h.edges[j + 1]);
        let counts: Vec<(f64, f64)> = (0..h.counts.len())
            .filter(|&j| h.counts[j] > 0.0 && centre(j) > 0.0)
            .map(|j| (centre(j), h.counts[j]))
            .collect();
        if counts.is_empty() {
            continue;
        }
        let mut c = LineChart::new(
            format!("Rainflow ranges of {} (per realization)", h.output),
            format!("stress range [{}]", h.unit),
            "cycles per bin",
        );
        c.log_x = true;
        c.log_y = true;
        c.series.push(Series::markers("rainflow count (Monte Carlo)", counts));
        if let Some(d) = &h.dirlik {
            let expected: Vec<(f64, f64)> = (0..d.len())
                .filter(|&j| d[j] > 0.0 && centre(j) > 0.0)
                .map(|j| (centre(j), d[j]))
                .collect();
            if !expected.is_empty() {
                c.series
                    .push(Series::line("Dirlik's expected count (analytic moments)", expected).analytic());
            }
        }
        out.push((h.output.clone(), c));
    }
    Ok(out)
}
