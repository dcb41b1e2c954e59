//! Adaptive Gauss–Kronrod quadrature with interval splitting, breakpoints and mapped infinite ranges.
//!
//! # Rule
//! Every subinterval is integrated with the 21-point Kronrod extension of the 10-point Gauss–Legendre
//! rule (G10/K21, the rule of QUADPACK's `QK21` used by `QAGS`, and by `scipy.integrate.quad` on finite
//! ranges). K21 integrates polynomials of degree 31 exactly with 21 evaluations, against degree 23 for
//! the 15 evaluations of G7/K15. The integrands of this crate (spectral densities times squared transfer
//! functions) are smooth away from a few narrow resonance peaks, and the requested accuracy is high
//! (default `rel_tol = 1e-10`): there the higher degree of K21 means fewer subintervals, fewer heap
//! operations and fewer evaluations in total than K15. K21 is used on mapped infinite ranges too.
//!
//! # Algorithm
//! Globally adaptive (QUADPACK `QAG`-style, without the ε-algorithm extrapolation of `QAGS`): the
//! subinterval with the largest error estimate is taken from a max-heap and bisected, until the sum of
//! the error estimates is at most `max(abs_tol, rel_tol·|value|)`, or every subinterval is down to its
//! roundoff floor, or `max_subintervals` is reached (an error). The value and error are summed
//! (compensated) over all subintervals again before returning, free of the drift of running updates.
//!
//! Infinite ranges are mapped onto `[0, 1)`: a tail `[c, ∞)` by `x = c + L·t/(1−t)`, a head `(−∞, c]`
//! by `x = c − L·t/(1−t)`. When breakpoints are given on an infinite range, the range is split into
//! finite pieces between the breakpoints, extended by one breakpoint scale `d` beyond the outermost
//! breakpoints, plus mapped tails beyond that; so resonance peaks are resolved in `x` exactly as on a
//! finite range, and the tails only see the smooth decay. The map scale is `L = max(|c|, d)`, which
//! makes power-law tails `|x|^−p` polynomial in `t` when `c` is the natural origin.
//!
//! # Contract
//! `integrate(f, a, b, &QuadOptions)` integrates `f` over `[a, b]`, where `a` may be `-inf` and `b` may be
//! `+inf`, returning the value, an absolute error estimate and the number of evaluations, or
//! [`Error::Quadrature`] with the best estimate when the tolerance is not met.

use std::cmp::Ordering;
use std::collections::BinaryHeap;

use crate::error::{Error, Result};

/// Tolerances and hints for [`integrate`].
#[derive(Debug, Clone)]
pub struct QuadOptions {
    /// Relative tolerance on the value.
    pub rel_tol: f64,
    /// Absolute tolerance on the value.
    pub abs_tol: f64,
    /// Maximum number of subintervals before giving up.
    pub max_subintervals: usize,
    /// Points inside (a, b) where the integrand has peaks or kinks (resonances, band edges).
    pub breakpoints: Vec<f64>,
}

impl Default for QuadOptions {
    fn default() -> Self {
        QuadOptions {
            rel_tol: 1e-10,
            abs_tol: 0.0,
            max_subintervals: 2000,
            breakpoints: Vec::new(),
        }
    }
}

/// Outcome of a converged quadrature.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct QuadResult {
    /// The integral.
    pub value: f64,
    /// Estimated absolute error.
    pub abs_error: f64,
    /// Integrand evaluations used.
    pub evaluations: usize,
}

// Gauss–Kronrod G10/K21 constants, from QUADPACK `dqk21.f` (Piessens, de Doncker-Kapenga, Überhuber,
// Kahaner 1983; computed by L. W. Fullerton in 80-digit arithmetic), reproduced to the published 33
// digits. Only the non-negative abscissae are stored; the rule is symmetric.
// Checked: K21 integrates x^k exactly on [-1, 1] for k <= 31, G10 for k <= 19 (50-digit mpmath).

