"""Usage: python3 transient_mc.py R. The transient Monte Carlo of the accelerating quarter car (w = 2 road, v: 5 m/s for 1 s, then 1.5 m/s^2
to 20 m/s; 15 s; 1200 steps, every 4th stored) in numpy: the same generator and integrator as stochvib's
(exact transition of the frozen coefficients at each step midpoint, Van Loan; z <- Phi z + L eps; mean and
M2 at the stored times, max y and max |y| per realization), vectorised over the realizations."""
import sys, time, os
for _v in ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ.setdefault(_v, "1")  # one BLAS thread (set before numpy loads): CPU time is then the work's
import numpy as np
from scipy.linalg import expm, cholesky

R = int(sys.argv[1]) if len(sys.argv) > 1 else 1000
ms, mu, ks, cs, kt = 300.0, 40.0, 20e3, 1.5e3, 200e3
A = np.array([[0, 0, 1, 0], [0, 0, 0, 1],
              [-ks / ms, ks / ms, -cs / ms, cs / ms],
              [ks / mu, -(ks + kt) / mu, cs / mu, -cs / mu]])
B = np.array([0, 0, 0, kt / mu])
g = np.linalg.solve(A, B)                      # relative coordinates x~ = x + A^-1 B u, u' white
H = np.array([A[2], [1, -1, 0, 0], [0, kt, 0, 0]])  # body_acc, travel, tyre_force in x~ (u = road)
c = np.pi * 0.01 * 256e-6                      # S_Omega = c / Omega^2
def v(t): return 5.0 if t < 1 else min(20.0, 5.0 + 1.5 * (t - 1))
T, N, k = 15.0, 1200, 4
dt = T / N
n = 4
def van_loan(q):
    M = np.zeros((2 * n, 2 * n)); M[:n, :n] = -A; M[:n, n:] = q; M[n:, n:] = A.T
    E = expm(M * dt)
    phi = E[n:, n:].T
    return phi, phi @ E[:n, n:]
t0 = time.process_time(); w0 = time.time()
tables = []
for j in range(N):
    q = 2 * np.pi * c * v((j + 0.5) * dt) * np.outer(g, g)
    phi, qd = van_loan(q)
    tables.append((phi, cholesky(qd + 1e-300 * np.eye(n), lower=True)))
# stationary start at v(0): P solves A P + P A^T + Q = 0
from scipy.linalg import solve_continuous_lyapunov
P0 = solve_continuous_lyapunov(A, -2 * np.pi * c * v(0) * np.outer(g, g))
rng = np.random.default_rng(1)
z = cholesky(P0, lower=True) @ rng.standard_normal((n, R))
K = N // k + 1
mean = np.zeros((3, K)); m2 = np.zeros((3, K))
y = H @ z; mx = y.copy(); mxa = np.abs(y)
mean[:, 0] = y.mean(1); m2[:, 0] = ((y - mean[:, :1]) ** 2).sum(1)
for j, (phi, L) in enumerate(tables):
    z = phi @ z + L @ rng.standard_normal((n, R))
    y = H @ z
    np.maximum(mx, y, out=mx); np.maximum(mxa, np.abs(y), out=mxa)
    if (j + 1) % k == 0:
        s = (j + 1) // k
        mean[:, s] = y.mean(1); m2[:, s] = ((y - mean[:, s:s + 1]) ** 2).sum(1)
cpu = time.process_time() - t0; wall = time.time() - w0
print(f"R = {R}: {cpu:.3f} s CPU, {wall:.3f} s wall; sigma_end = {np.sqrt(m2[:, -1] / (R - 1))}")
