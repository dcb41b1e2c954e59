"""Type stubs of the native module (import these names from ``stochvib``).

Units: ω in rad/s (``omega=``; rad/m for road profiles), f in Hz (``f=``; cycles/m), τ in s (m), everything
else SI; a string with a unit is accepted where a ``Quantity`` is. Densities: two-sided angular S(ω) unless
``convention=`` says otherwise. Polynomial coefficients: descending powers unless ``order="ascending"``.
"""

from __future__ import annotations

import os
from pathlib import Path
from typing import Any, Callable, Dict, List, Literal, Mapping, Optional, Sequence, Tuple, Union, overload

import numpy as np
import numpy.typing as npt

from .results import (
    AnalysisResult,
    NonlinearResult,
    NonlinearRunResult,
    OptimizeResult,
    ParetoFront,
    RunResult,
    SweepResult,
    TablesResult,
    TransientResult,
    VerdictTable,
)

__version__: str
ISO_BAND: Tuple[float, float]
"""ISO 8608 band for road variances, (0.011, 2.83) cycles/m."""

ArrayLike = npt.ArrayLike
FloatArray = npt.NDArray[np.float64]
PathLike = Union[str, os.PathLike[str]]
Convention = Literal["two-sided-angular", "one-sided-angular", "one-sided-cyclic", "engineering"]
Domain = Literal["temporal", "spatial"]
Progress = Union[bool, Callable[[int, int], Any]]
Order = Literal["descending", "ascending"]
Quantity = Union[float, str]
SampleRate = Union[float, str]
"""Samples per second: a number (Hz) or a string ("200 Hz", "200 1/s", "200 S/s" are all 200)."""

