//! A parameter study's table written while it is computed (`stochvib sweep`): the points are evaluated in
//! blocks of [`StreamOptions::block_points`] on every core, each worker turning the pieces of 256 points it
//! evaluated into the file's form at once (CSV text, HDF5 columns), and each finished block goes to a writer
//! thread that only writes it (one write per piece of CSV, one per HDF5 dataset) while the next block is
//! evaluated. Memory holds at most
//! three blocks (one being evaluated, one waiting, one being written), whatever the number of points, and
//! the file is the same, byte for byte (CSV) or value for value (HDF5), as [`SweepResults::write`] of the
//! whole table: every point is evaluated alone, so the blocking cannot change a number. With a Monte Carlo
//! batch per point the blocks are single points (each batch takes seconds): a point's row reaches the file
//! when its batch is done, and a failed write stops the study at the next point.
//!
//! A table file's pages are sent to disk while the next blocks are evaluated
//! ([`WriteBehind`], [`start_write_out`]),
//! so that the sync before the final rename waits for the last block only.
//!
//! JSON tables are one document and are written from the whole table ([`compute_sweep`], then
//! [`SweepResults::write_json`]).

use super::sweep_h5::{H5Rows, H5TableWriter};
use super::sweep_table::{
    compute_sweep, csv_header, prepare_table, sweep_identity, CsvRows, OutputValues, SweepMonteCarlo, SweepResults,
    TableFormat,
};
use crate::error::{Error, Result};
use crate::io_rules::{start_write_out, WriteBehind};
use crate::response::PointStatistics;
use crate::study::{Sweep, FAILED_POINT};
use std::io::Write;
use std::ops::Range;
use std::path::Path;

/// How a table is streamed.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct StreamOptions {
    /// Points per block (≥ 1): the unit of evaluation and of writing.
    pub block_points: usize,
    /// Evaluate each block on every core (rayon) rather than on the calling thread.
    pub parallel: bool,
}

impl Default for StreamOptions {
    /// Blocks of 16 384 points on every core: a block of 4 outputs is about 3.7 MB of evaluated rows in
    /// memory and 3.7 MB of numbers in the file, large enough that the per-block costs (an HDF5 hyperslab
    /// write per column, a channel hand-over) are small, small enough that evaluation and writing overlap.
    fn default() -> StreamOptions {
        StreamOptions {
            block_points: 16_384,
            parallel: true,
        }
    }
}

/// What a streamed table held.
#[derive(Debug, Clone, PartialEq)]
pub struct StreamedTable {
    /// Points written.
    pub n_points: usize,
    /// Failed points with the reason (their rows hold no numbers).
    pub errors: Vec<(usize, String)>,
}

