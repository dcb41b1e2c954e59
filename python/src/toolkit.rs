//! The rest of the toolkit on numpy arrays: frequency weightings of ISO 2631-1 / ISO 8041 as arrays and
//! filters, the exposure of a measured acceleration record (`exposure(a, fs)`), rainflow counting of an
//! array, and spectral fatigue from a one-sided density given as arrays. Each function is one library call
//! over the whole array (no per-element Python work).

use crate::arrays::{angular, polynomial_to_py, real_array, vector};
use crate::convert::to_python;
use crate::errors::{call, detached_if, invalid_input};
use numpy::{Complex64, PyArray1, PyArrayDyn, PyArrayMethods, PyUntypedArrayMethods};
use pyo3::prelude::*;
use pyo3::types::PyDict;
use std::path::PathBuf;
use stochvib::comfort::Weighting;
use stochvib::fatigue::{compare_methods, rainflow as lib_rainflow, SnCurve, SpectralMoments};
use stochvib::record::{
    evaluate_exposure, AxisAssignment, Channel, ExposureOptions, RecordInfo, RecordReader, TimeBase,
};
use stochvib::report::record_report::ExposureReport;
use stochvib::units::Dim;

/// The response W(iω) of the frequency weighting ``name`` (ISO 2631-1 / ISO 8041: "Wk", "Wd", "Wc", "We",
/// "Wj", "Wb", "Wf"; band limiting included) at ``omega`` (rad/s) or ``f`` (Hz), complex, shaped as the
/// argument.
#[pyfunction]
#[pyo3(signature = (name, omega=None, *, f=None))]
pub fn weighting_response<'py>(
    py: Python<'py>,
    name: &str,
    omega: Option<&Bound<'py, PyAny>>,
    f: Option<&Bound<'py, PyAny>>,
) -> PyResult<Bound<'py, PyArrayDyn<Complex64>>> {
    let w = call(py, || Weighting::parse(name))?;
    let x = angular(py, omega, f)?;
    // SAFETY: every element is written below before the array is returned.
    let out = unsafe { PyArrayDyn::<Complex64>::new(py, x.shape().to_vec(), false) };
    {
        let xr = x.readonly();
        let mut o = out.readwrite();
        let (xs, os) = (xr.as_slice()?, o.as_slice_mut()?);
        detached_if(py, xs.len(), crate::spectrum::DETACH_MIN_POINTS, || {
            for (y, &w_) in os.iter_mut().zip(xs) {
                *y = w.response(w_);
            }
            Ok(())
        })?;
    }
    Ok(out)
}

/// The weighting ``name`` as a rational filter (b, a) in powers of s, DESCENDING unless
/// ``order="ascending"``: ``scipy.signal.freqs(b, a, omega)`` is :func:`weighting_response`.
#[pyfunction]
#[pyo3(signature = (name, *, order="descending"))]
pub fn weighting_filter<'py>(py: Python<'py>, name: &str, order: &str) -> PyResult<crate::spectrum::Coefficients<'py>> {
    let desc = crate::arrays::descending(py, order)?;
    let w = call(py, || Weighting::parse(name))?;
    let (num, den) = w.polynomials();
    Ok((polynomial_to_py(py, &num, desc), polynomial_to_py(py, &den, desc)))
}

/// Rainflow cycles of a 1-D array (ASTM E1049 four-point counting, residue as half cycles): a dict of
/// arrays ``range``, ``amplitude``, ``mean``, ``count`` (1 or 0.5), ``start``, ``end`` (sample indices).
#[pyfunction]
pub fn rainflow<'py>(py: Python<'py>, x: &Bound<'py, PyAny>) -> PyResult<Bound<'py, PyDict>> {
    let x = real_array(py, x, "x")?;
    if x.ndim() != 1 {
        return Err(invalid_input(py, format!("`x` must be 1-D, got shape {:?}", x.shape())));
    }
    let xr = x.readonly();
    let xs = xr.as_slice()?;
    let cycles = detached_if(py, xs.len(), crate::spectrum::DETACH_MIN_POINTS, || {
        Ok(lib_rainflow(xs)?)
    })?;
    let d = PyDict::new(py);
    let col = |f: fn(&stochvib::fatigue::Cycle) -> f64| PyArray1::from_iter(py, cycles.iter().map(f));
    d.set_item("range", col(|c| c.range))?;
    d.set_item("amplitude", col(|c| c.amplitude))?;
    d.set_item("mean", col(|c| c.mean))?;
    d.set_item("count", col(|c| c.count))?;
    d.set_item("start", PyArray1::from_iter(py, cycles.iter().map(|c| c.start as i64)))?;
    d.set_item("end", PyArray1::from_iter(py, cycles.iter().map(|c| c.end as i64)))?;
    Ok(d)
}

