//! The HDF5 form of a parameter study's table (layout in [`sweep_table`](super::sweep_table)'s module docs),
//! written block by block: every dataset is created at its final length when the file is opened, each block
//! of points goes into its rows as it comes, and the failed points' messages are written last. A whole
//! table is one block ([`SweepResults::write`]); `stochvib sweep` streams its blocks while the next ones
//! are evaluated ([`write_sweep_table`](super::write_sweep_table)).

use super::sweep_table::{OutputValues, SweepIdentity, SweepResults};
use crate::error::{Error, Result};
use crate::store::{h5err as h5, open_sec2, OpenMode};
use hdf5::types::VarLenUnicode;
use std::ops::Range;
use std::path::{Path, PathBuf};

/// The exact statistics' columns of every output, in the file's order ([`exact_columns`]' order).
const EXACT_COLUMNS: [&str; 7] = [
    "mean",
    "variance",
    "sigma",
    "lower_3sigma",
    "upper_3sigma",
    "lambda2",
    "zero_upcrossing_rate",
];

/// The Monte Carlo columns (with a batch per point; [`mc_row`]'s order).
const MC_COLUMNS: [&str; 3] = ["mc_sigma", "mc_lower", "mc_upper"];

/// The exact statistics' columns of `rows` rows of one output whose stored values (mean, variance, λ₂; NaN
/// where a value does not exist) the caller has copied into theirs: the derived ones computed column by
/// column ([`derived_columns`]).
fn exact_columns(cols: &mut [&mut [f64]], rows: usize) {
    let [mean, variance, sigma, lower, upper, lambda2, rate] = cols else {
        unreachable!("an output has {} exact columns", EXACT_COLUMNS.len())
    };
    derived_columns(
        (&mean[..rows], &variance[..rows], &lambda2[..rows]),
        [
            &mut sigma[..rows],
            &mut lower[..rows],
            &mut upper[..rows],
            &mut rate[..rows],
        ],
    );
}

/// Row r's stored exact values (mean, variance, λ₂; NaN where a value does not exist) into an output's
/// exact columns ([`EXACT_COLUMNS`] first in `cols`).
#[inline]
fn stored_values(cols: &mut [&mut [f64]], r: usize, v: &OutputValues) {
    let [mean, variance, _, _, _, lambda2, _] = &mut cols[..EXACT_COLUMNS.len()] else {
        unreachable!("an output has {} exact columns", EXACT_COLUMNS.len())
    };
    mean[r] = v.mean.unwrap_or(f64::NAN);
    variance[r] = v.variance.unwrap_or(f64::NAN);
    lambda2[r] = v.lambda2.unwrap_or(f64::NAN);
}

/// σ, M ∓ 3σ and ν₀⁺ of each row from its (mean, variance, λ₂) (NaN for a missing value), column by column
/// so that the square roots and divisions run on vectors. Each value is the same operations in the same
/// order as [`PointStatistics::sigma`](crate::response::PointStatistics::sigma),
/// [`bounds(3.0)`](crate::response::PointStatistics::bounds) and
/// [`zero_upcrossing_rate`](crate::response::PointStatistics::zero_upcrossing_rate), so the same bits: a
/// missing mean, variance or λ₂ is a NaN operand, which gives a NaN result, and ν₀⁺ is NaN where the
/// variance is not positive.
fn derived_columns((mean, variance, lambda2): (&[f64], &[f64], &[f64]), out: [&mut [f64]; 4]) {
    let [sigma, lower, upper, rate] = out;
    for (s, v) in sigma.iter_mut().zip(variance) {
        *s = v.sqrt();
    }
    for ((lo, hi), (m, s)) in lower
        .iter_mut()
        .zip(upper.iter_mut())
        .zip(mean.iter().zip(sigma.iter()))
    {
        (*lo, *hi) = (m - 3.0 * s, m + 3.0 * s);
    }
    for (nu, (l0, l2)) in rate.iter_mut().zip(variance.iter().zip(lambda2)) {
        let x = (l2 / l0).sqrt() / (2.0 * std::f64::consts::PI);
        *nu = if *l0 > 0.0 { x } else { f64::NAN };
    }
}

