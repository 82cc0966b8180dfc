"""Spec 40 §8.1, §8.5 and §8.6 across the jobs of a raspberry diffusion study: the report's
`raspberry` block (docs/manifests.md, "Report").

Each anisodyn-lb-diffusion output gives one body in one box. The jobs of one body (every grid
variable but the box) are combined here:
  - D_0 = the intercept of D_t against 1/L (spec 40 §8.1, Hasimoto), for the lab D_t and each
    body-axis D_t,i; with one box, D_t + 2.837297 kT/(6 pi eta L) (Hasimoto's slope, not fitted);
  - D_r = the weighted mean over the boxes (no finite-size correction, spec 40 §8.2);
  - xi^t = kT/D_0 and xi^r = kT/D_r.
A study of spheres fits the calibration lines xi^t = m_t R + b_t and xi^r = m_r R^3 + b_r per
value of a grid variable (xi_bead) and writes them to raspberry_calibration.json; a study of
spheroids inverts such lines (or the Stokes lines 6 pi eta R, 8 pi eta R^3) into effective radii
and the factors A, B and t_ax, t_perp, r_ax, r_perp (E-L) of spec 40 §8.6, drawn against
Perrin and Happel-Brenner (spheroid_theory.py)."""
import csv
import json
import math
import os

from .fits import weighted_line, weighted_mean
from .manifest import format_value
from .report import fmt, read_scalars

HASIMOTO = 2.837297
TRANSLATION = ("D_t", "D_t_body_x", "D_t_body_y", "D_t_body_z")
ROTATION = ("D_r", "D_r_three_axis", "D_r_body_x", "D_r_body_y", "D_r_body_z")
CALIBRATION_FILE = "raspberry_calibration.json"


class RaspberryError(Exception):
    pass


class Extrapolation:
    """D_0 of one body from its boxes: value, SE, and how it was found."""

    def __init__(self, boxes, values, ses, kT, eta):
        theory_slope = -HASIMOTO * kT / (6.0 * math.pi * eta)
        self.boxes, self.theory_slope = sorted(boxes), theory_slope
        if len(set(boxes)) == 1:
            self.value = values[0] - theory_slope / boxes[0]
            self.se, self.slope, self.slope_se, self.chi2 = ses[0], theory_slope, 0.0, float("nan")
            self.method = "one box, Hasimoto's slope"
        else:
            fit = weighted_line([1.0 / L for L in boxes], values, ses)
            self.value, self.se, self.slope, self.slope_se, self.chi2 = fit.c0, fit.c0_se, fit.c1, fit.c1_se, fit.chi2
            self.method = f"fit over {len(boxes)} boxes"


class Body:
    """One raspberry (a grid point without the box variable) over its boxes."""

    def __init__(self, point, runs):
        details = runs[0][1]["D_t"][4]
        self.point = point
        self.semi_axes = details["semi_axes"]
        self.radius, self.kT, self.eta, self.friction_scale = details["radius"], details["kT"], details["eta"], details["friction_scale"]
        if details.get("rotation_convention", "default") != "default":
            raise RaspberryError(f"{point_label(point)}: the factors need D_r in the default convention (the stage used "
                                 f"rotation_convention '{details['rotation_convention']}')")
        self.boxes = [d["D_t"][4]["box"] for _, d in runs]
        self.translation = {n: Extrapolation(self.boxes, [d[n][0] for _, d in runs], [d[n][1] for _, d in runs], self.kT, self.eta)
                            for n in TRANSLATION}
        self.rotation = {n: weighted_mean([d[n][0] for _, d in runs], [d[n][1] for _, d in runs]) for n in ROTATION}

    @property
    def aspect(self):
        return self.semi_axes[0] / self.semi_axes[1]

    def friction_t(self, names=("D_t",)):
        """kT / D_0 (± SE) with D_0 the mean of the named extrapolations (e.g. the two body axes across)."""
        d = sum(self.translation[n].value for n in names) / len(names)
        se = math.sqrt(sum(self.translation[n].se ** 2 for n in names)) / len(names)
        return self.kT / d, self.kT * se / d ** 2

    def friction_r(self, names=("D_r",)):
        d = sum(self.rotation[n][0] for n in names) / len(names)
        se = math.sqrt(sum(self.rotation[n][1] ** 2 for n in names)) / len(names)
        return self.kT / d, self.kT * se / d ** 2


