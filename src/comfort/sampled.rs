//! Evaluation of a sampled frequency-weighted signal: r.m.s., VDV, MSDV, running r.m.s. and MTVV, crest
//! factor, and the ISO 2631-1 rule for when the basic (r.m.s.) method is not sufficient.

use crate::error::{Error, Result};

/// Integration time τ = 1 s of the running r.m.s. recommended for the MTVV (ISO 2631-1:1997, 6.3.1).
pub const MTVV_INTEGRATION_TIME_S: f64 = 1.0;

/// Crest factor above which the basic evaluation method may underestimate the effects (ISO 2631-1:1997,
/// 6.2.1: for crest factors ≤ 9 the basic method is normally sufficient).
pub const CREST_FACTOR_LIMIT: f64 = 9.0;

/// Ratio MTVV/a_w above which the additional methods should be used (ISO 2631-1:1997, 6.3.3).
pub const MTVV_RATIO_LIMIT: f64 = 1.5;

/// Ratio VDV/(a_w T^(1/4)) above which the additional methods should be used (ISO 2631-1:1997, 6.3.3).
pub const VDV_RATIO_LIMIT: f64 = 1.75;

/// Neumaier-compensated sum.
fn compensated_sum(values: impl Iterator<Item = f64>) -> f64 {
    let (mut sum, mut comp) = (0.0f64, 0.0f64);
    for v in values {
        let t = sum + v;
        if sum.abs() >= v.abs() {
            comp += (sum - t) + v;
        } else {
            comp += (v - t) + sum;
        }
        sum = t;
    }
    sum + comp
}

fn check_signal(samples: &[f64], dt_s: f64) -> Result<()> {
    if !(dt_s.is_finite() && dt_s > 0.0) {
        return Err(Error::invalid("dt", dt_s, "the time step must be finite and > 0 s"));
    }
    if samples.is_empty() {
        return Err(Error::invalid("samples", "[] (length 0)", "the signal is empty"));
    }
    if let Some((i, v)) = samples.iter().enumerate().find(|(_, v)| !v.is_finite()) {
        return Err(Error::invalid(
            &format!("samples[{i}]"),
            v,
            "every sample must be finite",
        ));
    }
    Ok(())
}

/// Number of samples of the running-r.m.s. window and the integration time it represents.
fn window(dt_s: f64, tau_s: f64) -> Result<usize> {
    if !(tau_s.is_finite() && tau_s > 0.0) {
        return Err(Error::invalid(
            "tau",
            tau_s,
            "the integration time must be finite and > 0 s",
        ));
    }
    let n = (tau_s / dt_s).round();
    if n < 1.0 {
        return Err(Error::invalid(
            "tau",
            tau_s,
            format!("the integration time is shorter than half a time step (dt = {dt_s} s)"),
        ));
    }
    Ok(n as usize)
}

