#!/usr/bin/env python3
"""The analysis executables end to end on real engine output: anisodyn-config -> anisodyn-dmc (three
replicas of a dilute board fluid with log-spaced frames), then every analysis stage over the replica
glob. Checks the output contract (architecture §4): HDF5 datasets with units and definition
attributes, root attributes tool_version and inputs (paths with SHA-256 equal to hashlib's), CSV
files beside the HDF5 file; and the bad-input contract: a missing dataset, frames out of order, a
director requested for an isotropic box, mismatched replicas, an unknown key and a glob matching
nothing each exit 2 with a message naming the problem, and write nothing. Time windows: a windowed
stage analyses the frames inside on the replicas' common grid and records the window (root attribute,
CSV line); a bad window (from >= to, stride 0, an unknown key, no frame or too few for a lag), the
refused frame keys (structure frames, clusters t_min) and director_species without a director exit 2.
"""
import glob
import hashlib
import json
import os
import shutil
import subprocess
import sys

import h5py
import numpy as np

bin_dir, tmp = sys.argv[1], sys.argv[2]
shutil.rmtree(tmp, ignore_errors=True)
os.makedirs(tmp)
os.chdir(tmp)


def run(args):
    return subprocess.run([os.path.join(bin_dir, args[0])] + args[1:], capture_output=True, text=True)


config = {"seed": 3,
          "species": [{"name": "board", "shape": {"type": "cuboid", "edges": [1, 3.4641, 12]},
                       "D_trans": [0.02, 0.024, 0.03], "D_rot": [0.0008, 0.001, 0.01]}],
          "composition": [{"species": "board", "count": 40, "orientation": {"mode": "random"}}],
          "box": {"edges": [30, 30, 30]}, "placement": "random"}
json.dump(config, open("config.json", "w"))
assert run(["anisodyn-config", "-q", "--config", "config.json", "--output", "start.h5"]).returncode == 0


def dmc(name, seed, time):
    json.dump({"seed": seed, "time": time, "time_step": {"board": 0.05}, "balance": {"mode": "per_cycle", "reference": "board"},
               "frames": {"log_first_time": 0.05, "log_per_decade": 8, "every_time": 1.0}}, open(f"{name}.json", "w"))
    r = run(["anisodyn-dmc", "-q", "--config", f"{name}.json", "--input", "start.h5", "--output", f"{name}.h5"])
    assert r.returncode == 0, r.stderr


for k in range(3):
    dmc(f"rep{k}", 10 + k, 20.0)
os.makedirs("odd")
dmc("odd/short", 20, 10.0)  # fewer frames: a mismatched replica


def check_output(path, tool):
    with h5py.File(path) as f:
        assert f.attrs["tool"] == tool, dict(f.attrs)
        assert "tool_version" in f.attrs
        inputs = json.loads(f.attrs["inputs"])
        assert [i["path"] for i in inputs] == sorted(glob.glob("rep*.h5")), inputs
        for i in inputs:
            assert i["sha256"] == hashlib.sha256(open(i["path"], "rb").read()).hexdigest()
        datasets = []
        f.visititems(lambda n, o: datasets.append((n, o)) if isinstance(o, h5py.Dataset) and n not in ("parameters", "provenance") else None)
        assert datasets, path
        for n, d in datasets:
            assert "units" in d.attrs and "definition" in d.attrs, n
        return {n: d[()] for n, d in datasets}
    

def stage(tool, params, out):
    json.dump(params, open(f"{out}.json", "w"))
    r = run([tool, "-q", "--config", f"{out}.json", "--input", "rep*.h5", "--output", f"{out}.h5"])
    assert r.returncode == 0, (tool, r.stderr)
    data = check_output(f"{out}.h5", tool)
    csvs = glob.glob(f"{out}.*.csv")
    assert csvs, f"no CSV beside {out}.h5"
    print(f"{tool}: {len(data)} datasets, CSV: {sorted(os.path.basename(c) for c in csvs)}")
    return data


d = stage("anisodyn-msd", {"species": "board", "body_frame": True}, "msd")
D = d["scalars/D_tot_board"]
assert D[0] > 0 and np.isfinite(D[1]), D
assert np.all(np.diff(d["msd_board/time"]) > 0)
d = stage("anisodyn-rotation", {"axes": ["L"]}, "rotation")
assert d["scalars/Dr_msad_L_board"][0] > 0
assert d["rotation_board/C1_L"][0] <= 1.0
d = stage("anisodyn-vanhove", {"times": [0.5, 5.0], "components": ["tot", "x"], "angular_axes": ["L"]}, "vanhove")
assert np.all(d["vanhove_board/G"] >= 0)
d = stage("anisodyn-clusters", {"mode": "nematic", "axis": "L", "K_par": 12.25, "K_perp": 1.55}, "clusters")
assert d["scalars/N_tot"][0] > 0
d = stage("anisodyn-clusters", {"mode": "dipolar", "gamma": 13.0}, "chains")
assert np.all(np.isfinite(d["chain_statistics/X_c"]))
d = stage("anisodyn-order", {}, "order")
U = d["order_board/U"]
assert np.all((U >= 0) & (U <= 1)), U
d = stage("anisodyn-structure", {"reference": "none", "dr": 0.5}, "structure")
assert np.all(np.isfinite(d["structure_board_board/g"]))

# ---- time windows: the frames inside, recorded in the output -------------------------------------
d = stage("anisodyn-msd", {"species": "board", "window": {"from": 2.0, "to": 15.0, "stride": 2}}, "msd_window")
with h5py.File("msd_window.h5") as f:
    w = json.loads(f.attrs["window"])
