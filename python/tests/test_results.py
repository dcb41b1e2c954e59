"""Typed results: one class per kind of analysis, attributes that type checkers and tab completion see,
repr like the command-line table, to_dict() as --json, to_dataframe() with pandas (skipped without it)."""

from __future__ import annotations

import dataclasses

import pytest

import stochvib
from stochvib import AnalysisResult, LevelCrossing, OutputResult, VarianceMethod


def test_analysis_result_is_typed(cli):
    path = "data/conveyor-idler.toml"
    r = stochvib.analyze(path)
    assert type(r) is AnalysisResult
    y = r["y"]
    assert type(y) is OutputResult and dataclasses.is_dataclass(y)
    names = {f.name for f in dataclasses.fields(OutputResult)}
    assert {"name", "unit", "mean", "sigma", "variance", "three_sigma", "methods", "levels"} <= names
    assert all(type(m) is VarianceMethod for m in y.methods)
    assert all(type(l) is LevelCrossing for l in y.levels)
    # attributes are the --json values (the Rust library's report)
    want = cli.json("analyze", path)
    out = next(o for o in want["outputs"] if o["statistics"]["name"] == "y")
    assert y.sigma == out["statistics"]["sigma"] and y.mean == out["statistics"]["mean"]
    assert y.three_sigma == (out["lower_3sigma"], out["upper_3sigma"])
    assert y.method("lyapunov").value == out["statistics"]["methods"][0]["outcome"]["value"]
    assert y.method("lyapunov").status == "value" and y.method("lyapunov")["status"] == "value"
    assert [l.level for l in y.levels] == [l["level"] for l in out["levels"]]
    assert r.to_dict() == want and y.to_dict() == out
    assert r.title == want["title"] and r.duration_s == want["duration_s"]
    with pytest.raises(KeyError):
        y.method("no-such-method")


def test_repr_reads_like_the_cli_table(cli):
    r = stochvib.analyze("data/quarter-car.toml")
    text = repr(r)
    lines = text.splitlines()
    assert lines[0].startswith("AnalysisResult: Quarter car")
    assert lines[1].split()[:4] == ["output", "unit", "mean", "sigma"]
    assert len(lines) == 2 + len(r)
    # σ printed as the CLI prints it (Rust's {:.6e}: 1.865465e-2, no zero-padded exponent)
    cli_text = cli.run("analyze", "data/quarter-car.toml").stdout
    for o in r:
        sigma_line = next(l for l in repr(o).splitlines() if l.strip().startswith("sigma"))
        value = sigma_line.split()[1]
        assert f"sigma         {value}" in cli_text
        assert value in text
    assert str(r).rstrip("\n") == cli_text.rstrip("\n")


def test_to_dataframe_one_row_per_output():
    pd = pytest.importorskip("pandas")
    r = stochvib.analyze("data/quarter-car.toml")
    df = r.to_dataframe()
    assert isinstance(df, pd.DataFrame) and list(df["output"]) == r.output_names
    assert list(df["sigma"]) == [o.sigma for o in r]


def test_to_dataframe_without_pandas_says_so(monkeypatch):
    import builtins

    real = builtins.__import__

    def no_pandas(name, *a, **k):
        if name == "pandas":
            raise ImportError("No module named 'pandas'")
        return real(name, *a, **k)

    monkeypatch.setattr(builtins, "__import__", no_pandas)
    with pytest.raises(ImportError, match="pandas"):
        stochvib.analyze("data/conveyor-idler.toml").to_dataframe()


def test_run_result_is_typed(tmp_path):
    run = stochvib.simulate("data/conveyor-idler.toml", 4, tmp_path / "r.h5", seed=3, duration=20.0, progress=False)
    assert type(run) is stochvib.RunResult
    assert run.path == tmp_path / "r.h5" and run.n_realizations == 4 and run.route in ("exact", "spectral")
    assert set(run.sigma) == set(run.statistics)
    assert repr(run).startswith("RunResult: ")
