#!/usr/bin/env python3
"""anisodyn-bd output through the BD rod analysis stages (spec 20 §5, §7, §9), end to end in seconds:

1. two replicas of 200 aligned rods (L/D = 50) with the overlap-volume potential decaying to isotropy;
2. anisodyn-pair-distances: D_eff/D is the mean of the per-replica <x> of the engine's summaries,
   with their standard error; P_d integrates to 1; the box edge is (250 pi L^2 D_eff)^(1/3);
3. anisodyn-order-relaxation, decay and regression: a finite D_r^coll with its window, the decay
   table's S_zz equal to the mean of the observables' rows, D_r^coll/D_r0 from the species table;
4. anisodyn-closure: both sides per frame, equal to the rod axes' moments computed here;
5. bad input exits 2, names the file and the JSON or HDF5 path, and writes nothing: no histogram
   (a run without the potential), an unknown method, keys of the other method, a window for the
   histogram, no order-tensor observable.
"""
import json
import math
import os
import sys

import h5py
import numpy as np

bin_dir, tmp, source = sys.argv[1], sys.argv[2], sys.argv[3]
sys.path.insert(0, os.path.join(source, "tests", "support"))
from script_io import enter_scratch, tool_runner, write  # noqa: E402

enter_scratch(tmp)

run = tool_runner(bin_dir)



rods = {"seed": 3, "placement": "random",
        "species": [{"name": "rod", "shape": {"type": "spherocylinder", "length": 5, "diameter": 0.1},
                     "D_trans": [1, 1, 2], "D_rot": [0.5, 0.5, 0]}],
        "composition": [{"species": "rod", "count": 200, "orientation": {"mode": "aligned", "axis": "L"}}],
        "box": {"edges": [20, 20, 20]}}
bd = {"seed": 4, "time_step": 1e-3, "steps": 2000, "observe_every": 10, "frames": {"every_steps": 100},
      "potential": {"type": "overlap_volume"}}
r = run("anisodyn-config", "--config", write("rods.json", rods), "--output", "start.h5")
assert r.returncode == 0, r.stderr
summaries = []
for k in range(2):
    r = run("anisodyn-bd", "--config", write("bd.json", bd), "--input", "start.h5", "--output", f"rep{k}.h5", "--replica", str(k))
    assert r.returncode == 0, r.stderr
    summaries.append(json.loads(r.stdout))
free = {k: v for k, v in bd.items() if k != "potential"}
r = run("anisodyn-bd", "--config", write("free.json", free), "--input", "start.h5", "--output", "free.h5")
assert r.returncode == 0, r.stderr


def scalars(path):
    with h5py.File(path) as f:
        return {k: tuple(f["scalars"][k][...]) for k in f["scalars"]}


# 2. effective diameter
r = run("anisodyn-pair-distances", "--config", write("pd.json", {}), "--input", "rep*.h5", "--output", "pd.h5")
assert r.returncode == 0, r.stderr
s = scalars("pd.h5")
x = [m["pair_distances"]["mean_x"] for m in summaries]
assert abs(s["D_eff_over_D_rod"][0] - np.mean(x)) < 1e-12 and abs(s["D_eff_over_D_rod"][1] - np.std(x, ddof=1) / math.sqrt(2)) < 1e-12, (s, x)
assert abs(s["D_eff_rod"][0] - 0.1 * np.mean(x)) < 1e-12
assert abs(s["box_edge_rod"][0] - (250 * math.pi * 25 * 0.1 * np.mean(x)) ** (1 / 3)) < 1e-9
assert s["pairs_rod"][0] == np.mean([m["pair_distances"]["pairs"] for m in summaries])
with h5py.File("pd.h5") as f:
    assert abs(f["pair_distances_rod/P_d"][...].sum() * 0.01 - 1) < 1e-12
    assert f["scalars/D_eff_rod"].attrs["units"] == "length"
print(f"pair distances: D_eff/D = {s['D_eff_over_D_rod'][0]:.4f} ± {s['D_eff_over_D_rod'][1]:.4f}, "
      f"sigma_x {s['sigma_x_rod'][0]:.4f}, box edge {s['box_edge_rod'][0]:.3f}")

# 3. collective rotation, both methods
rows = []
for k in range(2):
    with h5py.File(f"rep{k}.h5") as f:
        group = f["observables"] if "order_tensor_rod" in f.get("observables", {}) else f["anisodyn/observables"]
        rows.append(group["order_tensor_rod/value"][...])
