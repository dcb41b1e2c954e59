"""ISO 2631-1 weighted r.m.s. a_w of the operator seat over a stiffness x damping sweep with scipy: per point
the state space of white noise -> cab floor -> seat acceleration (scipy.signal.tf2ss) in series with the four
sections of W_k, and scipy.linalg.solve_continuous_lyapunov (the "scipy Lyapunov loop"). Same model, input and grid
as benches/weighting.rs (100 x 100 points). Prints a_w at the catalogue point and the time per point.

    python3 benches/compare/weighting.py [--reps 3]     (also run by benches/compare/run.sh)
"""
import sys, time
import numpy as np
from scipy.linalg import solve_continuous_lyapunov
from scipy.signal import tf2ss

TAU = 2 * np.pi
M_PR = 5.0 / 7.0 * 80.0 + 26.0  # kg, Sukharev (2012) 7.6

# cab-floor input of data/operator-seat-verdicts.toml: S(w) = N / D(w^2), two-sided, m^2 s/rad
N = 9.978705857784458
D = [124596039.48735943, -448861.0914846832, 404.2589962686201, 1.0]  # ascending powers of x = w^2
# spectral factor: D(-s^2) = A(s) A(-s), A Hurwitz
d_s = np.zeros(2 * len(D) - 1)
for k, c in enumerate(D):
    d_s[2 * k] = c * (-1) ** k  # x = -s^2
roots = np.roots(d_s[::-1])
A_IN = np.real(np.poly(roots[roots.real < 0]))  # descending powers, leading 1


def wk_sections():
    """W_k (ISO 2631-1 Annex A) as four low-order sections (numerator, denominator; descending powers of s).
    The upward step (1 + s/(q5 w5) + s^2/w5^2)/(1 + s/(q6 w6) + s^2/w6^2) (w5/w6)^2 is the monic ratio below."""
    f1, f2, f3, f4, q4, f5, q5, f6, q6 = 0.4, 100.0, 12.5, 12.5, 0.63, 2.37, 0.91, 3.35, 0.91
    q1 = q2 = 1 / np.sqrt(2)
    w1, w2, w3, w4, w5, w6 = (TAU * f for f in (f1, f2, f3, f4, f5, f6))
    return [
        ([1.0, 0.0, 0.0], [1.0, w1 / q1, w1 * w1]),  # high pass
        ([w2 * w2], [1.0, w2 / q2, w2 * w2]),  # low pass
        ([w4 * w4 / w3, w4 * w4], [1.0, w4 / q4, w4 * w4]),  # acceleration-velocity transition
        ([1.0, w5 / q5, w5 * w5], [1.0, w6 / q6, w6 * w6]),  # upward step
    ]


def series(s1, s2):
    """State space of s2 after s1 (SISO): x = [x1; x2]."""
    a1, b1, c1, d1 = s1
    a2, b2, c2, d2 = s2
    n1, n2 = a1.shape[0], a2.shape[0]
    a = np.zeros((n1 + n2, n1 + n2))
    a[:n1, :n1] = a1
    a[n1:, :n1] = b2 @ c1
    a[n1:, n1:] = a2
    b = np.vstack([b1, b2 @ d1])
    c = np.hstack([d2 @ c1, c2])
    return a, b, c, d2 @ d1


WK_BLOCKS = [tf2ss(n, d) for n, d in wk_sections()]


def a_w(k, b):
    # white noise -> cab floor -> seat acceleration: sqrt(N) s^2 (b s + k) / (A(s) (m s^2 + b s + k))
    num = np.polymul([b, k, 0.0, 0.0], [np.sqrt(N)])
    den = np.polymul([M_PR, b, k], A_IN)
    sys_ = tf2ss(num, den)
    for blk in WK_BLOCKS:
        sys_ = series(sys_, blk)
    a, bb, c, d = sys_
    p = solve_continuous_lyapunov(a, -bb @ bb.T)
    return np.sqrt(TAU * (c @ p @ c.T)[0, 0])


def main():
    reps = int(sys.argv[sys.argv.index("--reps") + 1]) if "--reps" in sys.argv else 3
    print("a_w at k = 6500 N/m, b = 2*4.22*m_pr N s/m:", a_w(6500.0, 2 * 4.22 * M_PR))
    ks = 3000.0 + 100.0 * np.arange(100)
    bs = 200.0 + 20.0 * np.arange(100)
    best = np.inf
    for _ in range(reps):
        t = time.perf_counter()
        acc = sum(a_w(k, b) for k in ks for b in bs)
        best = min(best, time.perf_counter() - t)
    print(f"scipy per point: {best / (len(ks) * len(bs)) * 1e6:.1f} us (best of {reps}; sum {acc:.6f})")


if __name__ == "__main__":
    main()
