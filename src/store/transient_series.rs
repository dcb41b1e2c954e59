//! The `/transient` group of a run file: the time series of Monte Carlo statistics of a non-stationary run
//! beside the exact curves, and the per-realization maxima of the mission with the analytic distributions
//! (layout: `docs/transients.md`, "The `/transient` group of a run file").

use super::checksum::Crc32;
use super::reader::{attr_scalar, attr_string, damaged};
use super::writer::{write_scalar_attr, write_str_attr};
use super::{h5err, RunFile, RunWriter};
use crate::error::{Error, Result};
use hdf5::Group;
use std::path::Path;

/// Group of the transient series.
pub const GROUP_TRANSIENT: &str = "transient";

/// The names of the per-output datasets, in the order of [`TransientOutput::arrays`].
pub const SERIES_DATASETS: [&str; 8] = [
    "mean",
    "mean_lower",
    "mean_upper",
    "sigma",
    "sigma_lower",
    "sigma_upper",
    "exact_mean",
    "exact_sigma",
];

/// The names of the maxima datasets, in the order of [`TransientOutput::maxima_arrays`].
pub const MAXIMA_DATASETS: [&str; 7] = [
    "max_y",
    "max_abs_y",
    "levels",
    "cdf_max_y_rice",
    "cdf_max_abs_y_rice",
    "cdf_max_y_vanmarcke",
    "cdf_max_abs_y_vanmarcke",
];

/// One output's series (every vector indexed like [`TransientSeries::times`]) and its mission maxima.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct TransientOutput {
    /// Output name (as in the run's outputs).
    pub output: String,
    /// Unit.
    pub unit: String,
    /// Ensemble mean and its Student-t interval.
    pub mean: Vec<f64>,
    /// Lower end.
    pub mean_lower: Vec<f64>,
    /// Upper end.
    pub mean_upper: Vec<f64>,
    /// Ensemble σ and its χ² interval.
    pub sigma: Vec<f64>,
    /// Lower end.
    pub sigma_lower: Vec<f64>,
    /// Upper end.
    pub sigma_upper: Vec<f64>,
    /// The exact route's mean.
    pub exact_mean: Vec<f64>,
    /// The exact route's σ.
    pub exact_sigma: Vec<f64>,
    /// max y of every realization, ascending.
    pub max_y: Vec<f64>,
    /// max |y| of every realization, ascending.
    pub max_abs_y: Vec<f64>,
    /// Levels b of the analytic distributions of the maxima.
    pub levels: Vec<f64>,
    /// P(max y ≤ b) by Poisson crossings at the integrated exact Rice rate.
    pub cdf_max_y_rice: Vec<f64>,
    /// P(max |y| ≤ b), the same.
    pub cdf_max_abs_y_rice: Vec<f64>,
    /// P(max y ≤ b) by Vanmarcke (1975) (stationary runs only; NaN otherwise).
    pub cdf_max_y_vanmarcke: Vec<f64>,
    /// P(max |y| ≤ b) by Vanmarcke (1975), the same.
    pub cdf_max_abs_y_vanmarcke: Vec<f64>,
}

/// The `/transient` group.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct TransientSeries {
    /// Stored times, s.
    pub times: Vec<f64>,
    /// Confidence of the intervals.
    pub confidence: f64,
    /// Half-width ε of the DKW band of the maxima' empirical distributions at `confidence`.
    pub dkw_epsilon: f64,
    /// How the exact curves were computed (route, tolerance, error estimate).
    pub exact_method: String,
    /// Per output.
    pub outputs: Vec<TransientOutput>,
}

impl TransientOutput {
    /// The time series, in the order of [`SERIES_DATASETS`].
    pub fn arrays(&self) -> [&Vec<f64>; 8] {
        [
            &self.mean,
            &self.mean_lower,
            &self.mean_upper,
            &self.sigma,
            &self.sigma_lower,
            &self.sigma_upper,
            &self.exact_mean,
            &self.exact_sigma,
        ]
    }

    /// The maxima and distributions, in the order of [`MAXIMA_DATASETS`].
    pub fn maxima_arrays(&self) -> [&Vec<f64>; 7] {
        [
            &self.max_y,
            &self.max_abs_y,
            &self.levels,
            &self.cdf_max_y_rice,
            &self.cdf_max_abs_y_rice,
            &self.cdf_max_y_vanmarcke,
            &self.cdf_max_abs_y_vanmarcke,
        ]
    }

    /// CRC-32 of every array (lengths included) and the unit (stored as the group's `@crc32`).
    pub fn checksum(&self) -> u32 {
        let mut c = Crc32::default();
        for a in self.arrays().into_iter().chain(self.maxima_arrays()) {
            c.update_f64(&[a.len() as f64]);
            c.update_f64(a);
        }
        c.update(self.unit.as_bytes());
        c.finish()
    }

