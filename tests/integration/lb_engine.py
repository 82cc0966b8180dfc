"""anisodyn-lb end to end (spec 40), on small lattices:
1. a free raspberry sphere in the thermal fluid: the total momentum (fluid, pending impulses, body
   and its pending half kick) is constant to round-off; the run records its units (spec 40 §1) and
   bodies; two threads give the same bits as one;
2. SIGINT and SIGKILL resume bit for bit (the fluid's populations travel as checkpoint arrays);
3. a raspberry spheroid held fixed between moving walls (deterministic fluid, spec 40 §7.2): the
   drag points along the wall velocity, with no steady force across it, and the spheroid's drag
   along its long axis is below the sphere's of the same volume (Perrin: 0.95x at aspect 2);
4. bad input exits 2, names the file and JSON path, writes nothing;
5. a raspberry in a pore stays off the wall;
6. anisodyn-lb-checks' bad input, likewise;
7. the single-layer ablation drops the outer layer only.
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


def config(name, shape, edges):
    cfg = {"seed": 1, "placement": "lattice", "species": [{"name": "body", "shape": shape}],
           "composition": [{"species": "body", "count": 1}], "box": {"edges": edges}}
    r = run([tool("anisodyn-config"), "-q", "--config", write(name + ".json", cfg), "--output", name + ".h5"])
    assert r.returncode == 0, r.stderr
    return name + ".h5"


SPHERE = {"type": "sphere", "diameter": 4.5}
sphere_start = config("sphere", SPHERE, [16, 16, 16])

# 1. A free sphere in the thermal fluid.
free = {"seed": 5, "time_step": 0.01, "steps": 2400, "observe_every": 200, "frames": {"every_steps": 400},
        "fluid": {"warmup_steps": 200}, "raspberries": {"xi_bead": 200}}
write("free.json", free)


def free_cmd(out, extra=()):
    return [tool("anisodyn-lb"), "-q", "--config", "free.json", "--input", sphere_start, "--output", out, "--checkpoint-every", "500", *extra]


t0 = time.time()
r = run(free_cmd("straight.h5"))
assert r.returncode == 0, r.stderr
duration, summary = time.time() - t0, json.loads(r.stdout)
body = summary["raspberries"]["bodies"]["body"]
assert body["layers"] == {"outer": 64, "inner": 38, "fill": body["layers"]["fill"], "centre": 1}, body["layers"]  # spec 40 §5.1's counts
assert summary["lb_steps_taken"] == (200 + 2400) // 2
with h5py.File("straight.h5") as f:
    total, _ = observable(f, "total_momentum")
    fluid, _ = observable(f, "fluid_momentum")
    temperature, _ = observable(f, "fluid_temperature")
    units = json.loads(f["parameters/provenance"][()])["units"]
    assert f["particles/all/position/value"].shape == (7, 1, 3)
    assert "angular_momentum" in f["particles/all"] and "velocity" in f["particles/all"]
drift = np.abs(total - total[0]).max()
print(f"free raspberry: fluid momentum moves by {np.abs(fluid - fluid[0]).max():.3g}, total by {drift:.2e}; "
      f"fluid temperature per row {np.round(temperature, 3).tolist()}")
assert np.abs(fluid - fluid[0]).max() > 1.0  # momentum does go between body and fluid
assert drift < 1e-9 * body["mass"], drift
assert abs(units["time_s"] - 6.3529e-12) < 1e-16 and abs(units["friction_scale"] - 0.8 / 5.6757) < 1e-12
assert abs(units["friction_kg_per_s"] - 2.6138e-14) < 1e-18, units  # spec 40 §1's table
r = run(free_cmd("threads2.h5", ("--threads", "2")))
assert r.returncode == 0, r.stderr
compare_outputs("straight.h5", "threads2.h5")
print("two threads give the same bits as one")

# 2. Resume.
for s in check_resumes(free_cmd, "free", "straight.h5", duration, run):
    assert json.loads(s) == summary

# 3. Fixed bodies between walls moving along z (the wall layer at y = 0), deterministic fluid.
U = 0.013976  # spec 40 §7.2: 2.20 m/s in sigma/t0
# Water's viscosity (5.6757, xi unscaled) brings the flow to steady state in about L^2/nu = 45 t0.
flow = {"seed": 1, "time_step": 0.01, "steps": 6000, "observe_every": 1000,
        "fluid": {"thermal": False, "viscosity": 5.6757, "initial_velocity": [0, 0, U], "warmup_steps": 0},
        "raspberries": {"xi_bead": 1000, "fixed": True}, "walls": {"normal": "y", "velocity": [0, 0, U]}}
# The same volume as the sphere: a b^2 = 2.25^3 with a = 2 b (aspect 2); the config places it
# unrotated, long axis along x: across a flow along z, along a flow along x.
b = 2.25 / 2 ** (1 / 3)
spheroid_start = config("spheroid", {"type": "ellipsoid", "semi_axes": [2 * b, b, b]}, [16, 16, 16])
with h5py.File(spheroid_start, "r+") as f:  # at the box centre, as the sphere
    p = f["particles/all/position/value"]
    p[0] = np.full((1, 3), 8.0)
drags = {}
for label, start, velocity in [("sphere", sphere_start, [0, 0, U]), ("spheroid across", spheroid_start, [0, 0, U]),
                               ("spheroid along", spheroid_start, [U, 0, 0])]:
    cfg = {**flow, "fluid": {**flow["fluid"], "initial_velocity": velocity}, "walls": {"normal": "y", "velocity": velocity}}
    r = run([tool("anisodyn-lb"), "-q", "--config", write("flow.json", cfg), "--input", start, "--output", "flow.h5"])
    assert r.returncode == 0, r.stderr
    with h5py.File("flow.h5") as f:
        force, _ = observable(f, "colloid_force")
    os.remove("flow.h5")
    along = int(np.argmax(np.abs(velocity)))
    drag = force[-1]
    print(f"{label}: drag {np.round(drag, 5).tolist()} (last row; the row before: {np.round(force[-2][along], 5)})")
    assert drag[along] > 0 and abs(force[-2][along] / drag[along] - 1) < 0.005  # steady
    # The beads are not placed symmetrically, so a small force across the flow is real; it is small.
    assert np.all(np.abs(np.delete(drag, along)) < 0.01 * drag[along]), drag
    drags[label] = drag[along]
# Happel–Brenner at aspect 2 (spec 40 §8.6, workflows/anisodyn_run/spheroid_theory.py): the
# equal-volume sphere's drag times c E = 0.9556 along the axis and c F = 1.0944 across it. The small
# box and the walls raise every drag; their ratio, 1.1453, is much less sensitive to them.
along, across = drags["spheroid along"] / drags["sphere"], drags["spheroid across"] / drags["sphere"]
print(f"drag ratios to the sphere: along {along:.3f} (Happel-Brenner 0.956), across {across:.3f} (1.094); "
      f"across / along {across / along:.4f} (1.1453)")
assert abs(across / along / 1.1453 - 1) < 0.03

# 4. Bad input.
odd_box = config("odd", SPHERE, [16, 16, 16.5])
good = {"seed": 1, "time_step": 0.01, "steps": 10, "raspberries": {"xi_bead": 200}}
big = config("big", {"type": "sphere", "diameter": 15.0}, [30, 30, 30])
with h5py.File(big, "r+") as f:  # anisodyn-config wants twice the diameter; shrink the box to 16
    f["particles/all/box/edges/value"][0] = np.diag([16.0] * 3)
    f["particles/all/position/value"][0] = np.full((1, 3), 8.0)
cube = config("cube", {"type": "cuboid", "edges": [2, 2, 2]}, [16, 16, 16])
bad_lb = [
    ("a box edge of 16.5 nodes", good, odd_box, "fluid.agrid"),
    ("a viscosity that makes tau <= 1/2", {**good, "fluid": {"viscosity": 0}}, sphere_start, "fluid.viscosity"),
    ("a raspberry larger than the box", good, big, "raspberries.species"),
    ("xi_bead beyond the stability limit", {**good, "raspberries": {"xi_bead": 5000}}, sphere_start, "raspberries.xi_bead"),
    ("a cube raspberry", good, cube, "raspberries.species"),
    ("an unknown raspberry species", {**good, "raspberries": {"xi_bead": 200, "species": ["rasp"]}}, sphere_start, "raspberries.species[0]"),
    ("kT with the deterministic fluid", {**good, "kT": 2, "fluid": {"thermal": False}}, sphere_start, "kT"),
    ("a wall moving along its normal", {**good, "walls": {"normal": "y", "velocity": [0, 1, 0]}}, sphere_start, "walls.velocity"),
    ("a warm-up of half an LB step", {**good, "fluid": {"warmup_steps": 3}}, sphere_start, "fluid.warmup_steps"),
    ("allow_unstable for a fixed body", {**good, "raspberries": {"xi_bead": 200, "fixed": True, "allow_unstable": True}}, sphere_start,
     "raspberries.allow_unstable"),
    ("no raspberries block", {k: v for k, v in good.items() if k != "raspberries"}, sphere_start, "raspberries"),
    ("an unknown fluid key", {**good, "fluid": {"viscosty": 0.8}}, sphere_start, "fluid.viscosty"),
]
for what, cfg, start, path in bad_lb:
    expect_bad_input(what, [tool("anisodyn-lb"), "--config", write("bad.json", cfg), "--input", start, "--output", "bad.h5"],
                     [path, ("bad.json", start)])
# A raspberry that reaches into the wall layer: the sphere (centre 8, reach 2.25) against a wall at x = 0 in a box of 10 along x.
near = config("near", SPHERE, [10, 16, 16])
with h5py.File(near, "r+") as f:
    p = f["particles/all/position/value"]
    new = p[0]
    new[0, 0] = 3.0
    p[0] = new
expect_bad_input("a raspberry crossing the wall layer", [tool("anisodyn-lb"), "--config", write("bad.json", {**good, "walls": {"normal": "x"}}),
                                                         "--input", near, "--output", "bad.h5"], ["walls.normal", "bad.json"])

# 5. A pore (spec 40 §6): the raspberry's inner layer against the wall beads keeps its centre within
# R_pore - R of the axis (up to the WCA's soft edge); the pore's own bad input.
pore_cfg = {"seed": 1, "placement": "centre", "species": [{"name": "body", "shape": SPHERE}], "composition": [{"species": "body", "count": 1}],
            "box": {"edges": [24, 24, 20]}}
r = run([tool("anisodyn-config"), "-q", "--config", write("pore_config.json", pore_cfg), "--output", "pore_start.h5"])
assert r.returncode == 0, r.stderr
with h5py.File("pore_start.h5", "r+") as f:  # start against the wall: 1.2 off the axis in a pore of radius 3.6 (gap 1.35)
    f["particles/all/position/value"][0] = np.array([[13.2, 12.0, 10.0]])
pore_run = {"seed": 2, "time_step": 0.01, "steps": 2000, "observe_every": 100, "frames": {"every_steps": 20}, "fluid": {"warmup_steps": 0},
            "raspberries": {"xi_bead": 200}, "pore": {"radius": 3.6}}
r = run([tool("anisodyn-lb"), "-q", "--config", write("pore.json", pore_run), "--input", "pore_start.h5", "--output", "pore.h5"])
assert r.returncode == 0, r.stderr
with h5py.File("pore.h5") as f:
    x = f["particles/all/position/value"][:, 0, :]
    wall, _ = observable(f, "pore_force")
d = np.hypot(x[:, 0] - 12, x[:, 1] - 12)
print(f"raspberry R = 2.25 in a pore of radius 3.6: distance from the axis {d.min():.3f} ... {d.max():.3f} (gap 1.35); "
      f"largest mean wall force per row {np.abs(wall).max():.3g}")
assert np.abs(wall).max() > 0  # it did meet the wall
assert d.max() < 1.35 + 0.3, d.max()  # the WCA edge is soft by a fraction of sigma's 1/6-power range
bad_pore = [
    ("a raspberry outside the pore", {**good, "pore": {"radius": 3.0}}, "pore_start.h5", "pore.radius"),
    ("wall beads outside the box", {**good, "pore": {"radius": 8.0}}, "pore_start.h5", "pore.radius"),
    ("walls and a pore", {**good, "pore": {"radius": 3.6}, "walls": {"normal": "x"}}, "pore_start.h5", "pore"),
    ("placement centre for two bodies", None, None, "composition"),
]
for what, cfg, start, path in bad_pore:
    if cfg is None:
        expect_bad_input(what, [tool("anisodyn-config"), "--config", write("bad.json", {**pore_cfg, "composition": [{"species": "body", "count": 2}]}),
                                "--output", "bad.h5"], [path, "bad.json"])
        continue
    expect_bad_input(what, [tool("anisodyn-lb"), "--config", write("bad.json", cfg), "--input", start, "--output", "bad.h5"], [path, ("bad.json", start)])

# 6. anisodyn-lb-checks (studies D0, D1) refuses what it cannot run, writing nothing (the smoke runs it).
for what, cfg, path in (("a lattice too small", {"box": 3}, "box"), ("too few steps for 10 blocks", {"lb_steps": 50}, "lb_steps"),
                        ("one mobility position", {"mobility_positions": 1}, "mobility_positions"),
                        ("an unknown key", {"viscosity": 0.1}, "viscosity"), ("an unknown suite", {"suite": "pore"}, "suite"),
                        ("a fluid key in the analytic suite", {"suite": "analytic", "box": 24}, "box"),
                        ("an analytic key in the fluid suite", {"bodies": 100}, "bodies")):
    expect_bad_input(what, [tool("anisodyn-lb-checks"), "--config", write("bad.json", cfg), "--output", "bad.h5"], [path, "bad.json"])
expect_bad_input("an input file", [tool("anisodyn-lb-checks"), "--config", write("bad.json", {}), "--input", sphere_start, "--output", "bad.h5"],
                 ["--input"])

# 7. The single-layer ablation (spec 40 §6): the same body without its outer layer.
single = {**free, "steps": 20, "fluid": {"warmup_steps": 0}, "raspberries": {"xi_bead": 200, "layers": "single"}}
r = run([tool("anisodyn-lb"), "-q", "--config", write("single.json", single), "--input", sphere_start, "--output", "single.h5"])
assert r.returncode == 0, r.stderr
layers = json.loads(r.stdout)["raspberries"]["bodies"]["body"]["layers"]
assert layers["outer"] == 0 and layers["inner"] == 38 and layers["centre"] == 1, layers
assert json.loads(r.stdout)["raspberries"]["layers"] == "single"
print(f"single-layer ablation: layers {layers}")
