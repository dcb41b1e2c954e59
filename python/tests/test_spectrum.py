"""stochvib.Spectrum: vectorised densities against numpy formulas, variances and correlations against closed
forms and scipy quadrature, the catalogue against the command-line tool, array handling."""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy import integrate, signal

import stochvib
from stochvib import DivergentError, InvalidInputError, NotApplicableError, Spectrum

# --- named tolerances -------------------------------------------------------------------------------------
# Same formula evaluated by numpy and by Rust: only the order of a few roundings differs.
REL_FORMULA = 1e-13
# A closed-form variance or correlation against the library's closed form (a few roundings).
REL_CLOSED = 1e-12
# scipy.integrate.quad of a smooth density on the whole line (its own epsrel is set to 1e-11).
REL_QUAD = 1e-9
# The cyclic abscissa f = ω/2π printed by the CLI, multiplied back by 2π here: ω differs by ≤ 1 ulp, the
# density by ≤ |d ln S/d ln ω| ulp (< 10 for these spectra).
REL_CYCLIC_ROUNDTRIP = 1e-14

# A grid on both sides of 0 (densities are even), rad/s.
OMEGA = np.linspace(-40.0, 40.0, 2001)


# Two-sided angular densities of the four standard types (DESIGN §2; Sukharev (2012) eqs. (8.13), (8.24)),
# written here independently of the library:
#   type 1: K = D e^{-α|τ|}          S = (1/2π)∫K e^{-iωτ}dτ = (D/2π)·2α/(α²+ω²) = αD/(π(α²+ω²))
#   type 2: K = D e^{-ατ²}           S = (D/2π)·√(π/α) e^{-ω²/(4α)} = D/(2√(πα)) e^{-ω²/(4α)}
#   type 3: K = D e^{-α|τ|} cos βτ   S = ½[S₁(ω-β) + S₁(ω+β)]  (cos shifts by ±β with weight ½)
#   type 4: K = D e^{-ατ²} cos βτ    S = ½[S₂(ω-β) + S₂(ω+β)]
def s1(w, d, a):
    return a * d / (np.pi * (a * a + w * w))


def s2(w, d, a):
    return d / (2.0 * np.sqrt(np.pi * a)) * np.exp(-w * w / (4.0 * a))


def s3(w, d, a, b):
    return 0.5 * (s1(w - b, d, a) + s1(w + b, d, a))


def s4(w, d, a, b):
    return 0.5 * (s2(w - b, d, a) + s2(w + b, d, a))


def k1(t, d, a):
    return d * np.exp(-a * np.abs(t))


def k2(t, d, a):
    return d * np.exp(-a * t * t)


def k3(t, d, a, b):
    return d * np.exp(-a * np.abs(t)) * np.cos(b * t)


def k4(t, d, a, b):
    return d * np.exp(-a * t * t) * np.cos(b * t)


STANDARD = [
    ("type 1", lambda: Spectrum.exponential(2.0, 1.5), lambda w: s1(w, 2.0, 1.5), lambda t: k1(t, 2.0, 1.5)),
    ("type 2", lambda: Spectrum.gaussian(2.0, 1.5), lambda w: s2(w, 2.0, 1.5), lambda t: k2(t, 2.0, 1.5)),
    (
        "type 3",
        lambda: Spectrum.exp_cosine(2.0, 1.5, 6.0),
        lambda w: s3(w, 2.0, 1.5, 6.0),
        lambda t: k3(t, 2.0, 1.5, 6.0),
    ),
    (
        "type 4",
        lambda: Spectrum.gauss_cosine(2.0, 1.5, 6.0),
        lambda w: s4(w, 2.0, 1.5, 6.0),
        lambda t: k4(t, 2.0, 1.5, 6.0),
    ),
]


@pytest.mark.parametrize("name,make,s,k", STANDARD, ids=[t[0] for t in STANDARD])
def test_standard_density_vectorised_against_numpy(name, make, s, k):
    sp = make()
    got = sp.density(OMEGA)
    assert got.shape == OMEGA.shape and got.dtype == np.float64
    np.testing.assert_allclose(got, s(OMEGA), rtol=REL_FORMULA, atol=0)


