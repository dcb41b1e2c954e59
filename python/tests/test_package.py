"""The package itself: the type stubs cover the native classes, docstrings state units and conventions, the
installed wheel is abi3, the exceptions form the documented hierarchy."""

from __future__ import annotations

import ast
import importlib.metadata
import inspect
from pathlib import Path

import pytest

import stochvib
from stochvib import _stochvib


def stub_members():
    """Class name → public member names declared in stochvib/_stochvib.pyi."""
    tree = ast.parse((Path(stochvib.__file__).parent / "_stochvib.pyi").read_text())
    out = {}
    for node in tree.body:
        if isinstance(node, ast.ClassDef):
            out[node.name] = {
                n.name for n in node.body if isinstance(n, (ast.FunctionDef, ast.AsyncFunctionDef)) and not n.name.startswith("_")
            }
    return out


@pytest.mark.parametrize("cls", [_stochvib.Spectrum, _stochvib.System, _stochvib.Scenario], ids=lambda c: c.__name__)
def test_stubs_match_the_native_classes(cls):
    runtime = {n for n in dir(cls) if not n.startswith("_")}
    assert stub_members()[cls.__name__] == runtime


KINDS = {
    inspect.Parameter.POSITIONAL_ONLY: "positional",
    inspect.Parameter.POSITIONAL_OR_KEYWORD: "positional",
    inspect.Parameter.KEYWORD_ONLY: "keyword",
    inspect.Parameter.VAR_POSITIONAL: "*args",
    inspect.Parameter.VAR_KEYWORD: "**kwargs",
}


def stub_signatures():
    """(class, method) → [(parameter, kind)] declared in stochvib/_stochvib.pyi (properties excluded)."""
    tree = ast.parse((Path(stochvib.__file__).parent / "_stochvib.pyi").read_text())
    out = {}
    for node in tree.body:
        if not isinstance(node, ast.ClassDef):
            continue
        for n in node.body:
            if not isinstance(n, ast.FunctionDef) or n.name.startswith("_"):
                continue
            if any(isinstance(d, ast.Name) and d.id == "property" for d in n.decorator_list):
                continue
            a = n.args
            pos = [x.arg for x in a.posonlyargs + a.args]
            if pos and pos[0] in ("self", "cls"):
                pos = pos[1:]
            params = [(x, "positional") for x in pos] + [(x.arg, "keyword") for x in a.kwonlyargs]
            params += [(a.vararg.arg, "*args")] if a.vararg else []
            params += [(a.kwarg.arg, "**kwargs")] if a.kwarg else []
            out[(node.name, n.name)] = params
    return out


def stub_functions():
    """Module-level function → [(parameter, kind)] declared in stochvib/_stochvib.pyi (the last overload)."""
    tree = ast.parse((Path(stochvib.__file__).parent / "_stochvib.pyi").read_text())
    out = {}
    for n in tree.body:
        if isinstance(n, ast.FunctionDef) and not n.name.startswith("_"):
            a = n.args
            params = [(x.arg, "positional") for x in a.posonlyargs + a.args] + [(x.arg, "keyword") for x in a.kwonlyargs]
            out[n.name] = params
    return out


def test_stubs_cover_the_native_functions():
    native = {n for n in dir(_stochvib) if not n.startswith("_") and inspect.isbuiltin(getattr(_stochvib, n))}
    assert set(stub_functions()) == native


def test_stub_signatures_match_the_native_methods():
    # Parameter names and kinds (positional / keyword-only / *args / **kwargs) of every method in the stubs
    # against the signatures PyO3 gives the native methods.
    stubs = stub_signatures()
    assert len(stubs) > 25
    for name, params in stub_functions().items():
        sig = inspect.signature(getattr(_stochvib, name))
        runtime = [(p.name, KINDS[p.kind]) for p in sig.parameters.values()]
        assert runtime == params, name
    for (cls, name), params in stubs.items():
        sig = inspect.signature(getattr(getattr(_stochvib, cls), name))
        runtime = [(p.name, KINDS[p.kind]) for p in sig.parameters.values() if p.name not in ("self", "cls")]
        assert runtime == params, f"{cls}.{name}"


@pytest.mark.parametrize("where", ["gil", "detached", "callback"])
def test_a_panic_in_the_binding_becomes_a_stochvib_error(where):
    # A test hook panics inside each of the binding's guards: the interpreter survives and gets a
    # StochvibError naming the panic.
    with pytest.raises(stochvib.StochvibError, match=rf"internal error .*panic guard check \({where}\)"):
        _stochvib._check_panic_guard(where)


def test_docstrings_state_units_and_conventions():
    d = stochvib.Spectrum.density.__doc__
    for word in ("two-sided-angular", "one-sided-cyclic", "rad/s", "Hz", "cycles/m", "4π S(2πf)"):
        assert word in d, word
    assert "rad/s" in stochvib.System.frequency_response.__doc__
    assert "m/s" in stochvib.Spectrum.at_speed.__doc__
    for obj in (stochvib.Spectrum, stochvib.System, stochvib.Scenario, stochvib.analyze, stochvib.simulate):
        assert inspect.getdoc(obj), obj
    for name in dir(stochvib.Spectrum) + dir(stochvib.System):
        if not name.startswith("_"):
            member = getattr(stochvib.Spectrum if hasattr(stochvib.Spectrum, name) else stochvib.System, name)
            assert inspect.getdoc(member), name


def test_installed_wheel_is_abi3_with_stubs():
    dist = importlib.metadata.distribution("stochvib")
    wheel = dist.read_text("WHEEL")
    assert "abi3" in wheel, wheel
    files = {str(f) for f in dist.files}
    assert "stochvib/_stochvib.pyi" in files and "stochvib/py.typed" in files


def test_exception_hierarchy():
    e = stochvib.errors
    assert issubclass(e.InvalidInputError, ValueError) and issubclass(e.InvalidInputError, e.StochvibError)
    assert issubclass(e.UnitError, e.InvalidInputError) and issubclass(e.UnitError, ValueError)
    assert issubclass(e.DivergentError, ArithmeticError) and issubclass(e.DivergentError, e.StochvibError)
    assert issubclass(e.NumericalError, ArithmeticError)
    assert issubclass(e.NotConvergedError, e.NumericalError) and issubclass(e.NotConvergedError, e.StochvibError)
    assert issubclass(e.FileError, OSError) and issubclass(e.FileError, e.StochvibError)
    assert issubclass(e.NotApplicableError, ValueError)
    for name in ("StochvibError", "InvalidInputError", "UnitError", "DivergentError", "NotConvergedError", "FileError"):
        assert getattr(stochvib, name) is getattr(e, name)
    err = e.FileError("f.toml: key `a` = 1: bad", path="f.toml", key="a")
    assert str(err) == "f.toml: key `a` = 1: bad" and err.key == "a" and err.path == "f.toml" and err.quantity is None
