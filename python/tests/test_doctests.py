"""Every Examples section of the package runs as a doctest: the Python modules and the native classes'
and functions' docstrings (which doctest's finder does not reach in an extension module)."""

from __future__ import annotations

import doctest
import inspect

import pytest

import stochvib
from stochvib import _stochvib, comfort, errors, estimate, fatigue, results, road


def native_docstrings():
    out = []
    for cls in (_stochvib.Spectrum, _stochvib.System, _stochvib.Scenario):
        for name, member in inspect.getmembers(cls):
            doc = getattr(member, "__doc__", None)
            if not name.startswith("_") and doc and ">>>" in doc:
                out.append((f"{cls.__name__}.{name}", doc))
    for name in dir(_stochvib):
        f = getattr(_stochvib, name)
        if inspect.isbuiltin(f) and f.__doc__ and ">>>" in f.__doc__:
            out.append((name, f.__doc__))
    return out


def python_docstrings():
    out = []
    finder = doctest.DocTestFinder()
    native = {d for _, d in native_docstrings()}
    for mod in (stochvib, comfort, errors, estimate, fatigue, results, road):
        for t in finder.find(mod, mod.__name__):
            if t.examples and t.docstring not in native:  # the native classes' methods: found above
                out.append((t.name, t.docstring))
    return out


ALL = native_docstrings() + python_docstrings()


def test_there_are_examples():
    names = {n for n, _ in ALL}
    assert len(ALL) >= 15
    for must in ("System.transfer_function", "Spectrum.density", "stochvib.analyze", "stochvib.exposure", "stochvib.analyze_nonlinear",
                 "stochvib.replay", "stochvib.workday", "stochvib.inspect"):
        assert any(must in n for n in names), must


@pytest.mark.parametrize("name,doc", ALL, ids=[n for n, _ in ALL])
def test_docstring_examples_run(name, doc):
    test = doctest.DocTestParser().get_doctest(doc, {}, name, None, 0)
    runner = doctest.DocTestRunner(optionflags=doctest.ELLIPSIS | doctest.NORMALIZE_WHITESPACE)
    runner.run(test)
    assert runner.failures == 0, f"{name}: {runner.failures} failing example(s) (see the output above)"


def _has_section(doc: str, section: str) -> bool:
    """A numpydoc section: its title line followed by a line of as many dashes."""
    lines = [line.strip() for line in (doc or "").splitlines()]
    return any(a == section and b == "-" * len(section) for a, b in zip(lines, lines[1:]))


def _takes_arguments(f) -> bool:
    """Whether ``f`` has a parameter besides self/cls (a callable without a readable signature is assumed to)."""
    try:
        params = inspect.signature(f).parameters
    except (TypeError, ValueError):
        return True
    return any(name not in ("self", "cls") for name in params)


# name → why it needs no Parameters/Returns sections (none at present: add a reason here, never silently).
EXEMPT: dict = {}


def public_callables():
    """Every function exported by ``stochvib.__all__`` (and by the ``__all__`` of the modules it exports) and
    every public method of System, Spectrum and Scenario (properties are attributes, not callables)."""
    out = []
    for name in stochvib.__all__:
        obj = getattr(stochvib, name)
        if inspect.ismodule(obj):
            out += [(f"{name}.{n}", getattr(obj, n)) for n in getattr(obj, "__all__", [])
                    if inspect.isfunction(getattr(obj, n)) or inspect.isbuiltin(getattr(obj, n))]
        elif inspect.isfunction(obj) or inspect.isbuiltin(obj):
            out.append((name, obj))
    for cls in (stochvib.System, stochvib.Spectrum, stochvib.Scenario):
        out += [(f"{cls.__name__}.{n}", m) for n, m in inspect.getmembers(cls)
                if not n.startswith("_") and callable(m) and not isinstance(inspect.getattr_static(cls, n), property)]
    return out


def test_every_public_callable_has_parameters_and_returns():
    """numpydoc ``Parameters`` (unless the callable takes no argument) and ``Returns`` sections on every public
    callable, so that an undocumented one cannot be added unnoticed."""
    checked = public_callables()
    names = {n for n, _ in checked}
    # the test is not vacuous: it reaches the native methods, the module functions and the submodules
    assert {"analyze", "simulate", "System.model", "Spectrum.at_speed", "Scenario.from_system", "fatigue.spectral"} <= names
    assert len(checked) >= 60
    missing = []
    for name, f in checked:
        if name in EXEMPT:
            continue
        doc = inspect.getdoc(f) or ""
        need = (["Parameters"] if _takes_arguments(f) else []) + ["Returns"]
        missing += [f"{name}: no {s} section" for s in need if not _has_section(doc, s)]
    assert not missing, "\n".join(missing)