@pytest.mark.parametrize("name,make,s,k", STANDARD, ids=[t[0] for t in STANDARD])
def test_standard_density_conventions(name, make, s, k):
    # The conversions of DESIGN §2: G(ω) = 2S(ω) (ω ≥ 0, zero below), G(f) = 4πS(2πf), Ŝ = 2πS.
    sp = make()
    w = np.linspace(0.0, 30.0, 301)
    f = w / (2.0 * np.pi)
    np.testing.assert_allclose(sp.density(w, convention="one-sided-angular"), 2.0 * s(w), rtol=REL_FORMULA, atol=0)
    np.testing.assert_allclose(sp.density(f=f), 4.0 * np.pi * s(2.0 * np.pi * f), rtol=REL_FORMULA, atol=0)
    np.testing.assert_allclose(
        sp.density(f=f, convention="one-sided-cyclic"), sp.density(f=f), rtol=0, atol=0
    )
    np.testing.assert_allclose(sp.density(w, convention="engineering"), 2.0 * np.pi * s(w), rtol=REL_FORMULA, atol=0)
    assert np.all(sp.density(-w[1:], convention="one-sided-angular") == 0.0)
    assert np.all(sp.density(f=-f[1:]) == 0.0)
    # each convention integrates to the same variance D = 2 (one-sided over [0, ∞), ∫Ŝ/2π over the line)
    g = lambda x: sp.density(f=x)  # noqa: E731
    d_cyc = integrate.quad(g, 0, np.inf, epsabs=0, epsrel=1e-11, limit=400)[0]
    assert d_cyc == pytest.approx(2.0, rel=REL_QUAD)


@pytest.mark.parametrize("name,make,s,k", STANDARD, ids=[t[0] for t in STANDARD])
def test_standard_variance_and_correlation(name, make, s, k):
    sp = make()
    # closed form: D = K(0) = 2 (the constructor's variance)
    assert sp.variance() == pytest.approx(2.0, rel=REL_CLOSED)
    # a different method: scipy's quadrature of the numpy density over the whole line
    quad = 2.0 * integrate.quad(s, 0, np.inf, epsabs=0, epsrel=1e-11, limit=400)[0]
    assert sp.variance() == pytest.approx(quad, rel=REL_QUAD)
    tau = np.array([0.0, 0.1, 0.37, 1.0, 2.5])
    np.testing.assert_allclose(sp.correlation(tau), k(tau), rtol=REL_CLOSED, atol=1e-15)
    assert isinstance(sp.correlation(0.37), float)


def test_rational_type1_equivalence():
    # S = 1/(π(1 + ω²)) is type 1 with D = 1, α = 1 (the formula above with a = d = 1)
    r = Spectrum.rational([1.0 / math.pi], [1.0, 1.0])
    np.testing.assert_allclose(r.density(OMEGA), s1(OMEGA, 1.0, 1.0), rtol=REL_FORMULA, atol=0)
    assert r.variance() == pytest.approx(1.0, rel=REL_CLOSED)
    num, den = r.rational_coefficients()
    np.testing.assert_allclose(num, [1.0 / math.pi], rtol=REL_FORMULA)
    np.testing.assert_allclose(den, [1.0, 1.0], rtol=REL_FORMULA)
    # type 1 with D = 2, α = 3: S = αD/(π(α² + ω²)) = (6/π) / (ω² + 9): descending [1, 9], ascending [9, 1]
    t = Spectrum.rational([6.0 / math.pi], [1.0, 9.0])
    np.testing.assert_allclose(t.density(OMEGA), s1(OMEGA, 2.0, 3.0), rtol=REL_FORMULA, atol=0)
    asc = Spectrum.rational([6.0 / math.pi], [9.0, 1.0], order="ascending")
    np.testing.assert_array_equal(asc.density(OMEGA), t.density(OMEGA))
    np.testing.assert_allclose(t.rational_coefficients(order="ascending")[1], [9.0, 1.0], rtol=REL_FORMULA)


