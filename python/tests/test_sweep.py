"""Scenario.sweep against the command-line tool's ``stochvib sweep … --json`` (the Rust library's answer for
the same study) and against the conveyor idler's closed form for the mean, the static deflection M_F/c
(Sukharev 2012, Example 8.1, M_F = 10 kN); zip against the diagonal of the grid."""

from __future__ import annotations

import numpy as np
import pytest

import stochvib
from stochvib import InvalidInputError

# The same library computation in the same process order: the JSON's shortest round-trip floats read back.
REL_SAME = 1e-15
# M_F / c recomputed here: one division against the library's static gain (a linear solve).
REL_STATIC = 1e-12


def test_sweep_against_the_cli(cli, root):
    want = cli.json(
        "sweep", "data/conveyor-idler.toml", "--param", "model.zeta=0.1,0.2,0.3", "--param", "model.c=50 kN/m,70 kN/m"
    )
    sc = stochvib.Scenario.load(root / "data" / "conveyor-idler.toml")
    r = sc.sweep({"model.zeta": [0.1, 0.2, 0.3], "model.c": ["50 kN/m", "70 kN/m"]})
    assert r.shape == (3, 2) and r.mode == "grid" and r.n_points == want["n_points"] == 6
    assert r.params == {"model.zeta": ["0.1", "0.2", "0.3"], "model.c": ["50 kN/m", "70 kN/m"]}
    for out in ("y", "y_vel"):
        exp = np.full(6, np.nan)
        for row in want["rows"]:
            if row["output"] == out:
                exp[row["point"]] = row["sigma"]
        np.testing.assert_allclose(r.sigma(out).ravel(), exp, rtol=REL_SAME)
    # the mean is the static deflection M_F / c (M_F = 10 kN), whatever ζ
    np.testing.assert_allclose(r.statistic("y", "mean"), np.tile(1e4 / np.array([5e4, 7e4]), (3, 1)), rtol=REL_STATIC)
    assert "SweepResult: 6 points (grid" in repr(r)


def test_sweep_zip_and_range(root):
    sc = stochvib.Scenario.load(root / "data" / "conveyor-idler.toml")
    z = sc.sweep({"model.zeta": [0.1, 0.2], "model.c": ["50 kN/m", "70 kN/m"]}, zip=True)
    assert z.shape == (2,)
    g = sc.sweep({"model.zeta": [0.1, 0.2], "model.c": ["50 kN/m", "70 kN/m"]})
    np.testing.assert_array_equal(z.sigma("y"), np.diag(g.sigma("y")))
    r = sc.sweep({"model.c": "50 kN/m..100 kN/m:3"})
    np.testing.assert_allclose(r.statistic("y", "mean"), 1e4 / np.array([5e4, 7.5e4, 1e5]), rtol=REL_STATIC)


def test_sweep_bad_key(root):
    sc = stochvib.Scenario.load(root / "data" / "conveyor-idler.toml")
    with pytest.raises(InvalidInputError, match="unknown key"):
        sc.sweep({"model.omega2": [1.0, 2.0]})


def test_sweep_with_monte_carlo_against_the_cli(cli, root):
    # the same seeded batch at every point (realization i uses the stream (seed, i)): the CLI's numbers
    want = cli.json(
        "sweep", "data/conveyor-idler.toml", "--param", "model.c=50 kN/m,70 kN/m",
        "--monte-carlo", "6", "--dt", "0.01", "--duration", "20", "--seed", "5",
    )
    sc = stochvib.Scenario.load(root / "data" / "conveyor-idler.toml")
    r = sc.sweep({"model.c": ["50 kN/m", "70 kN/m"]}, monte_carlo=6, dt=0.01, duration="20 s", seed=5, progress=False)
    assert r.monte_carlo_options["realizations"] == 6 and r.monte_carlo_options["seed"] == 5
    mc = r.monte_carlo("y")
    assert mc["sigma"].shape == r.shape == (2,)
    for row in want["rows"]:
        if row["output"] == "y":
            k = row["point"]
            assert (mc["sigma"][k], mc["lower"][k], mc["upper"][k], mc["covers"][k]) == (
                row["monte_carlo"]["sigma"], row["monte_carlo"]["lower"], row["monte_carlo"]["upper"], row["monte_carlo"]["covers"],
            )
    assert np.all(mc["lower"] < mc["sigma"]) and np.all(mc["sigma"] < mc["upper"])
    # the exact columns are those of the study without Monte Carlo
    np.testing.assert_array_equal(r.sigma("y"), sc.sweep({"model.c": ["50 kN/m", "70 kN/m"]}).sigma("y"))
    with pytest.raises(KeyError, match="no Monte Carlo"):
        sc.sweep({"model.c": ["50 kN/m"]}).monte_carlo("y")
    with pytest.raises(InvalidInputError, match="at least 2"):
        sc.sweep({"model.c": ["50 kN/m"]}, monte_carlo=1)
