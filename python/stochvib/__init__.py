"""stochvib: stochastic vibration and random-road analysis of machines, from Python.

Spectral densities of random roads and loads (:class:`Spectrum`), linear models of machines
(:class:`System`), and the statistics of their responses computed three ways — exact Lyapunov covariance,
the closed-form integral table, adaptive quadrature — (:func:`analyze`), and by seeded Monte Carlo runs
stored in HDF5 (:func:`simulate`).

Conventions (those of scipy.signal where scipy has one):

* polynomial coefficients in DESCENDING powers (highest first) like ``scipy.signal`` and
  ``python-control``; ``order="ascending"`` takes them lowest first (the scenario files' order);
* angular frequency is ``omega=`` in rad/s (rad/m for road profiles), frequency is ``f=`` in Hz (cycles/m):
  hertz are never taken in an argument named ``omega``;
* every spectral density is the TWO-SIDED density in ANGULAR frequency S(ω), with variance
  D = ∫_{-∞}^{∞} S(ω) dω; ``Spectrum.density(f=...)`` gives the one-sided G(f) = 4πS(2πf) of
  ``scipy.signal.welch``;
* numpy arrays in and out, any shape; options are keyword-only;
* every other quantity in SI units; a string with a unit ("10.8 km/h", "70 kN/m") is accepted wherever a
  quantity is.

Errors are :class:`StochvibError` subclasses (see :mod:`stochvib.errors`) with the command-line tool's
messages. A table mapping scipy / python-control calls to stochvib's is in ``docs/python.md``.
"""

from __future__ import annotations

import os
from typing import TYPE_CHECKING, Any, Callable, Dict, List, Literal, Optional, Sequence, Tuple, Union

if TYPE_CHECKING:
    import numpy.typing as npt

from . import comfort, errors, estimate, fatigue, linalg, road
from .estimate import WelchEstimate, welch
from . import _stochvib
from ._stochvib import ISO_BAND, Scenario, Spectrum, System, __version__
from .errors import (
    DivergentError,
    FileError,
    InvalidInputError,
    NotApplicableError,
    NotConvergedError,
    NumericalError,
    StochvibError,
    StochvibWarning,
    UnitError,
)
from .results import (
    AnalysisResult,
    ExposureResult,
    LevelCrossing,
    OutputResult,
    Report,
    NonlinearOutput,
    NonlinearResult,
    NonlinearRunResult,
    OptimizeResult,
    KktCheck,
    ParetoFront,
    ParetoPoint,
    RunResult,
    SweepResult,
    TablesResult,
    TransientResult,
    TransientRunResult,
    VarianceMethod,
    VerdictTable,
)
from .reports import ReplayedOutput, ReplayResult, RunInfo, WorkdayAxis, WorkdayResult, WorkdayTask

__all__ = [
    "Spectrum",
    "System",
    "Scenario",
    "analyze",
    "analyze_nonlinear",
    "simulate",
    "simulate_nonlinear",
    "replay",
    "workday",
    "inspect",
    "merge",
    "merge_transient",
    "merge_sweep",
    "exposure",
    "ExposureResult",
    "welch",
    "WelchEstimate",
    "estimate",
    "comfort",
    "fatigue",
    "road",
    "AnalysisResult",
    "OutputResult",
    "VarianceMethod",
    "LevelCrossing",
    "TablesResult",
    "RunResult",
    "SweepResult",
    "NonlinearResult",
    "NonlinearOutput",
    "NonlinearRunResult",
    "OptimizeResult",
    "KktCheck",
    "ParetoFront",
    "ParetoPoint",
    "TransientResult",
    "TransientRunResult",
    "VerdictTable",
    "ReplayResult",
    "ReplayedOutput",
    "WorkdayResult",
    "WorkdayTask",
    "WorkdayAxis",
    "RunInfo",
    "Report",
    "ISO_BAND",
    "linalg",
    "errors",
    "__version__",
]
__all__ += errors.__all__  # StochvibError and its subclasses, StochvibWarning

PathLike = Union[str, "os.PathLike[str]"]
Quantity = Union[float, str]
"""A number (SI) or a string with a unit ("10.8 km/h")."""
SampleRate = Union[float, str]
"""Samples per second: a number (Hz) or a string ("200 Hz", "200 1/s", "200 S/s" are all 200)."""
Input = Union[Spectrum, str, "os.PathLike[str]", Sequence[Spectrum]]


