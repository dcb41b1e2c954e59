"""Typed results: one class per kind of analysis, with attributes, ``to_dict()``, ``to_dataframe()``.

* :class:`AnalysisResult` — the ``stochvib analyze`` report of a stochastic scenario: one
  :class:`OutputResult` per output, each with its :class:`VarianceMethod` entries and
  :class:`LevelCrossing` rates;
* :class:`TablesResult` — the result tables of a deterministic model or a reference table of the sources;
* :class:`RunResult` — a finished Monte Carlo run (the HDF5 file and its statistics);
* :class:`ExposureResult` — the ISO 2631-1 evaluation of acceleration records (:func:`stochvib.exposure`);
* :class:`SweepResult` — a parameter study, with its Monte Carlo batches (:meth:`Scenario.sweep`);
* :class:`NonlinearResult`, :class:`NonlinearRunResult` — routes 1 to 3 of a model with nonlinear elements;
* :class:`OptimizeResult` — an optimum under constraints (:meth:`Scenario.optimize`);
* :class:`TransientResult` — σ(t) and the mission extremes of a transient (:meth:`Scenario.transient`).

``repr()`` reads like the command-line tool's table, ``str()`` is the tool's full text, ``to_dict()`` the
``--json`` data (plain dicts, lists, floats, strings and None), ``to_dataframe()`` a pandas DataFrame (one
row per output; pandas is an optional dependency). Fields a later library version adds are kept in
``to_dict()`` and readable as attributes.

Examples
--------
>>> import stochvib
>>> r = stochvib.analyze("data/conveyor-idler.toml")
>>> type(r["y"]).__name__, r["y"].unit
('OutputResult', 'm')
>>> r["y"].method("lyapunov").status
'value'
"""

from __future__ import annotations

import copy
import math
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, Dict, Iterator, List, Optional, Sequence, Tuple

__all__ = [
    "AnalysisResult",
    "OutputResult",
    "VarianceMethod",
    "LevelCrossing",
    "TablesResult",
    "RunResult",
    "Report",
    "ExposureResult",
    "AxisExposure",
    "SweepResult",
    "NonlinearResult",
    "NonlinearOutput",
    "NonlinearRunResult",
    "OptimizeResult",
    "OptimizedParam",
    "ConstraintState",
    "TransientResult",
    "TransientOutput",
]


def _e(x: Optional[float], digits: int = 6) -> str:
    """A number as the command-line tool prints it (Rust's ``{:.6e}``: ``1.865465e-2``); ``—`` for None."""
    if x is None:
        return "—"
    if not math.isfinite(x):
        return str(x)
    mant, exp = f"{x:.{digits}e}".split("e")
    return f"{mant}e{int(exp)}"


def _dataframe(rows: List[Dict[str, Any]]) -> Any:
    try:
        import pandas as pd
    except ImportError as e:  # pragma: no cover - depends on the environment
        raise ImportError("to_dataframe() needs pandas (pip install pandas); to_dict() has the same data") from e
    return pd.DataFrame(rows)


def _output(outputs: Any, name: str) -> Any:
    """``outputs[name]`` (a dict by name, or a list of names), else KeyError naming the outputs there are."""
    if name not in outputs:
        raise KeyError(f"no output {name!r}; the outputs are {list(outputs)}")
    return outputs[name] if isinstance(outputs, dict) else name


class _Mapping:
    """Read access by key as well as by attribute (``m["status"]`` is ``m.status``), for code written
    against the report's dict form."""

    def __getitem__(self, key: str) -> Any:
        try:
            return getattr(self, key)
        except AttributeError:
            raise KeyError(key) from None

    def get(self, key: str, default: Any = None) -> Any:
        return getattr(self, key, default)


@dataclass(frozen=True, repr=False)
class VarianceMethod(_Mapping):
    """One variance method of an output: ``method`` ("lyapunov", "integral-table", "quadrature",
    "lyapunov (delays)"), ``status`` ("value", "divergent", "not-converged", "not-applicable",
    "unreliable", "failed"), ``value`` (the variance in unit², None without one), ``error_estimate``,
    ``rel_diff`` (relative difference to the reference variance), ``reason`` (why there is no value), and
    for a quadrature that did not converge ``estimate`` (its best value)."""

    method: str
    status: str
    value: Optional[float] = None
    error_estimate: Optional[float] = None
    rel_diff: Optional[float] = None
    reason: Optional[str] = None
    estimate: Optional[float] = None

    @classmethod
    def _from(cls, m: Dict[str, Any]) -> "VarianceMethod":
        o = dict(m.get("outcome") or {})
        return cls(
            method=m.get("method", ""),
            status=o.get("status", ""),
            value=o.get("value"),
            error_estimate=o.get("error_estimate"),
            rel_diff=m.get("rel_diff"),
            reason=o.get("reason"),
            estimate=o.get("estimate"),
        )

    def __repr__(self) -> str:
        note = "" if self.reason is None else f"  {self.reason}"
        return f"{self.method:<20} {_e(self.value):>12} {_e(self.error_estimate, 1):>11} {_e(self.rel_diff, 1):>11}{note}"


@dataclass(frozen=True, repr=False)
class LevelCrossing(_Mapping):
    """Rice's up-crossing rate of ``level`` (the output's unit), per second (per metre along a road), and the
    Poisson probability of at least one exceedance in the analysis duration."""

    level: float
    upcrossing_rate: float
    exceedance_probability: float

    def __repr__(self) -> str:
        return (
            f"level {_e(self.level)}: up-crossing rate {_e(self.upcrossing_rate)}, "
            f"P(exceed) {_e(self.exceedance_probability)}"
        )


