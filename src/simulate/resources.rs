//! What a run will need — memory for its realizations and disk for its file — estimated before anything is
//! allocated or written, and compared with what the machine has, so that a run too large for it fails at
//! once with the numbers instead of aborting in an allocation or filling the disk.

use super::RunOptions;
use crate::error::{Error, Result};
use crate::store::RunMetadata;
use std::path::Path;

/// Bytes per f64 and per complex f64.
const F64: u128 = 8;
const C64: u128 = 16;

/// Upper bound of the working memory of a run, bytes: per worker thread the realization buffers of the
/// route, plus one shard's results and raw rows, plus the spectral route's transfer table.
///
/// # Formula
/// With N samples, p outputs, g independent input processes, s = shard size, T threads, B = N/8 ≤ 1024 Welch
/// bins: per thread N(p + g)·8 (samples) + N·8 + (N/2+1)·16·(g + 2) (FFT buffers); shard results
/// s·p·(B + 2)·8, and with raw data 2·s·N·(p + g)·8 (the rows and their copy for writing); the spectral route's
/// table g·p·(N/2+1)·16.
pub fn memory_bytes(n: usize, p: usize, g: usize, opts: &RunOptions, threads: usize) -> u128 {
    let (n, p, g) = (n as u128, p as u128, g as u128);
    let s = opts.shard_size.min(opts.realizations) as u128;
    let bins = (n / 8).clamp(4, 1024) / 2 + 1;
    let per_thread = n * (p + g) * F64 + n * F64 + (n / 2 + 1) * C64 * (g + 2);
    let shard = s * p * (bins + 2) * F64 + if opts.store_raw { 2 * s * n * (p + g) * F64 } else { 0 };
    let table = g * p * (n / 2 + 1) * C64;
    per_thread * threads as u128 + shard + table
}

/// Upper bound of the working memory of a statistics-only run of the exact route, which generates each
/// realization in blocks of `block` steps with its state carried across them, bytes: independent of the
/// number of samples N per realization.
///
/// # Formula
/// With n states, q simulated rows (outputs and recorded inputs), p outputs, b = min(block, N) steps per
/// block, B ≤ 513 Welch bins (segments of M ≤ 1024), s = shard size, P threads, and the L = 8 realizations
/// of a lockstep group ([`GaussMarkovLanes`](super::GaussMarkovLanes)) in a thread at a time:
/// ```text
/// per thread  17·n·8·L (states and 16 steps of normals) + b·q·8·(1 + L) (block, alone and in lanes)
///             + b·8 (one row) + L·p·(2M + B)·8 (Welch streams and sums) + 4M·8 (Welch scratch)
///             + 2·8·8·L·p (the time sums of the lanes' outputs, eight partial sums each)
/// shared      (2n² + q·n)·8 (transition, noise factor, output matrix) + s·p·(B + 2)·8 (the shard's results)
/// bytes       P·per thread + shared
/// ```
///
/// # Examples
/// ```
/// use stochvib::simulate::{RunOptions, resources::exact_block_memory_bytes};
/// let opts = RunOptions { realizations: 10, duration_s: 1e2, dt_s: 0.01, seed: 1, ..RunOptions::default() };
/// let short = exact_block_memory_bytes(6, 3, 3, 1 << 14, 1 << 20, &opts, 2);
/// let long = exact_block_memory_bytes(6, 3, 3, 1 << 14, 1 << 40, &opts, 2);
/// assert_eq!(short, long);
/// ```
pub fn exact_block_memory_bytes(
    states: usize,
    rows: usize,
    p: usize,
    block: usize,
    n: usize,
    opts: &RunOptions,
    threads: usize,
) -> u128 {
    let (nx, q, p) = (states as u128, rows as u128, p as u128);
    let b = block.min(n).max(1) as u128;
    let m = ((n as u128 / 8) & !1).clamp(4, 1024);
    let bins = m / 2 + 1;
    let s = opts.shard_size.min(opts.realizations) as u128;
    let l = super::LANES as u128;
    let per_thread = (1 + super::LANE_DRAW_STEPS as u128) * nx * F64 * l
        + b * q * F64 * (1 + l)
        + b * F64
        + l * p * (2 * m + bins) * F64
        + 4 * m * F64
        + 2 * super::TIME_SUM_WAYS as u128 * F64 * l * p;
    let shared = (2 * nx * nx + q * nx) * F64 + s * p * (bins + 2) * F64;
    per_thread * threads as u128 + shared
}

