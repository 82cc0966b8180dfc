#!/usr/bin/env python3
"""anisodyn-dpd's walls, drive, profiles and fixed colloid (spec 30 §6, §8) and anisodyn-flow:

1. a drive alone (no walls, periodic liquid): the total momentum grows by exactly f N dt per step
   (internal forces cancel pair by pair), to round-off; a list of slabs (two opposite halves, as in
   a periodic Poiseuille flow, and a push on all) adds up to the impulse counted from the frames;
   anisodyn-observables finds that slope and numpy's mean temperature;
2. a Couette channel (walls at z = 0 with friction and z = 8 without, drive on z > 6): no liquid
   particle leaves the channel; the slab counts of every row add up to N; two threads give the same
   bits; SIGINT and SIGKILL resume bit for bit; with the drive on every particle, the liquid's x
   momentum changes by the drive's impulse f N t minus the walls' (to velocity Verlet's half-step
   boundary term);
3. a fixed sphere in a driven liquid: its position and velocity stay bit for bit; its radial density
   profile is 0 inside the core and the bulk density far from it;
4. anisodyn-flow on profiles replaced by an exact line v_x = G z + a (with noise only outside the
   fit window): b = a/G and G recovered to 1e-12; slab density = count / (area width);
5. bad input exits 2, names the file and the JSON path, and writes nothing.
"""
import json
import os
import shutil
import sys
import time

import h5py
import numpy as np

bin_dir, tmp, source = sys.argv[1], sys.argv[2], sys.argv[3]
sys.path.insert(0, os.path.join(source, "tests", "support"))
from resume_checks import check_resumes, compare_outputs  # noqa: E402
from script_io import enter_scratch, expect_bad_input, observable, run, write  # noqa: E402

enter_scratch(tmp)


def tool(name):
    return os.path.join(bin_dir, name)


LIQ = {"name": "liquid", "shape": {"type": "sphere", "diameter": 1.0}}
channel = {"seed": 3, "placement": "colloids_in_liquid", "species": [LIQ],
           "liquid": {"species": "liquid", "density": 3, "z_range": [0, 8]}, "box": {"edges": [8, 8, 9.5]}}
r = run([tool("anisodyn-config"), "-q", "--config", write("channel.json", channel), "--output", "channel.h5"])
assert r.returncode == 0, r.stderr
with h5py.File("channel.h5") as f:
    z0 = f["particles/all/position/value"][0][:, 2]
    N = len(z0)
assert N == 1536 and z0.min() >= 0 and z0.max() <= 8, (N, z0.min(), z0.max())

# 1. The drive alone: dP/dt = f N exactly.
bulk = {"seed": 1, "placement": "uniform", "species": [LIQ], "composition": [{"species": "liquid", "count": 648}], "box": {"edges": [6, 6, 6]}}
r = run([tool("anisodyn-config"), "-q", "--config", write("bulk.json", bulk), "--output", "bulk.h5"])
assert r.returncode == 0, r.stderr
write("push.json", {"seed": 2, "time_step": 0.005, "steps": 2000, "observe_every": 100, "liquid": {"a": 25, "gamma": 4.5},
                    "drive": {"force": [0.01, -0.02, 0.0]}})
r = run([tool("anisodyn-dpd"), "-q", "--config", "push.json", "--input", "bulk.h5", "--output", "push.h5"])
assert r.returncode == 0, r.stderr
with h5py.File("push.h5") as f:
    P, t = observable(f, "momentum")
expected = np.outer(t, [0.01 * 648, -0.02 * 648, 0.0])
err = np.abs(P - expected).max()
print(f"drive alone: |P - f N t| <= {err:.1e} over {t[-1]:g} tau (P_x = {P[-1, 0]:.4f})")
assert err < 1e-9, err

# A list of slabs adds up: the lower half of the box pushed along +x and the upper half along -x,
# plus a push along y on all of it. dP/dt = f_x (N_lower - N_upper) + f_y N, counted here from the
# frames (z wrapped into the box) at every step's start, must match the momentum rows.
write("pair.json", {"seed": 2, "time_step": 0.005, "steps": 200, "observe_every": 1, "liquid": {"a": 25, "gamma": 4.5},
                    "frames": {"every_steps": 1},
                    "drive": [{"force": [0.01, 0, 0], "z_max": 3}, {"force": [-0.01, 0, 0], "z_min": 3}, {"force": [0, 0.02, 0]}]})
