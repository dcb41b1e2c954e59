"""The toolkit on arrays: frequency weightings against ISO 2631-1 Table 3 and scipy.signal.freqs, rainflow
against an independent transcription of ASTM E1049-85 §5.4.4 written here, spectral fatigue against the
narrow-band closed form, exposure(a, fs) against closed forms and the command-line tool."""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy import signal

import stochvib
from stochvib import InvalidInputError, comfort, fatigue

# --- named tolerances -------------------------------------------------------------------------------------
# ISO 2631-1:1997 Table 3 prints the weighting factors to three digits (×1000): rounding is ≤ 0.0005; the
# library's own test allows 0.001 for the same entries.
ABS_TABLE = 1e-3
# The weighting's rational form evaluated by scipy (polyval of degree-6..8 polynomials) against the library's
# factored form: both exact, rounding of polynomials whose coefficients span ~10^12.
REL_POLY = 1e-9
# Trapezoidal moments of a flat density on [99, 101] Hz with 0.01 Hz steps: m₂ is off by
# (b − a) h² G f''/12 ≈ 1.7e-5 of 1e4, i.e. 2e-9 relative; ν₀⁺ and the damage rate inherit it.
REL_TRAPZ = 1e-7
# a_w of a sine through the digital weighting (bilinear transform at 1 kHz, started at rest): the
# realisation error at 4 Hz (< 0.1 dB, ISO 8041 allows far more) and the start-up transient over 120 s.
REL_DIGITAL = 2e-2
# A(8) = a_w √(T_exp/8 h), Miner sums, VDV: the same formula recomputed here from the reported values, or
# the same sum in another order: a few roundings.
REL_FORMULA = 1e-12
# Rainflow ranges and means are differences and half-sums of the same samples in both counts: exact up to
# the last bit of the half-sum.
REL_RAINFLOW, ABS_RAINFLOW = 1e-15, 1e-12
# scipy.signal.welch (numpy's pocketfft) against the library (realfft) on 512-point segments: FFT rounding;
# f_j = j·fs/M computed two ways.
REL_WELCH, REL_FREQ = 1e-9, 1e-14
# χ² quantiles by scipy.stats against the library's own: both to ~1e-12 and more.
REL_CHI2 = 1e-9
# The output density: the library's modal form against |H|² S from the dense frequency response.
REL_DENSITY = 1e-10
# G(f) = 4π S(2πf) recomputed from S: a product of rounded numbers.
REL_CONVERSION = 1e-12
# A trapezoid of a smooth, fast-decaying output density on a grid of 1 mrad/s to 400 rad/s (the tail beyond
# holds < 1e-5 of the variance for the conveyor idler: |H|² S ~ ω⁻⁶) against the exact variance.
REL_TRAPZ_VARIANCE = 1e-4
# The same for the weighted seat on a 2 mrad/s grid to 4000 rad/s (Wk falls as ω⁻², the seat as ω⁻¹).
REL_TRAPZ_WEIGHTED = 1e-5
# The library's IRI against the command-line tool's on the same profile (the CSV's 0.001 mm rounding is the
# same for both; what remains is the CSV parse): the same computation.
REL_SAME = 1e-12


@pytest.mark.parametrize("f,want", [(1.0, 0.482), (8.0, 1.036), (16.0, 0.768), (31.5, 0.405)])
def test_wk_against_iso_2631_table_3(f, want):
    assert abs(comfort.weighting("Wk", f=f)) == pytest.approx(want, abs=ABS_TABLE)


