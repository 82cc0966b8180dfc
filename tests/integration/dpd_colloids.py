#!/usr/bin/env python3
"""anisodyn-config (placement colloids_in_liquid) -> anisodyn-dpd with rigid colloids (spec 30 §3-§5):

1. set-up: the liquid count N = round(rho (L^3 - V_colloid)), recorded in the provenance; no liquid
   particle inside the colloid; the colloid at the centre;
2. a free rigid rod (1,4) in vacuum with a random velocity and a random angular momentum
   perpendicular to its axis: energy and angular momentum conserved to 1e-8 relative over 1e5
   steps, the angular momentum perpendicular to the axis, the rod turned at the rate |L|/I_perp;
3. a rod in the liquid without thermostat (gamma = 0, gamma_surface = 0, conservative DPD and Mie
   core only): the total energy per particle drifts by less than 1e-3 kT over 2000 steps, so that
   site forces, torques and the core's energy agree;
4. equipartition in the liquid (gamma = 100, gamma_surface = 20/3, vector3d shell noise): the
   colloids' translational and rotational kinetic temperatures (a rod's 2 rotational degrees of
   freedom; a sphere's 3 with the surface-velocity friction) equal 1 within 3.5 standard errors
   (20 blocks of rows, each error below 0.03); the liquid's (1.005 at gamma = 100 from the time
   step) and the along_v noise's sphere temperature are reported;
5. the rod run on two threads has the same bits as on one; SIGINT and SIGKILL then resume bit for
   bit; the frames hold only frame_species;
6. bad input (anisodyn-config and anisodyn-dpd) exits 2, names the file and JSON path, writes nothing.
"""
import json
import os
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


def config(name, colloid_shape, edge, seed=1):
    cfg = {"seed": seed, "placement": "colloids_in_liquid",
           "species": [{"name": "colloid", "shape": colloid_shape}, {"name": "liquid", "shape": {"type": "sphere", "diameter": 1.0}}],
           "composition": [{"species": "colloid", "count": 1}],
           "liquid": {"species": "liquid", "density": 3}, "box": {"edges": [edge] * 3}}
    r = run([tool("anisodyn-config"), "-q", "--config", write(name + ".json", cfg), "--output", name + ".h5"])
    assert r.returncode == 0, r.stderr
    return name + ".h5"


def block_mean(x, blocks=20):
    m = np.array([v.mean() for v in np.array_split(np.asarray(x), blocks)])
    return m.mean(), m.std(ddof=1) / np.sqrt(blocks)


ROD = {"type": "spherocylinder", "length": 3.0, "diameter": 1.0}   # (d, L) = (1, 4): 7 sites
SPHERE = {"type": "sphere", "diameter": 2.0}
EDGE = 6.0

# 1. Set-up.
rod_start = config("rod_start", ROD, EDGE)
volume = np.pi * (1 + 1.5 * 3) / 6
with h5py.File(rod_start) as f:
    fill = json.loads(f["parameters/provenance"][()])["liquid_fill"]
    species = f["particles/all/species/value"][0]
    pos = f["particles/all/position/value"][0]
    q = f["particles/all/orientation/value"][0][0]
assert fill["liquid_particles"] == round(3 * (EDGE ** 3 - volume)) == np.count_nonzero(species == 1), (fill, np.bincount(species))
assert np.allclose(pos[0], EDGE / 2)
w, x, y, z = q
axis = np.array([2 * (x * z + w * y), 2 * (y * z - w * x), 1 - 2 * (x * x + y * y)])
d = pos[1:] - pos[0]
d -= EDGE * np.round(d / EDGE)
along = np.clip(d @ axis, -1.5, 1.5)
closest = np.linalg.norm(d - along[:, None] * axis, axis=1).min()
assert closest >= 0.5, closest
print(f"set-up: {fill['liquid_particles']} liquid particles = round(3 (6^3 - {volume:.4f})); nearest liquid {closest:.3f} from the rod axis")

