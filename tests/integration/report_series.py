#!/usr/bin/env python3
"""The report's scalar plots with several series (docs/manifests.md, Report), on synthetic analysis outputs:
  1. the manifest check refuses bad series lists, x_scale, y_scale, linear and periodic-box lines, naming the JSON path;
  2. a series list draws each entry's scalar against grid value × x_scale (its own stage and select), an
     entry whose stage does not depend on x as a horizontal line with its ±band, and the linear theory line
     from x = 0; the single-scalar form takes x_scale too; y_scale and an entry's own scales; Hasimoto's stick
     and slip lines and (1 - phi)/pi against their formulas (spec 30 §10); entries at their own x (at_x) with the
     Tirado-Garcia de la Torre D_par/D_perp line;
  3. at report time: an entry with several grid points at one x, a band on an entry that varies with x, and
     a missing scalar are errors naming the entry's path; an entry whose select matches nothing draws nothing.
argv: [1] build bin dir (unused), [2] scratch dir, [3] source dir."""
import os
import shutil
import sys

import h5py
import numpy as np

tmp, source = sys.argv[2], sys.argv[3]
sys.path.insert(0, os.path.join(source, "workflows"))
sys.path.insert(0, os.path.join(source, "tests", "support"))
from anisodyn_run.expand import Job  # noqa: E402
from anisodyn_run.manifest import ManifestError, validate_report  # noqa: E402
from anisodyn_run.report import Report, ReportError  # noqa: E402
from script_checks import check, finish  # noqa: E402

import matplotlib  # noqa: E402
matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

shutil.rmtree(tmp, ignore_errors=True)
os.makedirs(tmp)

NS, HARD = [90, 440, 1760], [1.0, 2.0]
BASE = {"study": "series", "grid": {"N": NS, "hardness": HARD, "label": ["a", "b"]},
        "stages": [{"name": "pairs", "tool": "x"}, {"name": "pilot", "tool": "x"}, {"name": "other", "tool": "x"}]}
GOOD_PLOT = {"name": "p", "x": "N", "x_scale": 0.001,
             "series": [{"stage": "pairs", "scalar": "D", "select": {"hardness": 1.0}, "label": "k"},
                        {"stage": "pilot", "scalar": "D", "band": 0.02, "label": "pilot"}],
             "theory": [{"kind": "linear", "intercept": 1.0, "slope": -0.2, "label": "1 - x/5"}]}


def manifest(plot):
    return dict(BASE, report={"plots": [plot]})


# 1. the manifest check
try:  # a plot of at_x entries, then others: each keeps its own path (an axis-key loop once renamed the items' list)
    validate_report(dict(BASE, report={"plots": [{"name": "a", "series": [{"stage": "pairs", "scalar": "D", "at_x": 2}]}, GOOD_PLOT,
                                                 {"stage": "pairs", "table": "t", "x": "time", "y": ["P"]}]}))
    check(True, "at_x plots followed by other plots pass the manifest check")
except ManifestError as e:
    check(False, f"at_x plots followed by other plots are refused: {e}")
try:
    validate_report(manifest(GOOD_PLOT))
    check(True, "a series list with x_scale, band and a linear line passes the manifest check")
except ManifestError as e:
    check(False, f"the good series plot is refused: {e}")

