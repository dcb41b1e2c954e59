"""A road of two coherent tracks built in Python (``Scenario.from_system(..., coherence=, track_width=,
tracks=, positions=)``): against the command-line tool's ``--json`` for the same scenario file (analysis and
Monte Carlo), and against a closed form for a constant coherence; bad input named."""

from __future__ import annotations

import numpy as np
import pytest

import stochvib
from stochvib import InvalidInputError

# The same library computation (the same excitation, the same order of operations) through the file and
# through Python: the JSON's shortest round-trip floats read back.
REL_SAME = 1e-15
# Two Lyapunov solutions of different systems (one input and two inputs) whose variances are in the exact
# ratio 2 + 2ρ: each to ~1e-13 relative.
REL_RATIO = 1e-10

FULL_VEHICLE = dict(
    mass="1400 kg",
    pitch_inertia="2100 kg*m^2",
    roll_inertia="500 kg*m^2",
    front_distance="1.2 m",
    rear_distance="1.5 m",
    track_width="1.5 m",
    tyre_stiffness="200 kN/m",
    suspension_stiffness={"front": "25 kN/m", "rear": "22 kN/m"},
    suspension_damping={"front": "2000 N*s/m", "rear": "1800 N*s/m"},
    unsprung_mass={"front": "40 kg", "rear": "35 kg"},
    seat={"ahead": "0.3 m", "left": "0.35 m"},
)
OUTPUTS = ["seat_acc", "bounce", "pitch", "roll", "travel_fl", "travel_rr", "tyre_force_fl"]
DODDS_ROBSON = {"kind": "dodds-robson", "waviness": 2}


def full_vehicle_scenario() -> stochvib.Scenario:
    """data/full-vehicle-two-tracks.toml built in Python: the model's own layout (fl, fr at 0 m, rl, rr at
    the wheelbase 2.7 m on the left/right tracks) and track width."""
    car = stochvib.System.model("full-vehicle", **FULL_VEHICLE)
    road = stochvib.Spectrum.load("iso8608-c")
    return stochvib.Scenario.from_system(
        car, road, speed="20 m/s", coherence=DODDS_ROBSON, outputs=OUTPUTS, duration_s="1 h"
    )


def test_full_vehicle_on_two_tracks_matches_the_cli(cli):
    want = cli.json("analyze", "data/full-vehicle-two-tracks.toml")
    r = full_vehicle_scenario().analyze()
    got = r.to_dict()["outputs"]
    assert [o["statistics"]["name"] for o in got] == OUTPUTS
    for g, w in zip(got, want["outputs"]):
        for key in ("mean", "variance", "sigma", "lambda2", "zero_upcrossing_rate"):
            assert g["statistics"][key] == pytest.approx(w["statistics"][key], rel=REL_SAME, abs=0.0), key
        methods = {m["method"]: m["outcome"] for m in w["statistics"]["methods"]}
        assert [m["method"] for m in g["statistics"]["methods"]] == list(methods)
        for m in g["statistics"]["methods"]:
            want_m = methods[m["method"]]
            assert m["outcome"]["status"] == want_m["status"], m["method"]
            if want_m.get("value") is not None:
                assert m["outcome"]["value"] == pytest.approx(want_m["value"], rel=REL_SAME), m["method"]


def test_full_vehicle_monte_carlo_matches_the_cli(cli):
    # the same seeded batch (realization i uses the stream (seed, i)) of the same excitation: the same numbers
    args = ("--monte-carlo", "4", "--dt", "0.005", "--duration", "20", "--seed", "7")
    want = cli.json("analyze", "data/full-vehicle-two-tracks.toml", *args)
    r = full_vehicle_scenario().analyze(monte_carlo=4, dt=0.005, duration=20.0, seed=7, progress=False)
    for g, w in zip(r.to_dict()["outputs"], want["outputs"]):
        assert g["monte_carlo"] is not None
        assert g["monte_carlo"] == w["monte_carlo"]


def test_constant_coherence_closed_form():
    # y = H(s)(u_left + u_right), H = 1/(s + a): with Var u_l = Var u_r and cross-density ρ S(ω) (a constant
    # coherence amplitude ρ, no delay), S_y = |H|² (2 + 2ρ) S, so σ_y² is (2 + 2ρ) times that of H u alone.
    a, rho = 3.0, 0.4
    two = stochvib.System.state_space([[-a]], [[1.0, 1.0]], [[1.0]], [[0.0, 0.0]])
    one = stochvib.System.state_space([[-a]], [[1.0]], [[1.0]], [[0.0]])
    road = stochvib.Spectrum.load("iso8608-b")
    r2 = stochvib.analyze(
        two,
        road,
        speed="15 m/s",
        coherence={"kind": "constant", "coherence_amplitude": rho},
        track_width="1.6 m",
        tracks=["left", "right"],
    )
    r1 = stochvib.analyze(one, road, speed="15 m/s")
    assert r2["y1"].variance == pytest.approx((2 + 2 * rho) * r1["y1"].variance, rel=REL_RATIO)
    # a wheelbase delay of the right track by ℓ/v adds the cross term 2ρ Re(e^{-iωℓ/v}) S: less than 2 + 2ρ
    r3 = stochvib.analyze(
        two,
        road,
        speed="15 m/s",
        coherence={"kind": "constant", "coherence_amplitude": rho},
        track_width="1.6 m",
        tracks=["left", "right"],
        positions=[0.0, "2.5 m"],
    )
    assert 2 * r1["y1"].variance < r3["y1"].variance < r2["y1"].variance


def test_two_track_input_errors():
    car = stochvib.System.model("full-vehicle", **FULL_VEHICLE)
    road = stochvib.Spectrum.load("iso8608-c")
    with pytest.raises(InvalidInputError, match="coherence"):
        stochvib.analyze(car, road, speed="20 m/s")
    with pytest.raises(InvalidInputError, match="track width is 1.5 m"):
        stochvib.analyze(car, road, speed="20 m/s", coherence=DODDS_ROBSON, track_width="1.6 m")
    with pytest.raises(InvalidInputError, match="speed"):
        stochvib.analyze(car, road, coherence=DODDS_ROBSON)
    two = stochvib.System.state_space([[-1.0]], [[1.0, 1.0]], [[1.0]], [[0.0, 0.0]])
    with pytest.raises(InvalidInputError, match="tracks"):
        stochvib.analyze(two, road, speed="20 m/s", coherence=DODDS_ROBSON, track_width="1.5 m", tracks=["left"])
    with pytest.raises(InvalidInputError, match="left"):
        stochvib.analyze(two, road, speed="20 m/s", coherence=DODDS_ROBSON, track_width="1.5 m", tracks=["up", 1])
    white = stochvib.Spectrum.load("type1")
    with pytest.raises(InvalidInputError, match="spatial"):
        stochvib.analyze(two, white, speed="20 m/s", coherence=DODDS_ROBSON, track_width="1.5 m", tracks=[0, 1])
    assert np.isfinite(
        stochvib.analyze(two, road, speed="20 m/s", coherence=DODDS_ROBSON, track_width="1.5 m", tracks=[0, 1])["y1"].sigma
    )