/// One row of [`MC_COLUMNS`].
#[inline]
fn mc_row(v: &OutputValues) -> [f64; 3] {
    v.mc.map_or([f64::NAN; 3], |m| [m.sigma, m.lower, m.upper])
}

/// The method code of a failed point.
const FAILED: u8 = 255;

/// The datasets of one output.
struct OutputSets {
    numbers: Vec<hdf5::Dataset>,
    method: hdf5::Dataset,
    covers: Option<hdf5::Dataset>,
}

/// A sweep table being written (see the module docs).
pub(crate) struct H5TableWriter {
    path: PathBuf,
    file: hdf5::File,
    /// The points of the study the file holds (row r is point `rows.start + r`).
    rows: Range<usize>,
    n_keys: usize,
    value_index: hdf5::Dataset,
    outputs: Vec<OutputSets>,
    /// The verdict columns (`verdicts/<k>`), empty without.
    verdicts: Vec<hdf5::Dataset>,
    monte_carlo: bool,
    errors: Vec<(usize, String)>,
    /// Rows written so far (blocks come in order).
    written: usize,
}

fn vlu(t: &str) -> VarLenUnicode {
    t.parse::<VarLenUnicode>().unwrap_or_default()
}

fn str_attr(loc: &hdf5::Location, name: &str, value: &str) -> hdf5::Result<()> {
    loc.new_attr::<VarLenUnicode>()
        .shape(())
        .create(name)?
        .write_scalar(&vlu(value))
}

fn list_attr(loc: &hdf5::Location, name: &str, values: &[&str]) -> hdf5::Result<()> {
    let values: Vec<VarLenUnicode> = values.iter().map(|v| vlu(v)).collect();
    let a = loc.new_attr::<VarLenUnicode>().shape(values.len()).create(name)?;
    if !values.is_empty() {
        a.write(&values[..])?;
    }
    Ok(())
}

/// The datasets `verdicts/<k>` of `columns` (quantity, unit) with `n` rows; no group without columns.
fn verdict_sets(file: &hdf5::File, columns: &[(String, String)], n: usize) -> hdf5::Result<Vec<hdf5::Dataset>> {
    if columns.is_empty() {
        return Ok(Vec::new());
    }
    let g = file.create_group("verdicts")?;
    let mut sets = Vec::with_capacity(columns.len());
    for (k, (quantity, unit)) in columns.iter().enumerate() {
        let ds = g.new_dataset::<f64>().shape(n).create(k.to_string().as_str())?;
        str_attr(&ds, "quantity", quantity)?;
        str_attr(&ds, "unit", unit)?;
        sets.push(ds);
    }
    Ok(sets)
}

