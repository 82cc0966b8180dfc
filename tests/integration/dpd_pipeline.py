#!/usr/bin/env python3
"""anisodyn-config (placement uniform) -> anisodyn-dpd end to end on the Groot-Warren liquid of
spec 30 §2 (rho = 3, a = 25, gamma = 4.5, dt = 0.005), 1536 particles in a box of 8:

1. an uninterrupted run: the summary, the frames (with velocities), the observables; the kinetic
   temperature 1 within 1% (its standard error, from 20 blocks of rows, below 0.3%, so that the
   1% is resolved); the total momentum conserved to round-off; the pressure and its four parts
   printed (the conservative part checked against an independent numpy sum on the last frame);
2. on a run of 1200 steps: two threads give the same bits as one; SIGINT (exit 130) then resumed,
   and SIGKILL after a periodic checkpoint then resumed: both bit for bit the uninterrupted output
   (the Green-Kubo record's rows included), with the same summary; `--replica 1` gives other starting velocities and another trajectory;
3. Groot-Warren's lambda = 0.65 keeps T_kin at 1 at dt = 0.04, where lambda = 1/2 heats the liquid;
4. bad input exits 2, names the file and the JSON path, and writes nothing.
"""
import json
import os
import subprocess
import sys
import time

import h5py
import numpy as np

bin_dir, tmp, source = sys.argv[1], sys.argv[2], sys.argv[3]
sys.path.insert(0, os.path.join(source, "tests", "support"))
from resume_checks import check_resumes, compare_outputs  # noqa: E402
from script_io import enter_scratch, write  # noqa: E402

enter_scratch(tmp)


def run(cmd):
    return subprocess.run(cmd, capture_output=True, text=True)


def tool(name):
    return os.path.join(bin_dir, name)


EDGE, N, STEPS, EVERY = 8.0, 1536, 10000, 100
liquid = {"seed": 1, "species": [{"name": "liquid", "shape": {"type": "sphere", "diameter": 1.0}}],
          "composition": [{"species": "liquid", "count": N}], "box": {"edges": [EDGE] * 3}, "placement": "uniform"}
dpd = {"seed": 4, "time_step": 0.005, "steps": STEPS, "observe_every": EVERY, "frames": {"every_steps": 2500},
       "liquid": {"a": 25, "gamma": 4.5}}
r = run([tool("anisodyn-config"), "-q", "--config", write("liquid.json", liquid), "--output", "start.h5"])
assert r.returncode == 0, r.stderr
write("dpd.json", dpd)


# The short run also records the Green-Kubo stress autocorrelation, so that its rows are checked
# across threads and restarts too.
write("short.json", {**dpd, "steps": 1200, "frames": {"every_steps": 400}, "green_kubo": {"blocks": 4, "max_lag": 1.0}})


def dpd_cmd(out, config="dpd.json", extra=()):
    return [tool("anisodyn-dpd"), "-q", "--config", config, "--input", "start.h5", "--output", out, "--checkpoint-every", "300", *extra]


t0 = time.time()
r = run(dpd_cmd("long.h5"))
assert r.returncode == 0, r.stderr
duration = time.time() - t0
summary = json.loads(r.stdout)
assert summary["steps"] == STEPS and summary["particles"] == N and summary["start_velocities"] == "maxwell_boltzmann", summary


def block_mean(x, blocks=20):
    b = np.array_split(x, blocks)
    m = np.array([v.mean() for v in b])
    return x.mean(), m.std(ddof=1) / np.sqrt(blocks)


with h5py.File("long.h5") as f:
    assert f["particles/all/position/step"][...].tolist() == list(range(0, STEPS + 1, 2500))
    assert f["particles/all/velocity/value"].shape == (5, N, 3)
    o = f["observables"]
    skip = 1000 // EVERY  # the first 5 tau relax the ideal-gas start
    T, T_se = block_mean(o["kinetic_temperature/value"][skip:])
    p, p_se = block_mean(o["pressure/value"][skip:])
    parts = {k: o[f"pressure_tensor_{k}/value"][skip:, :3].mean() for k in ("kinetic", "conservative", "dissipative", "random")}
    momentum = np.abs(o["momentum/value"][...]).max()
    last = f["particles/all/position/value"][-1]
    last_conservative = o["pressure_tensor_conservative/value"][-1, :3].mean()
print(f"uninterrupted: {duration:.1f} s, {N * STEPS / duration:.3g} particle-steps/s; T_kin = {T:.4f} ± {T_se:.4f}; "
      f"p = {p:.3f} ± {p_se:.3f} (Groot-Warren rho + 0.101 a rho^2 = {3 + 0.101 * 25 * 9:.2f}); parts "
      + ", ".join(f"{k} {v:.4f}" for k, v in parts.items()) + f"; largest |total momentum| {momentum:.2e}")
assert abs(T - 1.0) < 0.01 and T_se < 0.003, (T, T_se)
assert momentum < 1e-9, momentum  # Maxwell-Boltzmann start with zero momentum; pairwise forces keep it

