"""Road profile analysis on arrays: against the command-line tool's ``stochvib road --json`` for the same
profile (the Rust library's answer for a file), against scipy.signal.welch for the density, and against the
ISO 8608 class limits."""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy import signal

import stochvib
from stochvib import InvalidInputError

# --- named tolerances -------------------------------------------------------------------------------------
# The same computation on the same numbers: the tool reads the CSV (0.001 mm digits) and converts mm to m as
# the test does with numpy, and computes the step as the mean spacing; what remains is a few roundings of the
# parse and of the step, carried through FFTs of 2048 points and a least-squares fit.
REL_SAME = 1e-9
# The library's K₁ (its own series / asymptotic expansion) against scipy.special.k1 (Cephes): both to ~1e-14,
# the product x K₁(x) near 1e-15; 1e-9 leaves room for the library's stated accuracy of its Bessel function.
REL_BESSEL = 1e-9
# scipy.signal.welch (pocketfft) against the library (realfft) on 256-point segments: FFT rounding.
REL_WELCH = 1e-9


def read_profile(root):
    d = np.loadtxt(root / "data" / "measured-profile.csv", delimiter=",", comments="#", skiprows=7)
    return (d[-1, 0] - d[0, 0]) / (len(d) - 1), d[:, 1] / 1000.0, d[:, 2] / 1000.0


def test_profile_analysis_against_the_cli(cli, root):
    want = cli.json("road", "data/measured-profile.csv")
    step, left, right = read_profile(root)
    r = stochvib.road.analyze_profile({"left": left, "right": right}, step)
    assert (r.samples, r.segment_len, r.segments) == (want["samples"], want["segment_len"], want["segments"])
    assert r.dof == pytest.approx(want["dof"], rel=REL_SAME)
    for got, exp in zip(r.tracks, want["tracks"]):
        assert got.name == exp["name"]
        np.testing.assert_allclose(got.n, [b["n"] for b in exp["density"]], rtol=REL_SAME)
        np.testing.assert_allclose(got.G_d, [b["g_d"] for b in exp["density"]], rtol=REL_SAME)
        np.testing.assert_allclose(got.upper, [b["upper"] for b in exp["density"]], rtol=REL_SAME)
        assert got.iri_m_per_km == pytest.approx(exp["iri_m_per_km"], rel=REL_SAME)
        assert got.sigma_m == pytest.approx(exp["sigma_m"], rel=REL_SAME)
        for f, e in zip(got.fits, exp["fits"]):
            assert (f.mode, f.road_class) == (e["waviness_mode"], e["class"])
            assert f.g0_m3 == pytest.approx(e["g0_m3"], rel=REL_SAME)
            assert f.waviness == pytest.approx(e["waviness"], rel=REL_SAME)
            # the goodness of fit: the same as the command's; the synthetic class C road follows the law
            assert f.fit_p_value == pytest.approx(e["fit_p_value"], rel=REL_SAME) and f.fit_p_value > 1e-6
    # the synthetic profile was drawn from class C's geometric mean, G_d(n0) = 256e-6 m^3, w = 2
    assert r["left"].road_class == "C" and r.tracks[0].fits[1].waviness_interval[0] < 2.0
    np.testing.assert_allclose(
        r.coherence.gamma2, [c["squared_coherence"] for c in want["coherence"]], rtol=REL_SAME, atol=1e-12
    )
    assert r.coherence.tracks == ("left", "right")
    assert r.to_dict()["file"] == "<arrays>"


def test_profile_density_against_scipy_welch():
    """Ĝ_d(n) is scipy's one-sided Welch density with fs = 1/Δx (Hann, 50 % overlap, no segment detrend),
    of the track with its least-squares line removed, without the bins n = 0 and Nyquist."""
    rng = np.random.default_rng(8608)
    step, m = 0.05, 256
    z = np.cumsum(rng.normal(size=8192)) * 1e-3 + 0.01 * np.arange(8192) * step
    r = stochvib.road.analyze_profile(z, step, segment=m)
    zd = signal.detrend(z, type="linear")
    n, G = signal.welch(zd, fs=1.0 / step, window="hann", nperseg=m, noverlap=m // 2, detrend=False)
    np.testing.assert_allclose(r.tracks[0].n, n[1:-1], rtol=REL_WELCH)
    np.testing.assert_allclose(r.tracks[0].G_d, G[1:-1], rtol=REL_WELCH)
    assert r.coherence is None and r.tracks[0].name == "track0"
    # the χ² interval brackets the estimate
    assert np.all(r.tracks[0].lower < r.tracks[0].G_d) and np.all(r.tracks[0].G_d < r.tracks[0].upper)


def test_coherence_of_a_track_with_itself_and_with_an_independent_one():
    rng = np.random.default_rng(2)
    a, b = rng.normal(size=(2, 16384))
    same = stochvib.road.analyze_profile([a, a], "10 cm", segment=256).coherence
    np.testing.assert_allclose(same.gamma2, 1.0, rtol=1e-12)
    indep = stochvib.road.analyze_profile([a, b], 0.1, names=["l", "r"], segment=256).coherence
    # γ̂² of independent tracks has mean ≈ 1/K_e (K_e = ν/2 ≈ 60 here); 127 bins average it to ±~20 %
    assert indep.tracks == ("l", "r") and 0.0 < float(indep.gamma2.mean()) < 0.05


def test_profile_analysis_bad_input():
    with pytest.raises(InvalidInputError, match="detrend"):
        stochvib.road.analyze_profile(np.zeros(100), 0.1, detrend="quadratic")
    with pytest.raises(InvalidInputError):
        stochvib.road.analyze_profile([np.zeros(100), np.zeros(99)], 0.1)
    with pytest.raises(InvalidInputError):
        stochvib.road.analyze_profile(np.r_[np.zeros(99), math.nan], 0.1)
    with pytest.raises(InvalidInputError, match="segment"):
        stochvib.road.analyze_profile(np.random.default_rng(0).normal(size=4096), 0.1, segment=7)


def test_coherence_model_against_bessel_and_the_cli(cli):
    """Dodds & Robson's isotropic surface with w = 2: ρ(n) = x K₁(x), x = 2πnB (scipy.special.k1), and the
    tool's numbers for the same model (``stochvib coherence --model … --json``)."""
    from scipy.special import k1

    model = {"kind": "dodds-robson", "waviness": 2}
    n = np.array([[0.01, 0.1], [0.5, 2.0]])
    x = 2 * np.pi * n * 1.5
    rho = stochvib.road.coherence(model, n)
    assert rho.shape == (2, 2)
    np.testing.assert_allclose(rho, x * k1(x), rtol=REL_BESSEL)
    want = cli.json("coherence", "--model", '{ kind = "dodds-robson", waviness = 2 }', "--frequency", "0.1,1")
    got = stochvib.road.coherence(model, [0.1, 1.0], track_width="150 cm", squared=True)
    np.testing.assert_allclose(got, [r["model_squared_coherence"] for r in want["rows"]], rtol=REL_SAME)
    assert stochvib.road.coherence({"kind": "constant", "coherence_amplitude": 0.5}, 0.3) == 0.5
    # a bad model is an InvalidInputError naming the dict's key (not a FileError naming a file or flag)
    with pytest.raises(InvalidInputError, match=r"model\['kind'\] = nonsense: expected dodds-robson"):
        stochvib.road.coherence({"kind": "nonsense"}, 0.3)
    with pytest.raises(InvalidInputError, match="waviness") as e:
        stochvib.road.coherence({"kind": "dodds-robson", "waviness": -1}, 0.3)
    assert e.value.name == "model.waviness"
