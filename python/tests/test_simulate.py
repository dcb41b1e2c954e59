"""stochvib.simulate: runs identical to the command-line tool (numbers and file contents, read with h5py),
progress, KeyboardInterrupt (from a callback and from a real SIGINT) leaving a resumable .tmp, the GIL
released while a run computes."""

from __future__ import annotations

import os
import signal
import subprocess
import sys
import threading
import time

import h5py
import numpy as np
import pytest

import stochvib
from stochvib import FileError, Scenario, Spectrum, System

# No tolerance constants: every comparison here is exact (same seed, same streams, same arithmetic).

SCENARIO = "data/conveyor-idler.toml"  # exact route: exponential (rational) load, one input
OPTS = dict(dt=0.01, duration=5.0, seed=3, shard_size=5)
N = 20  # realizations: 4 shards of 5


def datasets(path):
    """Every dataset of a run file as numpy arrays, by name."""
    out = {}
    with h5py.File(path, "r") as f:
        f.visititems(lambda name, obj: out.__setitem__(name, obj[()]) if isinstance(obj, h5py.Dataset) else None)
    return out


def without_path(d):
    d = dict(d)
    d.pop("path")
    return d


@pytest.fixture(scope="module")
def reference(tmp_path_factory, cli):
    """The CLI's run of the scenario (the Rust library's answer) and its JSON summary."""
    d = tmp_path_factory.mktemp("cli")
    path = d / "cli.h5"
    summary = cli.json(
        "simulate", SCENARIO, "--realizations", str(N), "--dt", "0.01", "--duration", "5", "--seed", "3",
        "--shard-size", "5", "-o", str(path),
    )
    return path, summary


def test_run_identical_to_cli_and_readable_by_h5py(reference, tmp_path):
    cli_path, cli_summary = reference
    path = tmp_path / "py.h5"
    r = stochvib.simulate(SCENARIO, N, path, progress=False, **OPTS)
    assert r.path == path and path.is_file() and not (tmp_path / "py.h5.tmp").exists()
    assert without_path(r.to_dict()) == without_path(cli_summary)
    assert r.step == "given"
    with h5py.File(path, "r") as f:
        assert f.attrs["seed"] == 3 and f.attrs["n_realizations"] == N and f.attrs["complete"] == 1
        assert "conveyor-idler" in f.attrs["scenario"]
        sigma = f["statistics/y/sigma"]
        assert sigma[()] == r.statistics["y"]["sigma"]["estimate"]
        assert sigma.attrs["lower"] == r.statistics["y"]["sigma"]["lower"]
    a, b = datasets(path), datasets(cli_path)
    assert a.keys() == b.keys()
    for k in a:
        np.testing.assert_array_equal(a[k], b[k], err_msg=k)
    # the statistics view: σ estimate, interval, analytic σ
    s = r.statistics["y"]["sigma"]
    assert s["lower"] <= s["estimate"] <= s["upper"] and s["analytic"] > 0 and s["unit"] == "m"
    assert r.sigma["y"] == s["estimate"]
    assert "covers" in str(r)


def test_progress_callable_and_existing_file(tmp_path, reference):
    calls = []
    path = tmp_path / "p.h5"
    stochvib.simulate(SCENARIO, N, path, progress=lambda d, t: calls.append((d, t)), **OPTS)
    assert calls == [(0, 4), (1, 4), (2, 4), (3, 4), (4, 4)]
    with pytest.raises(FileError, match="exists"):
        stochvib.simulate(SCENARIO, N, path, progress=False, **OPTS)
    r = stochvib.simulate(SCENARIO, N, path, progress=False, overwrite=True, **OPTS)
    assert without_path(r.to_dict()) == without_path(reference[1])


def test_text_progress_bar(tmp_path, capsys, monkeypatch):
    monkeypatch.setitem(sys.modules, "tqdm.auto", None)  # no tqdm: the built-in text bar
    stochvib.simulate(SCENARIO, N, tmp_path / "bar.h5", progress=True, **OPTS)
    err = capsys.readouterr().err
    assert "\rshards [" in err and "4/4 (100 %)" in err and err.endswith("\n")


def test_keyboard_interrupt_from_callback_leaves_a_resumable_tmp(tmp_path, reference):
    path = tmp_path / "int.h5"
    tmp = tmp_path / "int.h5.tmp"

    def stop_after_two(done, total):
        if done == 2:
            raise KeyboardInterrupt

    with pytest.raises(KeyboardInterrupt):
        stochvib.simulate(SCENARIO, N, path, progress=stop_after_two, **OPTS)
    assert not path.exists() and tmp.is_file()
    assert sorted(p.name for p in tmp_path.iterdir()) == ["int.h5.tmp"]
    # the same call resumes: two shards read back, two computed, statistics bit-identical to the CLI's run
    r = stochvib.simulate(SCENARIO, N, path, progress=False, **OPTS)
    assert r.resumed_shards == 2 and path.is_file() and not tmp.exists()
    assert without_path(r.to_dict()) | {"resumed_shards": 0} == without_path(reference[1])