/// The running r.m.s. with linear integration over τ, at every instant that has a full window.
///
/// # Formula
/// ISO 2631-1:1997, 6.3.1 (linear integration): a_w(t₀) = [ (1/τ) ∫_{t₀−τ}^{t₀} a_w²(t) dt ]^(1/2). With samples aₖ
/// held over one step dt each (rectangle rule) and n = round(τ/dt) samples per window (integration time
/// n·dt), the value at sample j ≥ n − 1 is
///
/// ```text
/// a_w(t_j) = [ (1/n) Σ_{k=j−n+1}^{j} aₖ² ]^(1/2),      j = n−1, …, N−1,
/// ```
/// computed with a sliding sum that is recomputed from scratch every n samples (no drift).
///
/// # Errors
/// [`Error::InvalidParameter`] naming `dt` (finite, > 0), `samples` (empty), `samples[i]` (not finite),
/// `tau` (finite, > 0, at least half a step), or `tau` when the signal is shorter than one window.
///
/// # Examples
/// ```
/// use stochvib::comfort::running_rms;
/// let a = [0.0, 0.0, 2.0, 2.0];
/// let r = running_rms(&a, 0.5, 1.0).unwrap(); // 2 samples per window
/// assert_eq!(r, vec![0.0, 2f64.sqrt(), 2.0]);
/// ```
pub fn running_rms(samples: &[f64], dt_s: f64, tau_s: f64) -> Result<Vec<f64>> {
    check_signal(samples, dt_s)?;
    let n = window(dt_s, tau_s)?;
    if n > samples.len() {
        return Err(Error::invalid(
            "tau",
            tau_s,
            format!(
                "the signal ({} samples, {} s) is shorter than one integration window of {n} samples",
                samples.len(),
                samples.len() as f64 * dt_s
            ),
        ));
    }
    let mut out = Vec::with_capacity(samples.len() - n + 1);
    let mut sum = 0.0;
    for j in (n - 1)..samples.len() {
        let start = j + 1 - n;
        if (j + 1 - n) % n == 0 {
            sum = compensated_sum(samples[start..=j].iter().map(|v| v * v));
        } else {
            sum += samples[j] * samples[j] - samples[start - 1] * samples[start - 1];
        }
        out.push((sum.max(0.0) / n as f64).sqrt());
    }
    Ok(out)
}

/// ISO 2631-1's test of whether the basic (r.m.s.) evaluation method suffices.
///
/// # Formula
/// ```text
/// crest factor        CF = max|a_w(t)| / a_w          > 9     (6.2.1)
/// MTVV ratio          MTVV / a_w                        > 1.5   (6.3.3)
/// VDV ratio           VDV / (a_w · T^(1/4))             > 1.75  (6.3.3)
/// ```
/// The basic method is sufficient when none of the available criteria is exceeded. For reference: a
/// sinusoid has CF = √2, MTVV/a_w = 1 and VDV/(a_w T^(1/4)) = √2·(3/8)^(1/4) = 1.11; a stationary
/// Gaussian signal has VDV/(a_w T^(1/4)) → 3^(1/4) = 1.32.
///
/// # Errors
/// [`BasicMethodInputs::check`] rejects non-finite or negative values and a non-positive duration.
///
/// # Examples
/// ```
/// use stochvib::comfort::BasicMethodInputs;
/// // a_w = 1, peak 10, MTVV 1.2, VDV 1.5·T^(1/4), T = 16 s
/// let c = BasicMethodInputs { a_w: 1.0, peak: 10.0, mtvv: Some(1.2), vdv: 1.5 * 2.0, duration_s: 16.0 }
///     .check()
///     .unwrap();
/// assert!(c.crest_factor_exceeded && !c.mtvv_ratio_exceeded && !c.vdv_ratio_exceeded);
/// assert!(!c.basic_method_sufficient);
/// ```
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct BasicMethodCheck {
    /// max|a_w(t)|/a_w (`None` for an identically zero signal).
    pub crest_factor: Option<f64>,
    /// Crest factor > 9.
    pub crest_factor_exceeded: bool,
    /// MTVV/a_w (`None` when the MTVV is not available or a_w = 0).
    pub mtvv_ratio: Option<f64>,
    /// MTVV/a_w > 1.5.
    pub mtvv_ratio_exceeded: bool,
    /// VDV/(a_w T^(1/4)) (`None` when a_w = 0).
    pub vdv_ratio: Option<f64>,
    /// VDV/(a_w T^(1/4)) > 1.75.
    pub vdv_ratio_exceeded: bool,
    /// No available criterion is exceeded.
    pub basic_method_sufficient: bool,
    /// The metric that governs the evaluation ([`Governing`]).
    pub governing: Governing,
}

