"""The study report: results/<study>/report/summary.md, CSV tables and PNG plots (docs/manifests.md).

Reads the analysis outputs of the campaign (HDF5 tables and scalars with units and definitions),
draws the configured plots with the theory overlays of spec 70, and lists every scalar measured.
Written into report.partial/ and renamed, so a report is either complete or absent."""
import csv
import fnmatch
import json
import math
import os
import shutil
import sys
import time

from .expand import grid_points
from .fits import weighted_line
from .manifest import format_value

EXIT_FAILED = 3
H5MD_OUTPUTS = {"state", "trajectory"}  # output kinds (tool descriptions) that are H5MD files with a species table


def _imports():
    import h5py  # noqa: F401
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt  # noqa: F401
    import numpy  # noqa: F401


def read_scalars(path, details=False):
    """{name: (value, error, units, definition)} of an analysis output; with details, a fifth entry:
    the scalar's details (a dict: fit window, run parameters ...)."""
    import h5py
    out = {}
    with h5py.File(path, "r") as f:
        if "scalars" not in f:
            return out
        for name, ds in f["scalars"].items():
            v = ds[...]
            out[name] = (float(v[0]), float(v[1]) if v.shape[0] > 1 else float("nan"),
                         _attr(ds, "units"), _attr(ds, "definition")) + ((json.loads(_attr(ds, "details") or "{}"),) if details else ())
    return out


def read_table(path, table):
    import h5py
    with h5py.File(path, "r") as f:
        if table not in f:
            raise KeyError(f"{path} has no table '{table}' (tables: {', '.join(k for k in f if k not in ('scalars',) and hasattr(f[k], 'keys'))})")
        return {k: f[table][k][...] for k in f[table]}, {k: _attr(f[table][k], "units") for k in f[table]}


def window_text(path):
    """The time window a stage analysed (its output's root attribute `window`), or None."""
    import h5py
    with h5py.File(path, "r") as f:
        if "window" not in f.attrs:
            return None
        w = json.loads(_attr(f, "window"))
    span = f"t = {format_value(w['from']) if w['from'] is not None else 'start'} … {format_value(w['to']) if w['to'] is not None else 'end'}"
    frames = f"{w['frames']} frames" + (f", stride {w['stride']}" if w["stride"] > 1 else "")
    if w["frames"]:
        frames += f": {w['first_frame']}–{w['last_frame']} at t = {w['first_time']:.5g} … {w['last_time']:.5g}"
    return f"Time window {span} ({frames})."


def _attr(obj, name):
    v = obj.attrs.get(name, "")
    return v.decode() if isinstance(v, bytes) else str(v)


def point_text(point):
    return ", ".join(f"{k} = {format_value(v)}" for k, v in point.items()) or "(single point)"


def fmt(value, error):
    if value is None or (isinstance(value, float) and math.isnan(value)):
        return "n/a"
    if error is None or math.isnan(error) or error == 0:
        return f"{value:.5g}"
    return f"{value:.5g} ± {error:.2g}"


class ReportError(Exception):
    pass


def generate(m, jobs, by_stage, campaign, quiet=False):
    try:
        _imports()
    except ImportError as e:
        print(f"anisodyn-run: error: the report needs Python 3 with h5py, numpy and matplotlib ({e}); "
              "run scripts/setup, or use --no-report", file=sys.stderr)
        return EXIT_FAILED
    final = os.path.join(campaign, "report")
    work = final + ".partial"
    shutil.rmtree(work, ignore_errors=True)
    os.makedirs(work)
    try:
        lines = Report(m, jobs, by_stage, campaign, work).write()
    except (ReportError, KeyError, OSError) as e:
        shutil.rmtree(work, ignore_errors=True)
        print(f"anisodyn-run: error: report: {e}", file=sys.stderr)
        return EXIT_FAILED
    with open(os.path.join(work, "summary.md"), "w") as f:
        f.write("\n".join(lines) + "\n")
    shutil.rmtree(final, ignore_errors=True)
    os.replace(work, final)
    if not quiet:
        print(f"[{m['study']}] report: {os.path.join(final, 'summary.md')}", file=sys.stderr)
    return 0


