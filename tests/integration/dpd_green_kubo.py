#!/usr/bin/env python3
"""The Green-Kubo record of anisodyn-dpd and anisodyn-viscosity against independent numpy sums.

A liquid of 192 particles (box 4, rho = 3, a = 25, gamma = 100, the C-study liquid) runs 2400
steps with an observation row every step, so that the rows hold each step's pressure tensor by
part. From those rows numpy builds, for every block, the autocorrelation at the first-level lags
(0 ... 15 steps: the correlator's exact lags) and compares it with stress_acf to 1e-9 relative;
then anisodyn-viscosity's eta(t) and plateau are recomputed from the record (trapezoid, mean over
the plateau lags, standard error over the blocks). Bad green_kubo keys exit 2 naming the path.
"""
import os
import sys

import h5py
import numpy as np

bin_dir, tmp, source = sys.argv[1], sys.argv[2], sys.argv[3]
sys.path.insert(0, os.path.join(source, "tests", "support"))
from script_io import enter_scratch, tool_runner, write  # noqa: E402

enter_scratch(tmp)
run = tool_runner(bin_dir)

EDGE, N, STEPS, BLOCKS = 4.0, 192, 2400, 4
liquid = {"seed": 2, "species": [{"name": "liquid", "shape": {"type": "sphere", "diameter": 1.0}}],
          "composition": [{"species": "liquid", "count": N}], "box": {"edges": [EDGE] * 3}, "placement": "uniform"}
dpd = {"seed": 5, "time_step": 0.005, "steps": STEPS, "observe_every": 1, "liquid": {"a": 25, "gamma": 100},
       "green_kubo": {"blocks": BLOCKS, "max_lag": 2.0}}
r = run("anisodyn-config", "--config", write("liquid.json", liquid), "--output", "start.h5")
assert r.returncode == 0, r.stderr
r = run("anisodyn-dpd", "--config", write("dpd.json", dpd), "--input", "start.h5", "--output", "gk.h5")
assert r.returncode == 0, r.stderr

with h5py.File("gk.h5") as f:
    o = f["observables"]
    parts = ("kinetic", "conservative", "dissipative", "random")
    # [steps, part, component]: xy, xz, yz are elements 3, 4, 5 of each row
    p = np.stack([o[f"pressure_tensor_{k}/value"][:, 3:6] for k in parts], axis=1)
    steps = o["pressure_tensor_kinetic/step"][:]
    acf = o["stress_acf/value"][:]
    samples = o["stress_acf_samples/value"][:]
    lag_time = o["stress_acf_lag_time/value"][0]
    acf_steps = o["stress_acf/step"][:]
    attrs = dict(o["stress_acf"].attrs)
assert np.array_equal(steps, np.arange(1, STEPS + 1)), "expected one row per step"
assert list(acf_steps) == [STEPS * (b + 1) // BLOCKS for b in range(BLOCKS)], acf_steps
assert float(attrs["volume"]) == EDGE ** 3 and float(attrs["kT"]) == 1.0
channels = np.concatenate([p.sum(axis=1, keepdims=True), p], axis=1).reshape(STEPS, -1)  # total, then the parts
nch = channels.shape[1]
assert nch == 15 and acf.shape == (BLOCKS, len(lag_time) * nch), acf.shape
acf = acf.reshape(BLOCKS, len(lag_time), nch)
block_of = (np.arange(STEPS) * BLOCKS) // STEPS  # of the later sample (step k + 1 has index k)
worst = 0.0
for b in range(BLOCKS):
    for lag in range(16):
        later = np.nonzero(block_of == b)[0]
        later = later[later >= lag]
        products = channels[later] * channels[later - lag]
        assert samples[b, lag] == len(later), (b, lag, samples[b, lag], len(later))
        expected = products.mean(axis=0)
        scale = np.abs(channels).max() ** 2
        worst = max(worst, np.abs(acf[b, lag] - expected).max() / scale)
        assert lag_time[lag] == lag * 0.005 or abs(lag_time[lag] - lag * 0.005) < 1e-15
assert worst < 1e-9, worst
print(f"stress_acf at lags 0-15 steps, every block and channel: largest difference from numpy {worst:.1e} of the largest product")

r = run("anisodyn-viscosity", "--config", write("visc.json", {"plateau": {"t_min": 0.5, "t_max": 1.5}}),
         "--input", "gk.h5", "--output", "visc.h5")
assert r.returncode == 0, r.stderr
eta_blocks = []
for b in range(BLOCKS):
    c = acf[b, :, 0:3].mean(axis=1)
    eta = np.concatenate([[0.0], np.cumsum(0.5 * (c[1:] + c[:-1]) * np.diff(lag_time))]) * EDGE ** 3
    window = (lag_time >= 0.5) & (lag_time <= 1.5)
    eta_blocks.append(eta[window].mean())
eta_blocks = np.array(eta_blocks)
mean, se = eta_blocks.mean(), eta_blocks.std(ddof=1) / np.sqrt(BLOCKS)
with h5py.File("visc.h5") as f:
    value, error = f["scalars/eta"][...]
    table_eta = f["green_kubo/eta_total"][...]
assert abs(value - mean) < 1e-12 * abs(mean) + 1e-14 and abs(error - se) < 1e-9 * se, (value, mean, error, se)
assert table_eta[0] == 0.0 and len(table_eta) == len(lag_time)
print(f"anisodyn-viscosity: eta = {value:.4f} +- {error:.4f} (numpy {mean:.4f} +- {se:.4f}; a 12-tau record, no physics claim)")

bad = [
    ("one block", {**dpd, "green_kubo": {"blocks": 1}}, "green_kubo.blocks"),
    ("blocks shorter than max_lag", {**dpd, "green_kubo": {"blocks": 4, "max_lag": 5.0}}, "green_kubo.max_lag"),
    ("unknown key", {**dpd, "green_kubo": {"block": 4}}, "green_kubo.block"),
]
for what, config, path in bad:
    r = run("anisodyn-dpd", "--config", write("bad.json", config), "--input", "start.h5", "--output", "bad.h5")
    assert r.returncode == 2, (what, r.returncode, r.stderr)
    assert "bad.json" in r.stderr and path in r.stderr, (what, r.stderr)
    assert not any(n.startswith("bad.h5") for n in os.listdir(".")), (what, os.listdir("."))
    print(f"bad input, {what}: exit 2: {r.stderr.strip().splitlines()[-1][:150]}")
r = run("anisodyn-viscosity", "--config", write("badv.json", {"plateau": {"t_min": 0.5, "t_max": 9}}),
         "--input", "gk.h5", "--output", "badv.h5")
assert r.returncode == 2 and "plateau" in r.stderr and not os.path.exists("badv.h5"), r.stderr
print(f"bad input, a plateau beyond the recorded lags: exit 2: {r.stderr.strip().splitlines()[-1][:150]}")
r = run("anisodyn-viscosity", "--config", write("v.json", {}), "--input", "start.h5", "--output", "nogk.h5")
assert r.returncode == 2 and "stress_acf" in r.stderr, r.stderr
print(f"bad input, a file without a record: exit 2: {r.stderr.strip().splitlines()[-1][:150]}")
