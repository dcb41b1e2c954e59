"""Fatigue of random stresses: rainflow counting of an array (ASTM E1049) and the spectral methods
(narrow band, Wirsching–Light, Dirlik, Zhao–Baker, Tovo–Benasciutti) from a one-sided density given as
arrays.

Examples
--------
>>> from stochvib import fatigue
>>> c = fatigue.rainflow([0.0, 4.0, 2.0, 5.0, -1.0])  # 4→2 closes a cycle; 0→5→−1 is the residue
>>> c.range.tolist(), c.count.tolist()
([2.0, 5.0, 6.0], [1.0, 0.5, 0.5])
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any, Dict, List, Optional, Union

import numpy as np
import numpy.typing as npt

from . import _stochvib

__all__ = ["rainflow", "Cycles", "spectral", "SpectralFatigue", "MethodEstimate"]


@dataclass(frozen=True, repr=False)
class Cycles:
    """Rainflow cycles as arrays (one element per cycle, in the order they close; the residue last, as half
    cycles).

    Attributes
    ----------
    range, amplitude, mean : numpy.ndarray of float64
        ΔS = |x_e − x_s|, S_a = ΔS/2 and (x_s + x_e)/2, in the signal's unit.
    count : numpy.ndarray of float64
        1.0 for a full cycle, 0.5 for a half cycle.
    start, end : numpy.ndarray of int64
        Sample indices of the two turning points.
    """

    range: npt.NDArray[np.float64]
    amplitude: npt.NDArray[np.float64]
    mean: npt.NDArray[np.float64]
    count: npt.NDArray[np.float64]
    start: npt.NDArray[np.int64]
    end: npt.NDArray[np.int64]

    def damage(self, *, k: Union[float, str], c: Union[float, str], unit: str = "Pa") -> float:
        """Palmgren–Miner damage Σ nᵢ S_aᵢ^k / C of the S–N curve N·S_a^k = C (amplitudes, no endurance
        limit).

        Parameters
        ----------
        k : float, keyword-only
            The slope of the S–N curve, > 0 (a number; a dimensionless string "3" also).
        c : float or str, keyword-only
            C in unit^k, > 0: a number, or a string with a unit when k is an integer ("1e12 MPa^3" with
            ``unit="MPa"`` is 1e12), as for :func:`spectral`.
        unit : str, keyword-only
            The stress unit of the counted signal (of the amplitudes): "Pa" (default), "MPa", "N", ...

        Returns
        -------
        float
            The damage D (no unit; failure at D = 1).

        Raises
        ------
        InvalidInputError
            k or C not finite and > 0.
        UnitError
            A ``c`` string of another dimension than unit^k.

        Examples
        --------
        The amplitudes in MPa: C as the string "8 MPa^3" is the number 8.

        >>> from stochvib import fatigue
        >>> cycles = fatigue.rainflow([0.0, 2.0, -2.0, 2.0, 0.0])
        >>> cycles.damage(k=3, c="8 MPa^3", unit="MPa") == cycles.damage(k=3, c=8.0)
        True
        """
        k, c = _stochvib.sn_curve(k=k, c=c, unit=unit)
        return float(np.sum(self.count * self.amplitude**k) / c)

    def to_dict(self) -> Dict[str, List[Any]]:
        """The columns as lists."""
        return {k: getattr(self, k).tolist() for k in ("range", "amplitude", "mean", "count", "start", "end")}

    def to_dataframe(self) -> Any:
        """One row per cycle (pandas)."""
        import pandas as pd

        return pd.DataFrame({k: getattr(self, k) for k in ("range", "amplitude", "mean", "count", "start", "end")})

    def __len__(self) -> int:
        return len(self.range)

    def __repr__(self) -> str:
        full = int(np.sum(self.count == 1.0))
        half = len(self) - full
        top = f"{self.range.max():.6g}" if len(self) else "—"
        return f"Cycles: {full} full, {half} half; largest range {top}"


def rainflow(x: npt.ArrayLike) -> Cycles:
    """Rainflow cycles of a 1-D signal (ASTM E1049-85 four-point method; the residue counted as half
    cycles).

    Parameters
    ----------
    x : array_like, 1-D
        The signal (any unit); non-finite values raise :class:`InvalidInputError`.

    Returns
    -------
    Cycles

    Examples
    --------
    >>> from stochvib import fatigue
    >>> fatigue.rainflow([1.0, 4.0]).amplitude.tolist()
    [1.5]
    """
    return Cycles(**_stochvib.rainflow(x))


@dataclass(frozen=True)
class MethodEstimate:
    """One spectral method's estimate: ``method`` (its identifier), ``name`` (with its reference),
    ``damage_rate`` (1/s) and ``life`` (s; ``inf`` when the damage rate is 0: every amplitude below the
    endurance limit)."""

    method: str
    name: str
    damage_rate: float
    life: float


@dataclass(frozen=True, repr=False)
class SpectralFatigue:
    """The estimates of every spectral method for one stress density and S–N curve."""

    estimates: List[MethodEstimate]

    def __getitem__(self, method: str) -> MethodEstimate:
        for e in self.estimates:
            if e.method == method:
                return e
        raise KeyError(f"no method {method!r}; methods: {[e.method for e in self.estimates]}")

    def to_dict(self) -> List[Dict[str, Any]]:
        return [dict(e.__dict__) for e in self.estimates]

    def to_dataframe(self) -> Any:
        import pandas as pd

        return pd.DataFrame(self.to_dict())

    def __repr__(self) -> str:
        rows = [f"{'method':<24} {'damage rate (1/s)':>18} {'life (s)':>12}"]
        rows += [f"{e.method:<24} {e.damage_rate:>18.6e} {e.life:>12.6e}" for e in self.estimates]
        return "\n".join(rows)


def spectral(
    f: npt.ArrayLike,
    G: npt.ArrayLike,
    *,
    k: Union[float, str],
    c: Union[float, str],
    endurance_limit: Union[float, str, None] = None,
    unit: str = "Pa",
) -> SpectralFatigue:
    """Expected fatigue damage rate and life of a stationary Gaussian stress by every spectral method.

    Parameters
    ----------
    f : array_like, 1-D
        Frequencies in Hz, increasing (the moments are trapezoidal sums over them).
    G : array_like, 1-D
        The ONE-SIDED density G(f) of the stress, unit²/Hz (``scipy.signal.welch``'s; from a
        :class:`Spectrum`, ``spectrum.density(f=f)``).
    k : float, keyword-only
        The slope of the S–N curve N·S_a^k = C, S_a the amplitude (a number; a dimensionless string "3"
        also).
    c : float or str, keyword-only
        C in unit^k: a number, or a string with a unit when k is an integer ("1e30 MPa^3" with ``unit="Pa"``
        is 1e48).
    endurance_limit : float or str, keyword-only, optional
        Amplitudes below it do no damage: a number in ``unit`` or a string ("30 MPa").
    unit : str, keyword-only
        The stress unit of ``G`` (unit²/Hz) and of the numbers: "Pa" (default), "MPa", "N", ... Strings are
        converted into it; one of another dimension raises :class:`UnitError` naming the argument.

    Returns
    -------
    SpectralFatigue
        ``result["NarrowBand"]``, ``result["Dirlik"]``, ...

    Examples
    --------
    Narrow band: D/T = ν₀⁺ (√2 σ)^k Γ(1 + k/2) / C:

    >>> import math, numpy as np
    >>> from stochvib import fatigue
    >>> f = np.linspace(99.0, 101.0, 201)
    >>> r = fatigue.spectral(f, np.full_like(f, 0.5), k=3.0, c=1e12)  # σ² = 1
    >>> nb = r["NarrowBand"].damage_rate
    >>> round(nb / (100.0 * 2**1.5 * math.gamma(2.5) / 1e12), 3)
    1.0

    The same curve with units, the stress in MPa:

    >>> r2 = fatigue.spectral(f, np.full_like(f, 0.5), k=3, c="1e12 MPa^3", unit="MPa")
    >>> round(r2["NarrowBand"].damage_rate / nb, 12)
    1.0
    """
    rows = _stochvib.spectral_fatigue(f, G, k=k, c=c, endurance_limit=endurance_limit, unit=unit)
    # an unlimited life travels as JSON null
    return SpectralFatigue([MethodEstimate(**{**e, "life": math.inf if e["life"] is None else e["life"]}) for e in rows])
