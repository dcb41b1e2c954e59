//! The engine of a run: one realization of every simulated output (and, for raw storage, of the input
//! processes) from its random stream, reduced to its time averages and Welch sums.

use super::plan::Plan;
use super::verdict_stream::VerdictStream;
use super::{FirSynthesis, GaussMarkov, SpectralGenerator, TimeSumLanes, TimeSums, LANES};
use crate::error::{Error, Result};
use crate::estimate::WelchSums;
use realfft::num_complex::Complex;

/// gains\[g\]\[r\]\[j\]: the transfer from generator g's FFT coefficient c_j to output r.
pub(crate) type Gains = Vec<Vec<Vec<Complex<f64>>>>;

/// For a generator of a multi-component source: its source's first generator and the mixing row of its
/// component at every bin (see `plan::raw_mixing`).
pub(crate) type RawMix = Option<(usize, Vec<Vec<Complex<f64>>>)>;

/// How a realization is produced (one per run).
#[allow(clippy::large_enum_variant)] // one engine per run
pub(crate) enum Engine {
    /// The exact Gauss–Markov recursion of the system augmented with its shaping filters.
    Exact(GaussMarkov),
    /// Spectral synthesis and the periodic steady state in the frequency domain.
    Spectral {
        generators: Vec<SpectralGenerator>,
        /// gains\[g\]\[r\]\[j\]: the transfer from generator g's coefficient c_j to output r
        gains: Gains,
        /// inverse real FFT of size N
        inverse: std::sync::Arc<dyn realfft::ComplexToReal<f64>>,
        /// raw records only: per generator of a multi-component source, its source's first generator and
        /// the mixing row at every bin (the recorded input is the component, e.g. the right track)
        raw_mix: Vec<RawMix>,
        /// non-Gaussian inputs: one Laplace moving average per generator, on the generator's grid (empty for
        /// Gaussian inputs, which draw the generators' Rayleigh coefficients)
        laplace: Vec<super::LaplaceMovingAverage>,
    },
    /// Streamed spectral synthesis: white noise through FIR kernels by overlap-save (statistics only).
    SpectralStream(FirSynthesis),
}

/// One realization's per-output results.
pub(crate) struct Realization {
    /// Time averages m_i of each output.
    pub m: Vec<f64>,
    /// Time averages v_i of the square of each output.
    pub v: Vec<f64>,
    /// Welch sums of each output.
    pub welch: Vec<WelchSums>,
    /// The samples of each output (raw storage only).
    pub raw: Vec<Vec<f64>>,
    /// The samples of each input process (raw storage only).
    pub raw_inputs: Vec<Vec<f64>>,
}

/// Working memory of one thread.
pub(crate) struct Scratch {
    x: Vec<f64>,
    buf: Vec<f64>,
    q: Vec<Vec<f64>>,
    spec: Vec<super::SpectralScratch>,
    welch: crate::estimate::WelchScratch,
    fft_in: Vec<f64>,
    fft_out: Vec<Complex<f64>>,
    fft_scratch: Vec<Complex<f64>>,
    fir: Option<super::FirScratch>,
    laplace: Vec<super::LaplaceScratch>,
    /// One output's samples of a whole record (reused from realization to realization).
    sig: Vec<f64>,
    /// A block of the lockstep realizations of the exact route (`lanes[k·stride + r][l]`).
    lanes: Vec<[f64; LANES]>,
}

impl Scratch {
    /// Working memory for `plan`.
    pub(crate) fn new(plan: &Plan) -> Scratch {
        // the whole-record FFT buffers only for the whole-record spectral route
        let (nx, nq, nfft, n) = match &plan.engine {
            Engine::Exact(gm) => (gm.n_states(), 0, 0, 0),
            Engine::Spectral {
                generators, inverse, ..
            } => (0, generators.len(), inverse.get_scratch_len(), plan.n),
            Engine::SpectralStream(_) => (0, 0, 0, 0),
        };
        let rows = if plan.block_steps > 0 { plan.block_steps } else { plan.n };
        Scratch {
            x: vec![0.0; nx],
            buf: vec![0.0; rows * plan.stride],
            q: vec![vec![0.0; n]; nq],
            spec: match &plan.engine {
                Engine::Spectral { generators, .. } => generators.iter().map(|g| g.scratch()).collect(),
                Engine::Exact(_) | Engine::SpectralStream(_) => vec![],
            },
            welch: plan.welch.scratch(),
            fft_in: vec![0.0; n],
            fft_out: vec![Complex::new(0.0, 0.0); if n > 0 { n / 2 + 1 } else { 0 }],
            fft_scratch: vec![Complex::new(0.0, 0.0); nfft],
            fir: match &plan.engine {
                Engine::SpectralStream(fir) => Some(fir.scratch()),
                _ => None,
            },
            laplace: match &plan.engine {
                Engine::Spectral { laplace, .. } => laplace.iter().map(|l| l.scratch()).collect(),
                _ => vec![],
            },
            sig: Vec::new(),
            lanes: match &plan.engine {
                Engine::Exact(_) if plan.block_steps > 0 => vec![[0.0; LANES]; plan.block_steps * plan.stride],
                _ => vec![],
            },
        }
    }
}

