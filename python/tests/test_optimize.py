"""Scenario.optimize against the closed-form optimum of the quarter car under white road velocity, with the
travel constraint active and inactive where the closed form puts it, an infeasible problem answered with its
shortfall, the command-line tool's ``stochvib optimize --json`` for the same problem, and bad input.

Quarter car m_s = 400 kg, m_u = 40 kg, k_s = 20 kN/m, k_t = 200 kN/m (no tyre damping) on an ISO 8608 class C
road without band limits (w = 2: the road velocity q̇ = v dq/dx is white) at v = 20 m/s. Its two-sided
angular density: G_d(n) = G_d(n₀)(n₀/n)² gives q̇ the one-sided cyclic density 4π²n₀²G_d(n₀)v, so
S₀ = πn₀²G_d(n₀)v (G_d(n₀) = 256·10⁻⁶ m³ at n₀ = 0.1 cycles/m, ISO 8608:2016 Table 3). With the state
[x_s − x_u, ẋ_s, x_u − q, ẋ_u] the stationary Lyapunov equation solved by hand (M = m_s + m_u) gives

    σ²_acc = πS₀(k_t c² + k_s²M)/(c m_s²),   σ²_travel = πS₀M/c,

so σ_acc is least at c_opt = k_s√(M/k_t), where σ²_acc = 2πS₀k_s√(k_t M)/m_s² (the classical white-velocity
results; Gobbi & Mastinu 2001, J. Sound Vib. 245(3) 457–481). 3σ_travel ≤ d is c ≥ c_min = 9πS₀M/d², and
σ²_acc is convex in c: the constrained optimum is max(c_opt, c_min)."""

from __future__ import annotations

import math

import pytest

import stochvib
from stochvib import InvalidInputError

# COBYLA stops at a trust radius of 1e-9 of the range; an interior minimum is flat (the objective is quadratic
# in c − c_opt), so the argument is found to ~√ of the objective's resolution: 1e-6 relative, and the value
# to its square.
REL_ARGMIN = 1e-6
REL_MIN = 1e-10
# On an active constraint the argument is fixed by the constraint (a simple root): 1e-8 relative.
REL_ON_CONSTRAINT = 1e-8
# The same library computation through the file and the command-line tool: identical numbers.
REL_SAME = 1e-15

QUARTER_CAR = """
title = "Quarter car under white road velocity"
source = "test: closed forms of the white-velocity quarter car"
[model]
kind = "quarter-car"
sprung_mass = "400 kg"
unsprung_mass = "40 kg"
suspension_stiffness = "20 kN/m"
suspension_damping = "1.5 kN*s/m"
tyre_stiffness = "200 kN/m"
[input]
spectrum = { kind = "iso8608", class = "C", bound = "mean", unbounded = true }
speed = "20 m/s"
[analysis]
outputs = ["body_acc", "travel", "tyre_force"]
"""
M_S, M_U, K_S, K_T = 400.0, 40.0, 20e3, 200e3
M = M_S + M_U
S0 = math.pi * 0.1**2 * 256e-6 * 20.0
C_OPT = K_S * math.sqrt(M / K_T)
PARAM = {"model.suspension_damping": ("0.2 kN*s/m", "6 kN*s/m")}


def sigma_acc(c: float) -> float:
    return math.sqrt(math.pi * S0 * (K_T * c * c + K_S**2 * M) / (c * M_S**2))


@pytest.fixture
def quarter_car(tmp_path):
    p = tmp_path / "quarter-car.toml"
    p.write_text(QUARTER_CAR)
    return p


def test_comfort_optimum_is_ks_sqrt_m_over_kt(quarter_car):
    r = stochvib.Scenario.load(quarter_car).optimize(PARAM, minimize="sigma(body_acc)")
    assert isinstance(r, stochvib.OptimizeResult) and r.feasible and r.goal == "minimize"
    assert r.params[0].key == "model.suspension_damping" and r.params[0].at_bound is None
    assert r.x["model.suspension_damping"] == pytest.approx(C_OPT, rel=REL_ARGMIN)
    var_min = 2 * math.pi * S0 * K_S * math.sqrt(K_T * M) / M_S**2
    assert r.value == pytest.approx(math.sqrt(var_min), rel=REL_MIN)
    assert r.unit == "m/s^2"
    assert r.violations == [] and "minimum of sigma(body_acc)" in str(r)
    assert "OptimizeResult: minimize of sigma(body_acc)" in repr(r)