@dataclass(frozen=True, repr=False)
class OutputResult:
    """The statistics of one output, in the output's SI unit ``unit`` (rates per second, per metre for a
    system driven along a road).

    Attributes
    ----------
    name, unit : str
    mean : float
        M_y = H(0) M_u.
    variance, sigma : float or None
        The reference variance (Lyapunov, else integral table, else quadrature) and σ; None when infinite
        or undefined (``variance_note`` says why).
    three_sigma : (float, float) or None
        (M_y − 3σ, M_y + 3σ).
    zero_upcrossing_rate, bandwidth : float or None
        Rice's ν₀⁺ = (1/2π)√(λ₂/λ₀) and the bandwidth ε.
    lambda2, lambda4 : float or None
        Spectral moments ∫ω^k S_y dω.
    band_sigma, band_note
        σ in the analysis band, or why there is none.
    expected_largest_peak : float or None
        In the analysis duration.
    levels : list of LevelCrossing
    methods : list of VarianceMethod
    variance_outcome : dict
        The library's outcome of the reference variance (``status``, ``value``, ``reason``).
    monte_carlo : dict or None
        The Monte Carlo column, when asked for.
    """

    name: str
    unit: str
    mean: Optional[float]
    variance: Optional[float]
    sigma: Optional[float]
    three_sigma: Optional[Tuple[float, float]]
    zero_upcrossing_rate: Optional[float]
    bandwidth: Optional[float]
    lambda2: Optional[float]
    lambda4: Optional[float]
    band_sigma: Optional[float]
    band_note: Optional[str]
    expected_largest_peak: Optional[float]
    levels: List[LevelCrossing]
    methods: List[VarianceMethod]
    variance_outcome: Dict[str, Any]
    variance_note: Optional[str]
    monte_carlo: Optional[Dict[str, Any]]
    _raw: Dict[str, Any] = field(compare=False)

    @classmethod
    def _from(cls, data: Dict[str, Any]) -> "OutputResult":
        st = data.get("statistics", {})
        outcome = st.get("variance_outcome") or {}
        lo, hi = data.get("lower_3sigma"), data.get("upper_3sigma")
        return cls(
            name=st.get("name", ""),
            unit=st.get("unit", ""),
            mean=st.get("mean"),
            variance=st.get("variance"),
            sigma=st.get("sigma"),
            three_sigma=None if lo is None or hi is None else (lo, hi),
            zero_upcrossing_rate=st.get("zero_upcrossing_rate"),
            bandwidth=st.get("bandwidth"),
            lambda2=st.get("lambda2"),
            lambda4=st.get("lambda4"),
            band_sigma=data.get("band_sigma"),
            band_note=data.get("band_note"),
            expected_largest_peak=data.get("expected_largest_peak"),
            levels=[LevelCrossing(**l) for l in data.get("levels", [])],
            methods=[VarianceMethod._from(m) for m in st.get("methods", [])],
            variance_outcome=dict(outcome),
            variance_note=None if outcome.get("status", "value") == "value" else outcome.get("reason"),
            monte_carlo=data.get("monte_carlo"),
            _raw=data,
        )

    def __getattr__(self, name: str) -> Any:
        # fields a later library version adds: found in the statistics or the output's section
        raw = self.__dict__.get("_raw", {})
        for d in (raw.get("statistics", {}), raw):
            if name in d:
                return d[name]
        raise AttributeError(f"OutputResult has no attribute {name!r}")

    def method(self, name: str) -> VarianceMethod:
        """The variance method ``name`` ("lyapunov", "integral-table", "quadrature", "lyapunov (delays)")."""
        for m in self.methods:
            if m.method == name:
                return m
        raise KeyError(f"no variance method {name!r}; methods: {[m.method for m in self.methods]}")

    def to_dict(self) -> Dict[str, Any]:
        """The output's section of the report as the library serialises it (statistics nested)."""
        return copy.deepcopy(self._raw)

    def _row(self) -> Dict[str, Any]:
        lo, hi = self.three_sigma or (None, None)
        return {
            "output": self.name,
            "unit": self.unit,
            "mean": self.mean,
            "sigma": self.sigma,
            "variance": self.variance,
            "lower_3sigma": lo,
            "upper_3sigma": hi,
            "zero_upcrossing_rate": self.zero_upcrossing_rate,
            "bandwidth": self.bandwidth,
            "band_sigma": self.band_sigma,
            "expected_largest_peak": self.expected_largest_peak,
        }

    def __repr__(self) -> str:
        bounds = "—" if self.three_sigma is None else f"[{_e(self.three_sigma[0])}, {_e(self.three_sigma[1])}]"
        lines = [
            f"output {self.name} [{self.unit}]",
            f"  mean          {_e(self.mean)}",
            f"  sigma         {_e(self.sigma)}" + ("" if self.variance_note is None else f"  ({self.variance_note})"),
            f"  3σ bounds     {bounds}",
            f"  ν0+           {_e(self.zero_upcrossing_rate)}   bandwidth ε {_e(self.bandwidth)}",
            f"  {'variance method':<20} {'value':>12} {'error est.':>11} {'rel. diff':>11}  note",
        ]
        lines += [f"  {m!r}" for m in self.methods]
        return "\n".join(lines)


class _Text:
    """``str()`` is the command-line tool's text; ``to_dict()`` a deep copy of the data."""

    _data: Dict[str, Any]
    _text: str

    def __str__(self) -> str:
        return self._text

    def to_dict(self) -> Dict[str, Any]:
        """A deep copy of the data, as the command-line tool's ``--json`` prints it."""
        return copy.deepcopy(self._data)

    def __getattr__(self, name: str) -> Any:
        data = self.__dict__.get("_data", {})
        if name in data:
            return data[name]
        raise AttributeError(f"{type(self).__name__} has no attribute {name!r}")

    def __dir__(self) -> List[str]:
        return sorted(set(super().__dir__()) | set(self.__dict__.get("_data", {})))


