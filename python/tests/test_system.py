"""stochvib.System: frequency responses against scipy.signal.freqresp and direct numpy solves, modes against
scipy.linalg.eigh, catalogue models against their scenario files, argument checking."""

from __future__ import annotations

import numpy as np
import pytest
import scipy.linalg
import scipy.signal

from stochvib import InvalidInputError, NotApplicableError, System

# --- named tolerances -------------------------------------------------------------------------------------
# Two independent dense solves of the same small, well-conditioned complex system.
REL_SOLVE = 1e-11
# Absolute floor for response entries that are exactly zero in one solve and ~1e-17 in the other.
ABS_SOLVE = 1e-14
# Eigenvalues of a 3×3 symmetric-definite pencil by two LAPACK-free/LAPACK routes.
REL_EIG = 1e-10

W = np.linspace(0.0, 60.0, 241)

# A 3-DOF chain: masses 2, 1, 3 kg; springs 400, 250, 300 N/m (ground–1, 1–2, 2–3); dampers 3, 2, 1 N s/m.
M3 = np.diag([2.0, 1.0, 3.0])
K3 = np.array([[650.0, -250.0, 0.0], [-250.0, 550.0, -300.0], [0.0, -300.0, 300.0]])
B3 = np.array([[5.0, -2.0, 0.0], [-2.0, 3.0, -1.0], [0.0, -1.0, 1.0]])


def test_mdof_force_response_against_direct_solve():
    sys = System.mdof(mass=M3, damping=B3, stiffness=K3)  # default: a force on every coordinate, displacement outputs
    assert sys.n_inputs == 3 and [o[0] for o in sys.outputs] == ["q1", "q2", "q3"]
    h = sys.frequency_response(W)
    assert h.shape == (3, 3, W.size) and h.dtype == np.complex128
    # Q(iω) = (K − ω²M + iωB)⁻¹ F with F = I, solved by numpy at every ω
    for k, w in enumerate(W):
        direct = np.linalg.solve(K3 - w * w * M3 + 1j * w * B3, np.eye(3))
        np.testing.assert_allclose(h[:, :, k], direct, rtol=REL_SOLVE, atol=ABS_SOLVE)
    # a scalar ω gives one (outputs, inputs) matrix
    assert sys.frequency_response(3.0).shape == (3, 3)


def test_mdof_base_input_outputs_against_direct_solve():
    # base input through the first spring/damper pair (400 N/m, 3 N s/m): K_u = [400, 0, 0]ᵀ, B_u = [3, 0, 0]ᵀ
    # (base_stiffness, base_damping)
    ku = np.array([[400.0], [0.0], [0.0]])
    bu = np.array([[3.0], [0.0], [0.0]])
    outs = {"x3": ("displacement", [0, 0, 1]), "a3": ("acceleration", [0, 0, 1]), "v13": ("velocity", [1, 0, -1])}
    sys = System.mdof(mass=M3, damping=B3, stiffness=K3, base_stiffness=ku, base_damping=bu, outputs=outs)
    assert sys.n_inputs == 1
    assert sys.outputs == [("x3", "m"), ("a3", "m/s^2"), ("v13", "m/s")]
    h = sys.frequency_response(W)
    for k, w in enumerate(W):
        q = np.linalg.solve(K3 - w * w * M3 + 1j * w * B3, ku + 1j * w * bu)[:, 0]
        want = [q[2], -w * w * q[2], 1j * w * (q[0] - q[2])]
        np.testing.assert_allclose(h[:, 0, k], want, rtol=REL_SOLVE, atol=ABS_SOLVE)
    # static gain of a base-driven chain: every mass follows the base (H(0) = 1 for x3, 0 for a3 and v13)
    np.testing.assert_allclose(sys.static_gain(), [[1.0], [0.0], [0.0]], atol=1e-12)


@pytest.mark.filterwarnings("ignore::scipy.signal.BadCoefficients")  # scipy's own ss → tf conversion
def test_state_space_against_scipy_freqresp():
    # SDOF ẍ + 2ζωₙẋ + ωₙ²x = u, ωₙ = 10, ζ = 0.05, output x
    wn, z = 10.0, 0.05
    a = np.array([[0.0, 1.0], [-wn * wn, -2 * z * wn]])
    b = np.array([[0.0], [1.0]])
    c = np.array([[1.0, 0.0]])
    d = np.array([[0.0]])
    sys = System.state_space(a, b, c, d, outputs=[("x", "m")])
    _, ref = scipy.signal.freqresp(scipy.signal.StateSpace(a, b, c, d), w=W[1:])
    np.testing.assert_allclose(sys.frequency_response(W[1:])[0, 0], ref, rtol=REL_SOLVE, atol=0)
    # |λ| of the poles of an underdamped oscillator is ωₙ
    np.testing.assert_allclose(sys.natural_frequencies(), [wn], rtol=REL_EIG)
    with pytest.raises(NotApplicableError, match="System.mdof"):
        sys.modes()


