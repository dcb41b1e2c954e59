"""A scenario with nonlinear elements from Python: analyze() gives routes 1 and 3 as a NonlinearResult, not
the linear part's answer; the exact σ of the Duffing oscillator under white noise against the stationary
Fokker–Planck density computed here with scipy (Caughey 1963; Lin 1967, ch. 10): for m ẍ + c ẋ + U'(x) = w
with white w, p(x, v) ∝ exp(−(m v²/2 + U(x))/θ), θ = m σ_v², σ_v that of the linear oscillator (π S₀/(c m));
here U = k x²/2 + k₃ x⁴/4, m = 1 kg, k = (2π)² N/m, k₃ = 394 784.176 N/m³, the linear σ₀ = 1 cm, so
σ_v = 2π·0.01 m/s and θ = k σ₀²."""

from __future__ import annotations

import math

import pytest
from scipy import integrate

import stochvib
from stochvib import NotApplicableError

# Two adaptive quadratures of the same smooth, fast-decaying density (the library's and scipy's QUADPACK):
# both to ~1e-10 relative.
REL_QUAD = 1e-8


def test_duffing_routes_against_fokker_planck(root, tmp_path):
    sc = stochvib.Scenario.load(root / "data" / "duffing-white-noise.toml")
    r = sc.analyze(progress=False)
    assert isinstance(r, stochvib.NonlinearResult) and r.route1_converged
    k, k3, sigma0 = (2 * math.pi) ** 2, 394784.1760435743, 0.01
    theta = k * sigma0**2
    w = lambda x, p: x**p * math.exp(-(k * x * x / 2 + k3 * x**4 / 4) / theta)  # noqa: E731
    # the density is nil beyond |x| = 0.1 m (U/θ > 2.5e3 there)
    m0 = integrate.quad(w, -0.1, 0.1, args=(0,), points=[0.0], epsabs=0, epsrel=1e-12)[0]
    m2 = integrate.quad(w, -0.1, 0.1, args=(2,), points=[0.0], epsabs=0, epsrel=1e-12)[0]
    assert r["x"].exact() == pytest.approx(math.sqrt(m2 / m0), rel=REL_QUAD)
    assert r["v"].exact() == pytest.approx(2 * math.pi * sigma0, rel=REL_QUAD)
    # statistical linearisation underestimates σ_x of a hardening spring less than the linear σ₀ overstates it
    assert r["x"].route1() < r["x"].exact() < sigma0
    assert r["x"].rows["kurtosis"]["exact"] < 3.0 == r["x"].route1("kurtosis")
    assert "route 1" in repr(r) and "Duffing" in str(r)
    # route 2 (Monte Carlo) is refused clearly, nothing written
    with pytest.raises(NotApplicableError, match="nonlinear"):
        sc.simulate(20, tmp_path / "run.h5", progress=False)
    with pytest.raises(NotApplicableError, match="nonlinear"):
        sc.analyze(monte_carlo=20, progress=False)
    assert not list(tmp_path.iterdir())