/// The metric that governs an ISO 2631-1 evaluation: the basic r.m.s. method, or the additional method a
/// criterion of [`BasicMethodCheck`] calls for.
///
/// # Formula
/// Each criterion's ratio to its threshold, r_CF = CF/9, r_M = (MTVV/a_w)/1.5, r_V = (VDV/(a_w T^(1/4)))/1.75;
/// none above 1: [`Governing::Rms`]; else the criterion with the largest r governs: the MTVV ratio calls for
/// the MTVV (running r.m.s., ISO 2631-1:1997 6.3.1), the crest factor and the VDV ratio for the VDV (fourth
/// power, 6.3.2, which is "more sensitive to peaks"). Ties go to the VDV.
///
/// # Examples
/// ```
/// use stochvib::comfort::{BasicMethodInputs, Governing};
/// // a 1 s burst of a sinusoid in a 64 s record: CF = 8√2, MTVV/a_w = 8, VDV ratio = √2·(3/8)^(1/4)·64^(1/4)
/// let (a_w, duration_s) = (1.0 / 8.0 / 2f64.sqrt(), 64.0);
/// let (mtvv, vdv) = (Some(1.0 / 2f64.sqrt()), (3.0f64 / 8.0).powf(0.25));
/// let c = BasicMethodInputs { a_w, peak: 1.0, mtvv, vdv, duration_s }.check().unwrap();
/// assert_eq!(c.governing, Governing::Mtvv);
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum Governing {
    /// The basic method suffices: the weighted r.m.s. a_w (and A(8)) governs.
    Rms,
    /// The vibration dose value (crest factor or VDV ratio above its threshold).
    Vdv,
    /// The maximum transient vibration value (MTVV ratio above its threshold).
    Mtvv,
}

impl Governing {
    /// `r.m.s.`, `VDV` or `MTVV`.
    pub fn label(self) -> &'static str {
        match self {
            Governing::Rms => "r.m.s. (basic method)",
            Governing::Vdv => "VDV",
            Governing::Mtvv => "MTVV",
        }
    }
}

/// What [`BasicMethodCheck`] is evaluated from: the measures of one frequency-weighted signal.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BasicMethodInputs {
    /// The weighted r.m.s. a_w, m/s².
    pub a_w: f64,
    /// The peak max|a_w(t)|, m/s².
    pub peak: f64,
    /// The maximum transient vibration value, m/s² (`None` when the record is shorter than its window).
    pub mtvv: Option<f64>,
    /// The vibration dose value, m/s^1.75.
    pub vdv: f64,
    /// The duration T of the record, s.
    pub duration_s: f64,
}

