"""Unit strings for every quantity argument whose unit follows from another argument: the formula parameters of
the spectrum constructors (their dimension from ``domain=`` and ``unit=``), the S–N curve of
``fatigue.spectral`` (its stress unit ``unit=``), the process mean ``mean=`` (the spectrum's unit) and the
crossing levels ``levels=`` (the output's unit).

Expected values: the SI value of each string by hand (4 cm² = 4·10⁻⁴ m², 1 Hz = 2π rad/s, 0.1 cycles/m read as
a cyclic frequency is 0.1 cycles/m, 1e12 MPa³ = 10³⁰ Pa³), and the call with those numbers, which must give the
same spectrum, fatigue estimate or statistics. A decay rate or a density level written with Hz, rad or cycles is
refused (its SI value would silently carry 2π), as in spectrum files; every refusal is a UnitError naming the
argument, the value and the expected dimension."""

from __future__ import annotations

import math

import numpy as np
import pytest

import stochvib
from stochvib import Spectrum, System, fatigue

# A unit conversion is one correctly rounded multiplication or division (units::parse_quantity), the call
# with the hand-converted number another: the two SI values agree to an ulp or two, and so do the
# densities computed from them.
REL_CONVERTED = 1e-15
# A cyclic frequency read from a string is the angular SI value divided by 2π: two roundings more, which a
# power law raises to the power w = 2.
REL_CYCLIC = 2e-15

OMEGA = np.array([0.0, 0.3, 1.0, 2.5, 7.0])
TWO_PI = 2 * math.pi

# (constructor, string arguments, keyword arguments, the same arguments as SI numbers)
ACCEPTED = [
    (Spectrum.exponential, ("4 cm^2", "2 1/s"), {}, (4e-4, 2.0)),
    (Spectrum.exponential, ("2.25 cm^2", "0.04 1/cm"), {"domain": "spatial"}, (2.25e-4, 4.0)),
    (Spectrum.exponential, ("0.25 m^2/s^4", "3 1/s"), {"unit": "m/s^2"}, (0.25, 3.0)),
    (Spectrum.exponential, ("4 kN^2", "2 1/s"), {"unit": "N"}, (4e6, 2.0)),
    (Spectrum.gaussian, ("1 cm^2", "4 1/s^2"), {}, (1e-4, 4.0)),
    (Spectrum.gaussian, ("1 cm^2", "0.01 1/cm^2"), {"domain": "spatial"}, (1e-4, 100.0)),
    (Spectrum.exp_cosine, ("1 mm^2", "0.5 1/s", "1 Hz"), {}, (1e-6, 0.5, TWO_PI)),
    (Spectrum.exp_cosine, ("1 mm^2", "0.5 1/m", "0.6 rad/m"), {"domain": "spatial"}, (1e-6, 0.5, 0.6)),
    (Spectrum.gauss_cosine, ("1 mm^2", "0.25 1/s^2", "12 rad/s"), {}, (1e-6, 0.25, 12.0)),
    (Spectrum.band_white, ("1e-4 m^2 s", "1 Hz", "10 Hz"), {"convention": "one-sided-cyclic"}, (1e-4, 1.0, 10.0)),
    (Spectrum.band_white, ("1e-4 m^2 s", "1 Hz", "10 Hz"), {"convention": "two-sided-angular"}, (1e-4, TWO_PI, 10 * TWO_PI)),
    (Spectrum.band_white, ("2 mm^2 s", "3 rad/s", "9 rad/s"), {"convention": "one-sided-angular"}, (2e-6, 3.0, 9.0)),
]


@pytest.mark.parametrize("ctor, texts, kw, numbers", ACCEPTED, ids=lambda v: getattr(v, "__name__", None))
def test_constructor_quantities_take_unit_strings(ctor, texts, kw, numbers):
    a, b = ctor(*texts, **kw), ctor(*numbers, **kw)
    np.testing.assert_allclose(a.density(OMEGA), b.density(OMEGA), rtol=REL_CONVERTED, atol=0)
    assert a.variance() == pytest.approx(b.variance(), rel=REL_CONVERTED)


def test_mixed_numbers_and_strings():
    a = Spectrum.exp_cosine(1e-6, "0.5 1/s", 2 * math.pi)
    b = Spectrum.exp_cosine("1 mm^2", 0.5, "1 Hz")
    np.testing.assert_allclose(a.density(OMEGA), b.density(OMEGA), rtol=REL_CONVERTED, atol=0)


