#!/usr/bin/env python3
"""The report's panel, overlay and bar layouts (docs/manifests.md, Report; spec 60 D5 and D6), on synthetic analysis outputs:
  1. the manifest check accepts a panel with an overlay and a bar plot, and refuses bad or ineffective rows, overlay,
     theory columns, groups and bars, naming the JSON path;
  2. a panel (rows xi_bead, columns S_x, S_y, S_z) draws every grid point's table in its row and column, a colour per
     pore alike in every subplot, y shared along a column, the overlay stage's curves dashed with open markers in the
     matching colour in its row only, the centreline points in the S_z column only, and one legend for the figure;
     a single curve plot takes the overlay too;
  3. a bar plot draws a bar per (group, bar) value at its place with the scalar's value and SE, and the constant line;
  4. at report time: a panel over a variable its stage does not depend on, several grid points in one bar and a
     missing scalar are errors naming the path.
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
from anisodyn_run.pore_theory import haberman_sayre  # noqa: E402
from anisodyn_run.report import Report, ReportError  # noqa: E402
from script_checks import check, finish  # noqa: E402

import matplotlib  # noqa: E402
matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
from matplotlib.colors import to_hex  # noqa: E402

shutil.rmtree(tmp, ignore_errors=True)
os.makedirs(tmp)

PORES, XIS, NUS, BOXES = [8.5, 21.25], [50, 1000], [5.6757, 0.8], [32, 48, 64]
GRID = {"R_pore": PORES, "xi_bead": XIS, "nu": NUS, "L": BOXES, "seed": [1, 2]}
BASE = {"study": "layouts", "grid": GRID,
        "stages": [{"name": n, "tool": "x"} for n in ("pore", "pore_single", "diffusion", "seeded")]}
CENTRE = {"kind": "pore_centreline", "radius": 4.25, "columns": ["S_z"]}
PANEL = {"name": "S", "stage": "pore", "table": "pore_bins", "x": "beta", "y": ["S_x", "S_y", "S_z"], "rows": "xi_bead",
         "overlay": {"stage": "pore_single", "label": "single layer", "row": 1000}, "theory": [CENTRE]}
BARS = {"name": "b", "stage": "diffusion", "scalar": "xi_t", "groups": "L", "bars": "nu",
        "theory": [{"kind": "constant", "value": 1, "label": "Stokes"}]}


def manifest(plot):
    return dict(BASE, report={"plots": [plot]})


def without(d, key):
    return {k: v for k, v in d.items() if k != key}


# 1. the manifest check
for what, plot in (("a panel with an overlay and centreline points in one column", PANEL), ("a bar plot", BARS),
                   ("a curve plot with an overlay in every row", dict(without(PANEL, "theory"), overlay={"stage": "pore_single"})),
                   ("a single curve plot with an overlay", dict(without(without(PANEL, "rows"), "theory"), overlay={"stage": "pore_single"}))):
    try:
        validate_report(manifest(plot))
        check(True, f"{what} passes the manifest check")
    except ManifestError as e:
        check(False, f"{what} is refused: {e}")

BAD = [  # (what, plot, the path the message must name)
    ("rows not a grid variable", dict(PANEL, rows="phi"), "report.plots[0].rows"),
    ("rows on a scalar plot", {"stage": "diffusion", "scalar": "xi_t", "x": "L", "rows": "xi_bead"}, "report.plots[0].rows"),
    ("an overlay that is not an object", dict(PANEL, overlay="pore_single"), "report.plots[0].overlay"),
    ("an overlay of no stage", dict(PANEL, overlay={"stage": "nope"}), "report.plots[0].overlay.stage"),
    ("an overlay with an unknown key", dict(PANEL, overlay={"stage": "pore_single", "band": 0.1}), "report.plots[0].overlay.band"),
    ("an overlay label that is not a text", dict(PANEL, overlay={"stage": "pore_single", "label": 3}), "report.plots[0].overlay.label"),
    ("an overlay selecting no grid variable", dict(PANEL, overlay={"stage": "pore_single", "select": {"phi": 1}}),
     "report.plots[0].overlay.select.phi"),
    ("an overlay row outside a panel", dict(without(without(PANEL, "rows"), "theory")), "report.plots[0].overlay.row"),
    ("an overlay row that is not a value of the rows", dict(PANEL, overlay={"stage": "pore_single", "row": 200}),
     "report.plots[0].overlay.row"),
    ("an overlay on a bar plot", dict(BARS, overlay={"stage": "pore_single"}), "report.plots[0].overlay"),
    ("theory columns outside a panel", dict(without(without(PANEL, "rows"), "overlay")), "report.plots[0].theory[0].columns"),
    ("theory columns naming no y column", dict(PANEL, theory=[dict(CENTRE, columns=["S_w"])]), "report.plots[0].theory[0].columns"),
    ("theory columns as a text", dict(PANEL, theory=[dict(CENTRE, columns="S_z")]), "report.plots[0].theory[0].columns"),
    ("groups not a grid variable", dict(BARS, groups="box"), "report.plots[0].groups"),
    ("a bar plot without groups", without(BARS, "groups"), "report.plots[0].groups"),
    ("bars the same variable as groups", dict(BARS, bars="L"), "report.plots[0].bars"),
    ("x on a bar plot", dict(BARS, x="L"), "report.plots[0].x"),
    ("series on a bar plot", dict(BARS, series="seed"), "report.plots[0].series"),
    ("a log x axis on a bar plot", dict(BARS, log="xy"), "report.plots[0].log"),
    ("y_scale 0 on a bar plot", dict(BARS, y_scale=0), "report.plots[0].y_scale"),
    ("a linear line on a bar plot", dict(BARS, theory=[{"kind": "linear", "intercept": 1, "slope": 0}]), "report.plots[0].theory[0].kind"),
    ("bars without a scalar", without(BARS, "scalar"), "report.plots[0]"),
    ("bars on a curve plot", dict(PANEL, bars="nu"), "report.plots[0].bars"),
]
for what, plot, path in BAD:
    try:
        validate_report(manifest(plot))
        check(False, f"{what}: accepted")
    except ManifestError as e:
        check(str(e).startswith(f"at {path}: expected"), f"{what}: {e}")

# Synthetic outputs: pore at R_pore x xi_bead and pore_single at R_pore (tables pore_bins), diffusion at nu x L and seeded at
# nu x L x seed (scalars).
campaign = os.path.join(tmp, "campaign")
jobs, by_stage = {}, {}
BETA = np.array([0.05, 0.15, 0.25, 0.35])


def output(stage, point, scalars=None, table=None):
    directory = os.path.join(stage, *[f"{k}={v}" for k, v in point.items()])
    os.makedirs(os.path.join(campaign, directory), exist_ok=True)
    job = Job(f"{stage}{len(jobs)}", stage, "x", {}, point, None, [], directory, stage, stage + ".h5", info={"output": {"kind": "analysis"}})
    with h5py.File(os.path.join(campaign, job.output), "w") as f:
        for name, (v, e) in (scalars or {}).items():
            ds = f.create_dataset(f"scalars/{name}", data=np.array([v, e]))
            ds.attrs["units"], ds.attrs["definition"] = "1", "synthetic"
        for name, column in (table or {}).items():
            f.create_dataset(f"pore_bins/{name}", data=column).attrs["units"] = "1"
    jobs[job.id] = job
    by_stage.setdefault(stage, []).append(job.id)


def s_column(axis, pore, xi):
    """A distinct synthetic S per column, pore and bead friction (the single layer: xi None)."""
    return 1 + "xyz".index(axis) + pore / 10 + (xi or 7) / 1000 + BETA ** 2


def pore_table(pore, xi):
    out = {"beta": BETA}
    for axis in "xyz":
        out[f"S_{axis}"], out[f"S_{axis}_se"] = s_column(axis, pore, xi), np.full(BETA.size, 0.01 * (1 + "xyz".index(axis)))
    return out


def xi_value(nu, box):
    return 1 + box / 100 + (0.5 if nu == 0.8 else 0.0)


for pore in PORES:
    for xi in XIS:
        output("pore", {"R_pore": pore, "xi_bead": xi}, table=pore_table(pore, xi))
    output("pore_single", {"R_pore": pore}, table=pore_table(pore, None))
for nu in NUS:
    for box in BOXES:
        output("diffusion", {"nu": nu, "L": box}, {"xi_t": (xi_value(nu, box), 0.01 * box)})
        for seed in (1, 2):
            output("seeded", {"nu": nu, "L": box, "seed": seed}, {"xi_t": (1.0, 0.1)})
report = Report(dict(BASE, report={}), jobs, by_stage, campaign, tmp)


def curves(ax):
    """{label: data line} of the error-bar curves drawn on ax."""
    return {c.get_label(): c.lines[0] for c in ax.containers if hasattr(c, "has_yerr")}


def same_data(line, x, y):
    return np.allclose(line.get_xdata(), x) and np.allclose(line.get_ydata(), y)


# 2. the panel
fig = report.figure(PANEL, "report.plots[0]")
axes = np.array(fig.axes).reshape(len(XIS), 3)
check(len(fig.axes) == 6, f"a panel of 2 rows (xi_bead) x 3 columns (S_x, S_y, S_z): {len(fig.axes)} axes")
check([ax.get_title() for ax in axes[1]] == ["S_x, xi_bead = 1000", "S_y, xi_bead = 1000", "S_z, xi_bead = 1000"],
      f"subplot titles name the column and the row: {[ax.get_title() for ax in axes[1]]}")
colour = {}  # pore -> colour of its curve, checked alike in every subplot
for r, xi in enumerate(XIS):
    for c, axis in enumerate("xyz"):
        drawn = curves(axes[r][c])
        for pore in PORES:
            main = drawn.get(f"R_pore = {pore}")
            check(main is not None and same_data(main, BETA, s_column(axis, pore, xi)) and main.get_linestyle() == "-",
                  f"row xi_bead = {xi}, column S_{axis}: the curve of R_pore = {pore} is its table's column, solid")
            if main is not None:
                colour.setdefault(pore, to_hex(main.get_color()))
                check(to_hex(main.get_color()) == colour[pore], f"row {xi}, S_{axis}: R_pore = {pore} in its colour {colour[pore]}")
            over = drawn.get(f"single layer [R_pore = {pore}]")
            if xi == 1000:
                check(over is not None and same_data(over, BETA, s_column(axis, pore, None)) and over.get_linestyle() == "--"
                      and over.get_markerfacecolor() == "none" and to_hex(over.get_color()) == colour.get(pore),
                      f"row 1000, S_{axis}: the overlay of R_pore = {pore} is pore_single's column, dashed, open markers, the pore's colour")
            else:
                check(over is None, f"row {xi}, S_{axis}: no overlay (its row is 1000)")
        stars = [line for line in axes[r][c].get_lines() if line.get_marker() == "*"]
        if axis == "z":
            expected = {to_hex(colour[p]): haberman_sayre(4.25 / p) for p in PORES}
            check(len(stars) == 2 and all(np.isclose(line.get_ydata()[0], expected.get(to_hex(line.get_color()), np.nan))
                                          and line.get_xdata()[0] == 0 for line in stars),
                  f"row {xi}, S_z: a centreline star per pore at beta = 0, K(lambda) in the pore's colour")
        else:
            check(not stars, f"row {xi}, S_{axis}: no centreline (columns: S_z)")
check(len(set(colour.values())) == 2, f"the two pores have two colours: {colour}")
shared = axes[0][0].get_shared_y_axes()
check(shared.joined(axes[0][0], axes[1][0]) and not shared.joined(axes[0][0], axes[0][1]), "y is shared along a column, not across")
legends = fig.legends
labels = [t.get_text() for t in legends[0].get_texts()] if legends else []
check(len(legends) == 1 and all(not ax.get_legend() for ax in fig.axes) and len(labels) == len(set(labels)) == 6,
      f"one legend for the figure, each label once (2 pores, 2 overlays, 2 centreline points): {labels}")
plt.close(fig)

# the overlay in every row (no row), and on a single curve plot with one y: the main labels as before
fig = report.figure(dict(PANEL, overlay={"stage": "pore_single", "label": "single"}), "report.plots[0]")
check(all(f"single [R_pore = {PORES[0]}]" in curves(ax) for ax in fig.axes), "an overlay without row is drawn in every subplot")
plt.close(fig)
fig = report.figure({"stage": "pore", "table": "pore_bins", "x": "beta", "y": ["S_z"], "select": {"xi_bead": 1000},
                     "overlay": {"stage": "pore_single", "label": "single", "select": {"R_pore": 8.5}}}, "report.plots[0]")
drawn = curves(fig.axes[0])
check(set(drawn) == {"S_z [R_pore = 8.5]", "S_z [R_pore = 21.25]", "single"} and same_data(drawn["single"], BETA, s_column("z", 8.5, None))
      and to_hex(drawn["single"].get_color()) == to_hex(drawn["S_z [R_pore = 8.5]"].get_color()),
      f"a single curve plot: the overlay's selected curve in its pore's colour, the main labels unchanged: {sorted(drawn)}")
plt.close(fig)
lines = report.plot(dict(PANEL, name="panel_png"), 0)
check(os.path.getsize(os.path.join(tmp, "panel_png.png")) > 0 and "![panel_png](panel_png.png)" in lines, "the panel is written as a PNG")

# 3. the bar plot: bar for (L_i, nu_j) at i + (j - 1/2) 0.4, its height the scalar, its error bar 2 SE long
fig = report.figure(BARS, "report.plots[0]")
ax = fig.axes[0]
bars = [c for c in ax.containers if c.__class__.__name__ == "BarContainer"]
check(len(bars) == 2 and [b.get_label() for b in bars] == ["nu = 5.6757", "nu = 0.8"] and sum(len(b.patches) for b in bars) == 6,
      f"two bar series (nu) of three bars (L): {[b.get_label() for b in bars]}")
for j, (nu, series) in enumerate(zip(NUS, bars)):
    centres = [p.get_x() + p.get_width() / 2 for p in series.patches]
    heights = [p.get_height() for p in series.patches]
    check(np.allclose(centres, [i + (j - 0.5) * 0.4 for i in range(3)]) and np.allclose(heights, [xi_value(nu, b) for b in BOXES]),
          f"nu = {nu}: bars at the groups' places, heights the scalars: {np.round(heights, 4).tolist()}")
    segments = series.errorbar.lines[2][0].get_segments()
    check(np.allclose([s[1][1] - s[0][1] for s in segments], [0.02 * b for b in BOXES]), f"nu = {nu}: error bars ± SE")
check([t.get_text() for t in ax.get_xticklabels()] == ["32", "48", "64"] and ax.get_xlabel() == "L", "groups are the x ticks, L the x label")
stokes = [line for line in ax.get_lines() if line.get_label() == "Stokes"]
check(len(stokes) == 1 and np.allclose(stokes[0].get_ydata(), 1), "the constant line at 1")
plt.close(fig)
fig = report.figure(dict(BARS, select={"L": 48}, y_scale=2), "report.plots[0]")
heights = [p.get_height() for c in fig.axes[0].containers if c.__class__.__name__ == "BarContainer" for p in c.patches]
check(np.allclose(heights, [2 * xi_value(nu, 48) for nu in NUS]), f"select keeps one group, y_scale doubles the bars: {heights}")
plt.close(fig)

# 4. errors at report time
ERRORS = [
    ("a panel over a variable its stage does not depend on", dict(PANEL, rows="nu"), "report.plots[0].rows", "'nu'"),
    ("two grid points in one bar", dict(BARS, stage="seeded"), "report.plots[0]", "seed"),
    ("a scalar the stage did not write", dict(BARS, scalar="xi_r"), "report.plots[0].scalar", "no scalar 'xi_r'"),
    ("bars over a variable the stage does not depend on", dict(BARS, stage="pore", groups="R_pore"), "report.plots[0].bars", "'nu'"),
]
for what, plot, path, words in ERRORS:
    try:
        plt.close(report.figure(plot, "report.plots[0]"))
        check(False, f"{what}: drawn")
    except ReportError as e:
        check(str(e).startswith(path) and words in str(e), f"{what}: {e}")
check(not plt.get_fignums(), "no figure is left open after an error")

failed = finish()
assert not failed, f"{len(failed)} check(s) failed: {failed}"
