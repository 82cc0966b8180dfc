#!/usr/bin/env python3
"""Runs manifests/quickstart.json and every manifests/*-smoke.json with anisodyn-run and checks each: exit 0, a report (summary.md, at least one PNG when the manifest asks for plots),
and every scalar of every analysis output finite and physically sane: diffusion coefficients and
response times > 0; a pulled tracer's friction ratio gamma_eff/gamma_0 >= 1 - 4 SE (a bath cannot
speed the tracer up); uniaxial order parameters U in [0, 1]; fractions (X_c, p_b) in [0, 1]. Every engine trajectory (H5MD) must have finite positions, unit quaternions,
strictly increasing frame times and acceptances in [0, 1]; a DMC run that balanced several species
at equilibrium must report a realised balance within 5% of 1 (a sanity bound for short smoke runs;
the 0.5% acceptance check is the slow test validation_dmc_balance, docs/validation.md). Prints
each manifest's wall time.

When tests/golden/<manifest>.json exists, every dataset the run wrote must equal the recorded one
bit for bit (tests/support/golden_outputs.py; skipped, saying so, on a machine whose compiler or
instruction set differs from the recording's).

argv: [1] build bin dir, [2] scratch dir, [3] source dir, [4] optional: the one manifest to run
(name with or without .json; ctest registers one test per manifest, study_manifests.cmake),
[5] optional: runner workers (default 2)."""
import glob
import json
import math
import os
import re
import shutil
import subprocess
import sys
import time

import h5py
import numpy as np

sys.path.insert(0, os.path.join(sys.argv[3], "tests", "support"))
import golden_outputs  # noqa: E402

bin_dir, tmp, source = sys.argv[1], sys.argv[2], sys.argv[3]
only = sys.argv[4] if len(sys.argv) > 4 else None
workers = int(sys.argv[5]) if len(sys.argv) > 5 else 2
shutil.rmtree(tmp, ignore_errors=True)
os.makedirs(tmp)
runner = [sys.executable, os.path.join(source, "workflows", "anisodyn-run"), "--bin", bin_dir, "--jobs", str(workers), "--quiet",
          "--results", tmp]
manifests = [os.path.join(source, "manifests", "quickstart.json")] + sorted(glob.glob(os.path.join(source, "manifests", "*-smoke.json")))
if only:
    manifests = [m for m in manifests if os.path.basename(m) == only or os.path.basename(m) == only + ".json"]
    assert manifests, f"no manifest {only}"

RULES = [  # (scalar name pattern, lower, upper, what)
    (r"^D_", 0.0, math.inf, "a diffusion coefficient > 0"),
    (r"^(t_on|t_off)", 0.0, math.inf, "a response time > 0"),
    (r"^U_(L|W|T)?_?", 0.0, 1.0, "a uniaxial order parameter in [0, 1]"),
    (r"^(X_c|p_b)", 0.0, 1.0, "a fraction in [0, 1]"),
]


def trajectory_problems(f, name):
    out = []
    for group in f["particles"].values():
        pos, t = group["position/value"][...], group["position/time"][...]
        if not np.all(np.isfinite(pos)):
            out.append(f"{name}: non-finite positions")
        if len(t) > 1 and not np.all(np.diff(t) > 0):
            out.append(f"{name}: frame times do not increase")
        if "orientation" in group:
            q = group["orientation/value"][...]
            if not np.allclose(np.linalg.norm(q, axis=-1), 1.0, atol=1e-9):
                out.append(f"{name}: quaternions not normalised")
    obs = f["observables"] if "observables" in f else None
    if obs is not None and "acceptance" in obs:
        acc = obs["acceptance/value"][...]
        if not (np.all(acc >= 0) and np.all(acc <= 1)):
            out.append(f"{name}: acceptance outside [0, 1]")
    return out