impl BasicMethodInputs {
    /// Evaluates the three criteria of [`BasicMethodCheck`].
    ///
    /// # Formula
    /// See [`BasicMethodCheck`]'s `# Formula`; a ratio whose denominator is 0 is `None` and not exceeded.
    ///
    /// # Errors
    /// [`Error::InvalidParameter`] naming `a_w`, `peak`, `mtvv` or `vdv` (finite, ≥ 0) or `duration_s`
    /// (finite, > 0).
    ///
    /// # Examples
    /// ```
    /// use stochvib::comfort::BasicMethodInputs;
    /// let c = BasicMethodInputs { a_w: 1.0, peak: 2f64.sqrt(), mtvv: Some(1.0), vdv: 1.107, duration_s: 1.0 }
    ///     .check()
    ///     .unwrap();
    /// assert!(c.basic_method_sufficient);
    /// ```
    pub fn check(self) -> Result<BasicMethodCheck> {
        let BasicMethodInputs {
            a_w,
            peak,
            mtvv,
            vdv,
            duration_s,
        } = self;
        for (name, v) in [
            ("a_w", a_w),
            ("peak", peak),
            ("vdv", vdv),
            ("mtvv", mtvv.unwrap_or(0.0)),
        ] {
            if !(v.is_finite() && v >= 0.0) {
                return Err(Error::invalid(name, v, "must be finite and >= 0"));
            }
        }
        if !(duration_s.is_finite() && duration_s > 0.0) {
            return Err(Error::invalid(
                "duration_s",
                duration_s,
                "a duration must be finite and > 0 s",
            ));
        }
        let ratio = |x: f64, y: f64| (y > 0.0).then(|| x / y);
        let crest_factor = ratio(peak, a_w);
        let mtvv_ratio = mtvv.and_then(|m| ratio(m, a_w));
        let vdv_ratio = ratio(vdv, a_w * duration_s.powf(0.25));
        let crest_factor_exceeded = crest_factor.is_some_and(|c| c > CREST_FACTOR_LIMIT);
        let mtvv_ratio_exceeded = mtvv_ratio.is_some_and(|r| r > MTVV_RATIO_LIMIT);
        let vdv_ratio_exceeded = vdv_ratio.is_some_and(|r| r > VDV_RATIO_LIMIT);
        let over = |r: Option<f64>, limit: f64| r.map_or(0.0, |r| r / limit);
        let (r_cf, r_m, r_v) = (
            over(crest_factor, CREST_FACTOR_LIMIT),
            over(mtvv_ratio, MTVV_RATIO_LIMIT),
            over(vdv_ratio, VDV_RATIO_LIMIT),
        );
        let governing = if r_cf.max(r_m).max(r_v) <= 1.0 {
            Governing::Rms
        } else if r_m > r_cf.max(r_v) {
            Governing::Mtvv
        } else {
            Governing::Vdv
        };
        Ok(BasicMethodCheck {
            crest_factor,
            crest_factor_exceeded,
            mtvv_ratio,
            mtvv_ratio_exceeded,
            vdv_ratio,
            vdv_ratio_exceeded,
            basic_method_sufficient: !(crest_factor_exceeded || mtvv_ratio_exceeded || vdv_ratio_exceeded),
            governing,
        })
    }
}

/// The ISO 2631-1 metrics of one sampled frequency-weighted acceleration record.
///
/// # Formula
/// The samples aₖ, k = 0 … N−1, are taken to hold over one time step each (rectangle rule), so the record
/// lasts T = N·dt and (ISO 2631-1:1997, 6.1, 6.3.1, 6.3.2, 6.2.1, 9.2):
///
/// ```text
/// a_w  = [ (1/N) Σ aₖ² ]^(1/2)                    m/s²       (6.1)
/// VDV  = [ Σ aₖ⁴ · dt ]^(1/4)                     m/s^1.75   (6.3.2)
/// MSDV = [ Σ aₖ² · dt ]^(1/2) = a_w √T            m/s^1.5    (9.2, meaningful for Wf)
/// MTVV = max_j a_w(t_j), running r.m.s. over τ    m/s²       (6.3.1; τ = 1 s)
/// CF   = max|aₖ| / a_w                                        (6.2.1)
/// ```
/// For a trigonometric polynomial sampled over whole periods these sums equal the integrals exactly
/// (discrete orthogonality), e.g. a sinusoid of amplitude A gives a_w = A/√2 and VDV = A(3T/8)^(1/4).
/// Sums are compensated (Neumaier).
///
/// # Errors
/// [`SignalMetrics::from_samples`] rejects an empty signal, non-finite samples, dt ≤ 0 and an invalid
/// integration time.
///
/// # Examples
/// ```
/// use stochvib::comfort::SignalMetrics;
/// use std::f64::consts::PI;
/// let dt = 1.0 / 256.0;
/// // 2 Hz sinusoid of amplitude 3 m/s² over 10 s
/// let a: Vec<f64> = (0..2560).map(|k| 3.0 * (2.0 * PI * 2.0 * k as f64 * dt).sin()).collect();
/// let m = SignalMetrics::from_samples(&a, dt).unwrap();
/// assert!((m.a_w - 3.0 / 2f64.sqrt()).abs() < 1e-12);
/// assert!((m.vdv - 3.0 * (3.0 * 10.0 / 8.0f64).powf(0.25)).abs() < 1e-12);
/// assert!((m.mtvv.unwrap() - m.a_w).abs() < 1e-12);
/// assert!(m.check.basic_method_sufficient);
/// ```
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct SignalMetrics {
    /// Number of samples N.
    pub samples: usize,
    /// Time step dt, s.
    pub dt_s: f64,
    /// Duration T = N·dt, s.
    pub duration_s: f64,
    /// Weighted r.m.s. acceleration a_w, m/s² (rad/s² for We).
    pub a_w: f64,
    /// Peak max|aₖ|.
    pub peak: f64,
    /// Vibration dose value, m/s^1.75.
    pub vdv: f64,
    /// Motion sickness dose value (∫a² dt)^(1/2), m/s^1.5.
    pub msdv: f64,
    /// Maximum transient vibration value (`None` when the record is shorter than one window).
    pub mtvv: Option<f64>,
    /// Integration time actually used for the running r.m.s., n·dt, s.
    pub mtvv_integration_time_s: f64,
    /// The ISO 2631-1 criteria for the basic method.
    pub check: BasicMethodCheck,
}