class Spectrum:
    """A stationary random process described by its spectral density S(ω) (two-sided, angular)."""

    @staticmethod
    def exponential(variance: Quantity, alpha: Quantity, *, domain: Domain = "temporal", unit: str = "m") -> Spectrum:
        """Type 1: K = D e^{−α|τ|}; D in unit², α in 1/s (1/m)."""
    @staticmethod
    def gaussian(variance: Quantity, alpha: Quantity, *, domain: Domain = "temporal", unit: str = "m") -> Spectrum:
        """Type 2: K = D e^{−ατ²}; α in 1/s² (1/m²)."""
    @staticmethod
    def exp_cosine(
        variance: Quantity, alpha: Quantity, beta: Quantity, *, domain: Domain = "temporal", unit: str = "m"
    ) -> Spectrum:
        """Type 3: K = D e^{−α|τ|} cos βτ; α in 1/s, β in rad/s."""
    @staticmethod
    def gauss_cosine(
        variance: Quantity, alpha: Quantity, beta: Quantity, *, domain: Domain = "temporal", unit: str = "m"
    ) -> Spectrum:
        """Type 4: K = D e^{−ατ²} cos βτ; α in 1/s², β in rad/s."""
    @staticmethod
    def rational(
        numerator: ArrayLike,
        denominator: ArrayLike,
        *,
        order: Order = "descending",
        domain: Domain = "temporal",
        unit: str = "m",
    ) -> Spectrum:
        """S(ω) = N(ω²)/D(ω²), coefficients in descending powers of ω² unless order="ascending"."""
    @staticmethod
    def iso8608(
        road_class: str,
        *,
        bound: Literal["lower", "geometric-mean", "mean", "upper"] = "geometric-mean",
        band: Optional[Tuple[Quantity, Quantity]] = ...,
    ) -> Spectrum:
        """ISO 8608 class A–H (spatial, G_d(n) in m³, n in cycles/m); band default (0.011, 2.83), None = unbounded."""
    @staticmethod
    def power_law(
        g0: Quantity,
        n0: Quantity,
        waviness: Quantity,
        *,
        band: Optional[Tuple[Quantity, Quantity]] = None,
        domain: Domain = "spatial",
        unit: str = "m",
    ) -> Spectrum:
        """G(n) = g0 (n/n0)^{−w}, one-sided cyclic (n in cycles/m or Hz)."""
    @staticmethod
    def tabulated(
        x: ArrayLike, values: ArrayLike, *, convention: Convention, domain: Domain = "temporal", unit: str = "m"
    ) -> Spectrum:
        """Measured density at points ``x`` (the convention's abscissa), log–log interpolation, zero outside."""
    @staticmethod
    def band_white(
        level: Quantity, low: Quantity, high: Quantity, *, convention: Convention, domain: Domain = "temporal", unit: str = "m"
    ) -> Spectrum:
        """Constant ``level`` (in ``convention``) between ``low`` and ``high`` (the convention's abscissa)."""
    @staticmethod
    def load(path_or_name: PathLike, *, spectra_dir: Optional[PathLike] = None) -> Spectrum:
        """A catalogue name (``spectra/<name>.toml``) or a spectrum file path."""
    @staticmethod
    def catalogue(*, spectra_dir: Optional[PathLike] = None) -> Dict[str, Spectrum]:
        """Every valid spectrum of the catalogue directory, by name."""
    @overload
    def density(
        self, omega: float, *, f: None = None, convention: Optional[Convention] = None, out: None = None
    ) -> float: ...
    @overload
    def density(
        self,
        omega: Optional[ArrayLike] = None,
        *,
        f: Optional[ArrayLike] = None,
        convention: Optional[Convention] = None,
        out: Optional[FloatArray] = None,
    ) -> Union[float, FloatArray]:
        """S(ω) at ``omega`` (rad/s; conventions two-sided-angular, one-sided-angular, engineering), or the
        one-sided G(f) = 4πS(2πf) at ``f`` (Hz)."""
    @overload
    def correlation(self, tau: float) -> float: ...
    @overload
    def correlation(self, tau: ArrayLike) -> FloatArray:
        """K(τ) = ∫ S(ω) cos ωτ dω, τ in s (m)."""
    def variance(self) -> float:
        """D = ∫ S dω in unit²; raises DivergentError when infinite."""
    def at_speed(self, speed: Quantity) -> Spectrum:
        """The temporal spectrum S_t(ω) = S_Ω(ω/v)/v of a spatial one at ``speed`` m/s."""
    def rational_coefficients(self, *, order: Order = "descending") -> Optional[Tuple[FloatArray, FloatArray]]:
        """(N, D) in powers of ω² (descending unless order="ascending"), or None."""
    def shaping_filter(self, *, order: Order = "descending") -> Tuple[FloatArray, FloatArray]:
        """(b, a) in powers of s (descending unless order="ascending") with S = |b(iω)/a(iω)|²/(2π)."""
    @property
    def domain(self) -> Domain: ...
    @property
    def unit(self) -> str: ...
    @property
    def name(self) -> str: ...
    @property
    def description(self) -> str: ...
    @property
    def source(self) -> str: ...
    @property
    def text(self) -> str: ...

OutputSpec = Union[str, Tuple[str, str]]