/// Refuses a statistics-only exact run whose block memory `need` ([`exact_block_memory_bytes`]) exceeds
/// what the machine has available.
///
/// # Errors
/// [`Error::InvalidParameter`] (`block steps`) with the numbers.
pub fn check_block_memory(need: u128, n: usize, opts: &RunOptions) -> Result<()> {
    if let Some(have) = available_memory()
        && need > have
    {
        return Err(Error::invalid(
            "block steps",
            opts.block_steps,
            format!(
                "the exact route needs about {} of memory for its blocks (independent of the {n} samples per \
                     realization) but {} are available: fewer threads (RAYON_NUM_THREADS), a smaller block, a \
                     smaller --shard-size or fewer outputs",
                gib(need),
                gib(have)
            ),
        ));
    }
    Ok(())
}

/// The sizes that set the memory of the streamed spectral route ([`FirSynthesis`](super::FirSynthesis)).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct StreamSizes {
    /// Taps T of every kernel.
    pub taps: usize,
    /// Overlap-save FFT size F.
    pub fft_len: usize,
    /// Kernel grid L of the design.
    pub grid_len: usize,
    /// Least samples per block ([`RunOptions::block_steps`]).
    pub block_steps: usize,
    /// Simulated outputs p.
    pub outputs: usize,
    /// Generators (independent input processes) g.
    pub generators: usize,
}

/// Upper bound of the working memory of a statistics-only run of the streamed spectral route, bytes:
/// independent of the number of samples N per realization.
///
/// # Formula
/// With T taps, F the FFT size, H = F − T + 1 new samples per segment, b = ⌈block/H⌉·H samples per
/// block, B ≤ 513 Welch bins, s = shard size, P threads, L the kernel grid:
/// ```text
/// per thread  g·F·8 (noise history) + (g + 1)·(F/2+1)·16 (segment spectra) + (T − 1)·8 (kept samples)
///             + F·16 (FFT scratch) + p·F·8 (segment outputs) + p·b·8 (block) + 4·1024·8 (Welch)
/// shared      g·p·(T·8 + (F/2+1)·16) (taps, kernel spectra) + s·p·(B + 2)·8 (the shard's results)
/// design      g·p·((L/2+1)·16 + L·8) + p·L·8 (transient, before the realizations)
/// bytes       max(P·per thread + shared, design)
/// ```
///
/// # Examples
/// ```
/// use stochvib::simulate::{RunOptions, resources::{streamed_memory_bytes, StreamSizes}};
/// let z = StreamSizes { taps: 1000, fft_len: 4096, grid_len: 8192, block_steps: 16384, outputs: 2, generators: 1 };
/// let opts1 = RunOptions { realizations: 10, duration_s: 1e2, dt_s: 0.01, seed: 1, ..RunOptions::default() };
/// let opts2 = RunOptions { duration_s: 1e7, ..opts1.clone() };
/// let short = streamed_memory_bytes(&z, &opts1, 2);
/// let long = streamed_memory_bytes(&z, &opts2, 2);
/// assert_eq!(short, long);
/// ```
pub fn streamed_memory_bytes(z: &StreamSizes, opts: &RunOptions, threads: usize) -> u128 {
    let (t, f) = (z.taps as u128, z.fft_len as u128);
    let (p, g) = (z.outputs as u128, z.generators as u128);
    let hop = (f + 1).saturating_sub(t).max(1);
    let block = (z.block_steps.max(1) as u128).div_ceil(hop) * hop;
    let bins = 1024 / 2 + 1;
    let s = opts.shard_size.min(opts.realizations) as u128;
    let per_thread = g * f * F64
        + (g + 1) * (f / 2 + 1) * C64
        + t.saturating_sub(1) * F64
        + f * C64
        + p * f * F64
        + p * block * F64
        + 4 * 1024 * F64;
    let shared = g * p * (t * F64 + (f / 2 + 1) * C64) + s * p * (bins + 2) * F64;
    (per_thread * threads as u128 + shared).max(kernel_design_bytes(z.generators, z.outputs, z.grid_len))
}

/// Transient memory of the streamed route's kernel design on a grid of `grid_len` points, bytes:
/// g·p·((L/2+1)·16 + L·8) + p·L·8 (kernel spectra, kernels and energies of g generators × p outputs).
///
/// # Examples
/// ```
/// use stochvib::simulate::resources::kernel_design_bytes;
/// assert_eq!(kernel_design_bytes(1, 1, 8), (5 * 16 + 8 * 8 + 8 * 8) as u128);
/// ```
pub fn kernel_design_bytes(generators: usize, outputs: usize, grid_len: usize) -> u128 {
    let (g, p, l) = (generators as u128, outputs as u128, grid_len as u128);
    g * p * ((l / 2 + 1) * C64 + l * F64) + p * l * F64
}

