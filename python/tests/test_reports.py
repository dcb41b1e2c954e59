"""`stochvib.replay`, `stochvib.workday` and `stochvib.inspect` against the command-line tool: the ``--json``
text byte for byte (``to_json()``), the data (``to_dict()``), the text report (``str()``) and the markdown
report; typed attributes read from the same data; errors with the tool's message."""

from __future__ import annotations

import shutil
import struct

import pytest

import stochvib
from stochvib import Scenario

QUARTER = "data/quarter-car.toml"
PROFILE = "data/measured-profile.csv"
WORKDAY = "data/workday/scraper-operator.toml"


def test_replay_identical_to_cli(cli):
    want_json = cli.run("replay", QUARTER, PROFILE, "--speed", "15", "--json").stdout
    r = stochvib.replay(QUARTER, PROFILE, speed="54 km/h")  # 54 km/h is exactly 15 m/s
    assert isinstance(r, stochvib.ReplayResult)
    assert r.to_json() == want_json
    assert str(r) == cli.run("replay", QUARTER, PROFILE, "--speed", "15").stdout
    # the attributes are the report's numbers
    d = r.to_dict()
    assert r.speed_m_s == d["replay"]["speed_m_s"] == 15.0
    assert [o.name for o in r.outputs] == [o["name"] for o in d["outputs"]]
    for o, w in zip(r.outputs, d["outputs"]):
        assert (o.sigma, o.analytic_sigma, o.crest_factor) == (w["sigma"], w["analytic_sigma"], w["crest_factor"])
        assert r[o.name] is o and o.ratio == pytest.approx(w["sigma"] / w["analytic_sigma"], rel=0, abs=0)
    assert r.sigma == {o["name"]: o["sigma"] for o in d["outputs"]}
    assert repr(r).splitlines()[1].split()[:4] == ["output", "unit", "mean", "sigma"]
    # a Scenario object gives the same report as its file
    assert stochvib.replay(Scenario.load(QUARTER), PROFILE, speed=15.0).to_json() == want_json


def test_replay_options_and_history_as_the_cli(cli, tmp_path):
    args = ("--speed", "10", "--skip", "20", "--zero-start", "--detrend", "mean")
    cli_csv, py_csv = tmp_path / "cli.csv", tmp_path / "py.csv"
    want = cli.run("replay", QUARTER, PROFILE, *args, "-o", str(cli_csv), "--json").stdout
    r = stochvib.replay(QUARTER, PROFILE, speed=10, skip="2000 cm", zero_start=True, detrend="mean", history=py_csv)
    assert r.to_json() == want
    assert py_csv.read_bytes() == cli_csv.read_bytes()
    # the output rule: an existing history file is kept unless overwrite=True, as the tool's --overwrite
    with pytest.raises(stochvib.FileError, match="overwrite"):
        stochvib.replay(QUARTER, PROFILE, speed=10, history=py_csv)
    stochvib.replay(QUARTER, PROFILE, speed=10, history=py_csv, overwrite=True)


def test_replay_errors(cli):
    with pytest.raises(stochvib.InvalidInputError, match="detrend"):
        stochvib.replay(QUARTER, PROFILE, detrend="quadratic")
    with pytest.raises(stochvib.UnitError, match=r"`speed`.*expected m s\^-1"):
        stochvib.replay(QUARTER, PROFILE, speed="15 kg")
    # a bad speed: the library's message, as the tool prints it, naming the argument instead of the flag
    e = cli.error("replay", QUARTER, PROFILE, "--speed=-1")
    with pytest.raises(stochvib.InvalidInputError) as got:
        stochvib.replay(QUARTER, PROFILE, speed=-1.0)
    assert "`--speed`" in e and str(got.value) == e.replace("`--speed`", "`speed`")
    assert got.value.name == "speed"


def test_workday_identical_to_cli(cli):
    day = stochvib.workday(WORKDAY)
    assert isinstance(day, stochvib.WorkdayResult)
    assert day.to_json() == cli.run("workday", WORKDAY, "--json").stdout
    assert str(day) == cli.run("workday", WORKDAY).stdout
    assert day.to_markdown() == cli.run("workday", WORKDAY, "--format", "markdown").stdout
    d = day.to_dict()
    assert [t.name for t in day.tasks] == [t["task"]["name"] for t in d["tasks"]]
    assert [(a.axis, a.a8, a.vdv) for a in day.axes] == [(a["axis"], a["a8"], a["vdv"]) for a in d["axes"]]
    assert day.a8 == d["verdict"]["a8"] and day.dominant_a8 == d["dominant_a8"]
    # A(8) of the day per axis from its tasks' shares (Directive 2002/44/EC Annex B 1: the root sum of squares)
    for a in day.axes:
        shares = [x.a8 for t in day.tasks for x in t.axes if x.axis == a.axis]
        assert a.a8 == pytest.approx(sum(s * s for s in shares) ** 0.5, rel=1e-12)
    assert f"{len(day.tasks)} tasks" in repr(day)


def test_workday_errors_as_the_cli(cli, tmp_path):
    bad = tmp_path / "day.toml"
    bad.write_text('title = "t"\n[[task]]\nname = "a"\nscenario = "nowhere.toml"\nduration = "2 h"\n')
    want = cli.error("workday", str(bad))
    with pytest.raises(stochvib.StochvibError) as got:
        stochvib.workday(bad)
    assert str(got.value) == want


@pytest.fixture(scope="module")
def run_file(tmp_path_factory):
    path = tmp_path_factory.mktemp("inspect") / "run.h5"
    run = stochvib.simulate("data/conveyor-idler.toml", 20, path, seed=4, shard_size=10, progress=False)
    return path, run


def test_inspect_identical_to_cli(cli, run_file):
    run_file, run = run_file
    info = stochvib.inspect(run_file)
    assert isinstance(info, stochvib.RunInfo)
    assert info.to_json() == cli.run("inspect", str(run_file), "--json").stdout
    assert str(info) == cli.run("inspect", str(run_file)).stdout
    assert info.to_markdown() == cli.run("inspect", str(run_file), "--format", "markdown").stdout
    assert (info.n_realizations, info.seed, info.path) == (20, 4, run_file)
    # the statistics the run reported when it was written
    assert info.statistics == run.statistics and info.sigma == run.sigma
    assert repr(info).splitlines()[1].split()[:2] == ["output", "sigma"]


def test_inspect_refuses_damaged_and_unfinished_files_as_the_cli(cli, run_file, tmp_path):
    run_file, _ = run_file
    sigma = stochvib.inspect(run_file).sigma["y"]
    data = bytearray(run_file.read_bytes())
    at = data.find(struct.pack("<d", sigma))
    assert at >= 0
    data[at] ^= 0x10
    damaged = tmp_path / "damaged.h5"
    damaged.write_bytes(bytes(data))
    want = cli.error("inspect", str(damaged))
    with pytest.raises(stochvib.FileError, match="checksum mismatch") as got:
        stochvib.inspect(damaged)
    assert str(got.value) == want
    tmp = tmp_path / "run.h5.tmp"
    shutil.copy(run_file, tmp)
    with pytest.raises(stochvib.FileError, match="unfinished run"):
        stochvib.inspect(tmp)
    with pytest.raises(stochvib.FileError, match="no such file"):
        stochvib.inspect(tmp_path / "none.h5")
