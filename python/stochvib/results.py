"""Result objects: thin views of the library's reports.

The library serialises its reports (the ``stochvib analyze`` and ``stochvib simulate`` reports, the same
data as ``--json``); these classes give attribute access to them, keep the full data in ``to_dict()`` and
print as the command-line tool does. Fields the library adds later (comfort, fatigue, ...) appear in
``to_dict()`` and as attributes without a change here.
"""

from __future__ import annotations

import copy
import math
from pathlib import Path
from typing import Any, Dict, Iterator, List, Optional, Tuple

__all__ = ["Report", "AnalysisResult", "OutputResult", "RunResult"]


class _View:
    """Attribute access to a dict of report data (missing keys raise AttributeError)."""

    _data: Dict[str, Any]

    def __getattr__(self, name: str) -> Any:
        data = self.__dict__.get("_data", {})
        if name in data:
            return data[name]
        raise AttributeError(f"{type(self).__name__} has no attribute {name!r}; keys: {sorted(data)}")

    def to_dict(self) -> Dict[str, Any]:
        """A deep copy of the data (plain dicts, lists, floats, strings and None: JSON-compatible)."""
        return copy.deepcopy(self._data)

    def __dir__(self) -> List[str]:
        return sorted(set(super().__dir__()) | set(self._data))


class Report(_View):
    """A report of the library: ``to_dict()`` has its data, ``str()`` is the command-line tool's text."""

    def __init__(self, data: Dict[str, Any], text: str) -> None:
        self._data = data
        self._text = text

    def __str__(self) -> str:
        return self._text

    def __repr__(self) -> str:
        title = self._data.get("title", "")
        return f"<stochvib.{type(self).__name__} {title!r}>"


class OutputResult(_View):
    """The statistics of one output (units: the output's SI unit ``unit``; rates per second, per metre for a
    system driven along a road).

    Attributes: ``name``, ``unit``, ``mean`` (M_y = H(0) M_u), ``variance`` (reference variance: Lyapunov,
    else integral table, else quadrature), ``sigma``, ``variance_outcome`` (the library's outcome of the
    reference variance: ``status`` "value", "divergent", "not-converged", "not-applicable", "unreliable" or
    "failed", with ``reason`` when there is no value), ``variance_note`` (that reason, or None),
    ``methods`` (every variance method: ``method``, ``status``, ``value``, ``error_estimate``,
    ``rel_diff``, ``reason``; a method that did not converge has its ``estimate`` and which option raises the
    effort), ``lambda2``, ``lambda4`` (spectral moments ∫ω^k S_y dω, with ``lambda2_outcome`` and
    ``lambda4_outcome``), ``zero_upcrossing_rate`` ν₀⁺ = (1/2π)√(λ₂/λ₀), ``bandwidth`` ε, ``lower_3sigma``,
    ``upper_3sigma``, ``band_sigma``, ``band_note``, ``expected_largest_peak``, ``levels`` (Rice up-crossing
    rate and exceedance probability per level), ``monte_carlo`` (the Monte Carlo column, if asked). Missing
    values are ``None``.
    """

    def __init__(self, data: Dict[str, Any]) -> None:
        flat = dict(data.get("statistics", {}))
        flat.update({k: v for k, v in data.items() if k != "statistics"})
        flat["methods"] = [_flat_method(m) for m in flat.get("methods", [])]
        outcome = flat.get("variance_outcome") or {}
        flat["variance_note"] = None if outcome.get("status", "value") == "value" else outcome.get("reason")
        self._data = flat
        self._raw = data

    @property
    def three_sigma(self) -> Optional[Tuple[float, float]]:
        """The bounds (M_y − 3σ_y, M_y + 3σ_y) (two-sided probability 0.9973 for a Gaussian output)."""
        lo, hi = self._data.get("lower_3sigma"), self._data.get("upper_3sigma")
        return None if lo is None or hi is None else (lo, hi)

    def method(self, name: str) -> Dict[str, Any]:
        """The entry of ``methods`` for ``name`` ("lyapunov", "integral-table" or "quadrature"; "lyapunov
        (delays)" for delayed inputs): ``status``, ``value`` (None without one), ``error_estimate``,
        ``rel_diff``, ``reason``."""
        for m in self._data.get("methods", []):
            if m.get("method") == name:
                return dict(m)
        raise KeyError(f"no variance method {name!r}; methods: {[m.get('method') for m in self.methods]}")

    def to_dict(self) -> Dict[str, Any]:
        """The output's section of the report as the library serialises it (statistics nested)."""
        return copy.deepcopy(self._raw)

    def __repr__(self) -> str:
        sigma = self._data.get("sigma")
        s = "infinite/undefined" if sigma is None else f"{sigma:.6g} {self._data.get('unit', '')}"
        return f"<stochvib.OutputResult {self._data.get('name')!r}: sigma = {s}>"


