"""Every script of python/examples runs to the end (each checks its own numbers with assertions)."""

from __future__ import annotations

import runpy

import pytest

from conftest import ROOT

EXAMPLES = sorted((ROOT / "python" / "examples").glob("*.py"))


@pytest.mark.parametrize("path", EXAMPLES, ids=[p.name for p in EXAMPLES])
def test_example_runs(path, capsys):
    runpy.run_path(str(path), run_name="__main__")
    assert "sigma" in capsys.readouterr().out


def test_there_is_an_example():
    assert EXAMPLES