/// The S–N curve N·S_a^k = C as the numbers (k, C) in the stress unit ``unit``, validated (k > 0, C > 0,
/// finite): ``k`` a number or dimensionless string, ``c`` a number (in unit^k) or a string with a unit when
/// k is an integer ("1e12 MPa^3"), converted as by :func:`spectral_fatigue`.
#[pyfunction]
#[pyo3(signature = (*, k, c, unit="Pa"))]
pub fn sn_curve(py: Python<'_>, k: &Bound<'_, PyAny>, c: &Bound<'_, PyAny>, unit: &str) -> PyResult<(f64, f64)> {
    let k = crate::quantity::of_dim(py, k, "k", stochvib::units::Dim::DIMENSIONLESS)?;
    let c = crate::quantity::in_unit_power(py, c, "c", unit, k)?;
    let sn = call(py, || {
        SnCurve {
            k,
            c,
            endurance_limit: None,
        }
        .build()
    })?;
    Ok((sn.k, sn.c))
}

/// Expected fatigue damage rate and life by every spectral method (narrow band, Wirsching–Light, Dirlik,
/// Zhao–Baker, Tovo–Benasciutti, ...) of a stress process given by its one-sided density ``G`` (unit²/Hz)
/// at ``f`` (Hz, increasing, trapezoidal moments), with the S–N curve N·S_a^k = C (amplitudes) and an
/// optional endurance limit (amplitude). ``unit`` is the stress unit of the arrays ("Pa", "MPa"): ``c`` (in
/// unit^k) and ``endurance_limit`` (in unit) given as strings with a unit are converted into it. A list of
/// dicts ``method``, ``name``, ``damage_rate`` (1/s), ``life`` (s).
#[pyfunction]
#[pyo3(signature = (f, G, *, k, c, endurance_limit=None, unit="Pa"))]
#[allow(non_snake_case)]
pub fn spectral_fatigue<'py>(
    py: Python<'py>,
    f: &Bound<'py, PyAny>,
    G: &Bound<'py, PyAny>,
    k: &Bound<'py, PyAny>,
    c: &Bound<'py, PyAny>,
    endurance_limit: Option<&Bound<'py, PyAny>>,
    unit: &str,
) -> PyResult<Bound<'py, PyAny>> {
    let (fs, gs) = (vector(py, f, "f")?, vector(py, G, "G")?);
    let k = crate::quantity::of_dim(py, k, "k", stochvib::units::Dim::DIMENSIONLESS)?;
    let c = crate::quantity::in_unit_power(py, c, "c", unit, k)?;
    let endurance_limit = endurance_limit
        .filter(|e| !e.is_none())
        .map(|e| crate::quantity::in_unit_power(py, e, "endurance_limit", unit, 1.0))
        .transpose()?;
    let sn = call(py, || SnCurve { k, c, endurance_limit }.build())?;
    let cmp = call(py, || {
        let m = SpectralMoments::from_tabulated_one_sided_hz(&fs, &gs, true)?;
        compare_methods(&m, &sn)
    })?;
    // a damage of 0 is an unlimited life (an answer); one that is not a number is not (S^k overflowed)
    if let Some(e) = cmp.estimates.iter().find(|e| !e.damage_rate.is_finite()) {
        return Err(invalid_input(
            py,
            format!(
                "the {} damage rate is not a finite number ({}): S_a^k with k = {k} leaves the range of f64 for \
                 this density; check k, c and the unit of G",
                e.name, e.damage_rate
            ),
        ));
    }
    let rows: Vec<serde_json::Value> = cmp
        .estimates
        .iter()
        .map(|e| {
            serde_json::json!({
                "method": format!("{:?}", e.kind),
                "name": e.name,
                "damage_rate": e.damage_rate,
                "life": e.life,
            })
        })
        .collect();
    to_python(py, &rows)
}

/// Channels held in memory, read block by block as a record file would be.
struct ArrayRecord {
    info: RecordInfo,
    data: Vec<Vec<f64>>,
    at: usize,
}