/// Evaluates every point of `sweep` (with `mc`, a Monte Carlo batch per point) and writes the table to
/// `path`, format from its extension, under the output rule ([`crate::io_rules::Staged`]: a temporary file
/// of this process, renamed when complete; an existing table is only replaced with `overwrite`; the
/// scenario's files, directories, devices and files of another kind never). The table's size on disk (and,
/// for JSON, in memory) is estimated first ([`check_table_resources`](super::sweep_table::check_table_resources)).
/// CSV and HDF5 are streamed block by block (see the module docs); JSON is written from the whole table.
/// `progress(done, total)` is called after every Monte Carlo point. A killed study leaves only its
/// temporary file `<stem>.tmp-<pid>.<ext>`, which the next study writing the same table removes.
///
/// # Errors
/// An unknown extension; the refusals of the output rule; a table larger than the free disk (or a JSON
/// table larger than the free memory); a block of 0 points; I/O and HDF5 errors (the temporary file is
/// then removed and nothing at `path` is touched). A failing point is not an error: it is recorded in
/// [`StreamedTable::errors`] and in the table.
///
/// # Examples
/// ```
/// use stochvib::study::{write_sweep_table, StreamOptions};
/// use stochvib::scenario::load_scenario;
/// use stochvib::study::{Sweep, SweepMode, SweepParam, SweepSpec};
/// use std::path::Path;
/// let sc = load_scenario(Path::new("data/scraper-sprung-cab.toml"), Path::new("spectra")).unwrap();
/// let spec = SweepSpec::new(vec![SweepParam::parse("model.zeta2=0.1..0.4:7").unwrap()], SweepMode::Grid).unwrap();
/// let sweep = Sweep::new(&sc, spec).unwrap();
/// let dir = std::env::temp_dir().join(format!("stochvib-doc-stream-{}", std::process::id()));
/// std::fs::create_dir_all(&dir).unwrap();
/// let path = dir.join("table.csv");
/// let opts = StreamOptions { block_points: 3, parallel: false };
/// let t = write_sweep_table(&sweep, &path, false, None, opts, &|_, _| {}).unwrap();
/// assert_eq!((t.n_points, t.errors.len()), (7, 0));
/// let text = std::fs::read_to_string(&path).unwrap();
/// assert_eq!(text.lines().count(), 1 + 7 * sweep.outputs().len()); // header, one line per point and output
/// std::fs::remove_dir_all(&dir).unwrap();
/// ```
pub fn write_sweep_table(
    sweep: &Sweep,
    path: &Path,
    overwrite: bool,
    mc: Option<SweepMonteCarlo>,
    opts: StreamOptions,
    progress: &dyn Fn(usize, usize),
) -> Result<StreamedTable> {
    let inputs = sweep.scenario().source_files();
    let inputs: Vec<&Path> = inputs.iter().map(|p| p.as_path()).collect();
    let (format, staged) = prepare_table(path, overwrite, &inputs)?;
    let n = sweep.spec().n_points();
    super::sweep_table::check_table_resources(sweep, path, format, mc)?;
    let tmp = staged.temporary().to_path_buf();
    let created = |r: std::io::Result<std::fs::File>| {
        r.map_err(|source| Error::Io {
            path: tmp.clone(),
            source,
        })
    };
    // a JSON table is one document, and a table with verdict columns is evaluated whole
    let whole = format == TableFormat::Json || !sweep.verdicts().is_empty();
    let t = if whole {
        let t = compute_sweep(sweep, 0..n, opts.parallel, mc, progress)?;
        t.write_format(&tmp, format)?;
        StreamedTable {
            n_points: n,
            errors: t.errors,
        }
    } else if format == TableFormat::Csv {
        let file = WriteBehind::new(created(std::fs::File::create(&tmp))?);
        stream_sweep_csv(sweep, file, path, mc, opts, progress)?
    } else {
        let w = H5TableWriter::create(&tmp, &sweep_identity(sweep, mc), n, 0..n)?;
        // HDF5 writes the file; a handle of our own asks for the write-out of each block's pages
        let behind = std::fs::File::open(&tmp).ok();
        let fill = h5_columns(sweep, w.layout(), opts.parallel);
        let (w, errors) = pipeline(sweep, 0..n, mc, opts, progress, w, fill, |w, b| {
            match b {
                Block::Rows { points, buf, errors } => w.append_columns(points.clone(), buf, errors)?,
                Block::Table(t) => w.append(t)?,
            }
            behind.iter().for_each(start_write_out);
            Ok(())
        })?;
        w.finish()?;
        StreamedTable { n_points: n, errors }
    };
    // the temporary file is removed when `staged` is dropped without a commit (any error above)
    staged.commit()?;
    Ok(t)
}

/// Evaluates every point of `sweep` and writes the CSV table to `out` (`name` names it in errors, e.g.
/// `<stdout>`), block by block (see the module docs): the same text as
/// [`SweepResults::to_csv`] of the whole table.
///
/// # Errors
/// A block of 0 points; write errors of `out` ([`Error::Io`] naming `name`; the evaluation stops at the
/// next block). A closed pipe is such an error, with kind [`std::io::ErrorKind::BrokenPipe`].
pub fn stream_sweep_csv(
    sweep: &Sweep,
    out: impl Write + Send,
    name: &Path,
    mc: Option<SweepMonteCarlo>,
    opts: StreamOptions,
    progress: &dyn Fn(usize, usize),
) -> Result<StreamedTable> {
    let io = |source| Error::Io {
        path: name.to_path_buf(),
        source,
    };
    let n = sweep.spec().n_points();
    // a piece of text larger than the buffer goes to `out` in one write, without a copy
    let mut out = std::io::BufWriter::with_capacity(1 << 16, out);
    if !sweep.verdicts().is_empty() {
        // one row per point: the table is evaluated whole
        let t = compute_sweep(sweep, 0..n, opts.parallel, mc, progress)?;
        out.write_all(super::sweep_verdicts::VerdictSweep::of(&t).to_csv().as_bytes())
            .and_then(|()| out.flush())
            .map_err(io)?;
        return Ok(StreamedTable {
            n_points: n,
            errors: t.errors,
        });
    }
    let identity = sweep_identity(sweep, mc);
    out.write_all(csv_header(&identity).as_bytes()).map_err(io)?;
    let lines = CsvRows::new(&identity);
    let fill = csv_text(sweep, &lines, opts.parallel);
    let (mut out, errors) = pipeline(sweep, 0..n, mc, opts, progress, out, fill, |w, b| {
        let table;
        let pieces = match b {
            Block::Rows { buf, .. } => buf,
            Block::Table(t) => {
                table = t.csv_row_blocks();
                &table
            }
        };
        pieces
            .iter()
            .try_for_each(|text| w.write_all(text.as_bytes()).map_err(io))
    })?;
    out.flush().map_err(io)?;
    Ok(StreamedTable { n_points: n, errors })
}

