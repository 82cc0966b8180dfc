#!/usr/bin/env python3
"""The report's raspberry block (workflows/anisodyn_run/raspberry.py) on synthetic anisodyn-lb-diffusion
outputs built from known answers:
  - spheres whose D_t(L) follow Hasimoto's law exactly from frictions on chosen calibration lines
    (one per xi_bead): the section gives back D_0, the lines' slopes and intercepts and R² = 1 to
    round-off, and writes them to raspberry_calibration.json;
  - the same with Gaussian noise of known SE (fixed seed): every recovered parameter within 4 of its
    stated SE of the truth, and the SE of m_t within a factor 2 of the spread over 25 noisy repeats;
  - spheroids (phi = 1/2, 2, 4) whose frictions come from spec 40 §8.6's factors through those lines:
    a second section reading that file gives back A, B, E-L to round-off;
  - the manifest's raspberry block: each wrong key refused at its JSON path.
argv: [1] build bin dir (unused), [2] scratch dir, [3] source dir."""
import json
import math
import os
import sys

import h5py
import numpy as np

scratch, source = sys.argv[2], sys.argv[3]
sys.path.insert(0, os.path.join(source, "workflows"))
sys.path.insert(0, os.path.join(source, "tests", "support"))
from anisodyn_run import spheroid_theory as st  # noqa: E402
from anisodyn_run.manifest import ManifestError, validate_report  # noqa: E402
from anisodyn_run.raspberry import HASIMOTO, Section  # noqa: E402
from script_checks import check, finish  # noqa: E402

ETA, KT, SCALE = 4.8032, 1.0, 0.140951
LINES = {50: {"t": (1.10 * 6 * math.pi * ETA, 20.0), "r": (0.90 * 8 * math.pi * ETA, 300.0)},
         1000: {"t": (1.02 * 6 * math.pi * ETA, -15.0), "r": (0.97 * 8 * math.pi * ETA, -120.0)}}
BOXES = [16, 24, 32, 40]


class Job:
    def __init__(self, point, path):
        self.point, self.path = point, path


def write_output(path, semi_axes, box, values, rel_se, rng):
    """An lb-diffusion output: /scalars/<name> = [value, SE] with the details the section reads."""
    radius = float(np.cbrt(np.prod(semi_axes)))
    details = json.dumps({"box": box, "radius": radius, "semi_axes": list(semi_axes), "kT": KT, "eta": ETA,
                          "friction_scale": SCALE, "rotation_convention": "default"})
    with h5py.File(path, "w") as f:
        g = f.create_group("scalars")
        for name, v in values.items():
            se = rel_se * abs(v)
            noisy = v + (rng.normal(0.0, se) if rng is not None else 0.0)
            ds = g.create_dataset(name, data=np.array([noisy, se]))
            ds.attrs["details"] = details


def diffusion_values(xi_t, xi_t_axes, xi_r, xi_r_three, xi_r_axes, box):
    """Lab and body D_t at box L (Hasimoto), D_r without a box dependence."""
    shift = HASIMOTO * KT / (6 * math.pi * ETA * box)
    v = {"D_t": KT / xi_t - shift, "D_r": KT / xi_r, "D_r_three_axis": KT / xi_r_three}
    for axis, xt, xr in zip("xyz", xi_t_axes, xi_r_axes):
        v[f"D_t_body_{axis}"] = KT / xt - shift
        v[f"D_r_body_{axis}"] = KT / xr
    return v


def sphere_jobs(folder, rel_se, rng):
    os.makedirs(folder, exist_ok=True)
    jobs = []
    for xi_bead, line in LINES.items():
        for R in (2.25, 3.25, 4.25, 5.75):
            xi_t = line["t"][0] * R + line["t"][1]
            xi_r = line["r"][0] * R ** 3 + line["r"][1]
            for L in BOXES:
                path = os.path.join(folder, f"s_{xi_bead}_{R}_{L}.h5")
                write_output(path, (R, R, R), L, diffusion_values(xi_t, [xi_t] * 3, xi_r, xi_r, [xi_r] * 3, L), rel_se, rng)
                jobs.append(Job({"d": 2 * R, "L": L, "xi_bead": xi_bead}, path))
    return jobs