r = run([tool("anisodyn-dpd"), "-q", "--config", "pair.json", "--input", "bulk.h5", "--output", "pair.h5"])
assert r.returncode == 0, r.stderr
with h5py.File("pair.h5") as f:
    P, t = observable(f, "momentum")
    z = f["particles/all/position/value"][:, :, 2]
z = z - 6.0 * np.floor(z / 6.0)
# Velocity Verlet: the momentum after step n holds half of the drive at the start of step n and half
# at its end, so each step's change is the mean of the two frames' drives, times dt.
drive_x = 0.01 * ((z < 3).sum(axis=1) - (z >= 3).sum(axis=1))
change = 0.005 * 0.5 * (drive_x[:-1] + drive_x[1:])
P_x = np.concatenate([[0.0], np.cumsum(change)])
err = max(np.abs(P[:, 0] - P_x[-len(P):]).max(), np.abs(P[:, 1] - 0.02 * 648 * t).max())
print(f"two opposite slabs and a push along y: |P - sum of the drives' impulses| <= {err:.1e} over {t[-1]:g} tau")
assert err < 1e-9, err

# anisodyn-observables on the same run: the momentum's slope is f N exactly, the temperature's mean numpy's.
write("obs.json", {"means": ["kinetic_temperature"], "drifts": ["momentum"], "window": {"from": 2}})
r = run([tool("anisodyn-observables"), "-q", "--config", "obs.json", "--input", "push.h5", "--output", "obs.h5"])
assert r.returncode == 0, r.stderr
with h5py.File("obs.h5") as f, h5py.File("push.h5") as g:
    slope_x, slope_y = f["scalars/momentum_0_drift"][...], f["scalars/momentum_1_drift"][...]
    T = f["scalars/kinetic_temperature"][...]
    T_rows, T_times = observable(g, "kinetic_temperature")
print(f"anisodyn-observables: dP/dt = ({slope_x[0]:.10f}, {slope_y[0]:.10f}) (f N = 6.48, -12.96), T_kin {T[0]:.5f} ± {T[1]:.5f}")
assert abs(slope_x[0] - 6.48) < 1e-9 and abs(slope_y[0] + 12.96) < 1e-9 and slope_x[1] < 1e-9
assert abs(T[0] - T_rows[T_times >= 2 - 1e-9].mean()) < 1e-12 and 0 < T[1] < 0.05

# 2. The Couette channel.
couette = {"seed": 4, "time_step": 0.005, "steps": 2000, "observe_every": 100, "liquid": {"a": 25, "gamma": 100},
           "walls": {"type": "flat_mie", "height": 8, "gamma_surface": [10, 0]}, "drive": {"force": [0.05, 0, 0], "z_min": 6},
           "profiles": {"z_bin": 0.1}, "frames": {"every_steps": 200}}
write("couette.json", couette)


def couette_cmd(out, extra=()):
    return [tool("anisodyn-dpd"), "-q", "--config", "couette.json", "--input", "channel.h5", "--output", out, "--checkpoint-every", "300", *extra]


t0 = time.time()
r = run(couette_cmd("couette.h5"))
assert r.returncode == 0, r.stderr
duration, summary = time.time() - t0, json.loads(r.stdout)
with h5py.File("couette.h5") as f:
    z = f["particles/all/position/value"][:, :, 2] + 9.5 * f["particles/all/image/value"][:, :, 2]
    counts, _ = observable(f, "profile_z_count")
print(f"channel: liquid z in [{z.min():.4f}, {z.max():.4f}] over {len(z)} frames; slab counts per row {counts.sum(axis=1).min():.6f} ... "
      f"{counts.sum(axis=1).max():.6f}")
