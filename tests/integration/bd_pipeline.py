#!/usr/bin/env python3
"""anisodyn-config -> anisodyn-bd end to end on rods with the overlap-volume potential (reduced units):

1. an uninterrupted run; its summary, units, observables (order tensor, caps, energy) and frames;
2. SIGINT (exit 130, checkpoint, no output) then resumed, and SIGKILL after a periodic checkpoint
   then resumed: both bit for bit the uninterrupted output and the same summary;
3. `--replica 1` gives another trajectory from the same seed;
4. bad input exits 2, names the file and the JSON path, and writes nothing: a negative diffusion
   coefficient, an unknown key, a schedule (BD has no field to switch), a box smaller than twice
   the rods' cut-off, rods shorter than their diameter under the overlap-volume potential, SI units
   without a temperature, reduced units with a temperature, keys of the other potential.
"""
import json
import os
import sys
import subprocess
import time

import h5py
import numpy as np

bin_dir, tmp, source = sys.argv[1], sys.argv[2], sys.argv[3]
sys.path.insert(0, os.path.join(source, "tests", "support"))
from resume_checks import check_resumes, compare_outputs  # noqa: E402

os.makedirs(tmp, exist_ok=True)
os.chdir(tmp)
for f in os.listdir("."):
    os.remove(f)


def run(cmd):
    return subprocess.run(cmd, capture_output=True, text=True)


def tool(name):
    return os.path.join(bin_dir, name)


rods = {"seed": 3, "placement": "random",
        "species": [{"name": "rod", "shape": {"type": "spherocylinder", "length": 5, "diameter": 0.1},
                     "D_trans": [1, 1, 2], "D_rot": [0.5, 0.5, 0]}],
        "composition": [{"species": "rod", "count": 400, "orientation": {"mode": "random"}}],
        "box": {"edges": [20, 20, 20]}}
bd = {"seed": 4, "time_step": 1e-4, "steps": 8000, "observe_every": 100, "frames": {"every_steps": 1000},
      "potential": {"type": "overlap_volume"}}
json.dump(rods, open("rods.json", "w"))
json.dump(bd, open("bd.json", "w"))
r = run([tool("anisodyn-config"), "-q", "--config", "rods.json", "--output", "start.h5"])
assert r.returncode == 0, r.stderr


def bd_cmd(out, config="bd.json", extra=()):
    return [tool("anisodyn-bd"), "-q", "--config", config, "--input", "start.h5", "--output", out, "--checkpoint-every", "2000", *extra]


t0 = time.time()
r = run(bd_cmd("straight.h5"))
assert r.returncode == 0, r.stderr
duration = time.time() - t0
summary = json.loads(r.stdout)
assert summary["steps"] == 8000 and abs(summary["time"] - 0.8) < 1e-9, summary
assert summary["units"]["system"] == "reduced" and summary["potential"]["finite_length"] == "segment_distance", summary
with h5py.File("straight.h5") as f:
    steps = f["particles/all/position/step"][...]
    assert steps.tolist() == list(range(0, 8001, 1000)), steps
    group = f["observables"] if "order_tensor_rod" in f.get("observables", {}) else f["anisodyn/observables"]
    S = group["order_tensor_rod/value"][...]
    assert S.shape == (80, 6) and np.allclose(S[:, :3].sum(axis=1), 1.0), S.shape
    # The rows of `capped` add up to the summary's counts; the potential acts (its energy is seen).
    capped = group["capped/value"][...].sum(axis=0)
    assert capped.tolist() == [summary["capped_forces"], summary["capped_torques"]], (capped, summary)
    energy = group["potential_energy/value"][...]
    assert energy.max() > 0, "the overlap-volume potential never acted"
    # P_d(x) of the interacting pairs, summed over the observations, and D_eff = D <x> (spec 20 §5).
    hist = (f["observables"] if "pair_distance_histogram" in f.get("observables", {}) else
            f["anisodyn/observables"])["pair_distance_histogram/value"][...]
    assert hist.shape == (1, 100) and hist.sum() == summary["pair_distances"]["pairs"] > 0, (hist.shape, summary["pair_distances"])
    x = (np.arange(100) + 0.5) / 100
    assert abs((hist[0] * x).sum() / hist.sum() * 0.1 - summary["pair_distances"]["effective_diameter"]) < 1e-12
    assert 0 < summary["pair_distances"]["effective_diameter"] < 0.1
    # Method III's torque (spec 20 §6.3) rides with every frame, at the frame's configuration.
    torque = f["particles/all/systematic_torque/value"][...]
    assert torque.shape == (len(steps), 400, 3) and np.count_nonzero(torque.any(axis=2)) > 0, torque.shape
    print(f"uninterrupted: {duration:.1f} s; {len(steps)} frames; S_zz over the run {S[:, 2].mean():.4f} (isotropic 1/3); "
          f"energy per rod {energy.mean():.3g} kT; capped {summary['capped_forces']} forces, {summary['capped_torques']} torques; "
          f"{int(hist.sum())} interacting pairs, D_eff/D = {summary['pair_distances']['mean_x']:.3f}")

