//! `stochvib.System`: a linear system known through its frequency response H(iω) (outputs × inputs).

use crate::arrays::{matrix, matrix_to_py, vector};
use crate::convert::{to_python, toml_table};
use crate::errors::{call, detached_if, invalid_input, lib, not_applicable};
use numpy::{Complex64, PyArray1, PyArrayDyn, PyArrayMethods, PyUntypedArrayMethods};
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyList};
use std::path::{Path, PathBuf};
use std::sync::Arc;
use stochvib::models::{InputLayout, ModelInstance};
use stochvib::scenario::{build_model, BuiltModel, ModelContext, MODEL_KINDS};
use stochvib::system::{modal_analysis, FrequencyResponse, Mdof, OutputInfo, Quantity, StateSpace, TransferFunction};
use stochvib::Error;

/// A linear time-invariant system known through its frequency response H(iω), outputs × inputs, with
/// named outputs carrying SI units.
///
/// Build one from matrices (:meth:`mdof`: M q̈ + B q̇ + C q = K_u u + B_u u̇ + F f; :meth:`state_space`:
/// ẋ = Ax + Bu, y = Cx + Du + Eu̇; :meth:`transfer_function`: N(s)/D(s)), from a catalogue model
/// (:meth:`model`, :meth:`models`) or from a scenario file (:meth:`load`).
#[pyclass(name = "System", module = "stochvib", frozen)]
pub struct PySystem {
    /// The system.
    pub system: Arc<dyn FrequencyResponse>,
    /// How a random input reaches the inputs (catalogue models and scenario files).
    pub layout: Option<InputLayout>,
    /// One line.
    pub description: String,
    /// The model kind (`mdof`, `state-space`, `transfer-function` or a catalogue kind).
    pub kind: String,
    /// Mass and stiffness matrices, for modes (systems built by `System.mdof`).
    pub mass_stiffness: Option<(nalgebra::DMatrix<f64>, nalgebra::DMatrix<f64>)>,
}

impl PySystem {
    /// A system of a model instance (catalogue models, scenario files).
    pub fn from_instance(m: &ModelInstance, kind: &str) -> Self {
        PySystem {
            system: m.system.clone(),
            layout: Some(m.layout.clone()),
            description: m.description.clone(),
            kind: kind.to_string(),
            mass_stiffness: None,
        }
    }

    /// The model instance the analysis and the simulation use.
    pub fn instance(&self) -> ModelInstance {
        ModelInstance {
            system: self.system.clone(),
            layout: self.layout.clone().unwrap_or(InputLayout::Track {
                positions: vec![0.0; self.system.n_inputs()],
                gains: vec![1.0; self.system.n_inputs()],
            }),
            description: self.description.clone(),
        }
    }
}

/// Output names and units: a list of names or (name, unit) pairs, or `count` defaults `prefix1..`.
fn output_infos(
    py: Python<'_>,
    spec: Option<&Bound<'_, PyAny>>,
    count: usize,
    prefix: &str,
    unit: &str,
) -> PyResult<Vec<OutputInfo>> {
    let Some(spec) = spec else {
        return Ok((1..=count)
            .map(|k| OutputInfo::new(format!("{prefix}{k}"), unit))
            .collect());
    };
    let mut v = Vec::new();
    for item in spec.try_iter()? {
        let item = item?;
        if let Ok(name) = item.extract::<String>() {
            v.push(OutputInfo::new(name, unit));
        } else if let Ok((name, u)) = item.extract::<(String, String)>() {
            v.push(OutputInfo::new(name, u));
        } else {
            return Err(invalid_input(
                py,
                format!(
                    "output names: expected a name or a (name, unit) pair, got {}",
                    item.repr()?
                ),
            ));
        }
    }
    Ok(v)
}

fn quantity(py: Python<'_>, name: &str, kind: &str, point: Vec<f64>) -> PyResult<Quantity> {
    match kind {
        "displacement" => Ok(Quantity::Displacement(point)),
        "velocity" => Ok(Quantity::Velocity(point)),
        "acceleration" => Ok(Quantity::Acceleration(point)),
        other => lib(
            py,
            Err(Error::invalid(
                &format!("outputs[{name:?}]"),
                other,
                "expected \"displacement\", \"velocity\" or \"acceleration\" (of the point gᵀq)",
            )),
        ),
    }
}

