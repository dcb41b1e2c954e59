"""Scenario.transient (``stochvib transient``) from Python: σ(t) against the closed form of the quarter car in
its stationary state under white road velocity, the whole answer against the command-line tool's ``--json``
(exact route and a seeded Monte Carlo batch), the temporary run file, shards, and refusals.

data/quarter-car-accelerating.toml: m_s = 300 kg, m_u = 40 kg, k_s = 20 kN/m, c = 1.5 kN s/m, k_t = 200 kN/m
on an ISO 8608 class C road without band (w = 2: the road velocity is white, two-sided density
S₀(v) = πn₀²G_d(n₀)v with G_d(n₀) = 256·10⁻⁶ m³, n₀ = 0.1 cycles/m), starting in its stationary state at
5 m/s. The stationary Lyapunov equation solved by hand gives σ²_travel = πS₀M/c with M = m_s + m_u
(independent of the tyre; see python/tests/test_optimize.py), so σ_travel(0) = √(π S₀(5 m/s) M / c)."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest

import stochvib
from stochvib import InvalidInputError, NotApplicableError

SCENARIO = "data/quarter-car-accelerating.toml"
# The exact route integrates the covariance ODE with a local error control of ~1e-10 relative; the start is
# the stationary Lyapunov solution (to ~1e-12).
REL_EXACT = 1e-8
# The same library computation through the command-line tool: identical numbers.
REL_SAME = 1e-15


def test_sigma_at_the_start_is_the_stationary_closed_form(root):
    r = stochvib.Scenario.load(root / SCENARIO).transient()
    assert isinstance(r, stochvib.TransientResult)
    assert r.times[0] == 0.0 and r.times[-1] == pytest.approx(15.0)
    s0 = math.pi * 0.1**2 * 256e-6 * 5.0
    assert r["travel"].sigma[0] == pytest.approx(math.sqrt(math.pi * s0 * 340.0 / 1500.0), rel=REL_EXACT)
    # σ_travel² ∝ v: it grows with the speed, to √4 = 2 times the start once at 20 m/s and settled
    assert r["travel"].sigma[-1] > 1.9 * r["travel"].sigma[0]
    assert r["travel"].sigma.shape == r.times.shape == r["travel"].nu0_plus.shape
    assert r.monte_carlo is None and r.sigma_comparison is None
    assert "TransientResult" in repr(r) and "travel" in str(r)


def test_against_the_cli_with_monte_carlo(cli, root, tmp_path):
    want = cli.json("transient", SCENARIO, "--monte-carlo", "6", "-o", str(tmp_path / "cli.h5"), "--seed", "4")
    r = stochvib.Scenario.load(root / SCENARIO).transient(
        monte_carlo=6, path=tmp_path / "py.h5", seed=4, progress=False
    )
    got = r.to_dict()
    for g, w in zip(got["exact"]["outputs"], want["exact"]["outputs"]):
        np.testing.assert_allclose(g["sigma"], w["sigma"], rtol=REL_SAME)
        np.testing.assert_allclose(g["mean"], w["mean"], rtol=REL_SAME, atol=0.0)
    assert got["exact"]["mission"] == want["exact"]["mission"]
    assert got["sigma"] == want["sigma"]  # the same seeded batch: σ(t) per time with its interval
    assert got["monte_carlo"]["n_realizations"] == 6 and (tmp_path / "py.h5").is_file()
    c = r.sigma_comparison[0]
    assert set(c) >= {"output", "rows", "coverage", "outside"}


def test_temporary_run_and_shards(root, tmp_path):
    sc = stochvib.Scenario.load(root / SCENARIO)
    r = sc.transient(monte_carlo=4, seed=1, progress=False)
    assert r.sigma_comparison and r.monte_carlo["n_realizations"] == 4
    assert not Path(r.monte_carlo["path"]).exists()  # the temporary run file is removed
    for i in range(2):
        sc.transient(monte_carlo=4, seed=1, shard_size=2, path=tmp_path / "parts", shard=(i, 2), progress=False)
    assert sorted(p.name for p in (tmp_path / "parts").iterdir()) == ["shard-0-of-2.h5", "shard-1-of-2.h5"]


def test_refusals(root):
    with pytest.raises(InvalidInputError, match="shard"):
        stochvib.Scenario.load(root / SCENARIO).transient(monte_carlo=4, shard=(0, 2))
    with pytest.raises((InvalidInputError, NotApplicableError, stochvib.FileError)):
        stochvib.Scenario.load(root / "data" / "conveyor-idler.toml").transient()