def point_label(point):
    return ", ".join(f"{k} = {v:.5g}" if isinstance(v, float) else f"{k} = {format_value(v)}" for k, v in point.items()) or "(single point)"


def collect_bodies(jobs, path_of, box_var):
    """The bodies of a stage's jobs, grouped by every grid variable but box_var."""
    groups = {}
    for job in jobs:
        key = tuple((k, format_value(v)) for k, v in job.point.items() if k != box_var)
        groups.setdefault(key, []).append((job, read_scalars(path_of(job), details=True)))
    bodies = []
    for key, runs in groups.items():
        missing = [n for n in TRANSLATION + ROTATION if n not in runs[0][1]]
        if missing:
            raise RaspberryError(f"{path_of(runs[0][0])}: no scalars {', '.join(missing)} (an anisodyn-lb-diffusion output?)")
        bodies.append(Body({k: v for k, v in runs[0][0].point.items() if k != box_var}, runs))
    return bodies


class Calibration:
    """xi^t = m_t R + b_t and xi^r = m_r R^3 + b_r (spec 40 §8.5), with the parameters' covariances, in the
    units of the simulated fluid (eta, kT, friction_scale recorded with them)."""

    def __init__(self, t, r, eta, kT, friction_scale, source, radii=()):
        self.t, self.r = t, r  # each {"m", "b", "cov" [[bb, bm], [mb, mm]], "r2", "chi2", "points"}
        self.eta, self.kT, self.friction_scale, self.source, self.radii = eta, kT, friction_scale, source, list(radii)

    @staticmethod
    def fitted(bodies, source):
        radii = [b.radius for b in bodies]
        lines = []
        for x, friction in ((radii, Body.friction_t), ([r ** 3 for r in radii], Body.friction_r)):
            xi = [friction(b) for b in bodies]
            fit = weighted_line(x, [v for v, _ in xi], [e for _, e in xi])
            lines.append({"m": fit.c1, "b": fit.c0, "cov": fit.cov, "r2": fit.r2, "chi2": fit.chi2, "points": fit.points})
        b0 = bodies[0]
        return Calibration(lines[0], lines[1], b0.eta, b0.kT, b0.friction_scale, source, radii)

    @staticmethod
    def stokes(body):
        zero = [[0.0, 0.0], [0.0, 0.0]]
        return Calibration({"m": 6 * math.pi * body.eta, "b": 0.0, "cov": zero}, {"m": 8 * math.pi * body.eta, "b": 0.0, "cov": zero},
                           body.eta, body.kT, body.friction_scale, "the Stokes lines 6 pi eta R and 8 pi eta R^3 (no calibration)")

    def to_json(self):
        return {"t": self.t, "r": self.r, "eta": self.eta, "kT": self.kT, "friction_scale": self.friction_scale, "radii": self.radii}

    @staticmethod
    def from_json(d, source):
        return Calibration(d["t"], d["r"], d["eta"], d["kT"], d["friction_scale"], source, d.get("radii", ()))

    @staticmethod
    def invert(line, xi, xi_se):
        """x = (xi - b)/m with its SE from xi's and the line's covariance (first order)."""
        m, b, cov = line["m"], line["b"], line["cov"]
        x = (xi - b) / m
        var = (xi_se ** 2 + cov[0][0] + x * x * cov[1][1] + 2.0 * x * cov[0][1]) / (m * m)
        return x, math.sqrt(max(var, 0.0))

    def check_fluid(self, body):
        for name, mine, theirs in (("eta", self.eta, body.eta), ("kT", self.kT, body.kT), ("friction_scale", self.friction_scale, body.friction_scale)):
            if abs(mine - theirs) > 1e-9 * abs(theirs):
                raise RaspberryError(f"the calibration ({self.source}) has {name} = {mine:g}, the runs {theirs:g}: lines of another fluid")


