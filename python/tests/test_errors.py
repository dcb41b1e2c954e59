"""The error hierarchy (StochvibError → InvalidInputError (ValueError), UnitError, DivergentError,
NotConvergedError, FileError): each raised where the old API's traps were, with the command-line tool's message
and hint."""

from __future__ import annotations

import pytest

import stochvib
from stochvib import (
    DivergentError,
    FileError,
    InvalidInputError,
    NotConvergedError,
    Spectrum,
    StochvibError,
    System,
    UnitError,
)

UNSTABLE_TF = """title = "an unstable transfer function"
[model]
kind = "transfer-function"
numerator = [1.0]
denominator = [1.0, -1.0, 1.0]   # ascending: 1 − s + s², roots ½ ± i√3/2 in the right half-plane
output = { name = "y", unit = "m" }
[input]
spectrum = "type1"
"""


def test_trap_unstable_system_raises_divergent_error_with_the_cli_hint(cli, tmp_path):
    # The trap: an unstable system raised a generic InvalidInputError without the CLI's hint.
    # s² − s + 1 is the same polynomial in either order (a palindrome): the file and the call agree.
    path = tmp_path / "unstable.toml"
    path.write_text(UNSTABLE_TF)
    want = cli.error("analyze", str(path))
    sys_ = System.transfer_function([1.0], [1.0, -1.0, 1.0], unit="m")
    with pytest.raises(DivergentError) as e:
        stochvib.analyze(sys_, Spectrum.load("type1"))
    err = e.value
    assert isinstance(err, StochvibError) and isinstance(err, ArithmeticError)
    assert err.hint == "D(s) has a root with Re s ≥ 0 (a pole in the right half-plane or on the axis)"
    assert "not asymptotically stable" in err.reason and "max Re(eigenvalue) = 5e-1" in err.reason
    # the CLI's message names the file's key, then the same diagnosis and hint
    assert want.endswith(f"{err.reason}: {err.hint}"), (want, str(err))
    assert str(err).endswith(f"{err.reason}: {err.hint}")
    with pytest.raises(DivergentError):
        stochvib.simulate(sys_, 2, tmp_path / "run.h5", input=Spectrum.load("type1"), progress=False)


def test_undamped_mdof_is_divergent_with_the_model_hint():
    # m ẍ + k x = f without damping: poles ±i√(k/m) on the axis, no stationary response
    sys_ = System.mdof(mass=[[1.0]], damping=[[0.0]], stiffness=[[4.0]])
    with pytest.raises(DivergentError, match="check the stiffnesses, dampings and masses") as e:
        stochvib.analyze(sys_, Spectrum.exponential(1.0, 1.0, unit="N"))
    assert e.value.quantity.startswith("the stationary response")


def test_trap_unit_strings_accepted_wherever_a_quantity_is():
    # The trap: analyze(speed="10.8 km/h") raised a bare TypeError.
    car = System.model("quarter-car", sprung_mass="300 kg", unsprung_mass="40 kg",
                       suspension_stiffness="20 kN/m", suspension_damping="1.5 kN*s/m", tyre_stiffness="200 kN/m")
    road = Spectrum.iso8608("C")
    si = stochvib.analyze(car, road, speed=3.0, duration_s=600.0)
    text = stochvib.analyze(car, road, speed="10.8 km/h", duration_s="10 min")
    assert text.to_dict() == si.to_dict()  # 10.8 km/h = 3 m/s exactly, 10 min = 600 s
    with pytest.raises(UnitError) as e:
        stochvib.analyze(car, road, speed="10.8 km/hh")
    assert e.value.name == "speed" and e.value.value == "10.8 km/hh" and "unknown unit" in str(e.value)
    with pytest.raises(UnitError, match="dimension") as e:
        stochvib.analyze(car, road, speed="10.8 km")
    assert e.value.name == "speed" and isinstance(e.value, ValueError)
    with pytest.raises(InvalidInputError, match="expected a number"):
        stochvib.analyze(car, road, speed=[3.0])
    # positions of a track (m) with units too
    two = System.mdof(mass=[[1.0, 0.0], [0.0, 1.0]], damping=[[1.0, 0.0], [0.0, 1.0]], stiffness=[[1.0, 0.0], [0.0, 1.0]])
    a = stochvib.analyze(two, Spectrum.exponential(1.0, 1.0), positions=[0.0, "150 cm"], speed="5.4 km/h")
    b = stochvib.analyze(two, Spectrum.exponential(1.0, 1.0), positions=[0.0, 1.5], speed=1.5)
    assert [o.to_dict() for o in a] == [o.to_dict() for o in b]
    with pytest.raises(UnitError) as e:
        stochvib.analyze(two, Spectrum.exponential(1.0, 1.0), positions=[0.0, "1.5 s"], speed=1.5)
    assert e.value.name == "positions[1]"


def test_invalid_input_is_a_value_error_with_the_library_message():
    with pytest.raises(ValueError) as e:
        Spectrum.exponential(-1.0, 1.0)
    assert isinstance(e.value, InvalidInputError)
    assert str(e.value).startswith("invalid parameter `") and e.value.value == "-1"


def test_file_error_names_the_path():
    with pytest.raises(FileError) as e:
        stochvib.Scenario.load("data/no-such-file.toml")
    assert isinstance(e.value, OSError) and isinstance(e.value, StochvibError)
    assert e.value.path == "data/no-such-file.toml"


def test_quadrature_that_does_not_converge_is_not_converged_error():
    # K(τ) of an ISO 8608 road at a lag of 1000 km: the oscillatory quadrature runs out of subintervals
    with pytest.raises(NotConvergedError) as e:
        Spectrum.iso8608("C").correlation(1e6)
    err = e.value
    assert isinstance(err, stochvib.NumericalError) and isinstance(err, ArithmeticError)
    assert str(err).startswith("quadrature of ") and "did not converge" in str(err)
    assert err.evaluations > 0 and err.abs_error > 0 and err.estimate is not None