/// Abscissae of the 21-point Kronrod rule: `XGK[1], XGK[3], …, XGK[9]` are the 10-point Gauss
/// abscissae, `XGK[0], XGK[2], …` the Kronrod extension, `XGK[10] = 0` the centre.
#[allow(clippy::excessive_precision)] // the published 33-digit constants, kept verbatim
const XGK: [f64; 11] = [
    0.995_657_163_025_808_080_735_527_280_689_003,
    0.973_906_528_517_171_720_077_964_012_084_452,
    0.930_157_491_355_708_226_001_207_180_059_508,
    0.865_063_366_688_984_510_732_096_688_423_493,
    0.780_817_726_586_416_897_063_717_578_345_042,
    0.679_409_568_299_024_406_234_327_365_114_874,
    0.562_757_134_668_604_683_339_000_099_272_694,
    0.433_395_394_129_247_190_799_265_943_165_784,
    0.294_392_862_701_460_198_131_126_603_103_866,
    0.148_874_338_981_631_210_884_826_001_129_720,
    0.0,
];

/// Weights of the 21-point Kronrod rule, matching [`XGK`].
#[allow(clippy::excessive_precision)] // the published 33-digit constants, kept verbatim
const WGK: [f64; 11] = [
    0.011_694_638_867_371_874_278_064_396_062_192,
    0.032_558_162_307_964_727_478_818_972_459_390,
    0.054_755_896_574_351_996_031_381_300_244_580,
    0.075_039_674_810_919_952_767_043_140_916_190,
    0.093_125_454_583_697_605_535_065_465_083_366,
    0.109_387_158_802_297_641_899_210_590_325_805,
    0.123_491_976_262_065_851_077_958_109_831_074,
    0.134_709_217_311_473_325_928_054_001_771_707,
    0.142_775_938_577_060_080_797_094_273_138_717,
    0.147_739_104_901_338_491_374_841_515_972_068,
    0.149_445_554_002_916_905_664_936_468_389_821,
];

/// Weights of the 10-point Gauss rule, for the abscissae `XGK[1], XGK[3], …, XGK[9]`.
#[allow(clippy::excessive_precision)] // the published 33-digit constants, kept verbatim
const WG: [f64; 5] = [
    0.066_671_344_308_688_137_593_568_809_893_332,
    0.149_451_349_150_580_593_145_776_339_657_697,
    0.219_086_362_515_982_043_995_534_934_228_163,
    0.269_266_719_309_996_355_091_226_921_569_469,
    0.295_524_224_714_752_870_173_892_994_651_338,
];

/// Evaluations per application of the rule.
const NODES: usize = 21;

/// How a piece of the integration range is parametrised: `x = x(u)`, integrand `f(x(u))·x'(u)`.
#[derive(Debug, Clone, Copy)]
enum Map {
    /// `x = u`.
    Identity,
    /// `x = c + l·u/(1−u)`, `u ∈ [0, 1)`: the tail `[c, ∞)`.
    Tail { c: f64, l: f64 },
    /// `x = c − l·u/(1−u)`, `u ∈ [0, 1)`: the head `(−∞, c]`.
    Head { c: f64, l: f64 },
}

impl Map {
    /// The integration variable `x` at parameter `u`.
    #[inline(always)]
    fn x(self, u: f64) -> f64 {
        match self {
            Map::Identity => u,
            Map::Tail { c, l } => c + l * (u / (1.0 - u)),
            Map::Head { c, l } => c - l * (u / (1.0 - u)),
        }
    }

    /// `f(x(u))·|x'(u)|`, so that both `∫_c^∞ f dx` and `∫_{−∞}^c f dx` equal `∫_0^1 f(x(u)) l/(1−u)² du`.
    /// A zero `f` gives 0 even where the Jacobian overflows.
    #[inline(always)]
    fn eval<F: Fn(f64) -> f64>(self, f: &F, u: f64) -> f64 {
        match self {
            Map::Identity => f(u),
            Map::Tail { l, .. } | Map::Head { l, .. } => {
                let x = self.x(u);
                if x.is_infinite() {
                    // Only when u has rounded to 1 inside a subinterval of width ~ε at the singular end;
                    // an integrable f vanishes there.
                    return 0.0;
                }
                let fx = f(x);
                if fx == 0.0 {
                    return 0.0;
                }
                let s = 1.0 - u;
                fx * (l / s) / s
            }
        }
    }
}

