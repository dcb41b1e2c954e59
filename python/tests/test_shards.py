"""Sharded Monte Carlo runs from Python: the parts of a run (``simulate(..., shard=(I, N))``) merged by
``stochvib.merge`` give the statistics of the same run made in one piece (realization i uses the random
stream (seed, i) whatever the part: an independent computation of the same numbers, so they must agree to
the last bit, as the library promises for any thread or shard count)."""

from __future__ import annotations

import pytest

import stochvib
from stochvib import FileError, InvalidInputError


def test_parts_merged_equal_the_whole_run(tmp_path, root):
    sc = root / "data" / "conveyor-idler.toml"
    whole = stochvib.simulate(sc, 30, tmp_path / "whole.h5", seed=7, shard_size=10, progress=False)
    for i in range(3):
        part = stochvib.simulate(sc, 30, tmp_path / "parts", seed=7, shard_size=10, shard=(i, 3), progress=False)
        assert part.path == tmp_path / "parts" / f"shard-{i}-of-3.h5"
    merged = stochvib.merge(tmp_path / "merged.h5", tmp_path / "parts")
    assert merged.n_realizations == whole.n_realizations == 30
    for out in ("y", "y_vel"):
        for stat in ("mean", "sigma"):
            assert merged.statistics[out][stat]["estimate"] == whole.statistics[out][stat]["estimate"]
            assert merged.statistics[out][stat]["lower"] == whole.statistics[out][stat]["lower"]
    assert merged.sigma == whole.sigma


def test_merge_refuses_a_missing_part_and_a_bad_shard(tmp_path, root):
    sc = root / "data" / "conveyor-idler.toml"
    stochvib.simulate(sc, 20, tmp_path / "parts", shard=(0, 2), shard_size=10, progress=False)
    with pytest.raises(FileError):
        stochvib.merge(tmp_path / "m.h5", [tmp_path / "parts"])
    assert not (tmp_path / "m.h5").exists()
    with pytest.raises(InvalidInputError, match="shard"):
        stochvib.simulate(sc, 20, tmp_path / "parts", shard=(2, 2), shard_size=10, progress=False)
