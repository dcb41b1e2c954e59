#!/usr/bin/env python3
"""numpy peer of stochvib's route 2 (nonlinear Monte Carlo) on data/quarter-car-bump-stops.toml.

    python3 nonlinear.py --realizations R --samples N --burn B --dt DT [--chunk C] [--reps K] > py.json

The same job as `examples/compare_nonlinear.rs` (which prints the step, the burn-in and the sizes it used; the
run script passes them here): the quarter car (300 kg / 40 kg, 20 kN/m, 200 kN/m) with a bilinear damper
(rebound 2.2, compression 0.8 kN s/m), a two-sided bump stop (+7 cm / -5 cm, 300 kN/m) and a tyre that
leaves the road (static load 3335.4 N) on an ISO 8608 class D road (G_d(n0) = 1024e-6 m^3, band
0.011-2.83 cycles/m) at 15 m/s, R realizations of B + N steps of DT, the first B discarded.

The integrator is stochvib's, written for numpy and vectorised over realizations (state arrays of shape
(4, C), C realizations at a time):

* the linear part (suspension damping = the mean of the damper's two coefficients, the elements' linear
  parts) is stepped by its exact first-order hold between road samples, x <- Phi x + G0 u_k + G1 u_k+1
  (Phi, G0, G1 from one matrix exponential, scipy.linalg.expm);
* around it the exact flows of the element forces over h/2 (Strang splitting): the damper's remainder
  (c_r - c_c)/2 |v| in closed form, the stop's and the tyre's forces as impulses h/2 F(x); the two damper
  half-kicks that meet at a step boundary are fused into one (exact: the flow keeps the sign of v);
* the road by spectral synthesis with Rayleigh amplitudes (one irfft per realization, batched);
* per realization and output (body_acc, travel, tyre_force): mean, variance, kurtosis, max |y|, up-crossing
  rates of the clearances, a 120-bin histogram, the Welch density (Hann, half overlap, one batched FFT; equal
  to scipy.signal.welch to rounding and 20 % cheaper), the fraction of
  time in contact and the contact-entry rate of the stop and of the tyre lift-off.

Timed: synthesis + integration + statistics, best of K repetitions (wall and process CPU time), one process (numpy's element-wise
loops are single-threaded; the 4 x 4 matrix product is too small for BLAS threads to matter).
"""
import argparse
import json
import math
import time

import numpy as np
from numpy.lib.stride_tricks import sliding_window_view
from scipy.linalg import expm
from scipy.signal import get_window

# --- the scenario (data/quarter-car-bump-stops.toml) ----------------------------------------------------
M1, M2 = 300.0, 40.0
KS, KT = 20e3, 200e3
C_REB, C_COMP = 2.2e3, 0.8e3
C_MEAN, C_HALF = 0.5 * (C_REB + C_COMP), 0.5 * (C_REB - C_COMP)
UPPER, LOWER, K_STOP = 0.07, 0.05, 300e3
DELTA = 3335.4 / KT  # static tyre deflection: lift-off beyond it
G0_ROAD, N0, BAND = 1024e-6, 0.1, (0.011, 2.83)
SPEED = 15.0
BINS = 120


def foh(h):
    """Phi, G0, G1 of the first-order hold of the linear part; state [q1, q2, p1, p2], p = M q'."""
    minv = np.diag([1 / M1, 1 / M2])
    k = np.array([[KS, -KS], [-KS, KS + KT]])
    c = np.array([[C_MEAN, -C_MEAN], [-C_MEAN, C_MEAN]])
    a = np.block([[np.zeros((2, 2)), minv], [-k, -c @ minv]])
    b = np.array([[0.0], [0.0], [0.0], [KT]])
    big = np.zeros((6, 6))
    big[:4, :4], big[:4, 4:5], big[4, 5] = a * h, b * h, 1.0
    e = expm(big)
    phi, gam0, gam1 = e[:4, :4], e[:4, 4], e[:4, 5]
    return phi, gam0 - gam1, gam1


