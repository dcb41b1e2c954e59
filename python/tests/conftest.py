"""Shared fixtures: the repository root (scenario files, the spectrum catalogue) and the command-line tool, whose
``--json`` output is the Rust library's answer for the same inputs."""

from __future__ import annotations

import json
import os
import shutil
import subprocess
from pathlib import Path
from typing import Any, List

import pytest

ROOT = Path(__file__).resolve().parents[2]


@pytest.fixture(scope="session")
def root() -> Path:
    return ROOT


def _find_cli() -> Path:
    """STOCHVIB_CLI, else the binary of this checkout brought up to date by `cargo test --workspace --no-run` (a
    no-op after scripts/test.sh's `cargo test --workspace`, which built it in its profile and with its features;
    `cargo build --bin stochvib` would compile the library once more with other features; a stale binary would
    compare the package with an older library), else a built binary."""
    env = os.environ.get("STOCHVIB_CLI")
    if env:
        return Path(env)
    cargo = shutil.which("cargo")
    if cargo is not None:
        subprocess.run([cargo, "test", "--quiet", "--locked", "--workspace", "--no-run"], cwd=ROOT, check=True)
        return ROOT / "target" / "debug" / "stochvib"
    for profile in ("debug", "release"):
        p = ROOT / "target" / profile / "stochvib"
        if p.is_file():
            return p
    pytest.skip("no stochvib binary and no cargo to build one (set STOCHVIB_CLI)")


class Cli:
    """Runs the command-line tool from the repository root."""

    def __init__(self, exe: Path) -> None:
        self.exe = exe

    def run(self, *args: str, check: bool = True) -> subprocess.CompletedProcess:
        env = dict(os.environ)
        env.pop("STOCHVIB_SPECTRA", None)
        r = subprocess.run([str(self.exe), *args], cwd=ROOT, capture_output=True, text=True, env=env)
        if check and r.returncode != 0:
            raise AssertionError(f"stochvib {' '.join(args)} failed: {r.stderr}")
        return r

    def json(self, *args: str) -> Any:
        return json.loads(self.run(*args, "--json").stdout)

    def error(self, *args: str) -> str:
        """The message the tool prints after ``error: `` (it must fail)."""
        r = self.run(*args, check=False)
        assert r.returncode != 0, f"stochvib {' '.join(args)} unexpectedly succeeded"
        lines: List[str] = [l for l in r.stderr.splitlines() if l.startswith("error: ")]
        assert lines, r.stderr
        return lines[-1][len("error: ") :]


@pytest.fixture(scope="session")
def cli() -> Cli:
    return Cli(_find_cli())


@pytest.fixture(autouse=True)
def _in_root(monkeypatch: pytest.MonkeyPatch) -> None:
    """Every test runs in the repository root, as the command-line tool does (./spectra, data/...)."""
    monkeypatch.chdir(ROOT)
    monkeypatch.delenv("STOCHVIB_SPECTRA", raising=False)