assert z.min() > -0.05 and z.max() < 8.05, (z.min(), z.max())
assert np.abs(counts.sum(axis=1) - N).max() < 1e-9
assert counts.shape[1] == 95  # ceil(9.5 / 0.1) slabs
# Momentum balance with the drive on every particle (a run of its own): the liquid's x momentum
# changes by the drive's impulse f N t minus the walls' (internal forces cancel pair by pair), up to
# velocity Verlet's half-step boundary term dt/2 (F_0 - F_n) of the walls' per-step forces (noise of
# order 10^3 per step here: a few units).
write("balance.json", {**couette, "steps": 1000, "drive": {"force": [0.05, 0, 0]}, "frames": {}})
r = run([tool("anisodyn-dpd"), "-q", "--config", "balance.json", "--input", "channel.h5", "--output", "balance.h5"])
assert r.returncode == 0, r.stderr
with h5py.File("balance.h5") as f:
    P, t = observable(f, "momentum")
    wall, _ = observable(f, "wall_force_bottom")
    top, _ = observable(f, "wall_force_top")
drive = 0.05 * N * t[-1]
walls = ((wall[:, 0] + top[:, 0]) * 100 * 0.005).sum()
print(f"x momentum over {t[-1]:g} tau: change {P[-1, 0]:.3f} = drive {drive:.3f} - walls {walls:.3f} "
      f"(difference {P[-1, 0] - (drive - walls):.3f})")
assert abs(P[-1, 0] - (drive - walls)) < 5.0, (P[-1, 0], drive, walls)

r = run(couette_cmd("couette2.h5", ("--threads", "2")))
assert r.returncode == 0, r.stderr
compare_outputs("couette.h5", "couette2.h5")
print("channel: two threads give the same bits as one")
for s in check_resumes(couette_cmd, "couette", "couette.h5", duration, run):
    assert json.loads(s) == summary

# 3. A fixed sphere in a driven liquid.
sphere = {"seed": 5, "placement": "colloids_in_liquid", "species": [{"name": "sphere", "shape": {"type": "sphere", "diameter": 2.0}}, LIQ],
          "composition": [{"species": "sphere", "count": 1}], "liquid": {"species": "liquid", "density": 3}, "box": {"edges": [6, 6, 6]}}
r = run([tool("anisodyn-config"), "-q", "--config", write("sphere.json", sphere), "--output", "sphere.h5"])
assert r.returncode == 0, r.stderr
write("fixed.json", {"seed": 6, "time_step": 0.005, "steps": 4000, "observe_every": 200, "liquid": {"a": 25, "gamma": 100},
                     "colloids": {"species": ["sphere"], "gamma_surface": 3.3333333333333335, "fixed": True},
                     "drive": {"force": [0.002, 0, 0]}, "profiles": {"radial_bin": 0.1, "radial_max": 3},
                     "frame_species": ["sphere"], "frames": {"every_steps": 500}})
r = run([tool("anisodyn-dpd"), "-q", "--config", "fixed.json", "--input", "sphere.h5", "--output", "fixed.h5"])
assert r.returncode == 0, r.stderr
with h5py.File("fixed.h5") as f:
    pos = f["particles/all/position/value"][:, 0]
    vel = f["particles/all/velocity/value"][:, 0]
    counts, _ = observable(f, "profile_r_count")
assert (pos == pos[0]).all() and (vel == 0).all(), (pos, vel)
shells = 4 * np.pi / 3 * (np.arange(1, 31) ** 3 - np.arange(30) ** 3) * 0.1 ** 3
density = counts[5:].mean(axis=0) / shells
print(f"fixed sphere: position {pos[0]} over {len(pos)} frames, velocity 0; density inside r < 0.9: {density[:9].max():.3g}, "
      f"at 2.5 <= r < 3: {density[25:].mean():.3f}")
assert density[:9].max() == 0.0 and abs(density[25:].mean() - 3.0) < 0.15

# 4. anisodyn-flow on an exact line.
G, a = 0.04, 0.012
shutil.copy("couette.h5", "line.h5")
with h5py.File("line.h5", "r+") as f:
    group = "observables" if "observables/profile_z_count" in f else "anisodyn/observables"
    c = f[f"{group}/profile_z_count/value"]
    v = f[f"{group}/profile_z_vx_sum/value"]
    zc = (np.arange(95) + 0.5) * 0.1
    rng = np.random.default_rng(1)
    new_c = np.full(c.shape, 16.0)
    line = G * zc + a
    noisy = np.where((zc < 1.5) | (zc > 5.0), rng.normal(size=c.shape), 0.0)  # noise outside the fit window only
    c[...] = new_c
    v[...] = new_c * (line + noisy)
