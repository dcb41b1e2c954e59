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
/// block, B ≤ 513 Welch bins (segments of M ≤ 1024), s = shard size, P threads:
/// ```text
/// per thread  n·8 (state) + b·q·8 (block) + b·8 (one row) + p·(2M + B)·8 (Welch streams and sums)
///             + 4M·8 (Welch scratch) + 6·8 (running sums)
/// shared      (2n² + q·n)·8 (transition, noise factor, output matrix) + s·p·(B + 2)·8 (the shard's results)
/// bytes       P·per thread + shared
/// ```
///
/// # Examples
/// ```
/// use stochvib::simulate::{RunOptions, resources::exact_block_memory_bytes};
/// let short = exact_block_memory_bytes(6, 3, 3, 1 << 14, 1 << 20, &RunOptions::new(10, 1e2, 0.01, 1), 2);
/// let long = exact_block_memory_bytes(6, 3, 3, 1 << 14, 1 << 40, &RunOptions::new(10, 1e2, 0.01, 1), 2);
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
    let per_thread = nx * F64 + b * q * F64 + b * F64 + p * (2 * m + bins) * F64 + 4 * m * F64 + 6 * F64;
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
/// per thread  g·F·8 (noise history) + (g + 1)·(F/2+1)·16 (segment spectra) + 2F·8 + F·16 (FFT buffers)
///             + p·H·8 (segment outputs) + p·b·8 (block) + 4·1024·8 (Welch)
/// shared      g·p·(T·8 + (F/2+1)·16) (taps, kernel spectra) + s·p·(B + 2)·8 (the shard's results)
/// design      g·p·((L/2+1)·16 + L·8) + p·L·8 (transient, before the realizations)
/// bytes       max(P·per thread + shared, design)
/// ```
///
/// # Examples
/// ```
/// use stochvib::simulate::{RunOptions, resources::{streamed_memory_bytes, StreamSizes}};
/// let z = StreamSizes { taps: 1000, fft_len: 4096, grid_len: 8192, block_steps: 16384, outputs: 2, generators: 1 };
/// let short = streamed_memory_bytes(&z, &RunOptions::new(10, 1e2, 0.01, 1), 2);
/// let long = streamed_memory_bytes(&z, &RunOptions::new(10, 1e7, 0.01, 1), 2);
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
        + 2 * f * F64
        + f * C64
        + p * hop * F64
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

/// Memory the system can still give (Linux `MemAvailable`), bytes; `None` where unknown.
pub fn available_memory() -> Option<u128> {
    let text = std::fs::read_to_string("/proc/meminfo").ok()?;
    let line = text.lines().find(|l| l.starts_with("MemAvailable:"))?;
    let kib: u128 = line.split_whitespace().nth(1)?.parse().ok()?;
    Some(kib * 1024)
}

/// Free space for an unprivileged writer on the file system of `dir`, bytes; `None` where unknown.
pub fn available_disk(dir: &Path) -> Option<u128> {
    #[cfg(unix)]
    {
        use std::os::unix::ffi::OsStrExt;
        let c = std::ffi::CString::new(dir.as_os_str().as_bytes()).ok()?;
        let mut s: libc::statvfs = unsafe { std::mem::zeroed() };
        // SAFETY: `c` is a valid NUL-terminated path and `s` a writable statvfs.
        if unsafe { libc::statvfs(c.as_ptr(), &mut s) } != 0 {
            return None;
        }
        Some(s.f_bavail as u128 * s.f_frsize as u128)
    }
    #[cfg(not(unix))]
    {
        let _ = dir;
        None
    }
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