@pytest.mark.parametrize("name", comfort.WEIGHTINGS)
def test_weighting_filter_against_scipy_freqs(name):
    # descending (b, a) as scipy takes them: scipy.signal.freqs(b, a) is the weighting's response
    w = 2 * np.pi * np.geomspace(0.05, 400.0, 300)
    b, a = comfort.weighting_filter(name)
    _, h = signal.freqs(b, a, worN=w)
    np.testing.assert_allclose(comfort.weighting(name, w), h, rtol=REL_POLY, atol=0)
    np.testing.assert_allclose(comfort.weighting(name, f=w / (2 * np.pi)), h, rtol=REL_POLY, atol=0)
    # as a System (descending, no keyword): the same response
    sys_ = stochvib.System.transfer_function(b, a)
    np.testing.assert_allclose(sys_.frequency_response(w)[0, 0], h, rtol=REL_POLY, atol=0)
    with pytest.raises(InvalidInputError):
        comfort.weighting("Wz", w)


def astm_e1049_three_point(x):
    """ASTM E1049-85 §5.4.4 (three-point rainflow, half cycles peeled off the starting point), transcribed
    independently of the library: (range, mean, count) per cycle."""
    x = np.asarray(x, dtype=float)
    tp = [x[0]]
    for k in range(1, len(x) - 1):
        if (x[k] - tp[-1]) * (x[k + 1] - x[k]) < 0:
            tp.append(x[k])
    tp.append(x[-1])
    stack, out = [], []
    for p in tp:
        stack.append(p)
        while len(stack) >= 3:
            big_x, big_y = abs(stack[-1] - stack[-2]), abs(stack[-2] - stack[-3])
            if big_x < big_y:
                break
            if len(stack) == 3:  # Y contains the starting point: a half cycle, S moves on
                out.append((big_y, 0.5 * (stack[0] + stack[1]), 0.5))
                stack.pop(0)
            else:
                out.append((big_y, 0.5 * (stack[-3] + stack[-2]), 1.0))
                del stack[-3:-1]
    out += [(abs(b - a), 0.5 * (a + b), 0.5) for a, b in zip(stack, stack[1:])]
    return sorted(out)


def test_rainflow_against_an_independent_astm_transcription():
    rng = np.random.default_rng(2024)
    x = np.cumsum(rng.normal(size=5000))  # a wandering record: many nested cycles and a long residue
    c = fatigue.rainflow(x)
    got = sorted(zip(c.range.tolist(), c.mean.tolist(), c.count.tolist()))
    want = astm_e1049_three_point(x)
    assert len(got) == len(want)
    np.testing.assert_allclose(np.array(got), np.array(want), rtol=REL_RAINFLOW, atol=ABS_RAINFLOW)
    np.testing.assert_array_equal(c.amplitude, c.range / 2)
    assert np.all(c.start < c.end) and c.start.dtype == np.int64
    # Miner's damage from the arrays, against the same sum over the transcription
    k, cc = 3.0, 1e9
    assert c.damage(k=k, c=cc) == pytest.approx(sum(n * (r / 2) ** k for r, _, n in want) / cc, rel=REL_FORMULA)
    with pytest.raises(InvalidInputError, match="1-D"):
        fatigue.rainflow(np.ones((2, 2)))


def test_miner_damage_takes_c_with_a_unit_as_spectral_fatigue_does():
    """Cycles.damage(k=, c=, unit=): C in unit^k, a string converted into it (1 MPa³ = 1e18 Pa³), validated."""
    c = fatigue.rainflow(np.cumsum(np.random.default_rng(7).normal(size=500)))
    by_sum = float(np.sum(c.count * c.amplitude**3))  # Σ nᵢ S_aᵢ^k, k = 3
    assert c.damage(k=3, c="2e12 MPa^3", unit="MPa") == pytest.approx(by_sum / 2e12, rel=REL_FORMULA)
    assert c.damage(k="3", c="2e12 MPa^3") == pytest.approx(by_sum / 2e30, rel=REL_FORMULA)  # the default unit Pa
    assert c.damage(k=3, c=2e12, unit="MPa") == c.damage(k=3, c=2e12)  # a number is in unit^k as given
    with pytest.raises(stochvib.UnitError, match="c"):
        c.damage(k=3, c="2e12 m^3", unit="MPa")
    for k, cc in ((3, 0.0), (-1, 1e9), (3, float("nan"))):
        with pytest.raises(InvalidInputError):
            c.damage(k=k, c=cc)


