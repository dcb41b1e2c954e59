"""Cluster studies from Python against the command-line tool: parameter studies in shards
(``Scenario.sweep(..., shard=(I, N), path=DIR)`` = ``stochvib sweep --shard I --of N -o DIR``) joined by
``stochvib.merge_sweep`` (= ``stochvib merge TABLE DIR``), the parts of a transient Monte Carlo run joined by
``stochvib.merge_transient`` (= ``stochvib merge RUN DIR --json``), the verdict table of a study
(``Scenario.sweep_verdicts`` = ``stochvib sweep --verdicts``), and each merge refusing the files of another
kind with the name of the function that joins them.

The expected values are the command-line tool's files and ``--json`` for the same inputs (the Rust library's
answer reached through another front end), and the same study or run made in one piece: a point of a study
and realization i of a run (random stream (seed, i)) do not depend on the part that computes them, so a
merged study or run equals the whole one to the last bit."""

from __future__ import annotations

import json
import shutil

import numpy as np
import pytest

import stochvib
from stochvib import FileError, InvalidInputError

SWEEP = "data/conveyor-idler.toml"
VALUES = "50 kN/m..200 kN/m:5"
TRANSIENT = "data/quarter-car-accelerating.toml"
VERDICTS = "data/operator-seat-verdicts.toml"


def sweep_parts(tmp_path, n=2):
    """The shard files of the conveyor study, from Python, in tmp_path/py."""
    sc = stochvib.Scenario.load(SWEEP)
    return [sc.sweep({"model.c": VALUES}, shard=(i, n), path=tmp_path / "py", progress=False) for i in range(n)]


def transient_parts(tmp_path):
    """The two part files of a 6-realization transient run, from Python, in tmp_path/py."""
    sc = stochvib.Scenario.load(TRANSIENT)
    for i in range(2):
        sc.transient(monte_carlo=6, shard_size=3, seed=4, path=tmp_path / "py", shard=(i, 2), progress=False)


def test_sweep_shards_and_their_merge_are_the_cli_files(cli, tmp_path):
    for i in range(2):
        cli.run("sweep", SWEEP, "--param", f"model.c={VALUES}", "--shard", str(i), "--of", "2", "-o", str(tmp_path / "cli"))
    cli.run("merge", str(tmp_path / "cli.json"), str(tmp_path / "cli"))
    parts = sweep_parts(tmp_path)
    for i, part in enumerate(parts):
        name = f"sweep-shard-{i}-of-2.json"
        assert part.path == tmp_path / "py" / name
        assert part.path.read_bytes() == (tmp_path / "cli" / name).read_bytes()
    # a part holds numbers at its own points only: points 0..3 and 3..5 of 5
    assert (parts[0].points, parts[1].points) == (range(0, 3), range(3, 5))
    s0 = parts[0].sigma("y")
    assert np.isfinite(s0[:3]).all() and np.isnan(s0[3:]).all()
    t = stochvib.merge_sweep(tmp_path / "py.json", tmp_path / "py")
    assert t.path == tmp_path / "py.json"
    assert (tmp_path / "py.json").read_bytes() == (tmp_path / "cli.json").read_bytes()
    assert t.to_dict() == json.loads((tmp_path / "cli.json").read_text())
    assert t.to_dict() == stochvib.Scenario.load(SWEEP).sweep({"model.c": VALUES}).to_dict()


def test_merged_sweep_table_in_any_format_is_the_cli_table(cli, tmp_path):
    sweep_parts(tmp_path, n=3)
    for ext in ("csv", "h5"):
        cli.run("merge", str(tmp_path / f"cli.{ext}"), str(tmp_path / "py"))
        t = stochvib.merge_sweep(tmp_path / f"py.{ext}", tmp_path / "py")
        assert t.n_points == 5 and t.points == range(5)
        if ext == "csv":
            assert (tmp_path / "py.csv").read_bytes() == (tmp_path / "cli.csv").read_bytes()
    h5py = pytest.importorskip("h5py")
    with h5py.File(tmp_path / "py.h5") as a, h5py.File(tmp_path / "cli.h5") as b:
        assert sorted(a) == sorted(b)
    with pytest.raises(FileError, match="exists|overwrite"):
        stochvib.merge_sweep(tmp_path / "py.csv", tmp_path / "py")
    stochvib.merge_sweep(tmp_path / "py.csv", tmp_path / "py", overwrite=True)


def test_sweep_shard_needs_its_directory_and_a_valid_part(tmp_path):
    sc = stochvib.Scenario.load(SWEEP)
    with pytest.raises(InvalidInputError, match="path="):
        sc.sweep({"model.c": VALUES}, shard=(0, 2))
    with pytest.raises(InvalidInputError, match="`path`"):
        sc.sweep({"model.c": VALUES}, path=tmp_path)
    with pytest.raises(InvalidInputError, match="shard"):
        sc.sweep({"model.c": VALUES}, shard=(2, 2), path=tmp_path)
    with pytest.raises(InvalidInputError, match="only 5 points"):
        sc.sweep({"model.c": VALUES}, shard=(0, 6), path=tmp_path)


