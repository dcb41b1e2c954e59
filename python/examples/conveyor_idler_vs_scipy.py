# %% [markdown]
# # Conveyor idler under a random lump load (Sukharev 2012, 8.6, Example 8.1) — stochvib and scipy
#
# An idler of mass m = 100 kg on a support of stiffness c = 70 kN/m (damping ratio ζ = 0.2) carries the belt's
# lump load F(t): mean M_F = 10 kN, correlation K_F(τ) = σ_F² e^{−α|τ|} with σ_F = 2 kN, α = 0.5 1/s
# (the catalogue spectrum `conveyor-lump-load`). The book asks for the mean deflection, its σ and the design
# value a* = M_y + 3σ_y. stochvib reproduces the catalogue result (`stochvib book`: σ_y = 0.0291 m exact,
# 0.0062 m by the book's white-noise formula (8.62)); scipy computes the same σ two independent ways.
# Run it as a script or cell by cell in a notebook (`# %%` cells).

# %%
import math
from pathlib import Path

import numpy as np
from scipy import integrate, linalg, signal

import stochvib

ROOT = Path(__file__).resolve().parents[2]
scenario = stochvib.Scenario.load(ROOT / "data" / "conveyor-idler.toml")
result = scenario.analyze()
y = result["y"]
print(f"M_y = {y.mean:.6f} m, sigma_y = {y.sigma:.6f} m, a* = M_y + 3 sigma_y = {y.three_sigma[1]:.6f} m")
for m in y.methods:  # Lyapunov, integral table, quadrature (with its error estimate)
    print(f"  {m.method:<15} variance {m.value:.12e}  error estimate {m.error_estimate}  ({m.status})")
print(repr(result))  # the table of every output, as the command line prints it

# %% [markdown]
# The input: two-sided angular density S_F(ω) = αD/(π(α² + ω²)), D = σ_F².

# %%
load = scenario.input
m, c, zeta = 100.0, 70e3, 0.2
b = 2 * zeta * math.sqrt(m * c)
D, alpha = 2e3**2, 0.5
omega = np.linspace(0.0, 200.0, 4001)
assert np.allclose(load.density(omega), alpha * D / (math.pi * (alpha**2 + omega**2)), rtol=1e-13, atol=0)

# %% [markdown]
# scipy, way 1: the frequency response of m ÿ + b ẏ + c y = F from `scipy.signal.freqresp` against
# `System.frequency_response`, then σ_y² = ∫ |H(iω)|² S_F(ω) dω by `scipy.integrate.quad`.

# %%
system = scenario.system
h_stochvib = system.frequency_response(omega)[0, 0]  # output y, input F
_, h_scipy = signal.freqresp(signal.TransferFunction([1.0], [m, b, c]), w=omega)
assert np.allclose(h_stochvib, h_scipy, rtol=1e-12, atol=0)
# the same system built as scipy builds it: coefficients in descending powers of s
tf = stochvib.System.transfer_function([1.0], [m, b, c], output="y", unit="m")
assert np.allclose(tf.frequency_response(omega)[0, 0], h_scipy, rtol=1e-12, atol=0)
# and from the matrices, by name (no B/C confusion with state_space)
sdof = stochvib.System.mdof(mass=[[m]], damping=[[b]], stiffness=[[c]])
assert np.allclose(sdof.frequency_response(omega)[0, 0], h_scipy, rtol=1e-12, atol=0)


def s_y(w):
    return abs(1.0 / complex(c - m * w * w, b * w)) ** 2 * alpha * D / (math.pi * (alpha**2 + w * w))


var_quad = 2 * integrate.quad(s_y, 0, np.inf, points=None, limit=500, epsabs=0, epsrel=1e-12)[0]

# %% [markdown]
# scipy, way 2: the stationary covariance of the state [F_f, y, ẏ] (shaping filter F_f' = −αF_f + √(2αD) w
# with unit white noise w) by `scipy.linalg.solve_continuous_lyapunov`: A P + P Aᵀ + G Gᵀ = 0.

# %%
A = np.array([[-alpha, 0, 0], [0, 0, 1], [1 / m, -c / m, -b / m]])
G = np.array([[math.sqrt(2 * alpha * D)], [0], [0]])
P = linalg.solve_continuous_lyapunov(A, -G @ G.T)
var_lyap = P[1, 1]

print(f"sigma_y: stochvib {y.sigma:.10f}, scipy quad {math.sqrt(var_quad):.10f}, scipy Lyapunov {math.sqrt(var_lyap):.10f}")
assert abs(y.variance / var_lyap - 1) < 1e-10 and abs(y.variance / var_quad - 1) < 1e-8

# %% [markdown]
# The book's white-noise approximation (8.62), σ_y² = π S_F(ω₀)/(2βω₀³)·(1/m²) with β = ζ, ω₀ = √(c/m),
# is poor here: the load's spectrum is far from flat around ω₀ (α ≪ 2ζω₀), and the exact σ is 4.7 times larger.

# %%
w0 = math.sqrt(c / m)
sigma_white = math.sqrt(math.pi * load.density(w0) / (2 * zeta * w0**3)) / m
print(f"white-noise approximation (8.62): sigma_y = {sigma_white:.6f} m (exact {y.sigma:.6f} m)")
assert abs(sigma_white - 0.00620919) < 1e-8  # `stochvib book`, Example 8.1, row "sigma_y by (8.62)"
assert abs(y.sigma - 0.0291235) < 1e-7  # `stochvib book`, Example 8.1, row "sigma_y exact"
