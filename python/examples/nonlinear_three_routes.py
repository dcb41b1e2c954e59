# %% [markdown]
# # A Duffing oscillator under white noise: the three routes from Python
#
# A hardening spring (k₃ x³) makes the response non-Gaussian. `analyze_nonlinear` of a scenario with
# `[[model.nonlinear]]` (`analyze` refuses it and names this function) gives route 1 (statistical linearisation, Gaussian), route 3 (the exact stationary
# density of the Fokker–Planck equation, where it applies) and with `monte_carlo=N` route 2 (the nonlinear
# equations integrated in time, seeded). Here ε σ₀² = 1: the exact variance is 0.4679 σ₀², route 1 gives
# 0.4343 σ₀² (Caughey 1963; Lin 1967, ch. 10).

# %%
import stochvib

sc = stochvib.Scenario.load("data/duffing-white-noise.toml")
r = sc.analyze_nonlinear(monte_carlo=40, dt=0.01, duration=200.0, seed=1, progress=False)
print(repr(r))
x = r["x"]
sigma0 = 0.01
mc = x.route2()
print(f"sigma_x / sigma_0: route 1 {x.route1() / sigma0:.4f}, exact {x.exact() / sigma0:.4f}, "
      f"route 2 {mc['estimate'] / sigma0:.4f} [{mc['lower'] / sigma0:.4f}, {mc['upper'] / sigma0:.4f}]")
assert abs(x.exact() ** 2 / sigma0**2 - 0.4679199) < 1e-6
assert abs(x.route1() ** 2 / sigma0**2 - 0.4342585) < 1e-6
# the kurtosis of a hardening spring's response is below the Gaussian 3
print(f"kurtosis: exact {x.exact('kurtosis'):.4f}, route 1 {x.route1('kurtosis'):.1f}")
assert x.exact("kurtosis") < 3.0
