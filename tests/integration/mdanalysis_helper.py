#!/usr/bin/env python3
"""workflows/anisodyn_mda.py: universe(path) on a trajectory written by the engine's H5MD writer
(anisodyn-h5md-example: two species, particles crossing the periodic box, a box that changes
between frames) against the raw datasets read with h5py:
  - atom types are the species names of the particles, masses and ids those of the file, one
    residue per particle;
  - at every frame (iteration and random access) ts.data["orientation"] and ts.data["image"] equal
    that frame's datasets bit for bit, positions are the wrapped ones, or with unwrap=True the
    unwrapped ones (position + image * L of that frame; the file has particles with non-zero images);
  - further transformations run after the helper's; a pickled Universe reads the same data;
  - a file whose species change between frames is refused with a ValueError.
argv: [1] build bin dir, [2] scratch dir, [3] source dir. Exit 77 = skipped (no MDAnalysis)."""
import os
import pickle
import shutil
import subprocess
import sys

bin_dir, scratch, source = sys.argv[1], sys.argv[2], sys.argv[3]
sys.path.insert(0, os.path.join(source, "workflows"))
try:
    import h5py
    import numpy as np
    from anisodyn_mda import import_mdanalysis, universe
    import_mdanalysis()
except Exception as exc:  # ImportError, or a broken installation
    print(f"SKIP: MDAnalysis/h5py/numpy not importable: {exc}")
    sys.exit(77)

shutil.rmtree(scratch, ignore_errors=True)
os.makedirs(scratch)
path = os.path.join(scratch, "example.h5")
N_ATOMS, N_FRAMES = 57, 6
subprocess.run([os.path.join(bin_dir, "anisodyn-h5md-example"), path, "--particles", str(N_ATOMS), "--frames", str(N_FRAMES),
                "--seed", "5"], check=True, capture_output=True)
failures = []


def check(cond, what):
    print(f"{'ok  ' if cond else 'FAIL'} {what}")
    if not cond:
        failures.append(what)


with h5py.File(path, "r") as f:
    g = f["particles/all"]
    raw = {name: g[f"{name}/value"][()] for name in ("position", "image", "orientation", "species", "id")}
    raw["lengths"] = np.array([np.diagonal(e) for e in g["box/edges/value"][()]])
    names = list(f["parameters/species/name"].asstr()[()])
    masses = f["parameters/species/mass"][()]
unwrapped = raw["position"] + raw["image"] * raw["lengths"][:, None, :]
check(np.count_nonzero(raw["image"]) > 0 and len(set(raw["species"][0])) == 2,
      f"the example file has particles with non-zero images ({np.count_nonzero(raw['image'])}) and two species")


def frame_matches(ts, want_positions):
    i = ts.frame
    return (np.array_equal(ts.data["orientation"], raw["orientation"][i]) and ts.data["orientation"].dtype == np.float64
            and np.array_equal(ts.data["image"], raw["image"][i])
            and np.allclose(ts.positions, want_positions[i], rtol=1e-6, atol=1e-5))  # MDAnalysis keeps float32 positions


u = universe(path)
check(list(u.atoms.types) == [names[s] for s in raw["species"][0]], "atom types are the species names")
check(np.array_equal(u.atoms.masses, masses[raw["species"][0]]), "masses from the species table")
check(np.array_equal(u.atoms.ids, raw["id"][0]) and len(u.residues) == N_ATOMS, "ids from the file, one residue per particle")
check(len(u.trajectory) == N_FRAMES, f"{len(u.trajectory)} frames")
check(all(frame_matches(ts, raw["position"]) for ts in u.trajectory), "every frame: orientations, images, wrapped positions")
check(frame_matches(u.trajectory[3], raw["position"]) and frame_matches(u.trajectory[1], raw["position"]),
      "random access (frame 3, then 1)")

seen = []


def after_helper(ts):
    seen.append("orientation" in ts.data and ts.data["orientation"] is not None and np.array_equal(ts.data["image"], raw["image"][ts.frame]))
    return ts


u = universe(path, unwrap=True, transformations=[after_helper])
check(all(frame_matches(ts, unwrapped) for ts in u.trajectory), "unwrap=True: every frame's positions are position + image * L")
check(seen and all(seen), f"a further transformation runs after the helper's ({len(seen)} calls)")
copy = pickle.loads(pickle.dumps(u))
check(frame_matches(copy.trajectory[4], unwrapped), "a pickled Universe reads the same frame data")

changing = os.path.join(scratch, "changing.h5")
shutil.copy(path, changing)
with h5py.File(changing, "r+") as f:
    f["particles/all/species/value"][2, 0] = 1 - f["particles/all/species/value"][2, 0]
try:
    universe(changing)
    check(False, "species that change between frames are refused")
except ValueError as e:
    check("species" in str(e), f"species that change between frames are refused: {e}")

print(f"{len(failures)} failed")
assert not failures, f"{len(failures)} check(s) failed: {failures}"
