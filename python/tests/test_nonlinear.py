"""A scenario with nonlinear elements from Python: analyze_nonlinear() gives routes 1 and 3 as a NonlinearResult
(analyze() refuses it, naming analyze_nonlinear; analyze_nonlinear() refuses a linear model, naming analyze), and route 2 (the Monte Carlo of the nonlinear equations) as the command-line tool
runs it; the exact σ of the Duffing oscillator under white noise against the stationary
Fokker–Planck density computed here with scipy (Caughey 1963; Lin 1967, ch. 10): for m ẍ + c ẋ + U'(x) = w
with white w, p(x, v) ∝ exp(−(m v²/2 + U(x))/θ), θ = m σ_v², σ_v that of the linear oscillator (π S₀/(c m));
here U = k x²/2 + k₃ x⁴/4, m = 1 kg, k = (2π)² N/m, k₃ = 394 784.176 N/m³, the linear σ₀ = 1 cm, so
σ_v = 2π·0.01 m/s and θ = k σ₀²."""

from __future__ import annotations

import math

import pytest
from scipy import integrate

import stochvib

# Two adaptive quadratures of the same smooth, fast-decaying density (the library's and scipy's QUADPACK):
# both to ~1e-10 relative.
REL_QUAD = 1e-8


def test_duffing_routes_against_fokker_planck(root):
    sc = stochvib.Scenario.load(root / "data" / "duffing-white-noise.toml")
    r = sc.analyze_nonlinear(progress=False)
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
    assert r["x"].route2() is None  # no batch asked for


def test_one_function_and_one_result_type_per_kind_of_model(root):
    # analyze() is for linear models and always gives an AnalysisResult; analyze_nonlinear() for models with
    # nonlinear elements and always gives a NonlinearResult; each refuses the other kind, naming the other
    duffing = root / "data" / "duffing-white-noise.toml"
    with pytest.raises(stochvib.InvalidInputError, match=r"nonlinear elements.*stochvib\.analyze_nonlinear\(\)"):
        stochvib.analyze(duffing)
    with pytest.raises(stochvib.InvalidInputError, match=r"analyze_nonlinear"):
        stochvib.Scenario.load(duffing).analyze(monte_carlo=4, progress=False)
    with pytest.raises(stochvib.InvalidInputError, match=r"is linear.*stochvib\.analyze\(\)"):
        stochvib.analyze_nonlinear("data/quarter-car.toml")
    assert isinstance(stochvib.analyze_nonlinear(duffing), stochvib.NonlinearResult)
    assert type(stochvib.analyze("data/quarter-car.toml")) is stochvib.AnalysisResult
    # the same for the Monte Carlo runs: simulate() → RunResult, simulate_nonlinear() → NonlinearRunResult
    with pytest.raises(stochvib.InvalidInputError, match=r"nonlinear elements.*stochvib\.simulate_nonlinear\(\)"):
        stochvib.simulate(duffing, 4, root / "never.h5", progress=False)
    with pytest.raises(stochvib.InvalidInputError, match=r"is linear.*stochvib\.simulate\(\)"):
        stochvib.simulate_nonlinear("data/quarter-car.toml", 4, root / "never.h5", progress=False)
    assert not (root / "never.h5").exists()
    # the signatures say so (no union decided by the file)
    assert stochvib.analyze.__annotations__["return"] == "AnalysisResult"
    assert stochvib.analyze_nonlinear.__annotations__["return"] == "NonlinearResult"
    assert stochvib.simulate.__annotations__["return"] == "RunResult"
    assert stochvib.simulate_nonlinear.__annotations__["return"] == "NonlinearRunResult"


# The route-2 batch below: the same seeded realizations through the command-line tool and Python.
ROUTE2 = ("--dt", "0.01", "--duration", "60", "--seed", "3")


def test_route2_analyze_matches_the_cli(cli, root):
    want = cli.json("analyze", "data/duffing-white-noise.toml", "--monte-carlo", "8", *ROUTE2)
    sc = stochvib.Scenario.load(root / "data" / "duffing-white-noise.toml")
    r = sc.analyze_nonlinear(monte_carlo=8, dt=0.01, duration=60.0, seed=3, progress=False)
    got = r.to_dict()
    for g, w in zip(got["outputs"], want["outputs"]):
        assert [row["monte_carlo"] for row in g["rows"]] == [row["monte_carlo"] for row in w["rows"]]
    mc = r["x"].route2()
    assert set(mc) == {"estimate", "lower", "upper", "confidence"} and mc["lower"] < mc["estimate"] < mc["upper"]
    assert "sigma route 2" in repr(r)


def test_route2_simulate_writes_the_run_of_the_cli(cli, root, tmp_path):
    want = cli.json("simulate", "data/duffing-white-noise.toml", "--realizations", "6", "-o", str(tmp_path / "cli.h5"), *ROUTE2)
    sc = stochvib.Scenario.load(root / "data" / "duffing-white-noise.toml")
    r = sc.simulate_nonlinear(6, tmp_path / "py.h5", dt=0.01, duration=60.0, seed=3, progress=False)
    assert isinstance(r, stochvib.NonlinearRunResult) and r.path == tmp_path / "py.h5" and r.path.is_file()
    assert r.step == "given" and r.n_realizations == 6
    got = r.to_dict()
    assert got["burn_in_s"] == want["burn_in_s"] > 0 and got["halving_checks"] == want["halving_checks"]
    assert [o["statistics"] for o in got["run"]["outputs"]] == [o["statistics"] for o in want["run"]["outputs"]]
    assert set(r.sigma) == {o["output"] for o in want["run"]["outputs"]}


def test_an_escaping_response_is_route_2s_outcome(tmp_path, root):
    # the Duffing oscillator with its cubic term reversed (εσ₀² = −1): the potential's barrier lies at
    # x = σ₀ = 1 cm with βV = 0.25, so the realizations escape within a few periods; route 2 reports "no
    # stationary response" beside routes 1 and 3 (as `stochvib analyze --monte-carlo` does); the run alone
    # (simulate_nonlinear) raises DivergentError naming the realization, the output and the element
    text = (root / "data" / "duffing-white-noise.toml").read_text()
    soft = tmp_path / "softening.toml"
    soft.write_text(text.replace('"394784.1760435743 N/m^3"', '"-394784.1760435743 N/m^3"'))
    r = stochvib.Scenario.load(soft).analyze_nonlinear(monte_carlo=2, progress=False)
    d = r.to_dict()
    assert d["monte_carlo"].startswith("NO STATIONARY RESPONSE") and not d["route1_converged"]
    assert any("escaped" in v for v in d["verdicts"])
    assert r["x"].route2() is None
    with pytest.raises(stochvib.DivergentError, match=r"realization \d+ .*output `x`.*`hardening`"):
        stochvib.simulate_nonlinear(soft, 2, tmp_path / "run.h5", dt=0.01, duration=50.0, progress=False)
    assert not (tmp_path / "run.h5").exists()


def test_a_bad_burn_in_names_the_keyword(root):
    sc = stochvib.Scenario.load(root / "data" / "duffing-white-noise.toml")
    for bad in (-1.0, float("nan"), float("inf")):
        with pytest.raises(stochvib.InvalidInputError, match=r"`burn_in`"):
            sc.analyze_nonlinear(monte_carlo=2, burn_in=bad, progress=False)
