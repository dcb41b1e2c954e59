# %% [markdown]
# # A measured road replayed, a working day's exposure, a run file inspected
#
# Three commands of the command-line tool from Python, each with its typed result:
#
# * `stochvib.replay` drives the quarter car of `data/quarter-car.toml` over the measured profile
#   `data/measured-profile.csv` (the wheel follows the track, the model is stepped exactly between samples)
#   and puts beside each replayed σ the analytic σ of the same scenario whose road spectrum is the profile's
#   own Welch density;
# * `stochvib.workday` combines the tasks of an operator's day into the Directive 2002/44/EC A(8) and VDV;
# * `stochvib.inspect` reads back a Monte Carlo run file (after checking its checksums).

# %%
import math
import pathlib
import tempfile

import stochvib

r = stochvib.replay("data/quarter-car.toml", "data/measured-profile.csv", speed="54 km/h")
print(repr(r))
for o in r.outputs:
    # the replay's own statistics agree with each other: rms² = σ² + mean² (σ about the mean)
    assert math.isclose(o.rms**2, o.sigma**2 + o.mean**2, rel_tol=1e-9, abs_tol=1e-300)
    assert o.min <= o.mean <= o.max
    print(f"{o.name}: sigma replayed {o.sigma:.4e} {o.unit}, analytic {o.analytic_sigma:.4e} (ratio {o.ratio:.3f})")

# %% [markdown]
# The working day: per axis A(8) = √(Σ (k a_w)² T / 8 h) over the tasks, and VDV = (Σ VDV_i⁴)^¼ with the
# stationary Gaussian VDV_i = (3 T_i)^¼ k a_w (ISO 2631-1:1997 6.3.2 and Annex B; Directive 2002/44/EC Annex B).

# %%
day = stochvib.workday("data/workday/scraper-operator.toml")
print(repr(day))
for axis in day.axes:
    tasks = [(t.duration_s, a) for t in day.tasks for a in t.axes if a.axis == axis.axis]
    a8 = math.sqrt(sum((a.k * a.a_w) ** 2 * T / (8 * 3600) for T, a in tasks))
    vdv = sum(((3 * T) ** 0.25 * a.k * a.a_w) ** 4 for T, a in tasks) ** 0.25
    assert math.isclose(axis.a8, a8, rel_tol=1e-12) and math.isclose(axis.vdv, vdv, rel_tol=1e-12)
print(f"A(8) = {day.a8:.3f} m/s^2 (axis {day.dominant_a8}), VDV = {day.vdv:.2f} m/s^1.75; sigma of a_w per task above")

# %% [markdown]
# A seeded run written and read back: `inspect` gives the statistics the run reported when it was written.

# %%
path = pathlib.Path(tempfile.mkdtemp()) / "idler.h5"
run = stochvib.simulate("data/conveyor-idler.toml", 40, path, seed=3, progress=False)
info = stochvib.inspect(path)
print(repr(info))
assert (info.seed, info.n_realizations) == (3, 40) and info.sigma == run.sigma
