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
