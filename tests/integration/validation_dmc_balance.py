#!/usr/bin/env python3
"""Slow validation: the two-species DMC balance (spec 10 section 4.4) is realised in production.

Runs manifests/validation/dmc_balance_W1_spheres.json with anisodyn-run on one worker: 300 boards
12x1x1 + 30 spheres d = 0.1 at eta = 0.15, spheres as reference (dt_s = 1e-2), equilibrium
balancing (preliminary iterations of 1e4 cycles), 1e4 production cycles, 12 replicas, each prepared
independently (its own random lattice, compression and NVT). Each replica's realised balance
r = A_c dt_c / (A_s dt_s) over production (from its summary) differs from 1 by the sampling noise
of its own last preliminary estimate and of its production acceptances, so the mean over the
independent replicas must be 1 within k = 4 standard errors (SE over replicas).

SE bound: 0.5%/k, so that k SE stays within the 0.5% balance the validation asks for: a 0.5%
imbalance cannot pass unnoticed. For comparison the script prints the SE that each replica's own
acceptance series predict: var(ln r) = sum over species of (SE_prod^2 + SE_pre^2)/A^2, SE_prod from
block averaging of the production acceptance (rows of 100 cycles), SE_pre the same scaled to the
length of the preliminary iteration. Trial outcomes are correlated (a board in contact stays in
contact), so this is several times the binomial SE.
"""
import math
import sys

import h5py

sys.path[:0] = [sys.argv[3] + "/tests/support", sys.argv[3] + "/workflows"]
from summarise_mc import describe  # noqa: E402
from validation_runs import Run, mean_se  # noqa: E402

K = 4.0
SE_BOUND = 0.005 / K
run = Run(sys.argv, "manifests/validation/dmc_balance_W1_spheres.json")
counts = {c["species"]: c["count"] for c in run.spec["stages"][0]["params"]["composition"]}

balance, var_pred = [], []
print(f"{sum(counts.values())} particles ({counts}), k = {K}")
print("| replica | preliminary iterations | last change | dt_c | A_c | A_s | realised balance |")
for i, path in enumerate(run.outputs("dmc")):
    s = run.summary(path)
    names = [x["name"] for x in s["species"]]
    sp = {x["name"]: x for x in s["species"]}
    last = s["preliminary"][-1]
    with h5py.File(path) as f:
        rows = f["observables/acceptance/value"][...]
    v = 0.0
    for j, name in enumerate(names):
        a, se_prod = describe(rows[:, j].copy())[:2]
        se_pre = se_prod * math.sqrt(s["cycles"] / last["cycles"])  # scaled to the preliminary length
        v += (se_prod ** 2 + se_pre ** 2) / a ** 2
    var_pred.append(v)
    balance.append(sp["board"]["realised_balance"])
    print(f"| {i} | {len(s['preliminary'])} | {last['relative_change']:.2e} | {sp['board']['time_step']:.6f} | "
          f"{sp['board']['acceptance']:.5f} | {sp['hs']['acceptance']:.5f} | {balance[-1]:.5f} |")
m, se = mean_se(balance)
print(f"mean realised balance over {len(balance)} replicas: {m:.5f} ± {se:.5f} ({m - 1:+.3%}); "
      f"SE predicted from the replicas' acceptance series {math.sqrt(sum(var_pred)) / len(var_pred):.5f}")
run.check("realised balance A_c dt_c / (A_s dt_s) against 1", m, 1.0, se, K, SE_BOUND)
assert not run.failed_checks(), "validation checks failed (listed above)"