def spheroid_factors(body, cal):
    """{factor: (value, SE)} of spec 40 §8.6 from the body's frictions through the calibration lines."""
    a, c = body.semi_axes[0], body.semi_axes[1]
    out = {}

    def radius_t(names):
        return Calibration.invert(cal.t, *body.friction_t(names))

    def radius3_r(names):
        return Calibration.invert(cal.r, *body.friction_r(names))

    R, se = radius_t(("D_t",))
    out["A"] = (a / R, a * se / R ** 2)
    for name, names in (("B", ("D_r",)), ("B_three_axis", ("D_r_three_axis",))):
        R3, se3 = radius3_r(names)
        out[name] = (a ** 3 / R3, a ** 3 * se3 / R3 ** 2)
    for name, names in (("t_ax", ("D_t_body_x",)), ("t_perp", ("D_t_body_y", "D_t_body_z"))):
        R, se = radius_t(names)
        out[name] = (R / c, se / c)
    for name, names in (("r_ax", ("D_r_body_x",)), ("r_perp", ("D_r_body_y", "D_r_body_z"))):
        R3, se3 = radius3_r(names)
        out[name] = (R3 / c ** 3, se3 / c ** 3)
    return out


FACTOR_THEORY = {"A": "A", "B": "B", "B_three_axis": "B", "t_ax": "t_ax", "t_perp": "t_perp", "r_ax": "r_ax", "r_perp": "r_perp"}
FACTOR_LETTERS = {"t_ax": ("E", "G"), "t_perp": ("F", "H"), "r_ax": ("I", "K"), "r_perp": ("J", "L")}