summaries = check_resumes(bd_cmd, "bd", "straight.h5", duration, run)
for s in summaries:
    assert json.loads(s) == summary, "a resumed run's summary differs from the uninterrupted run's"

r = run(bd_cmd("replica1.h5", extra=("--replica", "1")))
assert r.returncode == 0, r.stderr
with h5py.File("straight.h5") as a, h5py.File("replica1.h5") as b:
    assert not np.array_equal(a["particles/all/position/value"][-1], b["particles/all/position/value"][-1])
print("--replica 1: another trajectory")

# SI units with the slender-body friction of spec 20 §2: the rods of spec 20 (L = 0.88 µm,
# D = 14.8 nm, lengths in µm) in water at 300 K; 70-theory §5.1 gives D_par = 3.0603 µm²/s,
# D_perp = 1.5302 µm²/s, D_r = 23.711 1/s.
fd = {**rods, "species": [{"name": "rod", "shape": {"type": "spherocylinder", "length": 0.88, "diameter": 0.0148}}],
      "box": {"edges": [2.08, 2.08, 2.08]}, "composition": [{"species": "rod", "count": 50, "orientation": {"mode": "random"}}]}
json.dump(fd, open("fd.json", "w"))
r = run([tool("anisodyn-config"), "-q", "--config", "fd.json", "--output", "fd_start.h5"])
assert r.returncode == 0, r.stderr
si = {"seed": 1, "time_step": 5e-8, "steps": 200, "units": {"system": "SI", "length": 1e-6, "temperature": 300},
      "slender_body": {"rod": {"viscosity": 1e-3}}}
json.dump(si, open("si.json", "w"))
r = run([tool("anisodyn-bd"), "-q", "--config", "si.json", "--input", "fd_start.h5", "--output", "si.h5"])
assert r.returncode == 0, r.stderr
d = json.loads(r.stdout)["species"][0]
assert abs(d["D_parallel"] - 3.0603) < 5e-5 and abs(d["D_perpendicular"] - 1.5302) < 5e-5 and abs(d["D_rotation"] - 23.711) < 5e-4, d
with h5py.File("si.h5") as f:
    assert json.loads(f["parameters/provenance"][()])["units"]["system"] == "SI"
# an analysis of an SI run labels its results in the run's units (µm, s), not length and tau
json.dump({"species": "rod"}, open("msd.json", "w"))
r = run([tool("anisodyn-msd"), "-q", "--config", "msd.json", "--input", "si.h5", "--output", "si_msd.h5"])
assert r.returncode == 0, r.stderr
with h5py.File("si_msd.h5") as f:
    units = {k: f["scalars"][k].attrs["units"] for k in f["scalars"]}
    assert units["D_tot_rod"] == "um^2/s" and f["msd_rod/time"].attrs["units"] == "s", units
print(f"SI slender-body rods: D_par {d['D_parallel']:.5f} µm²/s, D_perp {d['D_perpendicular']:.5f} µm²/s, D_r {d['D_rotation']:.4f} 1/s")

# Method II (spec 20 §6.2): a torque of 10 kT about z on rods 0 and 1, confined to the xy plane.
m2 = {**bd, "steps": 2000, "external_torque": {"particles": [0, 1], "torque_kT": 10, "confinement_kT": 100, "record_every": 10}}
m2.pop("potential")
json.dump(m2, open("m2.json", "w"))
r = run(bd_cmd("m2.h5", "m2.json"))
assert r.returncode == 0, r.stderr
with h5py.File("m2.h5") as f:
    group = f["observables"] if "tagged_axes" in f.get("observables", {}) else f["anisodyn/observables"]
    axes = group["tagged_axes/value"][...]
    assert axes.shape == (200, 6), axes.shape
print(f"Method II run: tagged axes recorded {axes.shape}")

# Spheres with the pseudo-hard Mie core and a pulled tracer (the cross-engine check with DMC,
# tests/integration/validation_bd_dmc_hs.py): 200 spheres at eta = 0.2 plus a tracer pulled at
# Pe = 1 along z; no caps (null). The tracer's unwrapped centre is recorded for anisodyn-microrheology.
spheres = {"seed": 5, "placement": "random",
           "species": [{"name": "hs", "shape": {"type": "sphere", "diameter": 1.0}, "D_trans": [0.1, 0.1, 0.1]},
                       {"name": "tracer", "shape": {"type": "sphere", "diameter": 1.0}, "D_trans": [0.1, 0.1, 0.1]}],
           "composition": [{"species": "hs", "count": 200}, {"species": "tracer", "count": 1}], "box": {"packing_fraction": 0.2}}
json.dump(spheres, open("spheres.json", "w"))
r = run([tool("anisodyn-config"), "-q", "--config", "spheres.json", "--output", "spheres.h5"])
assert r.returncode == 0, r.stderr
hs = {"seed": 6, "time_step": 1e-5, "steps": 4000, "observe_every": 1000, "caps": {"force": None, "torque": None},
      "potential": {"type": "mie", "sigma": "barker_henderson"}, "tracer": {"species": "tracer", "pe": 1, "record_every": 100}}