@pytest.mark.parametrize("make", [lambda: Spectrum.exponential(2.0, 1.5), lambda: Spectrum.exp_cosine(2.0, 1.5, 6.0)])
def test_shaping_filter_reproduces_density(make):
    # S(ω) = |b(iω)/a(iω)|²/(2π), b, a descending in s: evaluated by scipy.signal.freqs
    sp = make()
    b, a = sp.shaping_filter()
    _, h = signal.freqs(b, a, worN=OMEGA)
    np.testing.assert_allclose(np.abs(h) ** 2 / (2 * np.pi), sp.density(OMEGA), rtol=1e-10, atol=0)
    assert np.all(np.real(np.roots(a)) < 0)  # Hurwitz
    ba, aa = sp.shaping_filter(order="ascending")
    np.testing.assert_array_equal(ba, b[::-1])
    np.testing.assert_array_equal(aa, a[::-1])
    with pytest.raises(NotApplicableError, match="not rational"):
        Spectrum.gaussian(1.0, 1.0).shaping_filter()
    assert Spectrum.gaussian(1.0, 1.0).rational_coefficients() is None


def test_iso8608_class_c():
    # ISO 8608:2016 Table C.1 (via DESIGN §2): class C geometric mean G_d(n₀ = 0.1 cycles/m) = 256e-6 m³.
    c = Spectrum.iso8608("C")
    assert c.domain == "spatial" and c.unit == "m"
    assert c.density(f=0.1) == pytest.approx(256e-6, rel=REL_CLOSED)
    # G_d(n) = G_d(n₀)(n/n₀)^{-2} inside the band 0.011..2.83, zero outside
    n = np.array([0.005, 0.02, 0.1, 1.0, 2.0, 3.0])
    expected = np.where((n >= 0.011) & (n <= 2.83), 256e-6 * (n / 0.1) ** -2.0, 0.0)
    np.testing.assert_allclose(c.density(f=n), expected, rtol=REL_FORMULA, atol=0)
    # D = ∫_{n₁}^{n₂} G₀ n₀² n^{-2} dn = G₀ n₀² (1/n₁ − 1/n₂)
    assert c.variance() == pytest.approx(256e-6 * 0.01 * (1 / 0.011 - 1 / 2.83), rel=REL_CLOSED)
    # upper bound is twice the geometric mean (ISO 8608 class limits)
    assert Spectrum.iso8608("c", bound="upper").density(f=0.1) == pytest.approx(512e-6, rel=REL_CLOSED)


def test_unbounded_road_variance_is_divergent_with_diagnosis():
    with pytest.raises(DivergentError) as e:
        Spectrum.iso8608("C", band=None).variance()
    assert isinstance(e.value, ArithmeticError)
    assert "infinite" in str(e.value) and "band" in e.value.reason


def test_at_speed():
    # S_t(ω) = S_Ω(ω/v)/v (DESIGN §2, spatial → temporal)
    road = Spectrum.exponential(32e-4, 0.16, domain="spatial")
    v = 10.0
    t = road.at_speed(v)
    assert t.domain == "temporal"
    np.testing.assert_allclose(t.density(OMEGA), s1(OMEGA / v, 32e-4, 0.16) / v, rtol=REL_FORMULA, atol=0)
    assert t.variance() == pytest.approx(32e-4, rel=REL_CLOSED)
    with pytest.raises(InvalidInputError, match="spatial"):
        Spectrum.exponential(1.0, 1.0).at_speed(10.0)
    with pytest.raises(InvalidInputError, match="speed"):
        road.at_speed(-1.0)


def test_tabulated_and_band_white():
    # G(f) = f^-2 from 1 to 10 Hz, one-sided: D = ∫₁¹⁰ f^-2 df = 1 − 1/10 = 0.9 (exact for the log-log interpolant)
    t = Spectrum.tabulated([1.0, 10.0], [1.0, 0.01], convention="one-sided-cyclic")
    assert t.variance() == pytest.approx(0.9, rel=REL_CLOSED)
    f = np.array([1.0, 2.0, 5.0, 10.0])
    np.testing.assert_allclose(t.density(f=f), f**-2.0, rtol=REL_FORMULA)
    # level 1e-3 /Hz one-sided on 1..10 Hz: D = 9e-3
    w = Spectrum.band_white(1e-3, 1.0, 10.0, convention="one-sided-cyclic")
    assert w.variance() == pytest.approx(9e-3, rel=REL_CLOSED)
    with pytest.raises(TypeError):
        Spectrum.tabulated([1.0, 10.0], [1.0, 0.01])  # the convention is required


