//! Pictures of a nonlinear run (route 2): the response histogram of every output against route 1's Gaussian
//! and, where it exists, the exact (Fokker–Planck) density — on a linear and on a logarithmic density axis
//! (the tails beyond a stop's clearance are where the routes part).

use super::chart::{LineChart, Series};
use crate::store::ResponseHistogram;

/// The two charts (linear and logarithmic density axis) of a response histogram, titled after `title`.
///
/// # Formula
/// The Monte Carlo density n_b/(NΔy) at the bin centres (markers; empty bins left out on the log axis),
/// route 1's N(μ₁, σ₁²) and the exact density p(y) at the same centres (lines), as stored in
/// `/response_histogram/<output>`. On the log axis the curves are drawn down to a hundredth of the smallest
/// Monte Carlo density (one sample in a bin), the resolution of the estimate.
///
/// # Examples
/// ```
/// use stochvib::plot::nonlinear_plots::histogram_charts;
/// use stochvib::store::ResponseHistogram;
/// let h = ResponseHistogram { output: "x".into(), unit: "m".into(), edges: vec![0.0, 1.0, 2.0], density: vec![0.5, 0.5],
///     below: 0.0, above: 0.0, samples: 100.0, gaussian: Some(vec![0.4, 0.4]), exact: None };
/// let (lin, log) = histogram_charts("run", &h);
/// assert_eq!(lin.series.len(), 2);
/// assert!(log.log_y);
/// ```
pub fn histogram_charts(title: &str, h: &ResponseHistogram) -> (LineChart, LineChart) {
    let centres: Vec<f64> = h.edges.windows(2).map(|e| 0.5 * (e[0] + e[1])).collect();
    // one sample in a bin, over a hundred: the floor of the log axis
    let floor = 0.01 / (h.samples.max(1.0) * (h.edges[1] - h.edges[0]));
    let chart = |log: bool| {
        let keep = |v: f64| !log || v > floor;
        let pts = |v: &[f64]| -> Vec<(f64, f64)> {
            centres
                .iter()
                .zip(v)
                .filter(|(_, y)| keep(**y))
                .map(|(x, y)| (*x, *y))
                .collect()
        };
        let mut c = LineChart::new(
            format!(
                "{title}: {} — response density{}",
                h.output,
                if log { " (log)" } else { "" }
            ),
            format!("{} [{}]", h.output, h.unit),
            format!("probability density [{}]", super::style::per_unit(&h.unit)),
        );
        c.log_y = log;
        c.series.push(Series::markers(
            format!(
                "route 2: nonlinear Monte Carlo, {} samples ({:.2e} below, {:.2e} above the range)",
                h.samples, h.below, h.above
            ),
            pts(&h.density),
        ));
        if let Some(g) = &h.gaussian {
            c.series.push(
                Series::line(
                    "route 1: Gaussian of the statistical linearization (approximation)",
                    pts(g),
                )
                .with_color(1),
            );
        }
        if let Some(e) = &h.exact {
            c.series.push(
                Series::line("route 3: exact stationary density (Fokker–Planck)", pts(e))
                    .with_color(2)
                    .analytic(),
            );
        }
        c
    };
    (chart(false), chart(true))
}
