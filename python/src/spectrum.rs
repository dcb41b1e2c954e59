//! `stochvib.Spectrum`: a stationary random process described by its spectral density.

use crate::arrays::{check_out, real_array};
use crate::errors::{call, detached, detached_if, invalid_input, not_applicable, Failure};
use crate::names::{catalogue, domain_name};
use crate::spectrum_units::{BandArg, Dims};
use numpy::{PyArray1, PyArrayDyn, PyArrayMethods, PyUntypedArrayMethods};
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyFloat};
use std::path::PathBuf;
use std::sync::Arc;
use stochvib::scenario::{SpectrumFile, SpectrumOrigin};
use stochvib::spectrum::{
    AtSpeed, BandWhiteParameters, Convention, ExpCosine, Exponential, GaussCosineParameters, Gaussian, IsoBound,
    IsoClass, PowerLaw, PowerLawParameters, RationalSpectrum, Spectrum, Tabulated, ISO_BAND,
};

/// Grids shorter than this are evaluated without releasing the GIL (releasing costs more than the work).
pub const DETACH_MIN_POINTS: usize = 2048;

/// A pair of coefficient arrays (numerator, denominator).
pub type Coefficients<'py> = (Bound<'py, PyArray1<f64>>, Bound<'py, PyArray1<f64>>);

/// A stationary random process described by its spectral density.
///
/// Inside stochvib every density is the TWO-SIDED density in ANGULAR frequency S(ω), ω in rad/s
/// (temporal processes) or rad/m (spatial road profiles), normalised so that
/// K(τ) = ∫ S(ω) e^{iωτ} dω and the variance is D = K(0) = ∫_{-∞}^{∞} S(ω) dω.
/// Other conventions are exact, named conversions (``convention=`` of :meth:`density`):
///
/// ==================== ================================ ==========================
/// name                 abscissa x, ordinate             relation to S
/// ==================== ================================ ==========================
/// "two-sided-angular"  ω (rad/s or rad/m), S(ω)         S itself (canonical)
/// "one-sided-angular"  ω ≥ 0, G(ω)                      G = 2 S(ω)
/// "one-sided-cyclic"   f ≥ 0 (Hz or cycles/m), G(f)     G = 4π S(2πf)   (scipy.signal.welch, ISO 8608)
/// "engineering"        ω, Ŝ(ω), σ² = (1/2π)∫Ŝ dω        Ŝ = 2π S
/// ==================== ================================ ==========================
///
/// Build one with the constructors (:meth:`exponential`, :meth:`gaussian`, :meth:`exp_cosine`,
/// :meth:`gauss_cosine` — the four standard correlation types —, :meth:`rational`, :meth:`iso8608`,
/// :meth:`power_law`, :meth:`tabulated`, :meth:`band_white`) or from the catalogue (:meth:`load`,
/// :meth:`catalogue`).
#[pyclass(name = "Spectrum", module = "stochvib", frozen)]
pub struct PySpectrum {
    /// The process.
    pub spectrum: Arc<dyn Spectrum>,
    /// SI unit of the process itself.
    pub unit: String,
    /// Catalogue or file name ("" when built in Python).
    pub name: String,
    /// File description.
    pub description: String,
    /// Provenance of the parameter values.
    pub source: String,
    /// Spectrum-file text ("" when built in Python).
    pub text: String,
    /// Where it came from.
    pub origin: SpectrumOrigin,
}

impl PySpectrum {
    /// A spectrum built in Python.
    pub fn built(spectrum: Arc<dyn Spectrum>, unit: &str) -> Self {
        PySpectrum {
            spectrum,
            unit: unit.to_string(),
            name: String::new(),
            description: String::new(),
            source: String::new(),
            text: String::new(),
            origin: SpectrumOrigin::Inline,
        }
    }

    /// A spectrum read from a file.
    pub fn from_file(f: SpectrumFile) -> Self {
        PySpectrum {
            spectrum: f.spectrum,
            unit: f.unit,
            name: f.name,
            description: f.description,
            source: f.source,
            text: f.text,
            origin: f.origin,
        }
    }

    fn make<S: Spectrum + 'static>(
        py: Python<'_>,
        f: impl FnOnce() -> stochvib::Result<S>,
        unit: &str,
    ) -> PyResult<Self> {
        Ok(PySpectrum::built(Arc::new(call(py, f)?), unit))
    }
}

/// S in `conv` at the abscissae `x` (same length as `out`).
fn density_in(s: &dyn Spectrum, conv: Convention, x: &[f64], out: &mut [f64]) {
    convert_density(|w, o| s.density_into(w, o), conv, x, out)
}

/// A two-sided angular density `eval(ω, out)` evaluated in `conv` at the abscissae `x` (same length as
/// `out`): ω from the convention's abscissa, the ordinate converted, one-sided conventions 0 below zero.
pub fn convert_density(eval: impl Fn(&[f64], &mut [f64]), conv: Convention, x: &[f64], out: &mut [f64]) {
    if conv == Convention::TwoSidedAngular {
        eval(x, out);
        return;
    }
    let omega: Vec<f64> = x.iter().map(|&v| conv.to_canonical(v, 0.0).0).collect();
    eval(&omega, out);
    let one_sided = conv.is_one_sided();
    for ((o, &w), &v) in out.iter_mut().zip(&omega).zip(x) {
        *o = if one_sided && v < 0.0 {
            0.0
        } else {
            conv.from_canonical(w, *o).1
        };
    }
}