BAD = [  # (what, plot, the path the message must name)
    ("a linear line without its slope", dict(GOOD_PLOT, theory=[{"kind": "linear", "intercept": 1}]), "report.plots[0].theory[0].slope"),
    ("a linear line with a text intercept", dict(GOOD_PLOT, theory=[{"kind": "linear", "intercept": "1", "slope": 0}]),
     "report.plots[0].theory[0].intercept"),
    ("tau on a linear line", dict(GOOD_PLOT, theory=[{"kind": "linear", "intercept": 1, "slope": 0, "tau": 2}]),
     "report.plots[0].theory[0].tau"),
    ("x_scale 0", dict(GOOD_PLOT, x_scale=0), "report.plots[0].x_scale"),
    ("x_scale on a grid of texts", dict(GOOD_PLOT, x="label"), "report.plots[0].x_scale"),
    ("x_scale on a table plot", {"stage": "pairs", "table": "t", "y": ["P"], "x_scale": 2}, "report.plots[0].x_scale"),
    ("x_power 0", dict(GOOD_PLOT, x_power=0), "report.plots[0].x_power"),
    ("x_power on a grid of texts", dict({k: v for k, v in GOOD_PLOT.items() if k != "x_scale"}, x="label", x_power=2),
     "report.plots[0].x_power"),
    ("y_scale 0", dict(GOOD_PLOT, y_scale=0), "report.plots[0].y_scale"),
    ("an entry's x_scale as text", dict(GOOD_PLOT, series=[{"stage": "pairs", "scalar": "D", "x_scale": "2"}]),
     "report.plots[0].series[0].x_scale"),
    ("a Hasimoto line of an unknown boundary", dict(GOOD_PLOT, theory=[{"kind": "hasimoto", "boundary": "partial"}]),
     "report.plots[0].theory[0].boundary"),
    ("a band of 120%", dict(GOOD_PLOT, theory=[{"kind": "periodic_rotation", "band": 1.2}]), "report.plots[0].theory[0].band"),
    ("at_x as text", dict(GOOD_PLOT, series=[{"stage": "pairs", "scalar": "D", "at_x": "4"}]), "report.plots[0].series[0].at_x"),
    ("x beside entries that all give at_x", {"name": "p", "x": "N", "series": [{"stage": "pairs", "scalar": "D", "at_x": 4}]},
     "report.plots[0].x"),
    ("x_scale with at_x", dict(GOOD_PLOT, series=[{"stage": "pairs", "scalar": "D", "at_x": 4, "x_scale": 2}]),
     "report.plots[0].series[0].x_scale"),
    ("a stage beside a series list", dict(GOOD_PLOT, stage="pairs"), "report.plots[0].stage"),
    ("a scalar beside a series list", dict(GOOD_PLOT, scalar="D"), "report.plots[0]"),
    ("an empty series list", dict(GOOD_PLOT, series=[]), "report.plots[0].series"),
    ("an entry without a scalar", dict(GOOD_PLOT, series=[{"stage": "pairs"}]), "report.plots[0].series[0].scalar"),
    ("an entry of no stage", dict(GOOD_PLOT, series=[{"stage": "nope", "scalar": "D"}]), "report.plots[0].series[0].stage"),
    ("an entry with an unknown key", dict(GOOD_PLOT, series=[{"stage": "pairs", "scalar": "D", "tau": 1}]),
     "report.plots[0].series[0].tau"),
    ("an entry selecting no grid variable", dict(GOOD_PLOT, series=[{"stage": "pairs", "scalar": "D", "select": {"phi": 1}}]),
     "report.plots[0].series[0].select.phi"),
    ("a band of 2", dict(GOOD_PLOT, series=[{"stage": "pilot", "scalar": "D", "band": 2}]), "report.plots[0].series[0].band"),
    ("a series list without x", {k: v for k, v in GOOD_PLOT.items() if k != "x"}, "report.plots[0].x"),
]
for what, plot, path in BAD:
    try:
        validate_report(manifest(plot))
        check(False, f"{what}: accepted")
    except ManifestError as e:
        check(str(e).startswith(f"at {path}: expected"), f"{what}: {e}")

# 2. drawing, on synthetic outputs: pairs at N x hardness (D = 1 - N/5000 + hardness/100), other at N, pilot at no grid point
campaign = os.path.join(tmp, "campaign")
jobs, by_stage = {}, {}


def output(stage, point, scalars):
    directory = os.path.join(stage, *[f"{k}={v}" for k, v in point.items()])
    os.makedirs(os.path.join(campaign, directory), exist_ok=True)
    job = Job(f"{stage}{len(jobs)}", stage, "x", {}, point, None, [], directory, stage, stage + ".h5",
              info={"output": {"kind": "analysis"}})
    with h5py.File(os.path.join(campaign, job.output), "w") as f:
        for name, (v, e) in scalars.items():
            ds = f.create_dataset(f"scalars/{name}", data=np.array([v, e]))
            ds.attrs["units"], ds.attrs["definition"] = "1", "synthetic"
    jobs[job.id] = job
    by_stage.setdefault(stage, []).append(job.id)


def d_value(n, h):
    return 1 - n / 5000 + h / 100


for n in NS:
    for h in HARD:
        output("pairs", {"N": n, "hardness": h}, {"D": (d_value(n, h), 0.01)})
    output("other", {"N": n}, {"D": (0.5, 0.02)})
output("pilot", {}, {"D": (0.9, 0.003)})
m = dict(BASE, grid={"N": NS, "hardness": HARD})
report = Report(m, jobs, by_stage, campaign, tmp)


def labelled(ax):
    """{label: line} of the plain lines and of the data lines of the error-bar series."""
    out = {line.get_label(): line for line in ax.get_lines() if not line.get_label().startswith("_")}
    out.update({c.get_label(): c.lines[0] for c in ax.containers if hasattr(c, "has_yerr")})
    return out