def test_interrupted_run_resumed_by_another_process(tmp_path, reference, cli):
    # The interpreter lives on after the KeyboardInterrupt: the run must not stay claimed by it (the library
    # refuses a .tmp whose recorded writer is a live process), so the CLI resumes it, bit-identically.
    path = tmp_path / "other.h5"

    def stop_after_one(done, total):
        if done == 1:
            raise KeyboardInterrupt

    with pytest.raises(KeyboardInterrupt):
        stochvib.simulate(SCENARIO, N, path, progress=stop_after_one, **OPTS)
    assert sorted(p.name for p in tmp_path.iterdir()) == ["other.h5.tmp"]
    summary = cli.json(
        "simulate", SCENARIO, "--realizations", str(N), "--dt", "0.01", "--duration", "5", "--seed", "3",
        "--shard-size", "5", "-o", str(path),
    )
    assert summary["resumed_shards"] == 1
    a, b = datasets(path), datasets(reference[0])
    assert a.keys() == b.keys()
    for k in a:
        np.testing.assert_array_equal(a[k], b[k], err_msg=k)


def test_other_exceptions_from_the_callback_stop_the_run(tmp_path):
    def boom(done, total):
        if done == 1:
            raise ValueError("from the callback")

    with pytest.raises(ValueError, match="from the callback"):
        stochvib.simulate(SCENARIO, N, tmp_path / "e.h5", progress=boom, **OPTS)
    assert (tmp_path / "e.h5.tmp").is_file()


@pytest.mark.skipif(threading.current_thread() is not threading.main_thread(), reason="signals need the main thread")
def test_sigint_while_computing_stops_the_run(tmp_path):
    # A real SIGINT delivered by another thread while the library computes a shard without the GIL. The
    # progress callable is a builtin (list.append), which runs no bytecode, so no Python-level signal handler
    # can run inside it: the stop comes from Python::check_signals after the shard.
    path = tmp_path / "sig.h5"
    calls = {}  # done → total, recorded by dict.__setitem__ (a slot wrapper: no bytecode)

    def send_sigint_after_first_shard():
        while len(calls) < 2:  # (0, total) at the start, then (1, total)
            threading.Event().wait(0.001)
        os.kill(os.getpid(), signal.SIGINT)

    n, shard = 400, 5  # 80 shards of 5 × 4000 samples (about 0.5 s in all): the signal arrives long before the end
    # Python's own SIGINT handler, as in a terminal: a shell starts a background job with SIGINT ignored, and
    # then Python installs no handler (the test would be killed or the signal lost instead of testing stochvib)
    previous = signal.signal(signal.SIGINT, signal.default_int_handler)
    try:
        th = threading.Thread(target=send_sigint_after_first_shard)
        th.start()
        with pytest.raises(KeyboardInterrupt):
            stochvib.simulate(SCENARIO, n, path, progress=calls.__setitem__, dt=0.01, duration=40.0, seed=3, shard_size=shard)
        th.join()
    finally:
        signal.signal(signal.SIGINT, previous)
    assert not path.exists() and (tmp_path / "sig.h5.tmp").is_file()
    r = stochvib.simulate(SCENARIO, n, path, progress=False, dt=0.01, duration=40.0, seed=3, shard_size=shard)
    assert 1 <= r.resumed_shards < n // shard


CHILD = """
import signal
import sys
import stochvib

# Python's own SIGINT handler, as in a terminal, even when this test runs as a background job (started with
# SIGINT ignored, which the child inherits and for which Python would install no handler)
signal.signal(signal.SIGINT, signal.default_int_handler)

def progress(done, total):
    print(done, flush=True)

stochvib.simulate(sys.argv[1], 40, sys.argv[2], progress=progress, dt=0.01, duration=1000.0, seed=5, shard_size=5)
print("finished", flush=True)
"""
CHILD_OPTS = dict(dt=0.01, duration=1000.0, seed=5, shard_size=5)  # 8 shards of 5 × 10⁵ samples