/// The convention and the abscissae of `density(omega=…)` / `density(f=…, …)`: with `omega` (rad/s) an
/// angular convention, with `f` (Hz) the one-sided cyclic one.
pub fn density_argument<'py>(
    py: Python<'py>,
    omega: Option<&Bound<'py, PyAny>>,
    f: Option<&Bound<'py, PyAny>>,
    convention: Option<&str>,
) -> PyResult<(Convention, Bound<'py, PyArrayDyn<f64>>)> {
    let (x, by_f) = match (omega, f) {
        (Some(w), None) => (real_array(py, w, "omega")?, false),
        (None, Some(f)) => (real_array(py, f, "f")?, true),
        _ => {
            return Err(invalid_input(
                py,
                "give exactly one of `omega` (angular frequency, rad/s) and `f` (frequency, Hz)",
            ))
        }
    };
    let default = if by_f { "one-sided-cyclic" } else { "two-sided-angular" };
    let conv = crate::names::convention(py, convention.unwrap_or(default))?;
    let cyclic = conv == Convention::OneSidedCyclic;
    if cyclic != by_f {
        let why = if by_f {
            "an angular density is a function of ω in rad/s: pass omega=2*np.pi*f, or use the default \
             one-sided-cyclic G(f) with f="
        } else {
            "a one-sided-cyclic density G(f) is a function of f in Hz: pass f= (omega= is in rad/s)"
        };
        return Err(invalid_input(
            py,
            format!(
                "convention {:?} with `{}`: {why}",
                convention.unwrap_or(default),
                if by_f { "f" } else { "omega" }
            ),
        ));
    }
    Ok((conv, x))
}

/// Returns a Python float for a 0-d result, else the array.
pub fn scalar_or_array<'py>(
    py: Python<'py>,
    a: Bound<'py, PyArrayDyn<f64>>,
    scalar: bool,
) -> PyResult<Bound<'py, PyAny>> {
    if scalar {
        let v = a.readonly().as_slice()?[0];
        Ok(PyFloat::new(py, v).into_any())
    } else {
        Ok(a.into_any())
    }
}

#[pymethods]
impl PySpectrum {
    /// Type 1 (exponential correlation): K(τ) = D e^{−α|τ|}, S(ω) = αD / (π(α² + ω²)).
    ///
    /// ``variance`` D in unit², ``alpha`` α in 1/s (temporal) or 1/m (spatial). Rational: exact
    /// shaping filter √(2αD)/(s + α).
    ///
    /// Parameters
    /// ----------
    /// variance : float or str
    ///     D in unit² ("2.25 cm^2" for unit "m").
    /// alpha : float or str
    ///     α in 1/s (1/m spatial); a string names no angle ("1 Hz" would carry 2π: write "6.3 1/s").
    /// domain : {"temporal", "spatial"}, keyword-only
    /// unit : str, keyword-only
    ///     The SI unit of the process (strings of the other arguments are checked against it).
    ///
    /// Returns
    /// -------
    /// Spectrum
    ///
    /// Raises
    /// ------
    /// UnitError
    ///     A string of another dimension, naming the argument.
    /// InvalidInputError
    ///     D < 0, α ≤ 0 or β < 0, or a non-finite value.
    ///
    /// Examples
    /// --------
    /// >>> import stochvib
    /// >>> a = stochvib.Spectrum.exponential("2.25 cm^2", "0.5 1/cm", domain="spatial")
    /// >>> b = stochvib.Spectrum.exponential(2.25e-4, 50.0, domain="spatial")
    /// >>> a.density(1.0) == b.density(1.0)
    /// True
    #[staticmethod]
    #[pyo3(signature = (variance, alpha, *, domain="temporal", unit="m"))]
    fn exponential(
        py: Python<'_>,
        variance: &Bound<'_, PyAny>,
        alpha: &Bound<'_, PyAny>,
        domain: &str,
        unit: &str,
    ) -> PyResult<Self> {
        let q = Dims::new(py, domain, unit)?;
        let (v, a) = (q.variance(py, variance)?, q.decay_rate(py, alpha, "alpha", 1)?);
        Self::make(py, || Exponential::new(v, a, q.domain), unit)
    }

    /// Type 2 (Gaussian correlation): K(τ) = D e^{−ατ²}, S(ω) = D/(2√(πα)) e^{−ω²/(4α)}.
    ///
    /// ``variance`` D in unit², ``alpha`` α in 1/s² (temporal) or 1/m² (spatial). Not rational.
    ///
    /// Parameters
    /// ----------
    /// variance : float or str
    ///     D in unit² ("2.25 cm^2" for unit "m").
    /// alpha : float or str
    ///     α in 1/s² (1/m² spatial); a string names no angle ("1 Hz" would carry 2π: write "6.3 1/s").
    /// domain : {"temporal", "spatial"}, keyword-only
    /// unit : str, keyword-only
    ///     The SI unit of the process (strings of the other arguments are checked against it).
    ///
    /// Returns
    /// -------
    /// Spectrum
    ///
    /// Raises
    /// ------
    /// UnitError
    ///     A string of another dimension, naming the argument.
    /// InvalidInputError
    ///     D < 0, α ≤ 0 or β < 0, or a non-finite value.
    #[staticmethod]
    #[pyo3(signature = (variance, alpha, *, domain="temporal", unit="m"))]
    fn gaussian(
        py: Python<'_>,
        variance: &Bound<'_, PyAny>,
        alpha: &Bound<'_, PyAny>,
        domain: &str,
        unit: &str,
    ) -> PyResult<Self> {
        let q = Dims::new(py, domain, unit)?;
        let (v, a) = (q.variance(py, variance)?, q.decay_rate(py, alpha, "alpha", 2)?);
        Self::make(py, || Gaussian::new(v, a, q.domain), unit)
    }