    fn from_arrays(output: &str, unit: String, s: Vec<Vec<f64>>, m: Vec<Vec<f64>>) -> Self {
        let mut s = s.into_iter();
        let mut m = m.into_iter();
        let next = |it: &mut std::vec::IntoIter<Vec<f64>>| it.next().unwrap_or_default();
        TransientOutput {
            output: output.to_string(),
            unit,
            mean: next(&mut s),
            mean_lower: next(&mut s),
            mean_upper: next(&mut s),
            sigma: next(&mut s),
            sigma_lower: next(&mut s),
            sigma_upper: next(&mut s),
            exact_mean: next(&mut s),
            exact_sigma: next(&mut s),
            max_y: next(&mut m),
            max_abs_y: next(&mut m),
            levels: next(&mut m),
            cdf_max_y_rice: next(&mut m),
            cdf_max_abs_y_rice: next(&mut m),
            cdf_max_y_vanmarcke: next(&mut m),
            cdf_max_abs_y_vanmarcke: next(&mut m),
        }
    }
}

fn write_group(g: &Group, o: &TransientOutput) -> hdf5::Result<()> {
    write_str_attr(g, "unit", &o.unit)?;
    write_scalar_attr(g, "crc32", o.checksum())?;
    for (name, a) in SERIES_DATASETS.iter().zip(o.arrays()) {
        g.new_dataset_builder().with_data(a.as_slice()).create(*name)?;
    }
    for (name, a) in MAXIMA_DATASETS.iter().zip(o.maxima_arrays()) {
        g.new_dataset_builder().with_data(a.as_slice()).create(*name)?;
    }
    Ok(())
}

impl RunWriter {
    /// Writes the `/transient` group (replacing one already there).
    ///
    /// # Errors
    /// An output that is not one of the run's, series of another length than the times; HDF5 failures.
    pub fn write_transient(&mut self, s: &TransientSeries) -> Result<()> {
        let names: Vec<String> = self.metadata().outputs.iter().map(|o| o.name.clone()).collect();
        for o in &s.outputs {
            if !names.contains(&o.output) {
                return Err(Error::invalid(
                    "transient output",
                    &o.output,
                    "not an output of this run",
                ));
            }
            if o.arrays().iter().any(|a| a.len() != s.times.len()) {
                return Err(Error::invalid(
                    "transient series",
                    &o.output,
                    "every series has one value per stored time",
                ));
            }
        }
        let (file, path) = self.h5();
        let e = |what: &str| h5err(path, what);
        if file.link_exists(GROUP_TRANSIENT) {
            file.unlink(GROUP_TRANSIENT).map_err(e("replacing /transient"))?;
        }
        let g = file.create_group(GROUP_TRANSIENT).map_err(e("creating /transient"))?;
        let w = || -> hdf5::Result<()> {
            write_scalar_attr(&g, "confidence", s.confidence)?;
            write_scalar_attr(&g, "dkw_epsilon", s.dkw_epsilon)?;
            write_str_attr(&g, "exact_method", &s.exact_method)?;
            write_scalar_attr(&g, "times_crc32", super::checksum::crc32_f64(&s.times))?;
            g.new_dataset_builder().with_data(s.times.as_slice()).create("time")?;
            for o in &s.outputs {
                write_group(&g.create_group(&o.output)?, o)?;
            }
            Ok(())
        };
        w().map_err(e("writing /transient"))?;
        file.flush().map_err(e("flushing /transient"))
    }
}

fn read_f64(g: &Group, name: &str, p: &Path) -> Result<Vec<f64>> {
    g.dataset(name)
        .and_then(|d| d.read_raw::<f64>())
        .map_err(h5err(p, &format!("reading transient/{name}")))
}

impl RunFile {
    /// The `/transient` group, if the run is a transient run; every array checked against its `@crc32`.
    ///
    /// # Errors
    /// A malformed group or a checksum mismatch (a damaged file).
    pub fn transient(&self) -> Result<Option<TransientSeries>> {
        let (file, p) = (self.h5(), self.path());
        if !file.link_exists(GROUP_TRANSIENT) {
            return Ok(None);
        }
        let g = file.group(GROUP_TRANSIENT).map_err(h5err(p, "opening /transient"))?;
        let times = read_f64(&g, "time", p)?;
        if attr_scalar::<u32>(&g, "times_crc32", p)? != super::checksum::crc32_f64(&times) {
            return Err(damaged(p, "transient/time"));
        }
        let mut outputs = Vec::new();
        for sig in &self.metadata().outputs {
            if !g.link_exists(&sig.name) {
                continue;
            }
            let og = g.group(&sig.name).map_err(h5err(p, "opening a transient group"))?;
            let series = SERIES_DATASETS
                .iter()
                .map(|n| read_f64(&og, n, p))
                .collect::<Result<_>>()?;
            let maxima = MAXIMA_DATASETS
                .iter()
                .map(|n| read_f64(&og, n, p))
                .collect::<Result<_>>()?;
            let o = TransientOutput::from_arrays(&sig.name, attr_string(&og, "unit", p)?, series, maxima);
            if attr_scalar::<u32>(&og, "crc32", p)? != o.checksum() {
                return Err(damaged(p, &format!("transient/{}", sig.name)));
            }
            outputs.push(o);
        }
        Ok(Some(TransientSeries {
            times,
            confidence: attr_scalar(&g, "confidence", p)?,
            dkw_epsilon: attr_scalar(&g, "dkw_epsilon", p)?,
            exact_method: attr_string(&g, "exact_method", p)?,
            outputs,
        }))
    }
}
