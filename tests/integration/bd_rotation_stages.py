#!/usr/bin/env python3
"""Study B3's stages on anisodyn-bd runs (spec 20 §6.2, §6.3):

1. Method II end to end: free rods (reduced units, D_r = 0.5) with anisodyn-bd's external torque
   (βT_ex = 10 about z, βκ_c = 100) on 30 tagged rods; anisodyn-torque-drag must give
   D_r(φ)/D_r = 1 within 4 standard errors (a free rod turns at ⟨ω⟩ = D_r βT_ex);
2. Method III end to end: rods with the overlap-volume potential; anisodyn-restoring-torque writes
   its table and scalars, and the reconstructed C1 follows the direct one;
3. bad input exits 2, names the file and the path, and writes nothing: torque-drag on a run without
   external_torque, restoring-torque on a run without systematic_torque, unknown keys, a plateau
   given both ways, a word that belongs to no option (it used to be dropped silently).
argv: [1] build bin dir, [2] scratch dir, [3] source dir."""
import json
import os
import shutil
import sys

import h5py

bin_dir, tmp, source = sys.argv[1], sys.argv[2], sys.argv[3]
sys.path.insert(0, os.path.join(source, "tests", "support"))
from script_io import enter_scratch, tool_runner, write  # noqa: E402

enter_scratch(tmp)

run = tool_runner(bin_dir)


def scalar(path, name):
    with h5py.File(path) as f:
        return f["scalars/" + name][...]



rods = {"seed": 5, "placement": "random",
        "species": [{"name": "rod", "shape": {"type": "spherocylinder", "length": 5, "diameter": 0.1},
                     "D_trans": [1, 1, 2], "D_rot": [0.5, 0.5, 0]}],
        "composition": [{"species": "rod", "count": 150, "orientation": {"mode": "random"}}],
        "box": {"edges": [20, 20, 20]}}
r = run("anisodyn-config", "--config", write("rods.json", rods), "--output", "start.h5")
assert r.returncode == 0, r.stderr

# 1. Method II: 30 tagged free rods, D_r t = 1 (about 10 rad each). Caps out of reach: the default
# torque cap (a turn of 2d/(10ℓ) = 4e-3 rad per step) is reached now and then by the torque plus the
# confinement, and capped steps slow the rods (the stage reports them in its details). (A value,
# not null: anisodyn-bd reads "torque": null as the default step_bound, ConfigNode::has being false
# for null.)
tagged = list(range(30))
drag = {"seed": 2, "time_step": 2e-4, "steps": 10000, "frames": {"every_steps": 5000},
        "external_torque": {"particles": tagged, "torque_kT": 10, "axis": [0, 0, 1], "confinement_kT": 100, "record_every": 50},
        "caps": {"torque": 1e9}}
r = run("anisodyn-bd", "--config", write("drag.json", drag), "--input", "start.h5", "--output", "drag.h5")
assert r.returncode == 0, r.stderr
r = run("anisodyn-torque-drag", "--config", write("empty.json", {}), "--input", "drag.h5", "--output", "drag_out.h5")
assert r.returncode == 0, r.stderr
ratio, error = scalar("drag_out.h5", "Dr_phi_over_Dr")
with h5py.File("drag_out.h5") as f:
    assert json.loads(f["scalars/Dr_phi"].attrs["details"])["capped_torques"] == 0
assert abs(ratio - 1.0) < 4 * error and error < 0.05, (ratio, error)
print(f"Method II, free rods: D_r(phi)/D_r = {ratio:.4f} ± {error:.4f} (exact 1)")

# 2. Method III: rods with the potential
pot = {"seed": 3, "time_step": 1e-3, "steps": 1000, "frames": {"every_steps": 20}, "potential": {"type": "overlap_volume"}}
r = run("anisodyn-bd", "--config", write("pot.json", pot), "--input", "start.h5", "--output", "pot.h5")
assert r.returncode == 0, r.stderr
r = run("anisodyn-restoring-torque", "--config", write("plateau.json", {"plateau": {"t_min": 0.1, "t_max": 1.0}}),
        "--input", "pot.h5", "--output", "rt.h5")
assert r.returncode == 0, r.stderr
with h5py.File("rt.h5") as f:
    g = f["restoring_torque_rod"]
    t = g["time"][...]
    c = int(abs(t - 0.2).argmin())  # a lag with many origins (run/5); later lags have few
    c1, rec = g["C1"][c], g["C1_reconstructed"][c]
    tolerance = 4 * (g["C1_se"][c] ** 2 + g["C1_reconstructed_se"][c] ** 2) ** 0.5
    assert abs(rec - c1) < tolerance, (t[c], rec, c1, tolerance)
    ratio, error = f["scalars/Dr_phi_over_Dr_rod"][...]
    details = json.loads(f["scalars/Dr_phi_over_Dr_rod"].attrs["details"])
    assert details["plateau_t_min"] >= 0.1 and details["plateau_t_max"] <= 1.0 + 1e-9, details
    assert details["capped_torques"] > 0, details  # a random start overlaps: the caps act, and the stage says so
print(f"Method III, 150 rods with the potential (random start, {details['capped_torques']:.0f} capped torques): "
      f"D_r(phi)/D_r = {ratio:.4f} ± {error:.4f}; at t = {t[c]:.2f} C1 {c1:.4f}, reconstructed {rec:.4f} (tolerance {tolerance:.4f})")

# One --input takes several files (replicas), as repeating it does.
shutil.copy("pot.h5", "pot_copy.h5")
r = run("anisodyn-restoring-torque", "--config", "plateau.json", "--input", "pot.h5", "pot_copy.h5", "--output", "rt2.h5")
assert r.returncode == 0, r.stderr
with h5py.File("rt2.h5") as f:
    assert len(json.loads(f.attrs["inputs"])) == 2, f.attrs["inputs"]
print("--input pot.h5 pot_copy.h5: two replicas read")

# 3. bad input
bad = [
    ("a word that belongs to no option", ["anisodyn-restoring-torque", "--config", "empty.json", "stray_word", "--input", "pot.h5"],
     ["command line", "stray_word"]),
    ("torque-drag without external_torque", ["anisodyn-torque-drag", "--config", "empty.json", "--input", "pot.h5"],
     ["pot.h5", "/parameters/config", "external_torque"]),
    ("torque-drag: unknown key", ["anisodyn-torque-drag", "--config", write("bad_key.json", {"specis": "rod"}), "--input", "drag.h5"],
     ["bad_key.json", "specis"]),
    ("restoring-torque without systematic_torque", ["anisodyn-restoring-torque", "--config", "empty.json", "--input", "drag.h5"],
     ["drag.h5", "systematic_torque"]),
    ("restoring-torque: unknown key", ["anisodyn-restoring-torque", "--config", "bad_key.json", "--input", "pot.h5"],
     ["bad_key.json", "specis"]),
    ("restoring-torque: plateau given both ways",
     ["anisodyn-restoring-torque", "--config", write("both.json", {"plateau": {"t_min": 0.1, "t_max": 1}, "plateau_correlation": {"floor": 0.1}}),
      "--input", "pot.h5"], ["both.json", "plateau_correlation"]),
]
for what, cmd, words in bad:
    r = run(cmd[0], *cmd[1:], "--output", "bad.h5")
    assert r.returncode == 2, (what, r.returncode, r.stderr)
    assert all(w in r.stderr for w in words), (what, r.stderr)
    assert not any(f.startswith("bad.") for f in os.listdir(".")), what
    print(f"bad input, {what}: exit 2: {r.stderr.strip().splitlines()[-1][:160]}")
