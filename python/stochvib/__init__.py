"""stochvib: stochastic vibration and random-road analysis of machines, from Python.

Spectral densities of random roads and loads (:class:`Spectrum`), linear models of machines
(:class:`System`), and the statistics of their responses computed three ways — exact Lyapunov covariance,
the closed-form integral table, adaptive quadrature — (:func:`analyze`), and by seeded Monte Carlo runs
stored in HDF5 (:func:`simulate`).

Conventions (the same as the Rust library and the command-line tool):

* every spectral density is the TWO-SIDED density in ANGULAR frequency S(ω), ω in rad/s (rad/m for road
  profiles), with variance D = ∫_{-∞}^{∞} S(ω) dω; ``Spectrum.density(x, convention=...)`` converts to
  "one-sided-angular" G(ω) = 2S, "one-sided-cyclic" G(f) = 4πS(2πf) (f in Hz or cycles/m, scipy's
  ``welch`` convention) and "engineering" Ŝ = 2πS;
* frequencies: ω in rad/s, f in Hz, n in cycles/m; every other quantity in SI units; strings with units
  ("70 kN/m") are accepted where scenario files accept them (:meth:`System.model`);
* polynomial coefficients in ascending powers (of ω² for rational spectra, of s for transfer functions),
  unless ``order="descending"`` is given.

Errors are :class:`StochvibError` subclasses (see :mod:`stochvib.errors`) with the command-line tool's
messages.
"""

from __future__ import annotations

import os
from typing import Any, Callable, Dict, Literal, Optional, Sequence, Tuple, Union

from . import errors, linalg
from ._stochvib import ISO_BAND, Scenario, Spectrum, System, __version__
from .errors import (
    DivergentError,
    FileError,
    InvalidInputError,
    NotApplicableError,
    NumericalError,
    StochvibError,
    StochvibWarning,
)
from .results import AnalysisResult, OutputResult, Report, RunResult

__all__ = [
    "Spectrum",
    "System",
    "Scenario",
    "analyze",
    "simulate",
    "AnalysisResult",
    "OutputResult",
    "RunResult",
    "Report",
    "StochvibError",
    "InvalidInputError",
    "NotApplicableError",
    "DivergentError",
    "NumericalError",
    "FileError",
    "StochvibWarning",
    "ISO_BAND",
    "linalg",
    "errors",
    "__version__",
]

PathLike = Union[str, "os.PathLike[str]"]
Input = Union[Spectrum, str, "os.PathLike[str]", Sequence[Spectrum]]


def _scenario(
    subject: Union[Scenario, System, PathLike],
    input: Optional[Input],
    scenario_kw: Dict[str, Any],
    spectra_dir: Optional[PathLike],
) -> Scenario:
    if isinstance(subject, Scenario):
        if input is not None or scenario_kw:
            raise InvalidInputError(
                "a Scenario already has its input and options: pass input=/speed=/... only with a System"
            )
        return subject
    if isinstance(subject, System):
        if input is None:
            raise InvalidInputError("analyzing a System needs input= (a Spectrum, or one per system input)")
        return Scenario.from_system(subject, input, **scenario_kw)
    if isinstance(subject, (str, os.PathLike)):
        if input is not None or scenario_kw:
            raise InvalidInputError("a scenario file has its input and options: pass input=/speed=/... only with a System")
        return Scenario.load(subject, spectra_dir=spectra_dir)
    raise InvalidInputError(f"expected a Scenario, a System or a scenario file path, not {type(subject).__name__}")


