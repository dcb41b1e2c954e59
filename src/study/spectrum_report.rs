//! The `stochvib spectrum` report: variance two ways, correlation at a few lags, density at a few
//! frequencies in a chosen convention, as computed; [`crate::report::spectrum_text`] prints it.

use crate::error::{Error, Result};
use crate::numbers::rel_diff;
use crate::scenario::SpectrumFile;
use crate::spectrum::{numeric, Convention, Spectrum};
use serde::Serialize;

/// A value or the reason there is none (divergent, failed).
#[derive(Debug, Clone, Serialize)]
#[serde(untagged)]
pub enum Outcome {
    /// A number.
    Value(f64),
    /// Why there is no number.
    NoValue {
        /// The reason.
        error: String,
    },
}

impl From<Result<f64>> for Outcome {
    fn from(r: Result<f64>) -> Self {
        match r {
            Ok(v) if v.is_finite() => Outcome::Value(v),
            Ok(v) => Outcome::NoValue {
                error: format!("the value is not a finite number ({v}) in f64 arithmetic"),
            },
            Err(e) => Outcome::NoValue { error: e.to_string() },
        }
    }
}

/// Report on one spectrum.
#[derive(Debug, Clone, Serialize)]
pub struct SpectrumReport {
    /// Name of the spectrum.
    pub name: String,
    /// Its description with parameters.
    pub model: String,
    /// Provenance of the parameters.
    pub source: String,
    /// `temporal` or `spatial`.
    pub domain: String,
    /// SI unit of the process.
    pub unit: String,
    /// Variance from the model (closed form where one exists).
    pub variance: Outcome,
    /// Variance by adaptive quadrature of the density.
    pub variance_quadrature: Outcome,
    /// Quadrature error estimate.
    pub variance_quadrature_error: Option<f64>,
    /// Relative difference of the two variances.
    pub variance_rel_diff: Option<f64>,
    /// Standard deviation √D.
    pub sigma: Outcome,
    /// Convention of the density table.
    pub convention: Convention,
    /// Unit of the density table's abscissa.
    pub abscissa_unit: String,
    /// (lag, K model, K by quadrature).
    pub correlation: Vec<(f64, Outcome, Outcome)>,
    /// (abscissa in the convention, density in the convention).
    pub density: Vec<(f64, f64)>,
}

/// Where `stochvib spectrum` evaluates the density.
#[derive(Debug, Clone, PartialEq)]
pub enum DensityPoints {
    /// Five points around the spectrum's characteristic frequency (0.1, 0.3, 1, 3, 10 times it).
    Characteristic,
    /// Angular frequencies: rad/s for a temporal spectrum, rad/m for a spatial one.
    Angular(Vec<f64>),
    /// Cyclic frequencies: Hz for a temporal spectrum, cycles/m for a spatial one.
    Cyclic(Vec<f64>),
}

impl DensityPoints {
    /// Checks the points before a report is built at them.
    ///
    /// # Errors
    /// [`Error::InvalidParameter`] named `omega` or `frequency` for a point that is negative or not finite,
    /// or a cyclic frequency whose angular frequency 2πf is not finite (f above about 2.9·10³⁰⁷), which the
    /// report would print as `inf`.
    ///
    /// # Examples
    /// ```
    /// use stochvib::study::DensityPoints;
    /// assert!(DensityPoints::Cyclic(vec![0.5, 2.0]).check().is_ok());
    /// let e = DensityPoints::Cyclic(vec![1e308]).check().unwrap_err().to_string();
    /// assert!(e.contains("`frequency`") && e.contains("2πf"), "{e}");
    /// assert!(DensityPoints::Angular(vec![-1.0]).check().is_err());
    /// ```
    pub fn check(&self) -> Result<()> {
        let (name, points, scale) = match self {
            DensityPoints::Characteristic => return Ok(()),
            DensityPoints::Angular(w) => ("omega", w, 1.0),
            DensityPoints::Cyclic(f) => ("frequency", f, std::f64::consts::TAU),
        };
        for &x in points {
            if !(x.is_finite() && x >= 0.0) {
                return Err(Error::invalid(name, x, "frequencies must be finite and >= 0"));
            }
            if !(scale * x).is_finite() {
                return Err(Error::invalid(
                    name,
                    x,
                    "too large: its angular frequency 2πf is not a finite number",
                ));
            }
        }
        Ok(())
    }
}