def _given(**kw: Any) -> Dict[str, Any]:
    """The keyword arguments that were given (not None)."""
    return {k: v for k, v in kw.items() if v is not None}


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
    speed: Optional[Quantity] = None,
    positions: Optional[Sequence[Quantity]] = None,
    mean: Optional[Union[Quantity, Sequence[Quantity]]] = None,
    outputs: Optional[Sequence[str]] = None,
    band_rad_s: Optional[Tuple[Quantity, Quantity]] = None,
    duration_s: Optional[Quantity] = None,
    levels: Optional[Dict[str, Sequence[Quantity]]] = None,
    monte_carlo: Optional[int] = None,
    seed: int = 1,
    dt: Optional[Quantity] = None,
    duration: Optional[Quantity] = None,
    progress: Union[bool, Callable[[int, int], Any]] = True,
    spectra_dir: Optional[PathLike] = None,
    rel_tol: Optional[float] = None,
    max_subintervals: Optional[int] = None,
    max_half_periods: Optional[int] = None,
    coherence: Optional[Dict[str, Any]] = None,
    track_width: Optional[Quantity] = None,
    tracks: Optional[Sequence[Union[str, int]]] = None,
) -> AnalysisResult:
    """Response statistics of a linear model: a scenario, or ``system`` driven by ``input`` (the ``stochvib
    analyze`` report). A model with nonlinear elements is refused: :func:`analyze_nonlinear` analyses it.

    Quantities (``speed`` in m/s, ``positions`` in m, ``duration_s``, ``dt``, ``duration`` in s) are numbers
    in SI units or strings with a unit: ``analyze(car, road, speed="72 km/h")``.

    ``subject``: a :class:`Scenario`, a scenario file path, or a :class:`System` with ``input`` — one
    :class:`Spectrum` or a catalogue name such as "iso8608-c" (one process; a spatial road spectrum needs
    ``speed`` in m/s; several inputs fed by
    one track need ``positions`` in m unless the system comes from the catalogue or a scenario file) or a list
    with one spectrum per input (independent processes). ``mean``: the process mean (its unit; a number or a
    string such as "5 cm"), or one per process.

    Per output (``outputs``: names, default all): mean, σ, 3σ bounds, every variance method (Lyapunov,
    integral table, quadrature) with its value, error estimate and relative difference, spectral moments,
    Rice zero up-crossing rate ν₀⁺ (1/s), bandwidth, expected largest peak in ``duration_s`` (default 3600 s),
    crossing rates of ``levels`` ({output: [levels in the output's SI unit, or strings "3 cm"]}), σ in ``band_rad_s``
    (ω₁, ω₂ in rad/s, or unit strings: "1 Hz" is 2π rad/s). An infinite variance is reported, not raised: ``sigma`` is None,
    ``variance_outcome["status"]`` is "divergent" and ``variance_note`` holds the diagnosis.

    A road of two coherent tracks (left and right wheels, as a scenario file's ``[[input]] road``): ``input``
    the spatial spectrum of each track, ``coherence`` the coherence model between them (a dict as the file's
    ``coherence`` table, e.g. ``{"kind": "dodds-robson", "waviness": 2}``), ``track_width`` (m, default the
    model's), ``tracks`` ("left"/"right" per system input, default the model's layout) and ``positions`` (m
    behind the first contact: the wheelbase delays ℓ/v).

    ``monte_carlo=N`` adds a Monte Carlo column (N seeded realizations, time step ``dt`` s and realization
    ``duration`` s suggested when not given, ``progress`` bar; Ctrl-C stops it).

    ``rel_tol`` (default 1e-10), ``max_subintervals`` (2000) and ``max_half_periods`` (10 000) set the
    effort of the quadratures, over the scenario's ``[analysis.quadrature]`` (the CLI's ``--rel-tol``,
    ``--max-subintervals``, ``--max-half-periods``). A quadrature that does not converge is reported, not
    raised: its method entry has ``status`` "not-converged", the estimate and which option to raise.

    Parameters
    ----------
    subject : Scenario, System or path
        As above.
    input : Spectrum, str, os.PathLike or list of Spectrum, optional
        With a System only: the input process(es).
    speed : float or str, keyword-only, optional
        m/s or a speed string ("72 km/h"); needed by a spatial input.
    positions : list of float or str, keyword-only, optional
        m behind the first contact, one per system input.
    mean : float or str or list of them, keyword-only, optional
        The process mean(s) in the process's unit; default 0.
    outputs : list of str, keyword-only, optional
        Output names; default all.
    band_rad_s : (float or str, float or str), keyword-only, optional
        (ω₁, ω₂) in rad/s or frequency strings.
    duration_s : float or str, keyword-only, default 3600 s
    levels : dict of str to list of float or str, keyword-only, optional
        Levels in the output's SI unit.
    monte_carlo : int, keyword-only, optional
        N realizations (none by default).
    seed : int, keyword-only, default 1
    dt, duration : float or str, keyword-only, optional
        s or time strings; suggested when not given.
    progress : bool or callable, keyword-only, default True
        True: a bar; False: nothing; a callable(done, total).
    spectra_dir : str or os.PathLike, keyword-only, optional
        The spectrum catalogue directory.
    rel_tol : float, keyword-only, default 1e-10
    max_subintervals : int, keyword-only, default 2000
    max_half_periods : int, keyword-only, default 10 000
    coherence : dict, keyword-only, optional
    track_width : float or str, keyword-only, optional
        m.
    tracks : list of str or int, keyword-only, optional

    Returns
    -------
    AnalysisResult
        One :class:`OutputResult` per output; ``str()`` is the CLI's text, ``to_dict()`` its ``--json``.

    Raises
    ------
    DivergentError
        An unstable system (no stationary response), with the diagnosis and what to check.
    InvalidInputError, UnitError
        A bad argument (a spatial input without ``speed``, an unknown output, a bad unit); a model with
        nonlinear elements (the message names :func:`analyze_nonlinear`).
    NotApplicableError
        A file that is a deterministic model or a reference table (see :meth:`Scenario.tables`).

    Examples
    --------
    >>> import stochvib
    >>> car = stochvib.System.model("quarter-car", sprung_mass="300 kg", unsprung_mass="40 kg",
    ...     suspension_stiffness="20 kN/m", suspension_damping="1.5 kN*s/m", tyre_stiffness="200 kN/m")
    >>> r = stochvib.analyze(car, stochvib.Spectrum.iso8608("C"), speed="72 km/h")
    >>> r["travel"].unit, r["travel"].sigma > 0
    ('m', True)
    """
    kw = _given(speed=speed, positions=positions, mean=mean, outputs=outputs, band_rad_s=band_rad_s)
    kw.update(_given(duration_s=duration_s, levels=levels, coherence=coherence, track_width=track_width, tracks=tracks))
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