/// One subinterval `[lo, hi]` of a piece, in the piece's parameter `u`, with its K21 estimate.
#[derive(Debug, Clone, Copy)]
struct Segment {
    lo: f64,
    hi: f64,
    map: Map,
    value: f64,
    error: f64,
    /// The error estimate is at the roundoff floor of the subinterval: bisecting cannot improve it.
    at_floor: bool,
}

impl PartialEq for Segment {
    fn eq(&self, other: &Self) -> bool {
        self.cmp(other) == Ordering::Equal
    }
}
impl Eq for Segment {}
impl PartialOrd for Segment {
    fn partial_cmp(&self, other: &Self) -> Option<Ordering> {
        Some(self.cmp(other))
    }
}
impl Ord for Segment {
    fn cmp(&self, other: &Self) -> Ordering {
        self.error.total_cmp(&other.error)
    }
}

/// Why a single application of the rule failed.
enum RuleFailure {
    /// The (mapped) integrand was NaN or infinite at parameter `u`.
    NotFinite { u: f64 },
    /// All values finite but the weighted sum overflowed.
    Overflow,
}

/// Applies G10/K21 to `f` over `[lo, hi]` in the parameter of `map`, with QUADPACK's error estimate:
/// `err = resasc·min(1, (200·|K−G|/resasc)^1.5)`, raised to at least `50 ε resabs`.
#[inline]
fn gk21<F: Fn(f64) -> f64>(f: &F, map: Map, lo: f64, hi: f64) -> std::result::Result<Segment, RuleFailure> {
    let centre = 0.5 * (lo + hi);
    let half = 0.5 * (hi - lo);
    let abs_half = half.abs();

    let fc = map.eval(f, centre);
    let mut all_finite = fc.is_finite();
    let mut res_g = 0.0;
    let mut res_k = WGK[10] * fc;
    let mut res_abs = res_k.abs();
    let mut fv1 = [0.0f64; 10];
    let mut fv2 = [0.0f64; 10];
    for j in 0..10 {
        let dx = half * XGK[j];
        let f1 = map.eval(f, centre - dx);
        let f2 = map.eval(f, centre + dx);
        all_finite &= f1.is_finite() & f2.is_finite();
        fv1[j] = f1;
        fv2[j] = f2;
        let sum = f1 + f2;
        res_k += WGK[j] * sum;
        res_abs += WGK[j] * (f1.abs() + f2.abs());
        if j % 2 == 1 {
            res_g += WG[j / 2] * sum;
        }
    }
    if !all_finite {
        let u = if !fc.is_finite() {
            centre
        } else {
            let j = (0..10)
                .find(|&j| !fv1[j].is_finite() || !fv2[j].is_finite())
                .unwrap_or(0);
            if fv1[j].is_finite() {
                centre + half * XGK[j]
            } else {
                centre - half * XGK[j]
            }
        };
        return Err(RuleFailure::NotFinite { u });
    }

    let mean = 0.5 * res_k;
    let mut res_asc = WGK[10] * (fc - mean).abs();
    for j in 0..10 {
        res_asc += WGK[j] * ((fv1[j] - mean).abs() + (fv2[j] - mean).abs());
    }
    let value = res_k * half;
    res_abs *= abs_half;
    res_asc *= abs_half;
    let mut error = ((res_k - res_g) * half).abs();
    if res_asc != 0.0 && error != 0.0 {
        let r = 200.0 * error / res_asc;
        error = if r < 1.0 { res_asc * r * r.sqrt() } else { res_asc };
    }
    // Roundoff floors. QUADPACK's: the sum itself is not accurate beyond ~50 ε ∫|f|. Ours in addition:
    // the nodes m ± h·x_i are rounded by up to ε·max(|α|, |β|), which changes the sum by about that
    // times ∫|f'| ≈ 2·resasc/h; this dominates on tiny subintervals of a sharp peak far from the
    // origin (width ~ ζ·ω0), where it limits the attainable relative accuracy to ~ ε/ζ.
    let mut floor = 0.0f64;
    if res_abs > f64::MIN_POSITIVE / (50.0 * f64::EPSILON) {
        floor = 50.0 * f64::EPSILON * res_abs;
    }
    if abs_half > 0.0 {
        floor = floor.max(f64::EPSILON * (lo.abs().max(hi.abs()) / abs_half) * res_asc);
    }
    let at_floor = error <= floor;
    error = error.max(floor);
    if !value.is_finite() || !error.is_finite() {
        return Err(RuleFailure::Overflow);
    }
    Ok(Segment {
        lo,
        hi,
        map,
        value,
        error,
        at_floor,
    })
}