impl H5TableWriter {
    /// Creates the file at `path` (which must not exist) for the points `rows` of the study `identity` of `n_points` points:
    /// attributes, the key values, and every dataset at its final length.
    ///
    /// # Errors
    /// HDF5 errors ([`Error::Hdf5`] naming `path`).
    pub(crate) fn create(
        path: &Path,
        identity: &SweepIdentity,
        n_points: usize,
        rows: Range<usize>,
    ) -> Result<H5TableWriter> {
        let file = open_sec2(path, OpenMode::CreateExcl, |_| {}).map_err(h5(path, "creating the table"))?;
        let n = rows.len();
        let n_keys = identity.params.len();
        let monte_carlo = identity.monte_carlo.is_some();
        let make = || -> hdf5::Result<(hdf5::Dataset, Vec<OutputSets>, Vec<hdf5::Dataset>)> {
            str_attr(&file, "format", "stochvib sweep table")?;
            file.new_attr::<u32>()
                .shape(())
                .create("version")?
                .write_scalar(&1u32)?;
            str_attr(&file, "toolkit_version", &identity.toolkit_version)?;
            str_attr(&file, "scenario", &identity.scenario_text)?;
            str_attr(&file, "scenario_path", &identity.scenario_path)?;
            str_attr(&file, "mode", &identity.mode)?;
            file.new_attr::<u64>()
                .shape(())
                .create("n_points")?
                .write_scalar(&(n_points as u64))?;
            let keys: Vec<&str> = identity.params.iter().map(|p| p.0.as_str()).collect();
            list_attr(&file, "keys", &keys)?;
            let names: Vec<&str> = identity.outputs.iter().map(|o| o.0.as_str()).collect();
            list_attr(&file, "outputs", &names)?;
            let units: Vec<&str> = identity.outputs.iter().map(|o| o.1.as_str()).collect();
            list_attr(&file, "units", &units)?;
            let mc = identity
                .monte_carlo
                .map(|m| serde_json::to_string(&m).unwrap_or_default())
                .unwrap_or_default();
            str_attr(&file, "monte_carlo", &mc)?;
            let params = file.create_group("params")?;
            for (k, (key, vals)) in identity.params.iter().enumerate() {
                let v: Vec<VarLenUnicode> = vals.iter().map(|s| vlu(s)).collect();
                let ds = params
                    .new_dataset_builder()
                    .with_data(&v[..])
                    .create(k.to_string().as_str())?;
                str_attr(&ds, "key", key)?;
            }
            let value_index = file
                .new_dataset::<u64>()
                .shape((n, n_keys.max(1)))
                .create("value_index")?;
            let outs = file.create_group("outputs")?;
            let mut sets = Vec::with_capacity(identity.outputs.len());
            for (name, unit) in &identity.outputs {
                let g = outs.create_group(name)?;
                str_attr(&g, "unit", unit)?;
                let mut numbers = Vec::new();
                for cname in EXACT_COLUMNS {
                    numbers.push(g.new_dataset::<f64>().shape(n).create(cname)?);
                }
                let method = g.new_dataset::<u8>().shape(n).create("method")?;
                let mut covers = None;
                if monte_carlo {
                    for cname in MC_COLUMNS {
                        numbers.push(g.new_dataset::<f64>().shape(n).create(cname)?);
                    }
                    covers = Some(g.new_dataset::<u8>().shape(n).create("mc_covers")?);
                }
                sets.push(OutputSets {
                    numbers,
                    method,
                    covers,
                });
            }
            let verdicts = verdict_sets(&file, &identity.verdicts, n)?;
            Ok((value_index, sets, verdicts))
        };
        let (value_index, outputs, verdicts) = make().map_err(h5(path, "creating the table"))?;
        Ok(H5TableWriter {
            path: path.to_path_buf(),
            file,
            rows,
            n_keys,
            value_index,
            outputs,
            verdicts,
            monte_carlo,
            errors: Vec::new(),
            written: 0,
        })
    }

    /// Writes the rows of `block`, which holds the points that follow the last block's.
    ///
    /// # Errors
    /// A block out of order or of another width (a bug: [`Error::Numerical`]); HDF5 errors.
    pub(crate) fn append(&mut self, block: &SweepResults) -> Result<()> {
        let n = block.points.len();
        if block.values.len() != n * self.outputs.len()
            || block.value_index.len() != n * self.n_keys
            || block.verdicts.len() != n * self.verdicts.len()
        {
            return Err(self.out_of_order(&block.points));
        }
        let start = self.written;
        let n_keys = self.n_keys;
        let idx = |r: usize, out: &mut [u64]| {
            for (o, &i) in out.iter_mut().zip(&block.value_index[r * n_keys..]) {
                *o = i as u64;
            }
        };
        self.append_rows(block.points.clone(), idx, |i| block.values[i], &block.errors)?;
        let width = self.verdicts.len();
        let write = || -> hdf5::Result<()> {
            for (k, ds) in self.verdicts.iter().enumerate() {
                let col: Vec<f64> = (0..n)
                    .map(|r| block.verdicts[r * width + k].unwrap_or(f64::NAN))
                    .collect();
                ds.write_slice(&col, start..start + n)?;
            }
            Ok(())
        };
        write().map_err(h5(&self.path, "writing the table"))
    }

    fn out_of_order(&self, points: &Range<usize>) -> Error {
        Error::Numerical {
            what: format!("writing the table {}", self.path.display()),
            reason: format!(
                "block of points {points:?} does not follow the {} rows written of {:?}, or has another width",
                self.written, self.rows
            ),
        }
    }

