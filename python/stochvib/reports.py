"""Typed results of :func:`stochvib.replay`, :func:`stochvib.workday` and :func:`stochvib.inspect` (the
reports of ``stochvib replay``, ``stochvib workday`` and ``stochvib inspect``).

* :class:`ReplayResult` — a road profile replayed through a scenario's model: per output the replayed
  statistics beside the analytic σ from the profile's own measured density (:class:`ReplayedOutput`);
* :class:`WorkdayResult` — the daily exposure of a working day of several tasks (:class:`WorkdayTask`,
  :class:`WorkdayAxis`), against Directive 2002/44/EC and ISO 2631-1 Annex B;
* :class:`RunInfo` — the identity, sizes and statistics of a Monte Carlo run file.

As every result: ``repr()`` a table as the command-line tool prints it, ``str()`` the tool's full text,
``to_dict()`` its ``--json`` data, ``to_json()`` the ``--json`` text byte for byte, ``to_dataframe()`` a
pandas DataFrame (one row per output, task or statistic; pandas is optional).
"""

from __future__ import annotations

import json
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, Dict, List, Optional

from .results import _dataframe, _e, _Mapping, _run_statistics, _sigma_rows, _statistics_dataframe, _Text

__all__ = ["ReplayResult", "ReplayedOutput", "WorkdayResult", "WorkdayTask", "WorkdayAxis", "RunInfo"]


class _Printed(_Text):
    """A report given as the command-line tool prints it: its ``--json`` text and its text."""

    def __init__(self, json_text: str, text: str) -> None:
        self._json = json_text
        self._data = json.loads(json_text)
        self._text = text

    def to_json(self) -> str:
        """The ``--json`` text of the command-line tool, byte for byte."""
        return self._json


@dataclass(frozen=True, repr=False)
class ReplayedOutput(_Mapping):
    """One output of a replay: the statistics of its history after the skipped length, in ``unit`` (SI),
    and ``analytic_sigma``, σ of the same scenario whose road spectrum is the profile's measured density
    (None when that route gave no finite value); ``ratio`` = sigma / analytic_sigma."""

    name: str
    unit: str
    index: int
    mean: float
    sigma: float
    rms: float
    min: float
    max: float
    crest_factor: float
    analytic_sigma: Optional[float]

    @property
    def ratio(self) -> Optional[float]:
        return None if not self.analytic_sigma else self.sigma / self.analytic_sigma

    def __repr__(self) -> str:
        return (
            f"{self.name:<16} {self.unit:>6}  {_e(self.mean, 4):>12} {_e(self.sigma, 4):>12} "
            f"{_e(self.analytic_sigma, 4):>12}  {_e(self.min, 4):>12} {_e(self.max, 4):>12}"
        )