def run_section(spec, jobs, out):
    os.makedirs(out, exist_ok=True)
    return Section(spec, jobs, lambda j: j.path, out, os.path.join(scratch, "results", "spheroids")).write()


# --- exact spheres: the lines come back to round-off ---------------------------------------------
exact_out = os.path.join(scratch, "results", "spheres", "report")
lines = run_section({"stage": "diffusion", "box": "L", "calibration": {"fit": "xi_bead"}, "plot": {"x": "xi_bead", "series": "d"}},
                    sphere_jobs(os.path.join(scratch, "exact"), 0.01, None), exact_out)
cal = json.load(open(os.path.join(exact_out, "raspberry_calibration.json")))
for xi_bead, line in LINES.items():
    got = cal["lines"][str(xi_bead)]
    for kind in ("t", "r"):
        m, b = line[kind]
        check(abs(got[kind]["m"] / m - 1) < 1e-9 and abs(got[kind]["b"] - b) < 1e-7 * abs(m),
              f"xi_bead = {xi_bead}: m_{kind}, b_{kind} = {got[kind]['m']:.10g}, {got[kind]['b']:.10g} (true {m:.10g}, {b:g})")
        check(abs(got[kind]["r2"] - 1) < 1e-12, f"xi_bead = {xi_bead}: R² ({kind}) = {got[kind]['r2']:.15f}")
rows = list(__import__("csv").DictReader(open(os.path.join(exact_out, "raspberry_bodies.csv"))))
worst = max(abs(float(r["slope"]) / float(r["hasimoto_slope"]) - 1) for r in rows)
check(len(rows) == 8 and worst < 1e-8, f"8 bodies, each fitted D_t(1/L) slope equals Hasimoto's (worst relative {worst:.1e})")
for png in ("xi_t_vs_R.png", "xi_r_vs_R3.png", "calibration_bars.png", "friction_ratios.png"):
    check(os.path.getsize(os.path.join(exact_out, png)) > 10_000, f"plot {png} written")

# --- noisy spheres: errors that mean what they say ----------------------------------------------
pulls, slopes, stated = [], [], []
for repeat in range(25):
    rng = np.random.default_rng(1000 + repeat)
    out = os.path.join(scratch, "noisy", "report")
    run_section({"stage": "diffusion", "box": "L", "calibration": {"fit": "xi_bead"}},
                sphere_jobs(os.path.join(scratch, "noisy"), 0.004, rng), out)
    got = json.load(open(os.path.join(out, "raspberry_calibration.json")))["lines"]["1000"]
    for kind in ("t", "r"):
        (m, b), cov = LINES[1000][kind], got[kind]["cov"]
        pulls += [(got[kind]["m"] - m) / math.sqrt(cov[1][1]), (got[kind]["b"] - b) / math.sqrt(cov[0][0])]
    slopes.append(got["t"]["m"])
    stated.append(math.sqrt(got["t"]["cov"][1][1]))
check(max(abs(p) for p in pulls) < 4, f"noisy: every parameter within 4 SE of the truth (largest |pull| {max(abs(p) for p in pulls):.2f}, "
                                       f"RMS pull {math.sqrt(np.mean(np.square(pulls))):.2f})")
spread, mean_stated = float(np.std(slopes, ddof=1)), float(np.mean(stated))
check(0.5 < mean_stated / spread < 2.0, f"noisy: stated SE of m_t {mean_stated:.4g} against its spread over 25 repeats {spread:.4g}")