class AnalysisResult(_Text):
    """The ``stochvib analyze`` report of a stochastic scenario.

    Attributes
    ----------
    title, scenario, model, input : str
        What was analysed (``scenario`` is the file, or "<python>").
    band_rad_s : (float, float) or None
        The band of ``band_sigma``, rad/s.
    duration_s : float
        The duration of exceedance probabilities and expected peaks.
    outputs : list of OutputResult

    ``result["travel"]`` or ``result.outputs[2]`` give an output; ``result.sigma`` is a dict name → σ.
    """

    def __init__(self, data: Dict[str, Any], text: str) -> None:
        self._data = data
        self._text = text
        self.outputs: List[OutputResult] = [OutputResult._from(o) for o in data.get("outputs", [])]
        self.title: str = data.get("title", "")
        self.scenario: str = data.get("scenario", "")
        self.model: str = data.get("model", "")
        self.input: str = data.get("input", "")
        band = data.get("band_rad_s")
        self.band_rad_s: Optional[Tuple[float, float]] = None if band is None else (band[0], band[1])
        self.duration_s: Optional[float] = data.get("duration_s")

    @property
    def output_names(self) -> List[str]:
        """The names of the reported outputs."""
        return [o.name for o in self.outputs]

    def __getitem__(self, key: Any) -> OutputResult:
        if isinstance(key, str):
            for o in self.outputs:
                if o.name == key:
                    return o
            raise KeyError(f"no output {key!r}; outputs: {self.output_names}")
        return self.outputs[key]

    def __iter__(self) -> Iterator[OutputResult]:
        return iter(self.outputs)

    def __len__(self) -> int:
        return len(self.outputs)

    @property
    def sigma(self) -> Dict[str, Optional[float]]:
        """σ of every output (None when infinite or undefined)."""
        return {o.name: o.sigma for o in self.outputs}

    @property
    def mean(self) -> Dict[str, Optional[float]]:
        """Mean of every output."""
        return {o.name: o.mean for o in self.outputs}

    @property
    def three_sigma(self) -> Dict[str, Optional[Tuple[float, float]]]:
        """3σ bounds of every output."""
        return {o.name: o.three_sigma for o in self.outputs}

    @property
    def zero_upcrossing_rate(self) -> Dict[str, Optional[float]]:
        """ν₀⁺ of every output, per second (per metre along a road)."""
        return {o.name: o.zero_upcrossing_rate for o in self.outputs}

    def to_dataframe(self) -> Any:
        """One row per output (output, unit, mean, sigma, variance, 3σ bounds, ν₀⁺, bandwidth, band σ,
        expected largest peak) as a pandas DataFrame. Raises ImportError without pandas."""
        return _dataframe([o._row() for o in self.outputs])

    def __repr__(self) -> str:
        head = f"{'output':<14} {'unit':<8} {'mean':>12} {'sigma':>12} {'ν0+':>12}  reference"
        rows = []
        for o in self.outputs:
            ref = o.variance_outcome.get("status", "")
            rows.append(
                f"{o.name:<14} {o.unit:<8} {_e(o.mean):>12} {_e(o.sigma):>12} {_e(o.zero_upcrossing_rate):>12}  {ref}"
            )
        return "\n".join([f"AnalysisResult: {self.title}  ({self.scenario})", head, *rows])


class TablesResult(_Text):
    """The result tables of a deterministic model (a hoist, a chain) or a reference table of the sources
    (the ``stochvib analyze`` report of such a file): ``title`` and ``tables`` (each with its columns and
    rows, as ``to_dict()`` shows); ``str()`` is the command-line tool's text."""

    def __init__(self, data: Dict[str, Any], text: str) -> None:
        self._data = data
        self._text = text

    def to_dataframe(self) -> Any:
        """The data as a pandas DataFrame (``pandas.json_normalize`` of ``to_dict()``)."""
        _dataframe([])
        import pandas as pd

        return pd.json_normalize(self.to_dict())

    def __repr__(self) -> str:
        return f"<stochvib.TablesResult {self._data.get('title', '')!r}>"


Report = TablesResult  # the name of the previous versions


class RunResult(_Text):
    """A finished Monte Carlo run: the HDF5 file ``path`` (readable by h5py) and its statistics.

    Attributes
    ----------
    path : pathlib.Path
        The finished run file.
    n_realizations : int
    route : str
        "exact" or "spectral".
    step : str
        Whether Δt and the duration were given or suggested (and why).
    statistics : dict
        output → statistic name ("mean", "variance", "sigma", "sigma_discrete") → dict with
        ``estimate``, ``lower``, ``upper``, ``confidence``, ``analytic``, ``covers``, ``unit``, ``method``.
    """

    def __init__(self, data: Dict[str, Any], text: str, step: str) -> None:
        self._data = data
        self._text = text
        self.step = step
        self.path = Path(data["path"])
        self.n_realizations: Optional[int] = data.get("n_realizations")
        self.route: Optional[str] = data.get("route")
        self.statistics = self._statistics()

    def _statistics(self) -> Dict[str, Dict[str, Dict[str, Any]]]:
        return _run_statistics(self._data.get("outputs", []))

    @property
    def sigma(self) -> Dict[str, float]:
        """Monte Carlo σ estimate of every simulated output."""
        return {k: v["sigma"]["estimate"] for k, v in self.statistics.items() if "sigma" in v}

    def to_dataframe(self) -> Any:
        """One row per (output, statistic): estimate, lower, upper, confidence, analytic, covers."""
        return _statistics_dataframe(self.statistics)

    def __repr__(self) -> str:
        head = f"RunResult: {self.path} ({self.n_realizations} realizations, route {self.route})"
        return "\n".join([head, *_sigma_rows(self.statistics)])


def _run_statistics(outputs: List[Dict[str, Any]]) -> Dict[str, Dict[str, Dict[str, Any]]]:
    """output → statistic name → its interval and fields, from a run's per-output statistics (``--json``)."""
    out: Dict[str, Dict[str, Dict[str, Any]]] = {}
    for o in outputs:
        stats = {}
        for s in o.get("statistics", []):
            entry = dict(s.get("interval", {}))
            entry.update({k: v for k, v in s.items() if k not in ("interval", "name")})
            stats[s["name"]] = entry
        out[o["output"]] = stats
    return out


def _statistics_dataframe(statistics: Dict[str, Dict[str, Dict[str, Any]]]) -> Any:
    rows = [
        {"output": o, "statistic": name, **{k: v for k, v in s.items() if not isinstance(v, (dict, list))}}
        for o, stats in statistics.items()
        for name, s in stats.items()
    ]
    return _dataframe(rows)


def _sigma_rows(statistics: Dict[str, Dict[str, Dict[str, Any]]]) -> List[str]:
    """The σ table of a run: estimate, interval, analytic σ and whether the interval covers it."""
    rows = [f"{'output':<14} {'sigma':>12} {'lower':>12} {'upper':>12} {'analytic':>12}  covers"]
    for o, stats in statistics.items():
        s = stats.get("sigma", {})
        rows.append(
            f"{o:<14} {_e(s.get('estimate')):>12} {_e(s.get('lower')):>12} {_e(s.get('upper')):>12} "
            f"{_e(s.get('analytic')):>12}  {s.get('covers')}"
        )
    return rows