class ReplayResult(_Printed):
    """A road profile replayed through a scenario's model (``stochvib replay SCENARIO PROFILE``).

    Attributes
    ----------
    scenario, profile : pathlib.Path
    title : str
    speed_m_s, dt_s, step_m, skip_m : float
        The speed, the time step Δt = Δx/v, the profile's step and the length skipped for settling.
    n_samples, skip_samples : int
    wheels : list of dict
        The model input → (track, position m, gain, offset) map.
    outputs : list of ReplayedOutput
    analytic_track : str
        The profile column whose Welch density the analytic σ uses.
    """

    def __init__(self, json_text: str, text: str) -> None:
        super().__init__(json_text, text)
        d = self._data
        r = d.get("replay", {})
        self.scenario = Path(d["scenario"])
        self.profile = Path(d["profile"])
        self.title: str = d.get("title", "")
        self.speed_m_s: float = r.get("speed_m_s")
        self.dt_s: float = r.get("dt_s")
        self.step_m: float = r.get("step_m")
        self.skip_m: float = r.get("skip_m")
        self.n_samples: int = r.get("n_samples")
        self.skip_samples: int = r.get("skip_samples")
        self.wheels: List[Dict[str, Any]] = d.get("wheels", [])
        self.analytic_track: str = d.get("analytic_track", "")
        self.outputs = [
            ReplayedOutput(**{k: o.get(k) for k in ReplayedOutput.__dataclass_fields__}) for o in d.get("outputs", [])
        ]

    def __getitem__(self, name: str) -> ReplayedOutput:
        for o in self.outputs:
            if o.name == name:
                return o
        raise KeyError(f"no output {name!r}; the outputs are {[o.name for o in self.outputs]}")

    @property
    def sigma(self) -> Dict[str, float]:
        """The replayed σ of every output."""
        return {o.name: o.sigma for o in self.outputs}

    def to_dataframe(self) -> Any:
        """One row per output: name, unit, mean, sigma, rms, min, max, crest_factor, analytic_sigma."""
        return _dataframe([{k: getattr(o, k) for k in ReplayedOutput.__dataclass_fields__} for o in self.outputs])

    def __repr__(self) -> str:
        head = f"ReplayResult: {self.scenario} on {self.profile} at {self.speed_m_s} m/s"
        cols = f"{'output':<16} {'unit':>6}  {'mean':>12} {'sigma':>12} {'analytic':>12}  {'min':>12} {'max':>12}"
        return "\n".join([head, cols, *[repr(o) for o in self.outputs]])


@dataclass(frozen=True, repr=False)
class WorkdayAxis(_Mapping):
    """One axis of a task or of the day: ``axis`` ("x", "y", "z"), ``a8`` (m/s², the task's share or the
    day's A(8)), ``vdv`` (m/s^1.75); for a task also ``k`` (the health factor), ``a_w`` (m/s²), ``weighted``
    (k·a_w) and ``output`` (the weighted output it comes from)."""

    axis: str
    a8: float
    vdv: float
    k: Optional[float] = None
    a_w: Optional[float] = None
    weighted: Optional[float] = None
    output: Optional[str] = None

    @classmethod
    def _from(cls, d: Dict[str, Any]) -> "WorkdayAxis":
        return cls(**{k: d.get(k) for k in cls.__dataclass_fields__})


@dataclass(frozen=True, repr=False)
class WorkdayTask(_Mapping):
    """One task of the day: ``name``, ``scenario`` (as written), ``duration_s``, ``speed_m_s`` (None when
    the input has no speed), ``scenario_title`` and its ``axes`` (:class:`WorkdayAxis`)."""

    name: str
    scenario: str
    duration_s: float
    speed_m_s: Optional[float]
    scenario_title: str
    axes: List[WorkdayAxis] = field(default_factory=list)

    @classmethod
    def _from(cls, d: Dict[str, Any]) -> "WorkdayTask":
        t = d.get("task", {})
        return cls(
            name=t.get("name", ""),
            scenario=t.get("scenario", ""),
            duration_s=t.get("duration_s"),
            speed_m_s=d.get("speed_m_s"),
            scenario_title=d.get("scenario_title", ""),
            axes=[WorkdayAxis._from(a) for a in d.get("axes", [])],
        )

    def __repr__(self) -> str:
        top = max(self.axes, key=lambda a: a.a8, default=None)
        share = None if top is None else top.a8
        return f"{self.name:<20} {self.duration_s / 3600:>8.3g} h  A(8) share {_e(share, 4)} m/s^2"


