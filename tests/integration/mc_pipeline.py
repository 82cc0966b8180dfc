#!/usr/bin/env python3
"""anisodyn-config -> anisodyn-mc on a board + sphere mixture, end to end:

1. an uninterrupted run;
2. the same run interrupted by SIGINT (must exit 130 and leave a checkpoint, no output), then resumed;
3. the same run killed by SIGKILL after a periodic checkpoint, then resumed;
both resumed runs must end bit-for-bit equal to the uninterrupted one (frame steps, positions,
orientations, box, every observable) and print the same summary (its phase statistics need the
interrupted phase's samples, which the resumed run reads back from its partial output). Then the MC output is opened with MDAnalysis's H5MD reader (skipped if
MDAnalysis is missing) and compared with h5py.
"""
import json
import os
import signal
import subprocess
import sys
import time

import h5py
import numpy as np

bin_dir, tmp, source = sys.argv[1], sys.argv[2], sys.argv[3]
sys.path.insert(0, os.path.join(source, "tests", "support"))
from resume_checks import check_resumes, interrupted  # noqa: E402

os.makedirs(tmp, exist_ok=True)
os.chdir(tmp)
for f in os.listdir("."):
    os.remove(f)

config = {
    "seed": 5,
    "species": [{"name": "board", "shape": {"type": "cuboid", "edges": [1, 3.4641, 12]}},
                {"name": "hs", "shape": {"type": "sphere", "diameter": 1.0}}],
    "composition": [{"species": "board", "count": 60, "orientation": {"mode": "random"}},
                    {"species": "hs", "count": 40}],
    "box": {"packing_fraction": 0.01},
}
mc = {"seed": 9, "observe_every": 10, "frames": {"every_cycles": 5000},
      "phases": [{"type": "compress", "packing_fraction": 0.06, "cycles_per_step": 100},
                 {"type": "nvt", "cycles": 3000, "tune": True},
                 {"type": "nvt", "cycles": 40000}]}
json.dump(config, open("config.json", "w"))
json.dump(mc, open("mc.json", "w"))


def run(args, **kw):
    return subprocess.run([os.path.join(bin_dir, args[0])] + args[1:], capture_output=True, text=True, **kw)


r = run(["anisodyn-config", "-q", "--config", "config.json", "--output", "start.h5"])
assert r.returncode == 0, r.stderr
mc_args = lambda out: ["anisodyn-mc", "-q", "--config", "mc.json", "--input", "start.h5", "--output", out, "--checkpoint-every", "2000"]

t0 = time.time()
r = run(mc_args("straight.h5"))
assert r.returncode == 0, r.stderr
duration = time.time() - t0
summary = json.loads(r.stdout)
print(f"uninterrupted run: {duration:.1f} s, final packing fraction {summary['final_packing_fraction']:.6f}")


full_args = lambda out: [os.path.join(bin_dir, a) if i == 0 else a for i, a in enumerate(mc_args(out))]
for resumed in check_resumes(full_args, "mc", "straight.h5", duration, lambda cmd: subprocess.run(cmd, capture_output=True, text=True)):
    assert json.loads(resumed) == summary, "the resumed run's summary differs from the uninterrupted run's"
print("resumed runs print the uninterrupted run's summary")

# A checkpoint from different parameters is refused with exit code 2.
code, _ = interrupted(full_args("other.h5"), signal.SIGINT, min(1.0, duration / 3))
assert code == 130
r = subprocess.run([os.path.join(bin_dir, "anisodyn-mc"), "-q", "--config", "mc.json", "--set", "seed=10", "--input", "start.h5",
                    "--output", "other.h5"], capture_output=True, text=True)
assert r.returncode == 2 and "checkpoint" in r.stderr, (r.returncode, r.stderr)
print("checkpoint with different parameters refused:", r.stderr.strip()[:120])

# MDAnalysis reads the MC output.
try:
    import MDAnalysis as mda
except ImportError:
    print("MDAnalysis not installed: interoperability check skipped")
    sys.exit(77)
with h5py.File("straight.h5") as f:
    pos = f["particles/all/position/value"][...]
    edges = f["particles/all/box/edges/value"][...]
u = mda.Universe.empty(pos.shape[1], trajectory=True)
u.load_new("straight.h5", format="H5MD", convert_units=False)
assert u.atoms.n_atoms == 100, u.atoms.n_atoms
assert len(u.trajectory) == pos.shape[0]
for k, ts in enumerate(u.trajectory):
    box = edges[k] if edges.ndim == 2 else np.diag(edges[k])
    assert np.allclose(ts.dimensions[:3], box, rtol=1e-6), (ts.dimensions, box)
    assert np.allclose(ts.positions, pos[k], rtol=1e-6, atol=1e-4)
print(f"MDAnalysis: {u.atoms.n_atoms} atoms, {len(u.trajectory)} frames, box and positions match")
print("1 passed, 0 failed")