impl RecordReader for ArrayRecord {
    fn info(&self) -> &RecordInfo {
        &self.info
    }

    fn read_block(&mut self, out: &mut [Vec<f64>], max: usize) -> stochvib::Result<usize> {
        let n = self.data.first().map_or(0, Vec::len);
        let end = (self.at + max).min(n);
        for (o, d) in out.iter_mut().zip(&self.data) {
            o.clear();
            o.extend_from_slice(&d[self.at..end]);
        }
        let read = end - self.at;
        self.at = end;
        Ok(read)
    }
}

/// The ISO 2631-1 evaluation of acceleration records held in arrays (the `stochvib exposure` command):
/// ``channels`` name → 1-D array in m/s² (rad/s² for rotations), all of one length, sampled at ``fs`` Hz
/// (or a sample-rate string: "200 Hz", "200 1/s", "200 S/s").
/// ``axes``: "CHANNEL=LOCATION:AXIS" strings (default: channels x, y, z on the seat surface);
/// ``exposure_s``: the daily exposure (default the record's duration); ``motion_sickness``: channels for
/// Wf. Returns (data, text): the report's data (as ``--json``) and its text.
#[pyfunction]
#[pyo3(signature = (channels, fs, *, axes=None, exposure_s=None, motion_sickness=None))]
pub fn exposure<'py>(
    py: Python<'py>,
    channels: &Bound<'py, PyDict>,
    fs: &Bound<'py, PyAny>,
    axes: Option<Vec<String>>,
    exposure_s: Option<&Bound<'py, PyAny>>,
    motion_sickness: Option<Vec<String>>,
) -> PyResult<(Bound<'py, PyAny>, String)> {
    let fs = crate::quantity::sample_rate(py, fs, "fs")?;
    let exposure_s = crate::quantity::optional(py, exposure_s, "exposure", "s")?;
    let mut names = Vec::new();
    let mut data = Vec::new();
    for (k, v) in channels.iter() {
        let name: String = k
            .extract()
            .map_err(|_| invalid_input(py, "channel names must be strings"))?;
        data.push(vector(py, &v, &format!("channels[{name:?}]"))?);
        names.push(name);
    }
    if let Some(i) = data.iter().position(|d| d.len() != data[0].len()) {
        return Err(invalid_input(
            py,
            format!(
                "channel `{}` has {} samples, `{}` has {}: every channel needs the same length",
                names[i],
                data[i].len(),
                names[0],
                data[0].len()
            ),
        ));
    }
    let samples = data.first().map(Vec::len);
    let info = RecordInfo {
        source: PathBuf::from("<array>"),
        format: "array",
        sample_rate_hz: fs,
        time_base: TimeBase::Stated,
        channels: names
            .iter()
            .map(|n| Channel {
                name: n.clone(),
                unit: "m/s^2".into(),
                to_si: 1.0,
                dim: Dim::ACCELERATION,
            })
            .collect(),
        samples_hint: samples,
    };
    let axes = axes
        .unwrap_or_default()
        .iter()
        .map(|a| call(py, || AxisAssignment::parse(a)))
        .collect::<PyResult<Vec<_>>>()?;
    let opts = ExposureOptions {
        axes,
        motion_sickness: motion_sickness.unwrap_or_default(),
        exposure_s,
        ..ExposureOptions::default()
    };
    let mut rec = ArrayRecord { info, data, at: 0 };
    let work = samples.unwrap_or(0) * names.len();
    let e = detached_if(py, work, 0, || {
        stochvib::error::require_positive("fs", fs)?;
        // the library names the command line's flags; here they are the keyword arguments
        let named = |e: stochvib::Error| e.renamed("--exposure", "exposure").renamed("--axis", "axes");
        Ok(evaluate_exposure(&mut rec, &opts).map_err(named)?)
    })?;
    let report = ExposureReport(e);
    Ok((to_python(py, &report)?, report.to_string()))
}

