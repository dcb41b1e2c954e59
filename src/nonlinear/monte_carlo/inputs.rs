//! The input processes of a spectral-route nonlinear run: the linear runs' spectral generators (Rayleigh
//! amplitudes or Laplace moving averages, delays as circular shifts, two coherent tracks) synthesise every
//! system input u_j, and where an element needs it its exact derivative u̇_j, as the outputs of an identity
//! "system" H(iω) = [I; iω I_sel] run through the linear spectral engine.

use crate::error::{Error, Result};
use crate::response::Excitation;
use crate::simulate::{self, Route, RunInput, RunOptions};
use crate::spectrum::Asymptote;
use crate::store::Signal;
use crate::system::{FrequencyResponse, OutputInfo, StateSpace};
use nalgebra::{Complex, DMatrix};
use realfft::RealFftPlanner;

/// H(iω) = [I_m; iω E] for m inputs and the rates of the inputs `rates`: the outputs are the inputs
/// themselves and the derivatives of some (a decoupled stable dummy state gives it a state space).
#[derive(Debug, Clone)]
pub(crate) struct InputIdentity {
    m: usize,
    rates: Vec<usize>,
    infos: Vec<OutputInfo>,
    ss: StateSpace,
}

impl InputIdentity {
    pub(crate) fn new(m: usize, rates: Vec<usize>) -> Result<Self> {
        let p = m + rates.len();
        let mut infos: Vec<OutputInfo> = (0..m).map(|j| OutputInfo::new(format!("u{j}"), "-")).collect();
        infos.extend(rates.iter().map(|j| OutputInfo::new(format!("du{j}"), "-")));
        let mut d = DMatrix::zeros(p, m);
        let mut e = DMatrix::zeros(p, m);
        for j in 0..m {
            d[(j, j)] = 1.0;
        }
        for (r, &j) in rates.iter().enumerate() {
            e[(m + r, j)] = 1.0;
        }
        let ss = StateSpace::new(
            DMatrix::from_element(1, 1, -1.0),
            DMatrix::zeros(1, m),
            DMatrix::zeros(p, 1),
            Some(d),
            Some(e),
            infos.clone(),
        )?;
        Ok(InputIdentity { m, rates, infos, ss })
    }
}

impl FrequencyResponse for InputIdentity {
    fn n_inputs(&self) -> usize {
        self.m
    }
    fn outputs(&self) -> &[OutputInfo] {
        &self.infos
    }
    fn response(&self, omega: f64) -> DMatrix<Complex<f64>> {
        let mut h = DMatrix::from_element(self.infos.len(), self.m, Complex::new(0.0, 0.0));
        for j in 0..self.m {
            h[(j, j)] = Complex::new(1.0, 0.0);
        }
        for (r, &j) in self.rates.iter().enumerate() {
            h[(self.m + r, j)] = Complex::new(0.0, omega);
        }
        h
    }
    fn static_gain(&self) -> Option<DMatrix<f64>> {
        let mut g = DMatrix::zeros(self.infos.len(), self.m);
        for j in 0..self.m {
            g[(j, j)] = 1.0;
        }
        Some(g)
    }
    fn high_frequency(&self) -> Vec<Vec<Asymptote>> {
        self.asymptotes(2.0)
    }
    fn low_frequency(&self) -> Vec<Vec<Asymptote>> {
        self.asymptotes(2.0)
    }
    fn natural_frequencies(&self) -> Vec<f64> {
        Vec::new()
    }
    fn state_space(&self) -> Option<&StateSpace> {
        Some(&self.ss)
    }
}

impl InputIdentity {
    fn asymptotes(&self, rate_exponent: f64) -> Vec<Vec<Asymptote>> {
        (0..self.infos.len())
            .map(|r| {
                (0..self.m)
                    .map(|j| {
                        let on = if r < self.m {
                            r == j
                        } else {
                            self.rates[r - self.m] == j
                        };
                        match (on, r < self.m) {
                            (false, _) => Asymptote::Vanishing,
                            (true, true) => Asymptote::Power {
                                exponent: 0.0,
                                coefficient: 1.0,
                            },
                            (true, false) => Asymptote::Power {
                                exponent: rate_exponent,
                                coefficient: 1.0,
                            },
                        }
                    })
                    .collect()
            })
            .collect()
    }
}