# The conservative virial of the last frame, summed here over all pairs (r_ij . F^C_ij / 3V).
virial = 0.0
for i in range(N - 1):
    d = last[i] - last[i + 1:]
    d -= EDGE * np.round(d / EDGE)
    r_ = np.sqrt((d * d).sum(axis=1))
    near = r_ < 1.0
    virial += (25.0 * (1.0 - r_[near]) * r_[near]).sum()
# The engine's last row averages its 100 steps; the frame is the last of them: agree within the
# row's fluctuation (a few per mille), not to round-off.
assert abs(virial / (3 * EDGE ** 3) - last_conservative) < 0.01 * last_conservative, (virial / (3 * EDGE ** 3), last_conservative)
print(f"conservative pressure of the last frame: numpy {virial / (3 * EDGE ** 3):.4f}, the engine's last row {last_conservative:.4f}")

# Groot-Warren's lambda at their large time step (dt = 0.04, 100 tau each): the half-step scheme
# (lambda = 1/2) heats the liquid by a few per cent; lambda = 0.65 brings T_kin back to 1
# (Groot & Warren 1997). Measured 1.023 +- 0.002 and 1.001 +- 0.002.
lam_T = {}
for lam in (0.5, 0.65):
    r = run([tool("anisodyn-dpd"), "-q", "--config", write(f"lambda{lam}.json", {**dpd, "time_step": 0.04, "steps": 2500, "observe_every": 25,
                                                                                "velocity_lambda": lam}),
             "--input", "start.h5", "--output", f"lambda{lam}.h5"])
    assert r.returncode == 0, r.stderr
    assert json.loads(r.stdout)["velocity_lambda"] == lam
    with h5py.File(f"lambda{lam}.h5") as f:
        lam_T[lam] = block_mean(f["observables/kinetic_temperature/value"][10:])
(T_half, se_half), (T_gw, se_gw) = lam_T[0.5], lam_T[0.65]
print(f"dt = 0.04: T_kin = {T_half:.4f} +- {se_half:.4f} (lambda 1/2), {T_gw:.4f} +- {se_gw:.4f} (lambda 0.65)")
assert abs(T_gw - 1.0) < 4 * se_gw + 0.005, (T_gw, se_gw)
assert T_half - T_gw > 4 * np.hypot(se_half, se_gw), lam_T

# Threads and restarts on a shorter run (1200 steps, checkpoints every 300).
t0 = time.time()
r = run(dpd_cmd("straight.h5", "short.json"))
assert r.returncode == 0, r.stderr
duration, summary = time.time() - t0, json.loads(r.stdout)
r = run(dpd_cmd("threads2.h5", "short.json", extra=("--threads", "2")))
assert r.returncode == 0, r.stderr
compare_outputs("straight.h5", "threads2.h5")
print("two threads: the same bits as one")

summaries = check_resumes(lambda out: dpd_cmd(out, "short.json"), "dpd", "straight.h5", duration, run)
for s in summaries:
    assert json.loads(s) == summary, "a resumed run's summary differs from the uninterrupted run's"

r = run(dpd_cmd("replica1.h5", "short.json", extra=("--replica", "1")))
assert r.returncode == 0, r.stderr
with h5py.File("straight.h5") as a, h5py.File("replica1.h5") as b:
    assert not np.array_equal(a["particles/all/position/value"][-1], b["particles/all/position/value"][-1])
    assert not np.array_equal(a["particles/all/velocity/value"][0], b["particles/all/velocity/value"][0])
print("--replica 1: other starting velocities and another trajectory")

bad = [
    ("negative gamma", {**dpd, "liquid": {"gamma": -1}}, "liquid.gamma"),
    ("unknown key", {**dpd, "liquid": {"gama": 4.5}}, "liquid.gama"),
    ("no liquid block", {k: v for k, v in dpd.items() if k != "liquid"}, "liquid"),
    ("a box smaller than twice cut-off plus skin", {**dpd, "liquid": {"cutoff": 3.9}}, "liquid.cutoff"),
    ("unknown liquid species", {**dpd, "liquid": {"species": ["water"]}}, "liquid.species[0]"),
    ("velocities from an input without them", {**dpd, "velocities": "input"}, "velocities"),
    ("a schedule (no field in DPD)", {**dpd, "schedule": {"segments": []}}, "schedule"),
    ("Groot-Warren lambda beyond 1", {**dpd, "velocity_lambda": 1.5}, "velocity_lambda"),
    ("Groot-Warren lambda without velocity-dependent forces", {**dpd, "liquid": {"a": 25, "gamma": 0}, "velocity_lambda": 0.65},
     "velocity_lambda"),
]
for what, config, path in bad:
    r = run([tool("anisodyn-dpd"), "--config", write("bad.json", config), "--input", "start.h5", "--output", "bad.h5"])
    assert r.returncode == 2, (what, r.returncode, r.stderr)
    assert "bad.json" in r.stderr and path in r.stderr, (what, r.stderr)
    assert not any(f.startswith("bad.h5") for f in os.listdir(".")), what
    print(f"bad input, {what}: exit 2: {r.stderr.strip().splitlines()[-1][:150]}")
