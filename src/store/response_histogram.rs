//! The response histogram of an output of a nonlinear run, as stored under `/response_histogram/<output>`
//! (an optional group: only runs of models with nonlinear elements have it).

use super::layout as L;
use super::{checksum, h5err, Error, Result};
use std::path::Path;

/// The density of an output over all realizations on fixed bins, with the reference densities at the bin
/// centres.
///
/// # Formula
/// density_b = n_b/(N Δy) with n_b the samples in bin b of width Δy, N all samples counted (including those
/// outside the bins: `below`, `above` are their fractions).
///
/// # Examples
/// ```
/// use stochvib::store::ResponseHistogram;
/// let h = ResponseHistogram { output: "x".into(), unit: "m".into(), edges: vec![0.0, 1.0], density: vec![1.0],
///     below: 0.0, above: 0.0, samples: 10.0, gaussian: None, exact: None };
/// assert_ne!(h.checksum(), 0);
/// ```
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct ResponseHistogram {
    /// Run output.
    pub output: String,
    /// Unit of the output.
    pub unit: String,
    /// The bins + 1 edges.
    pub edges: Vec<f64>,
    /// Monte Carlo density per bin (1/unit).
    pub density: Vec<f64>,
    /// Fraction of the samples below the first edge.
    pub below: f64,
    /// Fraction of the samples above the last edge.
    pub above: f64,
    /// Samples counted.
    pub samples: f64,
    /// Route 1's Gaussian density at the bin centres, if route 1 converged.
    pub gaussian: Option<Vec<f64>>,
    /// The exact (route 3) density at the bin centres, where it exists.
    pub exact: Option<Vec<f64>>,
}

impl ResponseHistogram {
    /// CRC-32 of the values and texts (stored as `@crc32`).
    pub fn checksum(&self) -> u32 {
        let mut c = checksum::Crc32::default();
        c.update_f64(&self.edges);
        c.update_f64(&self.density);
        c.update_f64(&[self.below, self.above, self.samples]);
        for (tag, d) in [(b"gaussian", &self.gaussian), (b"exact...", &self.exact)] {
            if let Some(d) = d {
                c.update(tag);
                c.update_f64(d);
            }
        }
        for s in [&self.output, &self.unit] {
            c.update(s.as_bytes());
            c.update(&[0]);
        }
        c.finish()
    }

    /// Writes the histogram under `parent/<output>` (replacing an existing one).
    pub(crate) fn write(&self, parent: &hdf5::Group, path: &Path) -> Result<()> {
        let e = |what: &str| h5err(path, what);
        if parent.link_exists(&self.output) {
            parent
                .unlink(&self.output)
                .map_err(e("replacing a response histogram"))?;
        }
        let g = parent
            .create_group(&self.output)
            .map_err(e("creating a response histogram"))?;
        let w = || -> hdf5::Result<()> {
            super::writer::write_str_attr(&g, L::ATTR_UNIT, &self.unit)?;
            for (name, v) in [
                (L::ATTR_BELOW, self.below),
                (L::ATTR_ABOVE, self.above),
                (L::ATTR_SAMPLES, self.samples),
            ] {
                super::writer::write_scalar_attr(&g, name, v)?;
            }
            super::writer::write_scalar_attr(&g, L::ATTR_CRC32, self.checksum())?;
            g.new_dataset_builder()
                .with_data(self.edges.as_slice())
                .create(L::DS_EDGES)?;
            g.new_dataset_builder()
                .with_data(self.density.as_slice())
                .create(L::DS_DENSITY)?;
            for (name, d) in [(L::DS_GAUSSIAN, &self.gaussian), (L::DS_EXACT, &self.exact)] {
                if let Some(d) = d {
                    g.new_dataset_builder().with_data(d.as_slice()).create(name)?;
                }
            }
            Ok(())
        };
        w().map_err(e("writing a response histogram"))
    }

    /// Reads the histogram of `output` from `g`, checked against its `@crc32`.
    pub(crate) fn read(g: &hdf5::Group, output: &str, path: &Path) -> Result<ResponseHistogram> {
        let read = |name: &str| -> Result<Vec<f64>> {
            g.dataset(name)
                .and_then(|d| d.read_raw::<f64>())
                .map_err(h5err(path, &format!("reading response_histogram/{output}/{name}")))
        };
        let opt = |name: &str| -> Result<Option<Vec<f64>>> {
            if g.link_exists(name) {
                read(name).map(Some)
            } else {
                Ok(None)
            }
        };
        let scalar = |name: &str| -> Result<f64> {
            g.attr(name)
                .and_then(|a| a.read_scalar::<f64>())
                .map_err(h5err(path, &format!("reading response_histogram/{output}/@{name}")))
        };
        let unit = g
            .attr(L::ATTR_UNIT)
            .and_then(|a| a.read_scalar::<hdf5::types::VarLenUnicode>())
            .map_err(h5err(path, "reading a response histogram's unit"))?
            .to_string();
        let h = ResponseHistogram {
            output: output.to_string(),
            unit,
            edges: read(L::DS_EDGES)?,
            density: read(L::DS_DENSITY)?,
            below: scalar(L::ATTR_BELOW)?,
            above: scalar(L::ATTR_ABOVE)?,
            samples: scalar(L::ATTR_SAMPLES)?,
            gaussian: opt(L::DS_GAUSSIAN)?,
            exact: opt(L::DS_EXACT)?,
        };
        let crc = g
            .attr(L::ATTR_CRC32)
            .and_then(|a| a.read_scalar::<u32>())
            .map_err(h5err(path, "reading a response histogram's checksum"))?;
        if crc != h.checksum() || h.edges.len() != h.density.len() + 1 {
            return Err(Error::Hdf5 {
                path: path.to_path_buf(),
                reason: format!("response_histogram/{output} does not match its checksum: the file is damaged"),
            });
        }
        Ok(h)
    }
}
