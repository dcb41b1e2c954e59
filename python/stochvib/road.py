"""Road profiles: the International Roughness Index of a measured track, its expectation for a road
spectrum, and the ISO 8608 class of a level G_d(n₀).

Examples
--------
>>> import stochvib
>>> stochvib.road.iso8608_class(256e-6)  # G_d(0.1 cycles/m) = 256·10⁻⁶ m³: the middle of class C
'C'
>>> 6.0 < stochvib.road.expected_iri(stochvib.Spectrum.iso8608("C")).m_per_km < 12.3
True
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Tuple, Union

import numpy.typing as npt

from . import _stochvib
from ._stochvib import Spectrum

__all__ = ["iri", "Iri", "expected_iri", "ExpectedIri", "iso8608_class"]


@dataclass(frozen=True)
class Iri:
    """The IRI of one track: ``m_per_km`` (m/km = mm/m), the moving average (``moving_average_samples``
    over ``moving_average_base_m``), the golden car's ``steps`` and the evaluated ``length_m``."""

    m_per_km: float
    moving_average_samples: int
    moving_average_base_m: float
    steps: int
    length_m: float


@dataclass(frozen=True)
class ExpectedIri:
    """E[IRI] of a road spectrum: ``m_per_km`` (with the 250 mm moving average), without it, the σ of the
    golden car's relative velocity (m/s) and the band integrated over (cycles/m)."""

    m_per_km: float
    without_moving_average_m_per_km: float
    sigma_relative_velocity_m_s: float
    band_cycles_per_m: Tuple[float, float]


def iri(z: npt.ArrayLike, step: Union[float, str]) -> Iri:
    """The International Roughness Index of one track (ASTM E1926: the golden quarter car at 80 km/h,
    250 mm moving average; Sayers 1995).

    Parameters
    ----------
    z : array_like, 1-D
        Elevations in m, equally spaced.
    step : float or str
        The spacing in m, or with a unit ("50 mm"); at most 11 m (ASTM asks for ≤ 0.25 m).

    Returns
    -------
    Iri

    Examples
    --------
    A constant 2 % grade has no roughness:

    >>> import numpy as np
    >>> from stochvib import road
    >>> abs(road.iri(0.02 * 0.05 * np.arange(2000), "5 cm").m_per_km) < 1e-9
    True
    """
    return Iri(**_stochvib.iri(z, step))


def expected_iri(spectrum: Spectrum) -> ExpectedIri:
    """The expected IRI of a spatial road spectrum (``stochvib iri SPECTRUM``)."""
    d = _stochvib.expected_iri(spectrum)
    d["band_cycles_per_m"] = tuple(d["band_cycles_per_m"])
    return ExpectedIri(**d)


def iso8608_class(g0: Union[float, str]) -> str:
    """The ISO 8608 class "A" … "H" of a road whose G_d(n₀ = 0.1 cycles/m) is ``g0`` (m³, or with a unit);
    a level on a class limit belongs to the rougher class."""
    return _stochvib.iso8608_class(g0)
