"""The variance sweep of benches/sweep.rs, written for Python: σ of the sprung-cab scraper's cab acceleration
(Sukharev (2012) 8.7, eq. (8.65)) on the graded dirt road (8.69) at 10 m/s, over a 400 × 250 grid of cab mounts
(c₂, b₂) — the same constants and grid as benches/common/mod.rs and benches/compare/compare.py.

Two ways:

* ``sigma_h2``: the Python-driven stochvib way. numpy forms, for every grid point at once, the polynomials of
  H_ẍ₂(s)·B(s)/A(s) (B/A: the road's shaping filter from ``Spectrum.shaping_filter``), and one call of
  ``stochvib.linalg.h2_integral`` integrates every row with the closed-form table Iₙ:
      k₁ = c₁ + b₁s, k₂ = c₂ + b₂s, Δ = (m₁s² + k₁ + k₂)(m₂s² + k₂) − k₂², H_ẍ₂ = s²k₁k₂/Δ,
      σ² = (1/2π) ∫ |H_ẍ₂(iω) B(iω)/A(iω)|² dω.
* ``sigma_scipy_lyapunov``: a loop of ``scipy.linalg.solve_continuous_lyapunov`` on the augmented state
  z = [x_F, x₁, x₂, v₁, v₂] (road q = x_F, ẋ_F = −a x_F + g w with unit white noise w):
      m₁v̇₁ = −(c₁+c₂)x₁ + c₂x₂ − (b₁+b₂)v₁ + b₂v₂ + c₁q + b₁q̇,   m₂v̇₂ = c₂(x₁ − x₂) + b₂(v₁ − v₂),
      F P + P Fᵀ + G Gᵀ = 0,   σ² = h P hᵀ,   ẍ₂ = h z.
"""

from __future__ import annotations

import math

import numpy as np

M1 = 3.0e4  # front mass, kg
OMEGA1 = 18.5  # tyre natural frequency √(c₁/m₁), rad/s
ZETA1 = 0.1
M2 = 2.0e3  # cab mass, kg
SPEED = 10.0  # m/s
C1 = M1 * OMEGA1 * OMEGA1  # N/m
B1 = 2.0 * ZETA1 * math.sqrt(C1 * M1)  # N s/m
N_C2, N_B2 = 400, 250


def grid():
    """c₂ over [m₂(2π·0.8 Hz)², m₂(2π·2.5 Hz)²] N/m × b₂ over [1, 30] kN s/m, flattened (c₂ major)."""
    w = lambda f: 2.0 * math.pi * f  # noqa: E731
    c2 = np.linspace(M2 * w(0.8) ** 2, M2 * w(2.5) ** 2, N_C2)
    b2 = np.linspace(1.0e3, 3.0e4, N_B2)
    cc, bb = np.meshgrid(c2, b2, indexing="ij")
    return cc.ravel(), bb.ravel()


def road():
    """The temporal road: (8.69) (spatial type 1, D = 32 cm², α = 0.16 1/m) at 10 m/s."""
    import stochvib

    return stochvib.Spectrum.load("book-8-69").at_speed(SPEED)


def _mul(p, q):
    """Row-wise product of polynomials (ascending coefficients): p (k, n), q (k, m) or (m,) → (k, n + m − 1)."""
    q = np.broadcast_to(q, (p.shape[0], q.shape[-1]))
    out = np.zeros((p.shape[0], p.shape[1] + q.shape[1] - 1))
    for i in range(p.shape[1]):
        for j in range(q.shape[1]):
            out[:, i + j] += p[:, i] * q[:, j]
    return out


def polynomials(c2, b2, fnum, fden):
    """Numerator and denominator rows of H_ẍ₂·B/A for every (c₂, b₂)."""
    one = np.ones_like(c2)
    k2 = np.stack([c2, b2], axis=1)
    p1 = np.stack([(C1 + c2), (B1 + b2), M1 * one], axis=1)
    p2 = np.stack([c2, b2, M2 * one], axis=1)
    delta = _mul(p1, p2)
    delta[:, :3] -= _mul(k2, k2)
    n = np.zeros((c2.size, 5))
    n[:, 2:] = _mul(np.stack([C1 * one, B1 * one], axis=1), k2)
    return _mul(n, np.asarray(fnum)), _mul(delta, np.asarray(fden))


def sigma_h2(c2, b2, spectrum):
    """σ of ẍ₂ (m/s²) at every grid point: numpy polynomials, one stochvib.linalg.h2_integral call."""
    import stochvib

    fnum, fden = spectrum.shaping_filter(order="ascending")
    num, den = polynomials(c2, b2, fnum, fden)
    return np.sqrt(stochvib.linalg.h2_integral(num, den, order="ascending") / (2.0 * math.pi))


def sigma_scipy_lyapunov(c2, b2, spectrum):
    """σ of ẍ₂ (m/s²) at every grid point by a loop of scipy.linalg.solve_continuous_lyapunov."""
    from scipy.linalg import solve_continuous_lyapunov

    fnum, fden = spectrum.shaping_filter(order="ascending")
    assert len(fnum) == 1 and len(fden) == 2, "first-order road filter expected"
    pole, gain = fden[0] / fden[1], fnum[0] / fden[1]
    a = np.zeros((5, 5))
    a[0, 0] = -pole
    a[1, 3] = 1.0
    a[2, 4] = 1.0
    a[3, 0] = (C1 - B1 * pole) / M1
    g = np.array([gain, 0.0, 0.0, B1 * gain / M1, 0.0])
    qneg = -np.outer(g, g)
    out = np.empty(c2.size)
    for i, (c, b) in enumerate(zip(c2, b2)):
        a[3, 1] = -(C1 + c) / M1
        a[3, 2] = c / M1
        a[3, 3] = -(B1 + b) / M1
        a[3, 4] = b / M1
        a[4, 1] = c / M2
        a[4, 2] = -c / M2
        a[4, 3] = b / M2
        a[4, 4] = -b / M2
        p = solve_continuous_lyapunov(a, qneg)
        h = np.array([0.0, c / M2, -c / M2, b / M2, -b / M2])
        out[i] = math.sqrt(h @ p @ h)
    return out