/// Splits `[a, b]` (`a < b`, either may be infinite) into pieces `(map, u_lo, u_hi)` at the breakpoints.
///
/// # Formula
/// Finite ends: the pieces between consecutive points of a, the breakpoints, b. An infinite end beyond the
/// outermost breakpoint p gets a finite piece to p ± d first (d the largest of |p| and the breakpoints'
/// span, else 1) and then a tail map from p ± d with length scale max(|p ± d|, d); without breakpoints the
/// tail starts at the finite end (scale max(|end|, 1)), or both tails at 0 (scale 1).
fn pieces(a: f64, b: f64, breakpoints: &[f64]) -> Vec<(Map, f64, f64)> {
    let mut bps: Vec<f64> = breakpoints
        .iter()
        .copied()
        .filter(|&p| p.is_finite() && a < p && p < b)
        .collect();
    bps.sort_by(f64::total_cmp);
    bps.dedup();
    let head = |c: f64, l: f64| (Map::Head { c, l }, 0.0, 1.0);
    let tail = |c: f64, l: f64| (Map::Tail { c, l }, 0.0, 1.0);
    let mut out = Vec::with_capacity(bps.len() + 3);
    match (a.is_finite(), b.is_finite(), bps.first(), bps.last()) {
        (true, true, _, _) => finite_pieces(a, &bps, b, &mut out),
        (true, false, _, None) => out.push(tail(a, a.abs().max(1.0))),
        (true, false, _, Some(&pn)) => {
            let d = scale(&[pn.abs(), pn - a]);
            let hi = pn + d;
            finite_pieces(a, &bps, hi, &mut out);
            out.push(tail(hi, hi.abs().max(d)));
        }
        (false, true, None, _) => out.push(head(b, b.abs().max(1.0))),
        (false, true, Some(&p1), _) => {
            let d = scale(&[p1.abs(), b - p1]);
            let lo = p1 - d;
            out.push(head(lo, lo.abs().max(d)));
            finite_pieces(lo, &bps, b, &mut out);
        }
        (false, false, Some(&p1), Some(&pn)) => {
            let d = scale(&[p1.abs(), pn.abs(), pn - p1]);
            let (lo, hi) = (p1 - d, pn + d);
            out.push(head(lo, lo.abs().max(d)));
            finite_pieces(lo, &bps, hi, &mut out);
            out.push(tail(hi, hi.abs().max(d)));
        }
        (false, false, _, _) => {
            out.push(head(0.0, 1.0));
            out.push(tail(0.0, 1.0));
        }
    }
    out
}

/// Appends the identity-mapped pieces between consecutive points of `lo`, `bps`, `hi` (empty ones left out).
fn finite_pieces(lo: f64, bps: &[f64], hi: f64, out: &mut Vec<(Map, f64, f64)>) {
    let mut pts = Vec::with_capacity(bps.len() + 2);
    pts.push(lo);
    pts.extend_from_slice(bps);
    pts.push(hi);
    for w in pts.windows(2) {
        if w[0] < w[1] {
            out.push((Map::Identity, w[0], w[1]));
        }
    }
}

/// The largest of `candidates`, or 1 if that is not a positive finite number.
fn scale(candidates: &[f64]) -> f64 {
    let d = candidates.iter().copied().fold(0.0f64, f64::max);
    if d > 0.0 && d.is_finite() {
        d
    } else {
        1.0
    }
}