for method in ("decay", "regression"):
    r = run("anisodyn-order-relaxation", "--config", write(f"{method}.json", {"method": method}), "--input", "rep*.h5",
            "--output", f"{method}.h5")
    assert r.returncode == 0, r.stderr
    s = scalars(f"{method}.h5")
    rate, error = s["Dr_coll_rod"]
    assert math.isfinite(rate) and rate > 0, s
    assert abs(s["Dr_coll_over_Dr0_rod"][0] - rate / 0.5) < 1e-12
    with h5py.File(f"{method}.h5") as f:
        details = json.loads(f["scalars/Dr_coll_rod"].attrs["details"])
        assert details["fit_points"] >= 2 and details["fit_t_max"] > details["fit_t_min"], details
        if method == "decay":
            assert np.allclose(f["order_decay_rod/S_zz"][...], (rows[0][:, 2] + rows[1][:, 2]) / 2, atol=1e-12)
        else:
            assert f["order_correlation_rod/C_over_C0"][0] == 1.0
    print(f"{method}: D_r^coll = {rate:.4f} ± {error:.4f} (D_r of the free rods 0.5), window t = "
          f"[{details['fit_t_min']:.3f}, {details['fit_t_max']:.3f}]")

# 4. closure
r = run("anisodyn-closure", "--config", write("closure.json", {}), "--input", "rep*.h5", "--output", "closure.h5")
assert r.returncode == 0, r.stderr
with h5py.File("rep0.h5") as a, h5py.File("rep1.h5") as b, h5py.File("closure.h5") as c:
    def sides(q):  # rod axes (body z) from quaternions (w, x, y, z)
        w, x, y, z = q[..., 0], q[..., 1], q[..., 2], q[..., 3]
        u = np.stack([2 * (x * z + w * y), 2 * (y * z - w * x), 1 - 2 * (x * x + y * y)], axis=-1)
        S = np.einsum("fna,fnb->fab", u, u) / u.shape[1]
        exact = np.einsum("fna,fnb,fnc,fnd,fcd->fab", u, u, u, u, S) / u.shape[1]
        ss = np.einsum("fab,fab->f", S, S)
        closure = (2 * np.einsum("fac,fcb->fab", S, S) + 3 * S * ss[:, None, None]) / 5
        return exact, closure
    e0, c0 = sides(a["particles/all/orientation/value"][...])
    e1, c1 = sides(b["particles/all/orientation/value"][...])
    for i, comp in enumerate(("xx", "yy", "zz")):
        assert np.allclose(c[f"closure_rod/S4S_{comp}"][...], (e0[:, i, i] + e1[:, i, i]) / 2, atol=1e-12)
        assert np.allclose(c[f"closure_rod/closure_{comp}"][...], (c0[:, i, i] + c1[:, i, i]) / 2, atol=1e-12)
    print(f"closure: {len(c['closure_rod/time'])} frames; at the start S4S_zz = {c['closure_rod/S4S_zz'][0]:.4f}, "
          f"closure_zz = {c['closure_rod/closure_zz'][0]:.4f}")

# 5. bad input
bad = [
    ("no histogram", "anisodyn-pair-distances", {}, "free.h5", ["free.h5", "/observables/pair_distance_histogram"]),
    ("window for the histogram", "anisodyn-pair-distances", {"window": {"from": 1.0}}, "rep0.h5", ["window", "no effect"]),
    ("unknown method", "anisodyn-order-relaxation", {"method": "fit"}, "rep0.h5", ["method"]),
    ("decay key under regression", "anisodyn-order-relaxation", {"method": "regression", "noise_from": 1.0}, "rep0.h5",
     ["noise_from", "no effect"]),
    ("regression key under decay", "anisodyn-order-relaxation", {"method": "decay", "lags_per_decade": 5}, "rep0.h5",
     ["lags_per_decade", "no effect"]),
    ("no order tensor", "anisodyn-order-relaxation", {"method": "decay"}, "start.h5", ["start.h5", "/observables/order_tensor_rod"]),
    ("closure: unknown rod axis", "anisodyn-closure", {"rod_axis": "Q"}, "rep0.h5", ["rod_axis"]),
]
for k, (label, tool, config, data, needles) in enumerate(bad):
    cfg = write(f"bad{k}.json", config)
    out = f"bad{k}.h5"
    r = run(tool, "--config", cfg, "--input", data, "--output", out)
    problems = [] if r.returncode == 2 else [f"exit {r.returncode}"]
    problems += [f"does not name {n}" for n in needles if n not in r.stderr]
    if needles[0] in ("method", "window", "noise_from", "lags_per_decade", "rod_axis") and cfg not in r.stderr:
        problems.append(f"does not name {cfg}")
    if any(os.path.exists(f) for f in (out, f"bad{k}.scalars.csv")):
        problems.append("output written")
    assert not problems, f"{label}: {problems}: {r.stderr}"
    print(f"ok   {label}: {r.stderr.strip().splitlines()[-1][:160]}")
