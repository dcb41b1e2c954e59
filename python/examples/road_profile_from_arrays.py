# %% [markdown]
# # A two-track road profile as arrays: density, ISO 8608 class, IRI and coherence
#
# A class C road with two wheel tracks 1.5 m apart is synthesised here with numpy (the spectral
# representation: complex Gaussian Fourier coefficients with E|C_k|² = 2 G_d(n_k) Δn, the right track
# correlated with the left by the isotropic-surface coherence ρ(n) = x K₁(x), x = 2π n B, Dodds & Robson
# 1973). `stochvib.road.analyze_profile` then does what `stochvib road PROFILE.csv` does for a file: Welch
# density with χ² intervals, the ISO 8608 fits and class, the IRI, the squared coherence. Each number is
# checked against what the synthesis put in. Run as a script or cell by cell (`# %%` cells).

# %%
import math

import numpy as np
from scipy import special

import stochvib

step, N, B = 0.05, 2**16, 1.5  # m, samples (3.3 km), track width m
n = np.fft.rfftfreq(N, d=step)  # cycles/m
lo, hi = stochvib.ISO_BAND
G_d = np.where((n >= lo) & (n <= hi), 256e-6 * (np.maximum(n, lo) / 0.1) ** -2.0, 0.0)  # class C, w = 2, m³
x = 2 * math.pi * n * B
rho = np.where(x > 0, x * special.k1(np.maximum(x, 1e-300)), 1.0)  # amplitude coherence of the two tracks

rng = np.random.default_rng(8608)
cn = lambda: (rng.normal(size=n.size) + 1j * rng.normal(size=n.size)) / math.sqrt(2)  # noqa: E731, CN(0, 1)
c_left, c_indep = cn(), cn()
c_right = rho * c_left + np.sqrt(1 - rho**2) * c_indep
amp = np.sqrt(2 * G_d / (N * step)) * N / 2  # numpy's irfft divides by N and doubles the interior bins
left, right = np.fft.irfft(amp * c_left, N), np.fft.irfft(amp * c_right, N)
sigma_in = math.sqrt(np.sum(G_d) / (N * step))
print(f"sigma of the synthesised track: {left.std():.5f} m (spectrum {sigma_in:.5f} m)")

# %% [markdown]
# The analysis (one call, both tracks):

# %%
r = stochvib.road.analyze_profile({"left": left, "right": right}, step)
print(repr(r))
fixed, free = r["left"].fits
print(f"G_d(n0) = {fixed.g0_m3:.4e} m^3 [{fixed.g0_interval[0]:.4e}, {fixed.g0_interval[1]:.4e}], class {fixed.road_class}")
print(f"free w = {free.waviness:.3f} [{free.waviness_interval[0]:.3f}, {free.waviness_interval[1]:.3f}]")
assert fixed.road_class == "C" and free.road_class == "C"
assert abs(fixed.g0_m3 / 256e-6 - 1) < 0.1  # K = 8+ segments over ~100 bins: a few % scatter
assert abs(free.waviness - 2.0) < 0.1

# the density against what went in, over the fitted band (the window's leakage matters only near n = 0)
t = r["left"]
band = (t.n > 0.05) & (t.n < 2.0)
G_true = 256e-6 * (t.n[band] / 0.1) ** -2.0
inside = np.mean((t.lower[band] <= G_true) & (G_true <= t.upper[band]))
print(f"95 % intervals holding the true density: {inside:.0%} of {band.sum()} bins")
assert inside > 0.85

# %% [markdown]
# The IRI of each track against the expectation for the class C spectrum (the golden car's mean absolute
# relative velocity over 80 km/h: a 3.3 km track averages it to a few %).

# %%
e = stochvib.road.expected_iri(stochvib.Spectrum.iso8608("C"))
print(f"IRI left {r['left'].iri_m_per_km:.3f}, right {r['right'].iri_m_per_km:.3f}, expected {e.m_per_km:.3f} m/km")
assert all(abs(tr.iri_m_per_km / e.m_per_km - 1) < 0.15 for tr in r.tracks)

# %% [markdown]
# The squared coherence of the two tracks against ρ(n)² of the model (the estimate is biased upward by about
# (1 − γ²)²/K_e where the coherence is small, so the check is on the interval).

# %%
c = r.coherence
x_c = 2 * math.pi * c.n * B
model = (x_c * special.k1(x_c)) ** 2
sel = (c.n > 0.02) & (c.n < 1.0)
held = np.mean((c.lower[sel] <= model[sel]) & (model[sel] <= c.upper[sel]))
print(f"coherence intervals holding the model: {held:.0%} of {sel.sum()} bins")
assert held > 0.85