def balance_problems(log, name):
    try:
        summary = json.load(open(log))
    except (OSError, ValueError):
        return []
    if summary.get("balance_mode") != "equilibrium" or len(summary.get("species", [])) < 2:
        return []
    out = []
    for sp in summary["species"]:
        balance = sp.get("realised_balance")
        if balance is None or not math.isfinite(balance):
            out.append(f"{name}: no realised balance for {sp['name']}")
        elif abs(balance - 1) > 0.05:
            out.append(f"{name}: realised balance of {sp['name']} is {balance:.4f}")
    return out


def friction_problem(name, value, error, where):
    """gamma_eff/gamma_0 of a pulled tracer: a bath slows it, so the ratio is at least 1 - 4 SE, with a finite SE."""
    if not name.startswith("gamma_eff_over_gamma0"):
        return []
    if not math.isfinite(error) or error <= 0:
        return [f"{where}: {name} = {value:.4g} has no standard error"]
    if value < 1 - 4 * error:
        return [f"{where}: {name} = {value:.4g} ± {error:.2g} is more than 4 SE below 1"]
    return []


failures = 0
for path in manifests:
    m = json.load(open(path))
    study = m["study"]
    t0 = time.time()
    r = subprocess.run(runner + [path], capture_output=True, text=True)
    wall = time.time() - t0
    problems = []
    if r.returncode != 0:
        problems.append(f"exit {r.returncode}: {r.stderr[-1500:]}")
    campaign = os.path.join(tmp, study)
    if not problems and m.get("report"):
        report = os.path.join(campaign, "report")
        if not os.path.exists(os.path.join(report, "summary.md")):
            problems.append("no report/summary.md")
        if m["report"].get("plots") and not glob.glob(os.path.join(report, "*.png")):
            problems.append("no plot in the report")
    checked, notes = 0, []
    for h5 in glob.glob(os.path.join(campaign, "**", "*.h5"), recursive=True):
        with h5py.File(h5, "r") as f:
            if "particles" in f:
                problems += trajectory_problems(f, os.path.relpath(h5, campaign))
                log = h5[:-3] + ".log"
                if "/dmc/" in h5 and os.path.exists(log):
                    problems += balance_problems(log, os.path.relpath(h5, campaign))
            if "scalars" not in f:
                continue
            for name, ds in f["scalars"].items():
                value = float(ds[0])
                error = float(ds[1]) if ds.shape[0] > 1 else float("nan")
                checked += 1
                if not math.isfinite(value):
                    definition = ds.attrs.get("definition", "")
                    definition = definition.decode() if isinstance(definition, bytes) else str(definition)
                    if "NaN:" in definition:  # a documented outcome, e.g. a wake that never recovers in a smoke run
                        notes.append(f"{name} = NaN ({definition[definition.index('NaN:'):].split(')')[0]})")
                    else:
                        problems.append(f"{os.path.relpath(h5, campaign)}: {name} = {value} is not finite")
                    continue
                problems += friction_problem(name, value, error, os.path.relpath(h5, campaign))
                for pattern, lo, hi, what in RULES:
                    if re.match(pattern, name) and not (lo <= value <= hi):
                        problems.append(f"{os.path.relpath(h5, campaign)}: {name} = {value:.4g} is not {what}")
    golden = os.path.join(source, "tests", "golden", os.path.basename(path)[:-5] + ".json")
    if not problems and os.path.exists(golden):
        differences, note = golden_outputs.compare(tmp, golden)
        print(f"     {note}")
        problems += [f"not as recorded in {os.path.relpath(golden, source)}: {d}" for d in differences]
    status = "ok  " if not problems else "FAIL"
    if notes:
        print(f"     note: {len(notes)} scalar(s) NaN with a documented meaning: {sorted(set(notes))}")
    print(f"{status} {os.path.basename(path)}: {wall:.1f} s on {workers} worker{'s' if workers > 1 else ''}, {checked} scalars checked" + ("" if not problems else "\n    " + "\n    ".join(problems[:10])))
    failures += bool(problems)
print(f"{failures} failed")
assert failures == 0, f"{failures} manifest(s) failed (see above)"