class TransientRunResult(RunResult):
    """A merged transient Monte Carlo run (:func:`merge_transient`; ``to_dict()`` is ``stochvib merge OUT
    PARTS… --json`` of a transient run's parts).

    Attributes
    ----------
    path : pathlib.Path
        The merged run file.
    n_realizations : int
    statistics : dict
        As :attr:`RunResult.statistics`, at the last stored time.
    sigma_coverage : dict
        output → the fraction of stored times at which the σ interval covers the exact σ.
    verdicts : list of dict
        The verdicts on the maxima over the run (DKW band of half-width ``dkw_epsilon``).
    notes : list of str
    """

    def __init__(self, data: Dict[str, Any], text: str) -> None:
        super().__init__(data, text, "merged from the parts (their step)")
        self.sigma_coverage: Dict[str, float] = {k: v for k, v in data.get("sigma_coverage", [])}
        self.verdicts: List[Dict[str, Any]] = data.get("verdicts", [])
        self.dkw_epsilon: float = data["dkw_epsilon"]
        self.notes: List[str] = list(data.get("notes", []))

    def __repr__(self) -> str:
        head = f"TransientRunResult: {self.path} ({self.n_realizations} realizations)"
        rows = [f"{'output':<14} {'sigma(T)':>12} {'sigma coverage':>15}"]
        for o, stats in self.statistics.items():
            cov = self.sigma_coverage.get(o)
            rows.append(f"{o:<14} {_e(stats.get('sigma', {}).get('estimate')):>12} {_e(cov, 3):>15}")
        return "\n".join([head, *rows])


@dataclass(frozen=True, repr=False)
class AxisExposure:
    """One evaluated channel of an exposure evaluation (values of the weighted acceleration a_w(t)).

    Attributes
    ----------
    channel, location, axis, weighting : str
    a_w : float
        Weighted r.m.s. acceleration, m/s² (rad/s² for rotations).
    vdv : float
        Vibration dose value, m/s^1.75.
    msdv : float
        Motion sickness dose value, m/s^1.5.
    mtvv : float or None
        Maximum transient vibration value (τ = 1 s), None for a record shorter than one window.
    peak, crest_factor : float or None
    a8, daily_vdv : float or None
        The Directive's A(8) = k·a_w·√(T_exp/8 h) and daily VDV, for the axes it counts (else None).
    governing : str
        The metric that governs (ISO 2631-1 6.3.3).
    """

    channel: str
    location: str
    axis: str
    weighting: str
    a_w: float
    vdv: float
    msdv: float
    mtvv: Optional[float]
    peak: float
    crest_factor: Optional[float]
    a8: Optional[float]
    daily_vdv: Optional[float]
    governing: Optional[str]
    _raw: Dict[str, Any] = field(compare=False)

    @classmethod
    def _from(cls, d: Dict[str, Any]) -> "AxisExposure":
        m = d.get("metrics", {})
        h = d.get("health") or {}
        check = m.get("check", {})
        return cls(
            channel=d.get("channel", ""),
            location=str(d.get("location", "")),
            axis=str(d.get("axis", "")),
            weighting=str(d.get("weighting", "")),
            a_w=m.get("a_w"),
            vdv=m.get("vdv"),
            msdv=m.get("msdv"),
            mtvv=d.get("mtvv"),
            peak=m.get("peak"),
            crest_factor=check.get("crest_factor"),
            a8=h.get("a8"),
            daily_vdv=h.get("daily_vdv"),
            governing=None if check.get("governing") is None else str(check.get("governing")),
            _raw=d,
        )

    def to_dict(self) -> Dict[str, Any]:
        return copy.deepcopy(self._raw)

    def _row(self) -> Dict[str, Any]:
        return {k: getattr(self, k) for k in self.__dataclass_fields__ if not k.startswith("_")}

    def __repr__(self) -> str:
        return (
            f"{self.channel:<10} {self.location:<14} {self.axis:<3} {self.weighting:<3} a_w {_e(self.a_w)}  "
            f"VDV {_e(self.vdv)}  MTVV {_e(self.mtvv)}  A(8) {_e(self.a8)}"
        )


class ExposureResult(_Text):
    """The ISO 2631-1 evaluation of acceleration records (the ``stochvib exposure`` report).

    Attributes
    ----------
    duration_s, exposure_s : float
        The record's duration T and the daily exposure T_exp, s.
    axes : list of AxisExposure
        The health and comfort axes; ``motion_sickness`` the Wf channels.
    a8, vdv : float or None
        The verdict's A(8) (m/s²) and daily VDV (m/s^1.75) from the dominant axes.
    verdict : dict or None
        Directive 2002/44/EC limits and the ISO 2631-1 Annex B zones.
    """

    def __init__(self, data: Dict[str, Any], text: str) -> None:
        self._data = data
        self._text = text
        self.duration_s: float = data.get("duration_s")
        self.exposure_s: float = data.get("exposure_s")
        self.axes = [AxisExposure._from(a) for a in data.get("axes", [])]
        self.motion_sickness = [AxisExposure._from(a) for a in data.get("motion_sickness", [])]
        self.verdict: Optional[Dict[str, Any]] = data.get("verdict")
        v = self.verdict or {}
        self.a8: Optional[float] = v.get("a8")
        self.vdv: Optional[float] = v.get("vdv")

    def __getitem__(self, channel: str) -> AxisExposure:
        for a in self.axes + self.motion_sickness:
            if a.channel == channel:
                return a
        raise KeyError(f"no channel {channel!r}; channels: {[a.channel for a in self.axes + self.motion_sickness]}")

    def to_dataframe(self) -> Any:
        """One row per evaluated channel (pandas)."""
        return _dataframe([a._row() for a in self.axes + self.motion_sickness])

    def __repr__(self) -> str:
        head = f"ExposureResult: T = {_e(self.duration_s)} s, T_exp = {_e(self.exposure_s)} s, A(8) = {_e(self.a8)} m/s^2"
        return "\n".join([head, *[repr(a) for a in self.axes + self.motion_sickness]])