class Report:
    def __init__(self, m, jobs, by_stage, campaign, out):
        self.m, self.jobs, self.by_stage, self.campaign, self.out = m, jobs, by_stage, campaign, out
        self.spec = m.get("report", {})
        self.varying = []  # grid variables that differ among the jobs of the current plot
        self.drawn, self.notes = [], []  # of the current plot: its scalar points, text under it (a fitted line)

    def stage_jobs(self, stage, where="report"):
        if stage not in self.by_stage:
            raise ReportError(f"{where}: no stage '{stage}' in the manifest")
        return [self.jobs[j] for j in self.by_stage[stage]]

    def path(self, job):
        return os.path.join(self.campaign, job.output)

    def write(self):
        m = self.m
        points = len(grid_points(m))
        lines = [f"# {self.spec.get('title', m['study'])}", "", m.get("description", ""), "",
                 f"Study `{m['study']}`; generated {time.strftime('%Y-%m-%d %H:%M:%S')} from {len(self.jobs)} jobs "
                 f"({points} grid point{'s' if points != 1 else ''} × {m.get('replicas', 1)} replicas). Values are means ± "
                 "standard errors over replicas (docs/analysis.md).", ""]
        for k, block in enumerate(self.spec.get("scalars", [])):
            lines += self.scalar_table(block, k)
        plots = self.spec.get("plots", [])
        if plots:
            lines += ["## Plots", ""]
        for k, plot in enumerate(plots):
            lines += self.plot(plot, k)
        if "raspberry" in self.spec:
            lines += self.raspberry(self.spec["raspberry"])
        if "spheroid_reference" in self.spec:
            lines += self.spheroid_reference(self.spec["spheroid_reference"])
        lines += self.diffusion_sources()
        lines += self.all_scalars()
        return lines

    def raspberry(self, spec):
        from .raspberry import RaspberryError, Section
        try:
            return Section(spec, self.stage_jobs(spec["stage"], "report.raspberry"), self.path, self.out, self.campaign).write()
        except (RaspberryError, ValueError) as e:
            raise ReportError(f"report.raspberry: {e}")

    def spheroid_reference(self, spec):
        """Spec 40 §8.6's factors (spheroid_theory.py) against spec 70 §7.3's printed table, each entry within
        `tolerance` or half a unit of its last printed digit, whichever is larger; and the table's identities."""
        from .spheroid_theory import identity_checks, table_comparison
        tolerance = spec.get("tolerance", 1e-4)
        rows = table_comparison()
        failed = [r for r in rows if r[4] > max(tolerance, r[5])]
        worst = max(rows, key=lambda r: r[4])
        with open(os.path.join(self.out, "spheroid_reference.csv"), "w", newline="") as f:
            w = csv.writer(f)
            w.writerow(["phi", "factor", "computed", "printed", "difference", "half_unit_of_last_digit"])
            w.writerows(rows)
        lines = ["## Spheroid factors against spec 70 §7.3 (spec 40 §8.6)", "",
                 f"{len(rows)} printed entries (A, B, E–L as t_ax, t_perp, r_ax, r_perp, and R_eff,t) against "
                 "`workflows/anisodyn_run/spheroid_theory.py`: largest difference "
                 f"{worst[4]:.2g} (φ = {worst[0]}, {worst[1]}: {worst[2]:.6g} against {worst[3]}); "
                 f"{len(rows) - len(failed)} of {len(rows)} within {tolerance:g} or half a unit of their last digit. "
                 "Table: [spheroid_reference.csv](spheroid_reference.csv)", ""]
        lines += [f"- not within: φ = {r[0]}, {r[1]} = {r[2]:.6g}, printed {r[3]}" for r in failed]
        lines += ["| identity | computed | reference | relative difference |", "|---|---|---|---|"]
        lines += [f"| {what} | {value:.10g} | {ref:.10g} | {abs(value - ref) / abs(ref):.1e} |" for what, value, ref in identity_checks()]
        return lines + [""]

    def diffusion_sources(self):
        """Where each species' diffusion tensors came from: the engine outputs' provenance records the
        species file and entry (or "configuration" for values given in the stage's parameters)."""
        import h5py
        import json
        rows = {}
        for st in self.m["stages"]:
            for job in self.stage_jobs(st["name"]):
                if job.info["output"]["kind"] not in H5MD_OUTPUTS:
                    continue
                try:
                    with h5py.File(self.path(job), "r") as f:
                        text = f["parameters/provenance"][()] if "parameters/provenance" in f else b"{}"
                except OSError:
                    continue
                sources = json.loads(text.decode() if isinstance(text, bytes) else text).get("diffusion_sources", {})
                for species, origin in sources.items():
                    if isinstance(origin, dict):
                        where = f"`{origin['file']}`, entry `{origin['species']}`"
                        reference = origin.get("source", "")
                    else:
                        where, reference = f"{origin} (stage `{st['name']}`)", ""
                    rows[(point_text(job.point), species, where)] = reference
        if not rows:
            return []
        lines = ["## Diffusion tensors", "", "Where each species' infinite-dilution diffusion tensors came from (provenance of the "
                 "engine outputs).", "", "| grid point | species | taken from | published source |", "|---|---|---|---|"]
        lines += [f"| {p} | {sp} | {w} | {ref} |" for (p, sp, w), ref in sorted(rows.items())]
        return lines + [""]

    # --- tables ---------------------------------------------------------------------------
    def scalar_table(self, block, k):
        where = f"report.scalars[{k}]"
        jobs = self.stage_jobs(block.get("stage"), where)
        patterns = block.get("names", ["*"])
        rows, names, units = [], [], {}
        for job in jobs:
            scalars = read_scalars(self.path(job))
            chosen = [n for n in scalars if any(fnmatch.fnmatch(n, p) for p in patterns)]
            for n in chosen:
                if n not in names:
                    names.append(n)
                units[n] = scalars[n][2]
            rows.append((job.point, scalars))
        if not names:
            raise ReportError(f"{where}.names: no scalar of stage '{block['stage']}' matches {patterns}")
        grid_vars = list(self.m.get("grid", {}))
        # One file per block: a second block of the same stage gets the block's number (it would overwrite the first).
        csv_name = f"{block['stage']}_scalars.csv"
        if any(b.get("stage") == block["stage"] for b in self.spec.get("scalars", [])[:k]):
            csv_name = f"{block['stage']}_scalars_{k}.csv"
        with open(os.path.join(self.out, csv_name), "w", newline="") as f:
            w = csv.writer(f)
            w.writerow(grid_vars + sum([[n, n + "_se"] for n in names], []))
            w.writerow([""] * len(grid_vars) + sum([[units[n], units[n]] for n in names], []))
            for point, scalars in rows:
                w.writerow([format_value(point[v]) if v in point else "" for v in grid_vars] +
                           sum([[scalars[n][0], scalars[n][1]] if n in scalars else ["", ""] for n in names], []))
        title = block.get("caption", f"Scalars of stage {block['stage']}")
        lines = [f"## {title}", "", f"Table: [{csv_name}]({csv_name})", ""]
        header = [v for v in grid_vars if any(v in p for p, _ in rows)] or ["point"]
        lines.append("| " + " | ".join(header + [f"{n} ({units[n]})" for n in names]) + " |")
        lines.append("|" + "---|" * (len(header) + len(names)))
        for point, scalars in rows:
            cells = [format_value(point[v]) if v in point else "" for v in header] if header != ["point"] else ["—"]
            cells += [fmt(*scalars[n][:2]) if n in scalars else "" for n in names]
            lines.append("| " + " | ".join(cells) + " |")
        return lines + [""]

    def all_scalars(self):
        lines = ["## Every scalar measured", ""]
        for st in self.m["stages"]:
            for job in self.stage_jobs(st["name"]):
                if job.info["output"]["kind"] != "analysis":
                    continue
                try:
                    scalars = read_scalars(self.path(job))
                except OSError:
                    continue
                if not scalars:
                    continue
                lines += [f"### {st['name']} — {point_text(job.point)}", ""]
                window = window_text(self.path(job))
                if window:
                    lines += [window, ""]
                lines += ["| scalar | value ± SE | units | definition |", "|---|---|---|---|"]
                for n, (v, e, u, d) in scalars.items():
                    lines.append(f"| {n} | {fmt(v, e)} | {u} | {d.replace('|', '/')} |")
                lines.append("")
        return lines

    # --- plots ----------------------------------------------------------------------------
    def plot(self, spec, k):
        import matplotlib.pyplot as plt
        where = f"report.plots[{k}]"
        name = spec.get("name", f"plot{k}")
        fig = self.figure(spec, where, name)
        png = f"{name}.png"
        fig.savefig(os.path.join(self.out, png), dpi=110, bbox_inches="tight")  # "tight" keeps a panel's legend beside it
        plt.close(fig)
        return ([f"### {spec.get('title', name)}", "", f"![{name}]({png})", ""] + ([spec["caption"], ""] if "caption" in spec else [])
                + [line for note in self.notes for line in (note, "")])

    def figure(self, spec, where, name=""):
        """The plot's figure: a panel for a curve plot with rows, else one set of axes of the plot's kind."""
        import matplotlib.pyplot as plt
        self.drawn, self.notes = [], []  # the scalar points drawn, and text a fitted line leaves under the plot
        if "table" in spec and "rows" in spec:
            return self.panel(spec, where)
        fig, ax = plt.subplots(figsize=(6.4, 4.6))
        try:
            if "table" in spec:
                self.curve_plot(ax, spec, where)
            elif "bars" in spec:
                self.bar_plot(ax, spec, where)
            elif "scalar" in spec or isinstance(spec.get("series"), list):
                self.scalar_plot(ax, spec, where)
            else:
                raise ReportError(f"{where}: expected 'table' (curves), 'scalar' or a 'series' list (scalars against a grid variable)")
        except BaseException:
            plt.close(fig)
            raise
        self.log_axes(ax, spec)
        ax.set_xlabel(spec.get("xlabel", spec.get("x", spec.get("groups", ""))))
        ax.set_ylabel(spec.get("ylabel", ", ".join(spec["y"]) if "table" in spec else
                               spec.get("scalar") or ", ".join(e.get("label", e["scalar"]) for e in spec["series"])))
        ax.set_title(spec.get("title", name))
        if ax.get_legend_handles_labels()[0]:
            ax.legend(fontsize=7)
        fig.tight_layout()
        return fig

    @staticmethod
    def log_axes(ax, spec):
        log = spec.get("log", "")
        if "x" in log:
            ax.set_xscale("log")
        if "y" in log:
            ax.set_yscale("log")

    def panel(self, spec, where):
        """A curve plot with `rows`: a subplot per value of that grid variable (rows) and y column (columns), each
        curve coloured by its grid point alike in every subplot, one legend for the figure. x is shared, and y
        along a column, so that the rows compare one quantity (D5: S_x, S_y, S_z per xi_bead)."""
        import matplotlib.pyplot as plt
        from matplotlib.container import Container
        var, ys = spec["rows"], spec["y"]
        jobs = self.selected_jobs(spec, where)
        values = [v for v in self.m["grid"][var] if any(format_value(j.point.get(var)) == format_value(v) for j in jobs)]
        if not values:
            raise ReportError(f"{where}.rows: no selected grid point of stage '{spec['stage']}' has a value of '{var}' "
                              "(the stage does not depend on it, or select excludes every point)")
        varying = [v for v in self.m.get("grid", {}) if v != var and len({format_value(j.point.get(v)) for j in jobs}) > 1]
        fig, axes = plt.subplots(len(values), len(ys), figsize=(3.4 * len(ys), 2.6 * len(values) + 0.6), sharex=True, sharey="col",
                                 squeeze=False)
        palette = {}  # one colour per grid point across the subplots
        try:
            for r, value in enumerate(values):
                for c, y in enumerate(ys):
                    ax = axes[r][c]
                    self.curve_plot(ax, spec, where, {**spec.get("select", {}), var: value}, [y], varying, palette, value)
                    self.log_axes(ax, spec)
                    ax.set_title(f"{y}, {var} = {format_value(value)}", fontsize=9)
                axes[r][0].set_ylabel(spec.get("ylabel", ", ".join(ys)))
        except BaseException:
            plt.close(fig)
            raise
        for ax in axes[-1]:
            ax.set_xlabel(spec.get("xlabel", spec.get("x", "time")))
        fig.suptitle(spec.get("title", spec.get("name", "")))
        fig.tight_layout()
        legend = {}  # label -> handle, once for the figure (a curve recurs in every column)
        for ax in axes.flat:
            for handle, label in zip(*ax.get_legend_handles_labels()):
                legend.setdefault(label, handle)
        # curves (error-bar containers) before the theory points, which matplotlib lists first as plain lines
        legend = dict(sorted(legend.items(), key=lambda item: not isinstance(item[1], Container)))
        if legend:
            fig.legend(legend.values(), legend.keys(), loc="center left", bbox_to_anchor=(1.0, 0.5), fontsize=7)
        return fig

    def selected_jobs(self, spec, where, select=None):
        jobs = self.stage_jobs(spec.get("stage"), where)
        sel = spec.get("select", {}) if select is None else select
        return [j for j in jobs if all(format_value(j.point.get(v)) == format_value(val) for v, val in sel.items() if v in j.point)]

    def curve_plot(self, ax, spec, where, select=None, ys=None, varying=None, palette=None, row=None):
        """Columns ys (default the plot's y) of the stage's table against x, a curve per selected grid point and column;
        the overlay's curves over them in the same colours, dashed; then the theory lines. A panel passes its subplot's
        select, column, row value, the variables its legend names (varying) and the colours of its curves (palette)."""
        ys = ys or spec.get("y")
        if not isinstance(ys, list) or not ys:
            raise ReportError(f"{where}.y: expected a list of column names")
        jobs = self.selected_jobs(spec, where, select)
        if varying is None:
            varying = [v for v in self.m.get("grid", {}) if len({format_value(j.point.get(v)) for j in jobs}) > 1]
        self.varying = varying
        palette = {} if palette is None else palette
        curves = {}  # job id -> (job, x values drawn, colour)
        for job in jobs:
            for y in ys:
                point = point_text({v: job.point[v] for v in varying if v in job.point})
                # in a panel the column names y: a curve is its grid point (or its stage, when one point is drawn)
                label = (y if len(jobs) == 1 or not varying else f"{y} [{point}]") if row is None else point if varying else spec["stage"]
                colour = palette.setdefault((point, y if len(ys) > 1 else ""), f"C{len(palette) % 10}")
                xs = self.curve(ax, spec, job, y, where, label, color=colour)
                curves[job.id] = (job, xs, colour)
        over = spec.get("overlay")
        if over is not None and (row is None or "row" not in over or format_value(over["row"]) == format_value(row)):
            self.overlay(ax, spec, over, where, {**(spec.get("select", {}) if select is None else select), **over.get("select", {})},
                         ys, varying, palette)
        # a free-particle line per grid point (its species' D); any other overlay once; in a panel, in its columns only
        for t in spec.get("theory", []):
            if "columns" in t and not set(ys) & set(t["columns"]):
                continue
            per_curve = t.get("kind") in ("free_diffusion", "pore_centreline")  # drawn for each curve's grid point
            for job, xs, colour in list(curves.values())[:None if per_curve else 1]:
                self.theory(ax, t, job, xs, where, colour)

    def curve(self, ax, spec, job, y, where, label, **style):
        """One column y of the job's table against x, with error bars from <y>_se unless errors is false; the x drawn."""
        import numpy as np
        data, _ = read_table(self.path(job), spec["table"])
        x = spec.get("x", "time")
        if x not in data:
            raise ReportError(f"{where}.x: table '{spec['table']}' has no column '{x}' (columns: {', '.join(data)})")
        if y not in data:
            raise ReportError(f"{where}.y: table '{spec['table']}' has no column '{y}' (columns: {', '.join(data)})")
        err = data.get(y + "_se") if spec.get("errors", True) else None
        ok = np.isfinite(data[x]) & np.isfinite(data[y])
        style = {"marker": ".", "ms": 3, "lw": 1, **style}
        if err is not None:
            ax.errorbar(data[x][ok], data[y][ok], yerr=np.nan_to_num(err[ok]), label=label, capsize=1.5, **style)
        else:
            ax.plot(data[x][ok], data[y][ok], label=label, **style)
        return data[x][ok]

    def overlay(self, ax, spec, over, where, select, ys, varying, palette):
        """The overlay stage's curves (the same table and columns; D5: the single-layer ablation over xi_bead = 1000),
        dashed with open markers, each in the colour of the plot's curve at the same values of the varying variables."""
        jobs = self.selected_jobs(over, f"{where}.overlay", select)
        own = [v for v in self.m.get("grid", {}) if len({format_value(j.point.get(v)) for j in jobs}) > 1]
        label = over.get("label", over["stage"])
        for job in jobs:
            for y in ys:
                point = point_text({v: job.point[v] for v in varying if v in job.point})
                colour = palette.setdefault((point, y if len(ys) > 1 else ""), f"C{len(palette) % 10}")
                text = point_text({v: job.point[v] for v in own})
                self.curve(ax, spec, job, y, f"{where}.overlay", (f"{y}, " if len(ys) > 1 else "") + label + (f" [{text}]" if own else ""),
                           color=colour, ls="--", marker="o", mfc="none", ms=3.5)

    def bar_plot(self, ax, spec, where):
        """The stage's scalar ± SE as grouped bars: a group along x per value of the grid variable `groups`, in it a
        bar per value of `bars` side by side (D6: the two fluids per box), each bar labelled with its value."""
        import numpy as np
        grid, y_scale = self.m.get("grid", {}), spec.get("y_scale", 1.0)
        cells = {}  # (group value, bar value) -> (value, SE, job)
        for job in self.selected_jobs(spec, where):
            for key in ("groups", "bars"):
                if spec[key] not in job.point:
                    raise ReportError(f"{where}.{key}: stage '{spec['stage']}' does not depend on the grid variable '{spec[key]}'")
            scalars = read_scalars(self.path(job))
            if spec["scalar"] not in scalars:
                raise ReportError(f"{where}.scalar: stage '{spec['stage']}' has no scalar '{spec['scalar']}' ({', '.join(scalars)})")
            cell = (format_value(job.point[spec["groups"]]), format_value(job.point[spec["bars"]]))
            if cell in cells:
                differ = [v for v in grid if format_value(job.point.get(v)) != format_value(cells[cell][2].point.get(v))]
                raise ReportError(f"{where}: several grid points at {spec['groups']} = {cell[0]}, {spec['bars']} = {cell[1]} "
                                  f"(they differ in {', '.join(differ)}); pick one with select")
            v, e = scalars[spec["scalar"]][:2]
            cells[cell] = (v * y_scale, e * abs(y_scale), job)
        if not cells:  # as for a scalar plot: a select no grid point matches (e.g. in a smoke variant) draws nothing
            return
        groups = [g for g in map(format_value, grid[spec["groups"]]) if any(c[0] == g for c in cells)]
        bars = [b for b in map(format_value, grid[spec["bars"]]) if any(c[1] == b for c in cells)]
        width = 0.8 / len(bars)
        for j, b in enumerate(bars):
            at = [i for i, g in enumerate(groups) if (g, b) in cells]
            values = [cells[(groups[i], b)] for i in at]
            drawn = ax.bar([i + (j - (len(bars) - 1) / 2) * width for i in at], [v for v, _, _ in values], width * 0.95,
                           yerr=np.nan_to_num([e for _, e, _ in values]), capsize=3, label=f"{spec['bars']} = {b}")
            ax.bar_label(drawn, fmt="%.3g", fontsize=7, padding=2)
        ax.set_xticks(range(len(groups)), groups)
        ax.set_xlim(-0.7, len(groups) - 0.3)  # room either side, so that a single group's bars are not stretched edge to edge
        for t in spec.get("theory", []):
            self.theory(ax, t, None, np.arange(len(groups), dtype=float), where)

    def scalar_plot(self, ax, spec, where):
        """Scalars ± SE against the grid variable `x` (times `x_scale`, to the power `x_power`): one stage's scalar, one series per
        value of the grid variable `series`; or, with `series` a list, one series per entry, each with its
        own stage, scalar and select (an entry whose stage does not depend on `x` is a horizontal line)."""
        import numpy as np
        x, factor, power = spec.get("x"), spec.get("x_scale", 1.0), spec.get("x_power", 1.0)
        scale = self.x_scaling(factor, power)  # grid value → x coordinate
        grid = self.m.get("grid", {})
        fixed_x = isinstance(spec.get("series"), list) and all("at_x" in e for e in spec["series"])
        if x not in grid and not fixed_x:
            raise ReportError(f"{where}.x: expected a grid variable ({', '.join(grid) or 'none'})")
        if isinstance(spec.get("series"), list):
            xs = []
            for i, entry in enumerate(spec["series"]):
                select = {**spec.get("select", {}), **entry.get("select", {})}
                own = self.x_scaling(entry.get("x_scale", factor), power)
                xs += self.listed_series(ax, {"y_scale": spec.get("y_scale", 1.0), **entry}, f"{where}.series[{i}]", x, own, select)
        else:
            by = spec.get("series")
            if by is not None and by not in grid:
                raise ReportError(f"{where}.series: expected a grid variable ({', '.join(grid) or 'none'})")
            groups = {}
            for xv, v, e, job in self.scalar_points(spec, where, x, scale, spec.get("select", {})):
                v, e = v * spec.get("y_scale", 1.0), e * abs(spec.get("y_scale", 1.0))
                groups.setdefault(format_value(job.point.get(by)) if by else "", []).append((xv, v, e))
            xs = []
            for label, pts in groups.items():
                xs += self.draw_points(ax, pts, f"{by} = {label}" if by else spec["scalar"])
        if not fixed_x and not all(isinstance(v, (int, float)) and not isinstance(v, bool) for v in grid[x]):
            ax.set_xticks(range(len(grid[x])), [format_value(v) for v in grid[x]])
        xs = np.array(sorted(set(xs)))
        for t in spec.get("theory", []):
            if t.get("kind") == "fit_line":
                self.fit_line(ax, t, where)
            else:
                self.theory(ax, t, None, xs, where)

    def scalar_points(self, item, where, x, scale, select, constant_allowed=False):
        """(x coordinate, value, SE, job) of item's scalar for every selected grid point of item's stage; the
        x coordinate is None for a stage that does not depend on x (an error unless constant_allowed)."""
        out = []
        for job in self.selected_jobs(item, where, select):
            scalars = read_scalars(self.path(job))
            if item["scalar"] not in scalars:
                raise ReportError(f"{where}.scalar: stage '{item['stage']}' has no scalar '{item['scalar']}' ({', '.join(scalars)})")
            v, e = scalars[item["scalar"]][:2]
            out.append((scale(self.axis_value(x, job.point[x])) if x in job.point else None, v, e, job))
        if out and out[0][0] is None and not constant_allowed:
            raise ReportError(f"{where}.x: stage '{item['stage']}' does not depend on the grid variable '{x}'")
        return out

    def listed_series(self, ax, entry, where, x, scale, select):
        """One entry of a series list: its points against x, or a horizontal line (± `band`) when its stage
        does not depend on x. Several grid points at one x are an error: select must pick one."""
        label = entry.get("label", entry["scalar"])
        y = entry.get("y_scale", 1.0)
        points = [(xv, v * y, e * abs(y), job) for xv, v, e, job in self.scalar_points(entry, where, x, scale, select, constant_allowed=True)]
        if "at_x" in entry:  # the entry's one grid point, drawn at its own x (e.g. a rod's aspect ratio)
            if len(points) > 1:
                raise ReportError(f"{where}: {len(points)} grid points for an entry with at_x; pick one with select")
            return self.draw_points(ax, [(entry["at_x"], v, e) for _, v, e, _ in points], label) if points else []
        if not points:  # as for the single scalar: a select no grid point matches (e.g. in a smoke variant) draws nothing
            return []
        if points[0][0] is None:
            if len(points) > 1:
                raise ReportError(f"{where}: stage '{entry['stage']}' has {len(points)} grid points that do not differ in "
                                  f"'{x}'; pick one with select")
            value = points[0][1]
            probe, = ax.plot([], [])  # the next colour of the cycle (axhline does not take one)
            color = probe.get_color()
            probe.remove()
            ax.axhline(value, lw=1.2, color=color, label=label)
            if "band" in entry:
                ax.axhspan(value * (1 - entry["band"]), value * (1 + entry["band"]), color=color, alpha=0.15, lw=0,
                           label=f"{label} ± {100 * entry['band']:g}%")
            return []
        if "band" in entry:
            raise ReportError(f"{where}.band: no 'band': it has no effect, stage '{entry['stage']}' varies with '{x}' "
                              "(a band goes around the horizontal line of a stage that does not)")
        at = {}
        for xv, _, _, job in points:
            if xv in at:
                differ = [v for v in self.m.get("grid", {}) if format_value(job.point.get(v)) != format_value(at[xv].point.get(v))]
                raise ReportError(f"{where}: stage '{entry['stage']}' has several grid points at {x} = "
                                  f"{format_value(job.point[x])} (they differ in {', '.join(differ)}); pick one with select")
            at[xv] = job
        return self.draw_points(ax, [p[:3] for p in points], label)

    @staticmethod
    def x_scaling(factor, power):
        """Grid value → x coordinate: (value × factor) ** power."""
        return (lambda v: (v * factor) ** power) if power != 1.0 else (lambda v: v * factor)

    def draw_points(self, ax, points, label):
        import numpy as np
        a = np.array(sorted(points, key=lambda p: p[0]), dtype=float)
        ax.errorbar(a[:, 0], a[:, 1], yerr=np.nan_to_num(a[:, 2]), marker="o", ms=4, capsize=2, label=label)
        self.drawn += [tuple(row) for row in a]  # for a fitted line over the plot's points
        return list(a[:, 0])

    def fit_line(self, ax, t, where):
        """The weighted least-squares line c0 + c1 x through every point the scalar plot drew (fits.weighted_line:
        weights 1/SE², or equal when an SE is missing), drawn, and noted under the plot."""
        import numpy as np
        if len(self.drawn) < 3:
            raise ReportError(f"{where}.theory: a fitted line needs at least 3 points, the plot has {len(self.drawn)}")
        x, y, e = (np.array(c, dtype=float) for c in zip(*self.drawn))
        fit = weighted_line(x, y, e)
        line = np.linspace(min(0.0, x.min()), x.max(), 100)
        text = (f"fit: c0 = {fit.c0:.4g} ± {fit.c0_se:.2g}, c1 = {fit.c1:.4g} ± {fit.c1_se:.2g} ({len(x)} points, "
                f"reduced chi2 {fit.chi2:.2g})")
        ax.plot(line, fit.c0 + fit.c1 * line, color="k", lw=1, ls=":", label=t.get("label", text))
        self.notes.append(text)

    def axis_value(self, var, value):
        """A grid value as a plot coordinate: the number, or the position in the grid's list."""
        if isinstance(value, (int, float)) and not isinstance(value, bool):
            return float(value)
        return float([format_value(v) for v in self.m["grid"][var]].index(format_value(value)))

    # --- theory overlays (spec 70) ---------------------------------------------------------
    def theory(self, ax, t, job, xs, where, colour=None):
        """One theory line over x values xs; job is the curve's (or the plot's first), colour the curve's (a point
        of that curve's grid point, such as the pore centreline, takes it, so that several pores can be told apart)."""
        import numpy as np
        kind = t.get("kind")
        if len(xs) == 0:
            return
        lo, hi = float(np.min(xs[xs > 0])) if np.any(xs > 0) else float(np.min(xs)), float(np.max(xs))
        grid = np.geomspace(lo, hi, 200) if lo > 0 else np.linspace(lo, hi, 200)
        style = dict(color="k", lw=1, ls="--")
        if kind == "constant":
            ax.axhline(t["value"], label=t.get("label", f"theory: {t['value']}"), **style)
        elif kind == "linear":  # from x = 0 (the intercept) when the data are at x > 0
            line = np.linspace(min(0.0, float(np.min(xs))), hi, 200)
            ax.plot(line, t["intercept"] + t["slope"] * line,
                    label=t.get("label", f"{t['intercept']:g} + {t['slope']:g} x"), **style)
        elif kind == "power":
            ax.plot(grid, t["prefactor"] * grid ** t["exponent"], label=t.get("label", f"∝ x^{t['exponent']}"), **style)
        elif kind == "exponential":
            ax.plot(grid, t.get("amplitude", 1.0) * np.exp(-grid / t["tau"]), label=t.get("label", f"exp(-t/{t['tau']:.3g})"), **style)
        elif kind == "free_diffusion":
            slope = 2.0 * self.free_diffusivity(job, t, where)
            shown = {v: job.point[v] for v in self.varying if job is not None and v in job.point}
            suffix = f" [{point_text(shown)}]" if shown else ""
            ax.plot(grid, slope * grid, label=t.get("label", f"free diffusion, {t.get('component', 'tot')}") + suffix, **style)
        elif kind == "wertheim":
            scalars = read_scalars(self.path(job))
            name = t.get("scalar", "p_b")
            match = [n for n in scalars if fnmatch.fnmatch(n, name)]
            if not match:
                raise ReportError(f"{where}.theory: no scalar '{name}' for the Wertheim line")
            pb = scalars[match[0]][0]
            ls = np.arange(max(1, int(lo)), int(hi) + 1)
            ax.plot(ls, (1 - pb) ** 2 * pb ** (ls - 1), label=t.get("label", f"Wertheim, p_b = {pb:.3g}"), **style)
        elif kind == "tirado_ratio":
            # x = p = L/d: D_par/D_perp of a stick cylinder, Tirado & Garcia de la Torre (spec 30 §10)
            p = np.linspace(min(lo, 2.0), max(hi, 2.0), 200)
            nu_par = -0.207 + 0.980 / p - 0.133 / p ** 2
            nu_perp = 0.839 + 0.185 / p + 0.233 / p ** 2
            ax.plot(p, 2 * (np.log(p) + nu_par) / (np.log(p) + nu_perp), label=t.get("label", "Tirado-Garcia de la Torre"), **style)
        elif kind in ("hasimoto", "periodic_rotation"):
            # x = phi^(1/3): spec 30 §10's reduced D of a sphere in a simple cubic periodic array (Hasimoto's
            # Q, with Q' = (3 + 27.9 phi)/2 for slip), or a body's rotation (1 - phi)/pi (Linke, Kofinger & Hummer).
            line = np.linspace(0.0, hi, 200)
            phi = line ** 3
            if kind == "hasimoto":
                y = (1 - 1.7601 * line + phi - 1.5593 * phi ** 2) / (3 * np.pi)
                if t.get("boundary", "stick") == "slip":
                    y *= (3 + 27.9 * phi) / 2
                default = f"Hasimoto, {t.get('boundary', 'stick')}"
            else:
                y, default = (1 - phi) / np.pi, "(1 - phi)/pi"
            line_art, = ax.plot(line, y, label=t.get("label", default), **{**style, "color": None})
            if "band" in t:
                ax.fill_between(line, y * (1 - t["band"]), y * (1 + t["band"]), color=line_art.get_color(), alpha=0.15, lw=0,
                                label=f"± {100 * t['band']:g}%")
        elif kind == "pore_centreline":
            # x = beta: spec 70 §7.4's centreline drag K(lambda = radius/R_pore) of the curve's pore, as a point at beta = 0.
            from .pore_theory import FORMULAS, LABELS
            pore = job.point.get(t.get("pore_radius", "R_pore"))
            if pore is None:
                raise ReportError(f"{where}.theory.pore_radius: the curve's grid point has no '{t.get('pore_radius', 'R_pore')}'")
            lam = t["radius"] / float(pore)
            formula = t.get("formula", "haberman_sayre")
            hs = formula == "haberman_sayre"
            ax.plot([0.0], [FORMULAS[formula](lam)], marker="*" if hs else "D", ms=10 if hs else 6, ls="none", zorder=3,
                    color=colour or ("k" if hs else "0.55"), mec="k", mew=0.6,
                    label=t.get("label", f"{LABELS[formula]} (external), lambda = {lam:.3g}"))
        elif kind == "spheroid":
            # x = phi = a/c: a factor of spec 40 §8.6 (A, B, t_ax, t_perp, r_ax, r_perp, t_ratio, r_ratio), times `scale`.
            from .spheroid_theory import factor
            # A single aspect ratio (a smoke) gets the curve over a factor 1.25 either side, so the
            # point is seen against it.
            lo, hi = (lo / 1.25, hi * 1.25) if lo == hi and lo > 0 else (lo, hi)
            phis = np.geomspace(lo, hi, 200) if lo > 0 else np.linspace(lo, hi, 200)
            y = [t.get("scale", 1.0) * factor(t["factor"], float(p)) for p in phis]
            ax.plot(phis, y, label=t.get("label", f"spheroid {t['factor']} (spec 40 §8.6)"), **style)
        else:
            raise ReportError(f"{where}.theory: unknown kind '{kind}' (constant, linear, power, exponential, free_diffusion, wertheim, "
                              "hasimoto, periodic_rotation, tirado_ratio, spheroid)")

    def free_diffusivity(self, job, t, where):
        """D of the free-particle line (MSD = 2 D t), from the D0 scalars the msd stage wrote from its
        trajectory's species table: for the total MSD the sum over axes, 3 D0_tot."""
        species, component = t.get("species"), t.get("component", "tot")
        column = {"tot": "tot", "x": "x", "y": "y", "z": "z", "T": "body_x", "W": "body_y", "L": "body_z"}.get(component)
        if column is None:
            raise ReportError(f"{where}.theory.component: expected tot, x, y, z, T, W or L")
        scalars = read_scalars(self.path(job))
        name = f"D0_{column}_{species}"
        if name not in scalars:
            known = sorted(n[len("D0_"):] for n in scalars if n.startswith("D0_"))
            raise ReportError(f"{where}.theory: stage '{job.stage}' wrote no {name} (an anisodyn-msd output whose trajectory "
                              f"has D_trans for '{species}'; T, W, L need body_frame: true); it has D0 for: "
                              f"{', '.join(known) or 'none'}")
        d0 = scalars[name][0]
        return 3.0 * d0 if component == "tot" else d0