class WorkdayResult(_Printed):
    """The daily exposure of a working day (``stochvib workday FILE``).

    Attributes
    ----------
    title, file : str
    total_duration_s : float
    tasks : list of WorkdayTask
    axes : list of WorkdayAxis
        The day's A(8) and VDV per axis.
    a8, vdv : float
        The day's A(8) (m/s²) and VDV (m/s^1.75), the highest over the axes.
    dominant_a8, dominant_vdv : str
        The axes of those maxima.
    verdict : dict
        Against Directive 2002/44/EC (action and limit values) and the ISO 2631-1 Annex B zones.
    """

    def __init__(self, json_text: str, text: str, markdown: str) -> None:
        super().__init__(json_text, text)
        d = self._data
        self._markdown = markdown
        self.title: str = d.get("title", "")
        self.file: str = d.get("file", "")
        self.total_duration_s: float = d.get("total_duration_s")
        self.tasks = [WorkdayTask._from(t) for t in d.get("tasks", [])]
        self.axes = [WorkdayAxis._from(a) for a in d.get("axes", [])]
        self.dominant_a8: str = d.get("dominant_a8")
        self.dominant_vdv: str = d.get("dominant_vdv")
        self.verdict: Dict[str, Any] = d.get("verdict", {})
        self.a8: float = self.verdict.get("a8")
        self.vdv: Optional[float] = self.verdict.get("vdv")

    def to_markdown(self) -> str:
        """The report as ``stochvib workday FILE --format markdown`` prints it."""
        return self._markdown

    def to_dataframe(self) -> Any:
        """One row per (task, axis): task, duration_s, speed_m_s, axis, k, a_w, weighted, a8, vdv."""
        return _dataframe(
            [
                {"task": t.name, "duration_s": t.duration_s, "speed_m_s": t.speed_m_s, "axis": a.axis, "k": a.k,
                 "a_w": a.a_w, "weighted": a.weighted, "a8": a.a8, "vdv": a.vdv}
                for t in self.tasks
                for a in t.axes
            ]
        )

    def __repr__(self) -> str:
        head = f"WorkdayResult: {self.title}  ({self.file}), {len(self.tasks)} tasks"
        day = [f"  axis {a.axis}: A(8) {_e(a.a8, 4)} m/s^2, VDV {_e(a.vdv, 4)} m/s^1.75" for a in self.axes]
        return "\n".join([head, *[repr(t) for t in self.tasks], *day])


class RunInfo(_Printed):
    """The identity, sizes and statistics of a Monte Carlo run file (``stochvib inspect FILE``).

    Attributes
    ----------
    path : pathlib.Path
    format_version, seed, n_samples, n_realizations, n_shards : int
    toolkit_version, generator : str
    dt : float
        The time step, s.
    store_raw : bool
    outputs : list of str
    statistics : dict
        output → statistic name → dict (``estimate``, ``lower``, ``upper``, ``confidence``, ``analytic``,
        ``covers``, ``unit``, ...), as :attr:`RunResult.statistics`.
    """

    def __init__(self, json_text: str, text: str, markdown: str) -> None:
        super().__init__(json_text, text)
        d = self._data
        self._markdown = markdown
        self.path = Path(d["path"])
        self.format_version: int = d.get("format_version")
        self.toolkit_version: str = d.get("toolkit_version", "")
        self.seed: int = d.get("seed")
        self.generator: str = d.get("generator", "")
        self.dt: float = d.get("dt")
        self.n_samples: int = d.get("n_samples")
        self.n_realizations: int = d.get("n_realizations")
        self.n_shards: int = d.get("n_shards")
        self.store_raw: bool = d.get("store_raw")
        self.outputs: List[str] = d.get("outputs", [])
        self.statistics = _run_statistics(d.get("statistics", []))

    @property
    def sigma(self) -> Dict[str, float]:
        """Monte Carlo σ estimate of every output that has one."""
        return {k: v["sigma"]["estimate"] for k, v in self.statistics.items() if "sigma" in v}

    def to_markdown(self) -> str:
        """The summary as ``stochvib inspect FILE --format markdown`` prints it."""
        return self._markdown

    def to_dataframe(self) -> Any:
        """One row per (output, statistic): estimate, lower, upper, confidence, analytic, covers, unit."""
        return _statistics_dataframe(self.statistics)

    def __repr__(self) -> str:
        head = (
            f"RunInfo: {self.path} ({self.n_realizations} realizations of {self.n_samples} samples, "
            f"dt {_e(self.dt)} s, seed {self.seed})"
        )
        return "\n".join([head, *_sigma_rows(self.statistics)])
