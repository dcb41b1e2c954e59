"""stochvib.analyze / Scenario.analyze: variances against scipy.linalg.solve_continuous_lyapunov, crossing rates
against Rice's formula, the reports against the command-line tool (`stochvib analyze --json`), errors."""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.linalg import solve_continuous_lyapunov

import stochvib
from stochvib import InvalidInputError, Scenario, Spectrum, System

# --- named tolerances -------------------------------------------------------------------------------------
# Two Lyapunov solvers (the library's Bartels–Stewart, scipy's LAPACK one) on a 3-state, well-scaled system.
REL_LYAP = 1e-10
# The library's adaptive quadrature against an exact variance: its default relative tolerance is 1e-10;
# 1e-8 leaves room for its error estimate being an estimate.
REL_QUAD = 1e-8
# Formulas (Rice, 3σ bounds) recomputed here from the reported σ, mean and moments: a few roundings.
REL_FORMULA = 1e-13

# SDOF under a force: m ẍ + b ẋ + k x = F, m = 20 kg, b = 60 N s/m, k = 8 kN/m (ωₙ = 20 rad/s, ζ = 0.075);
# F of type 1 with D = 4 N², α = 5 1/s.
M, B, K = 20.0, 60.0, 8000.0
D_F, ALPHA = 4.0, 5.0


def sdof():
    return System.mdof(
        mass=[[M]], damping=[[B]], stiffness=[[K]], coordinates=[("x", "m")], outputs={"x": ("displacement", [1]), "v": ("velocity", [1])}
    )


def scipy_covariance():
    """Stationary covariance of z = [x_F, x, v] by scipy.

    Shaping filter of type 1: x_F' = −α x_F + g w with unit white noise w (E[w(t)w(t+τ)] = δ(τ), two-sided
    density 1/2π): S_F = g²/(2π(α² + ω²)), equal to αD/(π(α² + ω²)) for g² = 2αD. Then
    z' = A z + G w with A = [[−α, 0, 0], [0, 0, 1], [1/m, −k/m, −b/m]], G = [g, 0, 0]ᵀ, and the
    covariance P solves A P + P Aᵀ + G Gᵀ = 0 (scipy solves A X + X Aᴴ = Q: Q = −G Gᵀ).
    """
    g = math.sqrt(2.0 * ALPHA * D_F)
    a = np.array([[-ALPHA, 0.0, 0.0], [0.0, 0.0, 1.0], [1.0 / M, -K / M, -B / M]])
    gg = np.array([[g * g, 0.0, 0.0], [0.0, 0.0, 0.0], [0.0, 0.0, 0.0]])
    return solve_continuous_lyapunov(a, -gg)


def test_lyapunov_variance_against_scipy():
    p = scipy_covariance()
    r = stochvib.analyze(sdof(), Spectrum.exponential(D_F, ALPHA, unit="N"), mean=10.0, levels={"x": [1e-3]})
    x = r["x"]
    assert x.method("lyapunov")["value"] == pytest.approx(p[1, 1], rel=REL_LYAP)
    assert x.method("integral-table")["value"] == pytest.approx(p[1, 1], rel=REL_LYAP)
    q = x.method("quadrature")
    assert q["value"] == pytest.approx(p[1, 1], rel=REL_QUAD)
    assert 0 < q["error_estimate"] < REL_QUAD * p[1, 1]
    assert x.variance == pytest.approx(p[1, 1], rel=REL_LYAP)
    assert x.sigma == pytest.approx(math.sqrt(p[1, 1]), rel=REL_LYAP)
    assert r["v"].sigma == pytest.approx(math.sqrt(p[2, 2]), rel=REL_LYAP)
    # λ₂ of x is the variance of ẋ = v: ν₀⁺ = (1/2π)√(λ₂/λ₀) = (1/2π)√(P_vv/P_xx)
    assert x.zero_upcrossing_rate == pytest.approx(math.sqrt(p[2, 2] / p[1, 1]) / (2 * math.pi), rel=REL_LYAP)
    # mean M_x = H(0)·M_F = 10 N / k
    assert x.mean == pytest.approx(10.0 / K, rel=REL_FORMULA)
    lo, hi = x.three_sigma
    assert lo == pytest.approx(x.mean - 3 * x.sigma, rel=REL_FORMULA)
    assert hi == pytest.approx(x.mean + 3 * x.sigma, rel=REL_FORMULA)
    # Rice: ν_a⁺ = ν₀⁺ exp(−(a − M)²/(2σ²)); the first level is M + 3σ, then the requested 1 mm
    levels = x.levels
    assert [l["level"] for l in levels] == pytest.approx([hi, 1e-3], rel=REL_FORMULA)
    for l in levels:
        rate = x.zero_upcrossing_rate * math.exp(-((l["level"] - x.mean) ** 2) / (2 * x.sigma**2))
        assert l["upcrossing_rate"] == pytest.approx(rate, rel=REL_FORMULA)
        # Poisson exceedance within the default duration 3600 s
        assert l["exceedance_probability"] == pytest.approx(-math.expm1(-rate * 3600.0), rel=1e-12)
    assert r.sigma == {"x": x.sigma, "v": r["v"].sigma}
    d = r.to_dict()
    assert d["outputs"][0]["statistics"]["name"] == "x" and d["duration_s"] == 3600.0
    assert "lyapunov" in str(r)