def test_travel_constraint_active_and_inactive(quarter_car):
    sc = stochvib.Scenario.load(quarter_car)
    d = 0.040  # c_min = 9πS₀M/d² > c_opt: the constraint is active and c* = c_min
    c_min = 9 * math.pi * S0 * M / d**2
    assert c_min > C_OPT
    r = sc.optimize(PARAM, minimize="sigma(body_acc)", constraints=["3sigma(travel) <= 40 mm"])
    assert r.feasible and r.constraints[0].active and r.constraints[0].met
    assert r.x["model.suspension_damping"] == pytest.approx(c_min, rel=REL_ON_CONSTRAINT)
    assert r.value == pytest.approx(sigma_acc(c_min), rel=REL_ON_CONSTRAINT)
    assert r.constraints[0].value == pytest.approx(d, rel=REL_ON_CONSTRAINT)
    d = 0.060  # c_min < c_opt: inactive, margin d − 3√(πS₀M/c_opt)
    r = sc.optimize(PARAM, minimize="sigma(body_acc)", constraints=["3sigma(travel) <= 60 mm"])
    assert r.feasible and not r.constraints[0].active
    assert r.x["model.suspension_damping"] == pytest.approx(C_OPT, rel=REL_ARGMIN)
    assert r.constraints[0].margin == pytest.approx(d - 3 * math.sqrt(math.pi * S0 * M / C_OPT), rel=REL_ARGMIN)


def test_infeasible_is_answered_with_the_shortfall(quarter_car):
    # 3σ_travel ≤ 5 mm needs c ≥ 8·10⁴ N s/m, beyond 6 kN s/m: the least violating point is the upper bound,
    # where 3σ_travel = 3√(πS₀M/6000)
    r = stochvib.Scenario.load(quarter_car).optimize(
        PARAM, minimize="sigma(body_acc)", constraints=["3sigma(travel) <= 5 mm"]
    )
    assert not r.feasible and r.params[0].at_bound == "upper"
    assert r.constraints[0].value == pytest.approx(3 * math.sqrt(math.pi * S0 * M / 6000.0), rel=REL_ON_CONSTRAINT)
    assert len(r.violations) == 1 and "cannot be met" in r.violations[0]
    assert "INFEASIBLE" in repr(r)


def test_maximum_at_a_bound_and_the_cli(cli, quarter_car):
    r = stochvib.Scenario.load(quarter_car).optimize(
        {"model.suspension_damping": "0.2:6 kN*s/m"}, maximize="sigma(travel)", starts=2
    )
    assert r.params[0].at_bound == "lower"
    assert r.value == pytest.approx(math.sqrt(math.pi * S0 * M / 200.0), rel=REL_ON_CONSTRAINT)
    want = cli.json(
        "optimize", str(quarter_car), "--param", "model.suspension_damping=0.2:6 kN*s/m", "--maximize", "sigma(travel)", "--starts", "2"
    )
    got = r.to_dict()
    assert got["value"] == pytest.approx(want["value"], rel=REL_SAME)
    assert got["params"] == want["params"] and got["evaluations"] == want["evaluations"]


def test_bad_input(quarter_car):
    sc = stochvib.Scenario.load(quarter_car)
    with pytest.raises(InvalidInputError, match="exactly one"):
        sc.optimize(PARAM)
    with pytest.raises(InvalidInputError, match="exactly one"):
        sc.optimize(PARAM, minimize="sigma(travel)", maximize="sigma(travel)")
    with pytest.raises(InvalidInputError, match="lower bound"):
        sc.optimize({"model.suspension_damping": ("6 kN*s/m", "0.2 kN*s/m")}, minimize="sigma(travel)")
    with pytest.raises(InvalidInputError, match=r"\(low, high\)"):
        sc.optimize({"model.suspension_damping": ("1 kN*s/m",)}, minimize="sigma(travel)")
    with pytest.raises(InvalidInputError):
        sc.optimize(PARAM, minimize="sigma(nothing)")


FRONT_ARGS = ["--param", "model.suspension_damping=0.2:6 kN*s/m", "--minimize", "sigma(body_acc)", "--pareto", "3sigma(travel)", "--points", "5", "--starts", "2"]