def analyze(
    subject: Union[Scenario, System, PathLike],
    input: Optional[Input] = None,
    *,
    speed: Optional[float] = None,
    positions: Optional[Sequence[float]] = None,
    mean: Optional[Union[float, Sequence[float]]] = None,
    outputs: Optional[Sequence[str]] = None,
    band_rad_s: Optional[Tuple[float, float]] = None,
    duration_s: Optional[float] = None,
    levels: Optional[Dict[str, Sequence[float]]] = None,
    monte_carlo: Optional[int] = None,
    seed: int = 1,
    dt: Optional[float] = None,
    duration: Optional[float] = None,
    progress: Union[bool, Callable[[int, int], Any]] = True,
    spectra_dir: Optional[PathLike] = None,
    rel_tol: Optional[float] = None,
    max_subintervals: Optional[int] = None,
    max_half_periods: Optional[int] = None,
) -> Union[AnalysisResult, Report]:
    """Response statistics of a scenario, or of ``system`` driven by ``input`` (the ``stochvib analyze`` report).

    ``subject``: a :class:`Scenario`, a scenario file path, or a :class:`System` with ``input`` — one
    :class:`Spectrum` or a catalogue name such as "iso8608-c" (one process; a spatial road spectrum needs
    ``speed`` in m/s; several inputs fed by
    one track need ``positions`` in m unless the system comes from the catalogue or a scenario file) or a list
    with one spectrum per input (independent processes). ``mean``: the process mean (its unit).

    Per output (``outputs``: names, default all): mean, σ, 3σ bounds, every variance method (Lyapunov,
    integral table, quadrature) with its value, error estimate and relative difference, spectral moments,
    Rice zero up-crossing rate ν₀⁺ (1/s), bandwidth, expected largest peak in ``duration_s`` (default 3600 s),
    crossing rates of ``levels`` ({output: [levels in the output's SI unit]}), σ in ``band_rad_s``
    (ω₁, ω₂ in rad/s). An infinite variance is reported, not raised: ``sigma`` is None,
    ``variance_outcome["status"]`` is "divergent" and ``variance_note`` holds the diagnosis.

    ``monte_carlo=N`` adds a Monte Carlo column (N seeded realizations, time step ``dt`` s and realization
    ``duration`` s suggested when not given, ``progress`` bar; Ctrl-C stops it).

    ``rel_tol`` (default 1e-10), ``max_subintervals`` (2000) and ``max_half_periods`` (10 000) set the
    effort of the quadratures, over the scenario's ``[analysis.quadrature]`` (the CLI's ``--rel-tol``,
    ``--max-subintervals``, ``--max-half-periods``). A quadrature that does not converge is reported, not
    raised: its method entry has ``status`` "not-converged", the estimate and which option to raise.
    """
    kw: Dict[str, Any] = {}
    for k, v in (
        ("speed", speed),
        ("positions", positions),
        ("mean", mean),
        ("outputs", outputs),
        ("band_rad_s", band_rad_s),
        ("duration_s", duration_s),
        ("levels", levels),
    ):
        if v is not None:
            kw[k] = v
    sc = _scenario(subject, input, kw, spectra_dir)
    return sc.analyze(
        monte_carlo=monte_carlo,
        seed=seed,
        dt=dt,
        duration=duration,
        progress=progress,
        rel_tol=rel_tol,
        max_subintervals=max_subintervals,
        max_half_periods=max_half_periods,
    )


def simulate(
    subject: Union[Scenario, System, PathLike],
    realizations: int,
    path: PathLike,
    *,
    input: Optional[Input] = None,
    speed: Optional[float] = None,
    positions: Optional[Sequence[float]] = None,
    mean: Optional[Union[float, Sequence[float]]] = None,
    outputs: Optional[Sequence[str]] = None,
    dt: Optional[float] = None,
    duration: Optional[float] = None,
    seed: int = 1,
    shard_size: int = 50,
    store_raw: bool = False,
    compression: str = "none",
    route: Literal["auto", "exact", "spectral"] = "auto",
    confidence: float = 0.95,
    overwrite: bool = False,
    progress: Union[bool, Callable[[int, int], Any]] = True,
    spectra_dir: Optional[PathLike] = None,
) -> RunResult:
    """A seeded Monte Carlo run written to the HDF5 file ``path`` (``stochvib simulate``); returns a
    :class:`RunResult` with the file path and the statistics (σ with its interval against the analytic σ).

    ``subject`` and ``input``/``speed``/``positions``/``mean``/``outputs`` as in :func:`analyze`.
    ``realizations`` ≥ 2; ``dt`` (s) and ``duration`` (s per realization) suggested from the system when not
    given; realization i uses the random stream (seed, i), so results do not depend on threads or shards.
    The run is written to ``path.tmp`` and renamed when complete: Ctrl-C (checked after every shard of
    ``shard_size`` realizations) raises KeyboardInterrupt and leaves only the ``.tmp``, which the same call
    resumes. ``store_raw`` keeps every realization (``compression``: "none", "fast", "best", "deflate:N");
    ``route``: "auto", "exact" (rational inputs without delays) or "spectral"; ``confidence`` of the
    intervals; ``progress``: True (a bar), False or a callable(done, total). The GIL is released.
    """
    kw: Dict[str, Any] = {}
    for k, v in (("speed", speed), ("positions", positions), ("mean", mean), ("outputs", outputs)):
        if v is not None:
            kw[k] = v
    sc = _scenario(subject, input, kw, spectra_dir)
    return sc.simulate(
        realizations,
        path,
        dt=dt,
        duration=duration,
        seed=seed,
        shard_size=shard_size,
        store_raw=store_raw,
        compression=compression,
        route=route,
        confidence=confidence,
        overwrite=overwrite,
        progress=progress,
    )