/// One realization of the exact route in blocks of `plan.block_steps` steps, with memory O(block): the
/// state is carried from block to block, the time sums are fed in time order ([`TimeSums`]: the same bits
/// for any blocks) and the Welch segments are fed as they fill, so the results are bit-identical to a
/// whole-record realization (same draws from `rng`, same additions in the same order).
fn realize_in_blocks(
    plan: &Plan,
    gm: &GaussMarkov,
    s: &mut Scratch,
    rng: &mut rand::rngs::Xoshiro256PlusPlus,
    mut verdicts: Option<&mut VerdictStream>,
) -> Result<Realization> {
    let (n, p, stride, block) = (plan.n, plan.outputs.len(), plan.stride, plan.block_steps);
    gm.initial_state(rng, &mut s.x);
    let mut sums = vec![TimeSums::new(); p];
    let mut streams: Vec<_> = (0..p).map(|_| plan.welch.stream()).collect();
    let mut welch: Vec<WelchSums> = (0..p).map(|_| plan.welch.sums()).collect();
    let mut sig = vec![0.0; block];
    let mut done = 0;
    while done < n {
        let b = block.min(n - done);
        gm.advance(&mut s.x, rng, &mut s.buf[..b * stride]);
        for r in 0..p {
            for (k, v) in sig[..b].iter_mut().enumerate() {
                *v = s.buf[k * stride + r];
            }
            sums[r].push(&sig[..b]);
            plan.welch
                .push(&mut streams[r], &sig[..b], &mut welch[r], &mut s.welch)?;
            if let Some(v) = verdicts.as_deref_mut() {
                v.push(r, &sig[..b])?;
            }
        }
        done += b;
    }
    finish_blocks(plan, &sums, &mut streams, welch)
}

/// Realizations `first .. first + LANES` of `seed` on the exact route in lockstep ([`GaussMarkov::lanes`]),
/// in blocks of `plan.block_steps` steps: each lane's running sums, Welch segments and `verdicts[l]` are
/// fed with that lane's block in time order, as [`realize_in_blocks`] feeds them for the realization
/// alone, so every result is bit-identical to it.
pub(crate) fn realize_lanes(
    plan: &Plan,
    gm: &GaussMarkov,
    s: &mut Scratch,
    (seed, first): (u64, u64),
    mut verdicts: Option<&mut [VerdictStream]>,
) -> Result<Vec<Realization>> {
    let (n, p, stride, block) = (plan.n, plan.outputs.len(), plan.stride, plan.block_steps);
    let mut lanes = gm.lanes(seed, first);
    let mut sums = vec![TimeSumLanes::new(); p];
    let mut streams: Vec<Vec<_>> = (0..LANES)
        .map(|_| (0..p).map(|_| plan.welch.stream()).collect())
        .collect();
    let mut welch: Vec<Vec<WelchSums>> = (0..LANES)
        .map(|_| (0..p).map(|_| plan.welch.sums()).collect())
        .collect();
    let mut sig = vec![0.0; block];
    let mut done = 0;
    while done < n {
        let b = block.min(n - done);
        let buf = &mut s.lanes[..b * stride];
        lanes.fill(buf);
        for r in 0..p {
            sums[r].push(buf.iter().skip(r).step_by(stride).copied());
            for l in 0..LANES {
                for (v, y) in sig[..b].iter_mut().zip(buf.iter().skip(r).step_by(stride)) {
                    *v = y[l];
                }
                plan.welch
                    .push(&mut streams[l][r], &sig[..b], &mut welch[l][r], &mut s.welch)?;
                if let Some(v) = verdicts.as_deref_mut() {
                    v[l].push(r, &sig[..b])?;
                }
            }
        }
        done += b;
    }
    (0..LANES)
        .map(|l| {
            let sums: Vec<TimeSums> = sums.iter().map(|s| s.lane(l)).collect();
            finish_blocks(plan, &sums, &mut streams[l], std::mem::take(&mut welch[l]))
        })
        .collect()
}