def test_catalogue_and_load(root):
    cat = Spectrum.catalogue()
    for name in ("type1", "type2", "type3", "type4", "iso8608-c", "book-8-69"):
        assert name in cat, sorted(cat)
    # spectra/type3.toml: D = 1 cm² = 1e-4 m² (the file's value), α = 1 1/s, β = 6 1/s
    t3 = Spectrum.load("type3")
    assert t3.name == "type3" and t3.unit == "m" and "exp-cosine" in t3.text
    np.testing.assert_allclose(t3.density(OMEGA), s3(OMEGA, 1e-4, 1.0, 6.0), rtol=REL_FORMULA, atol=0)
    assert Spectrum.load(root / "spectra" / "type3.toml").variance() == t3.variance()
    assert cat["type3"].variance() == t3.variance()
    with pytest.raises(InvalidInputError, match="no-such-spectrum"):
        Spectrum.load("no-such-spectrum")


@pytest.mark.parametrize("name", ["type1", "type2", "type3", "type4", "iso8608-c", "book-8-66", "white-1-80hz"])
@pytest.mark.parametrize("convention", ["two-sided-angular", "one-sided-cyclic"])
def test_catalogue_identical_to_cli(cli, name, convention):
    # the Rust library's answer for the same spectrum: `stochvib spectrum NAME --json`
    rep = cli.json("spectrum", name, "--convention", convention)
    sp = Spectrum.load(name)
    if isinstance(rep["variance"], dict):  # {"error": message}
        with pytest.raises(stochvib.StochvibError) as e:
            sp.variance()
        assert str(e.value) == rep["variance"]["error"]
    else:
        assert sp.variance() == rep["variance"]
    lags = np.array([c[0] for c in rep["correlation"]])
    model = [c[1] for c in rep["correlation"]]
    if all(isinstance(m, float) for m in model):
        assert sp.correlation(lags).tolist() == model
    x = np.array([d[0] for d in rep["density"]])
    want = np.array([d[1] for d in rep["density"]])
    got = sp.density(f=x) if convention == "one-sided-cyclic" else sp.density(x, convention=convention)
    if convention == "two-sided-angular":
        assert got.tolist() == want.tolist()  # bit-identical
    else:
        np.testing.assert_allclose(got, want, rtol=REL_CYCLIC_ROUNDTRIP, atol=0)


# --- arrays of other dtypes, shapes and memory orders ---------------------------------------------------


@pytest.fixture
def t1():
    return Spectrum.exponential(2.0, 1.5)


def test_scalar_and_shapes(t1):
    assert isinstance(t1.density(1.0), float)
    assert t1.density(1.0) == s1(np.array(1.0), 2.0, 1.5)
    grid = OMEGA.reshape(3, 667)
    assert t1.density(grid).shape == (3, 667)
    assert t1.density(np.empty((0,))).shape == (0,)
    np.testing.assert_array_equal(t1.density(grid).ravel(), t1.density(OMEGA))


def test_converted_inputs_give_the_same_numbers(t1):
    ref = t1.density(np.arange(10, dtype=np.float64))
    same = [
        list(range(10)),  # a list of ints
        np.arange(10),  # int64
        np.arange(10, dtype=np.float32),  # float32 (exact for these integers)
        np.repeat(np.arange(10.0), 2)[::2],  # a strided view
        np.arange(10, dtype=">f8"),  # big-endian
    ]
    assert not same[3].flags.c_contiguous
    for x in same:
        np.testing.assert_array_equal(t1.density(x), ref)
    f = np.asfortranarray(OMEGA.reshape(3, 667))
    assert not f.flags.c_contiguous
    np.testing.assert_array_equal(t1.density(f), t1.density(np.ascontiguousarray(f)))
    strided = OMEGA[::7]
    np.testing.assert_array_equal(t1.density(strided), t1.density(strided.copy()))


def test_refused_inputs(t1):
    with pytest.raises(InvalidInputError, match="complex"):
        t1.density(np.array([1.0 + 2.0j]))
    with pytest.raises(InvalidInputError, match="omega"):
        t1.density(np.array(["a", "b"]))
    with pytest.raises(InvalidInputError, match="omega"):
        t1.density(np.array([True, False]))
    with pytest.raises(InvalidInputError, match="omega"):
        t1.density([[1.0, 2.0], [3.0]])  # ragged
    with pytest.raises(InvalidInputError, match="convention"):
        t1.density(1.0, convention="one-sided")