    /// The rows of `points`: `index(r, out)` writes row r's value indices, `value(r·outputs + j)` is output
    /// j of row r, `errors` (ascending) the failed points.
    fn append_rows(
        &mut self,
        points: Range<usize>,
        index: impl FnMut(usize, &mut [u64]),
        value: impl Fn(usize) -> OutputValues,
        errors: &[(usize, String)],
    ) -> Result<()> {
        let mut rows = H5Rows::default();
        let piece = rows.pieces(self.layout(), points.clone(), points.len().max(1)).pop();
        if let Some(piece) = piece {
            piece.fill(points.start, index, value, errors);
        }
        self.append_filled(points, &rows, errors)
    }

    /// The shape of a block's columns for this table.
    pub(crate) fn layout(&self) -> H5Layout {
        H5Layout {
            n_keys: self.n_keys,
            n_outputs: self.outputs.len(),
            monte_carlo: self.monte_carlo,
        }
    }

    /// Writes the columns `rows` of `points` ([`H5Rows::pieces`] filled), which follow the last block's;
    /// `errors` (ascending) are the failed points.
    ///
    /// # Errors
    /// As [`append`](Self::append).
    pub(crate) fn append_columns(
        &mut self,
        points: Range<usize>,
        rows: &H5Rows,
        errors: &[(usize, String)],
    ) -> Result<()> {
        if !self.verdicts.is_empty() {
            return Err(self.out_of_order(&points));
        }
        self.append_filled(points, rows, errors)
    }

    fn append_filled(&mut self, points: Range<usize>, block: &H5Rows, errors: &[(usize, String)]) -> Result<()> {
        let n_out = self.outputs.len();
        let first = self.rows.start + self.written;
        let n = points.len();
        let width = self.n_keys.max(1);
        let n_cols = self.layout().n_columns();
        if points.start != first
            || points.end > self.rows.end
            || block.index.len() != n * width
            || block.numbers.len() != n * n_cols * n_out
        {
            return Err(self.out_of_order(&points));
        }
        let rows = self.written..self.written + n;
        let write = || -> hdf5::Result<()> {
            let idx = ndarray::ArrayView2::from_shape((n, width), &block.index[..])
                .map_err(|err| hdf5::Error::from(err.to_string()))?;
            self.value_index.write_slice(idx, (rows.clone(), ..))?;
            for (j, sets) in self.outputs.iter().enumerate() {
                let cols = block.numbers[j * n_cols * n..(j + 1) * n_cols * n].chunks(n.max(1));
                for (col, ds) in cols.zip(&sets.numbers) {
                    ds.write_slice(col, rows.clone())?;
                }
                sets.method
                    .write_slice(&block.method[j * n..(j + 1) * n], rows.clone())?;
                if let Some(ds) = &sets.covers {
                    ds.write_slice(&block.covers[j * n..(j + 1) * n], rows.clone())?;
                }
            }
            Ok(())
        };
        write().map_err(h5(&self.path, "writing the table"))?;
        self.errors.extend(errors.iter().cloned());
        self.written += n;
        Ok(())
    }

    /// Writes the failed points' messages and closes the file.
    ///
    /// # Errors
    /// Fewer rows written than the file holds (a bug: [`Error::Numerical`]); HDF5 errors.
    pub(crate) fn finish(self) -> Result<()> {
        if self.written != self.rows.len() {
            return Err(Error::Numerical {
                what: format!("writing the table {}", self.path.display()),
                reason: format!("{} of {} rows written", self.written, self.rows.len()),
            });
        }
        let write = || -> hdf5::Result<()> {
            let eg = self.file.create_group("errors")?;
            let pts: Vec<u64> = self.errors.iter().map(|e| e.0 as u64).collect();
            let msgs: Vec<VarLenUnicode> = self.errors.iter().map(|e| vlu(&e.1)).collect();
            eg.new_dataset::<u64>()
                .shape(pts.len())
                .create("point")?
                .write(&pts[..])?;
            let ds = eg.new_dataset::<VarLenUnicode>().shape(msgs.len()).create("message")?;
            if !msgs.is_empty() {
                ds.write(&msgs[..])?;
            }
            Ok(())
        };
        write().map_err(h5(&self.path, "writing the table"))?;
        let path = self.path;
        drop((self.value_index, self.outputs, self.verdicts));
        self.file.close().map_err(h5(&path, "closing the table"))
    }
}