impl SignalMetrics {
    /// Metrics of a record with the standard integration time τ = 1 s for the MTVV.
    ///
    /// # Formula
    /// See the type's `# Formula`.
    ///
    /// # Errors
    /// [`Error::InvalidParameter`] naming `dt` (finite, > 0), `samples` (empty) or `samples[i]` (not
    /// finite).
    ///
    /// # Examples
    /// ```
    /// use stochvib::comfort::SignalMetrics;
    /// assert!(SignalMetrics::from_samples(&[], 0.01).is_err());
    /// assert!(SignalMetrics::from_samples(&[1.0, f64::NAN], 0.01).is_err());
    /// assert!(SignalMetrics::from_samples(&[1.0], 0.0).is_err());
    /// let m = SignalMetrics::from_samples(&[1.0, -1.0], 0.25).unwrap();
    /// assert_eq!((m.a_w, m.mtvv), (1.0, None)); // 0.5 s record: no full 1 s window
    /// ```
    pub fn from_samples(samples: &[f64], dt_s: f64) -> Result<Self> {
        Self::with_integration_time(samples, dt_s, MTVV_INTEGRATION_TIME_S)
    }

    /// Metrics of a record with a chosen running-r.m.s. integration time τ (s) for the MTVV.
    ///
    /// # Formula
    /// See the type's `# Formula`; n = round(τ/dt) samples per window.
    ///
    /// # Errors
    /// Those of [`SignalMetrics::from_samples`], and `tau` when not finite and > 0 or shorter than half a
    /// step.
    ///
    /// # Examples
    /// ```
    /// use stochvib::comfort::SignalMetrics;
    /// let a = [0.0, 0.0, 0.0, 2.0];
    /// let m = SignalMetrics::with_integration_time(&a, 1.0, 2.0).unwrap();
    /// assert_eq!(m.mtvv, Some(2f64.sqrt()));
    /// assert_eq!(m.a_w, 1.0);
    /// ```
    pub fn with_integration_time(samples: &[f64], dt_s: f64, tau_s: f64) -> Result<Self> {
        check_signal(samples, dt_s)?;
        let n_win = window(dt_s, tau_s)?;
        let n = samples.len();
        let duration_s = n as f64 * dt_s;
        let sum2 = compensated_sum(samples.iter().map(|v| v * v));
        let sum4 = compensated_sum(samples.iter().map(|v| (v * v) * (v * v)));
        let a_w = (sum2 / n as f64).sqrt();
        let peak = samples.iter().fold(0.0f64, |m, v| m.max(v.abs()));
        let vdv = (sum4 * dt_s).powf(0.25);
        let msdv = (sum2 * dt_s).sqrt();
        let mtvv = if n_win <= n {
            Some(running_rms(samples, dt_s, tau_s)?.into_iter().fold(0.0f64, f64::max))
        } else {
            None
        };
        let check = BasicMethodInputs {
            a_w,
            peak,
            mtvv,
            vdv,
            duration_s,
        }
        .check()?;
        Ok(SignalMetrics {
            samples: n,
            dt_s,
            duration_s,
            a_w,
            peak,
            vdv,
            msdv,
            mtvv,
            mtvv_integration_time_s: n_win as f64 * dt_s,
            check,
        })
    }
}

