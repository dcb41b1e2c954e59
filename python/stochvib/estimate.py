"""Estimates from records: Welch's spectral density with χ² confidence intervals.

Examples
--------
>>> import numpy as np, stochvib
>>> x = np.random.default_rng(1).normal(size=8192)  # unit white noise sampled at 100 Hz
>>> f, G = stochvib.welch(x, 100.0, nperseg=512)    # unpacks as scipy.signal.welch's (f, Pxx)
>>> round(float(np.mean(G[1:-1])) * 50.0, 1)        # σ² = ∫G df = G·f_N: G ≈ 1/50 per Hz
1.0
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any, Dict, Iterator, Union

import numpy as np
import numpy.typing as npt

from . import _stochvib

__all__ = ["welch", "WelchEstimate"]


@dataclass(frozen=True, repr=False)
class WelchEstimate:
    """Welch's estimate: ``f`` (Hz), ``Pxx`` the one-sided density G(f) (unit²/Hz, scipy.signal.welch's
    "density" scaling), its ``lower`` and ``upper`` confidence bounds (χ² with Welch's equivalent degrees of
    freedom ``dof``, halved at f = 0 and Nyquist), the number of ``segments`` and the ``confidence``.

    ``f, Pxx = welch(...)`` unpacks as scipy's pair."""

    f: npt.NDArray[np.float64]
    Pxx: npt.NDArray[np.float64]
    lower: npt.NDArray[np.float64]
    upper: npt.NDArray[np.float64]
    segments: int
    dof: float
    confidence: float

    def __iter__(self) -> Iterator[npt.NDArray[np.float64]]:
        return iter((self.f, self.Pxx))

    def to_dict(self) -> Dict[str, Any]:
        return {k: (v.tolist() if isinstance(v, np.ndarray) else v) for k, v in self.__dict__.items()}

    def to_dataframe(self) -> Any:
        """One row per frequency: f, Pxx, lower, upper (pandas)."""
        import pandas as pd

        return pd.DataFrame({"f": self.f, "Pxx": self.Pxx, "lower": self.lower, "upper": self.upper})

    def __repr__(self) -> str:
        return (
            f"WelchEstimate: {self.f.size} frequencies 0–{self.f[-1]:.6g} Hz, {self.segments} segments, "
            f"{self.dof:.4g} degrees of freedom, {self.confidence:.0%} intervals"
        )


def welch(
    x: npt.ArrayLike, fs: Union[float, str], *, nperseg: int = 256, detrend: bool = True, confidence: float = 0.95
) -> WelchEstimate:
    """Welch's averaged-periodogram density of a record, with confidence intervals.

    Parameters
    ----------
    x : array_like, 1-D
        The record, sampled at ``fs``.
    fs : float or str
        Sample rate, Hz, or a string: "200 Hz", "200 1/s" and "200 S/s" are all 200 samples per second.
    nperseg : int, keyword-only
        Segment length M (even, ≥ 4); Hann window, 50 % overlap (scipy.signal.welch's defaults).
    detrend : bool, keyword-only
        Remove each segment's mean (scipy's ``detrend="constant"``, the default) or not (``False``).
    confidence : float, keyword-only
        Of the intervals, in (0, 1).

    Returns
    -------
    WelchEstimate
        ``f, Pxx = welch(x, fs)`` is ``scipy.signal.welch(x, fs, nperseg=nperseg)``.

    Raises
    ------
    InvalidInputError
        An odd or too short ``nperseg``, a record shorter than one segment, a bad ``confidence``.
    UnitError
        A sample-rate string with an unknown unit or another dimension ("200 rad/s").
    """
    d = _stochvib.welch(x, fs, nperseg=nperseg, detrend=detrend, confidence=confidence)
    return WelchEstimate(d["f"], d["G"], d["lower"], d["upper"], d["segments"], d["dof"], confidence)