def test_transient_parts_merged_as_the_cli_merges_them(cli, tmp_path):
    for i in range(2):
        cli.run(
            "transient", TRANSIENT, "--monte-carlo", "6", "--shard-size", "3", "--seed", "4",
            "--shard", str(i), "--of", "2", "-o", str(tmp_path / "cli"),
        )  # fmt: skip
    want = cli.json("merge", str(tmp_path / "cli.h5"), str(tmp_path / "cli"))
    transient_parts(tmp_path)
    m = stochvib.merge_transient(tmp_path / "py.h5", tmp_path / "py")
    got = m.to_dict()
    assert (got.pop("path"), want.pop("path")) == (str(tmp_path / "py.h5"), str(tmp_path / "cli.h5"))
    assert got == want
    assert m.n_realizations == 6 and set(m.sigma_coverage) == {o["output"] for o in want["outputs"]}
    assert "TransientRunResult" in repr(m) and "merged 6 realizations" in str(m)
    whole = stochvib.Scenario.load(TRANSIENT).transient(
        monte_carlo=6, shard_size=3, seed=4, path=tmp_path / "whole.h5", progress=False
    )
    assert whole.monte_carlo["outputs"] == got["outputs"]
    assert whole.monte_carlo["sigma_coverage"] == got["sigma_coverage"]


def test_each_merge_refuses_the_files_of_another_kind(tmp_path):
    sweep_parts(tmp_path / "s")
    transient_parts(tmp_path / "t")
    for i in range(2):
        stochvib.simulate(SWEEP, 20, tmp_path / "r", shard=(i, 2), shard_size=10, progress=False)
    cases = [
        (stochvib.merge, tmp_path / "s" / "py", "stochvib.merge_sweep"),
        (stochvib.merge_transient, tmp_path / "s" / "py", "stochvib.merge_sweep"),
        (stochvib.merge, tmp_path / "t" / "py", "stochvib.merge_transient"),
        (stochvib.merge_sweep, tmp_path / "t" / "py", "stochvib.merge_transient"),
    ]
    for f, parts, name in cases:
        with pytest.raises(InvalidInputError, match=name):
            f(tmp_path / "out.h5", parts)
        assert not (tmp_path / "out.h5").exists()
    with pytest.raises(InvalidInputError, match=r"stationary Monte Carlo run: stochvib\.merge\("):
        stochvib.merge_transient(tmp_path / "out.h5", tmp_path / "r")
    assert not (tmp_path / "out.h5").exists()
    with pytest.raises(FileError, match="no sweep shard files"):
        stochvib.merge_sweep(tmp_path / "out.json", tmp_path / "r")
    # the merged file is never one of its parts
    with pytest.raises(FileError, match="is one of the shard files to merge"):
        stochvib.merge(tmp_path / "r" / "shard-0-of-2.h5", tmp_path / "r")
    with pytest.raises(FileError, match="is one of the shard files to merge"):
        stochvib.merge_transient(tmp_path / "t" / "py" / "shard-1-of-2.h5", tmp_path / "t" / "py")
    # one kind at a time
    shutil.copy(tmp_path / "s" / "py" / "sweep-shard-0-of-2.json", tmp_path / "r")
    with pytest.raises(FileError, match="one kind at a time"):
        stochvib.merge(tmp_path / "out.h5", tmp_path / "r")


def test_verdict_table_is_the_cli_table(cli):
    params = {"model.stiffness": ["5000 N/m", "8000 N/m"], "model.damping_rate": ["3 1/s", "4 1/s", "5 1/s"]}
    args = ["sweep", VERDICTS, "--param", "model.stiffness=5000 N/m,8000 N/m"]
    args += ["--param", "model.damping_rate=3 1/s,4 1/s,5 1/s", "--verdicts"]
    t = stochvib.Scenario.load(VERDICTS).sweep_verdicts(params)
    assert t.to_dict() == cli.json(*args)
    assert t.to_csv() == cli.run(*args).stdout
    assert t.shape == (2, 3) and t.columns[:3] == ["point", "model.stiffness [kg s^-2]", "model.damping_rate [s^-1]"]
    # the swept values in SI, the first key varying slowest
    np.testing.assert_array_equal(t.column("model.stiffness [kg s^-2]"), [[5000.0] * 3, [8000.0] * 3])
    np.testing.assert_array_equal(t.column("model.damping_rate [s^-1]"), [[3.0, 4.0, 5.0]] * 2)
    z = stochvib.Scenario.load(VERDICTS).sweep_verdicts({"model.stiffness": ["5000 N/m", "8000 N/m"]}, zip=True)
    assert z.shape == (2,) and "VerdictTable: 2 points" in repr(z)
    with pytest.raises(KeyError, match="no column"):
        t.column("sigma(nothing) [m]")