/// Points per piece of a block: what one worker evaluates and puts into the file's form.
const PIECE_POINTS: usize = 256;

/// A block on its way from the evaluation to the writer thread.
pub(crate) enum Block<B> {
    /// Rows of exact statistics ([`Sweep::evaluate_into`]), already in the file's form `buf`.
    Rows {
        points: Range<usize>,
        buf: B,
        errors: Vec<(usize, String)>,
    },
    /// A block with its Monte Carlo values ([`compute_sweep`]).
    Table(Box<SweepResults>),
}

/// Evaluates `points` of `sweep` piece by piece ([`PIECE_POINTS`] points; on every core with `parallel`)
/// into `stats`, and hands each piece's points, rows, failed points and its part of the output `pieces`
/// (one per piece, in order) to `format` on the worker that evaluated it. Returns the failed points
/// (ascending).
fn evaluate_pieces<P: Send>(
    sweep: &Sweep,
    points: Range<usize>,
    parallel: bool,
    stats: &mut Vec<PointStatistics>,
    pieces: Vec<P>,
    format: impl Fn(Range<usize>, &[PointStatistics], &[(usize, String)], P) + Sync,
) -> Vec<(usize, String)> {
    use rayon::prelude::*;
    let n_out = sweep.outputs().len();
    // every row is overwritten by the evaluation
    stats.resize(points.len() * n_out, FAILED_POINT);
    let mut rest = &mut stats[..];
    let mut jobs = Vec::with_capacity(pieces.len());
    for (c, piece) in pieces.into_iter().enumerate() {
        let start = points.start + c * PIECE_POINTS;
        let pts = start..(start + PIECE_POINTS).min(points.end);
        let (rows, tail) = std::mem::take(&mut rest).split_at_mut(pts.len() * n_out);
        rest = tail;
        jobs.push((pts, rows, piece));
    }
    let work = |(pts, rows, piece): (Range<usize>, &mut [PointStatistics], P)| {
        let errors = sweep.evaluate_into(pts.clone(), false, rows);
        format(pts, rows, &errors, piece);
        errors
    };
    let errors: Vec<Vec<(usize, String)>> = if parallel {
        jobs.into_par_iter().map(work).collect()
    } else {
        jobs.into_iter().map(work).collect()
    };
    errors.concat()
}

/// The failed points of a block: (point index, reason).
type FailedPoints = Vec<(usize, String)>;

/// The CSV lines of a block, one string per piece, formatted by the workers.
fn csv_text<'a>(
    sweep: &'a Sweep,
    lines: &'a CsvRows,
    parallel: bool,
) -> impl Fn(Range<usize>, &mut Vec<PointStatistics>, &mut Vec<String>) -> FailedPoints + 'a {
    move |points, stats, bufs| {
        bufs.resize_with(points.len().div_ceil(PIECE_POINTS), String::new);
        let n_out = sweep.outputs().len();
        let spec = sweep.spec();
        // about 170 bytes a line: the buffers grow once, in the first block, and are reused after it
        for s in bufs.iter_mut() {
            s.clear();
            s.reserve(PIECE_POINTS * n_out * 200);
        }
        let pieces = bufs.iter_mut();
        evaluate_pieces(
            sweep,
            points,
            parallel,
            stats,
            pieces.collect(),
            |pts, rows, errors, s| {
                let mut keys = vec![0; spec.params.len()];
                for (r, p) in pts.enumerate() {
                    spec.indices_into(p, &mut keys);
                    let err = errors
                        .binary_search_by_key(&p, |e| e.0)
                        .ok()
                        .map(|i| errors[i].1.as_str());
                    lines.push_point(s, p, &keys, |j| OutputValues::from_point(&rows[r * n_out + j]), err);
                }
            },
        )
    }
}

