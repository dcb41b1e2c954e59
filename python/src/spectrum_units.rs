//! The quantities of the `Spectrum` constructors as Python arguments: a number (SI, in the unit the
//! docstring states) or a string with a unit whose dimension follows from `domain=` and `unit=` — the
//! variance in unit², a decay rate α in 1/s or 1/m (1/s², 1/m² for the Gaussian kinds), β and the band edges
//! as frequencies, a density level in unit² per 1/s or 1/m. As in spectrum files, a decay rate and a density
//! level refuse `Hz`, `rad`, `cycles` and `deg`: their SI value would silently carry 2π (a frequency's SI
//! value is angular), and a density's per-Hz or per-rad/s is named by its `convention`.

use crate::errors::unit_error;
use crate::quantity::{frequency, frequency_pair, of_dim, without_angle};
use pyo3::prelude::*;
use pyo3::types::PyString;
use stochvib::spectrum::Domain;
use stochvib::units::{unit_dim, Dim};

/// Why a decay rate refuses an angle, and what to write.
const DECAY_RATE: &str = "a decay rate carries no angle or cycle (Hz, rad, cycles, deg would scale it by 2π or \
                          π/180): write it in 1/s, or 1/m for domain=\"spatial\" (1/s^2, 1/m^2 for a gaussian α)";

/// Why a density level refuses an angle, and what to write.
const DENSITY: &str = "a density level is per 1/s or 1/m: whether per Hz or per rad/s is said by `convention` (a \
                       unit would apply the 2π twice), e.g. \"1e-4 m^2 s\" or \"16e-6 m^3\"";

/// The dimensions of a constructor's quantities, from its `domain=` and the process's `unit=`.
pub struct Dims {
    /// The domain.
    pub domain: Domain,
    /// s (temporal) or m (spatial).
    lag: Dim,
    /// The process's dimension; `None` for a unit that is no coherent SI unit (then only numbers are taken).
    unit: Option<Dim>,
    /// `unit=` as given.
    unit_text: String,
}

impl Dims {
    /// The dimensions of a spectrum of `domain` ("temporal", "spatial") in `unit`.
    ///
    /// # Errors
    /// `InvalidInputError` for an unknown domain.
    pub fn new(py: Python<'_>, domain: &str, unit: &str) -> PyResult<Dims> {
        let domain = crate::names::domain(py, domain)?;
        let lag = match domain {
            Domain::Temporal => Dim::TIME,
            Domain::Spatial => Dim::LENGTH,
        };
        Ok(Dims {
            domain,
            lag,
            unit: unit_dim(unit),
            unit_text: unit.to_string(),
        })
    }

    /// 1/s or 1/m.
    pub fn inv_lag(&self) -> Dim {
        pow(self.lag, -1)
    }

    /// The variance D, unit².
    pub fn variance(&self, py: Python<'_>, obj: &Bound<'_, PyAny>) -> PyResult<f64> {
        let unit = self.process(py, obj, "variance")?;
        of_dim(py, obj, "variance", pow(unit, 2))
    }

    /// (variance, α, β) of a decaying cosine (types 3 and 4), α of dimension (1/lag)^`power`.
    pub fn decaying_cosine(
        &self,
        py: Python<'_>,
        [variance, alpha, beta]: [&Bound<'_, PyAny>; 3],
        power: i8,
    ) -> PyResult<(f64, f64, f64)> {
        Ok((
            self.variance(py, variance)?,
            self.decay_rate(py, alpha, "alpha", power)?,
            self.angular(py, beta, "beta")?,
        ))
    }

    /// A decay rate `name` of dimension (1/lag)^`power`.
    pub fn decay_rate(&self, py: Python<'_>, obj: &Bound<'_, PyAny>, name: &str, power: i8) -> PyResult<f64> {
        without_angle(py, obj, name, pow(self.lag, -power), DECAY_RATE)
    }

    /// An angular frequency `name` (rad/s or rad/m): "1 Hz" is 2π.
    pub fn angular(&self, py: Python<'_>, obj: &Bound<'_, PyAny>, name: &str) -> PyResult<f64> {
        frequency(py, obj, name, self.inv_lag(), false)
    }

    /// A band (low, high) in Hz or cycles/m when `cyclic`, else rad/s or rad/m.
    pub fn band(&self, py: Python<'_>, obj: &Bound<'_, PyAny>, name: &str, cyclic: bool) -> PyResult<(f64, f64)> {
        frequency_pair(py, obj, name, self.inv_lag(), cyclic)
    }

    /// A density level `name`: unit² per 1/lag, with no angle in the unit.
    pub fn density(&self, py: Python<'_>, obj: &Bound<'_, PyAny>, name: &str) -> PyResult<f64> {
        let unit = self.process(py, obj, name)?;
        let d = pow(unit, 2);
        let want = Dim::new(d.m + self.lag.m, d.kg + self.lag.kg, d.s + self.lag.s);
        without_angle(py, obj, name, want, DENSITY)
    }

    /// The process's dimension for the string `obj` given as `name` (a number needs none).
    fn process(&self, py: Python<'_>, obj: &Bound<'_, PyAny>, name: &str) -> PyResult<Dim> {
        match self.unit {
            Some(d) => Ok(d),
            None if !obj.is_instance_of::<PyString>() => Ok(Dim::DIMENSIONLESS),
            None => Err(unit_error(
                py,
                name,
                &obj.str()?.to_cow()?,
                &format!(
                    "unit={:?} is no coherent SI unit (m, N, m/s^2, rad, 1), so `{name}` has no dimension to \
                     check a string against: give it as a number",
                    self.unit_text
                ),
            )),
        }
    }
}

/// `d`^`k`.
fn pow(d: Dim, k: i8) -> Dim {
    Dim::new(d.m * k, d.kg * k, d.s * k)
}

/// `band=` of `Spectrum.iso8608`: not given (the ISO band), `None` (unbounded), or the edges.
pub enum BandArg<'py> {
    /// The default: the ISO band.
    Iso,
    /// `None`: no band.
    Unbounded,
    /// A pair of edges.
    Edges(Bound<'py, PyAny>),
}

impl<'a, 'py> FromPyObject<'a, 'py> for BandArg<'py> {
    type Error = PyErr;

    fn extract(obj: Borrowed<'a, 'py, PyAny>) -> PyResult<Self> {
        Ok(if obj.is_none() {
            BandArg::Unbounded
        } else {
            BandArg::Edges(obj.to_owned())
        })
    }
}
