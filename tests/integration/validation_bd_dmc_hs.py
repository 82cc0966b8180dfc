#!/usr/bin/env python3
"""Slow validation: two engines, one physics. Brownian dynamics of pseudo-hard spheres, taken to
the hard-sphere limit, against Dynamic Monte Carlo of hard spheres: the DMC time mapping must give
the Brownian time (issue 15's cross-engine check).

Runs manifests/validation/bd_dmc_hs.json with anisodyn-run on one worker: N = 250 spheres
(d = 1, D0 = 1/(3 pi)) at packing fraction eta, each of the replicas a lattice melted by its own
NVT MC run; from the same states, DMC (dt_MC = 1e-4 tau) and BD with the Mie(n, n-1) core cut at
its minimum, beta epsilon = 1, sigma such that the Barker-Henderson diameter is 1 (so that the
soft spheres are hard spheres of diameter 1 to first order), at the (n, dt) pairs of the grid,
5 tau each, frames every 0.25 tau.

For each replica, with numpy (workflows/summarise_dmc_msd.py, independent of the engines):
D(t) = MSD(t)/6t at t = 1, 2, 4 tau and the slope D_L = d MSD / 6 dt over [2, 5] tau.

The hard limit of BD: at n = 50 the time-step error is linear in dt, fitted over the grid's steps
(weighted by the standard errors) and extrapolated to dt = 0; the softness error is linear in 1/n
(Barker-Henderson is exact to first order in the softness), from n = 50 (extrapolated) and n = 100
(at its smallest step, corrected by the n = 50 time-step slope scaled by (100/50)^2, since the
force gradient at contact grows as n^2): D_hard = 2 D(100) - D(50). Errors are propagated from the
standard errors over replicas (the variants' noises are independent).

Checks (k = 4): for each t and D_L, |D_BD,hard - D_DMC| < k SE; the SE of the difference must be
below 0.75% of D (so that 4 SE resolve the 3% of the acceptance); the relative difference is
printed. The raw (n, dt) values are printed too.
"""
import sys

import h5py
import numpy as np

sys.path[:0] = [sys.argv[3] + "/tests/support", sys.argv[3] + "/workflows"]
from summarise_dmc_msd import fit_d, msd_by_lag, unwrapped  # noqa: E402
from validation_runs import Run, mean_se  # noqa: E402

K = 4.0
TIMES = (1.0, 2.0, 4.0)
SLOPE_WINDOW = (2.0, 5.0)
MAX_RELATIVE_SE = 0.0075
run = Run(sys.argv, "manifests/validation/bd_dmc_hs.json")
grid = run.spec["grid"]
variants = list(zip(grid["exponent"], grid["dt"]))
LABELS = [f"D({t:g})" for t in TIMES] + [f"D_L[{SLOPE_WINDOW[0]:g},{SLOPE_WINDOW[1]:g}]"]


def measures(path):
    """D(t) at TIMES and the long-time slope of one trajectory."""
    with h5py.File(path) as f:
        t, r = unwrapped(f, None)
    tl, msd = msd_by_lag(t, r)
    m = msd.mean(axis=1)
    row = [m[int(np.argmin(np.abs(tl - tf)))] / (6.0 * tl[int(np.argmin(np.abs(tl - tf)))]) for tf in TIMES]
    row.append(fit_d(tl, m, *SLOPE_WINDOW))
    return np.array(row)


def stats(rows):
    """Mean and SE over replicas of every measure: arrays [measure]."""
    a = np.array(rows)
    return a.mean(axis=0), a.std(axis=0, ddof=1) / np.sqrt(len(a))


def weighted_line(x, y, se):
    """Intercept and slope of a weighted least-squares line, with their standard errors."""
    w = 1.0 / np.asarray(se) ** 2
    A = np.vstack([np.ones_like(x), x]).T
    cov = np.linalg.inv(A.T @ (A * w[:, None]))
    coef = cov @ (A.T @ (w * np.asarray(y)))
    return coef, np.sqrt(np.diag(cov))


failures = 0
for eta in grid["eta"]:
    dmc = stats([measures(p) for p in run.outputs("dmc", eta=eta)])
    bd = {}
    for n, dt in variants:
        bd[n, dt] = stats([measures(p) for p in run.outputs("bd", eta=eta, exponent=n, dt=dt)])
    print(f"\neta = {eta}: D0 = {1 / (3 * np.pi):.5f}")
    print("| engine | " + " | ".join(LABELS) + " |")
    print(f"| DMC dt_MC 1e-4 | " + " | ".join(f"{m:.5f} ± {s:.5f}" for m, s in zip(*dmc)) + " |")
    for (n, dt), (m, s) in bd.items():
        print(f"| BD n={n} dt={dt:g} | " + " | ".join(f"{a:.5f} ± {b:.5f}" for a, b in zip(m, s)) + " |")
    steps50 = sorted(dt for n, dt in variants if n == 50)
    dt100 = min(dt for n, dt in variants if n == 100)
    for j, label in enumerate(LABELS):
        (d50, slope), (d50_se, slope_se) = weighted_line(np.array(steps50), [bd[50, dt][0][j] for dt in steps50],
                                                         [bd[50, dt][1][j] for dt in steps50])
        scale = (100 / 50) ** 2
        d100 = bd[100, dt100][0][j] - slope * scale * dt100
        d100_se = np.hypot(bd[100, dt100][1][j], slope_se * scale * dt100)
        hard, hard_se = 2 * d100 - d50, np.hypot(2 * d100_se, d50_se)
        diff, diff_se = hard - dmc[0][j], np.hypot(hard_se, dmc[1][j])
        print(f"  {label}: BD n=50 dt->0 {d50:.5f} ± {d50_se:.5f} (slope {slope:.4g}/tau ± {slope_se:.2g}), "
              f"n=100 dt->0 {d100:.5f} ± {d100_se:.5f}, hard limit {hard:.5f} ± {hard_se:.5f} "
              f"(D/D0 {hard * 3 * np.pi:.4f}); DMC {dmc[0][j]:.5f} ± {dmc[1][j]:.5f} (D/D0 {dmc[0][j] * 3 * np.pi:.4f}); "
              f"difference {diff / dmc[0][j]:+.2%} ({diff / diff_se:+.2f} SE)")
        run.check(f"eta={eta} {label}: BD hard limit - DMC", diff, 0.0, diff_se, K, MAX_RELATIVE_SE * dmc[0][j])
assert not run.failed_checks(), "validation checks failed (listed above)"
