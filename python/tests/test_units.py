"""Unit strings wherever a quantity is: sample rates (``fs=``: samples per second, where "200 Hz", "200 1/s" and
"200 S/s" are all 200 — not 2π·200 as for an angular frequency), accelerations (``a_w=``), the band of a
band-limited σ; a bad string raises UnitError naming the argument, with the library's message."""

from __future__ import annotations

import math

import numpy as np
import pytest

import stochvib
from stochvib import comfort

RATES = ["200 Hz", "200 1/s", "200 S/s", "200 samples/s", "0.2 kHz", "0.2 kS/s", "12000 1/min"]


@pytest.fixture(scope="module")
def record():
    return np.random.default_rng(5).standard_normal(4096)


@pytest.mark.parametrize("fs", RATES)
def test_welch_takes_a_sample_rate_string(record, fs):
    want = stochvib.welch(record, 200.0, nperseg=256)
    got = stochvib.welch(record, fs, nperseg=256)
    for name in ("f", "Pxx", "lower", "upper"):
        np.testing.assert_array_equal(getattr(got, name), getattr(want, name))


def test_exposure_takes_a_sample_rate_string():
    fs = 1000.0
    t = np.arange(0, 20.0, 1 / fs)
    a = np.sin(2 * np.pi * 4.0 * t)
    want = stochvib.exposure(a, fs, exposure="4 h").to_dict()
    for text in ("1 kHz", "1000 1/s", "1000 S/s", "1 kS/s"):
        assert stochvib.exposure(a, text, exposure="4 h").to_dict() == want, text


@pytest.mark.parametrize(
    "text, reason",
    [
        ("200 rad/s", "`rad` is an angle, not a count"),
        ("200 cycles/s", "`cycles` is an angle, not a count"),
        ("200 m", "dimension is m, expected s^-1 (a sample rate"),
        ("200", "dimension is dimensionless, expected s^-1 (a sample rate"),
        ("200 furlong/s", "unknown unit `furlong`"),
    ],
)
def test_a_bad_sample_rate_is_a_unit_error_naming_fs(record, text, reason):
    for call in (lambda: stochvib.welch(record, text), lambda: stochvib.exposure(record, text)):
        with pytest.raises(stochvib.UnitError) as e:
            call()
        assert e.value.name == "fs" and e.value.value == text
        assert reason in e.value.reason
        assert str(e.value).startswith(f"invalid parameter `fs` = {text!r}".replace("'", '"'))
    # not a TypeError for a non-number either: the argument is named
    with pytest.raises(stochvib.InvalidInputError, match="`fs`"):
        stochvib.welch(record, [200.0])


def test_a_w_takes_an_acceleration_string():
    assert comfort.a8("1 m/s^2", "2 h") == comfort.a8(1.0, 7200.0) == pytest.approx(0.5, rel=1e-15)
    assert comfort.a8("100 cm/s^2", "2 h") == comfort.a8(1.0, "2 h")
    assert comfort.vdv_gaussian("0.5 m/s²", "8 h") == comfort.vdv_gaussian(0.5, 28800.0)
    with pytest.raises(stochvib.UnitError) as e:
        comfort.a8("1 m/s", "2 h")
    assert e.value.name == "a_w" and "expected m s^-2" in str(e.value)


def test_the_band_of_a_band_sigma_takes_frequency_strings():
    # "1 Hz" is an angular frequency of 2π rad/s here: the angular reading of every frequency quantity
    sys = stochvib.System.model("conveyor-idler", m="100 kg", c="70 kN/m", zeta=0.2)
    lump = stochvib.Spectrum.load("conveyor-lump-load")
    want = stochvib.analyze(sys, lump, band_rad_s=(0.0, 20 * math.pi))["y"].band_sigma
    got = stochvib.analyze(sys, lump, band_rad_s=("0 Hz", "10 Hz"))["y"].band_sigma
    assert got == pytest.approx(want, rel=1e-12)
    with pytest.raises(stochvib.UnitError, match="band_rad_s"):
        stochvib.analyze(sys, lump, band_rad_s=("0 Hz", "10 m"))
    with pytest.raises(stochvib.InvalidInputError, match="band_rad_s"):
        stochvib.analyze(sys, lump, band_rad_s=(0.0, 1.0, 2.0))