class System:
    """A linear system known through H(iω) (outputs × inputs), with named outputs and SI units."""

    @staticmethod
    def mdof(
        *,
        mass: ArrayLike,
        damping: ArrayLike,
        stiffness: ArrayLike,
        base_stiffness: Optional[ArrayLike] = None,
        base_damping: Optional[ArrayLike] = None,
        forces: Optional[ArrayLike] = None,
        coordinates: Optional[Sequence[OutputSpec]] = None,
        outputs: Optional[Dict[str, Tuple[Literal["displacement", "velocity", "acceleration"], ArrayLike]]] = None,
    ) -> System:
        """M q̈ + B q̇ + C q = K_u u + B_u u̇ + F f (kg, N s/m, N/m)."""
    @staticmethod
    def state_space(
        A: ArrayLike,
        B: ArrayLike,
        C: ArrayLike,
        D: Optional[ArrayLike] = None,
        E: Optional[ArrayLike] = None,
        *,
        outputs: Optional[Sequence[OutputSpec]] = None,
    ) -> System:
        """ẋ = Ax + Bu, y = Cx + Du + Eu̇."""
    @staticmethod
    def transfer_function(
        numerator: ArrayLike,
        denominator: ArrayLike,
        *,
        order: Order = "descending",
        output: str = "y",
        unit: str = "1",
    ) -> System:
        """H(s) = N(s)/D(s), descending powers of s (scipy.signal's) unless order="ascending"."""
    @staticmethod
    def model(kind: str, *, speed: Optional[Quantity] = None, **params: Any) -> System:
        """A catalogue model built from keyword arguments (SI numbers or strings with units)."""
    @staticmethod
    def models() -> List[Dict[str, Any]]:
        """The registry of model kinds."""
    @staticmethod
    def load(path: PathLike, *, spectra_dir: Optional[PathLike] = None) -> System:
        """The system of a scenario file."""
    def frequency_response(
        self, omega: Optional[ArrayLike] = None, *, f: Optional[ArrayLike] = None
    ) -> npt.NDArray[np.complex128]:
        """H(iω), complex, shape (outputs, inputs, *omega.shape); ω in rad/s, or f in Hz."""
    def weighted(self, output: str, weighting: str) -> System:
        """Output ``output`` through the ISO weighting ``weighting`` (W·H), same inputs and layout."""
    def modes(self) -> Tuple[FloatArray, FloatArray]:
        """Undamped ω (rad/s) and mass-normalised mode shapes (columns); System.mdof systems only."""
    def natural_frequencies(self) -> FloatArray:
        """|λ| of the poles, rad/s."""
    def static_gain(self) -> Optional[FloatArray]:
        """H(0), or None when infinite."""
    def state_space_matrices(self) -> Optional[Dict[str, FloatArray]]:
        """"A", "B", "C", "D", "E" of the exact state-space form."""
    def output_index(self, name: str) -> int: ...
    @property
    def outputs(self) -> List[Tuple[str, str]]:
        """(name, unit) per output."""
    @property
    def n_inputs(self) -> int: ...
    @property
    def kind(self) -> str: ...
    @property
    def description(self) -> str: ...