/// The synthesis of every input (and the rates asked for) of one excitation over n samples of Δt.
pub(crate) struct InputSynthesis {
    plan: simulate::Plan,
    m: usize,
    n_rates: usize,
    /// The generator's description (for the run file's `@generator`).
    pub generator: String,
}

/// One realization's input samples: u\[j\]\[k\] and u̇\[r\]\[k\] (the rates in the order asked for), and the
/// recorded input processes.
pub(crate) struct InputSamples {
    pub u: Vec<Vec<f64>>,
    pub rates: Vec<Vec<f64>>,
    pub processes: Vec<Vec<f64>>,
}

impl InputSynthesis {
    /// Plans the synthesis of the m inputs of `exc` and of the rates of `rates`, with `kurtosis` per process
    /// and `signals` naming the processes recorded.
    ///
    /// # Errors
    /// A rate of infinite variance (the input's density decays as ω⁻² or slower); the spectral route's
    /// errors (delays that are not whole steps, memory).
    pub(crate) fn new(
        exc: &Excitation,
        rates: Vec<usize>,
        kurtosis: &[Option<f64>],
        signals: &[Signal],
        n: usize,
        dt: f64,
    ) -> Result<InputSynthesis> {
        let m = exc.n_inputs();
        let n_rates = rates.len();
        let id = InputIdentity::new(m, rates)?;
        let mut input = RunInput::new(&id, exc, (0..m + n_rates).collect(), signals.to_vec(), "");
        input.kurtosis = kurtosis.to_vec();
        let opts = RunOptions {
            route: Route::Spectral,
            store_raw: true,
            realizations: 2,
            duration_s: n as f64 * dt,
            dt_s: dt,
            seed: 0,
            ..RunOptions::default()
        };
        let plan = simulate::plan(&input, &opts)?;
        if let Some(s) = plan.skipped.first() {
            return Err(Error::invalid(
                "input rate",
                &s.name,
                format!(
                    "an element needs the rate of a base input, whose variance is infinite ({}): a velocity-dependent \
                     element on a base input needs an input spectrum decaying faster than ω⁻²",
                    s.reason
                ),
            ));
        }
        Ok(InputSynthesis {
            generator: plan.generator.clone(),
            plan,
            m,
            n_rates,
        })
    }

    /// A scratch for [`InputSynthesis::draw`].
    pub(crate) fn scratch(&self) -> simulate::Scratch {
        simulate::Scratch::new(&self.plan)
    }

    /// Realization `rng`'s inputs, with the recorded input processes if `processes` (else none).
    ///
    /// # Errors
    /// An FFT failure.
    pub(crate) fn draw(
        &self,
        s: &mut simulate::Scratch,
        rng: &mut rand::rngs::Xoshiro256PlusPlus,
        processes: bool,
    ) -> Result<InputSamples> {
        let (mut u, processes) = simulate::samples(&self.plan, s, rng, processes)?;
        let rates = u.split_off(self.m);
        debug_assert_eq!(rates.len(), self.n_rates);
        Ok(InputSamples { u, rates, processes })
    }
}

/// The samples at half steps of a periodic band-limited record (the trigonometric interpolant: the real
/// FFT zero-padded to twice the length; the Nyquist bin split between ±N/2), 2N samples.
///
/// # Errors
/// An FFT failure.
pub(crate) fn refine(x: &[f64]) -> Result<Vec<f64>> {
    let n = x.len();
    let mut planner = RealFftPlanner::<f64>::new();
    let fwd = planner.plan_fft_forward(n);
    let inv = planner.plan_fft_inverse(2 * n);
    let mut buf = x.to_vec();
    let mut spec = fwd.make_output_vec();
    let err = |e: realfft::FftError| Error::Numerical {
        what: "input refinement".into(),
        reason: e.to_string(),
    };
    fwd.process(&mut buf, &mut spec).map_err(err)?;
    let mut big = inv.make_input_vec();
    big[..spec.len()].copy_from_slice(&spec);
    if n.is_multiple_of(2) {
        big[n / 2] = spec[n / 2] * 0.5;
    }
    let mut out = inv.make_output_vec();
    inv.process(&mut big, &mut out).map_err(err)?;
    // forward then inverse of length 2N multiplies by N (unnormalised transforms): 1/N keeps the values
    let scale = 1.0 / n as f64;
    Ok(out.into_iter().map(|v| v * scale).collect())
}