    /// Type 3: K(τ) = D e^{−α|τ|} cos βτ,
    /// S(ω) = αD(ω² + α² + β²) / (π[(ω² − α² − β²)² + 4α²ω²]).
    ///
    /// ``alpha`` α in 1/s (1/m), ``beta`` β in rad/s (rad/m; a string "1 Hz" is 2π rad/s). Rational.
    ///
    /// Parameters
    /// ----------
    /// variance : float or str
    ///     D in unit² ("2.25 cm^2" for unit "m").
    /// alpha : float or str
    ///     α in 1/s (1/m spatial); a string names no angle ("1 Hz" would carry 2π: write "6.3 1/s").
    /// beta : float or str
    ///     β in rad/s (rad/m spatial); a string "1 Hz" is 2π rad/s.
    /// domain : {"temporal", "spatial"}, keyword-only
    /// unit : str, keyword-only
    ///     The SI unit of the process (strings of the other arguments are checked against it).
    ///
    /// Returns
    /// -------
    /// Spectrum
    ///
    /// Raises
    /// ------
    /// UnitError
    ///     A string of another dimension, naming the argument.
    /// InvalidInputError
    ///     D < 0, α ≤ 0 or β < 0, or a non-finite value.
    #[staticmethod]
    #[pyo3(signature = (variance, alpha, beta, *, domain="temporal", unit="m"))]
    fn exp_cosine(
        py: Python<'_>,
        variance: &Bound<'_, PyAny>,
        alpha: &Bound<'_, PyAny>,
        beta: &Bound<'_, PyAny>,
        domain: &str,
        unit: &str,
    ) -> PyResult<Self> {
        let q = Dims::new(py, domain, unit)?;
        let (variance, alpha, beta) = q.decaying_cosine(py, [variance, alpha, beta], 1)?;
        let domain = q.domain;
        Self::make(
            py,
            || {
                ExpCosine {
                    variance,
                    alpha,
                    beta,
                    domain,
                }
                .build()
            },
            unit,
        )
    }

    /// Type 4: K(τ) = D e^{−ατ²} cos βτ,
    /// S(ω) = D/(4√(πα)) [e^{−(ω−β)²/(4α)} + e^{−(ω+β)²/(4α)}].
    ///
    /// ``alpha`` α in 1/s² (1/m²), ``beta`` β in rad/s (rad/m; a string "1 Hz" is 2π rad/s). Not
    /// rational.
    ///
    /// Parameters
    /// ----------
    /// variance : float or str
    ///     D in unit² ("2.25 cm^2" for unit "m").
    /// alpha : float or str
    ///     α in 1/s² (1/m² spatial); a string names no angle ("1 Hz" would carry 2π: write "6.3 1/s").
    /// beta : float or str
    ///     β in rad/s (rad/m spatial); a string "1 Hz" is 2π rad/s.
    /// domain : {"temporal", "spatial"}, keyword-only
    /// unit : str, keyword-only
    ///     The SI unit of the process (strings of the other arguments are checked against it).
    ///
    /// Returns
    /// -------
    /// Spectrum
    ///
    /// Raises
    /// ------
    /// UnitError
    ///     A string of another dimension, naming the argument.
    /// InvalidInputError
    ///     D < 0, α ≤ 0 or β < 0, or a non-finite value.
    #[staticmethod]
    #[pyo3(signature = (variance, alpha, beta, *, domain="temporal", unit="m"))]
    fn gauss_cosine(
        py: Python<'_>,
        variance: &Bound<'_, PyAny>,
        alpha: &Bound<'_, PyAny>,
        beta: &Bound<'_, PyAny>,
        domain: &str,
        unit: &str,
    ) -> PyResult<Self> {
        let q = Dims::new(py, domain, unit)?;
        let (variance, alpha, beta) = q.decaying_cosine(py, [variance, alpha, beta], 2)?;
        let domain = q.domain;
        Self::make(
            py,
            || {
                GaussCosineParameters {
                    variance,
                    alpha,
                    beta,
                    domain,
                }
                .build()
            },
            unit,
        )
    }

    /// A rational density S(ω) = N(ω²)/D(ω²) (two-sided angular).
    ///
    /// Parameters
    /// ----------
    /// numerator, denominator : array_like
    ///     Coefficients of N and D as polynomials in ω², in DESCENDING powers (highest first, as numpy's
    ///     ``polyval`` and scipy.signal), SI units.
    /// order : {"descending", "ascending"}, keyword-only
    ///     ``"ascending"`` takes them lowest power first (the spectrum files' convention).
    /// domain : {"temporal", "spatial"}, keyword-only
    /// unit : str, keyword-only
    ///     SI unit of the process.
    ///
    /// Returns
    /// -------
    /// Spectrum
    ///
    /// Examples
    /// --------
    /// Type 1 with D = 1, α = 1: S(ω) = 1/(π(ω² + 1)):
    ///
    /// >>> import math, stochvib
    /// >>> s = stochvib.Spectrum.rational([1 / math.pi], [1.0, 1.0])
    /// >>> round(s.variance(), 12)
    /// 1.0
    #[staticmethod]
    #[pyo3(signature = (numerator, denominator, *, order="descending", domain="temporal", unit="m"))]
    fn rational(
        py: Python<'_>,
        numerator: &Bound<'_, PyAny>,
        denominator: &Bound<'_, PyAny>,
        order: &str,
        domain: &str,
        unit: &str,
    ) -> PyResult<Self> {
        let d = crate::names::domain(py, domain)?;
        let n = crate::arrays::polynomial(py, numerator, "numerator", order)?;
        let den = crate::arrays::polynomial(py, denominator, "denominator", order)?;
        Self::make(py, || RationalSpectrum::new(n, den, d), unit)
    }

