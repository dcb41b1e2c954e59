//! The reference values a route-2 run stores beside its estimates: route 1's Gaussian equivalent (mean, σ,
//! kurtosis 3, Rice's crossing rates, Gaussian regime fractions and rates) and, where it applies, route 3's
//! exact values.

use super::plan::{PlannedOutput, Reference, HISTOGRAM_BINS};
use super::NonlinearRunInput;
use crate::error::Result;
use crate::response::ResponseStatistics;
use crate::store::Signal;
use crate::system::OutputInfo;
use std::f64::consts::PI;

/// What an output's references are built from.
pub(crate) struct OutputRefs {
    /// Route 1's statistics of the output (with route 1's mean), if route 1 converged.
    route1: Option<ResponseStatistics>,
    /// The law that sets the histogram and the records' reference: route 1's, else the linear part's.
    centre: f64,
    sigma: f64,
    /// Route 3: the output is w·q (a displacement of the one coordinate).
    exact_weight: Option<f64>,
    /// Route 3: the output is w·q̇ (a velocity: Gaussian, σ = |w|σ_v, exactly).
    exact_rate_weight: Option<f64>,
}

/// The references of output `r`, or why it is not simulated.
pub(crate) fn output_references(input: &NonlinearRunInput, r: usize) -> std::result::Result<OutputRefs, String> {
    let route1 = input.route1_statistics.map(|s| s[r].clone());
    let (centre, sigma) = match (&route1, input.linear_statistics) {
        (Some(st), _) => (st.mean, st.sigma),
        (None, Some(ls)) => (ls[r].mean, ls[r].sigma),
        (None, None) => (None, None),
    };
    let sigma = sigma.ok_or_else(|| match &route1 {
        Some(st) => format!("route 1's variance {}", st.variance_outcome.describe()),
        None => "no reference variance (route 1 did not converge and the linear part has none)".into(),
    })?;
    let weights = input.route3.and_then(|_| input.model.linear().output_weights(r));
    let zero = |s: &[f64]| s.iter().all(|x| *x == 0.0);
    let only = |own: &[f64], others: [&[f64]; 4]| (own[0] != 0.0 && others.iter().all(|s| zero(s))).then_some(own[0]);
    Ok(OutputRefs {
        route1,
        centre: centre.unwrap_or(0.0),
        sigma,
        exact_weight: weights.and_then(|w| only(w.q, [w.v, w.a, w.u, w.du])),
        exact_rate_weight: weights.and_then(|w| only(w.v, [w.q, w.a, w.u, w.du])),
    })
}

fn gaussian_density(mean: f64, sigma: f64, y: f64) -> f64 {
    let u = (y - mean) / sigma;
    (-0.5 * u * u).exp() / (sigma * (2.0 * PI).sqrt())
}

/// The planned output r: histogram on μ ± 6σ of the reference law, and the references of every statistic.
#[allow(clippy::too_many_arguments)]
pub(crate) fn planned_output(
    input: &NonlinearRunInput,
    r: usize,
    info: &OutputInfo,
    refs: OutputRefs,
    offset: f64,
    acc: Vec<f64>,
    levels: Vec<f64>,
    regimes: Vec<usize>,
) -> Result<PlannedOutput> {
    let (c, s) = (refs.centre, refs.sigma.max(f64::MIN_POSITIVE));
    let lo = c - 6.0 * s;
    let width = 12.0 * s / HISTOGRAM_BINS as f64;
    let centres: Vec<f64> = (0..HISTOGRAM_BINS).map(|b| lo + (b as f64 + 0.5) * width).collect();
    let st3 = input.route3;
    let w3 = refs.exact_weight;
    let r1 = refs.route1.as_ref();
    // a velocity of the one coordinate is exactly Gaussian, N(0, (wσ_v)²)
    let v3 = st3.zip(refs.exact_rate_weight);
    let mut reference = vec![
        Reference {
            route1: r1.and_then(|s| s.mean),
            exact: st3.zip(w3).map(|(st, w)| w * st.mean).or(v3.map(|_| 0.0)),
        },
        Reference {
            route1: r1.and_then(|s| s.sigma),
            exact: st3
                .zip(w3)
                .map(|(st, w)| w.abs() * st.variance.sqrt())
                .or(v3.map(|(st, w)| w.abs() * st.sigma_v)),
        },
        Reference {
            route1: r1.map(|_| 3.0),
            exact: st3.zip(w3).map(|(st, _)| st.kurtosis).or(v3.map(|_| 3.0)),
        },
    ];
    for &a in &levels {
        reference.push(Reference {
            route1: r1.and_then(|s| s.upcrossing_rate(a)),
            exact: st3.zip(w3).map(|(st, w)| st.upcrossing_rate(a / w)),
        });
    }
    for &e in &regimes {
        let g = input.route1.and_then(|r| r.regime(input.model, e));
        let x = match st3 {
            Some(st) => st.regime(e)?,
            None => None,
        };
        reference.push(Reference {
            route1: g.map(|v| v.0),
            exact: x.map(|v| v.0),
        });
        reference.push(Reference {
            route1: g.map(|v| v.1),
            exact: x.map(|v| v.1),
        });
    }
    let gaussian = r1
        .and_then(|s| Some((s.mean?, s.sigma?)))
        .map(|(m, sd)| centres.iter().map(|&y| gaussian_density(m, sd, y)).collect());
    let exact = st3
        .zip(w3)
        .map(|(st, w)| centres.iter().map(|&y| st.density(y / w) / w.abs()).collect());
    Ok(PlannedOutput {
        index: r,
        signal: Signal::new(&info.name, &info.unit),
        centre: c,
        offset,
        acc,
        levels,
        regimes,
        hist_lo: lo,
        hist_width: width,
        reference,
        gaussian,
        exact,
    })
}