def test_power_law_and_iso_band_take_cyclic_frequency_strings():
    n = np.array([0.02, 0.1, 1.0, 2.5])
    a = Spectrum.power_law("256e-6 m^3", "0.1 cycles/m", 2, band=("0.011 cycles/m", "2.83 cycles/m"))
    b = Spectrum.power_law(256e-6, 0.1, 2, band=(0.011, 2.83))
    np.testing.assert_allclose(a.density(f=n), b.density(f=n), rtol=REL_CYCLIC, atol=0)
    assert a.variance() == pytest.approx(b.variance(), rel=REL_CYCLIC)
    # "1 rad/m" is 1/(2π) cycles/m; a temporal power law in Hz: g0 in m² s
    c = Spectrum.power_law(1e-3, "1 rad/m", "2")
    d = Spectrum.power_law(1e-3, 1 / TWO_PI, 2.0)
    np.testing.assert_allclose(c.density(f=n), d.density(f=n), rtol=REL_CYCLIC, atol=0)
    e = Spectrum.power_law("1e-3 m^2 s", "1 Hz", 2, band=("0.5 Hz", "50 Hz"), domain="temporal")
    g = Spectrum.power_law(1e-3, 1.0, 2, band=(0.5, 50.0), domain="temporal")
    assert e.variance() == pytest.approx(g.variance(), rel=REL_CYCLIC)
    iso = Spectrum.iso8608("C", band=("0.011 cycles/m", "2.83 cycles/m"))
    assert iso.variance() == pytest.approx(Spectrum.iso8608("C").variance(), rel=REL_CYCLIC)
    # band=None is still the unbounded road
    with pytest.raises(stochvib.DivergentError):
        Spectrum.iso8608("C", band=None).variance()


# (call, argument, text, fragment of the reason)
REFUSED = [
    (lambda: Spectrum.exponential(1.0, "1 Hz"), "alpha", "1 Hz", "a decay rate carries no angle"),
    (lambda: Spectrum.exponential(1.0, "2 rad/s"), "alpha", "2 rad/s", "expected dimension s^-1"),
    (lambda: Spectrum.exponential(1.0, "0.1 cycles/m", domain="spatial"), "alpha", "0.1 cycles/m", "expected dimension m^-1"),
    (lambda: Spectrum.exponential(1.0, "1 1/s", domain="spatial"), "alpha", "1 1/s", "dimension is s^-1, expected m^-1"),
    (lambda: Spectrum.gaussian(1.0, "1 1/s"), "alpha", "1 1/s", "dimension is s^-1, expected s^-2"),
    (lambda: Spectrum.exponential("1 m", 1.0), "variance", "1 m", "dimension is m, expected m^2"),
    (lambda: Spectrum.exponential("1 m^2", 1.0, unit="N"), "variance", "1 m^2", "dimension is m^2, expected m^2 kg^2 s^-4"),
    (lambda: Spectrum.exponential("1 cm^2", 1.0, unit="cm"), "variance", "1 cm^2", "no coherent SI unit"),
    (lambda: Spectrum.exp_cosine(1.0, 1.0, "1 m"), "beta", "1 m", "dimension is m, expected s^-1"),
    (lambda: Spectrum.power_law("1 m^2/Hz", 0.1, 2, domain="temporal"), "g0", "1 m^2/Hz", "said by `convention`"),
    (lambda: Spectrum.power_law("1 m^2", 0.1, 2), "g0", "1 m^2", "expected m^3"),
    (lambda: Spectrum.power_law(1e-4, "0.1 m", 2), "n0", "0.1 m", "expected m^-1"),
    (lambda: Spectrum.power_law(1e-4, 0.1, "2 m"), "waviness", "2 m", "expected dimensionless"),
    (lambda: Spectrum.band_white("1 m^2/Hz", 1, 2, convention="one-sided-cyclic"), "level", "1 m^2/Hz", "said by `convention`"),
    (lambda: Spectrum.band_white(1.0, "1 m", 2, convention="one-sided-cyclic"), "low", "1 m", "expected s^-1"),
    (lambda: Spectrum.iso8608("C", band=("0.011 cycles/s", 2.83)), "band[0]", "0.011 cycles/s", "expected m^-1"),
]


@pytest.mark.parametrize("call, name, text, reason", REFUSED, ids=[f"{r[1]}={r[2]}" for r in REFUSED])
def test_constructor_quantities_refuse_the_wrong_dimension(call, name, text, reason):
    with pytest.raises(stochvib.UnitError) as e:
        call()
    assert e.value.name == name and e.value.value == text
    assert reason in e.value.reason, e.value.reason
    assert str(e.value).startswith(f'invalid parameter `{name}` = "{text}"')