# 2. A free rod in vacuum.
vac = {"seed": 1, "placement": "uniform", "species": [{"name": "rod", "shape": ROD}],
       "composition": [{"species": "rod", "count": 1, "orientation": {"mode": "random"}}], "box": {"edges": [12, 12, 12]}}
r = run([tool("anisodyn-config"), "-q", "--config", write("vac.json", vac), "--output", "vac.h5"])
assert r.returncode == 0, r.stderr
rng = np.random.default_rng(3)
with h5py.File("vac.h5", "r+") as f:
    g = f["particles/all"]
    w, x, y, z = g["orientation/value"][0][0]
    u = np.array([2 * (x * z + w * y), 2 * (y * z - w * x), 1 - 2 * (x * x + y * y)])
    L0 = rng.normal(size=3) * 3.0
    L0 -= (L0 @ u) * u                      # perpendicular to the axis: a linear rotor has no spin about it
    V0 = rng.normal(size=3) * 0.3
    for name, value in (("velocity", V0), ("angular_momentum", L0)):
        e = g.create_group(name)
        e["step"], e["time"] = g["position/step"], g["position/time"]
        e.create_dataset("value", data=value.reshape(1, 1, 3))
STEPS = 100000
write("free.json", {"seed": 2, "time_step": 0.005, "steps": STEPS, "observe_every": 10000, "velocities": "input",
                    "frames": {"every_steps": 10000}, "liquid": {"a": 25, "gamma": 100}, "colloids": {"species": ["rod"]}})
r = run([tool("anisodyn-dpd"), "-q", "--config", "free.json", "--input", "vac.h5", "--output", "free.h5"])
assert r.returncode == 0, r.stderr
body = json.loads(r.stdout)["colloids"]["bodies"]["rod"]
M, I = body["mass"], body["moment_perpendicular"]
assert body["sites"] == 7 and abs(M - 8.639) < 1e-3 and abs(I - 8.639) < 1e-3, body  # spec 30 §3.2's table
with h5py.File("free.h5") as f:
    V = f["particles/all/velocity/value"][:, 0]
    L = f["particles/all/angular_momentum/value"][:, 0]
    Q = f["particles/all/orientation/value"][:, 0]
    t = f["particles/all/position/time"][...]
energy = 0.5 * M * (V * V).sum(axis=1) + (L * L).sum(axis=1) / (2 * I)
E_err = np.abs(energy / energy[0] - 1).max()
L_err = np.linalg.norm(L - L0, axis=1).max() / np.linalg.norm(L0)
axes = np.array([[2 * (x * z + w * y), 2 * (y * z - w * x), 1 - 2 * (x * x + y * y)] for w, x, y, z in Q])
perp = np.abs(axes @ L0).max() / np.linalg.norm(L0)
# The axis turns about L at |L|/I: after time t its angle to the start axis is |L| t / I (mod 2 pi).
turn = np.arccos(np.clip(axes[1] @ axes[0], -1, 1))
expected = (np.linalg.norm(L0) / I * (t[1] - t[0])) % (2 * np.pi)
expected = min(expected, 2 * np.pi - expected)
print(f"free rod, {STEPS} steps: |dE/E| {E_err:.2e}, |dL|/|L| {L_err:.2e}, |L.u|/|L| {perp:.2e}; "
      f"turn over {t[1] - t[0]:g} tau: {turn:.6f} rad (|L| t/I: {expected:.6f})")
assert E_err < 1e-8 and L_err < 1e-8 and perp < 1e-8, (E_err, L_err, perp)
assert abs(turn - expected) < 1e-6, (turn, expected)

# 3. A rod in the liquid without thermostat: conservative forces only.
write("nve.json", {"seed": 5, "time_step": 0.002, "steps": 2000, "observe_every": 100, "liquid": {"a": 25, "gamma": 0},
                   "colloids": {"species": ["colloid"]}, "frame_species": ["colloid"]})
write("relax.json", {"seed": 5, "time_step": 0.005, "time": 10, "observe_every": 1000, "liquid": {"a": 25, "gamma": 4.5},
                     "colloids": {"species": ["colloid"], "gamma_surface": 3.3333333333333335}})