def road(rng, r, n, dt):
    """r realizations of n road samples (rows), Rayleigh amplitudes on the grid of the record."""
    f = np.fft.rfftfreq(n, dt)
    nu = f / SPEED
    g = np.where((nu >= BAND[0]) & (nu <= BAND[1]), G0_ROAD * (N0 / np.maximum(nu, BAND[0])) ** 2 / SPEED, 0.0)
    amp = np.sqrt(g / (n * dt)) * (n / 2)  # one-sided G(f) df per line, split over cos and sin
    spec = amp * (rng.standard_normal((r, f.size)) + 1j * rng.standard_normal((r, f.size)))
    return np.fft.irfft(spec, n, axis=1)


def integrate(u, h, burn):
    """The splitting integrator over the road samples u (c x total); returns q1, q2, p1, p2 (4 x n x c)."""
    phi, gam0, gam1 = foh(h)
    c, total = u.shape
    n = total - burn
    ut = np.ascontiguousarray(u.T)
    x = np.zeros((4, c))
    hist = np.empty((4, n, c))  # contiguous (n, c) per state variable for the statistics
    tau = 0.5 * h
    kap = 1 / M1 + 1 / M2
    # damper flow over tau and over 2 tau: J = v (1 - e^{-kappa c_h t sgn v}) / kappa
    def factors(t):
        return (-math.expm1(-kap * C_HALF * t) / kap, -math.expm1(kap * C_HALF * t) / kap)

    half, whole = factors(tau), factors(h)
    kt_tau, ks_tau = KT * tau, K_STOP * tau
    q1, q2, p1, p2 = x[0], x[1], x[2], x[3]
    tmp = np.empty(c)
    v = np.empty(c)
    jd = np.empty(c)

    def damper(f):
        np.multiply(p1, 1 / M1, out=v)
        np.subtract(v, p2 / M2, out=v)
        np.multiply(v, np.where(v > 0, f[0], f[1]), out=jd)
        np.subtract(p1, jd, out=p1)
        np.add(p2, jd, out=p2)

    def stop_tyre(uk):
        # stop: F = k (x - d_up)_+ - k (-d_lo - x)_+ on x = q1 - q2; tyre: F = -k_t (q2 - u - delta)_+
        np.subtract(q1, q2, out=tmp)
        js = np.maximum(tmp - UPPER, 0.0)
        js -= np.maximum(-LOWER - tmp, 0.0)
        js *= ks_tau
        np.subtract(p1, js, out=p1)
        np.add(p2, js, out=p2)
        np.subtract(q2, uk, out=tmp)
        np.subtract(tmp, DELTA, out=tmp)
        np.maximum(tmp, 0.0, out=tmp)
        np.multiply(tmp, kt_tau, out=tmp)
        np.add(p2, tmp, out=p2)

    damper(half)
    stop_tyre(ut[0])
    for k in range(total - 1):
        x[:] = phi @ x + np.outer(gam0, ut[k]) + np.outer(gam1, ut[k + 1])
        stop_tyre(ut[k + 1])
        if k + 1 >= burn:
            damper(half)
            hist[:, k + 1 - burn] = x
            damper(half)
        else:
            damper(whole)
        stop_tyre(ut[k + 1])
    return hist, ut[burn:]