def test_a_band_is_a_pair():
    with pytest.raises(stochvib.InvalidInputError, match="`band`: expected a pair"):
        Spectrum.power_law(1e-4, 0.1, 2, band="1 Hz")


F = np.linspace(99.0, 101.0, 201)
G = np.full_like(F, 0.5)  # σ² = 1 (unit²)


def test_fatigue_sn_curve_takes_unit_strings():
    want = fatigue.spectral(F, G, k=3.0, c=1e12).to_dict()
    got = fatigue.spectral(F, G, k="3", c="1e12 MPa^3", unit="MPa").to_dict()
    for w, g in zip(want, got):
        assert g["damage_rate"] == pytest.approx(w["damage_rate"], rel=REL_CONVERTED)
    # in Pa: C = 1e12 MPa³ = 1e30 Pa³; an endurance limit of 0.5 MPa = 5e5 Pa with G in Pa²/Hz
    want = fatigue.spectral(F, G * 1e12, k=3, c=1e30, endurance_limit=5e5).to_dict()
    got = fatigue.spectral(F, G * 1e12, k=3, c="1e12 MPa^3", endurance_limit="0.5 MPa").to_dict()
    for w, g in zip(want, got):
        assert g["damage_rate"] == pytest.approx(w["damage_rate"], rel=REL_CONVERTED)
    # a stress in N (a force): N^k
    assert fatigue.spectral(F, G, k=2, c="1e6 kN^2", unit="N").to_dict() == fatigue.spectral(F, G, k=2, c=1e12, unit="N").to_dict()


@pytest.mark.parametrize(
    "kw, name, reason",
    [
        ({"k": 3.5, "c": "1e12 MPa^3"}, "c", "integer exponent"),
        ({"k": 3, "c": "1e12 MPa^2"}, "c", "expected m^-3 kg^3 s^-6"),
        ({"k": 3, "c": 1e12, "endurance_limit": "30 m"}, "endurance_limit", "expected m^-1 kg s^-2"),
        ({"k": "3 m", "c": 1e12}, "k", "expected dimensionless"),
        ({"k": 3, "c": "1e12 MPa^3", "unit": "furlong"}, "c", "is no unit"),
    ],
)
def test_fatigue_sn_curve_refuses_the_wrong_unit(kw, name, reason):
    with pytest.raises(stochvib.UnitError) as e:
        fatigue.spectral(F, G, **kw)
    assert e.value.name == name and reason in e.value.reason, e.value.reason


# SDOF m ẍ + b ẋ + k x = F (k = 8 kN/m) under a force of type 1 in N: the mean deflection is M_F / k.
def sdof():
    return System.mdof(mass=[[20.0]], damping=[[60.0]], stiffness=[[8000.0]], coordinates=[("x", "m")], outputs={"x": ("displacement", [1])})


FORCE = Spectrum.exponential("4 N^2", "5 1/s", unit="N")


def test_mean_and_levels_take_unit_strings():
    want = stochvib.analyze(sdof(), FORCE, mean=1e4, levels={"x": [1e-3, 0.5]})
    for mean in ("10 kN", ["10 kN"], [1e4]):
        got = stochvib.analyze(sdof(), FORCE, mean=mean, levels={"x": ["1 mm", "50 cm"]})
        assert got["x"].mean == want["x"].mean == pytest.approx(1e4 / 8000.0, rel=REL_CONVERTED)
        assert [l.level for l in got["x"].levels] == [l.level for l in want["x"].levels]
        assert [l.upcrossing_rate for l in got["x"].levels] == [l.upcrossing_rate for l in want["x"].levels]


@pytest.mark.parametrize(
    "kw, name, reason",
    [
        ({"mean": "10 kN*s"}, "mean", "expected m kg s^-2"),
        ({"mean": ["10 m"]}, "mean[0]", "expected m kg s^-2"),
        ({"levels": {"x": [1e-3, "1 s"]}}, 'levels["x"][1]', "dimension is s, expected m"),
    ],
)
def test_mean_and_levels_refuse_the_wrong_dimension(kw, name, reason):
    with pytest.raises(stochvib.UnitError) as e:
        stochvib.analyze(sdof(), FORCE, **kw)
    assert e.value.name == name and reason in e.value.reason, e.value.reason
