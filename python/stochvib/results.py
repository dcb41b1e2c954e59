"""Typed results: one class per kind of analysis, with attributes, ``to_dict()``, ``to_dataframe()``.

* :class:`AnalysisResult` — the ``stochvib analyze`` report of a stochastic scenario: one
  :class:`OutputResult` per output, each with its :class:`VarianceMethod` entries and
  :class:`LevelCrossing` rates;
* :class:`TablesResult` — the result tables of a deterministic model or a reference table of the sources;
* :class:`RunResult` — a finished Monte Carlo run (the HDF5 file and its statistics);
* :class:`ExposureResult` — the ISO 2631-1 evaluation of acceleration records (:func:`stochvib.exposure`).

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
from typing import Any, Dict, Iterator, List, Optional, Tuple

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
        out: Dict[str, Dict[str, Dict[str, Any]]] = {}
        for o in self._data.get("outputs", []):
            stats = {}
            for s in o.get("statistics", []):
                entry = dict(s.get("interval", {}))
                entry.update({k: v for k, v in s.items() if k not in ("interval", "name")})
                stats[s["name"]] = entry
            out[o["output"]] = stats
        return out

    @property
    def sigma(self) -> Dict[str, float]:
        """Monte Carlo σ estimate of every simulated output."""
        return {k: v["sigma"]["estimate"] for k, v in self.statistics.items() if "sigma" in v}

    def to_dataframe(self) -> Any:
        """One row per (output, statistic): estimate, lower, upper, confidence, analytic, covers."""
        rows = [
            {"output": o, "statistic": name, **{k: v for k, v in s.items() if not isinstance(v, (dict, list))}}
            for o, stats in self.statistics.items()
            for name, s in stats.items()
        ]
        return _dataframe(rows)

    def __repr__(self) -> str:
        head = f"RunResult: {self.path} ({self.n_realizations} realizations, route {self.route})"
        rows = [f"{'output':<14} {'sigma':>12} {'lower':>12} {'upper':>12} {'analytic':>12}  covers"]
        for o, stats in self.statistics.items():
            s = stats.get("sigma", {})
            rows.append(
                f"{o:<14} {_e(s.get('estimate')):>12} {_e(s.get('lower')):>12} {_e(s.get('upper')):>12} "
                f"{_e(s.get('analytic')):>12}  {s.get('covers')}"
            )
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