/// [`SignalMetrics`] accumulated block by block, in time order, with memory independent of the record's
/// length (one running-r.m.s. window): the same values as [`SignalMetrics::with_integration_time`] on the
/// whole record, bit for bit, for any split into blocks.
///
/// # Formula
/// As [`SignalMetrics`]: compensated (Neumaier) sums of a² and a⁴ carried across blocks, the peak, and the
/// sliding window sum of the running r.m.s. (recomputed from the window's samples every n samples, as
/// [`running_rms`] does), whose maximum gives the MTVV = √(max window sum / n).
///
/// # Errors
/// [`SignalMetricsStream::new`] as [`SignalMetrics::with_integration_time`]; [`SignalMetricsStream::push`]
/// a non-finite sample (named by its index in the record); [`SignalMetricsStream::finish`] an empty record.
///
/// # Examples
/// ```
/// use stochvib::comfort::{SignalMetrics, SignalMetricsStream};
/// let a: Vec<f64> = (0..700).map(|k| (0.07 * k as f64).sin() * (1.0 + 0.01 * k as f64)).collect();
/// let mut s = SignalMetricsStream::new(0.01, 1.0).unwrap();
/// for block in a.chunks(33) {
///     s.push(block).unwrap();
/// }
/// assert_eq!(s.finish().unwrap(), SignalMetrics::from_samples(&a, 0.01).unwrap());
/// ```
#[derive(Debug, Clone)]
pub struct SignalMetricsStream {
    dt_s: f64,
    sum2: (f64, f64),
    sum4: (f64, f64),
    peak: f64,
    samples: usize,
    /// the last `ring.len()` samples (the running-r.m.s. window), slot j mod n holds sample j
    ring: Vec<f64>,
    window_sum: f64,
    max_window_sum: f64,
}

/// Adds v to a Neumaier-compensated sum (sum, compensation), as [`compensated_sum`] does term by term.
#[inline(always)]
fn compensated_add(acc: &mut (f64, f64), v: f64) {
    let (sum, comp) = acc;
    let t = *sum + v;
    if sum.abs() >= v.abs() {
        *comp += (*sum - t) + v;
    } else {
        *comp += (v - t) + *sum;
    }
    *sum = t;
}

/// Σ a² over a window in order, compensated (the sum [`SignalMetricsStream`] restarts from every n samples).
fn window_mean_square_sum(window: &[f64]) -> f64 {
    let mut s = (0.0, 0.0);
    for a in window {
        compensated_add(&mut s, a * a);
    }
    s.0 + s.1
}

impl SignalMetricsStream {
    /// An empty record sampled at step `dt_s` with the running-r.m.s. integration time `tau_s`
    /// ([`MTVV_INTEGRATION_TIME_S`] for the standard's MTVV).
    ///
    /// # Errors
    /// See the type's `# Errors`.
    pub fn new(dt_s: f64, tau_s: f64) -> Result<Self> {
        if !(dt_s.is_finite() && dt_s > 0.0) {
            return Err(Error::invalid("dt", dt_s, "the time step must be finite and > 0 s"));
        }
        let n = window(dt_s, tau_s)?;
        Ok(SignalMetricsStream {
            dt_s,
            sum2: (0.0, 0.0),
            sum4: (0.0, 0.0),
            peak: 0.0,
            samples: 0,
            ring: vec![0.0; n],
            window_sum: 0.0,
            max_window_sum: 0.0,
        })
    }