grid = np.mean([h5py.File(p)["particles/all/position/time"][()] for p in sorted(glob.glob("rep*.h5"))], axis=0)
inside = np.flatnonzero((grid >= 2.0) & (grid <= 15.0))[::2]
assert (w["from"], w["to"], w["stride"], w["frames"]) == (2.0, 15.0, 2, len(inside)), w
assert (w["first_frame"], w["last_frame"]) == (inside[0], inside[-1]), w
assert d["msd_board/time"].max() <= grid[inside[-1]] - grid[inside[0]] + 1e-9, d["msd_board/time"].max()
assert open("msd_window.msd_board.csv").readline().startswith("# window: {"), "no window line in the CSV"
with h5py.File("msd.h5") as f:
    assert "window" not in f.attrs  # no window, no record
d = stage("anisodyn-order", {"window": {"from": 3.0, "to": 9.0}}, "order_window")
assert d["order_board/time"].min() >= 3.0 and d["order_board/time"].max() <= 9.0, d["order_board/time"]  # trajectory time
d = stage("anisodyn-structure", {"reference": "none", "dr": 0.5, "window": {"to": 5.0}}, "structure_window")
assert d["scalars/particles_board_board"][0] == 40
print(f"windows: msd over frames {inside[0]}-{inside[-1]} stride 2 ({len(inside)} frames), order and structure windowed")

# ---- bad input: exit 2, a message naming the problem, nothing written ----------------------------
with h5py.File("rep0.h5") as src:
    with h5py.File("no_image.h5", "w") as dst:
        for key in src:
            src.copy(key, dst)
        del dst["particles/all/image"]
shutil.copy("rep0.h5", "unordered.h5")
with h5py.File("unordered.h5", "r+") as f:
    t = f["particles/all/position/time"]
    v = t[()]
    v[3], v[4] = v[4], v[3]
    t[...] = v
json.dump({}, open("empty.json", "w"))
json.dump({"reference": "director"}, open("director.json", "w"))
json.dump({"reference": "director", "dr": 0.5}, open("structure_director.json", "w"))
json.dump({"lags_per_decde": 5}, open("typo.json", "w"))
json.dump({"window": {"from": 5.0, "to": 5.0}}, open("window_empty_range.json", "w"))
json.dump({"window": {"stride": 0}}, open("window_stride.json", "w"))
json.dump({"window": {"from": 1.0, "too": 3.0}}, open("window_key.json", "w"))
json.dump({"window": {"from": 100.0}}, open("window_late.json", "w"))
one = int(np.argmin(np.abs(grid - 5.0)))  # a window around one frame of the common grid
json.dump({"window": {"from": grid[one] - 1e-6, "to": grid[one] + 1e-6}}, open("window_one_frame.json", "w"))
json.dump({"frames": {"first": 2}}, open("structure_frames.json", "w"))
json.dump({"mode": "nematic", "axis": "L", "K_par": 12.25, "K_perp": 1.55, "t_min": 5}, open("clusters_t_min.json", "w"))
json.dump({"reference": "axes", "director_species": "board"}, open("director_species.json", "w"))
cases = [
    ("missing dataset", ["anisodyn-msd", "--config", "empty.json", "--input", "no_image.h5"], "particles/all/image"),
    ("frames out of order", ["anisodyn-msd", "--config", "empty.json", "--input", "unordered.h5"], "frames out of order"),
    ("director in an isotropic box", ["anisodyn-msd", "--config", "director.json", "--input", "rep*.h5"], "no orientational order"),
    ("mismatched replicas", ["anisodyn-msd", "--config", "empty.json", "--input", "rep*.h5", "--input", "odd/short.h5"], "mismatched replicas"),
    ("structure: director in an isotropic box", ["anisodyn-structure", "--config", "structure_director.json", "--input", "rep*.h5"], "director"),
    ("unknown key", ["anisodyn-msd", "--config", "typo.json", "--input", "rep*.h5"], "lags_per_decade"),
    ("glob matching nothing", ["anisodyn-rotation", "--config", "empty.json", "--input", "nothing*.h5"], "no input file matches"),
    ("rotation: frames out of order", ["anisodyn-rotation", "--config", "empty.json", "--input", "unordered.h5"], "frames out of order"),
    ("window: from >= to", ["anisodyn-msd", "--config", "window_empty_range.json", "--input", "rep*.h5"], "at window.to"),
    ("window: stride 0", ["anisodyn-rotation", "--config", "window_stride.json", "--input", "rep*.h5"], "at window.stride"),
    ("window: unknown key", ["anisodyn-order", "--config", "window_key.json", "--input", "rep*.h5"], "window.too"),
    ("window: no frame", ["anisodyn-structure", "--config", "window_late.json", "--input", "rep*.h5"], "selects 0 frame(s) of rep0.h5"),
    ("window: one frame for a lag", ["anisodyn-msd", "--config", "window_one_frame.json", "--input", "rep*.h5"], "needs at least 2"),
    ("structure: frame indices", ["anisodyn-structure", "--config", "structure_frames.json", "--input", "rep*.h5"], "at frames"),
    ("clusters: t_min", ["anisodyn-clusters", "--config", "clusters_t_min.json", "--input", "rep*.h5"], "at t_min"),
    ("msd: director_species without a director", ["anisodyn-msd", "--config", "director_species.json", "--input", "rep*.h5"], "at director_species"),
]
for name, args, expected in cases:
    out = "bad_" + name.replace(" ", "_").replace(":", "")
    r = run(args + ["--output", f"{out}.h5"])
    assert r.returncode == 2, (name, r.returncode, r.stderr)
    assert expected in r.stderr, (name, r.stderr)
    left = glob.glob(f"{out}*")
    assert not left, (name, left)
    print(f"bad input '{name}': exit 2: {r.stderr.strip()}")
print("analysis tools: all checks passed")