/// The shape of a block of a table's columns: the number of keys and outputs, with Monte Carlo columns or
/// without.
#[derive(Debug, Clone, Copy)]
pub(crate) struct H5Layout {
    n_keys: usize,
    n_outputs: usize,
    monte_carlo: bool,
}

impl H5Layout {
    /// The number columns of one output.
    fn n_columns(&self) -> usize {
        EXACT_COLUMNS.len() + if self.monte_carlo { MC_COLUMNS.len() } else { 0 }
    }
}

/// A block's columns as the file holds them, for rows 0..n: the value indices (row-major, at least one
/// column), then per output its number columns one after the other, its method codes and Monte Carlo
/// cover flags. Filled piece by piece ([`pieces`](Self::pieces)) by the evaluating workers and written by
/// [`H5TableWriter::append_columns`]; the buffers are kept from block to block.
#[derive(Debug, Default)]
pub(crate) struct H5Rows {
    index: Vec<u64>,
    numbers: Vec<f64>,
    method: Vec<u8>,
    covers: Vec<u8>,
}

/// The rows `points` of an [`H5Rows`] block, to be filled by one worker.
pub(crate) struct H5Piece<'a> {
    n_keys: usize,
    index: &'a mut [u64],
    /// Every number column of every output (output-major), this piece's rows.
    numbers: Vec<&'a mut [f64]>,
    method: Vec<&'a mut [u8]>,
    covers: Vec<&'a mut [u8]>,
    monte_carlo: bool,
}

/// The chunks of `chunk` rows of a column `col`, dealt to the pieces in turn.
fn deal<'a, T>(col: &'a mut [T], chunk: usize, to: &mut [Vec<&'a mut [T]>]) {
    for (piece, part) in to.iter_mut().zip(col.chunks_mut(chunk)) {
        piece.push(part);
    }
}

impl H5Rows {
    /// Sizes the buffers for the `points` of a block of `layout` and cuts them into pieces of `chunk`
    /// rows (the last shorter), in order.
    pub(crate) fn pieces(&mut self, layout: H5Layout, points: Range<usize>, chunk: usize) -> Vec<H5Piece<'_>> {
        let n = points.len();
        let (width, n_cols, n_out) = (layout.n_keys.max(1), layout.n_columns(), layout.n_outputs);
        let covers = if layout.monte_carlo { n * n_out } else { 0 };
        self.index.resize(n * width, 0);
        self.numbers.resize(n * n_cols * n_out, 0.0);
        self.method.resize(n * n_out, 0);
        self.covers.resize(covers, 0);
        let n_pieces = n.div_ceil(chunk);
        let mut numbers: Vec<Vec<&mut [f64]>> = (0..n_pieces).map(|_| Vec::new()).collect();
        let mut method: Vec<Vec<&mut [u8]>> = (0..n_pieces).map(|_| Vec::new()).collect();
        let mut cover: Vec<Vec<&mut [u8]>> = (0..n_pieces).map(|_| Vec::new()).collect();
        for col in self.numbers.chunks_mut(n.max(1)) {
            deal(col, chunk, &mut numbers);
        }
        for col in self.method.chunks_mut(n.max(1)) {
            deal(col, chunk, &mut method);
        }
        for col in self.covers.chunks_mut(n.max(1)) {
            deal(col, chunk, &mut cover);
        }
        let index = self.index.chunks_mut(chunk * width);
        index
            .zip(numbers)
            .zip(method.into_iter().zip(cover))
            .map(|((index, numbers), (method, covers))| H5Piece {
                n_keys: layout.n_keys,
                index,
                numbers,
                method,
                covers,
                monte_carlo: layout.monte_carlo,
            })
            .collect()
    }
}