class Scenario:
    """A model, its random input and what to report."""

    @staticmethod
    def load(path: PathLike, *, spectra_dir: Optional[PathLike] = None) -> Scenario: ...
    @staticmethod
    def from_system(
        system: System,
        input: Union[Spectrum, str, os.PathLike[str], Sequence[Spectrum]],
        *,
        speed: Optional[Quantity] = None,
        positions: Optional[Sequence[Quantity]] = None,
        mean: Optional[Union[Quantity, Sequence[Quantity]]] = None,
        outputs: Optional[Sequence[str]] = None,
        band_rad_s: Optional[Tuple[Quantity, Quantity]] = None,
        duration_s: Optional[Quantity] = None,
        levels: Optional[Dict[str, Sequence[Quantity]]] = None,
        title: Optional[str] = None,
        coherence: Optional[Mapping[str, Any]] = None,
        track_width: Optional[Quantity] = None,
        tracks: Optional[Sequence[Union[str, int]]] = None,
    ) -> Scenario:
        """``system`` driven by ``input`` (speed m/s, positions m, band rad/s, duration s); a road of two
        coherent tracks with ``coherence`` (a dict as a scenario road's table), ``track_width`` (m) and
        ``tracks`` ("left"/"right" per system input)."""
    def analyze(
        self,
        *,
        monte_carlo: Optional[int] = None,
        seed: int = 1,
        dt: Optional[Quantity] = None,
        duration: Optional[Quantity] = None,
        progress: Progress = True,
        rel_tol: Optional[float] = None,
        max_subintervals: Optional[int] = None,
        max_half_periods: Optional[int] = None,
    ) -> AnalysisResult:
        """The ``stochvib analyze`` report of a linear model (with a Monte Carlo column for
        ``monte_carlo=N``); ``rel_tol``, ``max_subintervals``, ``max_half_periods`` override the quadratures'
        ``[analysis.quadrature]``. A model with nonlinear elements raises InvalidInputError naming
        :meth:`analyze_nonlinear`."""
    def analyze_nonlinear(
        self,
        *,
        monte_carlo: Optional[int] = None,
        seed: int = 1,
        dt: Optional[Quantity] = None,
        duration: Optional[Quantity] = None,
        progress: Progress = True,
        rel_tol: Optional[float] = None,
        max_subintervals: Optional[int] = None,
        max_half_periods: Optional[int] = None,
        burn_in: Optional[Quantity] = None,
    ) -> NonlinearResult:
        """Routes 1 and 3 of a model with nonlinear elements, route 2 with ``monte_carlo=N`` (``burn_in`` in
        s). A linear model raises InvalidInputError naming :meth:`analyze`."""
    def output_density(
        self,
        output: str,
        omega: Optional[ArrayLike] = None,
        *,
        f: Optional[ArrayLike] = None,
        convention: Optional[Convention] = None,
    ) -> Union[float, FloatArray]:
        """S_y(ω) (rad/s) or the one-sided G_y(f) (Hz) of an output, shaped as the argument."""
    def sweep(
        self,
        params: Mapping[str, Union[str, Sequence[Quantity]]],
        *,
        zip: bool = False,
        monte_carlo: Optional[int] = None,
        seed: int = 1,
        dt: Optional[Quantity] = None,
        duration: Optional[Quantity] = None,
        shard_size: int = 50,
        confidence: float = 0.95,
        progress: Progress = True,
        shard: Optional[Tuple[int, int]] = None,
        path: Optional[PathLike] = None,
        overwrite: bool = False,
    ) -> SweepResult:
        """The exact statistics at every point of a parameter study (grid, or ``zip``), with a Monte Carlo
        batch of ``monte_carlo`` realizations per point; with ``shard=(I, N)`` part I of the points into the
        shard file ``path/sweep-shard-<I>-of-<N>.json``."""
    def sweep_verdicts(
        self,
        params: Mapping[str, Union[str, Sequence[Quantity]]],
        *,
        zip: bool = False,
    ) -> VerdictTable:
        """The verdicts (σ, a_w, a_v, A(8), VDV, damage rate, life) at every point of a parameter study."""
    def optimize(
        self,
        params: Mapping[str, Union[str, Sequence[Quantity]]],
        *,
        minimize: Optional[str] = None,
        maximize: Optional[str] = None,
        constraints: Sequence[str] = ...,
        starts: int = 4,
        max_evaluations: int = 2000,
    ) -> OptimizeResult:
        """The parameters (key → (low, high)) minimising or maximising a quantity under constraints."""
    def pareto(
        self,
        params: Mapping[str, Union[str, Sequence[Quantity]]],
        *,
        minimize: str,
        pareto: str,
        constraints: Sequence[str] = ...,
        points: int = 7,
        plots: Optional[PathLike] = None,
        starts: int = 4,
        max_evaluations: int = 2000,
    ) -> ParetoFront:
        """The Pareto front of two minimised quantities (ε-constraint), optionally drawn into ``plots``."""
    def transient(
        self,
        *,
        monte_carlo: Optional[int] = None,
        path: Optional[PathLike] = None,
        seed: int = 1,
        substeps: int = 4,
        shard_size: int = 50,
        confidence: float = 0.95,
        store_raw: bool = False,
        overwrite: bool = False,
        progress: Progress = True,
        shard: Optional[Tuple[int, int]] = None,
    ) -> TransientResult:
        """σ(t) and the mission extremes of a ``[transient]`` scenario, with a Monte Carlo batch."""
    def tables(self) -> TablesResult:
        """The result tables of a deterministic model or a reference table."""
    def simulate(
        self,
        realizations: int,
        path: PathLike,
        *,
        dt: Optional[Quantity] = None,
        duration: Optional[Quantity] = None,
        seed: int = 1,
        shard_size: int = 50,
        store_raw: bool = False,
        compression: str = "none",
        route: Literal["auto", "exact", "spectral"] = "auto",
        confidence: float = 0.95,
        overwrite: bool = False,
        progress: Progress = True,
        shard: Optional[Tuple[int, int]] = None,
    ) -> RunResult:
        """A seeded Monte Carlo run of a linear model into the HDF5 file ``path`` (dt, duration in s); with
        ``shard=(I, N)`` part I of N into the directory ``path``. A model with nonlinear elements raises
        InvalidInputError naming :meth:`simulate_nonlinear`."""
    def simulate_nonlinear(
        self,
        realizations: int,
        path: PathLike,
        *,
        dt: Optional[Quantity] = None,
        duration: Optional[Quantity] = None,
        seed: int = 1,
        shard_size: int = 50,
        store_raw: bool = False,
        compression: str = "none",
        route: Literal["auto", "exact", "spectral"] = "auto",
        confidence: float = 0.95,
        overwrite: bool = False,
        progress: Progress = True,
        shard: Optional[Tuple[int, int]] = None,
        burn_in: Optional[Quantity] = None,
    ) -> NonlinearRunResult:
        """Route 2 of a model with nonlinear elements into ``path`` (``burn_in`` in s). A linear model raises
        InvalidInputError naming :meth:`simulate`."""
    @property
    def title(self) -> str: ...
    @property
    def path(self) -> Path: ...
    @property
    def what(self) -> Literal["stochastic", "deterministic", "reference"]: ...
    @property
    def kind(self) -> str: ...
    @property
    def system(self) -> System: ...
    @property
    def input(self) -> Spectrum: ...
    @property
    def speed(self) -> Optional[float]: ...
    @property
    def outputs(self) -> List[str]: ...
    @property
    def text(self) -> str: ...