/// The realization of the time sums (per output) and Welch streams and sums after the last block: the
/// records' ends fed to Welch, the time averages.
fn finish_blocks(
    plan: &Plan,
    sums: &[TimeSums],
    streams: &mut [crate::estimate::WelchStream],
    mut welch: Vec<WelchSums>,
) -> Result<Realization> {
    for (st, ws) in streams.iter_mut().zip(welch.iter_mut()) {
        plan.welch.end_record(st, ws)?;
    }
    Ok(Realization {
        m: sums.iter().map(|s| s.averages().0).collect(),
        v: sums.iter().map(|s| s.averages().1).collect(),
        welch,
        raw: Vec::new(),
        raw_inputs: Vec::new(),
    })
}

/// One realization of the streamed spectral route: whole overlap-save segments of H samples (H fixed by the
/// kernels), grouped into blocks of at least `plan.block_steps` samples, each block fed to the running sums
/// and the Welch segments in time order; memory O(F + block). The draws come per segment, so the results
/// are bit-identical for any block size.
fn realize_streamed(
    plan: &Plan,
    fir: &FirSynthesis,
    s: &mut Scratch,
    rng: &mut rand::rngs::Xoshiro256PlusPlus,
    mut verdicts: Option<&mut VerdictStream>,
) -> Result<Realization> {
    let (n, p, hop) = (plan.n, plan.outputs.len(), fir.hop());
    let fs = s.fir.as_mut().ok_or_else(|| Error::Numerical {
        what: "streamed spectral synthesis".into(),
        reason: "scratch made for another route".into(),
    })?;
    let segments = plan.block_steps.max(1).div_ceil(hop);
    fir.start(rng, fs);
    let mut sums = vec![TimeSums::new(); p];
    let mut streams: Vec<_> = (0..p).map(|_| plan.welch.stream()).collect();
    let mut welch: Vec<WelchSums> = (0..p).map(|_| plan.welch.sums()).collect();
    let mut block = vec![vec![0.0; segments * hop]; p];
    let mut done = 0;
    while done < n {
        let mut filled = 0;
        for _ in 0..segments {
            if done + filled >= n {
                break;
            }
            fir.next_segment(rng, fs)?;
            let take = hop.min(n - done - filled);
            for (r, b) in block.iter_mut().enumerate() {
                b[filled..filled + take].copy_from_slice(&fir.output(fs, r)[..take]);
            }
            filled += take;
        }
        for r in 0..p {
            sums[r].push(&block[r][..filled]);
            plan.welch
                .push(&mut streams[r], &block[r][..filled], &mut welch[r], &mut s.welch)?;
            if let Some(v) = verdicts.as_deref_mut() {
                v.push(r, &block[r][..filled])?;
            }
        }
        done += filled;
    }
    finish_blocks(plan, &sums, &mut streams, welch)
}

/// One realization from `rng` (the stream (seed, i) of realization i); the block-wise routes also feed
/// `verdicts` block by block (the whole-record routes leave it untouched).
///
/// # Errors
/// An FFT or Welch failure (never for a valid plan).
pub(crate) fn realize(
    plan: &Plan,
    s: &mut Scratch,
    rng: &mut rand::rngs::Xoshiro256PlusPlus,
    keep_raw: bool,
    verdicts: Option<&mut VerdictStream>,
) -> Result<Realization> {
    let n = plan.n;
    let p = plan.outputs.len();
    match &plan.engine {
        Engine::Exact(gm) if plan.block_steps > 0 && !keep_raw => return realize_in_blocks(plan, gm, s, rng, verdicts),
        Engine::SpectralStream(fir) if !keep_raw => return realize_streamed(plan, fir, s, rng, verdicts),
        _ => fill(plan, s, rng, keep_raw)?,
    }
    let mut out = Realization {
        m: Vec::with_capacity(p),
        v: Vec::with_capacity(p),
        welch: Vec::with_capacity(p),
        raw: Vec::new(),
        raw_inputs: Vec::new(),
    };
    if keep_raw {
        out.raw_inputs = raw_inputs(plan, s);
    }
    let stride = plan.stride;
    let mut sig = std::mem::take(&mut s.sig);
    sig.resize(n, 0.0);
    for r in 0..p {
        for (k, v) in sig.iter_mut().enumerate() {
            *v = s.buf[k * stride + r];
        }
        let mut sums = TimeSums::new();
        sums.push(&sig);
        let (m, v) = sums.averages();
        out.m.push(m);
        out.v.push(v);
        let mut ws = plan.welch.sums();
        plan.welch.accumulate(&sig, &mut ws, &mut s.welch)?;
        out.welch.push(ws);
        if keep_raw {
            out.raw.push(sig.clone());
        }
    }
    s.sig = sig;
    Ok(out)
}

/// The samples of every output and of every input process of one realization (`samples[r][k]`).
pub(crate) type Samples = (Vec<Vec<f64>>, Vec<Vec<f64>>);