class SweepResult:
    """The exact statistics at every point of a parameter study (:meth:`Scenario.sweep`; the data of
    ``stochvib sweep SCENARIO --param … --json``).

    Attributes
    ----------
    params : dict
        key → the values swept (strings as given, with units), in order.
    mode : str
        "grid" (every combination; the first key varies slowest) or "zip" (the k-th values together).
    shape : tuple of int
        The study's shape: one axis per key for a grid, ``(n_points,)`` for zip.
    outputs : list of str
    rows : list of dict
        One per (point, output): ``point``, ``params``, ``output``, ``unit``, ``method``, ``mean``, ``sigma``,
        ``variance``, ``lower_3sigma``, ``upper_3sigma``, ``lambda2``, ``zero_upcrossing_rate``, ``error``
        (the reason a point failed, else None).
    points : range
        The points held: all of them, or those of one shard (``sweep(..., shard=(I, N))``).
    path : pathlib.Path or None
        The file written: the shard file of ``sweep(..., shard=...)``, the table of :func:`merge_sweep`.
    """

    def __init__(self, data: Dict[str, Any], path: Optional[Any] = None) -> None:
        self._data = data
        self.path: Optional[Path] = None if path is None else Path(path)
        ident = data["identity"]
        self.params: Dict[str, List[str]] = {k: list(v) for k, v in ident["params"]}
        self.mode: str = ident["mode"]
        self.outputs: List[str] = [o for o, _ in ident["outputs"]]
        self.n_points: int = data["n_points"]
        self.rows: List[Dict[str, Any]] = data["rows"]
        held = [r["point"] for r in self.rows]
        self.points: range = range(min(held), max(held) + 1) if held else range(self.n_points)
        grid = self.mode == "grid"
        self.shape: Tuple[int, ...] = tuple(len(v) for v in self.params.values()) if grid else (self.n_points,)

    def statistic(self, output: str, name: str = "sigma") -> Any:
        """The statistic ``name`` ("sigma", "mean", "variance", "zero_upcrossing_rate", …) of ``output`` at
        every point as a numpy array of :attr:`shape` (NaN where a point failed)."""
        import numpy as np

        _output(self.outputs, output)
        out = np.full(self.n_points, np.nan)
        for r in self.rows:
            if r["output"] == output and r.get(name) is not None:
                out[r["point"]] = r[name]
        return out.reshape(self.shape)

    def sigma(self, output: str) -> Any:
        """σ of ``output`` at every point, shaped as :attr:`shape`."""
        return self.statistic(output, "sigma")

    @property
    def monte_carlo_options(self) -> Optional[Dict[str, Any]]:
        """The batch of every point (``realizations``, ``duration_s``, ``dt_s``, ``seed``, ``shard_size``,
        ``confidence``), or None for a study without Monte Carlo."""
        return self._data["identity"].get("monte_carlo")

    def monte_carlo(self, output: str) -> Dict[str, Any]:
        """The Monte Carlo σ of ``output`` at every point (a study with ``monte_carlo=N``): a dict of arrays of
        :attr:`shape` — ``sigma`` (the estimate), ``lower``, ``upper`` (its interval) and ``covers`` (whether the
        interval covers the exact σ; False where a point failed). NaN where a point has no batch."""
        import numpy as np

        if self.monte_carlo_options is None:
            raise KeyError("this study has no Monte Carlo batches: sweep(..., monte_carlo=N)")
        _output(self.outputs, output)
        out = {k: np.full(self.n_points, np.nan) for k in ("sigma", "lower", "upper")}
        covers = np.zeros(self.n_points, dtype=bool)
        for r in self.rows:
            mc = r.get("monte_carlo")
            if r["output"] == output and mc is not None:
                for k in out:
                    out[k][r["point"]] = mc[k]
                covers[r["point"]] = mc["covers"]
        res: Dict[str, Any] = {k: v.reshape(self.shape) for k, v in out.items()}
        res["covers"] = covers.reshape(self.shape)
        return res

    def to_dict(self) -> Dict[str, Any]:
        """A deep copy of the data, as ``stochvib sweep … --json`` prints it."""
        return copy.deepcopy(self._data)

    def to_dataframe(self) -> Any:
        """One row per (point, output), one column per swept key (pandas)."""
        return _dataframe(
            [{**{k: v for k, v in r.items() if k not in ("params", "monte_carlo")}, **r["params"]} for r in self.rows]
        )

    def __repr__(self) -> str:
        keys = ", ".join(f"{k} ({len(v)} values)" for k, v in self.params.items())
        failed = len({r["point"] for r in self.rows if r.get("error")})
        head = f"SweepResult: {self.n_points} points ({self.mode} of {keys}), {failed} failed"
        rows = [f"{'output':<14} {'min sigma':>12} {'max sigma':>12}"]
        for o in self.outputs:
            s = [r["sigma"] for r in self.rows if r["output"] == o and r.get("sigma") is not None]
            rows.append(f"{o:<14} {_e(min(s) if s else None):>12} {_e(max(s) if s else None):>12}")
        return "\n".join([head, *rows])


class VerdictTable:
    """The verdicts at every point of a parameter study (:meth:`Scenario.sweep_verdicts`; ``to_dict()`` is
    ``stochvib sweep SCENARIO --param … --verdicts --json``, ``to_csv()`` its CSV).

    Attributes
    ----------
    columns : list of str
        ``point``, the swept keys, then the quantities, each with its SI unit (``model.c [kg s^-2]``,
        ``sigma(y) [m]``, ``a_v [m/s^2]``).
    rows : list of dict
        One per point: ``point``, ``values`` (in the order of the columns after ``point``; None where a value
        does not exist), ``error`` (why the point failed, else None).
    shape : tuple of int
        The study's shape: one axis per key for a grid, ``(n_points,)`` for zip.
    """

    def __init__(self, data: Dict[str, Any], csv: str, shape: Sequence[int]) -> None:
        self._data = data
        self._csv = csv
        self.columns: List[str] = list(data["columns"])
        self.rows: List[Dict[str, Any]] = data["rows"]
        self.shape: Tuple[int, ...] = tuple(shape)

    def column(self, name: str) -> Any:
        """The column ``name`` (as in :attr:`columns`, unit included) at every point as a numpy array of
        :attr:`shape` (NaN where a value does not exist)."""
        import numpy as np

        if name not in self.columns[1:]:
            raise KeyError(f"no column {name!r}; the columns are {self.columns}")
        k = self.columns.index(name) - 1
        out = np.array([np.nan if r["values"][k] is None else r["values"][k] for r in self.rows], dtype=float)
        return out.reshape(self.shape)

    def to_dict(self) -> Dict[str, Any]:
        """A deep copy of the data, as ``stochvib sweep … --verdicts --json`` prints it."""
        return copy.deepcopy(self._data)

    def to_csv(self) -> str:
        """The table as ``stochvib sweep … --verdicts`` prints it."""
        return self._csv

    def to_dataframe(self) -> Any:
        """One row per point, one column per entry of :attr:`columns`, and ``error`` (pandas)."""
        return _dataframe(
            [{"point": r["point"], **dict(zip(self.columns[1:], r["values"])), "error": r["error"]} for r in self.rows]
        )

    def __repr__(self) -> str:
        failed = sum(1 for r in self.rows if r.get("error"))
        head = f"VerdictTable: {len(self.rows)} points, {len(self.columns) - 1} columns, {failed} failed"
        rows = [f"{'column':<32} {'min':>12} {'max':>12}"]
        for c in self.columns[1:]:
            v = [x for x in self.column(c).ravel().tolist() if x == x]
            rows.append(f"{c:<32} {_e(min(v) if v else None):>12} {_e(max(v) if v else None):>12}")
        return "\n".join([head, *rows])