impl H5Piece<'_> {
    /// Fills the rows of this piece, whose first row is point `first`: `index(r, out)` writes row r's
    /// value indices, `value(r·outputs + j)` is output j of row r, `errors` (ascending) the failed points
    /// (of any range that holds this piece's).
    pub(crate) fn fill(
        self,
        first: usize,
        mut index: impl FnMut(usize, &mut [u64]),
        value: impl Fn(usize) -> OutputValues,
        errors: &[(usize, String)],
    ) {
        let width = self.n_keys.max(1);
        if self.n_keys > 0 {
            for (r, row) in self.index.chunks_mut(width).enumerate() {
                index(r, row);
            }
        }
        let n_out = self.method.len();
        let n_cols = self.numbers.len().checked_div(n_out).unwrap_or(0);
        let (mut numbers, mut method, mut covers) = (self.numbers, self.method, self.covers);
        let n_rows = method.first().map_or(0, |m| m.len());
        // the failed rows of this piece, from the ascending list, once for every output
        let mut failed = vec![false; n_rows];
        let from = errors.partition_point(|e| e.0 < first);
        for e in errors[from..].iter().take_while(|e| e.0 < first + n_rows) {
            failed[e.0 - first] = true;
        }
        for j in 0..n_out {
            let cols = &mut numbers[j * n_cols..(j + 1) * n_cols];
            // one pass over the rows: each row's values read once, its stored values and codes copied
            for r in 0..n_rows {
                let v = value(r * n_out + j);
                stored_values(cols, r, &v);
                if self.monte_carlo {
                    for (col, x) in cols[EXACT_COLUMNS.len()..].iter_mut().zip(mc_row(&v)) {
                        col[r] = x;
                    }
                    covers[j][r] = v.mc.map_or(0, |m| u8::from(m.covers));
                }
                method[j][r] = if failed[r] {
                    FAILED
                } else {
                    super::sweep_table::method_code(v.method)
                };
            }
            exact_columns(&mut cols[..EXACT_COLUMNS.len()], n_rows);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::response::{PointStatistics, VarianceMethod};

    /// The columns computed column by column equal, bit for bit, what the statistics' own methods give
    /// row by row (`sigma`, `bounds(3.0)`, `zero_upcrossing_rate`, the independent path the table used
    /// before), for values that exist and do not, a zero and a negative variance, zero and huge λ₂; a
    /// missing value is NaN in both.
    #[test]
    fn derived_columns_equal_the_statistics_methods() {
        let some = [
            Some(0.0),
            Some(-0.0),
            Some(1.5e-300),
            Some(4.464_195_602e-3),
            Some(7.3),
            Some(2.0e280),
            Some(-2.5),
            None,
        ];
        let mut points = Vec::new();
        for &mean in &some {
            for &variance in &some {
                for &lambda2 in &some {
                    points.push(PointStatistics {
                        mean,
                        variance,
                        lambda2,
                        method: VarianceMethod::IntegralTable,
                    });
                }
            }
        }
        let n = points.len();
        let mut cols = vec![vec![f64::INFINITY; n]; EXACT_COLUMNS.len()];
        let mut refs: Vec<&mut [f64]> = cols.iter_mut().map(|c| &mut c[..]).collect();
        for (r, p) in points.iter().enumerate() {
            stored_values(&mut refs, r, &OutputValues::from_point(p));
        }
        exact_columns(&mut refs, n);
        let same = |a: f64, b: f64| a.to_bits() == b.to_bits() || (a.is_nan() && b.is_nan());
        for (r, p) in points.iter().enumerate() {
            let (lo, hi) = p.bounds(3.0).unzip();
            let want = [
                p.mean,
                p.variance,
                p.sigma(),
                lo,
                hi,
                p.lambda2,
                p.zero_upcrossing_rate(),
            ];
            for (c, w) in want.into_iter().enumerate() {
                let w = w.unwrap_or(f64::NAN);
                assert!(
                    same(cols[c][r], w),
                    "{p:?}, column {}: {} against {w}",
                    EXACT_COLUMNS[c],
                    cols[c][r]
                );
            }
        }
    }
}