pub use crate::io_rules::{available_disk, available_memory};

/// The default of [`RunOptions::max_hours`]: a run estimated to take longer than a day is refused unless
/// the cap is raised (`--max-hours`).
pub const DEFAULT_MAX_HOURS: f64 = 24.0;

/// Normal draws per second and thread at best, for the lower bound of a run's time: Xoshiro256++ with the
/// ziggurat draws about 1.7·10⁸ per second on the machines the toolkit was developed on; every sample of
/// every input process of every realization needs at least one.
pub const MAX_DRAWS_PER_S: f64 = 2.0e8;

/// A lower bound of a run's computing time, s: every sample of every independent input process of every
/// realization the run computes needs at least one normal draw.
///
/// # Formula
/// t ≥ R_local · N · g / (r · P), with R_local the realizations of this file (of its part for a cluster
/// shard), N samples per realization, g ≥ 1 input processes, r = [`MAX_DRAWS_PER_S`], P threads.
///
/// # Examples
/// ```
/// use stochvib::simulate::resources::run_time_lower_bound;
/// // 10⁹ realizations of 10⁴ samples of one process on 2 threads: at least 25000 s
/// assert_eq!(run_time_lower_bound(1e9, 10_000, 1, 2), 25_000.0);
/// ```
pub fn run_time_lower_bound(realizations: f64, n: usize, processes: usize, threads: usize) -> f64 {
    realizations * n as f64 * processes.max(1) as f64 / (MAX_DRAWS_PER_S * threads.max(1) as f64)
}

/// Bytes of the run file of `opts` with `outputs` simulated outputs and `raw_inputs` recorded input
/// processes (with `--store-raw`): raw rows, the accumulators of every shard (moments and Welch sums; verdict
/// and band accumulators come on top), checksums and 1 MiB of metadata — the estimate of
/// [`RunMetadata::estimated_file_bytes`] before the run is planned.
///
/// # Formula
/// With R realizations of this file, N samples, p outputs, q recorded inputs, s = shard size, B shards, M the
/// Welch segment (N/8, even, 4..1024): raw R·N·(p + q)·8 (with raw data), accumulators B·p·(2s + M/2 + 3)·8,
/// checksums B·(p + q + 2p + 1)·4, plus 2²⁰.
///
/// # Errors
/// The options' errors ([`RunOptions::samples`]).
pub fn file_bytes(opts: &RunOptions, outputs: usize, raw_inputs: usize) -> Result<u128> {
    let n = opts.samples()?;
    let count = opts.part.map_or(1, |p| p.count).max(1) as u128;
    let s = opts.shard_size.min(opts.realizations).max(1) as u128;
    let shards = (opts.realizations as u128).div_ceil(s).div_ceil(count);
    let rows = (opts.realizations as u128).div_ceil(count);
    let (p, q) = (outputs as u128, if opts.store_raw { raw_inputs as u128 } else { 0 });
    let raw = if opts.store_raw {
        rows * n as u128 * (p + q) * F64
    } else {
        0
    };
    let bins = (((n / 8) & !1).clamp(4, 1024) / 2 + 1) as u128;
    let acc = shards * p * (2 * s + bins + 2) * F64;
    let checks = shards * (q + (if opts.store_raw { p } else { 0 }) + 2 * p + 1) * 4;
    Ok(raw + acc + checks + (1 << 20))
}

/// What a run of `opts` with `processes` input processes, `outputs` simulated outputs and `raw_inputs`
/// recorded input processes will at least take, in words, before anything is planned: samples, the run
/// file's size ([`file_bytes`]) and the computing time's lower bound ([`run_time_lower_bound`]).
///
/// # Errors
/// The options' errors ([`RunOptions::samples`]).
///
/// # Examples
/// ```
/// use stochvib::simulate::{resources::estimate_text, RunOptions};
/// let opts = RunOptions { realizations: 1000, duration_s: 100.0, dt_s: 0.01, seed: 1, ..RunOptions::default() };
/// let t = estimate_text(&opts, 1, 2, 1).unwrap();
/// assert!(t.starts_with("estimate: 1000 realizations × 10000 samples, a file of"), "{t}");
/// ```
pub fn estimate_text(opts: &RunOptions, processes: usize, outputs: usize, raw_inputs: usize) -> Result<String> {
    let n = opts.samples()?;
    let local = opts.realizations as f64 / opts.part.map_or(1, |p| p.count) as f64;
    let threads = rayon::current_num_threads();
    let t = run_time_lower_bound(local, n, processes, threads);
    let bytes = file_bytes(opts, outputs, raw_inputs)?;
    Ok(format!(
        "estimate: {} realizations × {n} samples, a file of {}{}; computing takes at least {} on {threads} threads \
         (refused above --max-hours {})",
        opts.realizations,
        crate::io_rules::bytes_text(bytes),
        if opts.store_raw { " with raw data" } else { "" },
        crate::io_rules::duration_text(t),
        crate::numbers::num(opts.max_hours)
    ))
}