def test_divergent_acceleration_is_reported_with_the_diagnosis():
    # base-excited mass through a spring and a damper: H_acc(iω) = −ω²(k + iωb)/(k − mω² + iωb) → ~ iωb/m·(−1),
    # |H|² ~ (b/m)² ω², times a type-1 input ~ ω⁻²: S_y tends to a constant and ∫S_y dω diverges.
    base = System.mdof(
        mass=[[M]], damping=[[B]], stiffness=[[K]], base_stiffness=[[K]], base_damping=[[B]],
        outputs={"acc": ("acceleration", [1])},
    )
    road = Spectrum.exponential(1e-4, 2.0)
    r = stochvib.analyze(base, road, band_rad_s=(0.0, 200.0))
    acc = r["acc"]
    assert acc.sigma is None and acc.variance is None
    assert "infinite" in acc.variance_note
    assert acc.band_sigma is not None and acc.band_sigma > 0  # a finite band has a finite σ
    assert acc.variance_outcome["status"] == "divergent"
    divergent = [m for m in acc.methods if m["status"] == "divergent"]
    assert divergent and all("infinite" in m["reason"] and m["value"] is None for m in divergent)


def test_quadrature_effort_as_the_cli_flags(cli):
    # A quadrature held to one subinterval and two half-periods does not converge: the report says so (the
    # estimate, and which option raises the effort) instead of raising, exactly as
    # `stochvib analyze --max-subintervals 1 --max-half-periods 2` does.
    path = "data/quarter-car.toml"
    want = cli.json("analyze", path, "--max-subintervals", "1", "--max-half-periods", "2")
    r = stochvib.analyze(path, max_subintervals=1, max_half_periods=2)
    assert r.to_dict() == want
    q = r["tyre_force"].method("quadrature")
    assert q["status"] == "not-converged" and q["value"] is None and q["estimate"] > 0
    assert "max_subintervals (now 1)" in q["reason"] and "max_half_periods (now 2)" in q["reason"]
    assert r["tyre_force"].variance is None and "max_subintervals" in r["tyre_force"].variance_note
    # the scenario's own options stay untouched; a tolerance the library refuses is an InvalidInputError
    assert stochvib.analyze(path).to_dict() == cli.json("analyze", path)
    with pytest.raises(InvalidInputError, match="rel_tol"):
        Scenario.load(path).analyze(rel_tol=-1.0)


@pytest.mark.parametrize(
    "path", ["data/quarter-car.toml", "data/conveyor-idler.toml", "data/half-car.toml", "data/scraper-sprung-cab.toml"]
)
def test_analysis_identical_to_cli(cli, path):
    # the Rust library's report for the same file: `stochvib analyze PATH --json`
    want = cli.json("analyze", path)
    r = stochvib.analyze(path)
    assert r.to_dict() == want
    assert str(r).rstrip("\n") == cli.run("analyze", path).stdout.rstrip("\n")


def test_deterministic_and_reference_files_identical_to_cli(cli):
    # one result type per kind of analysis: tables() for these files, analyze() refuses them
    for path in ("data/mine-hoist.toml", "data/reference/table-8-1.toml"):
        r = Scenario.load(path).tables()
        assert isinstance(r, stochvib.TablesResult) and not isinstance(r, stochvib.AnalysisResult)
        assert r.to_dict() == cli.json("analyze", path)
        with pytest.raises(stochvib.NotApplicableError, match=r"tables\(\)"):
            stochvib.analyze(path)
    with pytest.raises(stochvib.NotApplicableError, match="deterministic"):
        Scenario.load("data/mine-hoist.toml").system
    with pytest.raises(stochvib.NotApplicableError, match="analyze"):
        Scenario.load("data/quarter-car.toml").tables()


