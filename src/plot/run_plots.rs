//! Pictures of a Monte Carlo run file (`.h5` written by [`run`](crate::simulate::run())):
//! per output, the Welch estimate with its interval band against the analytic density, and — when the file
//! stores raw realizations — realization excerpts, the histogram of the samples against N(M, σ) and the
//! correlation estimate against the model. Everything is read from the file; the charts are built with
//! [`mc_plots`](super::mc_plots).

use super::chart::{Histogram, LineChart, Series};
use super::mc_plots::{correlation_chart, histogram_chart, realizations_chart, welch_chart};
use crate::error::{Error, Result};
use crate::estimate::time_correlation;
use crate::scenario::Scenario;
use crate::store::{OutputStatistics, PsdEstimate, RunFile, RunMetadata, SignalGroup};
use crate::study::scenario_curves::model_correlation;
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

/// Builds the charts of every output of a run file without rendering them (see [`run_plots`]).
///
/// # Formula
/// Welch picture: one-sided cyclic G(f) = 4π S(ω) at f = ω/(2π) from the stored two-sided S(ω) (estimate,
/// interval and analytic). Histogram: N(M, σ) with M = `@analytic` of `mean` and σ = `@analytic` of `sigma`.
/// Correlation: K̂(mΔt) averaged over realizations ([`time_correlation`] with the known zero mean) against
/// the model K(τ) of the scenario rebuilt from the text stored in the file ([`model_correlation`]: one
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
        let o = OutputPlot {
            run: &run,
            meta: &meta,
            name: &sig.name,
            unit: &sig.unit,
            title: format!("{scenario}: {}", sig.name),
            quantity: format!("output {}", sig.name),
        };
        let (psd, analytic) = stored_density(&psds, &sig.name)?;
        let welch = o.welch(psd, analytic, response.is_empty())?;
        let response_density = response
            .iter()
            .find(|h| h.output == sig.name)
            .map(|h| super::nonlinear_plots::histogram_charts(&scenario, h));
        let (mut realizations, mut histogram, mut correlation) = (None, None, None);
        if meta.store_raw && response.is_empty() {
            realizations = Some(o.excerpts()?);
            let st = stats
                .iter()
                .find(|s| s.output == sig.name)
                .ok_or_else(|| Error::invalid("output", &sig.name, "no statistics in /statistics"))?;
            let (h, samples) = o.histogram(st)?;
            histogram = Some(h);
            correlation = Some(o.correlation(&samples, psd, analytic, st, model_sc.as_ref())?);
        }
        out.push(OutputCharts {
            output: sig.name.clone(),
            welch,
            realizations,
            histogram,
            correlation,
            response_density,
        });
    }
    Ok(out)
}

/// The Welch estimate of output `name` and the analytic density stored beside it, checked against its grid.
fn stored_density<'a>(psds: &'a [PsdEstimate], name: &str) -> Result<(&'a PsdEstimate, &'a [f64])> {
    let psd = psds
        .iter()
        .find(|p| p.output == name)
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
    Ok((psd, analytic))
}

/// The analytic value of statistic `key` of an output.
fn analytic_statistic(st: &OutputStatistics, key: &str) -> Result<f64> {
    st.statistics
        .iter()
        .find(|s| s.name == key)
        .and_then(|s| s.analytic)
        .ok_or_else(|| Error::invalid("statistic", key, format!("no @analytic for output {}", st.output)))
}

/// The samples the histogram drew from, with the realizations they span.
struct Samples {
    data: Vec<f64>,
    realizations: usize,
    mean: f64,
    sigma: f64,
}

/// One output of a run file and the texts of its charts.
struct OutputPlot<'a> {
    run: &'a RunFile,
    meta: &'a RunMetadata,
    name: &'a str,
    unit: &'a str,
    title: String,
    quantity: String,
}