/// One realization's samples of every output and, with `inputs`, of every input process: the draws and
/// the bits of [`realize`] with `keep_raw`, without its time averages and Welch sums (for a caller that
/// only needs the samples: route 2's input synthesis).
///
/// # Errors
/// An FFT failure; the streamed spectral route (it keeps no samples).
pub(crate) fn samples(
    plan: &Plan,
    s: &mut Scratch,
    rng: &mut rand::rngs::Xoshiro256PlusPlus,
    inputs: bool,
) -> Result<Samples> {
    fill(plan, s, rng, inputs)?;
    let stride = plan.stride;
    let raw = (0..plan.outputs.len())
        .map(|r| (0..plan.n).map(|k| s.buf[k * stride + r]).collect())
        .collect();
    Ok((raw, if inputs { raw_inputs(plan, s) } else { Vec::new() }))
}

/// The samples of every input process of a whole-record realization in `s`.
fn raw_inputs(plan: &Plan, s: &Scratch) -> Vec<Vec<f64>> {
    match &plan.engine {
        Engine::Exact(_) => (plan.outputs.len()..plan.stride)
            .map(|r| (0..plan.n).map(|k| s.buf[k * plan.stride + r]).collect())
            .collect(),
        // the recorded period is aligned with the input processes' own samples
        Engine::Spectral { .. } => s.q.clone(),
        Engine::SpectralStream(_) => Vec::new(),
    }
}

/// The samples of a whole-record realization into `s.buf` (and with `keep_raw` the input processes into
/// `s.q` on the spectral route).
fn fill(plan: &Plan, s: &mut Scratch, rng: &mut rand::rngs::Xoshiro256PlusPlus, keep_raw: bool) -> Result<()> {
    let n = plan.n;
    let p = plan.outputs.len();
    match &plan.engine {
        Engine::SpectralStream(_) => {
            return Err(Error::invalid(
                "store raw",
                true,
                "the streamed spectral route keeps no realizations (statistics only)",
            ))
        }
        Engine::Exact(gm) => {
            gm.initial_state(rng, &mut s.x);
            gm.advance(&mut s.x, rng, &mut s.buf);
        }
        Engine::Spectral {
            generators,
            gains,
            inverse,
            raw_mix,
            laplace,
        } => {
            let fft_err = |e: realfft::FftError| Error::Numerical {
                what: "inverse real FFT".into(),
                reason: e.to_string(),
            };
            if laplace.is_empty() {
                for (g, sc) in generators.iter().zip(s.spec.iter_mut()) {
                    g.draw(rng, sc);
                }
            } else {
                for ((l, w), sc) in laplace.iter().zip(s.laplace.iter_mut()).zip(s.spec.iter_mut()) {
                    l.draw_with(rng, w, sc)?;
                }
            }
            let half = n / 2;
            for r in 0..p {
                // output r's coefficients: 0 + Σ_g G_{g,r}(ω_j) c_{g,j} in generator order, one generator at a
                // time over every bin (compiled for the widest instruction set, the same bits), then one
                // inverse FFT
                let mut terms = gains.iter().zip(&s.spec);
                match terms.next() {
                    Some((gain, sc)) => {
                        crate::linalg::vmath::complex_mul_from_zero(&mut s.fft_out, &gain[r], sc.coefficients())
                    }
                    None => s.fft_out.fill(Complex::new(0.0, 0.0)),
                }
                for (gain, sc) in terms {
                    crate::linalg::vmath::complex_mul_add(&mut s.fft_out, &gain[r], sc.coefficients());
                }
                s.fft_out[0].im = 0.0;
                s.fft_out[half].im = 0.0;
                inverse
                    .process_with_scratch(&mut s.fft_out, &mut s.fft_in, &mut s.fft_scratch)
                    .map_err(fft_err)?;
                for (k, v) in s.fft_in.iter().enumerate() {
                    s.buf[k * p + r] = *v;
                }
            }
            if keep_raw {
                for (g, (q, sc)) in s.q.iter_mut().zip(&s.spec).enumerate() {
                    match &raw_mix[g] {
                        None => {
                            for (o, c) in s.fft_out.iter_mut().zip(sc.coefficients()) {
                                *o = *c;
                            }
                        }
                        // a component of a multi-component source: Σ_k M_ck(ω_j) c_{k,j}
                        Some((first, rows)) => {
                            for (j, o) in s.fft_out.iter_mut().enumerate() {
                                *o = rows[j]
                                    .iter()
                                    .enumerate()
                                    .map(|(k, m)| m * s.spec[first + k].coefficients()[j])
                                    .sum();
                            }
                            s.fft_out[0].im = 0.0;
                            s.fft_out[half].im = 0.0;
                        }
                    }
                    inverse
                        .process_with_scratch(&mut s.fft_out, q, &mut s.fft_scratch)
                        .map_err(fft_err)?;
                }
            }
        }
    }
    Ok(())
}