class AnalysisResult(Report):
    """The ``stochvib analyze`` report of a scenario: one :class:`OutputResult` per reported output.

    ``result["travel"]`` or ``result.outputs[2]`` give an output; ``result.sigma`` is a dict name → σ;
    ``to_dict()`` is the whole report (as ``stochvib analyze --json``); ``str(result)`` the CLI text.
    """

    def __init__(self, data: Dict[str, Any], text: str) -> None:
        super().__init__(data, text)
        self._outputs = [OutputResult(o) for o in data.get("outputs", [])]

    @property
    def outputs(self) -> List[OutputResult]:
        """The reported outputs, in order."""
        return list(self._outputs)

    @property
    def output_names(self) -> List[str]:
        """The names of the reported outputs."""
        return [o.name for o in self._outputs]

    def __getitem__(self, key: Any) -> OutputResult:
        if isinstance(key, str):
            for o in self._outputs:
                if o.name == key:
                    return o
            raise KeyError(f"no output {key!r}; outputs: {self.output_names}")
        return self._outputs[key]

    def __iter__(self) -> Iterator[OutputResult]:
        return iter(self._outputs)

    def __len__(self) -> int:
        return len(self._outputs)

    def _by_name(self, field: str) -> Dict[str, Any]:
        return {o.name: o._data.get(field) for o in self._outputs}

    @property
    def sigma(self) -> Dict[str, Optional[float]]:
        """σ of every output (None when infinite or undefined)."""
        return self._by_name("sigma")

    @property
    def mean(self) -> Dict[str, Optional[float]]:
        """Mean of every output."""
        return self._by_name("mean")

    @property
    def three_sigma(self) -> Dict[str, Optional[Tuple[float, float]]]:
        """3σ bounds of every output."""
        return {o.name: o.three_sigma for o in self._outputs}

    @property
    def zero_upcrossing_rate(self) -> Dict[str, Optional[float]]:
        """ν₀⁺ of every output, per second (per metre along a road)."""
        return self._by_name("zero_upcrossing_rate")


class RunResult(Report):
    """A finished Monte Carlo run: the HDF5 file ``path`` (readable by h5py) and its statistics.

    ``statistics`` is a dict output → statistic name ("mean", "variance", "sigma", "sigma_discrete") → dict
    with ``estimate``, ``lower``, ``upper``, ``confidence``, ``analytic``, ``covers``, ``unit``, ``method``.
    ``to_dict()`` is the run summary as ``stochvib simulate --json`` prints it; ``str()`` the CLI text.
    ``step`` says whether Δt and the duration were given or suggested (and why).
    """

    def __init__(self, data: Dict[str, Any], text: str, step: str) -> None:
        super().__init__(data, text)
        self.step = step

    @property
    def path(self) -> Path:
        """The finished run file."""
        return Path(self._data["path"])

    @property
    def statistics(self) -> Dict[str, Dict[str, Dict[str, Any]]]:
        """Per output, per statistic: estimate with its interval and the analytic value."""
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

    def __repr__(self) -> str:
        return (
            f"<stochvib.RunResult {str(self.path)!r}: {self._data.get('n_realizations')} realizations, "
            f"route {self._data.get('route')}>"
        )


def _flat_method(m: Dict[str, Any]) -> Dict[str, Any]:
    """A method entry with its outcome merged in: value and error estimate (None when there is none), status
    and reason."""
    out: Dict[str, Any] = {"method": m.get("method"), "value": None, "error_estimate": None, "reason": None}
    out.update(m.get("outcome") or {})
    out.update({k: v for k, v in m.items() if k not in ("outcome", "method")})
    return out


def _isfinite(x: Any) -> bool:
    return isinstance(x, float) and math.isfinite(x)