r = run([tool("anisodyn-dpd"), "-q", "--config", "relax.json", "--input", rod_start, "--output", "relaxed.h5"])
assert r.returncode == 0, r.stderr
r = run([tool("anisodyn-dpd"), "-q", "--config", "nve.json", "--input", "relaxed.h5", "--output", "nve.h5"])
assert r.returncode == 0, r.stderr
with h5py.File("nve.h5") as f:
    E, _ = observable(f, "total_energy")
    assert f["particles/all/position/value"].shape[1] == 1  # the colloid alone
drift = abs(E[-1] - E[0])
print(f"rod in the liquid, NVE (gamma 0, dt 0.002, 2000 steps): total energy per particle {E[0]:.6f} -> {E[-1]:.6f}, "
      f"drift {drift:.2e} kT, row-to-row scatter {np.std(np.diff(E)):.2e}")
assert drift < 1e-3, drift

# 4. Equipartition.
sphere_start = config("sphere_start", SPHERE, EDGE, seed=2)
equi = {"seed": 7, "time_step": 0.005, "time": 200, "observe_every": 200, "liquid": {"a": 25, "gamma": 100},
        "colloids": {"species": ["colloid"], "gamma_surface": 6.666666666666667}, "frame_species": ["colloid"]}
results = {}
cases = (("rod (1,4)", rod_start, "vector3d", "centre"), ("sphere d=2", sphere_start, "vector3d", "centre"),
         ("sphere d=2", sphere_start, "along_v", "centre"), ("rotating sphere d=2", sphere_start, "vector3d", "surface"))
for label, start, noise, at in cases:
    cfg = {**equi, "colloids": {**equi["colloids"], "shell_noise": noise, "friction_velocity": at}}
    out = f"equi_{label[:3]}_{noise}_{at}.h5"
    t0 = time.time()
    r = run([tool("anisodyn-dpd"), "-q", "--config", write("equi.json", cfg), "--input", start, "--output", out])
    assert r.returncode == 0, r.stderr
    with h5py.File(out) as f:
        skip = 10  # the first 10 tau: the colloid starts at rest
        rows = {k: block_mean(observable(f, k)[0][skip:]) for k in ("kinetic_temperature", "colloid_temperature_translational")}
        if "rod" in label or "rotating" in label:
            rows["colloid_temperature_rotational"] = block_mean(observable(f, "colloid_temperature_rotational")[0][skip:])
        momentum = np.abs(observable(f, "momentum")[0]).max()
    print(f"{label}, {noise} ({time.time() - t0:.1f} s): " + ", ".join(f"{k} {m:.4f} ± {s:.4f}" for k, (m, s) in rows.items())
          + f"; largest |total momentum| {momentum:.1e}")
    assert momentum < 1e-9, momentum
    if noise == "vector3d":
        # The colloids' temperatures; the liquid's at gamma = 100 is 1.005 from the time step (docs/dpd.md), reported only.
        for k, (m, s) in rows.items():
            if k != "kinetic_temperature":
                assert abs(m - 1) < 3.5 * s and s < 0.03, (label, k, m, s)

# 5. Threads and restarts, on the rod.
write("short.json", {**equi, "time": 6, "observe_every": 100, "frames": {"every_steps": 100}})


def rod_cmd(out, extra=()):
    return [tool("anisodyn-dpd"), "-q", "--config", "short.json", "--input", rod_start, "--output", out, "--checkpoint-every", "300", *extra]


t0 = time.time()
r = run(rod_cmd("straight.h5"))
assert r.returncode == 0, r.stderr
duration, summary = time.time() - t0, json.loads(r.stdout)
r = run(rod_cmd("threads2.h5", ("--threads", "2")))
assert r.returncode == 0, r.stderr
compare_outputs("straight.h5", "threads2.h5")
with h5py.File("straight.h5") as f:
    assert f["particles/all/position/value"].shape == (13, 1, 3) and "angular_momentum" in f["particles/all"]
print("rod in the liquid: two threads give the same bits as one; frames hold the colloid alone")
for s in check_resumes(rod_cmd, "rod", "straight.h5", duration, run):
    assert json.loads(s) == summary

