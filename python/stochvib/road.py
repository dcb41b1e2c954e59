"""Road profiles: the analysis of measured tracks given as arrays (spatial density with χ² intervals, ISO 8608
fits and class, IRI, the coherence of two tracks: ``stochvib road`` on arrays), the International Roughness
Index of a track, its expectation for a road spectrum, and the ISO 8608 class of a level G_d(n₀).

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
from typing import Any, Dict, List, Mapping, Optional, Sequence, Tuple, Union

import numpy as np
import numpy.typing as npt

from . import _stochvib
from ._stochvib import Spectrum
from .errors import FileError, InvalidInputError

__all__ = [
    "iri",
    "Iri",
    "expected_iri",
    "ExpectedIri",
    "iso8608_class",
    "analyze_profile",
    "ProfileAnalysis",
    "TrackAnalysis",
    "IsoFit",
    "TrackCoherence",
    "coherence",
]


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
    """The expected IRI of a spatial road spectrum (``stochvib iri SPECTRUM``).

    Parameters
    ----------
    spectrum : Spectrum
        A spatial (road) spectrum, elevation in m.

    Returns
    -------
    ExpectedIri
        ``m_per_km`` (the IRI, m/km), ``without_moving_average_m_per_km``, ``sigma_relative_velocity_m_s``,
        ``band_cycles_per_m``.

    Raises
    ------
    NotApplicableError
        A temporal spectrum.

    Examples
    --------
    >>> import stochvib
    >>> from stochvib import road
    >>> road.expected_iri(stochvib.Spectrum.iso8608("C")).m_per_km > road.expected_iri(stochvib.Spectrum.iso8608("B")).m_per_km
    True
    """
    d = _stochvib.expected_iri(spectrum)
    d["band_cycles_per_m"] = tuple(d["band_cycles_per_m"])
    return ExpectedIri(**d)


def iso8608_class(g0: Union[float, str]) -> str:
    """The ISO 8608 class "A" … "H" of a road whose G_d(n₀ = 0.1 cycles/m) is ``g0``; a level on a class
    limit belongs to the rougher class.

    Parameters
    ----------
    g0 : float or str
        G_d(n₀) in m³ ("256e-6 m^3").

    Returns
    -------
    str
        "A" … "H".

    Raises
    ------
    UnitError
        A string of another dimension.
    InvalidInputError
        g0 ≤ 0 or not finite.

    Examples
    --------
    >>> from stochvib import road
    >>> road.iso8608_class(256e-6), road.iso8608_class("256e-6 m^3")  # the geometric mean of class C
    ('C', 'C')
    """
    return _stochvib.iso8608_class(g0)


@dataclass(frozen=True)
class IsoFit:
    """An ISO 8608 fit G_d(n) = G_d(n₀)(n/n₀)^−w, n₀ = 0.1 cycles/m, by least squares on log Ĝ_d: ``mode``
    ("fixed w = 2" or "free w"), ``g0_m3`` with its ``g0_interval``, ``waviness`` with its
    ``waviness_interval`` (the fixed value twice when fixed), the ISO ``road_class``, the fitted ``band``
    (cycles/m), the ``reduced_chi2`` (≈ 1 for a power-law road) and ``fit_p_value``, the probability of a
    fit this poor or worse for a road that follows the power law (below 1e-6 the class is the level of
    G_d at n₀ only)."""

    mode: str
    g0_m3: float
    g0_interval: Tuple[float, float]
    waviness: float
    waviness_interval: Tuple[float, float]
    road_class: str
    band: Tuple[float, float]
    reduced_chi2: float
    fit_p_value: float


@dataclass(frozen=True, repr=False)
class TrackAnalysis:
    """One track: ``name``, ``sigma_m`` (σ of the detrended elevation), ``iri_m_per_km`` (of the track as
    given), the Welch density ``G_d`` (m³, one-sided in cycles/m) at ``n`` (cycles/m) with its χ² interval
    ``lower``, ``upper``, and the ISO 8608 ``fits`` (w = 2 fixed, then w free)."""

    name: str
    sigma_m: float
    iri_m_per_km: float
    n: npt.NDArray[np.float64]
    G_d: npt.NDArray[np.float64]
    lower: npt.NDArray[np.float64]
    upper: npt.NDArray[np.float64]
    fits: Tuple[IsoFit, ...]

    @property
    def road_class(self) -> str:
        """The ISO 8608 class of the fit with w = 2 (the standard's definition)."""
        return self.fits[0].road_class

    def __repr__(self) -> str:
        f = self.fits[0]
        return (
            f"track {self.name}: sigma {self.sigma_m:.6e} m, IRI {self.iri_m_per_km:.4f} m/km, "
            f"G_d(n0) = {f.g0_m3:.4e} m^3 (w = 2), class {f.road_class}, {self.n.size} bins"
        )


@dataclass(frozen=True, repr=False)
class TrackCoherence:
    """The squared coherence γ̂²(n) of two tracks (``tracks``) at ``n`` (cycles/m) with its Fisher-z interval
    ``lower``, ``upper``."""

    tracks: Tuple[str, str]
    n: npt.NDArray[np.float64]
    gamma2: npt.NDArray[np.float64]
    lower: npt.NDArray[np.float64]
    upper: npt.NDArray[np.float64]

    def __repr__(self) -> str:
        return f"coherence of {self.tracks[0]} and {self.tracks[1]}: {self.n.size} bins"


@dataclass(frozen=True, repr=False)
class ProfileAnalysis:
    """The analysis of a profile (``stochvib road`` on arrays): ``tracks`` (:class:`TrackAnalysis`, in order;
    ``result["left"]`` by name), ``coherence`` of the first two tracks (:class:`TrackCoherence`, or None for
    one track), the sampling (``step_m``, ``samples``, ``length_m``), the Welch ``segment_len``,
    ``segments`` and ``dof``, the ``detrend`` and the ``confidence`` of the intervals."""

    tracks: Tuple[TrackAnalysis, ...]
    coherence: Optional[TrackCoherence]
    step_m: float
    samples: int
    length_m: float
    segment_len: int
    segments: int
    dof: float
    detrend: str
    confidence: float
    _data: Dict[str, Any]

    def __getitem__(self, name: str) -> TrackAnalysis:
        for t in self.tracks:
            if t.name == name:
                return t
        raise KeyError(f"no track {name!r}; the tracks are {[t.name for t in self.tracks]}")

    def to_dict(self) -> Dict[str, Any]:
        """The data of ``stochvib road PROFILE --json`` (``file`` is ``"<arrays>"``)."""
        return dict(self._data)

    def to_dataframe(self) -> Any:
        """One row per track and bin: track, n, G_d, lower, upper (pandas)."""
        from .results import _dataframe

        return _dataframe(
            [
                {"track": t.name, "n": n, "G_d": g, "lower": lo, "upper": hi}
                for t in self.tracks
                for n, g, lo, hi in zip(t.n.tolist(), t.G_d.tolist(), t.lower.tolist(), t.upper.tolist())
            ]
        )

    def __repr__(self) -> str:
        head = (
            f"ProfileAnalysis: {self.samples} samples at {self.step_m:.6g} m ({self.length_m:.6g} m), Welch "
            f"segments of {self.segment_len}, K = {self.segments}, nu = {self.dof:.1f}, detrend {self.detrend}"
        )
        lines = [head] + [f"  {t!r}" for t in self.tracks]
        if self.coherence is not None:
            lines.append(f"  {self.coherence!r}")
        return "\n".join(lines)


def _columns(rows: List[Dict[str, Any]], *keys: str) -> List[npt.NDArray[np.float64]]:
    return [np.array([r[k] for r in rows], dtype=float) for k in keys]


def _fit(d: Dict[str, Any]) -> IsoFit:
    return IsoFit(
        d["waviness_mode"],
        d["g0_m3"],
        tuple(d["g0_interval"]),
        d["waviness"],
        tuple(d["waviness_interval"]),
        d["class"],
        tuple(d["band"]),
        d["reduced_chi2"],
        d["fit_p_value"],
    )


def _track(d: Dict[str, Any]) -> TrackAnalysis:
    n, g, lo, hi = _columns(d["density"], "n", "g_d", "lower", "upper")
    fits = tuple(_fit(f) for f in d["fits"])
    return TrackAnalysis(d["name"], d["sigma_m"], d["iri_m_per_km"], n, g, lo, hi, fits)


def _named_tracks(
    tracks: Union[npt.ArrayLike, Mapping[str, npt.ArrayLike]], names: Optional[Sequence[str]]
) -> List[Tuple[str, Any]]:
    if isinstance(tracks, Mapping):
        if names is not None:
            raise TypeError("names= is taken from the mapping's keys; pass one or the other")
        return [(str(k), v) for k, v in tracks.items()]
    if isinstance(tracks, (list, tuple)) and tracks and np.ndim(tracks[0]) == 1:
        rows = list(tracks)  # a sequence of tracks, maybe of different lengths (the library says so)
    else:
        z = np.asarray(tracks, dtype=float)
        rows = [z] if z.ndim == 1 else list(z)
    default = ["left", "right"] if len(rows) == 2 else [f"track{i}" for i in range(len(rows))]
    names = default if names is None else list(names)
    if len(names) != len(rows):
        raise InvalidInputError(f"names: {len(names)} names for {len(rows)} tracks", name="names")
    return list(zip(names, rows))


def analyze_profile(
    tracks: Union[npt.ArrayLike, Mapping[str, npt.ArrayLike]],
    step: Union[float, str],
    *,
    names: Optional[Sequence[str]] = None,
    segment: Optional[int] = None,
    detrend: str = "linear",
    confidence: float = 0.95,
) -> ProfileAnalysis:
    """The analysis of a road profile given as arrays, as ``stochvib road PROFILE.csv`` does for a file.

    Per track: the Welch estimate of the one-sided spatial density Ĝ_d(n) (m³ at n in cycles/m; Hann window,
    50 % overlap, the bins n = 0 and Nyquist left out) with its χ² interval, the ISO 8608 fits (w = 2 and w
    free; G_d(n₀) with its interval and the class) and the IRI; for two or more tracks the squared coherence
    of the first two with its Fisher-z interval.

    Parameters
    ----------
    tracks : array_like or mapping of str to array_like
        Elevations in m, equally spaced: a 1-D array (one track), a 2-D array (one track per row; two rows
        are named "left" and "right", more "track0", "track1", …) or a mapping name → 1-D array.
    step : float or str
        The spacing in m, or with a unit ("5 cm").
    names : sequence of str, keyword-only
        Names of the rows of a 2-D array.
    segment : int, keyword-only
        Welch segment length M in samples (even, ≥ 4, at most the record); default the largest power of two
        giving at least 8 half-overlapping segments.
    detrend : {"linear", "mean"}, keyword-only
        The trend removed before the densities and the coherence (the IRI uses the track as given).
    confidence : float, keyword-only
        Of the intervals, in (0, 1).

    Returns
    -------
    ProfileAnalysis

    Raises
    ------
    InvalidInputError
        Non-finite elevations, tracks of different lengths, a bad ``segment``, ``detrend`` or ``confidence``.
    FileError
        A track too short for an estimate or a fit (named by its column, the profile named ``<arrays>``).

    Examples
    --------
    A white track of unit variance at 0.1 m has G_d = 2Δx = 0.2 m³ at every n:

    >>> import numpy as np, stochvib
    >>> z = np.random.default_rng(1).normal(size=16384)
    >>> r = stochvib.road.analyze_profile(z, "10 cm", segment=256)
    >>> round(float(r.tracks[0].G_d.mean()), 2)
    0.2
    >>> bool(r.tracks[0].n[0] == 1 / (256 * 0.1)), r.coherence is None
    (True, True)
    """
    named = _named_tracks(tracks, names)
    d = _stochvib.road_profile(named, step, segment=segment, detrend=detrend, confidence=confidence)
    coh = None
    if d["coherence_tracks"] is not None:
        n, g2, lo, hi = _columns(d["coherence"], "n", "squared_coherence", "lower", "upper")
        coh = TrackCoherence(tuple(d["coherence_tracks"]), n, g2, lo, hi)
    return ProfileAnalysis(
        tuple(_track(t) for t in d["tracks"]),
        coh,
        d["step_m"],
        d["samples"],
        d["length_m"],
        d["segment_len"],
        d["segments"],
        d["dof"],
        d["detrend"],
        d["confidence"],
        d,
    )


def coherence(
    model: Mapping[str, Any],
    n: npt.ArrayLike,
    *,
    track_width: Union[float, str] = "1.5 m",
    squared: bool = False,
) -> Union[float, npt.NDArray[np.float64]]:
    """The coherence of two road tracks under a coherence model, as an array (``stochvib coherence --model``).

    Parameters
    ----------
    model : mapping
        The model as a scenario road's ``coherence`` table: ``{"kind": "dodds-robson", "waviness": 2}``
        (isotropic surface, Dodds & Robson 1973), ``{"kind": "ammon-bormann", ...}``, ``{"kind": "tabulated",
        ...}``, ``{"kind": "constant", "coherence_amplitude": 0.5}``.
    n : array_like
        Spatial frequencies, cycles/m (any shape).
    track_width : float or str, keyword-only
        The distance of the tracks, m (or with a unit).
    squared : bool, keyword-only
        Return γ²(n) = ρ(n)² instead of the amplitude ρ(n) (S_LR = ρ S for two tracks of density S).

    Returns
    -------
    float or ndarray
        ρ(n) (or γ²), shaped as ``n``.

    Raises
    ------
    InvalidInputError
        A bad argument; an unknown kind or a bad value of the model (named by its key).

    Examples
    --------
    The isotropic surface with w = 2 has ρ = x K₁(x), x = 2πnB:

    >>> import numpy as np
    >>> from scipy.special import k1
    >>> from stochvib import road
    >>> n = np.array([0.05, 0.1, 0.5])
    >>> x = 2 * np.pi * n * 1.5
    >>> bool(np.allclose(road.coherence({"kind": "dodds-robson", "waviness": 2}, n), x * k1(x), rtol=1e-9))
    True
    """
    try:
        rho = _stochvib.coherence_amplitude(dict(model), n, track_width=track_width)
    except FileError as e:  # the library names the model as the CLI's --model: name the dict's key instead
        if e.path != "--model":
            raise
        key = (e.key or "").split(".", 1)[-1]
        raise InvalidInputError(
            f"model[{key!r}] = {e.value}: {e.reason}", name=f"model.{key}", value=e.value, reason=e.reason
        ) from None
    out = rho * rho if squared else rho
    return float(out) if np.ndim(out) == 0 else out