def draw(plot):
    fig, ax = plt.subplots()
    try:
        report.scalar_plot(ax, plot, "report.plots[0]")
        return ax
    finally:
        plt.close(fig)


ax = draw(GOOD_PLOT)
lines = labelled(ax)
k = lines.get("k")
check(k is not None and np.allclose(k.get_xdata(), [0.09, 0.44, 1.76]) and
      np.allclose(k.get_ydata(), [d_value(n, 1.0) for n in NS]), "entry 'k': x = N × 0.001, y the selected hardness' values")
pilot = lines.get("pilot")
check(pilot is not None and np.allclose(pilot.get_ydata(), 0.9), "an entry of a stage without x is a horizontal line at its value")
bands = [p for p in ax.patches if p.get_label() == "pilot ± 2%"]
check(len(bands) == 1 and np.allclose(sorted({round(y, 12) for _, y in bands[0].get_xy()}), [0.9 * 0.98, 0.9 * 1.02]),
      "its band spans the value ± 2%")
theory = lines.get("1 - x/5")
check(theory is not None and np.isclose(theory.get_xdata()[0], 0) and np.isclose(theory.get_xdata()[-1], 1.76) and
      np.allclose(theory.get_ydata(), 1 - 0.2 * theory.get_xdata()), "the linear line runs from x = 0 to the largest x, y = 1 - x/5")

ax = draw({"name": "q", "stage": "pairs", "scalar": "D", "x": "N", "x_scale": 0.001, "series": "hardness"})
lines = labelled(ax)
check(set(lines) == {"hardness = 1.0", "hardness = 2.0"} and np.allclose(lines["hardness = 2.0"].get_xdata(), [0.09, 0.44, 1.76]) and
      np.allclose(lines["hardness = 2.0"].get_ydata(), [d_value(n, 2.0) for n in NS]), "the single-scalar form scales x too")

ax = draw({"name": "r", "stage": "pairs", "scalar": "D", "x": "N", "x_power": -1, "select": {"hardness": 1.0}})
lines = labelled(ax)
check("D" in lines and np.allclose(sorted(lines["D"].get_xdata()), sorted(1 / n for n in NS)), "x_power -1 draws against 1/N")

# y_scale (the plot's, an entry's own) and an entry's x_scale; the periodic-box theory lines of spec 30 §10 against x = phi^(1/3).
ax = draw({"name": "s", "x": "N", "x_scale": 0.001, "y_scale": 2.0,
           "series": [{"stage": "pairs", "scalar": "D", "select": {"hardness": 1.0}, "label": "k"},
                      {"stage": "pairs", "scalar": "D", "select": {"hardness": 2.0}, "x_scale": 0.0001, "y_scale": 3.0, "label": "2k"}],
           "theory": [{"kind": "hasimoto", "boundary": "stick", "band": 0.2}, {"kind": "hasimoto", "boundary": "slip"},
                      {"kind": "periodic_rotation"}]})
lines = labelled(ax)
check(np.allclose(lines["k"].get_ydata(), [2 * d_value(n, 1.0) for n in NS]) and np.allclose(lines["2k"].get_ydata(), [3 * d_value(n, 2.0) for n in NS])
      and np.allclose(lines["2k"].get_xdata(), [0.009, 0.044, 0.176]), "y_scale multiplies the values, an entry's own x_scale and y_scale override the plot's")
stick, slip, rot = lines["Hasimoto, stick"], lines["Hasimoto, slip"], lines["(1 - phi)/pi"]
x = stick.get_xdata()
phi = x ** 3
q = 1 - 1.7601 * x + phi - 1.5593 * phi ** 2
check(np.allclose(stick.get_ydata(), q / (3 * np.pi)) and np.isclose(stick.get_ydata()[0], 1 / (3 * np.pi)) and
      np.allclose(slip.get_ydata(), q * (3 + 27.9 * phi) / 2 / (3 * np.pi)) and np.isclose(slip.get_ydata()[0], 1 / (2 * np.pi)) and
      np.allclose(rot.get_ydata(), (1 - rot.get_xdata() ** 3) / np.pi),
      "Hasimoto's stick Q/(3 pi) (1/(3 pi) at phi = 0), slip Q Q'/(3 pi) (1/(2 pi) at phi = 0) and (1 - phi)/pi")
check(any(p.get_label() == "± 20%" for p in ax.collections), "the stick line's ±20% band")