json.dump(hs, open("hs.json", "w"))
r = run([tool("anisodyn-bd"), "-q", "--config", "hs.json", "--input", "spheres.h5", "--output", "hs.h5"])
assert r.returncode == 0, r.stderr
s = json.loads(r.stdout)
assert s["caps"] == {"force": None, "torque": None}, s["caps"]
assert s["potential"]["type"] == "mie" and s["potential"]["exponents"] == [50, 49], s["potential"]
assert abs(s["potential"]["sigma"]["hs"] * s["potential"]["barker_henderson_diameter_over_sigma"] - 1.0) < 1e-12, s["potential"]
assert s["tracer"]["beta_force"] == 2.0, s["tracer"]  # Pe / a with a = 1/2
with h5py.File("hs.h5") as f:
    obs = f["observables"]
    path = obs["tracer_position/value"][...]
    assert path.shape == (40, 3) and obs["tracer_position"].attrs["definition"], path.shape
    assert obs["potential_energy/value"][-1] > 0, "the Mie cores of a fluid at eta = 0.2 touch"
print(f"Mie spheres + pulled tracer: sigma {s['potential']['sigma']['hs']:.6f}, tracer moved {path[-1, 2] - path[0, 2]:+.4f} along z")

bad = [
    ("Mie key for the overlap volume", {**bd, "potential": {"type": "overlap_volume", "exponent": 50}}, "potential.exponent"),
    ("overlap-volume key for Mie", {**bd, "potential": {"type": "mie", "hardness": 1}}, "potential.hardness"),
    ("Mie between rods", {**bd, "potential": {"type": "mie", "species": ["rod"]}}, "potential.species[0]"),
    ("tracer species with 400 particles", {**bd, "tracer": {"species": "rod", "pe": 1}}, "tracer.species"),
    ("negative D_trans", {**bd, "species": {"rod": {"D_trans": [-1, 1, 2]}}}, "species.rod.D_trans"),
    ("unknown key", {**bd, "tme_step": 1}, "tme_step"),
    ("schedule", {**bd, "schedule": {"segments": [{"field": "on", "steps": 10}]}}, "schedule"),
    ("SI without temperature", {**bd, "units": {"system": "SI", "length": 1e-6}}, "units.temperature"),
    ("temperature in reduced units", {**bd, "units": {"temperature": 300}}, "units.temperature"),
    ("zero time step", {**bd, "time_step": 0}, "time_step"),
    ("caps for free rods", {k: v for k, v in {**bd, "caps": {"force": 1}}.items() if k != "potential"}, "caps"),
    ("slender body and species entry", {**bd, "species": {"rod": {"D_trans": [1, 1, 2]}}, "slender_body": {"rod": {"viscosity": 1}}},
     "slender_body.rod"),
    ("external torque on an unknown particle", {**bd, "external_torque": {"particles": [4000], "torque_kT": 10}},
     "external_torque.particles[0]"),
    ("slender body of an unknown species", {**bd, "slender_body": {"disc": {"viscosity": 1}}}, "slender_body.disc"),
]
for what, config, path in bad:
    json.dump(config, open("bad.json", "w"))
    r = run(bd_cmd("bad.h5", "bad.json"))
    assert r.returncode == 2, (what, r.returncode, r.stderr)
    assert "bad.json" in r.stderr and path in r.stderr, (what, r.stderr)
    assert not any(n.startswith("bad.h5") for n in os.listdir(".")), (what, os.listdir("."))
    print(f"bad input ({what}): exit 2, {r.stderr.strip()[:110]}")

small = {**rods, "box": {"edges": [9, 9, 9]}, "composition": [{"species": "rod", "count": 5, "orientation": {"mode": "random"}}]}
json.dump(small, open("small.json", "w"))
r = run([tool("anisodyn-config"), "-q", "--config", "small.json", "--output", "small.h5"])
if r.returncode == 0:  # the builder may already refuse it; then the engine must too
    r = run([tool("anisodyn-bd"), "-q", "--config", "bd.json", "--input", "small.h5", "--output", "bad.h5"])
assert r.returncode == 2 and not os.path.exists("bad.h5"), (r.returncode, r.stderr)
print(f"box below twice the cut-off: exit 2, {r.stderr.strip()[:110]}")

stubby = {**rods, "species": [{**rods["species"][0], "shape": {"type": "spherocylinder", "length": 0.05, "diameter": 0.1}}]}
json.dump(stubby, open("stubby.json", "w"))
r = run([tool("anisodyn-config"), "-q", "--config", "stubby.json", "--output", "stubby.h5"])
assert r.returncode == 0, r.stderr
r = run([tool("anisodyn-bd"), "-q", "--config", "bd.json", "--input", "stubby.h5", "--output", "bad.h5"])
assert r.returncode == 2 and "bd.json" in r.stderr and "potential.species" in r.stderr, (r.returncode, r.stderr)
assert not any(n.startswith("bad.h5") for n in os.listdir(".")), os.listdir(".")
print(f"rods shorter than their diameter: exit 2, {r.stderr.strip()[:110]}")
print("1 passed, 0 failed")