def test_out_argument(t1):
    out = np.empty_like(OMEGA)
    r = t1.density(OMEGA, out=out)
    assert r is out
    np.testing.assert_array_equal(out, t1.density(OMEGA))
    with pytest.raises(InvalidInputError, match="float64"):
        t1.density(OMEGA, out=np.empty(OMEGA.shape, dtype=np.float32))
    with pytest.raises(InvalidInputError, match="shape"):
        t1.density(OMEGA, out=np.empty(OMEGA.size + 1))
    with pytest.raises(InvalidInputError, match="C-contiguous"):
        t1.density(OMEGA[:1000], out=np.empty(2000)[::2])
    ro = np.empty_like(OMEGA)
    ro.flags.writeable = False
    with pytest.raises(InvalidInputError, match="out"):
        t1.density(OMEGA, out=ro)
    x = OMEGA.copy()
    with pytest.raises(InvalidInputError, match="out"):
        t1.density(x, out=x)


def test_constructor_errors_name_the_parameter():
    with pytest.raises(InvalidInputError) as e:
        Spectrum.exponential(1.0, -2.0)
    assert e.value.name == "alpha" and e.value.value == "-2"
    assert str(e.value) == "invalid parameter `alpha` = -2: must be finite and > 0"
    with pytest.raises(InvalidInputError, match="domain"):
        Spectrum.exponential(1.0, 2.0, domain="spacial")
    with pytest.raises(InvalidInputError, match="class"):
        Spectrum.iso8608("Z")
    with pytest.raises(InvalidInputError, match="numerator"):
        Spectrum.rational([-1.0], [1.0, 1.0])


def test_catalogue_directory_and_invalid_files(root, tmp_path):
    (tmp_path / "good.toml").write_text((root / "spectra" / "type1.toml").read_text())
    (tmp_path / "bad.toml").write_text('kind = "exponential"\nvariance = -1\nalpha = "1 1/s"\n')
    with pytest.warns(stochvib.StochvibWarning, match="bad.toml"):
        cat = Spectrum.catalogue(spectra_dir=tmp_path)
    assert list(cat) == ["good"]
    assert Spectrum.load("good", spectra_dir=tmp_path).variance() == Spectrum.load("type1").variance()
    with pytest.raises(stochvib.FileError) as e:
        Spectrum.load("bad", spectra_dir=tmp_path)
    assert e.value.key == "variance"


def test_trap_density_never_takes_hertz_in_omega():
    # The trap: density(omega, convention="one-sided-cyclic") took hertz in an argument named omega.
    # Now omega= is rad/s and f= is Hz; the cyclic convention belongs to f= only.
    t1 = Spectrum.exponential(2.0, 1.5)
    f = np.array([0.1, 0.5, 2.0])
    np.testing.assert_allclose(t1.density(f=f), 4 * np.pi * s1(2 * np.pi * f, 2.0, 1.5), rtol=REL_FORMULA, atol=0)
    np.testing.assert_allclose(t1.density(omega=2 * np.pi * f), s1(2 * np.pi * f, 2.0, 1.5), rtol=REL_FORMULA, atol=0)
    with pytest.raises(InvalidInputError, match="pass f="):
        t1.density(f, convention="one-sided-cyclic")
    with pytest.raises(InvalidInputError, match="rad/s"):
        t1.density(f=f, convention="two-sided-angular")
    with pytest.raises(InvalidInputError, match="exactly one"):
        t1.density(1.0, f=1.0)
    with pytest.raises(InvalidInputError, match="exactly one"):
        t1.density()
    with pytest.raises(TypeError):  # the convention is keyword-only
        t1.density(f, "one-sided-angular")


def test_density_broadcasts_over_any_shape():
    t1 = Spectrum.exponential(2.0, 1.5)
    w = np.linspace(0.0, 10.0, 24).reshape(2, 3, 4)
    assert t1.density(w).shape == (2, 3, 4)
    np.testing.assert_array_equal(t1.density(w).ravel(), t1.density(w.ravel()))
    assert t1.density(f=w).shape == (2, 3, 4)


def test_at_speed_accepts_a_unit():
    road = Spectrum.iso8608("C")
    np.testing.assert_array_equal(road.at_speed("72 km/h").density(OMEGA), road.at_speed(20.0).density(OMEGA))
    with pytest.raises(stochvib.UnitError) as e:
        road.at_speed("72 km")
    assert e.value.name == "speed" and "dimension" in str(e.value)
