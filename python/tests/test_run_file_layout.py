"""A run file decoded by the layout documented in docs/run-file-format.md ("Decoding the accumulators and
checksums"), with h5py, numpy, scipy and zlib only — no stochvib code: the shard checksums, the statistics and
the Welch densities recomputed from the accumulators equal what the file stores.

Provenance: the expected values are the file's own stored statistics (written by the Rust library); this
test recomputes them by the documented formulas, an independent implementation of the reader's side.
"""

from __future__ import annotations

import math
import struct
import zlib

import h5py
import numpy as np
from scipy import stats

# The Student t and χ² quantiles come from scipy here and from statrs in the library: both are accurate to
# a few ulp, so interval bounds (a quantile times a standard error) agree to this relative tolerance.
QUANTILE_REL_TOL = 1e-12

SCENARIO = "data/conveyor-idler.toml"  # exact route, outputs y and y_vel
N, SHARD = 18, 5  # four shards, the last one of 3 realizations (zero-padded accumulator rows)


def _run(cli, tmp_path):
    path = tmp_path / "run.h5"
    cli.run(
        "simulate", SCENARIO, "--realizations", str(N), "--dt", "0.01", "--duration", "5", "--seed", "11",
        "--shard-size", str(SHARD), "--store-raw", "-o", str(path),
    )
    return h5py.File(path, "r")


def _strings(values):
    return [v.decode() if isinstance(v, bytes) else str(v) for v in values]


def _shard_rows(f, b):
    r, size = int(f.attrs["n_realizations"]), int(f.attrs["shard_size"])
    return range(b * size, min((b + 1) * size, r))


def _seq_sum(values):
    """Left to right, as documented (numpy's pairwise sum differs in the last bits)."""
    s = 0.0
    for v in values:
        s += float(v)
    return s


def _mean_interval(values, conf):
    n = len(values)
    m = _seq_sum(values) / n
    s2 = _seq_sum([(v - m) * (v - m) for v in values]) / (n - 1)
    h = stats.t.ppf(0.5 + 0.5 * conf, n - 1) * math.sqrt(s2 / n)
    return m, m - h, m + h


def _close(a, b):
    return abs(a - b) <= QUANTILE_REL_TOL * max(abs(a), abs(b))


def test_shard_checksums_follow_the_documented_layout(cli, tmp_path):
    with _run(cli, tmp_path) as f:
        n_shards = int(f.attrs["n_shards"])
        assert n_shards == math.ceil(N / SHARD) and list(f["shards/complete"][()]) == [1] * n_shards
        sums = f["shards/checksums"][()]
        checked = _strings(f["shards/checksums"].attrs["checked"])
        accumulators = _strings(f["shards"].attrs["accumulators"])
        assert checked == (
            [f"inputs/{n}" for n in _strings(f["inputs"].attrs["names"])]
            + [f"outputs/{n}" for n in _strings(f["outputs"].attrs["names"])]
            + [f"shards/{a}" for a in accumulators]
        )
        for b in range(n_shards):
            rows = _shard_rows(f, b)
            for j, name in enumerate(checked):
                data = f[name][b] if name.startswith("shards/") else f[name][rows.start : rows.stop]
                crc = zlib.crc32(np.ascontiguousarray(data, dtype="<f8").tobytes())
                assert crc == sums[b, j], f"{name}, shard {b}"


def test_statistics_recomputed_from_the_moments_accumulator(cli, tmp_path):
    with _run(cli, tmp_path) as f:
        size, n_shards = int(f.attrs["shard_size"]), int(f.attrs["n_shards"])
        for out in _strings(f["outputs"].attrs["names"]):
            acc = f[f"shards/{out}:moments"][()]
            assert acc.shape == (n_shards, 2 * size)
            m, v = [], []
            for b in range(n_shards):
                k = len(_shard_rows(f, b))
                m.extend(acc[b, :k])
                v.extend(acc[b, size : size + k])
                assert not acc[b, k:size].any() and not acc[b, size + k :].any(), "padding is zero"
            g = f[f"statistics/{out}"]
            assert int(g.attrs["n_used"]) == len(m) == N
            for name, values in (("mean", m), ("variance", v)):
                ds = g[name]
                est, lo, hi = _mean_interval(values, float(ds.attrs["confidence"]))
                assert est == ds[()], f"{out}/{name}: estimate"
                assert _close(lo, ds.attrs["lower"]) and _close(hi, ds.attrs["upper"]), f"{out}/{name}"
            var = g["variance"]
            for name in ("sigma", "sigma_discrete"):
                ds = g[name]
                assert ds[()] == math.sqrt(var[()])
                assert ds.attrs["lower"] == math.sqrt(max(var.attrs["lower"], 0.0))
                assert ds.attrs["upper"] == math.sqrt(var.attrs["upper"])
            # the statistic's own checksum, as documented
            for name in _strings(g.attrs["names"]):
                ds = g[name]
                a = ds.attrs
                blob = struct.pack(
                    "<5d", ds[()], a["lower"], a["upper"], a["confidence"], a.get("analytic", float("nan"))
                )
                blob += bytes([int(a["covers"]) if "covers" in a else 2])
                for text in (name, a["unit"], a["method"]):
                    blob += (text.decode() if isinstance(text, bytes) else str(text)).encode() + b"\0"
                assert zlib.crc32(blob) == a["crc32"], f"{out}/{name}: @crc32"


def test_density_recomputed_from_the_welch_accumulator(cli, tmp_path):
    with _run(cli, tmp_path) as f:
        n_shards, dt = int(f.attrs["n_shards"]), float(f.attrs["dt"])
        for out in _strings(f["outputs"].attrs["names"]):
            g = f[f"psd/{out}"]
            omega, density = g["omega"][()], g["density"][()]
            bins = len(omega)
            acc = f[f"shards/{out}:welch"][()]
            assert acc.shape == (n_shards, bins + 2)
            total, segments, nu = np.zeros(bins), 0.0, 0.0
            for b in range(n_shards):
                total = total + acc[b, :bins]
                segments += acc[b, bins]
                nu += acc[b, bins + 1]
            assert segments == int(segments) and nu == g.attrs["dof"]
            np.testing.assert_array_equal(density, total / segments)
            m = 2 * (bins - 1)
            np.testing.assert_array_equal(omega, np.arange(bins) * (2.0 * math.pi / (m * dt)))
            p = 1.0 - float(g.attrs["confidence"])
            for j in (0, 1, bins // 2, bins - 1):
                dof = nu / 2.0 if j in (0, bins - 1) else nu
                lo = dof * density[j] / stats.chi2.ppf(1.0 - p / 2.0, dof)
                hi = dof * density[j] / stats.chi2.ppf(p / 2.0, dof)
                assert _close(lo, g["lower"][j]) and _close(hi, g["upper"][j]), f"{out}: bin {j}"