#[pymethods]
impl PySystem {
    /// A multi-degree-of-freedom model M q̈ + B q̇ + C q = K_u u + B_u u̇ + F f.
    ///
    /// Parameters
    /// ----------
    /// mass, damping, stiffness : array_like, n × n
    ///     M (kg or kg m², symmetric positive definite), B (N s/m, symmetric) and C (N/m, symmetric).
    ///     Keyword-only: ``mdof(mass=M, damping=B, stiffness=C)`` (state_space's B and C are other
    ///     matrices).
    /// base_stiffness, base_damping : array_like, n × n_base, optional
    ///     K_u (N/m) and B_u (N s/m): how the base (kinematic) inputs u push the coordinates.
    /// forces : array_like, n × n_force, optional
    ///     F: how the force inputs f enter; default the identity (one force per coordinate) when there
    ///     are no base inputs. Inputs are ordered base inputs first, then forces.
    /// coordinates : sequence of str or (str, str), optional
    ///     Names or (name, unit) pairs of q (default q1…qn in m).
    /// outputs : dict, optional
    ///     name → (quantity, g) with quantity "displacement", "velocity" or "acceleration" of the point
    ///     gᵀq (default: the displacement of every coordinate).
    ///
    /// Returns
    /// -------
    /// System
    ///
    /// Raises
    /// ------
    /// InvalidInputError
    ///     A matrix of the wrong shape, not symmetric, M not positive definite.
    ///
    /// Examples
    /// --------
    /// >>> import stochvib
    /// >>> s = stochvib.System.mdof(mass=[[20.0]], damping=[[60.0]], stiffness=[[8000.0]])
    /// >>> s.outputs
    /// [('q1', 'm')]
    #[staticmethod]
    #[pyo3(signature = (*, mass, damping, stiffness, base_stiffness=None, base_damping=None, forces=None, coordinates=None, outputs=None))]
    #[allow(clippy::too_many_arguments)]
    fn mdof(
        py: Python<'_>,
        mass: &Bound<'_, PyAny>,
        damping: &Bound<'_, PyAny>,
        stiffness: &Bound<'_, PyAny>,
        base_stiffness: Option<&Bound<'_, PyAny>>,
        base_damping: Option<&Bound<'_, PyAny>>,
        forces: Option<&Bound<'_, PyAny>>,
        coordinates: Option<&Bound<'_, PyAny>>,
        outputs: Option<&Bound<'_, PyDict>>,
    ) -> PyResult<Self> {
        let m = matrix(py, mass, "mass")?;
        let b = matrix(py, damping, "damping")?;
        let c = matrix(py, stiffness, "stiffness")?;
        let n = m.nrows();
        let opt = |x: Option<&Bound<'_, PyAny>>, name: &str| x.map(|x| matrix(py, x, name)).transpose();
        let (ku, bu) = match (
            opt(base_stiffness, "base_stiffness")?,
            opt(base_damping, "base_damping")?,
        ) {
            (None, None) => (nalgebra::DMatrix::zeros(n, 0), nalgebra::DMatrix::zeros(n, 0)),
            (Some(k), None) => {
                let z = nalgebra::DMatrix::zeros(k.nrows(), k.ncols());
                (k, z)
            }
            (None, Some(bb)) => (nalgebra::DMatrix::zeros(bb.nrows(), bb.ncols()), bb),
            (Some(k), Some(bb)) => (k, bb),
        };
        let f = match opt(forces, "forces")? {
            Some(f) => f,
            None if ku.ncols() == 0 => nalgebra::DMatrix::identity(n, n),
            None => nalgebra::DMatrix::zeros(n, 0),
        };
        let coords = output_infos(py, coordinates, n, "q", "m")?;
        let pairs: Vec<(&str, &str)> = coords.iter().map(|o| (o.name.as_str(), o.unit.as_str())).collect();
        let mut model = call(py, || Mdof::new(&pairs, m.clone(), b, c.clone(), ku, bu, f))?;
        match outputs {
            None => {
                for (k, o) in coords.iter().enumerate() {
                    let mut g = vec![0.0; n];
                    g[k] = 1.0;
                    model = call(py, || model.with_output(&o.name, Quantity::Displacement(g)))?;
                }
            }
            Some(d) => {
                for (name, spec) in d.iter() {
                    let name: String = name.extract()?;
                    let (kind, point): (String, Bound<'_, PyAny>) = spec.extract().map_err(|_| {
                        invalid_input(py, format!("outputs[{name:?}]: expected (quantity, point vector)"))
                    })?;
                    let g = vector(py, &point, &format!("outputs[{name:?}] point"))?;
                    let q = quantity(py, &name, &kind, g)?;
                    model = call(py, || model.with_output(&name, q))?;
                }
            }
        }
        let description = format!(
            "multi-degree-of-freedom model, {n} coordinates, {} inputs, {} outputs",
            model.n_inputs(),
            model.outputs().len()
        );
        Ok(PySystem {
            system: Arc::new(model),
            layout: None,
            description,
            kind: "mdof".into(),
            mass_stiffness: Some((m, c)),
        })
    }

    /// A state-space system ẋ = A x + B u, y = C x + D u + E u̇ (H(s) = C(sI − A)⁻¹B + D + sE).
    ///
    /// ``A`` n × n, ``B`` n × m, ``C`` p × n, ``D`` and ``E`` p × m (default zero). ``outputs``: p names or
    /// (name, unit) pairs (default y1…yp, unit "1").
    ///
    /// Parameters
    /// ----------
    /// A, B, C : array_like
    ///     n × n, n × m and p × n real matrices (SI units of the states, inputs and outputs; t in s).
    /// D, E : array_like, optional
    ///     p × m; default zero. E multiplies u̇ (its unit per 1/s).
    /// outputs : list of str or of (str, str), keyword-only, optional
    ///     One name or (name, SI unit) per row of C; default "y1" … "yp", unit "1".
    ///
    /// Returns
    /// -------
    /// System
    ///
    /// Raises
    /// ------
    /// InvalidInputError
    ///     Shapes that do not fit, non-finite or non-numeric entries, a wrong number of outputs.
    ///
    /// Examples
    /// --------
    /// ẋ = −2x + u, y = x: H(s) = 1/(s + 2), so H(0) = 1/2.
    ///
    /// >>> import stochvib
    /// >>> sys = stochvib.System.state_space([[-2.0]], [[1.0]], [[1.0]], outputs=[("x", "m")])
    /// >>> complex(sys.frequency_response(0.0)[0, 0])
    /// (0.5+0j)
    #[staticmethod]
    #[pyo3(signature = (A, B, C, D=None, E=None, *, outputs=None))]
    #[allow(non_snake_case)]
    fn state_space(
        py: Python<'_>,
        A: &Bound<'_, PyAny>,
        B: &Bound<'_, PyAny>,
        C: &Bound<'_, PyAny>,
        D: Option<&Bound<'_, PyAny>>,
        E: Option<&Bound<'_, PyAny>>,
        outputs: Option<&Bound<'_, PyAny>>,
    ) -> PyResult<Self> {
        let a = matrix(py, A, "A")?;
        let b = matrix(py, B, "B")?;
        let c = matrix(py, C, "C")?;
        let d = D.map(|x| matrix(py, x, "D")).transpose()?;
        let e = E.map(|x| matrix(py, x, "E")).transpose()?;
        let infos = output_infos(py, outputs, c.nrows(), "y", "1")?;
        let ss = call(py, || StateSpace::new(a, b, c, d, e, infos))?;
        let description = format!(
            "state space, {} states, {} inputs, {} outputs",
            ss.n_states(),
            ss.n_inputs(),
            ss.outputs().len()
        );
        Ok(PySystem {
            system: Arc::new(ss),
            layout: None,
            description,
            kind: "state-space".into(),
            mass_stiffness: None,
        })
    }

    /// A single-input single-output transfer function H(s) = N(s)/D(s).
    ///
    /// Parameters
    /// ----------
    /// numerator, denominator : array_like
    ///     Real coefficients in DESCENDING powers of s (highest power first), as ``scipy.signal.freqs``,
    ///     ``scipy.signal.TransferFunction`` and ``control.tf`` take them.
    /// order : {"descending", "ascending"}, keyword-only
    ///     ``"ascending"`` takes the coefficients lowest power first (the scenario files' convention).
    /// output, unit : str, keyword-only
    ///     The output's name and SI unit.
    ///
    /// The numerator may exceed the denominator degree by one (a derivative feedthrough, e.g. a damper's
    /// base-velocity term).
    ///
    /// Returns
    /// -------
    /// System
    ///
    /// Raises
    /// ------
    /// InvalidInputError
    ///     Non-finite coefficients, a zero leading denominator coefficient, a bad ``order``.
    ///
    /// Examples
    /// --------
    /// H(s) = 1/(s² + 2s + 5), as ``scipy.signal.freqs([1], [1, 2, 5])``:
    ///
    /// >>> import stochvib
    /// >>> h = stochvib.System.transfer_function([1.0], [1.0, 2.0, 5.0])
    /// >>> complex(h.frequency_response(0.0)[0, 0])
    /// (0.2+0j)
    #[staticmethod]
    #[pyo3(signature = (numerator, denominator, *, order="descending", output="y", unit="1"))]
    fn transfer_function(
        py: Python<'_>,
        numerator: &Bound<'_, PyAny>,
        denominator: &Bound<'_, PyAny>,
        order: &str,
        output: &str,
        unit: &str,
    ) -> PyResult<Self> {
        let n = crate::arrays::polynomial(py, numerator, "numerator", order)?;
        let d = crate::arrays::polynomial(py, denominator, "denominator", order)?;
        let tf = call(py, || TransferFunction::new(n, d, OutputInfo::new(output, unit)))?;
        Ok(PySystem {
            system: Arc::new(tf),
            layout: None,
            description: "transfer function".into(),
            kind: "transfer-function".into(),
            mass_stiffness: None,
        })
    }

    /// A model of the catalogue (``stochvib.System.models()`` lists the kinds), built by the library from
    /// the keyword arguments exactly as from the ``[model]`` table of a scenario file: numbers are SI,
    /// strings carry units ("70 kN/m", "30 t"). ``speed`` (m/s) is the ``[input] speed`` some models need.
    /// Deterministic kinds (the hoists, the chain) have no frequency response for random analysis: load
    /// their scenario file with :meth:`Scenario.load` instead.
    ///
    /// A bad value raises :class:`InvalidInputError` (a bad unit :class:`UnitError`) naming the parameter.
    ///
    /// Parameters
    /// ----------
    /// kind : str
    ///     A model kind of :meth:`models` (e.g. "quarter-car").
    /// speed : float or str, keyword-only, optional
    ///     m/s or a speed string ("72 km/h"), for the kinds that need it.
    /// **params : float or str
    ///     The kind's parameters as named in its ``[model]`` table: SI numbers or strings with units.
    ///
    /// Returns
    /// -------
    /// System
    ///     With the kind's outputs and input layout.
    ///
    /// Raises
    /// ------
    /// InvalidInputError
    ///     An unknown kind, a missing, unknown or invalid parameter (named).
    /// UnitError
    ///     A parameter string of the wrong dimension.
    /// NotApplicableError
    ///     A deterministic kind.
    ///
    /// Examples
    /// --------
    /// >>> import stochvib
    /// >>> car = stochvib.System.model("quarter-car", sprung_mass="300 kg", unsprung_mass="40 kg",
    /// ...     suspension_stiffness="20 kN/m", suspension_damping="1.5 kN*s/m", tyre_stiffness="200 kN/m")
    /// >>> [name for name, unit in car.outputs][:2]
    /// ['body', 'body_acc']
    #[staticmethod]
    #[pyo3(signature = (kind, *, speed=None, **params))]
    fn model(
        py: Python<'_>,
        kind: &str,
        speed: Option<&Bound<'_, PyAny>>,
        params: Option<&Bound<'_, PyDict>>,
    ) -> PyResult<Self> {
        let speed = crate::quantity::optional(py, speed, "speed", "m/s")?;
        if let Some(k) = stochvib::scenario::model_kind(kind).filter(|k| !k.stochastic) {
            return Err(not_applicable(
                py,
                format!(
                    "`{}` is a deterministic model (no random input): load its scenario file (e.g. {}) with \
                     stochvib.Scenario.load(path) and call analyze()",
                    k.name, k.example
                ),
            ));
        }
        let table = match params {
            Some(d) => toml_table(py, "model", d)?,
            None => toml::Table::new(),
        };
        let path = Path::new("System.model");
        let f = stochvib::fields::Fields::new(path, "model", &table);
        let built = build_model(
            kind,
            &f,
            ModelContext {
                speed,
                several_inputs: false,
            },
        )
        .and_then(|b| f.finish().map(|()| b))
        .map_err(|e| model_param_error(py, e, &table))?;
        match built {
            BuiltModel::Stochastic(m) => Ok(PySystem::from_instance(&m, kind)),
            BuiltModel::Deterministic(_) => Err(not_applicable(
                py,
                format!("`{kind}` is a deterministic model (no random input): use stochvib.Scenario.load"),
            )),
        }
    }

    /// Every model kind a scenario file (and :meth:`model`) may name: a list of dicts with ``name``,
    /// ``family`` ("generic" or "catalogue"), ``stochastic``, ``summary`` and ``example`` (a scenario file).
    ///
    /// Returns
    /// -------
    /// list of dict
    ///
    /// Examples
    /// --------
    /// >>> import stochvib
    /// >>> "quarter-car" in [m["name"] for m in stochvib.System.models()]
    /// True
    #[staticmethod]
    fn models(py: Python<'_>) -> PyResult<Bound<'_, PyAny>> {
        to_python(py, &MODEL_KINDS)
    }

    /// The system of a scenario file (with the layout of its random input).
    ///
    /// Parameters
    /// ----------
    /// path : str or os.PathLike
    ///     A scenario file (TOML).
    /// spectra_dir : str or os.PathLike, keyword-only, optional
    ///     The spectrum catalogue directory (see :meth:`Spectrum.load`).
    ///
    /// Returns
    /// -------
    /// System
    ///
    /// Raises
    /// ------
    /// FileError
    ///     A file that cannot be read or is invalid, naming the file, key, value and reason.
    ///
    /// Examples
    /// --------
    /// >>> import stochvib
    /// >>> "y" in [name for name, unit in stochvib.System.load("data/conveyor-idler.toml").outputs]
    /// True
    #[staticmethod]
    #[pyo3(signature = (path, *, spectra_dir=None))]
    fn load(py: Python<'_>, path: PathBuf, spectra_dir: Option<PathBuf>) -> PyResult<Self> {
        let cat = crate::names::catalogue(spectra_dir);
        let sc = call(py, || stochvib::scenario::load_scenario(&path, cat.dir()))?;
        Ok(PySystem::from_instance(&sc.model, &sc.kind))
    }

    /// The frequency response H(iω): y(iω) = H(iω) u(iω).
    ///
    /// Parameters
    /// ----------
    /// omega : array_like, optional
    ///     Angular frequencies ω in rad/s (rad/m for a system driven along a road), any shape.
    /// f : array_like, keyword-only, optional
    ///     Cyclic frequencies in Hz instead (ω = 2πf). Exactly one of ``omega`` and ``f``.
    ///
    /// Returns
    /// -------
    /// numpy.ndarray of complex128
    ///     Shape (outputs, inputs, *omega.shape); a scalar gives an (outputs, inputs) array. For a SISO
    ///     system ``h[0, 0]`` is what ``scipy.signal.freqs(b, a, worN=omega)[1]`` returns.
    ///
    /// The GIL is released for long arrays.
    ///
    /// Examples
    /// --------
    /// >>> import numpy as np, stochvib
    /// >>> h = stochvib.System.transfer_function([1.0], [1.0, 1.0])
    /// >>> h.frequency_response(np.array([0.0, 1.0])).shape
    /// (1, 1, 2)
    /// >>> round(float(abs(h.frequency_response(f=1 / (2 * np.pi))[0, 0])) ** 2, 12)  # |1/(1 + i)|²
    /// 0.5
    #[pyo3(signature = (omega=None, *, f=None))]
    fn frequency_response<'py>(
        &self,
        py: Python<'py>,
        omega: Option<&Bound<'py, PyAny>>,
        f: Option<&Bound<'py, PyAny>>,
    ) -> PyResult<Bound<'py, PyAny>> {
        let x = crate::arrays::angular(py, omega, f)?;
        let (p, m) = (self.system.outputs().len(), self.system.n_inputs());
        let mut dims = vec![p, m];
        dims.extend_from_slice(x.shape());
        // SAFETY: every element is written below before the array is returned.
        let result = unsafe { PyArrayDyn::<Complex64>::new(py, dims, false) };
        {
            let xr = x.readonly();
            let mut rw = result.readwrite();
            let xs = xr.as_slice()?;
            let os = rw.as_slice_mut()?;
            let sys = &*self.system;
            let n = xs.len();
            let fill = |os: &mut [Complex64]| {
                for (k, &w) in xs.iter().enumerate() {
                    let h = sys.response(w);
                    for i in 0..p {
                        for j in 0..m {
                            os[(i * m + j) * n + k] = h[(i, j)];
                        }
                    }
                }
            };
            // one response per point costs about a microsecond: release the GIL from 128 points on
            detached_if(py, n, crate::spectrum::DETACH_MIN_POINTS / 16, || {
                fill(os);
                Ok(())
            })?;
        }
        Ok(result.into_any())
    }

    /// The system whose single output is output ``output`` passed through the ISO 2631-1 / ISO 8041
    /// frequency weighting ``weighting`` ("Wk", "Wd", ...): W(iω)·H_output(iω), a state-space system with
    /// the same inputs (and input layout), whose output ``<output>_<W>`` has the weighted r.m.s. a_w as its
    /// σ under a stationary input — ``stochvib.analyze(system.weighted("seat_acc", "Wk"), road, speed=…)``.
    ///
    /// Parameters
    /// ----------
    /// output : str
    ///     The name of an acceleration output (m/s²).
    /// weighting : str
    ///     "Wk", "Wd", "Wc", "We", "Wj", "Wb" or "Wf" (case and an underscore ignored).
    ///
    /// Returns
    /// -------
    /// System
    ///     One output, ``<output>_<weighting>``, in m/s².
    ///
    /// Raises
    /// ------
    /// InvalidInputError
    ///     An unknown output or weighting, an output that is not an acceleration.
    /// NotApplicableError
    ///     A system without a finite state-space form.
    ///
    /// Examples
    /// --------
    /// >>> import numpy as np, stochvib
    /// >>> seat = stochvib.System.mdof(mass=[[80.0]], damping=[[1e3]], stiffness=[[5e4]],
    /// ...     base_stiffness=[[5e4]], base_damping=[[1e3]], outputs={"acc": ("acceleration", [1])})
    /// >>> w = seat.weighted("acc", "Wk")
    /// >>> w.outputs
    /// [('acc_Wk', 'm/s^2')]
    /// >>> h, hw = seat.frequency_response(f=4.0)[0, 0], w.frequency_response(f=4.0)[0, 0]
    /// >>> bool(np.isclose(hw, stochvib.comfort.weighting("Wk", f=4.0) * h, rtol=1e-9))
    /// True
    fn weighted(&self, py: Python<'_>, output: &str, weighting: &str) -> PyResult<Self> {
        let w = call(py, || stochvib::comfort::Weighting::parse(weighting))?;
        let i = call(py, || self.system.output_index(output))?;
        let Some(ss) = self.system.state_space() else {
            return Err(not_applicable(
                py,
                format!(
                    "weighting an output needs a finite state-space form; this {} has none",
                    self.kind
                ),
            ));
        };
        let ws = call(py, || stochvib::comfort::weighted_output(ss, i, &w))?;
        Ok(PySystem {
            system: Arc::new(ws),
            layout: self.layout.clone(),
            description: format!("{} (output {output} weighted by {})", self.description, w.name()),
            kind: self.kind.clone(),
            mass_stiffness: None,
        })
    }

    /// Undamped natural frequencies (rad/s, ascending) and mass-normalised mode shapes (columns) of
    /// C φ = ω² M φ, for systems built with :meth:`mdof`. Rigid-body modes have ω = 0. Other systems raise
    /// :class:`NotApplicableError` (use :meth:`natural_frequencies`).
    ///
    /// Returns
    /// -------
    /// (numpy.ndarray, numpy.ndarray)
    ///     ω in rad/s (n,) and the mode shapes (n × n).
    ///
    /// Raises
    /// ------
    /// NotApplicableError
    ///     A system not built with :meth:`mdof`.
    fn modes<'py>(&self, py: Python<'py>) -> PyResult<(Bound<'py, PyArray1<f64>>, Bound<'py, PyAny>)> {
        let Some((m, c)) = &self.mass_stiffness else {
            return Err(not_applicable(
                py,
                format!(
                    "modes need the mass and stiffness matrices, which the library exposes only for systems \
                     built with System.mdof; this is a {} system (use natural_frequencies())",
                    self.kind
                ),
            ));
        };
        let (w, shapes) = call(py, || modal_analysis(m, c))?;
        Ok((PyArray1::from_vec(py, w), matrix_to_py(py, &shapes)?))
    }

    /// |λ| of the poles (rad/s, ascending, repeated values once): the natural frequencies of the damped
    /// system, for any system with a state-space form.
    ///
    /// Returns
    /// -------
    /// numpy.ndarray of float64
    ///     rad/s, ascending.
    fn natural_frequencies<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        PyArray1::from_vec(py, self.system.natural_frequencies())
    }

    /// H(0) (outputs × inputs, real), or None when it is infinite (a rigid-body mode, an integrator).
    ///
    /// Returns
    /// -------
    /// numpy.ndarray of float64 or None
    ///     In output unit per input unit.
    fn static_gain<'py>(&self, py: Python<'py>) -> PyResult<Option<Bound<'py, PyAny>>> {
        self.system.static_gain().map(|g| matrix_to_py(py, &g)).transpose()
    }

    /// The exact state-space form as a dict of arrays "A", "B", "C", "D", "E" (y = Cx + Du + Eu̇), or None
    /// when the system is not finite-dimensional.
    ///
    /// Returns
    /// -------
    /// dict of str to numpy.ndarray, or None
    fn state_space_matrices<'py>(&self, py: Python<'py>) -> PyResult<Option<Bound<'py, PyDict>>> {
        let Some(ss) = self.system.state_space() else {
            return Ok(None);
        };
        let d = PyDict::new(py);
        for (k, mat) in [("A", &ss.a), ("B", &ss.b), ("C", &ss.c), ("D", &ss.d), ("E", &ss.e)] {
            d.set_item(k, matrix_to_py(py, mat)?)?;
        }
        Ok(Some(d))
    }

    /// The outputs as a list of (name, unit) pairs, in row order of H.
    #[getter]
    fn outputs<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyList>> {
        PyList::new(
            py,
            self.system.outputs().iter().map(|o| (o.name.clone(), o.unit.clone())),
        )
    }

    /// Number of inputs (columns of H).
    #[getter]
    fn n_inputs(&self) -> usize {
        self.system.n_inputs()
    }

    /// The model kind ("mdof", "state-space", "transfer-function" or a catalogue kind).
    #[getter]
    fn kind(&self) -> &str {
        &self.kind
    }

    /// One line: model, parameters, source section.
    #[getter]
    fn description(&self) -> &str {
        &self.description
    }

    /// Index (row of H) of the output called ``name``; raises :class:`InvalidInputError` listing the
    /// outputs there are.
    ///
    /// Parameters
    /// ----------
    /// name : str
    ///     An output name (see :attr:`outputs`).
    ///
    /// Returns
    /// -------
    /// int
    ///     The row of :meth:`frequency_response` and of ``C``, from 0.
    ///
    /// Raises
    /// ------
    /// InvalidInputError
    ///     An unknown name (the message lists the outputs).
    ///
    /// Examples
    /// --------
    /// >>> import stochvib
    /// >>> stochvib.System.state_space([[-2.0]], [[1.0]], [[1.0], [2.0]], outputs=["a", "b"]).output_index("b")
    /// 1
    fn output_index(&self, py: Python<'_>, name: &str) -> PyResult<usize> {
        call(py, || self.system.output_index(name))
    }

    fn __repr__(&self) -> String {
        let outs: Vec<&str> = self.system.outputs().iter().map(|o| o.name.as_str()).collect();
        format!(
            "<stochvib.System {}: {} inputs, outputs [{}]>",
            self.description,
            self.system.n_inputs(),
            outs.join(", ")
        )
    }
}

/// An error of a catalogue model built from keyword arguments: the library names the key of the
/// `[model]` table of a pseudo-file "System.model"; here it names the keyword argument instead, as
/// `InvalidInputError`, or `UnitError` when the argument was a string whose unit is unknown or of the wrong
/// dimension.
fn model_param_error(py: Python<'_>, e: Error, params: &toml::Table) -> PyErr {
    let (file, key, value, reason) = match e {
        Error::File {
            file,
            key,
            value,
            reason,
        } => (file, key, value, reason),
        other => return crate::errors::lib_error(py, &other),
    };
    if file != Path::new("System.model") {
        return crate::errors::lib_error(
            py,
            &Error::File {
                file,
                key,
                value,
                reason,
            },
        );
    }
    let name = key.strip_prefix("model.").unwrap_or(&key).to_string();
    if let Some(toml::Value::String(text)) = params.get(&name) {
        let bad_unit = stochvib::units::parse_quantity(text).is_err() || reason.contains("dimension is");
        if bad_unit {
            return crate::errors::unit_error(py, &name, text, &reason);
        }
    }
    crate::errors::lib_error(py, &Error::InvalidParameter { name, value, reason })
}