# --- spheroids through the file: the factors of spec 40 §8.6 --------------------------------------
folder = os.path.join(scratch, "spheroids")
os.makedirs(folder, exist_ok=True)
(mt, bt), (mr, br) = LINES[1000]["t"], LINES[1000]["r"]
jobs = []
for phi in (0.5, 2.0, 4.0):
    a, c = 4.25 * phi ** (2 / 3), 4.25 * phi ** (-1 / 3)
    A, B = st.lab_factors(phi)
    t_ax, t_perp = st.translation_factors(phi)
    r_ax, r_perp = st.rotation_factors(phi)
    xi_t, xi_r = mt * a / A + bt, mr * a ** 3 / B + br
    xi_t_axes = [mt * c * t_ax + bt] + [mt * c * t_perp + bt] * 2
    xi_r_axes = [mr * c ** 3 * r_ax + br] + [mr * c ** 3 * r_perp + br] * 2
    for L in (32, 48):
        path = os.path.join(folder, f"e_{phi}_{L}.h5")
        write_output(path, (a, c, c), L, diffusion_values(xi_t, xi_t_axes, xi_r, xi_r, xi_r_axes, L), 0.01, None)
        jobs.append(Job({"a": a, "b": c, "L": L}, path))
out = os.path.join(scratch, "results", "spheroids", "report")
text = run_section({"stage": "diffusion", "box": "L", "calibration": {"file": "spheres/report/raspberry_calibration.json", "xi_bead": 1000}},
                   jobs, out)
rows = list(__import__("csv").DictReader(open(os.path.join(out, "spheroid_factors.csv"))))
for r in rows:
    phi = float(r["phi"])
    worst = max(abs(float(r[n]) / float(r[n + "_theory"]) - 1) for n in ("A", "B", "B_three_axis", "t_ax", "t_perp", "r_ax", "r_perp"))
    check(worst < 1e-8, f"phi = {phi:.3g}: A, B, E-L back through the calibration file (worst relative {worst:.1e})")
check(len(rows) == 3, "three spheroids in spheroid_factors.csv")
missing = run_section({"stage": "diffusion", "box": "L", "calibration": {"file": "none/raspberry_calibration.json", "xi_bead": 1000}},
                      jobs, os.path.join(scratch, "missing"))
check(any("does not exist" in line for line in missing), "a missing calibration file is said so in the report, and no factors are made")

# --- the manifest's block ---------------------------------------------------------------------------
base = {"study": "x", "grid": {"L": [16, 24], "xi_bead": [50]},
        "stages": [{"name": "lb", "tool": "lb", "params": {}}, {"name": "diffusion", "tool": "lb-diffusion", "params": {}}]}
for block, path in ((["x"], "report.raspberry"), ({"stage": "lb", "box": "L", "calibration": "stokes"}, "report.raspberry.stage"),
                    ({"stage": "diffusion", "box": "d", "calibration": "stokes"}, "report.raspberry.box"),
                    ({"stage": "diffusion", "box": "L", "calibration": {"fit": "L"}}, "report.raspberry.calibration.fit"),
                    ({"stage": "diffusion", "box": "L", "calibration": {"file": "f.json"}}, "report.raspberry.calibration.xi_bead"),
                    ({"stage": "diffusion", "box": "L", "calibration": "stokes", "series": "d"}, "report.raspberry.series"),
                    ({"stage": "diffusion", "box": "L", "calibration": "perrin"}, "report.raspberry.calibration"),
                    ({"stage": "diffusion", "box": "L", "plot": {"x": "L"}}, "report.raspberry.plot.x"),
                    ({"stage": "diffusion", "box": "L", "plot": {"x": "xi_bead", "colour": "d"}}, "report.raspberry.plot.colour")):
    try:
        validate_report({**base, "report": {"raspberry": block}})
        check(False, f"{block} refused")
    except ManifestError as e:
        check(str(e).startswith(path + ":") or f"{path}:" in str(e), f"{json.dumps(block)} refused at {path}: {e}")
validate_report({**base, "report": {"raspberry": {"stage": "diffusion", "box": "L", "calibration": {"fit": "xi_bead"}}}})
check(True, "a well-formed raspberry block is accepted")
assert not finish()