    /// An ISO 8608 road class (spatial): G_d(n) = G_d(n₀)(n/n₀)^{−2}, n₀ = 0.1 cycles/m, one-sided in
    /// cycles/m, G_d(n₀) = 16·4^k × 10⁻⁶ m³ for class A (k = 0) … H (k = 7).
    ///
    /// ``road_class``: "A" … "H"; ``bound``: "lower", "geometric-mean" or "upper"; ``band``: (n₁, n₂) in
    /// cycles/m, default the ISO band (0.011, 2.83); ``None`` leaves it unbounded (then the variance is
    /// infinite and :meth:`variance` raises :class:`DivergentError`). The edges may be strings with a unit
    /// ("0.011 cycles/m"; "1 rad/m" is 1/(2π) cycles/m).
    ///
    /// Parameters
    /// ----------
    /// road_class : str
    ///     "A" … "H".
    /// bound : {"lower", "geometric-mean", "upper"}, keyword-only, default "geometric-mean"
    ///     Which G_d(n₀) of the class ("mean" is taken for "geometric-mean").
    /// band : (float or str, float or str) or None, keyword-only, default (0.011, 2.83)
    ///     (n₁, n₂) in cycles/m or frequency strings; None: unbounded.
    ///
    /// Returns
    /// -------
    /// Spectrum
    ///     Spatial, unit "m".
    ///
    /// Raises
    /// ------
    /// InvalidInputError
    ///     An unknown class or bound, a band that is not 0 < n₁ < n₂.
    /// UnitError
    ///     A band edge that is not a spatial frequency.
    ///
    /// Examples
    /// --------
    /// >>> import stochvib
    /// >>> road = stochvib.Spectrum.iso8608("C", band=("0.011 cycles/m", "2.83 cycles/m"))
    /// >>> road.domain, road.unit
    /// ('spatial', 'm')
    #[staticmethod]
    #[pyo3(signature = (road_class, *, bound="geometric-mean", band=BandArg::Iso))]
    fn iso8608(py: Python<'_>, road_class: &str, bound: &str, band: BandArg<'_>) -> PyResult<Self> {
        let c: IsoClass = call(py, || road_class.parse())?;
        let b: IsoBound = call(py, || bound.parse())?;
        let band = match band {
            BandArg::Iso => Some(ISO_BAND),
            BandArg::Unbounded => None,
            BandArg::Edges(edges) => Some(Dims::new(py, "spatial", "m")?.band(py, &edges, "band", true)?),
        };
        Self::make(py, || PowerLaw::iso8608(c, b, band), "m")
    }

    /// A power-law density G(n) = g0 (n/n0)^{−w}, one-sided cyclic (n in cycles/m for a spatial process,
    /// Hz for a temporal one), optionally restricted to ``band`` = (n₁, n₂) in the same unit.
    ///
    /// Parameters
    /// ----------
    /// g0 : float or str
    ///     G(n0) in unit²·m (unit²·s temporal): a number or a string without an angle ("256e-6 m^3"; per
    ///     cycle is said by the one-sided cyclic convention, never by a unit).
    /// n0 : float or str
    ///     The reference frequency in cycles/m (Hz), or a frequency string ("0.1 cycles/m"; "1 rad/m" and
    ///     "1 1/m" are 1/(2π) cycles/m).
    /// waviness : float
    ///     w, a pure number.
    /// band : (float or str, float or str), keyword-only, optional
    ///     (n₁, n₂) in cycles/m (Hz) or frequency strings; None: unbounded.
    /// domain : {"spatial", "temporal"}, keyword-only
    /// unit : str, keyword-only
    ///     The SI unit of the process.
    ///
    /// Returns
    /// -------
    /// Spectrum
    ///
    /// Raises
    /// ------
    /// UnitError
    ///     A string of another dimension, naming the argument.
    ///
    /// Examples
    /// --------
    /// >>> import stochvib
    /// >>> a = stochvib.Spectrum.power_law("256e-6 m^3", "0.1 cycles/m", 2, band=("0.011 cycles/m", "2.83 cycles/m"))
    /// >>> b = stochvib.Spectrum.power_law(256e-6, 0.1, 2, band=(0.011, 2.83))
    /// >>> round(a.variance() / b.variance(), 12)
    /// 1.0
    #[staticmethod]
    #[pyo3(signature = (g0, n0, waviness, *, band=None, domain="spatial", unit="m"))]
    fn power_law(
        py: Python<'_>,
        g0: &Bound<'_, PyAny>,
        n0: &Bound<'_, PyAny>,
        waviness: &Bound<'_, PyAny>,
        band: Option<&Bound<'_, PyAny>>,
        domain: &str,
        unit: &str,
    ) -> PyResult<Self> {
        let q = Dims::new(py, domain, unit)?;
        let p = PowerLawParameters {
            g0: q.density(py, g0, "g0")?,
            n0: crate::quantity::frequency(py, n0, "n0", q.inv_lag(), true)?,
            waviness: crate::quantity::of_dim(py, waviness, "waviness", stochvib::units::Dim::DIMENSIONLESS)?,
            band: band
                .filter(|b| !b.is_none())
                .map(|b| q.band(py, b, "band", true))
                .transpose()?,
            domain: q.domain,
        };
        Self::make(py, || p.build(), unit)
    }