# at_x: each entry's one grid point at its own x (a rod's p), no grid variable on x; the Tirado-Garcia de la Torre ratio.
ax = draw({"name": "t", "series": [{"stage": "pairs", "scalar": "D", "select": {"N": 90, "hardness": 1.0}, "at_x": 2.0, "label": "p2"},
                                   {"stage": "pairs", "scalar": "D", "select": {"N": 440, "hardness": 2.0}, "at_x": 6.0, "label": "p6"}],
           "theory": [{"kind": "tirado_ratio"}]})
lines = labelled(ax)
p_line = lines["Tirado-Garcia de la Torre"]
pp = p_line.get_xdata()
ratio = 2 * (np.log(pp) - 0.207 + 0.980 / pp - 0.133 / pp ** 2) / (np.log(pp) + 0.839 + 0.185 / pp + 0.233 / pp ** 2)
check(np.allclose(lines["p2"].get_xdata(), [2.0]) and np.allclose(lines["p2"].get_ydata(), [d_value(90, 1.0)]) and
      np.allclose(lines["p6"].get_xdata(), [6.0]) and np.allclose(lines["p6"].get_ydata(), [d_value(440, 2.0)]),
      "entries with at_x draw their one grid point at their own x")
check(np.allclose(p_line.get_ydata(), ratio) and np.isclose(np.interp(2.0, pp, p_line.get_ydata()), 0.07503 / 0.06696, rtol=1e-3),
      "the Tirado-Garcia de la Torre D_par/D_perp, 1.121 at p = 2 (spec 30 §10's table)")
try:
    draw({"name": "u", "series": [{"stage": "pairs", "scalar": "D", "select": {"hardness": 1.0}, "at_x": 2.0}]})
    check(False, "an at_x entry with several grid points is drawn")
except ReportError as e:
    check("at_x" in str(e) and "report.plots[0].series[0]" in str(e), f"an at_x entry with several grid points: {e}")

# fit_line: the weighted line through the plot's points, here exactly on a line (d_value is linear in N)
report.drawn, report.notes = [], []
ax = draw({"name": "f", "stage": "pairs", "scalar": "D", "x": "N", "select": {"hardness": 1.0}, "theory": [{"kind": "fit_line"}]})
fit = [line for line in ax.get_lines() if line.get_label().startswith("fit: ")]
check(len(fit) == 1 and np.allclose(fit[0].get_ydata(), 1 + 1.0 / 100 - fit[0].get_xdata() / 5000) and report.notes
      and report.notes[0].startswith("fit: c0 = 1.01 ± ") and "c1 = -0.0002 ± " in report.notes[0],
      f"fit_line recovers the line through the points and notes it: {report.notes}")
try:
    validate_report(manifest({"stage": "pairs", "table": "t", "x": "time", "y": ["P"], "theory": [{"kind": "fit_line"}]}))
    check(False, "fit_line on a curve plot passes the manifest check")
except ManifestError as e:
    check("report.plots[0].theory[0].kind" in str(e), f"fit_line on a curve plot: {e}")

ax = draw(dict(GOOD_PLOT, select={"hardness": 2.0}, series=[{"stage": "pairs", "scalar": "D", "label": "2k"},
                                                             {"stage": "pairs", "scalar": "D", "select": {"hardness": 1.0}, "label": "k"}]))
lines = labelled(ax)
check(np.allclose(lines["2k"].get_ydata(), [d_value(n, 2.0) for n in NS]) and np.allclose(lines["k"].get_ydata(), [d_value(n, 1.0) for n in NS]),
      "the plot's select applies to every entry, an entry's own select overrides it")

ax = draw(dict(GOOD_PLOT, series=[{"stage": "other", "scalar": "D", "select": {"N": 7}, "label": "none"},
                                   {"stage": "other", "scalar": "D", "label": "other"}]))
lines = labelled(ax)
check("none" not in lines and "other" in lines, "an entry whose select matches no grid point draws nothing (as a single scalar's)")

# 3. errors at report time
ERRORS = [
    ("an entry with two grid points at one x", [{"stage": "pairs", "scalar": "D"}], "report.plots[0].series[0]", "hardness"),
    ("a band on an entry that varies with x", [{"stage": "other", "scalar": "D", "band": 0.02}], "report.plots[0].series[0].band",
     "no effect"),
    ("a scalar the stage did not write", [{"stage": "pilot", "scalar": "D"}, {"stage": "other", "scalar": "Q"}],
     "report.plots[0].series[1].scalar", "no scalar 'Q'"),
]
for what, series, path, words in ERRORS:
    try:
        draw(dict(GOOD_PLOT, series=series))
        check(False, f"{what}: drawn")
    except ReportError as e:
        check(str(e).startswith(path) and words in str(e), f"{what}: {e}")

failed = finish()
assert not failed, f"{len(failed)} check(s) failed: {failed}"
