//! The picture of a Pareto front (`stochvib optimize --pareto Q --points N --plots DIR`): the second
//! quantity against the first, one marker per point of the table, the points joined in the table's order.

use super::chart::{LineChart, Series};
use crate::optimize::ParetoFront;

/// The chart of `front`, titled after `title` (the scenario's): x the first quantity, y the second, both in
/// their SI units; the feasible points as markers joined by a line (the front), any infeasible point (an
/// ε-limit the search could not meet) as a marker of its own. The points are the table's values
/// ([`ParetoFront::to_csv`]) unchanged.
///
/// # Examples
/// ```
/// use stochvib::optimize::{ParetoFront, ParetoPoint};
/// use stochvib::plot::pareto_plots::pareto_chart;
/// let p = |a: f64, b: f64| ParetoPoint { params: vec![a], values: [a, b], limit: None, feasible: true };
/// let front = ParetoFront {
///     keys: vec!["model.c".into()],
///     quantities: ["sigma(a)".into(), "sigma(t)".into()],
///     units: ["m/s^2".into(), "m".into()],
///     points: vec![p(1.0, 0.03), p(1.2, 0.02)],
///     evaluations: 10,
/// };
/// let chart = pareto_chart("quarter car", &front);
/// assert_eq!(chart.series[0].points, vec![(1.0, 0.03), (1.2, 0.02)]);
/// ```
pub fn pareto_chart(title: &str, front: &ParetoFront) -> LineChart {
    let [q1, q2] = &front.quantities;
    let [u1, u2] = &front.units;
    let mut chart = LineChart::new(
        format!("{title}: Pareto front of {q1} and {q2}"),
        format!("{q1} [{u1}]"),
        format!("{q2} [{u2}]"),
    );
    let pts = |feasible: bool| -> Vec<(f64, f64)> {
        front
            .points
            .iter()
            .filter(|p| p.feasible == feasible)
            .map(|p| (p.values[0], p.values[1]))
            .collect()
    };
    let keys = front.keys.join(", ");
    chart.series.push(Series::markers(
        format!("{} points (ε-constraint method over {keys})", pts(true).len()),
        pts(true),
    ));
    chart
        .series
        .push(Series::line("the front, in the table's order", pts(true)).with_color(0));
    let missed = pts(false);
    if !missed.is_empty() {
        chart
            .series
            .push(Series::markers(format!("{} points whose ε-limit was not met", missed.len()), missed).with_color(5));
    }
    chart
}