impl OutputPlot<'_> {
    /// The Welch estimate with its band against the analytic density, and the expected estimate when stored.
    fn welch(&self, psd: &PsdEstimate, analytic: &[f64], linear: bool) -> Result<LineChart> {
        let f: Vec<f64> = psd.omega.iter().map(|w| w / (2.0 * PI)).collect();
        let g = |v: &[f64]| v.iter().map(|s| 4.0 * PI * s).collect::<Vec<f64>>();
        let ga: Vec<(f64, f64)> = f.iter().cloned().zip(g(analytic)).collect();
        let mut welch = welch_chart(
            &self.title,
            &f,
            &g(&psd.density),
            &g(&psd.lower),
            &g(&psd.upper),
            psd.confidence,
            &ga,
            &self.quantity,
            self.unit,
        )?;
        welch.series[0].name = format!("Welch estimate (ν = {})", crate::numbers::num(psd.dof));
        welch.series[1].name = if linear {
            "continuous-time analytic density".into()
        } else {
            "route 1: density of the equivalent linear system (an approximation)".into()
        };
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
        Ok(welch)
    }

    /// Excerpts of the first realizations.
    fn excerpts(&self) -> Result<LineChart> {
        let ne = EXCERPT_REALIZATIONS.min(self.meta.n_realizations);
        let m = EXCERPT_SAMPLES.min(self.meta.n_samples);
        let first = self.run.read_signals(SignalGroup::Outputs, self.name, 0..ne)?;
        let t: Vec<f64> = (0..m).map(|k| k as f64 * self.meta.dt).collect();
        let rows: Vec<(String, Vec<f64>)> = (0..ne)
            .map(|i| {
                (
                    format!("realization {i}"),
                    first.row(i).iter().take(m).cloned().collect(),
                )
            })
            .collect();
        let refs: Vec<(&str, &[f64])> = rows.iter().map(|(s, v)| (s.as_str(), &v[..])).collect();
        realizations_chart(&self.title, &t, &refs, &self.quantity, self.unit)
    }

    /// The histogram of whole realizations (at most [`MAX_HISTOGRAM_SAMPLES`] samples) against N(M, σ)
    /// of the analytic mean and σ, and the samples it drew.
    fn histogram(&self, st: &OutputStatistics) -> Result<(Histogram, Samples)> {
        let (mean, sigma) = (analytic_statistic(st, "mean")?, analytic_statistic(st, "sigma")?);
        let n = self.meta.n_samples;
        let nh = (MAX_HISTOGRAM_SAMPLES / n.max(1)).clamp(1, self.meta.n_realizations);
        let all = self.run.read_signals(SignalGroup::Outputs, self.name, 0..nh)?;
        let (data, _) = all.into_raw_vec_and_offset();
        let mut h = histogram_chart(&self.title, &data, mean, sigma, &self.quantity, self.unit, None)?;
        h.x_label = format!("{} [{}]", self.quantity, self.unit);
        h.curves[0].name = format!(
            "{} (analytic σ); {} samples of {nh} realizations",
            h.curves[0].name,
            data.len()
        );
        let samples = Samples {
            data,
            realizations: nh,
            mean,
            sigma,
        };
        Ok((h, samples))
    }

    /// The correlation estimate averaged over realizations against the model (see [`run_charts`]).
    fn correlation(
        &self,
        samples: &Samples,
        psd: &PsdEstimate,
        analytic: &[f64],
        st: &OutputStatistics,
        model_sc: Option<&Scenario>,
    ) -> Result<LineChart> {
        let (n, dt) = (self.meta.n_samples, self.meta.dt);
        let dw = uniform_step(&psd.omega, self.name)?;
        let tau_max = (n as f64 * dt / 4.0).min(2.0 * PI / (4.0 * dw));
        let max_lag = ((tau_max / dt).floor() as usize).clamp(1, n.saturating_sub(1).max(1));
        let (k, nc) = self.estimated_correlation(samples, max_lag)?;
        let lags: Vec<f64> = (0..=max_lag).map(|m| m as f64 * dt).collect();
        let (model, model_name) = match model_sc {
            Some(sc) => {
                let (k, dw_f) = model_correlation(sc, self.name, dt, n, max_lag)?;
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
        let mut c = correlation_chart(&self.title, &lags, &k, &model, None, &self.quantity, self.unit)?;
        c.series[0].name = format!("estimate K̂(τ), mean of {nc} realizations");
        c.series[1].name = model_name;
        let sigma = samples.sigma;
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
        Ok(c)
    }

    /// K̂(mΔt), m = 0..=max_lag, averaged over the first [`MAX_CORRELATION_REALIZATIONS`] realizations
    /// (reusing the histogram's samples where they cover them), and the count averaged.
    fn estimated_correlation(&self, samples: &Samples, max_lag: usize) -> Result<(Vec<f64>, usize)> {
        let n = self.meta.n_samples;
        let nc = MAX_CORRELATION_REALIZATIONS.min(self.meta.n_realizations);
        let rows = if nc <= samples.realizations {
            None
        } else {
            Some(self.run.read_signals(SignalGroup::Outputs, self.name, 0..nc)?)
        };
        let mut k = vec![0.0; max_lag + 1];
        for i in 0..nc {
            let x: &[f64] = match &rows {
                Some(r) => r.row(i).to_slice().unwrap_or(&[]),
                None => &samples.data[i * n..(i + 1) * n],
            };
            for (a, b) in k.iter_mut().zip(time_correlation(x, max_lag, Some(samples.mean))?) {
                *a += b / nc as f64;
            }
        }
        Ok((k, nc))
    }
}

/// The step Δω of a density grid, which must be uniform.
fn uniform_step(omega: &[f64], name: &str) -> Result<f64> {
    let dw = omega[1] - omega[0];
    let uniform = omega
        .windows(2)
        .all(|w| ((w[1] - w[0]) - dw).abs() <= 1e-9 * dw.abs().max(f64::MIN_POSITIVE));
    if dw.is_nan() || dw <= 0.0 || !uniform {
        return Err(Error::invalid("psd", name, "density grid is not uniform in ω"));
    }
    Ok(dw)
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