class NonlinearOutput:
    """One output of a model with nonlinear elements: ``name``, ``unit``, and per statistic
    ("mean_response", "sigma_response", "kurtosis", "upcrossing_rate[<level>]", …) the value by route 1
    (statistical linearisation, Gaussian) and the exact one (route 3, where it applies): ``rows`` maps the
    statistic to a dict ``route1``, ``exact``, ``unit``; ``route1_nu0`` the zero-upcrossing rate by route 1."""

    def __init__(self, data: Dict[str, Any]) -> None:
        self._data = data
        self.name: str = data["name"]
        self.unit: str = data["unit"]
        self.route1_nu0: Optional[float] = data.get("route1_nu0")
        self.rows: Dict[str, Dict[str, Any]] = {r["statistic"]: r for r in data.get("rows", [])}

    def route1(self, statistic: str = "sigma_response") -> Optional[float]:
        """The statistic by route 1 (statistical linearisation), or None where it gives none."""
        return self.rows[statistic].get("route1")

    def exact(self, statistic: str = "sigma_response") -> Optional[float]:
        """The statistic by route 3 (the exact stationary density), or None where route 3 does not apply."""
        return self.rows[statistic].get("exact")

    def route2(self, statistic: str = "sigma_response") -> Optional[Dict[str, float]]:
        """The statistic by route 2 (the Monte Carlo of the nonlinear equations, ``analyze(monte_carlo=N)``):
        a dict ``estimate``, ``lower``, ``upper``, ``confidence``; None without a batch."""
        mc = self.rows[statistic].get("monte_carlo")
        return None if mc is None else dict(mc)

    @property
    def sigma(self) -> Optional[float]:
        """σ of the output: the exact one where route 3 applies, else route 1's."""
        e = self.exact()
        return e if e is not None else self.route1()

    def __repr__(self) -> str:
        return f"NonlinearOutput {self.name} [{self.unit}]: sigma route 1 {_e(self.route1())}, exact {_e(self.exact())}"


class NonlinearResult(_Text):
    """The analysis of a model with nonlinear elements (``stochvib analyze`` of such a file): route 1
    (statistical linearisation; ``route1`` says how it converged, ``route1_converged``) and route 3 (the exact
    stationary density where it applies; ``route3`` says whether and why). ``result["x"]`` is a
    :class:`NonlinearOutput`; ``elements`` the equivalent linear elements (dicts, as the ``--json``)."""

    def __init__(self, data: Dict[str, Any], text: str) -> None:
        self._data = data
        self._text = text
        self.outputs: Dict[str, NonlinearOutput] = {o["name"]: NonlinearOutput(o) for o in data.get("outputs", [])}

    def __getitem__(self, name: str) -> NonlinearOutput:
        return _output(self.outputs, name)

    def to_dataframe(self) -> Any:
        """One row per (output, statistic): route1, exact, unit."""
        return _dataframe(
            [
                {"output": o.name, "statistic": k, "unit": r.get("unit"), "route1": r.get("route1"), "exact": r.get("exact")}
                for o in self.outputs.values()
                for k, r in o.rows.items()
            ]
        )

    def __repr__(self) -> str:
        head = f"NonlinearResult: {self._data.get('title')}  ({self._data.get('scenario')})"
        rows = [f"{'output':<14} {'unit':<8} {'sigma route 1':>14} {'sigma exact':>14} {'sigma route 2':>14}"]
        for o in self.outputs.values():
            r2 = o.route2() if "sigma_response" in o.rows else None
            mc = None if r2 is None else r2.get("estimate")
            rows.append(f"{o.name:<14} {o.unit:<8} {_e(o.route1()):>14} {_e(o.exact()):>14} {_e(mc):>14}")
        return "\n".join([head, *rows])


class NonlinearRunResult(RunResult):
    """A finished route-2 run of a model with nonlinear elements (:func:`stochvib.simulate` of such a
    scenario; the data of ``stochvib simulate --json``): the attributes of :class:`RunResult` (the run as a
    linear run reports it, its statistics against route 1's Gaussian σ), and ``burn_in_s`` (s) and
    ``halving_checks`` (realizations repeated with Δt/2 to check the step)."""

    def __init__(self, data: Dict[str, Any], text: str, step: str) -> None:
        super().__init__(data["run"], text, step)
        self._data = data
        self.burn_in_s: float = data["burn_in_s"]
        self.halving_checks: int = data["halving_checks"]

    def __repr__(self) -> str:
        return super().__repr__() + f"\nburn-in {_e(self.burn_in_s)} s, {self.halving_checks} dt-halving checks"


@dataclass(frozen=True, repr=False)
class OptimizedParam(_Mapping):
    """A parameter at the answer of :meth:`Scenario.optimize`: ``key``, ``value`` (SI), ``text`` (in the unit
    of the bounds), ``at_bound`` ("lower", "upper" or None)."""

    key: str
    value: float
    text: str
    at_bound: Optional[str]

    def __repr__(self) -> str:
        b = "" if self.at_bound is None else f"  (at the {self.at_bound} bound)"
        return f"{self.key} = {self.text}  ({_e(self.value, 9)} SI){b}"


@dataclass(frozen=True, repr=False)
class ConstraintState(_Mapping):
    """A constraint at the answer of :meth:`Scenario.optimize`: ``text`` as given, ``value`` and ``limit``
    (SI, in ``unit``), ``margin`` (≥ 0 when met), ``active`` (the optimum lies on it), ``met``."""

    text: str
    value: float
    limit: float
    unit: str
    margin: float
    active: bool
    met: bool

    def __repr__(self) -> str:
        state = "ACTIVE" if self.met and self.active else ("inactive" if self.met else "VIOLATED")
        return f"constraint {self.text}: value {_e(self.value)} {self.unit}, margin {_e(self.margin)} {self.unit}  {state}"


