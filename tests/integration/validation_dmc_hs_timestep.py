#!/usr/bin/env python3
"""Slow validation: DMC of hard spheres at eta = 0.30 does not depend on the MC time step (for
dt_MC <= 1e-3; the offset at 1e-2 is measured and printed).

Runs manifests/validation/dmc_hs_eta0.30.json with anisodyn-run on one worker: N = 250 spheres,
16 replicas (each melted by its own MC run), DMC for 9 tau at dt_MC = 1e-4, 1e-3 and 1e-2 tau,
frames every 0.25 tau. For each replica, with numpy (workflows/summarise_dmc_msd.py, independent
of the engine): the MSD of the unwrapped positions over all time origins, and the apparent
diffusion coefficient D(t) = MSD(t)/6t at t = 1 tau (inside the cage-escape regime) and 4 tau
(MSD ~ 1.3 sigma^2, close to the long-time limit).

Checks, with k = 4 and standard errors over the 16 independent replicas:
- for the time steps in ASSERTED and each t, the mean paired difference D_a(t) - D_b(t) (same
  replica, i.e. the same starting configuration) is within k SE of 0; the pairs with dt = 1e-2
  are printed the same way but not asserted (see ASSERTED);
- the SE of each D(t) is below the bound 1.5 D(t) / sqrt(n), n = replicas x particles x
  floor(9 tau / t) non-overlapping displacement windows: for independent windows,
  var(r^2)/<r^2>^2 = 2/3 + 5 alpha_2/3 <= 1 while the non-Gaussian parameter alpha_2 <= 0.2, and
  averaging over all origins only lowers it; the factor 1.5 allows for correlated neighbours. The
  SE of a difference must be below the two bounds added in quadrature.
"""
import sys

import h5py
import numpy as np

sys.path[:0] = [sys.argv[3] + "/tests/support", sys.argv[3] + "/workflows"]
from summarise_dmc_msd import msd_by_lag, unwrapped  # noqa: E402
from validation_runs import Run, mean_se  # noqa: E402

K = 4.0
TIMES = (1.0, 4.0)
# The time steps whose agreement is asserted. dt = 1e-2 (acceptance 0.82) is run and reported but
# not asserted: its D is 2.4% (1 tau) and 4.1% (4 tau) lower than at 1e-4, 4.8 and 4.4 SE. The
# time mapping assumes accepted moves are as long as trial moves on average; at large steps the
# long ones are rejected more often. docs/validation.md states the measured offsets.
ASSERTED = (1e-4, 1e-3)
run = Run(sys.argv, "manifests/validation/dmc_hs_eta0.30.json")

steps = run.spec["grid"]["dt"]
t_run = run.spec["stages"][2]["params"]["time"]
d_app = {}      # dt -> array [replica, time]
acceptance = {}
particles = replicas = None
for dt in steps:
    rows, acc = [], []
    for path in run.outputs("dmc", dt=dt):
        with h5py.File(path) as f:
            t, r = unwrapped(f, None)
        tl, msd = msd_by_lag(t, r)
        m = msd.mean(axis=1)
        row = []
        for t_fix in TIMES:
            k = int(np.argmin(np.abs(tl - t_fix)))  # frames are 0.25 tau apart: the lag nearest t_fix
            row.append(m[k] / (6.0 * tl[k]))
        rows.append(row)
        acc.append(run.summary(path)["species"][0]["acceptance"])
        particles = r.shape[1]
    d_app[dt] = np.array(rows)
    acceptance[dt] = float(np.mean(acc))
    replicas = len(rows)

print(f"N = {particles}, {replicas} replicas, {t_run} tau per run, k = {K}")
print("| dt_MC | acceptance | " + " | ".join(f"D({t:g} tau)" for t in TIMES) + " |")
stats, bound = {}, {}
for dt in steps:
    for j, t_fix in enumerate(TIMES):
        stats[dt, j] = mean_se(d_app[dt][:, j])
        bound[dt, j] = 1.5 * stats[dt, j][0] / np.sqrt(replicas * particles * int(t_run // t_fix))
    print(f"| {dt:g} | {acceptance[dt]:.4f} | " + " | ".join(f"{stats[dt, j][0]:.5f} ± {stats[dt, j][1]:.5f}" for j in range(len(TIMES))) + " |")
for dt in steps:
    for j, t_fix in enumerate(TIMES):
        run.check_se(f"dt={dt:g}: D({t_fix:g})", stats[dt, j][1], bound[dt, j])
for a in range(len(steps)):
    for b in range(a + 1, len(steps)):
        da, db = steps[a], steps[b]
        asserted = da in ASSERTED and db in ASSERTED
        for j, t_fix in enumerate(TIMES):
            diff, se = mean_se(d_app[da][:, j] - d_app[db][:, j])
            label = f"D({t_fix:g}) at dt={da:g} minus dt={db:g} (relative {diff / stats[db, j][0]:+.2%}), paired over replicas"
            if asserted:
                run.check(label, diff, 0.0, se, K, float(np.hypot(bound[da, j], bound[db, j])))
            else:
                run.report(label + ", reported, not asserted", diff, 0.0, se)
assert not run.failed_checks(), "validation checks failed (listed above)"