def test_spectral_fatigue_narrow_band_closed_form():
    # A flat one-sided density G = 0.5 /Hz on [99, 101] Hz: σ² = m₀ = 1, ν₀⁺ = √(m₂/m₀) with
    # m₂ = ∫ f² G df = 0.5 (101³ − 99³)/3; narrow band (Bendat 1964): D/T = ν₀⁺ (√2 σ)^k Γ(1 + k/2)/C.
    f = np.linspace(99.0, 101.0, 201)
    k, c = 3.0, 1e12
    r = fatigue.spectral(f, np.full_like(f, 0.5), k=k, c=c)
    nu0 = math.sqrt(0.5 * (101.0**3 - 99.0**3) / 3.0)
    want = nu0 * math.sqrt(2.0) ** k * math.gamma(1 + k / 2) / c
    assert r["NarrowBand"].damage_rate == pytest.approx(want, rel=REL_TRAPZ)
    assert r["NarrowBand"].life == pytest.approx(1 / want, rel=REL_TRAPZ)
    # the narrow-band estimate is the conservative one (Wirsching & Light 1980): no method predicts less life
    assert min(e.life for e in r.estimates) == pytest.approx(r["NarrowBand"].life, rel=REL_FORMULA)
    # from a Spectrum: its one-sided density as arrays
    t3 = stochvib.Spectrum.exp_cosine(1.0, 2.0, 60.0)
    ff = np.linspace(0.0, 200.0, 4001)
    r3 = fatigue.spectral(ff, t3.density(f=ff), k=k, c=c)
    assert {e.method for e in r3.estimates} >= {"NarrowBand", "Dirlik"}
    with pytest.raises(InvalidInputError):
        fatigue.spectral(f, np.full_like(f, 0.5), k=-1.0, c=c)
    # S^k beyond f64 (k = 10⁶): refused by name, not a damage rate of None whose repr raised TypeError
    with pytest.raises(InvalidInputError, match="not a finite number"):
        fatigue.spectral(f, np.full_like(f, 0.5), k=1e6, c=c)
    # every amplitude far below an endurance limit of 10¹⁰ σ: no damage, an unlimited life (inf, not None)
    r0 = fatigue.spectral(f, np.full_like(f, 0.5), k=k, c=c, endurance_limit=1e10)
    assert r0["NarrowBand"].damage_rate == 0.0 and math.isinf(r0["NarrowBand"].life)
    assert "inf" in repr(r0)


def test_exposure_of_a_sine_closed_forms():
    # 2 m/s² amplitude at 4 Hz for 120 s on the seat surface, z: a_w = 2|W_k(4 Hz)|/√2; A(8) with a 4 h
    # exposure = k a_w √(4 h/8 h), k = 1 for z (Directive 2002/44/EC Annex B).
    fs = 1000.0
    t = np.arange(0.0, 120.0, 1.0 / fs)
    r = stochvib.exposure(2.0 * np.sin(2 * np.pi * 4.0 * t), fs, exposure="4 h")
    z = r["z"]
    wk = abs(comfort.weighting("Wk", f=4.0))
    assert z.a_w == pytest.approx(2.0 * wk / math.sqrt(2.0), rel=REL_DIGITAL)
    assert r.exposure_s == 4 * 3600.0 and r.duration_s == pytest.approx(120.0)
    assert z.a8 == pytest.approx(z.a_w * math.sqrt(0.5), rel=REL_FORMULA)
    assert r.a8 == z.a8
    # VDV of a sine: (∫a⁴dt)^¼ = a_peak (3T/8)^¼
    assert z.vdv == pytest.approx(2.0 * wk * (3 * 120.0 / 8) ** 0.25, rel=REL_DIGITAL)
    assert "a_w" in str(r) or "A(8)" in str(r)
    with pytest.raises(InvalidInputError):
        stochvib.exposure(np.ones((10, 2)), fs)
    with pytest.raises(InvalidInputError, match="same length"):
        stochvib.exposure({"x": np.zeros(10), "z": np.zeros(11)}, fs)
    # a daily exposure is 1 min to 24 h, as a scenario's; one channel per location and axis; each named by
    # its keyword
    with pytest.raises(InvalidInputError, match="`exposure`.*less than 1 min"):
        stochvib.exposure(2.0 * np.sin(2 * np.pi * 4.0 * t), fs, exposure="30 s")
    with pytest.raises(InvalidInputError, match="`exposure`.*at most 24 h"):
        stochvib.exposure(2.0 * np.sin(2 * np.pi * 4.0 * t), fs, exposure="25 h")
    two = {"a": np.zeros(t.size), "b": np.zeros(t.size)}
    with pytest.raises(InvalidInputError, match="`axes`.*already given"):
        stochvib.exposure(two, fs, axes=["a=seat-surface:z", "b=seat-surface:z"])