/// Refuses a run whose time lower bound ([`run_time_lower_bound`]) exceeds `opts.max_hours`, before
/// anything is planned, allocated or written.
///
/// # Errors
/// [`Error::InvalidParameter`] naming `realizations` with the estimate, the cap and what to change.
pub fn check_run_time(opts: &RunOptions, n: usize, processes: usize) -> Result<()> {
    let local = opts.realizations as f64 / opts.part.map_or(1, |p| p.count) as f64;
    let threads = rayon::current_num_threads();
    let t = run_time_lower_bound(local, n, processes, threads);
    crate::io_rules::check_time(
        t,
        opts.max_hours,
        "realizations",
        format!(
            "{} of {n} samples ({} s at Δt = {} s)",
            opts.realizations, opts.duration_s, opts.dt_s
        ),
        &format!(
            "computing {} realizations × {n} samples × {processes} input processes on {threads} threads",
            crate::numbers::num(local)
        ),
        "fewer --realizations, a shorter --duration, a longer --dt, or a cluster run (--shard I --of N)",
    )
}

fn gib(b: u128) -> String {
    format!("{:.3} GiB", b as f64 / (1u128 << 30) as f64)
}

/// Refuses a run whose working memory exceeds what the machine has available.
///
/// # Errors
/// [`Error::InvalidParameter`] (`realizations`/`duration`) with the numbers and what to change.
pub fn check_memory(n: usize, p: usize, g: usize, opts: &RunOptions) -> Result<()> {
    let threads = rayon::current_num_threads();
    let need = memory_bytes(n, p, g, opts, threads);
    if let Some(have) = available_memory()
        && need > have
    {
        return Err(Error::invalid(
            "duration",
            format!(
                "{} s at Δt = {} s ({n} samples per realization)",
                opts.duration_s, opts.dt_s
            ),
            format!(
                "the run needs about {} of memory ({threads} threads, {p} outputs, {g} input processes{}) \
                     but {} are available: shorten the realizations, use fewer threads (RAYON_NUM_THREADS), a \
                     smaller --shard-size, no --store-raw, or (statistics only) --route spectral-stream",
                gib(need),
                if opts.store_raw { ", raw rows of a shard" } else { "" },
                gib(have)
            ),
        ));
    }
    Ok(())
}

/// Refuses a streamed spectral run whose working memory `need` ([`streamed_memory_bytes`]) exceeds what
/// the machine has available.
///
/// # Errors
/// [`Error::InvalidParameter`] (`block steps`) with the numbers.
pub fn check_streamed_memory(need: u128, n: usize, opts: &RunOptions) -> Result<()> {
    if let Some(have) = available_memory()
        && need > have
    {
        return Err(Error::invalid(
            "block steps",
            opts.block_steps,
            format!(
                "the streamed spectral route needs about {} of memory for its kernels and blocks (independent of \
                     the {n} samples per realization) but {} are available: fewer threads (RAYON_NUM_THREADS), a \
                     smaller block, fewer outputs or a smoother output",
                gib(need),
                gib(have)
            ),
        ));
    }
    Ok(())
}

/// Refuses a run whose file would not fit on the disk of `out`.
///
/// # Errors
/// [`Error::InvalidParameter`] (`realizations`) with the numbers and what to change.
pub fn check_disk(meta: &RunMetadata, out: &Path) -> Result<()> {
    let need = meta.estimated_file_bytes();
    let dir = out
        .parent()
        .filter(|d| !d.as_os_str().is_empty())
        .unwrap_or(Path::new("."));
    if let Some(have) = available_disk(dir)
        && need > have
    {
        return Err(Error::invalid(
            "realizations",
            meta.n_realizations,
            format!(
                "the run file would take about {} ({} realizations × {} samples{}, {} shards of accumulators) \
                     but {} are free on the disk of {}: fewer or shorter realizations, no --store-raw, or another \
                     disk",
                gib(need),
                meta.n_realizations,
                meta.n_samples,
                if meta.store_raw { ", raw data stored" } else { "" },
                meta.n_shards(),
                gib(have),
                dir.display()
            ),
        ));
    }
    Ok(())
}