class OptimizeResult(_Text):
    """The answer of :meth:`Scenario.optimize` (the data of ``stochvib optimize --json``).

    Attributes
    ----------
    goal : str
        "minimize" or "maximize".
    objective, unit : str
        The quantity and its SI unit.
    value : float
        The quantity at the answer, SI.
    feasible : bool
        Every constraint met; when False the answer is the least violating point and ``violations`` says
        by how much each constraint is missed.
    params : list of OptimizedParam
    constraints : list of ConstraintState
    evaluations : int
        Analyses in all starts.
    kkt : KktCheck or None
        The first-order optimality check at the answer with the analytic gradients (the ``KKT`` lines of the
        command-line tool); None where the problem has no analytic gradients.
    """

    def __init__(self, data: Dict[str, Any], text: str) -> None:
        self._data = data
        self._text = text
        self.goal: str = str(data["goal"]).lower()
        self.objective: str = data["objective"]
        self.unit: str = data["unit"]
        self.value: float = data["value"]
        self.feasible: bool = data["feasible"]
        self.evaluations: int = data["evaluations"]
        self.params: List[OptimizedParam] = [
            OptimizedParam(p["key"], p["value"], p["text"], p.get("at_bound")) for p in data["params"]
        ]
        self.constraints: List[ConstraintState] = [
            ConstraintState(**{k: c[k] for k in ("text", "value", "limit", "unit", "margin", "active", "met")})
            for c in data["constraints"]
        ]
        kkt = data.get("kkt")
        self.kkt: Optional[KktCheck] = None if kkt is None else KktCheck.from_dict(kkt, [p.key for p in self.params])

    @property
    def x(self) -> Dict[str, float]:
        """key → the parameter's value at the answer (SI)."""
        return {p.key: p.value for p in self.params}

    @property
    def violations(self) -> List[str]:
        """One sentence per constraint that is not met (empty when feasible), as the command-line tool says it."""
        return [line.strip() for line in self._text.splitlines() if "cannot be met" in line]

    def to_dataframe(self) -> Any:
        """One row per parameter: key, value, text, at_bound."""
        return _dataframe([{"key": p.key, "value": p.value, "text": p.text, "at_bound": p.at_bound} for p in self.params])

    def __repr__(self) -> str:
        state = "" if self.feasible else " (INFEASIBLE: the least violating point)"
        head = f"OptimizeResult: {self.goal} of {self.objective}{state}: {_e(self.value)} {self.unit}"
        kkt = [] if self.kkt is None else [f"  {self.kkt!r}"]
        return "\n".join([head, *(f"  {p!r}" for p in self.params), *(f"  {c!r}" for c in self.constraints), *kkt])


@dataclass(frozen=True, repr=False)
class KktCheck:
    """The first-order optimality (KKT) check of an optimum with the analytic gradients (Lyapunov
    sensitivities), ``OptimizeResult.kkt``.

    Attributes
    ----------
    keys : list of str
        The parameters, in the order of the gradients.
    gradient : numpy.ndarray
        ∂(objective)/∂x_k, SI per SI unit of each parameter.
    constraint_gradients : numpy.ndarray
        One row per constraint: ∂(its quantity)/∂x_k.
    multipliers : numpy.ndarray
        Per constraint, its Lagrange multiplier in unit coordinates (0 for an inactive one).
    bound_multipliers : numpy.ndarray
        Per parameter, the multiplier of the bound it sits at (0 inside).
    residual : float
        The stationarity residual in unit coordinates: 0 at a KKT point.
    satisfied : bool
        The residual is at most the tolerance (1e-5) and no multiplier is negative beyond it.
    """

    keys: List[str]
    gradient: Any
    constraint_gradients: Any
    multipliers: Any
    bound_multipliers: Any
    residual: float
    satisfied: bool

    @classmethod
    def from_dict(cls, d: Dict[str, Any], keys: List[str]) -> "KktCheck":
        import numpy as np

        g = d["gradients"]
        rows = np.asarray(g["constrained"], dtype=float).reshape(len(g["constrained"]), len(keys))
        return cls(
            keys,
            np.asarray(g["objective"], dtype=float),
            rows,
            np.asarray(d["multipliers"], dtype=float),
            np.asarray(d["bound_multipliers"], dtype=float),
            float(d["residual"]),
            bool(d["satisfied"]),
        )

    def to_dict(self) -> Dict[str, Any]:
        """The ``kkt`` object of ``stochvib optimize --json``."""
        return {
            "gradients": {"objective": self.gradient.tolist(), "constrained": self.constraint_gradients.tolist()},
            "multipliers": self.multipliers.tolist(),
            "bound_multipliers": self.bound_multipliers.tolist(),
            "residual": self.residual,
            "satisfied": self.satisfied,
        }

    def __repr__(self) -> str:
        grads = ", ".join(f"d/d {k} = {_e(v)}" for k, v in zip(self.keys, self.gradient))
        ok = "satisfied" if self.satisfied else "NOT satisfied"
        return f"KKT: stationarity residual {_e(self.residual, 3)} in unit coordinates, {ok}; gradient {grads}"


@dataclass(frozen=True, repr=False)
class ParetoPoint(_Mapping):
    """A point of a Pareto front: ``params`` (key → SI value), ``values`` (the two quantities, SI), ``limit``
    (the limit ε on the second quantity; None at the two ends), ``feasible`` (every constraint met)."""

    params: Dict[str, float]
    values: Tuple[float, float]
    limit: Optional[float]
    feasible: bool

    def __repr__(self) -> str:
        ps = ", ".join(f"{k} = {_e(v)}" for k, v in self.params.items())
        lim = "end" if self.limit is None else f"limit {_e(self.limit)}"
        return f"{ps}: {_e(self.values[0])}, {_e(self.values[1])} ({lim}{'' if self.feasible else ', INFEASIBLE'})"