def test_ctrl_c_of_a_python_process_then_resume_bit_identical(tmp_path):
    # Ctrl-C as a user gives it: SIGINT to a Python process whose main thread is inside simulate() (the GIL
    # released, the library computing a shard). The process stops after that shard with KeyboardInterrupt
    # (uncaught, so Python ends itself by SIGINT), leaving only the resumable .tmp; resuming it gives files
    # and statistics bit-identical to a run never interrupted.
    path = tmp_path / "child.h5"
    child = subprocess.Popen(
        [sys.executable, "-c", CHILD, SCENARIO, str(path)],
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
    )
    lines = []
    for line in child.stdout:
        lines.append(line.strip())
        if line.strip() == "1":  # one shard written, the second computing
            child.send_signal(signal.SIGINT)
            break
    out, err = child.communicate(timeout=120)
    lines += out.split()
    assert child.returncode == -signal.SIGINT, (child.returncode, err)
    assert "KeyboardInterrupt" in err and "finished" not in lines
    assert sorted(p.name for p in tmp_path.iterdir()) == ["child.h5.tmp"]
    done = max(int(x) for x in lines)
    assert 1 <= done < 8
    r = stochvib.simulate(SCENARIO, 40, path, progress=False, **CHILD_OPTS)
    # the shard computing when the signal came is finished and kept (the check follows every shard), unless
    # the signal caught the child still returning from its progress call
    assert done <= r.resumed_shards <= done + 1
    whole = stochvib.simulate(SCENARIO, 40, tmp_path / "whole.h5", progress=False, **CHILD_OPTS)
    assert without_path(r.to_dict()) | {"resumed_shards": 0} == without_path(whole.to_dict())
    a, b = datasets(path), datasets(whole.path)
    assert a.keys() == b.keys()
    for k in a:
        np.testing.assert_array_equal(a[k], b[k], err_msg=k)


def test_gil_released_while_a_run_computes(tmp_path):
    # While a worker thread is inside the library computing a shard (~0.4 s here), this thread keeps running
    # Python code. Measured as the fraction of each shard's wall time this thread's loop ran, from its speed
    # alone: with the GIL held during the shard it could run only around the progress callbacks (about one
    # switch interval per shard, set to 0.5 ms here: a fraction ≈ 0.002); released, it runs whenever it gets
    # a core (it shares the two cores with the library's two threads: 0.19–0.22 measured on an idle machine).
    count = [0]

    def spin(seconds):
        end = time.perf_counter() + seconds
        n = 0
        while time.perf_counter() < end:
            n += 1
        return n / seconds

    rate = spin(0.2)  # iterations per second of the loop below, alone
    marks = []
    done = threading.Event()

    def record(d, t):
        marks.append((time.perf_counter(), count[0]))

    def work():
        try:
            stochvib.simulate(
                SCENARIO, 200, tmp_path / "gil.h5", progress=record, dt=0.002, duration=200.0, seed=1, shard_size=50
            )
        finally:
            done.set()

    interval = sys.getswitchinterval()
    sys.setswitchinterval(0.0005)
    try:
        th = threading.Thread(target=work)
        th.start()
        while not done.is_set():
            time.perf_counter()
            count[0] += 1
        th.join()
    finally:
        sys.setswitchinterval(interval)
    assert len(marks) == 5
    fractions = [(c1 - c0) / rate / (t1 - t0) for (t0, c0), (t1, c1) in zip(marks, marks[1:])]
    assert min(fractions) > 0.05, fractions


def test_simulate_a_system_built_in_python(tmp_path):
    sys_ = System.mdof(mass=[[20.0]], damping=[[60.0]], stiffness=[[8000.0]], outputs={"x": ("displacement", [1])})
    load = Spectrum.exponential(4.0, 5.0, unit="N")
    r = stochvib.simulate(sys_, 10, tmp_path / "s.h5", input=load, dt=0.005, duration=4.0, progress=False)
    assert r.route == "exact"
    with h5py.File(r.path, "r") as f:
        assert "Scenario.from_system" in f.attrs["scenario"]
        assert list(f["statistics"]) == ["x"]
    # the suggested step when none is given
    r2 = stochvib.simulate(sys_, 4, tmp_path / "s2.h5", input=load, progress=False)
    assert r2.step.startswith("suggested")
    with pytest.raises(stochvib.InvalidInputError, match="realizations"):
        stochvib.simulate(sys_, 1, tmp_path / "s3.h5", input=load, dt=0.005, duration=4.0, progress=False)
    with pytest.raises(stochvib.InvalidInputError, match="compression"):
        stochvib.simulate(sys_, 4, tmp_path / "s4.h5", input=load, compression="zip", progress=False)


def test_analyze_with_monte_carlo_column(cli):
    want = cli.json("analyze", SCENARIO, "--monte-carlo", "20", "--seed", "2", "--dt", "0.01", "--duration", "5")
    got = Scenario.load(SCENARIO).analyze(monte_carlo=20, seed=2, dt=0.01, duration=5.0, progress=False)
    assert got.to_dict() == want
    assert got["y"].monte_carlo["realizations"] == 20