def test_state_space_mimo_with_derivative_feedthrough_against_direct_formula():
    rng = np.random.default_rng(5)
    a = np.array([[-1.0, 2.0, 0.0], [-2.0, -1.0, 0.5], [0.0, 0.0, -3.0]])
    b = rng.normal(size=(3, 2))
    c = rng.normal(size=(2, 3))
    d = rng.normal(size=(2, 2))
    e = rng.normal(size=(2, 2))
    sys = System.state_space(a, b, c, d, e)
    assert sys.outputs == [("y1", "1"), ("y2", "1")]
    h = sys.frequency_response(W)
    for k, w in enumerate(W):
        want = c @ np.linalg.solve(1j * w * np.eye(3) - a, b) + d + 1j * w * e
        np.testing.assert_allclose(h[:, :, k], want, rtol=REL_SOLVE, atol=ABS_SOLVE)
    m = sys.state_space_matrices()
    np.testing.assert_array_equal(m["A"], a)
    np.testing.assert_array_equal(m["E"], e)


@pytest.mark.parametrize("order", ["ascending", "descending"])
def test_transfer_function_against_scipy(order):
    # H(s) = (2 + 0.5 s) / (100 + 1 s + s²)  (scipy: descending coefficients)
    num_desc, den_desc = [0.5, 2.0], [1.0, 1.0, 100.0]
    args = (num_desc[::-1], den_desc[::-1]) if order == "ascending" else (num_desc, den_desc)
    sys = System.transfer_function(*args, order=order, output="y", unit="m")
    _, ref = scipy.signal.freqresp(scipy.signal.TransferFunction(num_desc, den_desc), w=W)
    np.testing.assert_allclose(sys.frequency_response(W)[0, 0], ref, rtol=REL_SOLVE, atol=0)
    assert sys.outputs == [("y", "m")]


def test_trap_transfer_function_takes_descending_coefficients_like_scipy_freqs():
    # The trap: the same call as scipy.signal.freqs(b, a) must build the same system, with no keyword.
    # H(s) = (3 s + 1) / (2 s³ + 5 s² + 4 s + 7); scipy.signal.freqs evaluates polyval(b, iω)/polyval(a, iω).
    b, a = [3.0, 1.0], [2.0, 5.0, 4.0, 7.0]
    _, ref = scipy.signal.freqs(b, a, worN=W)
    h = System.transfer_function(b, a).frequency_response(W)[0, 0]
    np.testing.assert_allclose(h, ref, rtol=REL_SOLVE, atol=0)
    # ascending only when asked for, and the two differ (a reversed denominator is another system)
    asc = System.transfer_function(b[::-1], a[::-1], order="ascending").frequency_response(W)[0, 0]
    np.testing.assert_allclose(asc, ref, rtol=REL_SOLVE, atol=0)
    assert not np.allclose(System.transfer_function(b, a, order="ascending").frequency_response(W)[0, 0], ref)
    with pytest.raises(InvalidInputError, match="order"):
        System.transfer_function(b, a, order="reversed")
    # options are keyword-only: a third positional argument is refused
    with pytest.raises(TypeError):
        System.transfer_function(b, a, "ascending")


def test_trap_mdof_takes_named_matrices_only():
    # The trap: mdof(M, B, C) beside state_space(A, B, C, D) invites swapping damping and stiffness.
    with pytest.raises(TypeError):
        System.mdof(M3, B3, K3)
    sys = System.mdof(stiffness=K3, mass=M3, damping=B3)  # any order of the keywords is the same system
    for k, w in enumerate(W[:5]):
        direct = np.linalg.solve(K3 - w * w * M3 + 1j * w * B3, np.eye(3))
        np.testing.assert_allclose(sys.frequency_response(W[:5])[:, :, k], direct, rtol=REL_SOLVE, atol=ABS_SOLVE)


def test_frequency_response_in_hertz_and_broadcasting():
    # f= (Hz) is ω = 2πf; any array shape broadcasts to (outputs, inputs, *shape)
    sys = System.transfer_function([1.0], [1.0, 2.0, 5.0])
    f = np.linspace(0.0, 3.0, 12).reshape(3, 4)
    np.testing.assert_array_equal(sys.frequency_response(f=f), sys.frequency_response(2 * np.pi * f))  # ω = (2π)·f
    assert sys.frequency_response(f=f).shape == (1, 1, 3, 4)
    with pytest.raises(InvalidInputError, match="exactly one"):
        sys.frequency_response(1.0, f=1.0)
    with pytest.raises(InvalidInputError, match="exactly one"):
        sys.frequency_response()


def test_modes_against_scipy_eigh():
    sys = System.mdof(mass=M3, damping=B3, stiffness=K3)
    w, phi = sys.modes()
    lam = scipy.linalg.eigh(K3, M3, eigvals_only=True)
    np.testing.assert_allclose(w, np.sqrt(lam), rtol=REL_EIG)
    # mass-normalised: Φᵀ M Φ = I and Φᵀ K Φ = diag(ω²)
    np.testing.assert_allclose(phi.T @ M3 @ phi, np.eye(3), atol=1e-12)
    np.testing.assert_allclose(phi.T @ K3 @ phi, np.diag(lam), rtol=REL_EIG, atol=1e-9)