/// Welch's density estimate of a 1-D record with χ² intervals, in scipy.signal.welch's convention: the
/// one-sided G(f) in unit²/Hz at f = j·fs/nperseg (Hann window, 50 % overlap, density scaling; at f = 0 and
/// Nyquist not doubled). ``detrend``: remove each segment's mean (scipy's default "constant") or not.
/// A dict of arrays ``f``, ``G``, ``lower``, ``upper`` (the ``confidence`` interval of G at each f) and the
/// numbers ``segments``, ``dof`` (Welch's equivalent degrees of freedom).
#[pyfunction]
#[pyo3(signature = (x, fs, *, nperseg=256, detrend=true, confidence=0.95))]
pub fn welch<'py>(
    py: Python<'py>,
    x: &Bound<'py, PyAny>,
    fs: &Bound<'py, PyAny>,
    nperseg: usize,
    detrend: bool,
    confidence: f64,
) -> PyResult<Bound<'py, PyDict>> {
    let fs = crate::quantity::sample_rate(py, fs, "fs")?;
    let xs = vector(py, x, "x")?;
    let n = xs.len();
    let (est, lo, hi) = detached_if(py, n, crate::spectrum::DETACH_MIN_POINTS, || {
        stochvib::error::require_positive("fs", fs)?;
        // the library names its parameters; here they are the keyword arguments
        let named = |e: stochvib::Error| e.renamed("segment length", "nperseg").renamed("record length", "x");
        let mut w = stochvib::estimate::Welch::new(nperseg, 1.0 / fs).map_err(named)?;
        if detrend {
            w = w.with_segment_mean_removed();
        }
        let est = w.estimate(&xs).map_err(named)?;
        let (lo, hi) = est.intervals(confidence)?;
        Ok((est, lo, hi))
    })?;
    let (f, g) = est.one_sided_cyclic();
    // the interval of S scaled as G is (4π inside, 2π at the end bins)
    let scale = |v: Vec<f64>| -> Vec<f64> {
        v.iter()
            .zip(&est.density)
            .zip(&g)
            .map(|((b, s), gg)| if *s > 0.0 { b * gg / s } else { 0.0 })
            .collect()
    };
    let d = PyDict::new(py);
    d.set_item("f", PyArray1::from_vec(py, f))?;
    d.set_item("lower", PyArray1::from_vec(py, scale(lo)))?;
    d.set_item("upper", PyArray1::from_vec(py, scale(hi)))?;
    d.set_item("G", PyArray1::from_vec(py, g))?;
    d.set_item("segments", est.segments)?;
    d.set_item("dof", est.dof)?;
    Ok(d)
}

/// The International Roughness Index (ASTM E1926: golden car at 80 km/h, 250 mm moving average) of one
/// track's elevations ``z`` (m) sampled every ``step`` m: a dict ``m_per_km``, ``moving_average_samples``,
/// ``moving_average_base_m``, ``steps``, ``length_m``.
#[pyfunction]
pub fn iri<'py>(py: Python<'py>, z: &Bound<'py, PyAny>, step: &Bound<'py, PyAny>) -> PyResult<Bound<'py, PyDict>> {
    let step = crate::quantity::quantity(py, step, "step", "m")?;
    let zs = vector(py, z, "z")?;
    let r = detached_if(py, zs.len(), crate::spectrum::DETACH_MIN_POINTS, || {
        Ok(stochvib::road::iri(&zs, step)?)
    })?;
    let d = PyDict::new(py);
    d.set_item("m_per_km", r.m_per_km)?;
    d.set_item("moving_average_samples", r.moving_average_samples)?;
    d.set_item("moving_average_base_m", r.moving_average_base_m)?;
    d.set_item("steps", r.steps)?;
    d.set_item("length_m", r.length_m)?;
    Ok(d)
}

/// The expected IRI of a spatial road spectrum (the `stochvib iri` expectation): a dict ``m_per_km``,
/// ``without_moving_average_m_per_km``, ``sigma_relative_velocity_m_s``, ``band_cycles_per_m``.
#[pyfunction]
pub fn expected_iri<'py>(
    py: Python<'py>,
    spectrum: &Bound<'py, crate::spectrum::PySpectrum>,
) -> PyResult<Bound<'py, PyAny>> {
    let s = spectrum.get().spectrum.clone();
    let e = crate::errors::detached(py, || Ok(stochvib::road::expected_iri(&*s)?))?;
    to_python(py, &e)
}

/// The ISO 8608 class ("A" … "H") of a road whose G_d(n₀ = 0.1 cycles/m) is ``g0`` m³ (class limits at the
/// geometric means between the classes' values; a limit belongs to the rougher class).
#[pyfunction]
pub fn iso8608_class(py: Python<'_>, g0: &Bound<'_, PyAny>) -> PyResult<String> {
    let g0 = crate::quantity::quantity(py, g0, "g0", "m^3")?;
    Ok(call(py, || stochvib::road::iso8608_class(g0))?.to_string())
}

