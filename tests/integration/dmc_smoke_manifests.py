#!/usr/bin/env python3
"""Runs every manifest in manifests/smoke/ (the DMC systems of spec 10 at the reduced sizes of
spec 60) with anisodyn-run and checks that each ends in a readable DMC trajectory: frames with
finite positions, unit quaternions and increasing Brownian time, acceptances in [0, 1], and the
summary's realised balance within 5% of 1 when balancing was on (a sanity bound: the smoke runs'
short preliminary stages and brief equilibration leave ~1% noise and drift; the 0.5% acceptance
check is the full-size run in docs/validation.md)."""
import glob
import json
import os
import subprocess
import sys
import time

import h5py
import numpy as np

bin_dir, tmp, source = sys.argv[1], sys.argv[2], sys.argv[3]
failures = 0
for manifest in sorted(glob.glob(os.path.join(source, "manifests", "smoke", "*.json"))):
    study = json.load(open(manifest))["study"]
    t0 = time.time()
    r = subprocess.run([sys.executable, os.path.join(source, "workflows", "anisodyn-run"), "--bin", bin_dir,
                        "--results", tmp, "--from", "config", "--jobs", "1", "--quiet", manifest], capture_output=True, text=True)
    if r.returncode != 0:
        print(f"FAIL {study}: exit {r.returncode}\n{r.stderr[-2000:]}")
        failures += 1
        continue
    path = os.path.join(tmp, study, "dmc", "dmc-r0.h5")
    with h5py.File(path) as f:
        pos = f["particles/all/position/value"][...]
        q = f["particles/all/orientation/value"][...]
        t = f["particles/all/position/time"][...]
        acc = f["observables/acceptance/value"][...] if "acceptance" in f["observables"] else f["anisodyn/observables/acceptance/value"][...]
        problems = []
        if pos.shape[0] < 2: problems.append("fewer than 2 frames")
        if not np.all(np.isfinite(pos)): problems.append("non-finite positions")
        if not np.allclose(np.linalg.norm(q, axis=2), 1.0, atol=1e-9): problems.append("quaternions not normalised")
        if not np.all(np.diff(t) > 0): problems.append("frame times do not increase")
        if not (np.all(acc >= 0) and np.all(acc <= 1)): problems.append("acceptance outside [0, 1]")
    summary = json.load(open(os.path.join(tmp, study, "dmc", "dmc-r0.log")))
    if summary.get("balance_mode") == "equilibrium" and len(summary["species"]) > 1:
        for sp in summary["species"]:
            if abs(sp["realised_balance"] - 1) > 0.05:
                problems.append(f"realised balance of {sp['name']} is {sp['realised_balance']:.4f}")
    if problems:
        print(f"FAIL {study}: {'; '.join(problems)}")
        failures += 1
    else:
        print(f"ok   {study}: {time.time() - t0:.1f} s, {pos.shape[0]} frames of {pos.shape[1]} particles, t = {t[-1]:.4g}, "
              f"acceptance {np.round(acc.mean(axis=0), 3).tolist()}")
print(f"{'0 failed' if failures == 0 else f'{failures} failed'}")
assert failures == 0, f"{failures} smoke manifest(s) failed (see above)"