    /// A measured density given at points, interpolated linearly in log–log coordinates, zero outside.
    ///
    /// ``x``: abscissae in the convention's unit (Hz or cycles/m for "one-sided-cyclic", rad/s or rad/m
    /// otherwise), strictly increasing and > 0; ``values``: the density in that convention, > 0.
    /// ``convention`` is required: a wrong guess would scale the variance by 2, 2π or 4π.
    ///
    /// Parameters
    /// ----------
    /// x : array_like
    ///     Abscissae: Hz (cycles/m) for "one-sided-cyclic", rad/s (rad/m) otherwise; strictly increasing, > 0.
    /// values : array_like
    ///     The density at ``x`` in ``convention`` (unit² per the abscissa's unit), > 0, as many as ``x``.
    /// convention : str, keyword-only
    ///     "two-sided-angular", "one-sided-angular", "one-sided-cyclic" or "engineering".
    /// domain : {"temporal", "spatial"}, keyword-only, default "temporal"
    /// unit : str, keyword-only, default "m"
    ///     The SI unit of the process.
    ///
    /// Returns
    /// -------
    /// Spectrum
    ///
    /// Raises
    /// ------
    /// InvalidInputError
    ///     An unknown convention or domain; abscissae not increasing or not > 0; values not > 0; lengths
    ///     that differ; non-numeric input.
    ///
    /// Examples
    /// --------
    /// A flat one-sided cyclic level G = 1e-4 m²/Hz from 1 Hz to 11 Hz: σ² = G·10 Hz.
    ///
    /// >>> import stochvib
    /// >>> s = stochvib.Spectrum.tabulated([1.0, 11.0], [1e-4, 1e-4], convention="one-sided-cyclic")
    /// >>> round(s.variance() / 1e-3, 6)
    /// 1.0
    #[staticmethod]
    #[pyo3(signature = (x, values, *, convention, domain="temporal", unit="m"))]
    fn tabulated(
        py: Python<'_>,
        x: &Bound<'_, PyAny>,
        values: &Bound<'_, PyAny>,
        convention: &str,
        domain: &str,
        unit: &str,
    ) -> PyResult<Self> {
        let c = crate::names::convention(py, convention)?;
        let d = crate::names::domain(py, domain)?;
        let xs = crate::arrays::vector(py, x, "x")?;
        let vs = crate::arrays::vector(py, values, "values")?;
        Self::make(py, || Tabulated::new(c, xs, vs, d), unit)
    }

    /// Band-limited white noise: a constant ``level`` (in ``convention``) between the band edges ``low``
    /// and ``high`` (Hz or cycles/m for "one-sided-cyclic", rad/s or rad/m otherwise), zero outside.
    ///
    /// Parameters
    /// ----------
    /// level : float or str
    ///     The density in ``convention``: a number, or a string in unit² per 1/s (1/m) without an angle
    ///     ("1e-4 m^2 s"; per Hz or per rad/s is said by the convention).
    /// low, high : float or str
    ///     The band edges in the convention's abscissa (Hz or cycles/m for "one-sided-cyclic", rad/s or
    ///     rad/m otherwise), or frequency strings ("1 Hz" is 1 Hz there and 2π rad/s in the angular ones).
    /// convention : str, keyword-only
    ///     "two-sided-angular", "one-sided-angular", "one-sided-cyclic" or "engineering".
    /// domain : {"temporal", "spatial"}, keyword-only
    /// unit : str, keyword-only
    ///     The SI unit of the process.
    ///
    /// Returns
    /// -------
    /// Spectrum
    ///
    /// Raises
    /// ------
    /// UnitError
    ///     A string of another dimension, naming the argument.
    ///
    /// Examples
    /// --------
    /// σ² = G·(f₂ − f₁) for a one-sided cyclic level G:
    ///
    /// >>> import stochvib
    /// >>> s = stochvib.Spectrum.band_white("1e-4 m^2 s", "1 Hz", "11 Hz", convention="one-sided-cyclic")
    /// >>> round(s.variance() / 1e-3, 12)
    /// 1.0
    #[staticmethod]
    #[pyo3(signature = (level, low, high, *, convention, domain="temporal", unit="m"))]
    fn band_white(
        py: Python<'_>,
        level: &Bound<'_, PyAny>,
        low: &Bound<'_, PyAny>,
        high: &Bound<'_, PyAny>,
        convention: &str,
        domain: &str,
        unit: &str,
    ) -> PyResult<Self> {
        let c = crate::names::convention(py, convention)?;
        let q = Dims::new(py, domain, unit)?;
        let edge =
            |x: &Bound<'_, PyAny>, name: &str| crate::quantity::frequency(py, x, name, q.inv_lag(), c.is_cyclic());
        let p = BandWhiteParameters {
            convention: c,
            level: q.density(py, level, "level")?,
            lo: edge(low, "low")?,
            hi: edge(high, "high")?,
            domain: q.domain,
        };
        Self::make(py, || p.build(), unit)
    }

