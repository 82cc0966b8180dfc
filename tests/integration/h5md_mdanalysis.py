#!/usr/bin/env python3
"""H5MD files written by anisodyn open in MDAnalysis (architecture §4: MDAnalysis's H5MD reader is
the check). Runs anisodyn-h5md-example, then reads the file with MDAnalysis and compares the number
of atoms, the box and the positions of every frame with the raw datasets (h5py) and with the
summary the tool prints. Also checks that observables sampled more often than frames stay readable
and that sparser ones were moved out of /observables.

argv: [1] build bin dir, [2] scratch dir, [3] source dir. Exit 77 = skipped (no MDAnalysis/h5py).
"""
import json
import os
import subprocess
import sys
import warnings

try:
    import numpy as np
    import h5py
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        import MDAnalysis as mda
except Exception as exc:  # ImportError, or a broken installation
    print(f"SKIP: MDAnalysis/h5py/numpy not importable: {exc}")
    sys.exit(77)

bin_dir, scratch = sys.argv[1], sys.argv[2]
os.makedirs(scratch, exist_ok=True)
path = os.path.join(scratch, "example.h5")
if os.path.exists(path):
    os.remove(path)

failures = []


def check(condition, message):
    if not condition:
        failures.append(message)
        print("FAIL:", message)


n_atoms, n_frames = 57, 5
tool = os.path.join(bin_dir, "anisodyn-h5md-example")
run = subprocess.run([tool, path, "--particles", str(n_atoms), "--frames", str(n_frames), "--seed", "11"],
                     capture_output=True, text=True)
if run.returncode != 0:
    print(run.stdout, run.stderr)
    sys.exit(f"anisodyn-h5md-example failed with exit code {run.returncode}")
summary = json.loads(run.stdout)
check(not os.path.exists(path + ".partial"), "partial file left behind")

# A bad output directory is refused with exit code 2 and nothing is written.
bad = subprocess.run([tool, os.path.join(scratch, "no-such-dir", "x.h5")], capture_output=True, text=True)
check(bad.returncode == 2, f"bad output path gave exit code {bad.returncode}, expected 2")
check("cannot write output" in bad.stderr, f"unexpected message for bad output path: {bad.stderr!r}")
check(not os.path.exists(os.path.join(scratch, "no-such-dir")), "bad output path created a directory")

# ---- raw datasets ---------------------------------------------------------------------------------
with h5py.File(path, "r") as f:
    check(list(f["h5md"].attrs["version"]) == [1, 1], "h5md version attribute is not [1, 1]")
    check(list(f["particles"].keys()) == ["all"], f"particle groups: {list(f['particles'].keys())}")
    pos = f["particles/all/position/value"][()]
    steps = f["particles/all/position/step"][()]
    times = f["particles/all/position/time"][()]
    edges = f["particles/all/box/edges/value"][()]
    obs_names = sorted(f["observables"].keys()) if "observables" in f else []
    obs_rows = {k: f["observables"][k]["value"].shape[0] for k in obs_names}
    moved = sorted(f["anisodyn/observables"].keys()) if "anisodyn/observables" in f else []
    species_names = [s.decode() if isinstance(s, bytes) else s for s in f["parameters/species/name"][()]]
    config = json.loads(f["parameters/config"][()])
    provenance = json.loads(f["parameters/provenance"][()])
    checkpoint = json.loads(f["anisodyn/checkpoint/engine_state"][()])

check(pos.shape == (n_frames, n_atoms, 3), f"position shape {pos.shape}")
check(pos.dtype == np.float64, f"position dtype {pos.dtype}")
check(edges.shape == (n_frames, 3, 3), f"box edges shape {edges.shape}")
check(np.array_equal(edges, np.array([np.diag(e) for e in summary["box"]])), "box edges differ from the tool's summary")
check(list(steps) == summary["steps"], "steps differ from the tool's summary")
check(np.allclose(times, summary["times"], rtol=0, atol=0), "times differ from the tool's summary")
for f_idx in range(n_frames):
    L = np.array(summary["box"][f_idx])
    check(np.all(pos[f_idx] >= 0) and np.all(pos[f_idx] < L), f"frame {f_idx}: positions not wrapped into the box")
check(obs_names == ["acceptance", "packing_fraction"], f"observables: {obs_names}")
check(all(r > n_frames for r in obs_rows.values()), f"observable rows {obs_rows} (expected more than frames)")
check(moved == ["sparse_energy"], f"/anisodyn/observables holds {moved}, expected ['sparse_energy']")
check(species_names == ["board", "bead"], f"species names {species_names}")
check(config.get("particles") == n_atoms, f"parameters/config {config}")
check(provenance.get("tool") == "anisodyn-h5md-example", f"provenance {provenance}")
check(checkpoint.get("step") == summary["steps"][-1], f"checkpoint {checkpoint}")

# ---- MDAnalysis -----------------------------------------------------------------------------------
# MDAnalysis has no H5MD topology parser (and its minimal-topology path only looks at a particle
# group called 'trajectory'), so an empty topology with the right number of atoms is used. The
# files carry reduced units without `unit` attributes, hence convert_units=False.
with warnings.catch_warnings():
    warnings.simplefilter("ignore")
    u = mda.Universe.empty(n_atoms, trajectory=True)
    u.load_new(path, format="H5MD", convert_units=False)

check(u.atoms.n_atoms == n_atoms, f"MDAnalysis sees {u.atoms.n_atoms} atoms")
check(len(u.trajectory) == n_frames, f"MDAnalysis sees {len(u.trajectory)} frames")
seen = 0
for ts in u.trajectory:
    i = ts.frame
    seen += 1
    dims = ts.dimensions
    check(dims is not None, f"frame {i}: MDAnalysis found no box")
    if dims is not None:
        check(np.allclose(dims[:3], summary["box"][i], rtol=1e-6), f"frame {i}: box {dims[:3]} vs {summary['box'][i]}")
        check(np.allclose(dims[3:], 90.0), f"frame {i}: box angles {dims[3:]}")
    # MDAnalysis stores coordinates in float32.
    check(np.allclose(ts.positions, pos[i], rtol=1e-6, atol=1e-5), f"frame {i}: positions differ")
    check(int(ts.data["step"]) == summary["steps"][i], f"frame {i}: step {ts.data['step']}")
    check(abs(ts.time - summary["times"][i]) < 1e-9, f"frame {i}: time {ts.time}")
    check("packing_fraction" in ts.data and "acceptance" in ts.data, f"frame {i}: observables missing in ts.data")
    check("sparse_energy" not in ts.data, f"frame {i}: sparse observable visible to MDAnalysis")
check(seen == n_frames, f"iterated {seen} frames")

# Random access and the last frame.
ts = u.trajectory[-1]
check(np.allclose(ts.positions, pos[-1], rtol=1e-6, atol=1e-5), "last frame via random access differs")
u.trajectory.close()

assert not failures, f"{len(failures)} check(s) failed: " + "; ".join(failures[:5])
print(f"OK: MDAnalysis {mda.__version__} read {n_frames} frames of {n_atoms} particles")