/// The subintervals of a running integration.
struct Partition {
    /// Subintervals that may still be bisected, worst error on top.
    active: BinaryHeap<Segment>,
    /// Subintervals whose error is at their roundoff floor: bisecting them cannot help.
    settled: Vec<Segment>,
}

impl Partition {
    fn len(&self) -> usize {
        self.active.len() + self.settled.len()
    }

    fn push(&mut self, s: Segment) {
        if s.at_floor {
            self.settled.push(s);
        } else {
            self.active.push(s);
        }
    }

    /// Neumaier-compensated sum of the values, and sum of the error estimates, of all subintervals.
    fn totals(&self) -> (f64, f64) {
        let (mut sum, mut comp, mut err) = (0.0f64, 0.0f64, 0.0f64);
        for s in self.active.iter().chain(self.settled.iter()) {
            let t = sum + s.value;
            comp += if sum.abs() >= s.value.abs() {
                (sum - t) + s.value
            } else {
                (s.value - t) + sum
            };
            sum = t;
            err += s.error;
        }
        (sum + comp, err)
    }
}

/// Integrates `f` over `[a, b]` (infinite limits allowed) by globally adaptive G10/K21 Gauss–Kronrod
/// quadrature.
///
/// # Formula
/// On each subinterval `[α, β]` with centre `m = (α+β)/2` and half-width `h = (β−α)/2`,
///
/// ```text
/// K = h Σ_{i=1}^{21} w_i^K f(m + h x_i),   G = h Σ_{j=1}^{10} w_j^G f(m + h x_{2j}),
/// resasc = h Σ w_i^K |f(m + h x_i) − K/(2h)|,   resabs = h Σ w_i^K |f(m + h x_i)|,
/// err = max( resasc · min(1, (200 |K − G| / resasc)^{3/2}),  50 ε resabs,  ε (max(|α|,|β|)/h) resasc )
/// ```
///
/// (QUADPACK `QK21`, plus the last term: the effect of rounding the nodes, which bounds the attainable
/// accuracy on the tiny subintervals of a sharp peak far from 0); `K` is the value, `err` its error
/// estimate. The subinterval with the largest `err`
/// is bisected until `Σ err ≤ max(abs_tol, rel_tol·|Σ K|)`. Infinite limits are mapped to `[0, 1)`:
///
/// ```text
/// ∫_c^∞ f(x) dx = ∫_0^1 f(c + L t/(1−t)) · L/(1−t)² dt,   ∫_{−∞}^c f(x) dx = ∫_0^1 f(c − L t/(1−t)) · L/(1−t)² dt
/// ```
///
/// with `L = max(|c|, 1)` without breakpoints (`(−∞, ∞)` is split at 0). With breakpoints `p₁ < … < pₙ`
/// the pieces between breakpoints stay in `x`, the finite part is extended to `pₙ + d` (and/or
/// `p₁ − d`) with `d` the breakpoint scale (`max(|pₙ|, pₙ − a)` for `[a, ∞)`), and only the rest is
/// mapped, with `L = max(|c|, d)`. The Gauss–Kronrod nodes are interior, so `f` is never evaluated at
/// `a`, `b`, a breakpoint or `t = 1`.
///
/// Breakpoints outside the open interval `(a, b)` and non-finite ones are ignored; the rest are sorted
/// and deduplicated and split the initial range, so peaks and kinks at them are resolved.
///
/// Subintervals whose error estimate is at its roundoff floor (the last two terms) are not bisected
/// further. When only such subintervals remain before the tolerance is met (a value that cancels to 0
/// with `abs_tol = 0`, or `rel_tol` below ~ε/ζ for a peak of relative width ζ), tighter accuracy is not
/// attainable in double precision: the result is returned with the sum of those floors as `abs_error`,
/// so `abs_error` may then exceed the requested tolerance.
///
/// # Errors
/// - [`Error::InvalidParameter`] if `a` or `b` is NaN, `a > b`, or `rel_tol` / `abs_tol` is negative
///   or NaN. `a == b` gives `value = 0` with no evaluations.
/// - [`Error::Quadrature`] if `f` (or `f` times the Jacobian of a tail map) is NaN or infinite at a node
///   (`reason` says `integrand not finite at x = …`), if `max_subintervals` is reached before the
///   tolerance, or if a subinterval becomes too small to bisect (a non-integrable singularity); `estimate`
///   and `abs_error` then hold the best estimate so far.
///
/// # Examples
/// ```
/// use stochvib::quad::{integrate, QuadOptions};
///
/// // ∫_{-∞}^{∞} dx / (1 + x²) = π
/// let r = integrate(|x| 1.0 / (1.0 + x * x), f64::NEG_INFINITY, f64::INFINITY, &QuadOptions::default())?;
/// assert!((r.value - std::f64::consts::PI).abs() < 1e-12);
/// assert!(r.abs_error < 1e-9);
///
/// // A lightly damped resonance, with its peak given as a breakpoint:
/// // ∫_0^∞ dω / ((ω0² − ω²)² + (2ζω0ω)²) = π / (4ζω0³)
/// let (w0, zeta) = (50.0, 0.01);
/// let opts = QuadOptions { breakpoints: vec![w0], ..QuadOptions::default() };
/// let r = integrate(
///     |w| 1.0 / ((w0 * w0 - w * w).powi(2) + (2.0 * zeta * w0 * w).powi(2)),
///     0.0,
///     f64::INFINITY,
///     &opts,
/// )?;
/// let exact = std::f64::consts::PI / (4.0 * zeta * w0.powi(3));
/// assert!((r.value - exact).abs() <= 1e-10 * exact);
/// # Ok::<(), stochvib::Error>(())
/// ```
pub fn integrate(f: impl Fn(f64) -> f64, a: f64, b: f64, opts: &QuadOptions) -> Result<QuadResult> {
    check_arguments(a, b, opts)?;
    if a == b {
        return Ok(QuadResult {
            value: 0.0,
            abs_error: 0.0,
            evaluations: 0,
        });
    }

    let pieces = pieces(a, b, &opts.breakpoints);
    let mut part = Partition {
        active: BinaryHeap::with_capacity(opts.max_subintervals.clamp(16, 4096)),
        settled: Vec::new(),
    };
    let mut evaluations = 0usize;
    let tolerance = |value: f64| opts.abs_tol.max(opts.rel_tol * value.abs());

    let failure = |fail: RuleFailure, map: Map, lo: f64, hi: f64, part: &Partition, evaluations: usize| {
        rule_failure(&f, (fail, map, lo, hi), part, evaluations)
    };

    // Running sums, updated incrementally; recomputed exactly before any decision to stop.
    let (mut value, mut error) = (0.0f64, 0.0f64);
    for &(map, lo, hi) in &pieces {
        evaluations += NODES;
        match gk21(&f, map, lo, hi) {
            Ok(s) => {
                value += s.value;
                error += s.error;
                part.push(s);
            }
            Err(e) => return Err(failure(e, map, lo, hi, &part, evaluations)),
        }
    }

    loop {
        if error <= tolerance(value) || part.active.is_empty() {
            (value, error) = part.totals();
            // Converged, or every subinterval is at its roundoff floor (the tolerance is below what
            // double precision can deliver; abs_error says what was reached).
            if error <= tolerance(value) || part.active.is_empty() {
                return Ok(QuadResult {
                    value,
                    abs_error: error,
                    evaluations,
                });
            }
        }
        let Some(worst) = part.active.pop() else {
            return Ok(QuadResult {
                value,
                abs_error: error,
                evaluations,
            }); // not reached: checked above
        };
        let (x_lo, x_hi) = (worst.map.x(worst.lo), worst.map.x(worst.hi));
        if part.len() + 1 >= opts.max_subintervals.max(1) {
            let reason = format!(
                "maximum of {} subintervals reached; the largest error estimate {:e} is on [{x_lo:e}, {x_hi:e}] \
                 (add a breakpoint there, or raise max_subintervals or the tolerance)",
                opts.max_subintervals, worst.error
            );
            part.active.push(worst);
            return Err(stopped(&part, evaluations, reason));
        }
        let mid = 0.5 * (worst.lo + worst.hi);
        let width = worst.hi - worst.lo;
        if !(worst.lo < mid && mid < worst.hi) || width <= 100.0 * f64::EPSILON * worst.lo.abs().max(worst.hi.abs()) {
            let reason = too_small_to_bisect(x_lo, x_hi, worst.error);
            part.active.push(worst);
            return Err(stopped(&part, evaluations, reason));
        }
        evaluations += 2 * NODES;
        let left = gk21(&f, worst.map, worst.lo, mid);
        let right = gk21(&f, worst.map, mid, worst.hi);
        match (left, right) {
            (Ok(l), Ok(r)) => {
                value += (l.value + r.value) - worst.value;
                error += (l.error + r.error) - worst.error;
                part.push(l);
                part.push(r);
            }
            (Err(e), _) => {
                part.active.push(worst);
                return Err(failure(e, worst.map, worst.lo, mid, &part, evaluations));
            }
            (_, Err(e)) => {
                part.active.push(worst);
                return Err(failure(e, worst.map, mid, worst.hi, &part, evaluations));
            }
        }
    }
}