    /// A spectrum file or catalogue entry: a catalogue name (e.g. "iso8608-c", "type3") is looked up in the
    /// catalogue directory only; anything else is a path to a spectrum file (TOML).
    ///
    /// The catalogue directory is ``spectra_dir`` if given, else ``$STOCHVIB_SPECTRA``, else ``./spectra``
    /// if it exists, else the ``spectra/`` directory of the source tree the package was built from (as the
    /// command-line tool).
    ///
    /// Parameters
    /// ----------
    /// path_or_name : str or os.PathLike
    ///     A catalogue name, or the path of a spectrum file.
    /// spectra_dir : str or os.PathLike, keyword-only, optional
    ///     The catalogue directory (default as above).
    ///
    /// Returns
    /// -------
    /// Spectrum
    ///     With ``name``, ``description``, ``source`` and the file's text.
    ///
    /// Raises
    /// ------
    /// FileError
    ///     A file that cannot be read or parsed, naming the file, key, value and reason.
    /// InvalidInputError
    ///     A name that is neither a file nor in the catalogue (the message names the catalogue directory).
    ///
    /// Examples
    /// --------
    /// >>> import stochvib
    /// >>> stochvib.Spectrum.load("iso8608-c").domain
    /// 'spatial'
    #[staticmethod]
    #[pyo3(signature = (path_or_name, *, spectra_dir=None))]
    fn load(py: Python<'_>, path_or_name: PathBuf, spectra_dir: Option<PathBuf>) -> PyResult<Self> {
        let reference = path_or_name.to_string_lossy().into_owned();
        let f = call(py, || catalogue(spectra_dir).resolve(&reference, None))?;
        Ok(PySpectrum::from_file(f))
    }

