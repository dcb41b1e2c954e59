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
    sys = System.mdof(M3, B3, K3)  # default: a force on every coordinate, displacement outputs
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
    ku = np.array([[400.0], [0.0], [0.0]])
    bu = np.array([[3.0], [0.0], [0.0]])
    outs = {"x3": ("displacement", [0, 0, 1]), "a3": ("acceleration", [0, 0, 1]), "v13": ("velocity", [1, 0, -1])}
    sys = System.mdof(M3, B3, K3, K_u=ku, B_u=bu, outputs=outs)
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


def test_modes_against_scipy_eigh():
    sys = System.mdof(M3, B3, K3)
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


def test_model_errors_are_the_file_reader_messages():
    from stochvib import FileError

    with pytest.raises(FileError, match="unknown model kind; known kinds: mdof, "):
        System.model("quarter-kar")
    with pytest.raises(FileError) as e:
        System.model("quarter-car", sprung_mass="300 kg")
    assert e.value.key.startswith("model.")
    with pytest.raises(FileError, match="unknown key"):
        System.model(
            "quarter-car",
            sprung_mass="300 kg",
            unsprung_mass="40 kg",
            suspension_stiffness="20 kN/m",
            suspension_damping="1.5 kN*s/m",
            tyre_stiffness="200 kN/m",
            tyre_stifness="1 N/m",
        )
    with pytest.raises(InvalidInputError, match="expected a number"):
        System.model("quarter-car", sprung_mass=None)


def test_matrix_arguments_checked():
    with pytest.raises(InvalidInputError, match="2-D"):
        System.state_space(np.eye(2), np.ones(2), np.ones((1, 2)))  # B 1-D: row or column?
    with pytest.raises(InvalidInputError, match="complex"):
        System.mdof(M3 + 0j, B3, K3)
    with pytest.raises(InvalidInputError) as e:
        System.state_space(np.eye(2), np.ones((3, 1)), np.ones((1, 2)))
    assert e.value.name == "B" and "must be 2x1" in str(e.value)
    with pytest.raises(InvalidInputError, match="mass matrix"):
        System.mdof(np.zeros((3, 3)), B3, K3)
    with pytest.raises(InvalidInputError, match="symmetric"):
        System.mdof(M3, B3, K3 + np.triu(np.ones((3, 3)), 1))
    # Fortran-ordered, integer and list matrices are converted and give the same system
    ref = System.mdof(M3, B3, K3).frequency_response(W)
    alt = System.mdof(np.asfortranarray(M3), B3.tolist(), K3.astype(np.int64))
    np.testing.assert_array_equal(alt.frequency_response(W), ref)
    with pytest.raises(InvalidInputError, match="output"):
        System.mdof(M3, B3, K3).output_index("nope")