def analyze_nonlinear(
    subject: Union[Scenario, PathLike],
    *,
    monte_carlo: Optional[int] = None,
    seed: int = 1,
    dt: Optional[Quantity] = None,
    duration: Optional[Quantity] = None,
    burn_in: Optional[Quantity] = None,
    progress: Union[bool, Callable[[int, int], Any]] = True,
    spectra_dir: Optional[PathLike] = None,
    rel_tol: Optional[float] = None,
    max_subintervals: Optional[int] = None,
    max_half_periods: Optional[int] = None,
) -> NonlinearResult:
    """Routes 1 to 3 of a model with nonlinear elements (``[[model.nonlinear]]``; ``stochvib analyze`` of such a
    file).

    Parameters
    ----------
    subject : Scenario or path
        A scenario with nonlinear elements, or its file.
    monte_carlo : int, keyword-only, optional
        Realizations of route 2, the time-domain Monte Carlo of the nonlinear equations (``stochvib analyze
        --monte-carlo N``); ``seed``, ``dt`` and ``duration`` (s or unit strings; suggested for route 2 when
        not given), ``burn_in`` (s; default from the slowest decay rate of the Gaussian equivalent),
        ``progress`` as for :func:`analyze`.
    spectra_dir, rel_tol, max_subintervals, max_half_periods
        As for :func:`analyze`.

    Returns
    -------
    NonlinearResult
        Route 1 (statistical linearisation), route 3 (the exact stationary density where it applies) and,
        with ``monte_carlo``, route 2 per output.

    Raises
    ------
    InvalidInputError
        A linear model (the message names :func:`analyze`).

    Examples
    --------
    >>> import stochvib
    >>> r = stochvib.analyze_nonlinear("data/duffing-white-noise.toml")
    >>> r["x"].route1() < r["x"].exact() < 0.01  # a hardening spring: below the linear σ₀ = 1 cm
    True
    """
    if not isinstance(subject, Scenario):
        if not isinstance(subject, (str, os.PathLike)):
            raise InvalidInputError(f"expected a Scenario or a scenario file path, not {type(subject).__name__}")
        subject = Scenario.load(subject, spectra_dir=spectra_dir)
    return subject.analyze_nonlinear(
        monte_carlo=monte_carlo,
        seed=seed,
        dt=dt,
        duration=duration,
        progress=progress,
        rel_tol=rel_tol,
        max_subintervals=max_subintervals,
        max_half_periods=max_half_periods,
        burn_in=burn_in,
    )