# 6. Bad input.
big_rod = config("big_rod", {"type": "spherocylinder", "length": 5.0, "diameter": 1.0}, 6.0)
two = {"seed": 3, "placement": "colloids_in_liquid",
       "species": [{"name": "colloid", "shape": SPHERE}, {"name": "liquid", "shape": {"type": "sphere", "diameter": 1.0}}],
       "composition": [{"species": "colloid", "count": 2}], "liquid": {"species": "liquid", "density": 3}, "box": {"edges": [8, 8, 8]}}
r = run([tool("anisodyn-config"), "-q", "--config", write("two.json", two), "--output", "two.h5"])
assert r.returncode == 0, r.stderr
with h5py.File("two.h5", "r+") as f:  # two spheres d = 2 whose cores overlap: the second 1.5 from the first
    p = f["particles/all/position/value"]
    s = f["particles/all/species/value"][0]
    a, b = np.flatnonzero(s == 0)
    new = p[0]
    new[b] = new[a] + np.array([1.5, 0, 0])
    new[b] %= 8.0
    p[0] = new
good = {"seed": 1, "time_step": 0.005, "steps": 10, "liquid": {"a": 25, "gamma": 100},
        "colloids": {"species": ["colloid"], "gamma_surface": 1.0}}
bad_dpd = [
    ("a rod too long for the box (extent 7 > 6)", good, big_rod, "colloids.species"),
    ("overlapping colloids", good, "two.h5", "/particles/all"),
    ("a time step beyond the Mie core's limit", {**good, "time_step": 0.01}, rod_start, "time_step"),
    ("negative gamma_surface", {**good, "colloids": {"species": ["colloid"], "gamma_surface": -1}}, rod_start, "colloids.gamma_surface"),
    ("shell without friction", {**good, "colloids": {"species": ["colloid"], "shell": 0.5}}, rod_start, "colloids.shell"),
    ("unknown shell noise", {**good, "colloids": {"species": ["colloid"], "gamma_surface": 1, "shell_noise": "scalar"}}, rod_start,
     "colloids.shell_noise"),
    ("unknown colloid species", {**good, "colloids": {"species": ["rods"]}}, rod_start, "colloids.species[0]"),
    ("a colloid species that is liquid too", {**good, "liquid": {"species": ["liquid", "colloid"]}}, sphere_start, "colloids.species[0]"),
    ("a species neither liquid nor colloid", {k: v for k, v in good.items() if k != "colloids"}, rod_start, "liquid.species"),
    ("unknown frame species", {**good, "frame_species": ["rod"]}, rod_start, "frame_species[0]"),
    ("surface friction without friction", {**good, "colloids": {"species": ["colloid"], "friction_velocity": "surface"}}, sphere_start,
     "colloids.friction_velocity"),
    ("surface friction on a fixed colloid", {**good, "colloids": {**good["colloids"], "friction_velocity": "surface", "fixed": True}},
     sphere_start, "colloids.friction_velocity"),
]
for what, cfg, start, path in bad_dpd:
    expect_bad_input(what, [tool("anisodyn-dpd"), "--config", write("bad.json", cfg), "--input", start, "--output", "bad.h5"],
                     [path, ("bad.json", start)])
cube = {**two, "species": [{"name": "colloid", "shape": {"type": "cuboid", "edges": [1, 1, 1]}}, two["species"][1]],
        "composition": [{"species": "colloid", "count": 1}]}
bad_config = [
    ("the liquid in the composition", {**two, "composition": [{"species": "liquid", "count": 3}]}, "liquid.species"),
    ("a liquid block without its placement", {**two, "placement": "random"}, "liquid"),
    ("a cube colloid", cube, "composition"),
    ("an unknown liquid species", {**two, "liquid": {"species": "water"}}, "liquid.species"),
]
for what, cfg, path in bad_config:
    expect_bad_input("config, " + what, [tool("anisodyn-config"), "--config", write("bad.json", cfg), "--output", "bad.h5"], [path, "bad.json"])