/// The limits are not NaN and a ≤ b; the tolerances are ≥ 0.
fn check_arguments(a: f64, b: f64, opts: &QuadOptions) -> Result<()> {
    if a.is_nan() {
        return Err(Error::invalid("a", a, "lower integration limit must not be NaN"));
    }
    if b.is_nan() {
        return Err(Error::invalid("b", b, "upper integration limit must not be NaN"));
    }
    if a > b {
        return Err(Error::invalid(
            "a",
            a,
            format!("lower integration limit must be <= upper limit b = {b}"),
        ));
    }
    if opts.rel_tol.is_nan() || opts.rel_tol < 0.0 {
        return Err(Error::invalid("rel_tol", opts.rel_tol, "must be >= 0"));
    }
    if opts.abs_tol.is_nan() || opts.abs_tol < 0.0 {
        return Err(Error::invalid("abs_tol", opts.abs_tol, "must be >= 0"));
    }
    Ok(())
}

/// The error of an integration stopped for `reason`, with the estimate and error of the partition so far.
fn stopped(part: &Partition, evaluations: usize, reason: String) -> Error {
    let (estimate, abs_error) = part.totals();
    Error::Quadrature {
        what: "integral".into(),
        estimate,
        abs_error,
        evaluations,
        reason,
    }
}