/// Builds the report for `file`, with the density written in `convention` at five characteristic points.
pub fn spectrum_report(file: &SpectrumFile, convention: Convention) -> SpectrumReport {
    spectrum_report_at(file, convention, &DensityPoints::Characteristic)
}

/// Builds the report for `file`, with the density written in `convention` at `points`. The abscissa is
/// printed in the convention's own unit (Hz or cycles/m for the cyclic convention, rad/s or rad/m
/// otherwise), whichever unit the points were given in. Points from a user are checked first with
/// [`DensityPoints::check`] (as `stochvib spectrum` does): a negative, non-finite or overflowing point
/// would be reported as it is, a density at ω = inf or NaN.
pub fn spectrum_report_at(file: &SpectrumFile, convention: Convention, points: &DensityPoints) -> SpectrumReport {
    let s = file.spectrum.as_ref();
    let variance: Outcome = s.variance().into();
    let quad = numeric::variance(s);
    let (variance_quadrature, variance_quadrature_error) = match &quad {
        Ok(q) => (Outcome::Value(q.value), Some(q.abs_error)),
        Err(e) => (Outcome::NoValue { error: e.to_string() }, None),
    };
    let variance_rel_diff = match (&variance, &quad) {
        (Outcome::Value(a), Ok(q)) => Some(rel_diff(*a, q.value)),
        _ => None,
    };
    let sigma = match &variance {
        Outcome::Value(v) => Outcome::Value(v.sqrt()),
        Outcome::NoValue { error } => Outcome::NoValue { error: error.clone() },
    };
    let wc = characteristic_frequency(s);
    let correlation = [0.0, 0.25, 0.5, 1.0, 2.0, 4.0]
        .iter()
        .map(|k| {
            let tau = k / wc;
            (
                tau,
                s.correlation(tau).into(),
                numeric::correlation(s, tau).map(|r| r.value).into(),
            )
        })
        .collect();
    let omegas: Vec<f64> = match points {
        DensityPoints::Characteristic => [0.1, 0.3, 1.0, 3.0, 10.0].iter().map(|k| k * wc).collect(),
        DensityPoints::Angular(w) => w.clone(),
        DensityPoints::Cyclic(f) => f.iter().map(|f| 2.0 * std::f64::consts::PI * f).collect(),
    };
    // The same batch path as every other caller of a density table (the Python package included),
    // so a value printed here is bit-identical to the one an array evaluation returns.
    let mut canonical = vec![0.0; omegas.len()];
    s.density_into(&omegas, &mut canonical);
    let density = omegas
        .iter()
        .zip(&canonical)
        .map(|(&w, &v)| convention.from_canonical(w, v))
        .collect();
    let abscissa_unit = if convention.is_cyclic() {
        s.domain().cyclic_unit()
    } else {
        s.domain().angular_unit()
    }
    .to_string();
    SpectrumReport {
        name: file.name.clone(),
        model: s.describe(),
        source: file.source.clone(),
        domain: format!("{:?}", s.domain()).to_lowercase(),
        unit: file.unit.clone(),
        variance,
        variance_quadrature,
        variance_quadrature_error,
        variance_rel_diff,
        sigma,
        convention,
        abscissa_unit,
        correlation,
        density,
    }
}

/// A frequency that sets the scale of the table: the geometric mean of the breakpoints, else the middle
/// of the support, else 1.
fn characteristic_frequency(s: &dyn Spectrum) -> f64 {
    let b: Vec<f64> = s
        .breakpoints()
        .into_iter()
        .filter(|w| *w > 0.0 && w.is_finite())
        .collect();
    if !b.is_empty() {
        return (b.iter().map(|w| w.ln()).sum::<f64>() / b.len() as f64).exp();
    }
    let (lo, hi) = s.support();
    if hi.is_finite() && lo > 0.0 {
        (lo * hi).sqrt()
    } else if hi.is_finite() {
        hi / 2.0
    } else {
        1.0
    }
}