def welch_segment(n):
    """Route 2's Welch segment (its generator version 2): the largest even 2^a 3^b 5^c <= min(1024, n // 8),
    at least 4 (an FFT of small factors only)."""
    m = min(max((n // 8) & ~1, 4), 1024)
    while True:
        r = m
        for p in (2, 3, 5):
            while r % p == 0:
                r //= p
        if r == 1:
            return m
        m -= 2


def welch(y, h, nper):
    """The Welch density of every column of y (n x c): Hann segments of nper with half overlap, the segment
    mean removed, one-sided (as scipy.signal.welch with its defaults, which it equals to rounding), averaged
    over the segments. Written out with one batched real FFT over all segments of all columns: 20 % less CPU
    than scipy.signal.welch(y, axis=0) on this job (scipy moves the axis and detrends segment by segment)."""
    win = get_window("hann", nper)
    seg = sliding_window_view(y, nper, axis=0)[:: nper - nper // 2]  # (segments, c, nper), a view
    seg = seg - seg.mean(axis=-1, keepdims=True)
    seg *= win
    x = np.fft.rfft(seg, axis=-1)
    p = x.real * x.real + x.imag * x.imag
    p *= h / (win * win).sum()
    p[..., 1 : (nper + 1) // 2] *= 2  # one-sided: every line but 0 (and nper/2 for even nper) twice
    return p.mean(axis=0)


def crossings(y, level, t):
    return np.count_nonzero((y[:-1] < level) & (y[1:] >= level), axis=0) / t


def regime(on, t):
    return on.mean(axis=0), np.count_nonzero(~on[:-1] & on[1:], axis=0) / t


def statistics(hist, u, h):
    """Per-realization statistics of the three outputs (each array: one value per realization)."""
    q1, q2, p1, p2 = hist
    n = q1.shape[0]
    t = n * h
    travel = q1 - q2
    v = p1 / M1 - p2 / M2
    stop = K_STOP * (np.maximum(travel - UPPER, 0) - np.maximum(-LOWER - travel, 0))
    body_acc = (-KS * travel - C_MEAN * v - C_HALF * np.abs(v) - stop) / M1
    defl = q2 - u
    tyre = KT * defl  # the linear part of the tyre force, as the output `tyre_force` of the model
    out = {}
    for name, y, levels in (("body_acc", body_acc, []), ("travel", travel, [UPPER, -LOWER]), ("tyre_force", tyre, [])):
        m = y.mean(axis=0)
        d = y - m
        d *= d
        var = d.mean(axis=0)
        d *= d
        kurt = d.mean(axis=0) / var**2
        mx = np.abs(y).max(axis=0)
        rates = [crossings(y, a, t) for a in levels]
        lo, hi = m.mean() - 6 * math.sqrt(var.mean()), m.mean() + 6 * math.sqrt(var.mean())
        hcount = np.histogram(y, bins=BINS, range=(lo, hi))[0]
        psd = welch(y, h, welch_segment(n))
        out[name] = (m, var, kurt, mx, rates, hcount, psd.mean(axis=0))
    out["stop"] = regime((travel > UPPER) | (travel < -LOWER), t)
    out["lift_off"] = regime(defl > DELTA, t)
    return out


def run(r, n, burn, dt, chunk, seed):
    rng = np.random.default_rng(seed)
    sig, contact = [], []
    for start in range(0, r, chunk):
        c = min(chunk, r - start)
        u = road(rng, c, burn + n, dt)
        hist, ur = integrate(u, dt, burn)
        s = statistics(hist, ur, dt)
        sig.extend(np.sqrt(s["travel"][1]))
        contact.extend(s["stop"][0])
    return float(np.mean(sig)), float(np.mean(contact))


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--realizations", type=int, required=True)
    ap.add_argument("--samples", type=int, required=True)
    ap.add_argument("--burn", type=int, required=True)
    ap.add_argument("--dt", type=float, required=True)
    ap.add_argument("--chunk", type=int, default=0, help="realizations at a time (default: all)")
    ap.add_argument("--reps", type=int, default=1)
    ap.add_argument("--seed", type=int, default=1)
    a = ap.parse_args()
    chunk = a.chunk or a.realizations
    best, cpu, checks = float("inf"), float("inf"), None
    for _ in range(a.reps):
        t0, c0 = time.perf_counter(), time.process_time()
        checks = run(a.realizations, a.samples, a.burn, a.dt, chunk, a.seed)
        best = min(best, time.perf_counter() - t0)
        cpu = min(cpu, time.process_time() - c0)
    print(json.dumps({
        "job": "nonlinear quarter car, route 2",
        "realizations": a.realizations, "samples": a.samples, "burn": a.burn, "dt": a.dt, "chunk": chunk,
        "seconds": best, "cpu_seconds": cpu, "ns_per_realization_step": best / (a.realizations * (a.samples + a.burn)) * 1e9,
        "sigma_travel_m": checks[0], "stop_contact_fraction": checks[1],
        "numpy": np.__version__,
    }))


if __name__ == "__main__":
    main()
