# %% [markdown]
# # A quarter car accelerating on a rough road: σ(t), the mission extremes and a Monte Carlo check
#
# `Scenario.transient` (`stochvib transient`) gives the non-stationary response of a scenario with a
# `[transient]` section: here a quarter car starts in its stationary state at 5 m/s and accelerates at
# 1.5 m/s² to 20 m/s on an ISO 8608 class C road with white velocity, so σ²_travel = πS₀(v)M/c follows the
# speed with the suspension's lag. A seeded Monte Carlo batch of the same transient checks σ(t).

# %%
import math

import numpy as np

import stochvib

sc = stochvib.Scenario.load("data/quarter-car-accelerating.toml")
r = sc.transient(monte_carlo=40, seed=1, progress=False)
print(repr(r))
travel = r["travel"]
for t in (0.0, 5.0, 10.0, 15.0):
    k = int(np.argmin(abs(r.times - t)))
    print(f"t = {r.times[k]:5.2f} s: sigma travel {1e3 * travel.sigma[k]:.3f} mm")

# %% [markdown]
# At the start the closed form of the stationary state: σ²_travel = πS₀M/c, S₀ = πn₀²G_d(n₀)v at 5 m/s.

# %%
s0 = math.pi * 0.1**2 * 256e-6 * 5.0
closed = math.sqrt(math.pi * s0 * 340.0 / 1500.0)
print(f"sigma travel at t = 0: {travel.sigma[0]:.6e} m, closed form {closed:.6e} m")
assert abs(travel.sigma[0] / closed - 1) < 1e-8

# %% [markdown]
# The Monte Carlo σ(t) of 40 realizations against the exact one, and the probability of exceeding each
# mission level:

# %%
for c in r.sigma_comparison:
    print(f"{c['output']}: the per-time interval covers the exact sigma at {100 * c['coverage']:.0f} % of the times")
for m in r.mission[:3]:
    print(f"{m['output']} above {m['level']} {m['unit']}: P = {m['p_integrated_rate']:.3e}")