write("flow.json", {"slip": {"top_from": 7, "top_to": 8, "height": 8}, "window": {"from": 1}})
r = run([tool("anisodyn-flow"), "-q", "--config", "flow.json", "--input", "line.h5", "--output", "line_flow.h5"])
assert r.returncode == 0, r.stderr
with h5py.File("line_flow.h5") as f:
    b = f["scalars/slip_length"][...]
    g = f["scalars/shear_gradient"][...]
    dens = f["profile_z/density"][...]
print(f"anisodyn-flow on a line: b = {b[0]:.12f} (a/G = {a / G:.12f}) ± {b[1]:.1e}, G = {g[0]:.12f} ± {g[1]:.1e}; density {dens[0]:.6f}")
assert abs(b[0] - a / G) < 1e-12 and b[1] < 1e-12 and abs(g[0] - G) < 1e-12
assert np.allclose(dens, 16.0 / (64 * 0.1))

# 5. Bad input.
good = dict(couette, steps=10)
bad = [
    ("an unknown wall type", {**good, "walls": {**couette["walls"], "type": "corrugated"}}, "channel.h5", "walls.type"),
    ("a channel as tall as the box", {**good, "walls": {**couette["walls"], "height": 9}}, "channel.h5", "walls.height"),
    ("a negative wall friction", {**good, "walls": {**couette["walls"], "gamma_surface": [-1, 0]}}, "channel.h5", "walls.gamma_surface"),
    ("one wall friction", {**good, "walls": {**couette["walls"], "gamma_surface": [1]}}, "channel.h5", "walls.gamma_surface"),
    ("a shell without wall friction", {**good, "walls": {**couette["walls"], "gamma_surface": [0, 0], "shell": 0.5}}, "channel.h5", "walls.shell"),
    ("liquid outside the channel", {**good, "walls": {**couette["walls"], "height": 7}}, "channel.h5", "/particles/all"),
    ("a drive slab upside down", {**good, "drive": {"force": [1, 0, 0], "z_min": 6, "z_max": 5}}, "channel.h5", "drive.z_max"),
    ("a listed drive slab upside down", {**good, "drive": [{"force": [1, 0, 0]}, {"force": [1, 0, 0], "z_min": 6, "z_max": 5}]}, "channel.h5",
     "drive[1].z_max"),
    ("a drive that is neither object nor list", {**good, "drive": 0.05}, "channel.h5", "drive"),
    ("empty profiles", {**good, "profiles": {}}, "channel.h5", "profiles"),
    ("radial profiles without colloids", {**good, "profiles": {"radial_bin": 0.1}}, "channel.h5", "profiles.radial_bin"),
    ("radial_max without radial_bin", {**good, "profiles": {"z_bin": 0.1, "radial_max": 2}}, "channel.h5", "profiles.radial_max"),
    ("walls with colloids", {**good, "colloids": {"species": ["sphere"]}}, "sphere.h5", "walls"),
    ("a time step beyond the walls' Mie core", {**good, "time_step": 0.01}, "channel.h5", "time_step"),
]
for what, cfg, start, path in bad:
    expect_bad_input(what, [tool("anisodyn-dpd"), "--config", write("bad.json", cfg), "--input", start, "--output", "bad.h5"],
                     [path, ("bad.json", start)])
for what, cfg, inp, path in [("slip without slab profiles", {"slip": {}}, "fixed.h5", "slip"),
                             ("a run without profiles", {}, "push.h5", "/observables/profile_z_count"),
                             ("a fit window upside down", {"slip": {"fit_from": 5, "fit_to": 1}}, "couette.h5", "slip.fit_to"),
                             ("both fits", {"slip": {}, "poiseuille": {"force": 0.05}}, "couette.h5", "poiseuille"),
                             ("a Poiseuille fit without a force", {"poiseuille": {}}, "couette.h5", "poiseuille.force"),
                             ("a Poiseuille fit without slab profiles", {"poiseuille": {"force": 0.05}}, "fixed.h5", "poiseuille")]:
    expect_bad_input("anisodyn-flow, " + what, [tool("anisodyn-flow"), "--config", write("bad.json", cfg), "--input", inp, "--output", "bad.h5"],
                     [path])