/// Why a subinterval [x_lo, x_hi] whose error estimate is `error` cannot be bisected further.
fn too_small_to_bisect(x_lo: f64, x_hi: f64, error: f64) -> String {
    if x_lo.is_infinite() || x_hi.is_infinite() {
        format!(
            "subinterval [{x_lo:e}, {x_hi:e}] of the infinite range too small to bisect further with error \
             estimate {error:e} (the integrand does not decay fast enough: divergent integral?)"
        )
    } else {
        format!(
            "subinterval [{x_lo:e}, {x_hi:e}] too small to bisect further with error estimate {error:e} \
             (non-integrable singularity or discontinuity there?)"
        )
    }
}

/// The error of a failed rule application on [lo, hi] (in the parameter of `map`).
fn rule_failure(
    f: &impl Fn(f64) -> f64,
    (fail, map, lo, hi): (RuleFailure, Map, f64, f64),
    part: &Partition,
    evaluations: usize,
) -> Error {
    let reason = match fail {
        RuleFailure::NotFinite { u } => {
            let x = map.x(u);
            let fx = f(x);
            if fx.is_finite() {
                format!(
                    "integrand not finite at x = {x:e} once multiplied by the Jacobian of the infinite-range \
                     map (f = {fx:e}): the integrand does not decay fast enough"
                )
            } else {
                format!("integrand not finite at x = {x:e} (f = {fx})")
            }
        }
        RuleFailure::Overflow => {
            format!("integral overflows on [{:e}, {:e}]", map.x(lo), map.x(hi))
        }
    };
    stopped(part, evaluations, reason)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::tolerance::{ROUNDING, ULPS};

    fn opts(rel_tol: f64) -> QuadOptions {
        QuadOptions {
            rel_tol,
            ..QuadOptions::default()
        }
    }

    #[test]
    fn polynomials_exact_up_to_degree_31() {
        // ∫_0^1 x^k dx = 1/(k+1); K21 is exact for degree <= 31, so one rule application suffices.
        for k in 0..=31 {
            let r = integrate(|x| x.powi(k), 0.0, 1.0, &opts(1e-12)).unwrap();
            let exact = 1.0 / (k as f64 + 1.0);
            assert!((r.value - exact).abs() < ROUNDING, "k = {k}: {} vs {exact}", r.value);
        }
    }

    #[test]
    fn single_rule_for_smooth_low_degree() {
        // ∫_0^1 x^5 dx = 1/6 (exact in one K21 application; error estimate at its roundoff floor).
        let r = integrate(|x| x.powi(5), 0.0, 1.0, &opts(1e-10)).unwrap();
        assert_eq!(r.evaluations, 21);
        assert!((r.value - 1.0 / 6.0).abs() < ULPS);
    }

    #[test]
    fn a_equals_b_is_zero() {
        let r = integrate(|x| x, 3.0, 3.0, &QuadOptions::default()).unwrap();
        assert_eq!(
            r,
            QuadResult {
                value: 0.0,
                abs_error: 0.0,
                evaluations: 0
            }
        );
    }

    #[test]
    fn invalid_limits() {
        let o = QuadOptions::default();
        assert!(matches!(
            integrate(|x| x, f64::NAN, 1.0, &o),
            Err(Error::InvalidParameter { .. })
        ));
        assert!(matches!(
            integrate(|x| x, 0.0, f64::NAN, &o),
            Err(Error::InvalidParameter { .. })
        ));
        assert!(matches!(
            integrate(|x| x, 1.0, 0.0, &o),
            Err(Error::InvalidParameter { .. })
        ));
        assert!(matches!(
            integrate(|x| x, f64::INFINITY, 0.0, &o),
            Err(Error::InvalidParameter { .. })
        ));
        let bad = QuadOptions {
            rel_tol: -1.0,
            ..QuadOptions::default()
        };
        assert!(matches!(
            integrate(|x| x, 0.0, 1.0, &bad),
            Err(Error::InvalidParameter { .. })
        ));
        let bad = QuadOptions {
            abs_tol: f64::NAN,
            ..QuadOptions::default()
        };
        assert!(matches!(
            integrate(|x| x, 0.0, 1.0, &bad),
            Err(Error::InvalidParameter { .. })
        ));
    }

    #[test]
    fn breakpoints_outside_are_ignored() {
        // ∫_0^2 |x − 1| dx = 1 (two triangles of area 1/2); kink at the breakpoint 1 -> exact per piece.
        let o = QuadOptions {
            breakpoints: vec![-5.0, 1.0, 1.0, f64::NAN, 2.0, 7.0],
            ..QuadOptions::default()
        };
        let r = integrate(|x| (x - 1.0).abs(), 0.0, 2.0, &o).unwrap();
        assert!((r.value - 1.0).abs() < ULPS);
        assert_eq!(r.evaluations, 2 * 21);
    }

    #[test]
    fn pieces_partition() {
        let p = pieces(0.0, f64::INFINITY, &[50.0]);
        // [0, 50], [50, 100], tail from 100 with scale 100.
        assert_eq!(p.len(), 3);
        assert!(matches!(p[2].0, Map::Tail { c, l } if c == 100.0 && l == 100.0));
        let p = pieces(f64::NEG_INFINITY, f64::INFINITY, &[]);
        assert_eq!(p.len(), 2);
        let p = pieces(f64::NEG_INFINITY, f64::INFINITY, &[-50.0, 50.0]);
        assert_eq!(p.len(), 5);
        let p = pieces(f64::NEG_INFINITY, 0.0, &[-3.0]);
        assert!(matches!(p[0].0, Map::Head { c, l } if c == -6.0 && l == 6.0));
    }
}
