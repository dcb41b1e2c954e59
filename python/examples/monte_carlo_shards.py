# %% [markdown]
# # A Monte Carlo run in shards, merged, and its records against the analytic density
#
# `simulate(..., shard=(I, K))` runs part I of K of a seeded run (on K machines or processes, as
# `stochvib simulate --shard I --of K`); `merge` joins the parts into the run made in one piece: realization i
# uses the random stream (seed, i) wherever it runs. The stored records (`store_raw=True`, HDF5 read with
# h5py) are then checked against the analytic output density: Welch's estimate averaged over the realizations
# against G_y(f) = 4π S_y(2πf) of `Scenario.output_density`.

# %%
import pathlib
import tempfile

import h5py
import numpy as np

import stochvib

sc = stochvib.Scenario.load("data/conveyor-idler.toml")  # the idler's deflection y under a random lump load
work = pathlib.Path(tempfile.mkdtemp())
opts = dict(dt=0.01, duration=60.0, seed=11, shard_size=10, store_raw=True, progress=False)
for i in range(2):
    sc.simulate(40, work / "parts", shard=(i, 2), **opts)
merged = stochvib.merge(work / "run.h5", work / "parts", copy=True)
whole = sc.simulate(40, work / "whole.h5", **opts)
print(repr(merged))
print(f"sigma_y merged {merged.sigma['y']:.6e} m, in one piece {whole.sigma['y']:.6e} m")
assert merged.sigma == whole.sigma  # bit-identical

# %% [markdown]
# The records: Welch's one-sided density of each realization, averaged, against the analytic G_y(f).

# %%
with h5py.File(work / "run.h5", "r") as f:
    y = f["outputs/y"][()]  # one row per realization
fs = 1.0 / opts["dt"]
est = [stochvib.welch(row, fs, nperseg=1024) for row in y]
freq = est[0].f
G = np.mean([e.Pxx for e in est], axis=0)
G_exact = sc.output_density("y", f=freq)
band = (freq > 0.5) & (freq < 15.0)
ratio = G[band] / G_exact[band]
print(f"{len(est)} realizations: median Welch / analytic over 0.5-15 Hz = {np.median(ratio):.3f}")
assert abs(np.median(ratio) - 1.0) < 0.1