/// The HDF5 columns of a block of a table of `layout`, filled by the workers.
fn h5_columns<'a>(
    sweep: &'a Sweep,
    layout: super::sweep_h5::H5Layout,
    parallel: bool,
) -> impl Fn(Range<usize>, &mut Vec<PointStatistics>, &mut H5Rows) -> FailedPoints + 'a {
    move |points, stats, rows| {
        let spec = sweep.spec();
        let pieces = rows.pieces(layout, points.clone(), PIECE_POINTS);
        evaluate_pieces(sweep, points, parallel, stats, pieces, |pts, rows, errors, piece| {
            let mut keys = vec![0; spec.params.len()];
            let index = |r: usize, out: &mut [u64]| {
                spec.indices_into(pts.start + r, &mut keys);
                for (o, &k) in out.iter_mut().zip(&keys) {
                    *o = k as u64;
                }
            };
            piece.fill(pts.start, index, |i| OutputValues::from_point(&rows[i]), errors);
        })
    }
}

/// Evaluates `points` in blocks on the calling thread (each block on every core with `opts.parallel`:
/// `fill(block, rows, buf)` evaluates it into the file's form `buf` and returns its failed points) and
/// hands each block, in order, to `put` with `sink` on a writer thread, which only writes; returns the sink
/// and the failed points. The calling thread only evaluates, so that the cores are never idle while a
/// block is written. A failing `put` stops the evaluation at the next block (the next point with Monte
/// Carlo, whose blocks are single points) and is the error returned.
#[allow(clippy::too_many_arguments)]
fn pipeline<S: Send, B: Send + Default>(
    sweep: &Sweep,
    points: Range<usize>,
    mc: Option<SweepMonteCarlo>,
    opts: StreamOptions,
    progress: &dyn Fn(usize, usize),
    sink: S,
    fill: impl Fn(Range<usize>, &mut Vec<PointStatistics>, &mut B) -> Vec<(usize, String)>,
    mut put: impl FnMut(&mut S, &Block<B>) -> Result<()> + Send,
) -> Result<(S, Vec<(usize, String)>)> {
    if opts.block_points == 0 {
        return Err(Error::invalid("block_points", 0, "a block holds at least one point"));
    }
    let total = points.len();
    // a Monte Carlo batch takes seconds: one point per block
    let block_points = if mc.is_some() { 1 } else { opts.block_points };
    // one block evaluated while one is written and one waits; spent buffers come back for reuse
    let (tx, rx) = std::sync::mpsc::sync_channel::<Block<B>>(1);
    let (back_tx, back_rx) = std::sync::mpsc::channel::<B>();
    std::thread::scope(|scope| {
        let writer = scope.spawn(move || -> Result<(S, Vec<(usize, String)>)> {
            let mut sink = sink;
            let mut failed = Vec::new();
            for block in rx {
                put(&mut sink, &block)?;
                match block {
                    Block::Rows { buf, errors, .. } => {
                        failed.extend(errors);
                        let _ = back_tx.send(buf);
                    }
                    Block::Table(t) => failed.extend(t.errors),
                }
            }
            Ok((sink, failed))
        });
        let mut evaluated = Ok(());
        let mut stats = Vec::new();
        for start in points.clone().step_by(block_points) {
            let block = start..(start + block_points).min(points.end);
            let b = match mc {
                None => {
                    let mut buf = back_rx.try_recv().unwrap_or_default();
                    let errors = fill(block.clone(), &mut stats, &mut buf);
                    Block::Rows {
                        points: block,
                        buf,
                        errors,
                    }
                }
                Some(_) => {
                    let done = start - points.start;
                    match compute_sweep(sweep, block, opts.parallel, mc, &|d, _| progress(done + d, total)) {
                        Ok(t) => Block::Table(Box::new(t)),
                        Err(e) => {
                            evaluated = Err(e);
                            break;
                        }
                    }
                }
            };
            if tx.send(b).is_err() {
                break; // the writer failed: its error is returned below
            }
        }
        drop(tx);
        let (sink, failed) = match writer.join() {
            Ok(r) => r?,
            Err(panic) => std::panic::resume_unwind(panic),
        };
        evaluated.map(|()| (sink, failed))
    })
}
