#!/usr/bin/env python3
"""Green-Kubo viscosity of the C-study DPD liquid (rho = 3, a = 25, gamma = 100, dt = 0.005), anisodyn
against LAMMPS on the same liquid, box and run length: an independent check of the whole chain
(forces, stress by part, correlator, integral, plateau, block errors).

anisodyn: anisodyn-config (uniform), anisodyn-dpd 20 tau (discarded), then anisodyn-dpd with the
green_kubo record (BLOCKS blocks) and anisodyn-viscosity (plateau 2 ... 5 tau).
LAMMPS: bench/peers/dpd_liquid.lmp (pair_style dpd, fix nve) with gk = the block length:
fix ave/correlate of pxy, pxz, pyz every step, each block on its own (ave one); this script
integrates each block's C(t) by the trapezoid rule (V/kT), averages eta(t) over 2 ... 5 tau, and
gives mean +- standard error over the blocks, as anisodyn-viscosity does.

Usage: bench/peers/dpd_viscosity_side_by_side.py [BIN_DIR] [--box L] [--time T] [--blocks B]
Without LAMMPS (lammps.sh exits 77) it reports anisodyn alone and says so.
"""
import argparse
import json
import os
import subprocess
import sys
import tempfile

import h5py
import numpy as np

here = os.path.dirname(os.path.abspath(__file__))
ap = argparse.ArgumentParser()
ap.add_argument("bin", nargs="?", default=os.path.join(here, "..", "..", "build", "bin"))
ap.add_argument("--box", type=float, default=5.0)
ap.add_argument("--time", type=float, default=2000.0, help="production time per code, tau")
ap.add_argument("--blocks", type=int, default=10)
ap.add_argument("--gamma", type=float, default=100.0)
args = ap.parse_args()
DT, KT, T_MIN, T_MAX = 0.005, 1.0, 2.0, 5.0
L, n = args.box, int(round(3 * args.box ** 3))
steps = int(round(args.time / DT))
block_steps = steps // args.blocks
work = tempfile.mkdtemp(prefix="dpd_gk_")


def run(cmd, **kw):
    r = subprocess.run(cmd, capture_output=True, text=True, **kw)
    if r.returncode != 0:
        sys.exit(f"failed: {' '.join(cmd)}\n{r.stderr}")
    return r


def write(name, value):
    path = os.path.join(work, name)
    json.dump(value, open(path, "w"))
    return path


def plateau_of_blocks(lag, acf_blocks, volume):
    """eta per block: (V/kT) trapezoid of C(t), mean over the lags in [T_MIN, T_MAX]; mean and SE over blocks."""
    window = (lag >= T_MIN) & (lag <= T_MAX)
    etas = []
    for c in acf_blocks:
        eta = np.concatenate([[0.0], np.cumsum(0.5 * (c[1:] + c[:-1]) * np.diff(lag))]) * volume / KT
        etas.append(eta[window].mean())
    etas = np.array(etas)
    return etas.mean(), etas.std(ddof=1) / np.sqrt(len(etas))


def anisodyn():
    tool = lambda name: os.path.join(args.bin, name)  # noqa: E731
    liquid = {"seed": 1, "species": [{"name": "liquid", "shape": {"type": "sphere", "diameter": 1.0}}],
              "composition": [{"species": "liquid", "count": n}], "box": {"edges": [L] * 3}, "placement": "uniform"}
    dpd = {"seed": 2, "time_step": DT, "observe_every": 1000, "liquid": {"a": 25, "gamma": args.gamma}}
    start, relaxed, out = (os.path.join(work, f) for f in ("start.h5", "relaxed.h5", "gk.h5"))
    run([tool("anisodyn-config"), "-q", "--config", write("liquid.json", liquid), "--output", start])
    run([tool("anisodyn-dpd"), "-q", "--config", write("relax.json", {**dpd, "time": 20.0}), "--input", start, "--output", relaxed])
    production = {**dpd, "seed": 3, "steps": steps, "velocities": "input", "green_kubo": {"blocks": args.blocks, "max_lag": 10.0}}
    run([tool("anisodyn-dpd"), "-q", "--config", write("gk.json", production), "--input", relaxed, "--output", out])
    visc = os.path.join(work, "visc.h5")
    run([tool("anisodyn-viscosity"), "-q", "--config", write("visc.json", {}), "--input", out, "--output", visc])
    with h5py.File(visc) as f:
        value, error = f["scalars/eta"][...]
    # The same numbers from the record by this script's own integration, as for LAMMPS below.
    with h5py.File(out) as f:
        lag = f["observables/stress_acf_lag_time/value"][0]
        acf = f["observables/stress_acf/value"][:].reshape(args.blocks, len(lag), -1)[:, :, 0:3].mean(axis=2)
    mine = plateau_of_blocks(lag, acf, L ** 3)
    return value, error, mine


def lammps():
    r = subprocess.run([os.path.join(here, "lammps.sh")], capture_output=True, text=True)
    if r.returncode != 0:
        print(f"LAMMPS is not available ({r.stderr.strip().splitlines()[-1] if r.stderr.strip() else 'lammps.sh failed'}): anisodyn alone")
        return None
    lmp = r.stdout.strip()
    lags = int(round(6.0 / DT))
    run([lmp, "-in", os.path.join(here, "dpd_liquid.lmp"), "-var", "L", str(L), "-var", "gamma", str(args.gamma), "-var", "equil", "4000",
         "-var", "steps", str(block_steps * args.blocks), "-var", "gk", str(block_steps), "-var", "lags", str(lags), "-log", "none",
         "-screen", "none"], cwd=work)
    blocks, current = [], None
    for line in open(os.path.join(work, "gk.dat")):
        if line.startswith("#"):
            continue
        fields = line.split()
        if len(fields) == 2:  # "Timestep Number-of-rows": a new block
            current = []
            blocks.append(current)
        else:  # Index TimeDelta Ncount pxy*pxy pxz*pxz pyz*pyz
            current.append([float(fields[1]) * DT] + [float(v) for v in fields[3:6]] + [float(fields[2])])
    # Whole blocks only: the first output (the production's step 0) holds one sample and no lag.
    blocks = [np.array(b) for b in blocks if len(b) == lags and b[-1][4] > 0]
    lag = blocks[0][:, 0]
    return plateau_of_blocks(lag, [b[:, 1:4].mean(axis=1) for b in blocks], L ** 3), len(blocks)


print(f"DPD liquid rho = 3, a = 25, gamma = {args.gamma:g}, dt = {DT}, box {L:g} (N = {n}), {args.time:g} tau in {args.blocks} blocks; "
      f"plateau {T_MIN:g} ... {T_MAX:g} tau; work dir {work}")
value, error, mine = anisodyn()
print(f"anisodyn: eta = {value:.4f} +- {error:.4f} (anisodyn-viscosity; this script's integration of the record: {mine[0]:.4f} +- {mine[1]:.4f})")
peer = lammps()
if peer:
    (eta, se), count = peer
    print(f"LAMMPS:   eta = {eta:.4f} +- {se:.4f} ({count} blocks, fix ave/correlate, linear lags)")
    print(f"difference: {value - eta:+.4f} +- {np.hypot(error, se):.4f} ({(value - eta) / np.hypot(error, se):+.1f} SE)")