def test_welch_against_scipy_and_its_intervals():
    # The same estimate as scipy.signal.welch (Hann, 50 % overlap, constant detrend, density scaling)
    rng = np.random.default_rng(7)
    x = signal.lfilter([1.0], [1.0, -0.9], rng.normal(size=20000))
    fs = 200.0
    est = stochvib.welch(x, fs, nperseg=512)
    f_ref, p_ref = signal.welch(x, fs, nperseg=512)
    f, pxx = est
    np.testing.assert_allclose(f, f_ref, rtol=REL_FREQ, atol=0)
    np.testing.assert_allclose(pxx, p_ref, rtol=REL_WELCH, atol=0)
    # intervals: lower < G < upper, and Welch's ν = 36K²/(19K − 1) for K segments (Hann, 50 % overlap)
    k = est.segments
    assert k == (x.size - 512) // 256 + 1
    assert est.dof == pytest.approx(36 * k * k / (19 * k - 1), rel=REL_FORMULA)
    assert np.all(est.lower[1:-1] < pxx[1:-1]) and np.all(pxx[1:-1] < est.upper[1:-1])
    # χ² interval inside: [ν G/χ²_{ν,0.975}, ν G/χ²_{ν,0.025}], from scipy.stats
    from scipy.stats import chi2

    nu = est.dof
    np.testing.assert_allclose(est.lower[5], nu * pxx[5] / chi2.ppf(0.975, nu), rtol=REL_CHI2)
    np.testing.assert_allclose(est.upper[5], nu * pxx[5] / chi2.ppf(0.025, nu), rtol=REL_CHI2)
    with pytest.raises(InvalidInputError, match="`nperseg` = 511"):
        stochvib.welch(x, fs, nperseg=511)
    # a record shorter than one segment is named by its keyword, x (it read `record length`)
    with pytest.raises(InvalidInputError, match="`x` = 3"):
        stochvib.welch(x[:3], fs)


def read_profile(root):
    """data/measured-profile.csv: distance (m), left and right elevations (mm)."""
    d = np.loadtxt(root / "data" / "measured-profile.csv", delimiter=",", comments="#", skiprows=7)
    return d[1, 0] - d[0, 0], d[:, 1] / 1000.0, d[:, 2] / 1000.0


def test_iri_and_iso_class_against_the_cli(cli, root):
    # the Rust library's answer for the same profile and spectrum: `stochvib iri iso8608-c --profile … --json`
    want = cli.json("iri", "iso8608-c", "--profile", "data/measured-profile.csv")
    step, left, right = read_profile(root)
    assert step == pytest.approx(0.05)
    got = [stochvib.road.iri(left, step).m_per_km, stochvib.road.iri(right, "5 cm").m_per_km]
    np.testing.assert_allclose(got, [m["m_per_km"] for m in want["measured"]], rtol=REL_SAME)
    e = stochvib.road.expected_iri(stochvib.Spectrum.load("iso8608-c"))
    assert e.m_per_km == want["expected"]["m_per_km"]
    # ISO 8608 class limits (Table F.2): C is 128e-6 ≤ G_d(n₀) < 512e-6 m³, a limit belongs to the rougher class
    assert [stochvib.road.iso8608_class(g) for g in (256e-6, 128e-6, 127e-6, 512e-6)] == ["C", "C", "B", "D"]
    with pytest.raises(InvalidInputError):
        stochvib.road.iso8608_class(-1.0)


