# %% [markdown]
# # The damping of a quarter car that minimises the body acceleration, with a travel limit
#
# `Scenario.optimize` (`stochvib optimize`) searches the scenario's keys between bounds for the least (or
# largest) response quantity under constraints, every point analysed exactly. On a road whose velocity is
# white (ISO 8608, waviness 2, no band) the quarter car has closed forms (Gobbi & Mastinu 2001):
# σ²_acc = πS₀(k_t c² + k_s²M)/(c m_s²) and σ²_travel = πS₀M/c, M = m_s + m_u, S₀ = πn₀²G_d(n₀)v; the least
# σ_acc is at c = k_s√(M/k_t), and 3σ_travel ≤ d needs c ≥ 9πS₀M/d². Run as a script or cell by cell.

# %%
import math
import pathlib
import tempfile

import stochvib

text = """
title = "Quarter car under white road velocity"
[model]
kind = "quarter-car"
sprung_mass = "400 kg"
unsprung_mass = "40 kg"
suspension_stiffness = "20 kN/m"
suspension_damping = "1.5 kN*s/m"
tyre_stiffness = "200 kN/m"
[input]
spectrum = { kind = "iso8608", class = "C", bound = "mean", unbounded = true }
speed = "20 m/s"
[analysis]
outputs = ["body_acc", "travel"]
"""
path = pathlib.Path(tempfile.mkdtemp()) / "quarter-car.toml"
path.write_text(text)
sc = stochvib.Scenario.load(path)
bounds = {"model.suspension_damping": ("0.2 kN*s/m", "6 kN*s/m")}

free = sc.optimize(bounds, minimize="sigma(body_acc)")
print(repr(free))
m_s, M, k_s, k_t = 400.0, 440.0, 20e3, 200e3
S0 = math.pi * 0.1**2 * 256e-6 * 20.0
c_opt = k_s * math.sqrt(M / k_t)
print(f"c* = {free.x['model.suspension_damping']:.3f} N s/m, closed form {c_opt:.3f} N s/m")
assert abs(free.x["model.suspension_damping"] / c_opt - 1) < 1e-6

# %% [markdown]
# With 3σ_travel ≤ 40 mm the optimum moves onto the constraint, c* = 9πS₀M/d²:

# %%
limited = sc.optimize(bounds, minimize="sigma(body_acc)", constraints=["3sigma(travel) <= 40 mm"])
print(repr(limited))
c_min = 9 * math.pi * S0 * M / 0.04**2
print(f"sigma_acc = {limited.value:.6f} m/s^2 at c = {limited.x['model.suspension_damping']:.3f} N s/m "
      f"(closed form {c_min:.3f})")
assert limited.constraints[0].active and abs(limited.x["model.suspension_damping"] / c_min - 1) < 1e-8

# %% [markdown]
# The optimum on the constraint is a KKT point: the analytic gradients (Lyapunov sensitivities) balance with
# a positive multiplier, and dσ_acc/dc has the closed form πS₀(k_t − k_s²M/c²)/(2σ_acc m_s²):

# %%
c = limited.x["model.suspension_damping"]
kkt = limited.kkt
print(repr(kkt))
d_sigma = math.pi * S0 * (k_t - k_s**2 * M / c**2) / (2 * limited.value * m_s**2)
assert kkt.satisfied and kkt.multipliers[0] > 0 and abs(kkt.gradient[0] / d_sigma - 1) < 1e-8

# %% [markdown]
# Comfort against travel: the Pareto front (ε-constraint: σ_acc least with 3σ_travel ≤ ε). Every inner point
# sits on its limit, at c = 9πS₀M/ε²; `plots=` would also draw it (`pareto-front.svg`, `.png`).

# %%
front = sc.pareto(bounds, minimize="sigma(body_acc)", pareto="3sigma(travel)", points=5, starts=2)
print(repr(front))
for p in front.points[1:-1]:
    assert abs(p.params["model.suspension_damping"] / (9 * math.pi * S0 * M / p.limit**2) - 1) < 1e-8