def test_pareto_front_against_the_closed_form_and_the_cli(cli, quarter_car, tmp_path):
    """Comfort against travel: σ_acc is least at c_opt, 3σ_travel = 3√(πS₀M/c) at the upper bound 6 kN s/m; an
    inner point minimises σ_acc with 3σ_travel ≤ ε, active (σ_acc grows beyond c_opt), so c = 9πS₀M/ε²."""
    fr = stochvib.Scenario.load(quarter_car).pareto(
        {"model.suspension_damping": "0.2:6 kN*s/m"}, minimize="sigma(body_acc)", pareto="3sigma(travel)", points=5, starts=2, plots=tmp_path / "py"
    )
    assert isinstance(fr, stochvib.ParetoFront) and fr.keys == ["model.suspension_damping"]
    assert fr.units == ["m/s^2", "m"] and fr.values.shape == (5, 2) and fr.params.shape == (5, 1)
    first, last = fr.points[0], fr.points[-1]
    assert first.limit is None and last.limit is None
    assert first.params["model.suspension_damping"] == pytest.approx(C_OPT, rel=REL_ARGMIN)
    assert last.params["model.suspension_damping"] == pytest.approx(6000.0, rel=REL_ON_CONSTRAINT)
    assert last.values[1] == pytest.approx(3 * math.sqrt(math.pi * S0 * M / 6000.0), rel=REL_ON_CONSTRAINT)
    for p in fr.points[1:-1]:
        c = 9 * math.pi * S0 * M / p.limit**2
        assert p.feasible and p.values[1] == pytest.approx(p.limit, rel=REL_ON_CONSTRAINT)
        assert p.params["model.suspension_damping"] == pytest.approx(c, rel=REL_ON_CONSTRAINT)
        assert p.values[0] == pytest.approx(sigma_acc(c), rel=REL_ON_CONSTRAINT)
    assert list(fr.values[:, 0]) == sorted(fr.values[:, 0]) and list(fr.values[:, 1]) == sorted(fr.values[:, 1], reverse=True)
    # the command-line tool: the same JSON, the same CSV, the same picture
    assert fr.to_dict() == cli.json("optimize", str(quarter_car), *FRONT_ARGS)
    assert fr.to_csv() == str(fr) == cli.run("optimize", str(quarter_car), *FRONT_ARGS, "--plots", str(tmp_path / "cli")).stdout
    assert sorted(p.name for p in fr.plots) == ["pareto-front.png", "pareto-front.svg"]
    assert (tmp_path / "py" / "pareto-front.svg").read_text() == (tmp_path / "cli" / "pareto-front.svg").read_text()
    assert repr(fr).startswith("ParetoFront of sigma(body_acc) [m/s^2] and 3sigma(travel) [m]: 5 points")
    assert repr(fr.points[0]).startswith("model.suspension_damping = ")


def test_pareto_front_bad_input(quarter_car):
    sc = stochvib.Scenario.load(quarter_car)
    with pytest.raises(InvalidInputError, match="at least its two ends"):
        sc.pareto(PARAM, minimize="sigma(body_acc)", pareto="sigma(travel)", points=1)
    with pytest.raises(InvalidInputError, match="no point meets every constraint"):
        sc.pareto(PARAM, minimize="sigma(body_acc)", pareto="sigma(travel)", constraints=["3sigma(travel) <= 5 mm"], points=3)
    with pytest.raises(TypeError):
        sc.pareto(PARAM, minimize="sigma(body_acc)")  # the second quantity is required


def test_kkt_check_at_an_active_constraint_against_the_closed_form(cli, quarter_car):
    """At c* = c_min (the travel constraint active) the analytic gradients are those of the closed forms:
    dσ_acc/dc = πS₀(k_t − k_s²M/c²)/(2σ_acc m_s²) and d(3σ_travel)/dc = −(3/2)√(πS₀M) c^{−3/2}; the KKT check holds
    with a positive multiplier."""
    sc = stochvib.Scenario.load(quarter_car)
    r = sc.optimize(PARAM, minimize="sigma(body_acc)", constraints=["3sigma(travel) <= 40 mm"])
    c = r.x["model.suspension_damping"]
    k = r.kkt
    assert isinstance(k, stochvib.KktCheck) and k.satisfied and k.residual <= 1e-5
    dacc = math.pi * S0 * (K_T - K_S**2 * M / c**2) / (2 * sigma_acc(c) * M_S**2)
    assert k.gradient[0] == pytest.approx(dacc, rel=REL_ON_CONSTRAINT)
    assert k.constraint_gradients[0, 0] == pytest.approx(-1.5 * math.sqrt(math.pi * S0 * M) * c**-1.5, rel=REL_ON_CONSTRAINT)
    assert k.multipliers[0] > 0 and k.bound_multipliers[0] == 0
    want = cli.json("optimize", str(quarter_car), "--param", "model.suspension_damping=0.2:6 kN*s/m", "--minimize", "sigma(body_acc)", "--constraint", "3sigma(travel) <= 40 mm")
    assert k.to_dict() == want["kkt"] == r.to_dict()["kkt"]
    assert "KKT: stationarity residual" in repr(r) and "KKT: stationarity residual" in str(r)


def test_pareto_front_and_kkt_as_tables(quarter_car):
    pd = pytest.importorskip("pandas")
    sc = stochvib.Scenario.load(quarter_car)
    fr = sc.pareto(PARAM, minimize="sigma(body_acc)", pareto="3sigma(travel)", points=3, starts=1)
    df = fr.to_dataframe()
    assert isinstance(df, pd.DataFrame) and len(df) == 3
    assert list(df.columns) == ["model.suspension_damping", "sigma(body_acc) [m/s^2]", "3sigma(travel) [m]", "limit", "feasible"]
    assert df["sigma(body_acc) [m/s^2]"].tolist() == fr.values[:, 0].tolist()
    r = sc.optimize(PARAM, minimize="sigma(body_acc)", constraints=["3sigma(travel) <= 40 mm"])
    assert r.to_dataframe()["key"].tolist() == ["model.suspension_damping"]