class ParetoFront(_Text):
    """The Pareto front of two quantities (:meth:`Scenario.pareto`; ``to_dict()`` is the ``--json`` of
    ``stochvib optimize --pareto``, ``to_csv()`` and ``str()`` its CSV).

    Attributes
    ----------
    keys : list of str
        The parameters.
    quantities, units : list of str
        The two quantities as given and their SI units.
    points : list of ParetoPoint
        In order of increasing first quantity; the first and last are the single-objective optima.
    values : numpy.ndarray
        (N, 2): the two quantities at each point, SI.
    params : numpy.ndarray
        (N, len(keys)): the parameters at each point, SI.
    evaluations : int
        Analyses in all searches.
    plots : list of pathlib.Path
        The pictures drawn (``plots=``): ``pareto-front.svg`` and ``.png``.
    """

    def __init__(self, data: Dict[str, Any], csv: str, plots: Sequence[Any] = ()) -> None:
        import numpy as np

        self._data = data
        self._text = csv
        self.keys: List[str] = list(data["keys"])
        self.quantities: List[str] = list(data["quantities"])
        self.units: List[str] = list(data["units"])
        self.evaluations: int = data["evaluations"]
        self.points: List[ParetoPoint] = [
            ParetoPoint(dict(zip(self.keys, p["params"])), tuple(p["values"]), p["limit"], p["feasible"])
            for p in data["points"]
        ]
        self.values = np.array([p["values"] for p in data["points"]], dtype=float).reshape(-1, 2)
        self.params = np.array([p["params"] for p in data["points"]], dtype=float).reshape(-1, len(self.keys))
        self.plots: List[Path] = [Path(p) for p in plots]

    def to_csv(self) -> str:
        """The command's CSV (``stochvib optimize --pareto`` without ``--json``), byte for byte."""
        return self._text

    def to_dataframe(self) -> Any:
        """One row per point: the parameters (SI), the two quantities, the limit, feasibility."""
        rows = []
        for p in self.points:
            row: Dict[str, Any] = dict(p.params)
            row.update({f"{q} [{u}]": v for q, u, v in zip(self.quantities, self.units, p.values)})
            row.update({"limit": p.limit, "feasible": p.feasible})
            rows.append(row)
        return _dataframe(rows)

    def __repr__(self) -> str:
        head = f"ParetoFront of {self.quantities[0]} [{self.units[0]}] and {self.quantities[1]} [{self.units[1]}]"
        cols = [*self.keys, *(f"{q} [{u}]" for q, u in zip(self.quantities, self.units)), "limit", "feasible"]
        rows = [" | ".join(cols)]
        for p in self.points:
            cells = [*(_e(v) for v in p.params.values()), *(_e(v) for v in p.values), _e(p.limit)]
            rows.append(" | ".join([*cells, "yes" if p.feasible else "no"]))
        return "\n".join([f"{head}: {len(self.points)} points, {self.evaluations} evaluations", *rows])


class TransientOutput:
    """One output of a transient analysis over the reported times: ``name``, ``unit``, numpy arrays ``mean``,
    ``sigma`` (σ(t); for a weighted output the running r.m.s. a_w(t)) and ``nu0_plus`` (Hz),
    ``upcrossing_rates`` (level → array of ν⁺(b, t) in Hz), ``weighted_of``, ``note``."""

    def __init__(self, data: Dict[str, Any]) -> None:
        import numpy as np

        self._data = data
        self.name: str = data["name"]
        self.unit: str = data["unit"]
        self.weighted_of: Optional[str] = data.get("weighted_of")
        self.note: Optional[str] = data.get("note")
        self.mean = np.asarray(data["mean"], dtype=float)
        self.sigma = np.asarray(data["sigma"], dtype=float)
        self.nu0_plus = np.asarray(data["nu0_plus"], dtype=float)
        self.upcrossing_rates: Dict[float, Any] = {b: np.asarray(r, dtype=float) for b, r in data.get("upcrossing_rates", [])}

    def __repr__(self) -> str:
        return f"TransientOutput {self.name} [{self.unit}]: max sigma {_e(float(self.sigma.max()) if self.sigma.size else None)}"


class TransientResult(_Text):
    """The non-stationary response of a scenario with a ``[transient]`` section (:meth:`Scenario.transient`;
    ``to_dict()`` is the ``--json`` of ``stochvib transient``: ``exact``, ``monte_carlo``, ``sigma``).

    Attributes
    ----------
    times : numpy.ndarray
        The reported times, s.
    outputs : dict
        name → :class:`TransientOutput` (σ(t), mean, ν₀⁺(t) by the exact route).
    mission : list of dict
        Per (output, level): expected up-crossings and the probability of exceeding the level in the mission
        (``p_integrated_rate``, ``p_poisson``, ``p_vanmarcke``, ``p_der_kiureghian``).
    mission_duration : float
        s.
    monte_carlo : dict or None
        With a batch: the run summary (``path``, ``n_realizations``, the DKW verdicts of the maxima).
    sigma_comparison : list of dict or None
        With a batch, per output: ``rows`` (t, exact σ, Monte Carlo σ, lower, upper), ``coverage``,
        ``simultaneous_confidence``, ``outside`` (times where the exact σ is outside the simultaneous interval).
    notes : list of str
        Outputs left out of the batch and why.
    """

    def __init__(self, data: Dict[str, Any], text: str, notes: List[str]) -> None:
        import numpy as np

        self._data = data
        self._text = text
        self.notes = list(notes)
        exact = data["exact"]
        self.times = np.asarray(exact["times"], dtype=float)
        self.outputs: Dict[str, TransientOutput] = {o["name"]: TransientOutput(o) for o in exact["outputs"]}
        self.mission: List[Dict[str, Any]] = exact.get("mission", [])
        self.mission_duration: float = exact["mission_duration"]
        self.monte_carlo: Optional[Dict[str, Any]] = data.get("monte_carlo")
        self.sigma_comparison: Optional[List[Dict[str, Any]]] = data.get("sigma")

    def __getitem__(self, name: str) -> TransientOutput:
        return _output(self.outputs, name)

    def to_dataframe(self) -> Any:
        """One row per (time, output): t, output, mean, sigma, nu0_plus."""
        return _dataframe(
            [
                {"t": float(t), "output": o.name, "mean": float(o.mean[k]), "sigma": float(o.sigma[k]), "nu0_plus": float(o.nu0_plus[k])}
                for o in self.outputs.values()
                for k, t in enumerate(self.times)
            ]
        )

    def __repr__(self) -> str:
        head = f"TransientResult: {self._data['exact'].get('title')}  ({len(self.times)} times to {_e(float(self.times[-1]))} s)"
        rows = [f"{'output':<16} {'unit':<8} {'max sigma':>12} {'sigma(T)':>12}"]
        for o in self.outputs.values():
            rows.append(f"{o.name:<16} {o.unit:<8} {_e(float(o.sigma.max())):>12} {_e(float(o.sigma[-1])):>12}")
        if self.sigma_comparison:
            for c in self.sigma_comparison:
                rows.append(f"Monte Carlo {c['output']}: coverage {c['coverage']:.3f}, {len(c['outside'])} times outside")
        return "\n".join([head, *rows])