def test_catalogue_model_matches_its_scenario_file(root):
    # data/quarter-car-model.toml's [model] table, given as keyword arguments with the same units
    from_file = System.load(root / "data" / "quarter-car-model.toml")
    import tomllib

    table = tomllib.loads((root / "data" / "quarter-car-model.toml").read_text())["model"]
    kind = table.pop("kind")
    built = System.model(kind, **table)
    assert built.kind == from_file.kind == "quarter-car"
    assert built.outputs == from_file.outputs
    np.testing.assert_array_equal(built.frequency_response(W), from_file.frequency_response(W))


def test_models_lists_the_registry():
    kinds = {k["name"]: k for k in System.models()}
    assert {"mdof", "state-space", "transfer-function", "quarter-car", "half-car", "mine-hoist"} <= set(kinds)
    assert kinds["mine-hoist"]["stochastic"] is False
    with pytest.raises(NotApplicableError, match="deterministic"):
        System.model("mine-hoist")


def test_model_errors_name_the_parameter():
    from stochvib import FileError, UnitError

    with pytest.raises(InvalidInputError, match="unknown model kind; known kinds: mdof, "):
        System.model("quarter-kar")
    with pytest.raises(InvalidInputError) as e:
        System.model("quarter-car", sprung_mass="300 kg")
    assert e.value.name == "unsprung_mass" and not isinstance(e.value, FileError)
    with pytest.raises(InvalidInputError, match="unknown key") as e:
        System.model(
            "quarter-car",
            sprung_mass="300 kg",
            unsprung_mass="40 kg",
            suspension_stiffness="20 kN/m",
            suspension_damping="1.5 kN*s/m",
            tyre_stiffness="200 kN/m",
            tyre_stifness="1 N/m",
        )
    assert e.value.name == "tyre_stifness"
    with pytest.raises(InvalidInputError, match="expected a number"):
        System.model("quarter-car", sprung_mass=None)


def test_trap_unit_error_in_a_model_parameter_is_a_unit_error_naming_it():
    # The trap: a bad unit in a keyword argument raised FileError naming a scenario-file key `model.…`.
    from stochvib import FileError, UnitError

    good = dict(
        sprung_mass="300 kg",
        unsprung_mass="40 kg",
        suspension_stiffness="20 kN/m",
        suspension_damping="1.5 kN*s/m",
        tyre_stiffness="200 kN/m",
    )
    for key, bad, why in [("sprung_mass", "300 kgg", "unknown unit"), ("suspension_stiffness", "20 kN", "dimension")]:
        with pytest.raises(UnitError, match=why) as e:
            System.model("quarter-car", **{**good, key: bad})
        err = e.value
        assert isinstance(err, InvalidInputError) and isinstance(err, ValueError) and not isinstance(err, FileError)
        assert err.name == key and err.value == bad
        assert str(err).startswith(f"invalid parameter `{key}` = ") and "model." not in str(err)
    # a value in range with a good unit but out of range is an InvalidInputError, not a UnitError
    with pytest.raises(InvalidInputError) as e:
        System.model("quarter-car", **{**good, "sprung_mass": "-300 kg"})
    assert not isinstance(e.value, UnitError) and e.value.name == "sprung_mass"


def test_matrix_arguments_checked():
    with pytest.raises(InvalidInputError, match="2-D"):
        System.state_space(np.eye(2), np.ones(2), np.ones((1, 2)))  # B 1-D: row or column?
    with pytest.raises(InvalidInputError, match="complex"):
        System.mdof(mass=M3 + 0j, damping=B3, stiffness=K3)
    with pytest.raises(InvalidInputError) as e:
        System.state_space(np.eye(2), np.ones((3, 1)), np.ones((1, 2)))
    assert e.value.name == "B" and "must be 2x1" in str(e.value)
    with pytest.raises(InvalidInputError, match="mass matrix"):
        System.mdof(mass=np.zeros((3, 3)), damping=B3, stiffness=K3)
    with pytest.raises(InvalidInputError, match="symmetric"):
        System.mdof(mass=M3, damping=B3, stiffness=K3 + np.triu(np.ones((3, 3)), 1))
    # Fortran-ordered, integer and list matrices are converted and give the same system
    ref = System.mdof(mass=M3, damping=B3, stiffness=K3).frequency_response(W)
    alt = System.mdof(mass=np.asfortranarray(M3), damping=B3.tolist(), stiffness=K3.astype(np.int64))
    np.testing.assert_array_equal(alt.frequency_response(W), ref)
    with pytest.raises(InvalidInputError, match="output"):
        System.mdof(mass=M3, damping=B3, stiffness=K3).output_index("nope")