@overload
def h2_integral(numerator: Sequence[float], denominator: Sequence[float], *, order: Order = "descending") -> float: ...
@overload
def h2_integral(numerator: ArrayLike, denominator: ArrayLike, *, order: Order = "descending") -> Any:
    """∫|N(iω)/D(iω)|² dω, descending powers of s unless order="ascending"; 2-D arguments: one per row."""
def weighting_response(
    name: str, omega: Optional[ArrayLike] = None, *, f: Optional[ArrayLike] = None
) -> npt.NDArray[np.complex128]: ...
def weighting_filter(name: str, *, order: Order = "descending") -> Tuple[FloatArray, FloatArray]: ...
def rainflow(x: ArrayLike) -> Dict[str, npt.NDArray[Any]]: ...
def sn_curve(*, k: Quantity, c: Quantity, unit: str = "Pa") -> Tuple[float, float]: ...
def spectral_fatigue(
    f: ArrayLike,
    G: ArrayLike,
    *,
    k: Quantity,
    c: Quantity,
    endurance_limit: Optional[Quantity] = None,
    unit: str = "Pa",
) -> List[Dict[str, Any]]: ...
def exposure(
    channels: Dict[str, ArrayLike],
    fs: SampleRate,
    *,
    axes: Optional[List[str]] = None,
    exposure_s: Optional[Quantity] = None,
    motion_sickness: Optional[List[str]] = None,
) -> Tuple[Dict[str, Any], str]: ...
def welch(
    x: ArrayLike, fs: SampleRate, *, nperseg: int = 256, detrend: bool = True, confidence: float = 0.95
) -> Dict[str, Any]: ...
def iri(z: ArrayLike, step: Quantity) -> Dict[str, Any]: ...
def expected_iri(spectrum: Spectrum) -> Dict[str, Any]: ...
def iso8608_class(g0: Quantity) -> str: ...
def merge(
    path: PathLike,
    inputs: Sequence[PathLike],
    *,
    copy: bool = False,
    overwrite: bool = False,
    confidence: Optional[float] = None,
    transient: bool = False,
) -> Tuple[Dict[str, Any], str]: ...
def merge_sweep(path: PathLike, inputs: Sequence[PathLike], *, overwrite: bool = False) -> Dict[str, Any]: ...
def coherence_amplitude(model: Dict[str, Any], n: ArrayLike, *, track_width: Quantity) -> FloatArray: ...
def road_profile(
    tracks: List[Tuple[str, ArrayLike]],
    step: Quantity,
    *,
    segment: Optional[int] = ...,
    detrend: str = ...,
    confidence: float = ...,
) -> Dict[str, Any]: ...
def daily_exposure_a8(a_w: Quantity, duration: Quantity) -> float: ...
def vdv_gaussian(a_w: Quantity, duration: Quantity) -> float: ...
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
) -> Tuple[str, str]:
    """``stochvib replay``: (the ``--json`` text, the text report)."""
def workday(path: PathLike, *, spectra_dir: Optional[PathLike] = None) -> Tuple[str, str, str]:
    """``stochvib workday``: (the ``--json`` text, the text report, the markdown report)."""
def inspect(path: PathLike) -> Tuple[str, str, str]:
    """``stochvib inspect``: (the ``--json`` text, the text summary, the markdown summary)."""