def simulate(
    subject: Union[Scenario, System, PathLike],
    realizations: int,
    path: PathLike,
    *,
    input: Optional[Input] = None,
    speed: Optional[Quantity] = None,
    positions: Optional[Sequence[Quantity]] = None,
    mean: Optional[Union[Quantity, Sequence[Quantity]]] = None,
    outputs: Optional[Sequence[str]] = None,
    dt: Optional[Quantity] = None,
    duration: Optional[Quantity] = None,
    seed: int = 1,
    shard_size: int = 50,
    store_raw: bool = False,
    compression: str = "none",
    route: Literal["auto", "exact", "spectral"] = "auto",
    confidence: float = 0.95,
    overwrite: bool = False,
    progress: Union[bool, Callable[[int, int], Any]] = True,
    spectra_dir: Optional[PathLike] = None,
    shard: Optional[Tuple[int, int]] = None,
    coherence: Optional[Dict[str, Any]] = None,
    track_width: Optional[Quantity] = None,
    tracks: Optional[Sequence[Union[str, int]]] = None,
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
    ``shard=(I, N)``: part I of N of the run (``stochvib simulate --shard I --of N -o DIR``), ``path`` the run
    directory receiving ``shard-<I>-of-<N>.h5``; :func:`merge` joins the parts into one run file with the
    statistics of the unsharded run. ``coherence``/``track_width``/``tracks``: a road of two coherent tracks
    as in :func:`analyze`. A model with nonlinear elements raises :class:`InvalidInputError` naming
    :func:`simulate_nonlinear`.

    Parameters
    ----------
    subject : Scenario, System or path
        As for :func:`analyze`.
    realizations : int
        N ≥ 2.
    path : str or os.PathLike
        The run file (HDF5); with ``shard``, the run directory.
    input, speed, positions, mean, outputs, spectra_dir, coherence, track_width, tracks
        As for :func:`analyze` (keyword-only).
    dt, duration : float or str, keyword-only, optional
        Δt and the duration of one realization in s, or time strings; suggested when not given.
    seed : int, keyword-only, default 1
    shard_size : int, keyword-only, default 50
    store_raw : bool, keyword-only, default False
    compression : str, keyword-only, default "none"
    route : {"auto", "exact", "spectral"}, keyword-only, default "auto"
    confidence : float, keyword-only, default 0.95
    overwrite : bool, keyword-only, default False
    progress : bool or callable, keyword-only, default True
    shard : (int, int), keyword-only, optional

    Returns
    -------
    RunResult

    Raises
    ------
    InvalidInputError
        A bad argument (fewer than 2 realizations, an unknown route, a spatial input without ``speed``); a
        model with nonlinear elements.
    UnitError
        A quantity string of the wrong dimension, naming the argument.
    FileError
        ``path`` exists (without ``overwrite``) or cannot be written.
    DivergentError
        An unstable system.
    KeyboardInterrupt
        Ctrl-C: the ``.tmp`` file is kept for resuming.

    Examples
    --------
    >>> import pathlib, tempfile, stochvib
    >>> with tempfile.TemporaryDirectory() as d:
    ...     r = stochvib.simulate("data/conveyor-idler.toml", 2, pathlib.Path(d) / "run.h5", dt=0.01,
    ...                           duration=5.0, progress=False)
    ...     r.n_realizations, r.path.name
    (2, 'run.h5')
    """
    kw = _given(speed=speed, positions=positions, mean=mean, outputs=outputs)
    kw.update(_given(coherence=coherence, track_width=track_width, tracks=tracks))
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
        shard=shard,
    )


def simulate_nonlinear(
    subject: Union[Scenario, PathLike],
    realizations: int,
    path: PathLike,
    *,
    dt: Optional[Quantity] = None,
    duration: Optional[Quantity] = None,
    burn_in: Optional[Quantity] = None,
    seed: int = 1,
    shard_size: int = 50,
    store_raw: bool = False,
    compression: str = "none",
    route: Literal["auto", "exact", "spectral"] = "auto",
    confidence: float = 0.95,
    overwrite: bool = False,
    progress: Union[bool, Callable[[int, int], Any]] = True,
    spectra_dir: Optional[PathLike] = None,
    shard: Optional[Tuple[int, int]] = None,
) -> NonlinearRunResult:
    """Route 2 of a model with nonlinear elements written to the HDF5 file ``path`` (``stochvib simulate`` of
    such a file): the nonlinear equations integrated in time, seeded.

    ``subject`` a :class:`Scenario` with ``[[model.nonlinear]]`` or its file; ``dt`` and ``duration`` (s or
    unit strings) suggested for route 2 when not given; ``burn_in`` (s) before the record, default from the
    slowest decay rate of the Gaussian equivalent; the other arguments as for :func:`simulate`. Returns a
    :class:`NonlinearRunResult` (the statistics against route 1's Gaussian σ, ``burn_in_s``,
    ``halving_checks``). A linear model raises :class:`InvalidInputError` naming :func:`simulate`.

    Parameters
    ----------
    subject : Scenario or path
        A scenario with nonlinear elements, or its file.
    realizations, path, dt, duration, seed, shard_size, store_raw, compression, route, confidence, overwrite, progress, spectra_dir, shard
        As for :func:`simulate`.
    burn_in : float or str, keyword-only, optional
        s, or a time string.

    Returns
    -------
    NonlinearRunResult

    Raises
    ------
    InvalidInputError
        A linear model; a bad argument.
    UnitError, FileError, KeyboardInterrupt
        As for :func:`simulate`.

    Examples
    --------
    >>> import pathlib, tempfile, stochvib
    >>> with tempfile.TemporaryDirectory() as d:
    ...     r = stochvib.simulate_nonlinear("data/duffing-white-noise.toml", 2, pathlib.Path(d) / "run.h5",
    ...                                     dt=0.01, duration=5.0, progress=False)
    ...     r.n_realizations, r.burn_in_s > 0
    (2, True)
    """
    if not isinstance(subject, Scenario):
        subject = _scenario(subject, None, {}, spectra_dir)
    return subject.simulate_nonlinear(
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
        shard=shard,
        burn_in=burn_in,
    )


def merge(
    path: PathLike,
    inputs: Union[PathLike, Sequence[PathLike]],
    *,
    copy: bool = False,
    overwrite: bool = False,
    confidence: Optional[float] = None,
) -> RunResult:
    """Joins the part files of a sharded run into one run file (``stochvib merge OUT INPUTS…``).

    Parameters
    ----------
    path : str or os.PathLike
        The merged run file (HDF5), written as ``path.tmp`` and renamed when complete.
    inputs : path or sequence of paths
        The part files, or directories holding them (``shard-<I>-of-<N>.h5``); every part must be there
        and of the same run (scenario, seed, step).
    copy : bool, keyword-only
        Copy stored raw realizations into the merged file instead of referencing the part files.
    overwrite : bool, keyword-only
        Replace an existing run file at ``path``.
    confidence : float, keyword-only
        Of the intervals; default that of the parts.

    Returns
    -------
    RunResult
        The merged statistics: those of the same run made in one piece (realization i uses the random
        stream (seed, i) in any part).

    Raises
    ------
    FileError
        A missing or foreign part, a damaged file, an existing ``path`` without ``overwrite``, ``path`` one
        of the parts.
    InvalidInputError
        Parts of a transient run or of a parameter study (the message names :func:`merge_transient` or
        :func:`merge_sweep`).

    Examples
    --------
    >>> import tempfile, pathlib, stochvib
    >>> d = pathlib.Path(tempfile.mkdtemp())
    >>> for i in range(2):
    ...     _ = stochvib.simulate("data/conveyor-idler.toml", 20, d / "parts", shard=(i, 2), shard_size=10,
    ...                           progress=False)
    >>> m = stochvib.merge(d / "run.h5", d / "parts")
    >>> m.n_realizations, m.path.name
    (20, 'run.h5')
    """
    data, text = _stochvib.merge(path, _paths(inputs), copy=copy, overwrite=overwrite, confidence=confidence)
    return RunResult(data, text, "merged from the parts (their step)")


def _paths(inputs: Union[PathLike, Sequence[PathLike]]) -> List[PathLike]:
    return [inputs] if isinstance(inputs, (str, os.PathLike)) else list(inputs)


def merge_transient(
    path: PathLike,
    inputs: Union[PathLike, Sequence[PathLike]],
    *,
    copy: bool = False,
    overwrite: bool = False,
    confidence: Optional[float] = None,
) -> TransientRunResult:
    """Joins the part files of a transient Monte Carlo run (``Scenario.transient(monte_carlo=N, path=DIR,
    shard=(I, N))``, ``stochvib transient --monte-carlo N --shard I --of N -o DIR``) into one run file, as
    ``stochvib merge OUT DIR`` does.

    Parameters
    ----------
    path, inputs, copy, overwrite, confidence
        As for :func:`merge`: the merged run file, the part files (or their directories), and the options.

    Returns
    -------
    TransientRunResult
        The merged run: the statistics at the last stored time, the σ(t) coverage and the verdicts on the
        maxima; the same numbers as the run made in one piece.

    Raises
    ------
    FileError
        A missing or foreign part, a damaged file, an existing ``path`` without ``overwrite``, ``path``
        one of the parts.
    InvalidInputError
        Parts of a stationary run or of a parameter study (the message names :func:`merge` or
        :func:`merge_sweep`).

    Examples
    --------
    >>> import tempfile, pathlib, stochvib
    >>> d = pathlib.Path(tempfile.mkdtemp())
    >>> sc = stochvib.Scenario.load("data/quarter-car-accelerating.toml")
    >>> for i in range(2):
    ...     _ = sc.transient(monte_carlo=8, path=d / "parts", shard=(i, 2), shard_size=4, progress=False)
    >>> m = stochvib.merge_transient(d / "run.h5", d / "parts")
    >>> m.n_realizations, m.path.name
    (8, 'run.h5')
    """
    data, text = _stochvib.merge(
        path, _paths(inputs), copy=copy, overwrite=overwrite, confidence=confidence, transient=True
    )
    return TransientRunResult(data, text)


def merge_sweep(path: PathLike, inputs: Union[PathLike, Sequence[PathLike]], *, overwrite: bool = False) -> SweepResult:
    """Joins the shard files of a parameter study (``Scenario.sweep(params, shard=(I, N), path=DIR)``,
    ``stochvib sweep --shard I --of N -o DIR``) into one table, as ``stochvib merge TABLE DIR`` does: the
    same file as the study made in one piece.

    Parameters
    ----------
    path : str or os.PathLike
        The table: CSV, JSON or HDF5 from its extension (``.csv``, ``.json``, ``.h5``).
    inputs : path or sequence of paths
        The shard files (``sweep-shard-<I>-of-<N>.json``), or directories holding them; every part must be
        there and of the same study.
    overwrite : bool, keyword-only
        Replace an existing table.

    Returns
    -------
    SweepResult
        The whole study (``path`` is the table).

    Raises
    ------
    FileError
        A missing, duplicate or foreign shard, an existing ``path`` without ``overwrite``.
    InvalidInputError
        Part files of a Monte Carlo run (the message names :func:`merge` or :func:`merge_transient`).

    Examples
    --------
    >>> import tempfile, pathlib, stochvib
    >>> d = pathlib.Path(tempfile.mkdtemp())
    >>> sc = stochvib.Scenario.load("data/conveyor-idler.toml")
    >>> for i in range(2):
    ...     _ = sc.sweep({"model.c": "50 kN/m..200 kN/m:4"}, shard=(i, 2), path=d / "parts", progress=False)
    >>> t = stochvib.merge_sweep(d / "table.csv", d / "parts")
    >>> t.n_points, t.path.name
    (4, 'table.csv')
    """
    data = _stochvib.merge_sweep(path, _paths(inputs), overwrite=overwrite)
    return SweepResult(data, path)


def exposure(
    a: Union["npt.ArrayLike", Dict[str, "npt.ArrayLike"]],
    fs: SampleRate,
    *,
    axes: Optional[Sequence[str]] = None,
    exposure: Optional[Quantity] = None,
    motion_sickness: Optional[Sequence[str]] = None,
) -> ExposureResult:
    """The ISO 2631-1 evaluation of measured (or simulated) accelerations: a_w, VDV, MSDV, MTVV, crest
    factor, the Directive's A(8) and daily VDV, the comfort vector sum — ``stochvib exposure`` on arrays.

    Parameters
    ----------
    a : array_like or dict
        Unweighted acceleration in m/s² (rad/s² for rotations): a 1-D array (the vertical seat-surface
        axis, channel "z"), a 2-D array of shape (n, 3) (columns x, y, z of the seat surface), or a dict
        channel name → 1-D array (channels x, y, z are the seat surface unless ``axes`` says otherwise).
    fs : float or str
        Sample rate, Hz, or a string: "1 kHz", "1000 1/s" and "1000 S/s" are all 1000 samples per second.
    axes : sequence of str, keyword-only, optional
        "CHANNEL=LOCATION:AXIS", LOCATION one of seat-surface, seat-back, feet, standing-floor, AXIS one of
        x, y, z, rx, ry, rz.
    exposure : float or str, keyword-only, optional
        The daily exposure T_exp in s or with a unit ("4 h"); default the record's duration.
    motion_sickness : sequence of str, keyword-only, optional
        Channels evaluated with Wf (MSDV).

    Returns
    -------
    ExposureResult

    Raises
    ------
    InvalidInputError
        Channels of different lengths, a sample rate that loses a weighting band, an unknown axis.
    UnitError
        A sample rate or exposure string with an unknown unit or another dimension (``"200 rad/s"``).

    Examples
    --------
    A 4 Hz vertical sine of amplitude 1 m/s² for 60 s: a_w = |W_k(4 Hz)|/√2.

    >>> import numpy as np, stochvib
    >>> fs = 1000.0
    >>> t = np.arange(0, 60.0, 1 / fs)
    >>> r = stochvib.exposure(np.sin(2 * np.pi * 4.0 * t), fs)
    >>> wk = abs(stochvib.comfort.weighting("Wk", f=4.0))
    >>> round(float(r["z"].a_w / (wk / np.sqrt(2))), 2)
    1.0
    """
    import numpy as np

    if isinstance(a, dict):
        channels = dict(a)
    else:
        arr = np.asarray(a)
        if arr.ndim == 1:
            channels = {"z": arr}
        elif arr.ndim == 2 and arr.shape[1] == 3:
            channels = {"x": arr[:, 0], "y": arr[:, 1], "z": arr[:, 2]}
        else:
            raise InvalidInputError(
                f"`a` has shape {arr.shape}: expected 1-D (the vertical axis), (n, 3) (x, y, z) or a dict of channels"
            )
    data, text = _stochvib.exposure(channels, fs, axes=list(axes) if axes else None, exposure_s=exposure, motion_sickness=list(motion_sickness) if motion_sickness else None)
    return ExposureResult(data, text)


def replay(
    scenario: Union[Scenario, PathLike],
    profile: PathLike,
    *,
    speed: Optional[Quantity] = None,
    skip: Optional[Quantity] = None,
    zero_start: bool = False,
    track: Optional[str] = None,
    detrend: Literal["linear", "mean"] = "linear",
    history: Optional[PathLike] = None,
    overwrite: bool = False,
    spectra_dir: Optional[PathLike] = None,
) -> ReplayResult:
    """A measured road profile replayed through a scenario's model as a deterministic input, beside the
    analytic σ from the profile's own measured density (``stochvib replay SCENARIO PROFILE``).

    Each wheel follows its track (delay = position/speed) and the model is stepped exactly between samples.

    Parameters
    ----------
    scenario : Scenario or path
        A scenario whose inputs are roads.
    profile : path
        The profile CSV (header ``distance [m], left [mm], right [mm]``, every column ``name [unit]``).
    speed : float or str, keyword-only, optional
        m/s or a unit string ("54 km/h"); default the scenario's speed.
    skip : float or str, keyword-only, optional
        Length (m) skipped before the statistics; default the settling length v·7/min|Re λ|.
    zero_start : bool, keyword-only
        Start from x = 0 instead of the static state under the first input sample.
    track : str, keyword-only, optional
        The profile column under a road of one track (default the first).
    detrend : {"linear", "mean"}, keyword-only
        Removed from every track (and before the measured density).
    history : path, keyword-only, optional
        Write the history of every output (after the skipped length) to this CSV file (``-o``);
        ``overwrite`` replaces an existing one.

    Returns
    -------
    ReplayResult
        Per output the replayed mean, σ, min, max, crest factor and the analytic σ (``result["x1"]``).

    Raises
    ------
    FileError
        A scenario input that is not a road, no speed, a missing track, a profile too short.
    InvalidInputError, UnitError
        A bad ``detrend``, ``speed`` or ``skip``.

    Examples
    --------
    >>> import stochvib
    >>> r = stochvib.replay("data/quarter-car.toml", "data/measured-profile.csv", speed="54 km/h")
    >>> r.speed_m_s, 0.8 < r["travel"].ratio < 1.25
    (15.0, True)
    """
    json_text, text = _stochvib.replay(
        scenario,
        profile,
        speed=speed,
        skip=skip,
        zero_start=zero_start,
        track=track,
        detrend=detrend,
        history=history,
        overwrite=overwrite,
        spectra_dir=spectra_dir,
    )
    return ReplayResult(json_text, text)


def workday(path: PathLike, *, spectra_dir: Optional[PathLike] = None) -> WorkdayResult:
    """The daily vibration exposure of a working day of several tasks (``stochvib workday FILE``): per task
    and axis k·a_w with the health factors, the day's A(8) = √(Σ (k a_w)² T / 8 h) and VDV = (Σ VDV⁴)^(1/4)
    per axis, against Directive 2002/44/EC and ISO 2631-1 Annex B.

    Parameters
    ----------
    path : path
        The workday file ([[task]] tables naming a scenario with [analysis.comfort], an optional speed and
        a duration; format in docs/comfort.md).
    spectra_dir : path, keyword-only, optional
        The spectrum catalogue (as :meth:`Scenario.load`).

    Returns
    -------
    WorkdayResult
        ``tasks``, ``axes`` (the day's A(8) and VDV per axis), ``a8`` and ``vdv`` (m/s², m/s^1.75),
        ``verdict``; ``to_markdown()`` the ``--format markdown`` report.

    Raises
    ------
    FileError
        A bad workday file or task scenario, naming the file and key.

    Examples
    --------
    >>> import stochvib
    >>> day = stochvib.workday("data/workday/scraper-operator.toml")
    >>> day.a8 == max(a.a8 for a in day.axes)
    True
    """
    return WorkdayResult(*_stochvib.workday(path, spectra_dir=spectra_dir))


def inspect(path: PathLike) -> RunInfo:
    """The identity, sizes and statistics of a Monte Carlo run file (``stochvib inspect FILE``), after
    checking every checksum of the file as the command does.

    Parameters
    ----------
    path : path
        A finished run file (HDF5), whole, merged or one shard.

    Returns
    -------
    RunInfo
        ``seed``, ``dt`` (s), ``n_samples``, ``n_realizations``, ``outputs``, ``statistics``; ``str()`` the
        command's text summary, ``to_markdown()`` its ``--format markdown``.

    Raises
    ------
    FileError
        No such file, not a run file, an unfinished run (``.tmp``), a damaged file (checksum mismatch).

    Examples
    --------
    >>> import tempfile, pathlib, stochvib
    >>> path = pathlib.Path(tempfile.mkdtemp()) / "run.h5"
    >>> _ = stochvib.simulate("data/conveyor-idler.toml", 20, path, progress=False)
    >>> info = stochvib.inspect(path)
    >>> info.n_realizations, info.seed
    (20, 1)
    """
    return RunInfo(*_stochvib.inspect(path))