class Section:
    """The report's raspberry block: tables, plots and (for a calibration fit) the calibration file."""

    def __init__(self, spec, jobs, path_of, out, campaign):
        self.spec, self.out, self.campaign = spec, out, campaign
        self.bodies = sorted(collect_bodies(jobs, path_of, spec["box"]), key=lambda b: (b.aspect, b.radius, sorted(b.point.items())))

    def write(self):
        lines = ["## Raspberry frictions, calibration and factors (spec 40 §8)", "",
                 "Per body, over its boxes: D_0 the intercept of D_t against 1/L (Hasimoto, spec 40 §8.1; the fitted slope is next to "
                 f"-{HASIMOTO} kT/(6πη)), D_r the weighted mean over the boxes (§8.2), ξ^t = kT/D_0, ξ^r = kT/D_r; units of the "
                 "simulated fluid (η = ρν of the run).", ""]
        lines += self.body_table()
        if "plot" in self.spec:
            lines += self.ratio_plot(self.spec["plot"]["x"], self.spec["plot"].get("series"))
        cal = self.spec.get("calibration")
        if isinstance(cal, dict) and "fit" in cal:
            lines += self.calibration_fit(cal["fit"])
        elif cal is not None:
            lines += self.factors(cal)
        return lines

    def body_table(self):
        header = ["body", "R", "boxes", "D_0 (method)", "slope / Hasimoto's", "ξ^t", "ξ^t/(6πηR)", "D_r", "ξ^r", "ξ^r/(8πηR³)"]
        lines = ["| " + " | ".join(header) + " |", "|" + "---|" * len(header)]
        rows = []
        for b in self.bodies:
            t = b.translation["D_t"]
            xi_t, xi_t_se = b.friction_t()
            xi_r, xi_r_se = b.friction_r()
            st, sr = 6 * math.pi * b.eta * b.radius, 8 * math.pi * b.eta * b.radius ** 3
            ratio = "—" if t.method.startswith("one box") else fmt(t.slope / t.theory_slope, t.slope_se / abs(t.theory_slope))
            lines.append(f"| {point_label(b.point)} | {b.radius:.4g} | {', '.join(format_value(L) for L in t.boxes)} | "
                         f"{fmt(t.value, t.se)} ({t.method}) | {ratio} | {fmt(xi_t, xi_t_se)} | {fmt(xi_t / st, xi_t_se / st)} | "
                         f"{fmt(*b.rotation['D_r'])} | {fmt(xi_r, xi_r_se)} | {fmt(xi_r / sr, xi_r_se / sr)} |")
            rows.append({**{k: format_value(v) for k, v in b.point.items()}, "radius": b.radius, "boxes": " ".join(map(format_value, t.boxes)),
                         "D0_t": t.value, "D0_t_se": t.se, "D0_t_method": t.method, "slope": t.slope, "slope_se": t.slope_se,
                         "hasimoto_slope": t.theory_slope, "reduced_chi2": t.chi2, "xi_t": xi_t, "xi_t_se": xi_t_se,
                         "D_r": b.rotation["D_r"][0], "D_r_se": b.rotation["D_r"][1], "xi_r": xi_r, "xi_r_se": xi_r_se,
                         "xi_t_over_6pi_eta_R": xi_t / st, "xi_r_over_8pi_eta_R3": xi_r / sr, "eta": b.eta, "kT": b.kT,
                         "friction_scale": b.friction_scale})
        self.write_csv("raspberry_bodies.csv", rows)
        return ["### Frictions per body", "", "Table: [raspberry_bodies.csv](raspberry_bodies.csv)", ""] + lines + [""]

    def ratio_plot(self, x, series):
        """xi^t/(6 pi eta R) and xi^r/(8 pi eta R^3) per body against a grid variable (spec 60 D2's two panels)."""
        import matplotlib.pyplot as plt
        import numpy as np
        fig, axes = plt.subplots(1, 2, figsize=(9.6, 4.0))
        groups = {}
        for b in self.bodies:
            groups.setdefault(format_value(b.point.get(series)) if series else "", []).append(b)
        for ax, kind, title in ((axes[0], "t", "translation: ξ^t/(6πηR)"), (axes[1], "r", "rotation: ξ^r/(8πηR³)")):
            for label, bodies in groups.items():
                pts = []
                for b in bodies:
                    xi, se = b.friction_t() if kind == "t" else b.friction_r()
                    stokes = 6 * math.pi * b.eta * b.radius if kind == "t" else 8 * math.pi * b.eta * b.radius ** 3
                    pts.append((float(b.point[x]), xi / stokes, se / stokes))
                p = np.array(sorted(pts))
                ax.errorbar(p[:, 0], p[:, 1], yerr=p[:, 2], marker="o", ms=4, capsize=2, label=f"{series} = {label}" if series else None)
            ax.axhline(1.0, color="k", lw=1, ls="--", label="Stokes" if kind == "t" else "Stokes-Einstein-Debye")
            ax.set_xlabel(x)
            ax.set_title(title)
            ax.legend(fontsize=7)
        fig.tight_layout()
        fig.savefig(os.path.join(self.out, "friction_ratios.png"), dpi=110)
        plt.close(fig)
        return ["![friction_ratios](friction_ratios.png)", ""]

    def write_csv(self, name, rows):
        with open(os.path.join(self.out, name), "w", newline="") as f:
            w = csv.DictWriter(f, fieldnames=list(rows[0]) if rows else ["none"])
            w.writeheader()
            w.writerows(rows)

    # --- spheres: the calibration lines ---------------------------------------------------------
    def calibration_fit(self, series):
        groups = {}
        for b in self.bodies:
            groups.setdefault(format_value(b.point.get(series)), []).append(b)
        lines = ["### Calibration lines (spec 40 §8.5)", ""]
        fitted, skipped = {}, []
        for value, bodies in groups.items():
            if len({round(b.radius, 9) for b in bodies}) < 2:
                skipped.append(value)
                continue
            fitted[value] = Calibration.fitted(bodies, f"{series} = {value}")
        if skipped:
            lines += [f"No line for {series} = {', '.join(skipped)}: a calibration line needs at least two radii.", ""]
        if not fitted:
            return lines
        header = [series, "m_t", "b_t", "m_t/(6πη)", "R² (t)", "m_r", "b_r", "m_r/(8πη)", "R² (r)"]
        lines += ["ξ^t = m_t R + b_t and ξ^r = m_r R³ + b_r, weighted by the frictions' errors (parameter errors scaled by the "
                  f"reduced χ² where it exceeds 1); written to [{CALIBRATION_FILE}]({CALIBRATION_FILE}) for the spheroid study.", "",
                  "| " + " | ".join(header) + " |", "|" + "---|" * len(header)]
        for value, cal in fitted.items():
            t, r = cal.t, cal.r
            st, sr = 6 * math.pi * cal.eta, 8 * math.pi * cal.eta
            lines.append(f"| {value} | {fmt(t['m'], math.sqrt(t['cov'][1][1]))} | {fmt(t['b'], math.sqrt(t['cov'][0][0]))} | "
                         f"{fmt(t['m'] / st, math.sqrt(t['cov'][1][1]) / st)} | {t['r2']:.5f} | {fmt(r['m'], math.sqrt(r['cov'][1][1]))} | "
                         f"{fmt(r['b'], math.sqrt(r['cov'][0][0]))} | {fmt(r['m'] / sr, math.sqrt(r['cov'][1][1]) / sr)} | {r['r2']:.5f} |")
        with open(os.path.join(self.out, CALIBRATION_FILE), "w") as f:
            json.dump({"series": series, "lines": {v: c.to_json() for v, c in fitted.items()}}, f, indent=1)
        lines += ["", *self.calibration_plots(series, fitted, groups)]
        return lines + [""]

    def calibration_plots(self, series, fitted, groups):
        import matplotlib.pyplot as plt
        import numpy as np
        out = []
        for kind, power, name, theory, label in (("t", 1, "xi_t_vs_R", 6, "ξ^t"), ("r", 3, "xi_r_vs_R3", 8, "ξ^r")):
            fig, ax = plt.subplots(figsize=(6.4, 4.6))
            eta = None
            for value, cal in fitted.items():
                pts = [(b.radius ** power, *(b.friction_t() if kind == "t" else b.friction_r())) for b in groups[value]]
                x, y, e = (np.array(c) for c in zip(*sorted(pts)))
                art = ax.errorbar(x, y, yerr=e, marker="o", ms=4, capsize=2, ls="none", label=f"{series} = {value}")
                line = getattr(cal, kind)
                grid = np.linspace(0.0, x.max() * 1.05, 100)
                ax.plot(grid, line["m"] * grid + line["b"], color=art[0].get_color(), lw=1)
                eta = cal.eta
            grid = np.linspace(0.0, ax.get_xlim()[1], 100)
            ax.plot(grid, theory * math.pi * eta * grid, "k--", lw=1, label=f"{theory}πη R{'³' if power == 3 else ''} (Stokes{'' if kind == 't' else '-Einstein-Debye'})")
            ax.set_xlabel("R (nm)" if power == 1 else "R³ (nm³)")
            ax.set_ylabel(f"{label} (simulated fluid's units)")
            ax.set_title(f"Calibration: {label} against R{'³' if power == 3 else ''}")
            ax.legend(fontsize=7)
            fig.tight_layout()
            fig.savefig(os.path.join(self.out, f"{name}.png"), dpi=110)
            plt.close(fig)
            out += [f"![{name}]({name}.png)", ""]
        fig, axes = plt.subplots(1, 2, figsize=(8.4, 3.8))
        labels = list(fitted)
        x = np.arange(len(labels))
        for ax, key, title in ((axes[0], "m", "slope / Stokes (6πη, 8πη)"), (axes[1], "b", "intercept / Stokes (nm, nm³)")):
            for k, (kind, st) in enumerate((("t", 6), ("r", 8))):
                vals = [getattr(fitted[v], kind)[key] / (st * math.pi * fitted[v].eta) for v in labels]
                errs = [math.sqrt(getattr(fitted[v], kind)["cov"][1 if key == "m" else 0][1 if key == "m" else 0]) / (st * math.pi * fitted[v].eta)
                        for v in labels]
                ax.bar(x + (k - 0.5) * 0.38, vals, 0.38, yerr=errs, capsize=2, label="translation" if kind == "t" else "rotation")
            ax.set_xticks(x, labels)
            ax.set_xlabel(series)
            ax.set_title(title)
            ax.axhline(1.0 if key == "m" else 0.0, color="k", lw=0.8, ls="--")
            ax.legend(fontsize=7)
        fig.tight_layout()
        fig.savefig(os.path.join(self.out, "calibration_bars.png"), dpi=110)
        plt.close(fig)
        return out + ["![calibration_bars](calibration_bars.png)", ""]

    # --- spheroids: the factors ----------------------------------------------------------------
    def load_calibration(self, spec):
        if spec == "stokes":
            return Calibration.stokes(self.bodies[0])
        path = spec["file"]
        if not os.path.isabs(path):
            path = os.path.join(os.path.dirname(os.path.abspath(self.campaign)), path)
        if not os.path.isfile(path):
            return None
        with open(path) as f:
            d = json.load(f)
        key = format_value(spec["xi_bead"])
        if key not in d.get("lines", {}):
            raise RaspberryError(f"{path} has no calibration line for {d.get('series')} = {key} (it has {', '.join(d.get('lines', {}))})")
        return Calibration.from_json(d["lines"][key], f"{path}, {d.get('series')} = {key}")

    def factors(self, spec):
        from .spheroid_theory import factor
        cal = self.load_calibration(spec)
        lines = ["### Spheroid factors (spec 40 §8.6)", ""]
        if cal is None:
            return lines + [f"The calibration file `{spec['file']}` (relative to the results folder) does not exist: run the sphere "
                            "study first, then rewrite this report with `--only report`. No factors without it.", ""]
        for b in self.bodies:
            cal.check_fluid(b)
        lines += [f"Effective radii from {cal.source}: R_eff,t = (ξ^t − b_t)/m_t, R_eff,r³ = (ξ^r − b_r)/m_r; A = a/R_eff,t, "
                  "B = (a/R_eff,r)³ (from the 4τ D_r; B_three_axis from the three-axis estimator), t = R_eff,t/c and r = (R_eff,r/c)³ "
                  "along (ax: D_x^b) and across (perp: the mean of D_y^b and D_z^b) the symmetry axis. Errors include the calibration's.", ""]
        names = list(FACTOR_THEORY)
        header = ["φ"] + [f"{n}" + (f" ({'/'.join(FACTOR_LETTERS[n])})" if n in FACTOR_LETTERS else "") for n in names]
        lines += ["| " + " | ".join(header) + " |", "|" + "---|" * len(header)]
        rows, measured = [], {}
        for b in self.bodies:
            phi = b.aspect
            f = spheroid_factors(b, cal)
            measured[phi] = f
            cells = [f"{format_value(round(phi, 4))}"]
            for n in names:
                theory = factor(FACTOR_THEORY[n], phi)
                cells.append(f"{fmt(*f[n])} (theory {theory:.4g})")
            lines.append("| " + " | ".join(cells) + " |")
            rows.append({"phi": phi, **{k: v for n in names for k, v in ((n, f[n][0]), (n + "_se", f[n][1]),
                                                                             (n + "_theory", factor(FACTOR_THEORY[n], phi)))}})
        self.write_csv("spheroid_factors.csv", rows)
        lines += ["", "Table: [spheroid_factors.csv](spheroid_factors.csv)", ""]
        return lines + self.factor_plots(measured)

    def factor_plots(self, measured):
        import matplotlib.pyplot as plt
        import numpy as np
        from .spheroid_theory import factor
        phis = sorted(measured)
        lo, hi = min(phis), max(phis)
        lo, hi = (lo / 1.25, hi * 1.25) if lo == hi else (lo, hi)
        grid = np.geomspace(lo, hi, 200)
        out = []
        for name, panel, title, theory_name in (
                ("factors_lab", ("A", "B", "B_three_axis"), "Lab frame: A and B against Perrin", "Perrin"),
                ("factors_translation", ("t_ax", "t_perp"), "Body-frame translation: E, F (prolate), G, H (oblate)", "Happel-Brenner"),
                ("factors_rotation", ("r_ax", "r_perp"), "Body-frame rotation: I, J (prolate), K, L (oblate)", "Perrin")):
            fig, ax = plt.subplots(figsize=(6.4, 4.6))
            for n in panel:
                y = np.array([measured[p][n] for p in phis])
                art = ax.errorbar(phis, y[:, 0], yerr=y[:, 1], marker="o", ms=4, capsize=2, ls="none", label=f"{n}, measured")
                if n != "B_three_axis":
                    ax.plot(grid, [factor(FACTOR_THEORY[n], float(p)) for p in grid], color=art[0].get_color(), lw=1,
                            label=f"{n}, {theory_name}")
            ax.set_xscale("log")
            if name != "factors_translation":
                ax.set_yscale("log")
            ax.set_xlabel("φ = a/c")
            ax.set_ylabel("factor")
            ax.set_title(title)
            ax.legend(fontsize=7)
            fig.tight_layout()
            fig.savefig(os.path.join(self.out, f"{name}.png"), dpi=110)
            plt.close(fig)
            out += [f"![{name}]({name}.png)", ""]
        return out
