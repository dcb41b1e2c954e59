"""stochvib.linalg.h2_integral: closed forms, row-wise evaluation, errors; the Python-driven variance sweep of
the benchmark against scipy's Lyapunov solver and against the library's analysis of the catalogue model."""

from __future__ import annotations

import math
import sys

import numpy as np
import pytest

import stochvib
from stochvib import DivergentError, InvalidInputError
from stochvib.linalg import h2_integral

from conftest import ROOT

sys.path.insert(0, str(ROOT / "python" / "bench"))
import sweep_problem as sp  # noqa: E402

# --- named tolerances -------------------------------------------------------------------------------------
# A closed-form integral against the table's Hurwitz solve (a few roundings).
REL_CLOSED = 1e-14
# σ by the integral table vs by a Lyapunov solver (two exact methods; the 5-state scraper spans 1e-3..1e9
# in its matrix entries, so each carries ~1e-12 relative rounding).
REL_METHODS = 1e-9


def test_closed_forms():
    # H = 1/(s + 2): ∫ dω/(4 + ω²) = π/2 (coefficients descending, as scipy.signal)
    assert h2_integral([1.0], [1.0, 2.0]) == pytest.approx(math.pi / 2, rel=REL_CLOSED)
    # m ẍ + c ẋ + k x = f: the table's I₂ = π(A₀B₁² + A₂B₀²)/(A₀A₁A₂) with B = [1, 0], A = [k, c, m] is π/(kc)
    k, c, m = 50.0, 0.3, 2.0
    assert h2_integral([1.0], [m, c, k]) == pytest.approx(math.pi / (k * c), rel=REL_CLOSED)
    assert h2_integral([1.0], [k, c, m], order="ascending") == h2_integral([1.0], [m, c, k])
    assert isinstance(h2_integral([1.0], [1.0, 2.0]), float)


def test_rows_are_independent_integrals():
    num = np.array([[0.0, 1.0], [0.5, 1.0], [0.0, 2.0]])
    den = np.array([[0.0, 1.0, 2.0], [2.0, 0.3, 50.0], [1.0, 3.0, 1.0]])
    rows = h2_integral(num, den)
    assert rows.shape == (3,)
    for i in range(3):
        assert rows[i] == h2_integral(num[i], den[i])  # leading zeros trimmed: the same integral
    np.testing.assert_array_equal(h2_integral(num[:, ::-1], den[:, ::-1], order="ascending"), rows)


def test_errors_name_the_row():
    with pytest.raises(DivergentError):
        h2_integral([1.0, 0.0], [1.0, 2.0])  # deg N = deg D: |H|² → 1
    with pytest.raises(InvalidInputError, match=r"row 1"):
        h2_integral(np.array([[1.0], [1.0]]), np.array([[1.0, 2.0], [1.0, -2.0]]))  # s − 2: unstable
    with pytest.raises(InvalidInputError, match="rows"):
        h2_integral(np.ones((2, 1)), np.ones((3, 2)))
    with pytest.raises(InvalidInputError, match="1-D or 2-D"):
        h2_integral(np.ones((2, 1, 1)), np.ones((2, 1, 2)))
    with pytest.raises(InvalidInputError, match="order"):
        h2_integral([1.0], [1.0, 2.0], order="up")


def test_python_driven_sweep_agrees_with_scipy_and_the_library():
    c2, b2 = sp.grid()
    pick = np.arange(0, c2.size, 8333)  # 12 points spread over the grid
    road = sp.road()
    fast = sp.sigma_h2(c2[pick], b2[pick], road)
    slow = sp.sigma_scipy_lyapunov(c2[pick], b2[pick], road)
    np.testing.assert_allclose(fast, slow, rtol=REL_METHODS, atol=0)
    # the library's own analysis of the catalogue model at one point (Lyapunov on its state space)
    i = pick[5]
    model = stochvib.System.model("scraper-sprung-cab", m1=sp.M1, c1=sp.C1, b1=sp.B1, m2=sp.M2, c2=c2[i], b2=b2[i])
    r = stochvib.analyze(model, stochvib.Spectrum.load("book-8-69"), speed=sp.SPEED, outputs=["x2_acc"])
    assert r["x2_acc"].sigma == pytest.approx(fast[5], rel=REL_METHODS)