    /// Samples consumed so far.
    pub fn samples(&self) -> usize {
        self.samples
    }

    /// Samples per running-r.m.s. window, n = round(τ/dt).
    pub fn window_samples(&self) -> usize {
        self.ring.len()
    }

    /// Adds the next samples of the record.
    ///
    /// # Errors
    /// See the type's `# Errors`; the block is then not consumed.
    pub fn push(&mut self, x: &[f64]) -> Result<()> {
        self.push_each(x, |_| {})
    }

    /// As [`SignalMetricsStream::push`], calling `running` with the running mean square
    /// (1/n)·Σ_{k=j−n+1}^{j} a_k² of every sample j that completes a window (its square root is the
    /// running r.m.s. a_w(t_j) of ISO 2631-1 6.3.1).
    ///
    /// # Errors
    /// As [`SignalMetricsStream::push`].
    pub fn push_each(&mut self, x: &[f64], mut running: impl FnMut(f64)) -> Result<()> {
        if let Some((i, v)) = x.iter().enumerate().find(|(_, v)| !v.is_finite()) {
            return Err(Error::invalid(
                &format!("samples[{}]", self.samples + i),
                v,
                "every sample must be finite",
            ));
        }
        let n = self.ring.len();
        let inv_n = 1.0 / n as f64;
        let (mut sum2, mut sum4, mut peak) = (self.sum2, self.sum4, self.peak);
        let (mut window_sum, mut max_window_sum) = (self.window_sum, self.max_window_sum);
        let mut j = self.samples;
        // slot = j mod n, carried instead of divided; the window that ends at sample j starts at j + 1 − n,
        // a multiple of n exactly when slot = n − 1, and then the ring holds it in order
        let mut slot = j % n;
        for &v in x {
            let v2 = v * v;
            compensated_add(&mut sum2, v2);
            compensated_add(&mut sum4, v2 * v2);
            peak = peak.max(v.abs());
            let old = self.ring[slot]; // sample j − n (when j ≥ n)
            self.ring[slot] = v;
            if j + 1 >= n {
                if slot == n - 1 {
                    window_sum = window_mean_square_sum(&self.ring);
                } else {
                    window_sum += v2 - old * old;
                }
                let w = window_sum.max(0.0);
                max_window_sum = max_window_sum.max(w);
                running(w * inv_n);
            }
            j += 1;
            slot = if slot + 1 == n { 0 } else { slot + 1 };
        }
        (self.sum2, self.sum4, self.peak) = (sum2, sum4, peak);
        (self.window_sum, self.max_window_sum, self.samples) = (window_sum, max_window_sum, j);
        Ok(())
    }

    /// The metrics of the record so far.
    ///
    /// # Errors
    /// See the type's `# Errors`.
    pub fn finish(&self) -> Result<SignalMetrics> {
        let n = self.samples;
        if n == 0 {
            return Err(Error::invalid("samples", "[] (length 0)", "the signal is empty"));
        }
        let n_win = self.ring.len();
        let duration_s = n as f64 * self.dt_s;
        let (sum2, sum4) = (self.sum2.0 + self.sum2.1, self.sum4.0 + self.sum4.1);
        let a_w = (sum2 / n as f64).sqrt();
        let vdv = (sum4 * self.dt_s).powf(0.25);
        let msdv = (sum2 * self.dt_s).sqrt();
        let mtvv = (n_win <= n).then(|| (self.max_window_sum / n_win as f64).sqrt());
        let check = BasicMethodInputs {
            a_w,
            peak: self.peak,
            mtvv,
            vdv,
            duration_s,
        }
        .check()?;
        Ok(SignalMetrics {
            samples: n,
            dt_s: self.dt_s,
            duration_s,
            a_w,
            peak: self.peak,
            vdv,
            msdv,
            mtvv,
            mtvv_integration_time_s: n_win as f64 * self.dt_s,
            check,
        })
    }
}