def test_from_system_equals_the_scenario_file():
    # data/conveyor-idler.toml written in Python: the catalogue model, the catalogue spectrum, the mean 10 kN
    sys = System.model("conveyor-idler", m="100 kg", c="70 kN/m", zeta=0.2)
    lump = Spectrum.load("conveyor-lump-load")
    py = stochvib.analyze(sys, lump, mean=10e3, outputs=["y", "y_vel"])
    f = stochvib.analyze("data/conveyor-idler.toml")
    assert [o.to_dict() for o in py] == [o.to_dict() for o in f]
    # a road under two axles: the half car's layout gives the wheelbase delay from the speed
    sc = Scenario.load("data/half-car.toml")
    py = stochvib.analyze(sc.system, sc.input, speed=sc.speed, outputs=sc.outputs)
    assert [o.to_dict() for o in py] == [o.to_dict() for o in stochvib.analyze(sc)]


def test_analysis_argument_errors():
    sys = sdof()
    road = Spectrum.iso8608("C")
    with pytest.raises(InvalidInputError, match="speed"):
        stochvib.analyze(sys, road)  # a spatial spectrum needs a speed
    with pytest.raises(InvalidInputError, match="no such output; the system has: x, v"):
        stochvib.analyze(sys, Spectrum.exponential(1, 1), outputs=["y"])
    two = System.mdof(mass=np.eye(2), damping=np.eye(2), stiffness=np.eye(2))
    with pytest.raises(InvalidInputError, match="2 inputs"):
        stochvib.analyze(two, Spectrum.exponential(1, 1))
    # one independent spectrum per input, or one track with positions
    r = stochvib.analyze(two, [Spectrum.exponential(1, 1), Spectrum.exponential(2, 3)])
    assert len(r) == 2
    r = stochvib.analyze(two, Spectrum.exponential(1, 1), positions=[0.0, 0.0])
    assert len(r) == 2
    with pytest.raises(InvalidInputError, match="speed"):
        stochvib.analyze(two, Spectrum.exponential(1, 1), positions=[0.0, 1.0])
    with pytest.raises(InvalidInputError, match="input"):
        stochvib.analyze(sys, 42)
    # a catalogue name is loaded as Spectrum.load does
    by_name = stochvib.analyze(sys, "type1", outputs=["x"])
    assert by_name["x"].to_dict() == stochvib.analyze(sys, Spectrum.load("type1"), outputs=["x"])["x"].to_dict()
    with pytest.raises(InvalidInputError, match="input="):
        stochvib.analyze(sys)
    with pytest.raises(InvalidInputError, match="duration_s"):
        stochvib.analyze(sys, Spectrum.exponential(1, 1), duration_s=-1.0)


def test_file_errors_carry_the_cli_message(cli, tmp_path):
    with pytest.raises(stochvib.FileError) as e:
        Scenario.load("data/no-such-file.toml")
    assert isinstance(e.value, OSError)
    assert e.value.path == "data/no-such-file.toml"
    # The CLI prints the error with anyhow's `{:#}`, which appends the io::Error source a second time
    # ("…: No such file or directory (os error 2): No such file or directory (os error 2)"); the library's
    # message is the first part.
    assert cli.error("analyze", "data/no-such-file.toml").startswith(str(e.value))
    assert str(e.value).endswith("(os error 2)")
    bad = tmp_path / "bad.toml"
    bad.write_text(
        (stochvib_root() / "data" / "conveyor-idler.toml").read_text().replace('m = "100 kg"', 'm = "-100 kg"')
    )
    with pytest.raises(stochvib.FileError) as e:
        Scenario.load(bad)
    assert e.value.key == "model.m"
    assert str(e.value) == cli.error("analyze", str(bad))
    unit = tmp_path / "unit.toml"
    unit.write_text((stochvib_root() / "data" / "conveyor-idler.toml").read_text().replace('"70 kN/m"', '"70 furlong"'))
    with pytest.raises(stochvib.FileError) as e:
        Scenario.load(unit)
    assert str(e.value) == cli.error("analyze", str(unit))


def stochvib_root():
    from conftest import ROOT

    return ROOT