/// The Directive 2002/44/EC daily exposure A(8) = a_w·√(T/8 h) (m/s²) of a weighted r.m.s. ``a_w`` (m/s²,
/// already multiplied by the axis factor k) over ``duration`` (s, or with a unit "4 h").
#[pyfunction]
pub fn daily_exposure_a8(py: Python<'_>, a_w: &Bound<'_, PyAny>, duration: &Bound<'_, PyAny>) -> PyResult<f64> {
    let a_w = crate::quantity::quantity(py, a_w, "a_w", "m/s^2")?;
    let t = crate::quantity::quantity(py, duration, "duration", "s")?;
    call(py, || stochvib::comfort::daily_exposure_a8(a_w, t))
}

/// The vibration dose value (m/s^1.75) of a stationary Gaussian weighted acceleration of r.m.s. ``a_w``
/// over ``duration``: VDV = (3 T)^(1/4) a_w (the fourth-power mean of a Gaussian process).
#[pyfunction]
pub fn vdv_gaussian(py: Python<'_>, a_w: &Bound<'_, PyAny>, duration: &Bound<'_, PyAny>) -> PyResult<f64> {
    let a_w = crate::quantity::quantity(py, a_w, "a_w", "m/s^2")?;
    let t = crate::quantity::quantity(py, duration, "duration", "s")?;
    call(py, || stochvib::comfort::vdv_gaussian(a_w, t))
}

/// The `stochvib road` analysis of tracks given as arrays: ``tracks`` a list of (name, elevations in m),
/// equally spaced by ``step``; the report's data as a dict (its ``--json``), the profile named ``<arrays>``.
#[pyfunction]
#[pyo3(signature = (tracks, step, *, segment=None, detrend="linear", confidence=0.95))]
pub fn road_profile<'py>(
    py: Python<'py>,
    tracks: Vec<(String, Bound<'py, PyAny>)>,
    step: &Bound<'py, PyAny>,
    segment: Option<usize>,
    detrend: &str,
    confidence: f64,
) -> PyResult<Bound<'py, PyAny>> {
    use stochvib::road::{Profile, Track};
    use stochvib::study::road_profile::{profile_report, RoadReportOptions};
    let step = crate::quantity::quantity(py, step, "step", "m")?;
    let detrend = crate::names::detrend(py, detrend)?;
    if !(confidence > 0.0 && confidence < 1.0) {
        return Err(invalid_input(
            py,
            format!("confidence={confidence}: expected a number in (0, 1)"),
        ));
    }
    let tracks = tracks
        .into_iter()
        .map(|(name, z)| {
            Ok(Track {
                elevation_m: vector(py, &z, &name)?,
                name,
            })
        })
        .collect::<PyResult<Vec<_>>>()?;
    let work = tracks.iter().map(|t| t.elevation_m.len()).sum();
    let opts = RoadReportOptions {
        segment_len: segment,
        detrend,
        confidence,
    };
    let r = detached_if(py, work, crate::spectrum::DETACH_MIN_POINTS, || {
        let p = Profile::new(step, 0.0, tracks)?;
        Ok(profile_report(&p, std::path::Path::new("<arrays>"), &opts)?)
    })?;
    to_python(py, &r)
}

/// The coherence amplitude ρ(n) of two road tracks ``track_width`` apart under the coherence ``model`` (a
/// dict as a scenario road's ``coherence`` table: kinds "dodds-robson", "ammon-bormann", "tabulated",
/// "constant") at the spatial frequencies ``n`` (cycles/m), shaped as ``n``; γ² = ρ².
#[pyfunction]
#[pyo3(signature = (model, n, *, track_width))]
pub fn coherence_amplitude<'py>(
    py: Python<'py>,
    model: &Bound<'py, PyDict>,
    n: &Bound<'py, PyAny>,
    track_width: &Bound<'py, PyAny>,
) -> PyResult<Bound<'py, PyArrayDyn<f64>>> {
    use numpy::IntoPyArray;
    let width = crate::quantity::quantity(py, track_width, "track_width", "m")?;
    let text = toml::Value::Table(crate::convert::toml_table(py, "model", model)?).to_string();
    let c = call(py, || stochvib::scenario::coherence_from_toml(&text, width))?;
    let x = real_array(py, n, "n")?;
    let out = x.readonly().as_array().mapv(|v| c.coherence_amplitude(v));
    Ok(out.into_pyarray(py))
}