def test_weighted_output_of_any_system_gives_a_w_two_ways():
    # A seat on a vibrating floor: m = 80 kg, k = 50 kN/m, b = 1 kN s/m, base input; the Wk-weighted seat
    # acceleration's σ is a_w. Way 1: analyze (Lyapunov) of System.weighted; way 2: ∫|W H|² S dω with the
    # arrays of frequency_response and density (trapezoid); and W·H checked against comfort.weighting.
    seat = stochvib.System.mdof(mass=[[80.0]], damping=[[1e3]], stiffness=[[5e4]], base_stiffness=[[5e4]],
                                base_damping=[[1e3]], outputs={"acc": ("acceleration", [1])})
    w = seat.weighted("acc", "Wk")
    assert w.outputs == [("acc_Wk", "m/s^2")] and w.n_inputs == 1
    floor = stochvib.Spectrum.exp_cosine(0.05, 3.0, 30.0, unit="m")  # floor displacement, m
    r = stochvib.analyze(w, floor)
    a_w = r["acc_Wk"].sigma
    omega = np.linspace(0.0, 4000.0, 2_000_001)
    sy = np.abs(w.frequency_response(omega)[0, 0]) ** 2 * floor.density(omega)
    var_trapz = 2.0 * np.sum(0.5 * (sy[1:] + sy[:-1]) * np.diff(omega))
    assert a_w == pytest.approx(math.sqrt(var_trapz), rel=REL_TRAPZ_WEIGHTED)
    # the series connection against the product of the two responses (two exact evaluations; below 1 rad/s
    # both are ~1e-12 and the state-space solve loses digits to cancellation)
    wg = np.geomspace(1.0, 1000.0, 500)
    h = seat.frequency_response(wg)[0, 0] * comfort.weighting("Wk", wg)
    np.testing.assert_allclose(w.frequency_response(wg)[0, 0], h, rtol=REL_POLY, atol=0)
    # A(8) and the Gaussian VDV of that a_w
    assert comfort.a8(a_w, "8 h") == pytest.approx(a_w, rel=REL_FORMULA)
    assert comfort.vdv_gaussian(a_w, 3600.0) == pytest.approx((3 * 3600.0) ** 0.25 * a_w, rel=REL_FORMULA)
    with pytest.raises(InvalidInputError, match="Wz"):
        seat.weighted("acc", "Wz")


def test_output_density_arrays_against_frequency_response_and_the_variance():
    # S_y = |H|² S_u for a single-input system; its integral is the analytic variance (Lyapunov)
    sc = stochvib.Scenario.load("data/conveyor-idler.toml")
    sys_, load = sc.system, sc.input
    w = np.linspace(0.0, 400.0, 400_001)  # 1 mrad/s
    sy = sc.output_density("y", w)
    np.testing.assert_allclose(sy, np.abs(sys_.frequency_response(w)[0, 0]) ** 2 * load.density(w), rtol=REL_DENSITY)
    var = 2.0 * np.sum(0.5 * (sy[1:] + sy[:-1]) * np.diff(w))
    assert var == pytest.approx(stochvib.analyze(sc)["y"].variance, rel=REL_TRAPZ_VARIANCE)
    f = w[:1000] / (2 * np.pi)
    np.testing.assert_allclose(sc.output_density("y", f=f), 4 * np.pi * sy[:1000], rtol=REL_CONVERSION)
    assert sc.output_density("y", w.reshape(400_001, 1)).shape == (400_001, 1)
    with pytest.raises(InvalidInputError, match="no such output"):
        sc.output_density("nope", w)