    /// Every spectrum of the catalogue directory (see :meth:`load`), as a dict name → Spectrum, sorted by
    /// name. Invalid files are left out with a ``StochvibWarning`` naming the file and the reason.
    ///
    /// Parameters
    /// ----------
    /// spectra_dir : str or os.PathLike, keyword-only, optional
    ///     The catalogue directory (default as for :meth:`load`).
    ///
    /// Returns
    /// -------
    /// dict of str to Spectrum
    ///
    /// Raises
    /// ------
    /// FileError
    ///     A catalogue directory that cannot be listed.
    ///
    /// Examples
    /// --------
    /// >>> import stochvib
    /// >>> "iso8608-c" in stochvib.Spectrum.catalogue()
    /// True
    #[staticmethod]
    #[pyo3(signature = (*, spectra_dir=None))]
    fn catalogue<'py>(py: Python<'py>, spectra_dir: Option<PathBuf>) -> PyResult<Bound<'py, PyDict>> {
        let entries = call(py, || catalogue(spectra_dir).entries())?;
        let d = PyDict::new(py);
        for e in entries {
            match e.spectrum {
                Ok(f) => {
                    let name = f.name.clone();
                    d.set_item(name, Py::new(py, PySpectrum::from_file(f))?)?;
                }
                Err(msg) => {
                    let warning = py.import("stochvib.errors")?.getattr("StochvibWarning")?;
                    let text = std::ffi::CString::new(format!("{}: {msg}", e.path.display()))
                        .unwrap_or_else(|_| c"invalid spectrum file".into());
                    PyErr::warn(py, &warning, &text, 1)?;
                }
            }
        }
        Ok(d)
    }

    /// The spectral density at angular frequencies ``omega`` (rad/s) or at frequencies ``f`` (Hz).
    ///
    /// Parameters
    /// ----------
    /// omega : array_like, optional
    ///     ω in rad/s (rad/m for a spatial process), any shape; a scalar gives a float.
    /// f : array_like, keyword-only, optional
    ///     f in Hz (cycles/m for a spatial process) instead. Exactly one of ``omega`` and ``f``.
    /// convention : str, keyword-only, optional
    ///     With ``omega``: "two-sided-angular" (default) S(ω) in unit²·s/rad, "one-sided-angular"
    ///     G(ω) = 2S(ω) for ω ≥ 0 (0 below), or "engineering" Ŝ(ω) = 2π S(ω).
    ///     With ``f``: "one-sided-cyclic" (the default and the only one) G(f) = 4π S(2πf) in unit²/Hz,
    ///     0 for f < 0 — the convention of ``scipy.signal.welch`` and ISO 8608.
    /// out : numpy.ndarray, keyword-only, optional
    ///     A float64 C-contiguous array of the result's shape to write into (not converted).
    ///
    /// Returns
    /// -------
    /// float or numpy.ndarray of float64
    ///     The density, shaped as the argument.
    ///
    /// Raises
    /// ------
    /// InvalidInputError
    ///     Both or neither of ``omega`` and ``f``; a convention that does not belong to the argument
    ///     (hertz are never taken in an argument named ``omega``); complex or non-numeric input.
    ///
    /// Arguments are converted to C-contiguous float64 when they are not (lists, integers, strided or
    /// Fortran-ordered arrays). The GIL is released for long arrays.
    ///
    /// Examples
    /// --------
    /// >>> import stochvib
    /// >>> road = stochvib.Spectrum.iso8608("C")
    /// >>> round(road.density(f=0.1) * 1e6, 6)  # G_d(n0) of class C, m³
    /// 256.0
    /// >>> t1 = stochvib.Spectrum.exponential(1.0, 1.0)
    /// >>> round(t1.density(0.0) * 3.141592653589793, 12)  # S(0) = D/(πα)
    /// 1.0
    #[pyo3(signature = (omega=None, *, f=None, convention=None, out=None))]
    fn density<'py>(
        &self,
        py: Python<'py>,
        omega: Option<&Bound<'py, PyAny>>,
        f: Option<&Bound<'py, PyAny>>,
        convention: Option<&str>,
        out: Option<&Bound<'py, PyAny>>,
    ) -> PyResult<Bound<'py, PyAny>> {
        let (conv, x) = density_argument(py, omega, f, convention)?;
        let shape = x.shape().to_vec();
        let result = match out {
            Some(o) => check_out(py, o, &shape)?,
            // SAFETY: every element is written by `density_in` before the array is returned.
            None => unsafe { PyArrayDyn::<f64>::new(py, shape.clone(), false) },
        };
        {
            let xr = x.readonly();
            let mut rw = result
                .try_readwrite()
                .map_err(|e| invalid_input(py, format!("`out` cannot be written (is it `omega` itself?): {e}")))?;
            let xs = xr.as_slice()?;
            let os = rw.as_slice_mut()?;
            let s = &*self.spectrum;
            detached_if(py, xs.len(), DETACH_MIN_POINTS, || {
                density_in(s, conv, xs, os);
                Ok(())
            })?;
        }
        if out.is_some() {
            return Ok(result.into_any());
        }
        scalar_or_array(py, result, shape.is_empty())
    }

    /// The correlation function K(τ) = ∫ S(ω) cos(ωτ) dω at ``tau`` (s, or m for a spatial process; any
    /// shape; a scalar gives a float). Closed form where one exists, adaptive quadrature otherwise (raises
    /// :class:`NumericalError` if it does not converge, :class:`DivergentError` for an infinite variance).
    /// The GIL is released.
    ///
    /// Parameters
    /// ----------
    /// tau : array_like
    ///     The lag τ in s (m for a spatial process), any shape.
    ///
    /// Returns
    /// -------
    /// float or numpy.ndarray of float64
    ///     K(τ) in unit², shaped as ``tau``.
    ///
    /// Raises
    /// ------
    /// DivergentError
    ///     An infinite variance (e.g. an unbounded ISO 8608 road).
    /// NumericalError
    ///     A quadrature that does not converge.
    /// InvalidInputError
    ///     Complex or non-numeric ``tau``.
    ///
    /// Examples
    /// --------
    /// K(τ) = D e^{−α|τ|} for the exponential correlation with D = 1, α = 2:
    ///
    /// >>> import math, stochvib
    /// >>> k = stochvib.Spectrum.exponential(1.0, 2.0).correlation([0.0, 0.5])
    /// >>> round(float(k[0]), 12), round(float(k[1]) * math.e, 12)
    /// (1.0, 1.0)
    fn correlation<'py>(&self, py: Python<'py>, tau: &Bound<'py, PyAny>) -> PyResult<Bound<'py, PyAny>> {
        let x = real_array(py, tau, "tau")?;
        let shape = x.shape().to_vec();
        // SAFETY: every element is written below, or the array is dropped on error.
        let result = unsafe { PyArrayDyn::<f64>::new(py, shape.clone(), false) };
        {
            let xr = x.readonly();
            let mut rw = result.readwrite();
            let xs = xr.as_slice()?;
            let os = rw.as_slice_mut()?;
            let s = &*self.spectrum;
            detached(py, || {
                for (o, &t) in os.iter_mut().zip(xs) {
                    *o = s.correlation(t).map_err(Failure::Lib)?;
                }
                Ok(())
            })?;
        }
        scalar_or_array(py, result, shape.is_empty())
    }

    /// The variance D = K(0) = ∫ S(ω) dω, in unit². Closed form where one exists, quadrature otherwise.
    /// Raises :class:`DivergentError` (with the reason and what finite question to ask instead) when it
    /// is infinite, e.g. an ISO 8608 road without a band.
    ///
    /// Returns
    /// -------
    /// float
    ///     D in unit².
    ///
    /// Raises
    /// ------
    /// DivergentError
    ///     An infinite variance.
    /// NumericalError
    ///     A quadrature that does not converge.
    ///
    /// Examples
    /// --------
    /// >>> import stochvib
    /// >>> stochvib.Spectrum.exponential(2.25, 1.0).variance()
    /// 2.25
    fn variance(&self, py: Python<'_>) -> PyResult<f64> {
        let s = &*self.spectrum;
        detached(py, || s.variance().map_err(Failure::Lib))
    }

    /// The temporal process a vehicle at ``speed`` (m/s) feels from this spatial (road) spectrum:
    /// S_t(ω) = S_Ω(ω/v)/v, ω in rad/s. Raises :class:`InvalidInputError` for a temporal spectrum.
    /// ``speed`` may carry a unit ("36 km/h").
    ///
    /// Parameters
    /// ----------
    /// speed : float or str
    ///     v in m/s, > 0, or a speed string ("36 km/h").
    ///
    /// Returns
    /// -------
    /// Spectrum
    ///     Temporal, same unit; the variance is unchanged.
    ///
    /// Raises
    /// ------
    /// InvalidInputError
    ///     A temporal spectrum; a speed that is not finite and > 0.
    /// UnitError
    ///     A speed string of another dimension.
    ///
    /// Examples
    /// --------
    /// >>> import stochvib
    /// >>> road = stochvib.Spectrum.iso8608("C")
    /// >>> t = road.at_speed("36 km/h")
    /// >>> t.domain, round(t.variance() / road.variance(), 6)
    /// ('temporal', 1.0)
    fn at_speed(&self, py: Python<'_>, speed: &Bound<'_, PyAny>) -> PyResult<Self> {
        let speed = crate::quantity::quantity(py, speed, "speed", "m/s")?;
        let a = call(py, || AtSpeed::new(self.spectrum.clone(), speed))?;
        Ok(PySpectrum {
            spectrum: Arc::new(a),
            unit: self.unit.clone(),
            name: if self.name.is_empty() {
                String::new()
            } else {
                format!("{} at {speed} m/s", self.name)
            },
            description: self.description.clone(),
            source: self.source.clone(),
            text: self.text.clone(),
            origin: self.origin.clone(),
        })
    }

    /// The rational form S = N(ω²)/D(ω²) (two-sided angular) as (N, D) coefficient arrays in powers of ω²,
    /// DESCENDING unless ``order="ascending"``; None when the density is not rational.
    ///
    /// Parameters
    /// ----------
    /// order : {"descending", "ascending"}, keyword-only, default "descending"
    ///
    /// Returns
    /// -------
    /// (numpy.ndarray, numpy.ndarray) or None
    ///     N and D; S(ω) in unit²·s/rad (unit²·m/rad spatial).
    ///
    /// Raises
    /// ------
    /// InvalidInputError
    ///     An unknown ``order``.
    ///
    /// Examples
    /// --------
    /// S(ω) = (Dα/π)/(ω² + α²) for the exponential correlation, D = 1, α = 2:
    ///
    /// >>> import math, stochvib
    /// >>> n, d = stochvib.Spectrum.exponential(1.0, 2.0).rational_coefficients()
    /// >>> [round(float(x / d[0]), 12) for x in d], round(float(n[0] / d[0]) * math.pi / 2, 12)
    /// ([1.0, 4.0], 1.0)
    /// >>> stochvib.Spectrum.iso8608("C").rational_coefficients() is None
    /// True
    #[pyo3(signature = (*, order="descending"))]
    fn rational_coefficients<'py>(&self, py: Python<'py>, order: &str) -> PyResult<Option<Coefficients<'py>>> {
        let desc = crate::arrays::descending(py, order)?;
        Ok(self.spectrum.rational().map(|r| {
            (
                crate::arrays::polynomial_to_py(py, r.numerator(), desc),
                crate::arrays::polynomial_to_py(py, r.denominator(), desc),
            )
        }))
    }

    /// The stable minimum-phase shaping filter (b, a) with S(ω) = |b(iω)/a(iω)|² / (2π): unit-intensity
    /// white noise (E[w(t)w(t+τ)] = δ(τ)) through b/a has this spectrum.
    ///
    /// Coefficients in powers of s, DESCENDING unless ``order="ascending"`` (``scipy.signal.freqs(b, a)``
    /// takes them as returned). Raises :class:`NotApplicableError` for a non-rational density.
    ///
    /// Parameters
    /// ----------
    /// order : {"descending", "ascending"}, keyword-only, default "descending"
    ///
    /// Returns
    /// -------
    /// (numpy.ndarray, numpy.ndarray)
    ///     b and a: the filter maps a white noise of unit intensity (1/s) onto the process (its unit).
    ///
    /// Raises
    /// ------
    /// NotApplicableError
    ///     A density that is not rational (e.g. an ISO 8608 road).
    /// InvalidInputError
    ///     An unknown ``order``.
    ///
    /// Examples
    /// --------
    /// >>> import stochvib
    /// >>> b, a = stochvib.Spectrum.exponential(1.0, 2.0).shaping_filter()
    /// >>> [round(float(x), 12) for x in a], [round(float(x * x), 12) for x in b]  # √(2αD)/(s + α)
    /// ([1.0, 2.0], [4.0])
    #[pyo3(signature = (*, order="descending"))]
    fn shaping_filter<'py>(&self, py: Python<'py>, order: &str) -> PyResult<Coefficients<'py>> {
        let desc = crate::arrays::descending(py, order)?;
        let r = self.spectrum.rational().ok_or_else(|| {
            not_applicable(
                py,
                format!(
                    "{} is not rational: it has no exact shaping filter",
                    self.spectrum.describe()
                ),
            )
        })?;
        let f = call(py, || r.shaping_filter())?;
        Ok((
            crate::arrays::polynomial_to_py(py, &f.num, desc),
            crate::arrays::polynomial_to_py(py, &f.den, desc),
        ))
    }

    /// "temporal" (ω in rad/s, τ in s) or "spatial" (Ω in rad/m, lag in m).
    #[getter]
    fn domain(&self) -> &'static str {
        domain_name(self.spectrum.domain())
    }

    /// SI unit of the process itself (e.g. "m" for a road profile, "N" for a force).
    #[getter]
    fn unit(&self) -> &str {
        &self.unit
    }

    /// Catalogue or file name ("" for a spectrum built in Python).
    #[getter]
    fn name(&self) -> &str {
        &self.name
    }

    /// One line: the model, its parameters and units.
    #[getter]
    fn description(&self) -> String {
        self.spectrum.describe()
    }

    /// Provenance of the parameter values (spectrum files).
    #[getter]
    fn source(&self) -> &str {
        &self.source
    }

    /// The spectrum file's text ("" for a spectrum built in Python).
    #[getter]
    fn text(&self) -> &str {
        &self.text
    }

    fn __repr__(&self) -> String {
        let name = if self.name.is_empty() {
            String::new()
        } else {
            format!("{}: ", self.name)
        };
        format!("<stochvib.Spectrum {name}{} [{}]>", self.spectrum.describe(), self.unit)
    }
}
