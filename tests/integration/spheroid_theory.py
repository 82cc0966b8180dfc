#!/usr/bin/env python3
"""The spheroid factors of spec 40 §8.6 (workflows/anisodyn_run/spheroid_theory.py) against spec 70
§7.3's table (every printed digit: within half a unit of the last) and its verified identities:
E-H equal the radii from the general ellipsoid's integrals; the harmonic mean of the axis radii is
Perrin's a/A and the rotational mean gives B; every factor is 1 for a sphere and tends to it as
phi -> 1; the disk limits G -> 8/(3 pi), H -> 16/(9 pi); (I/J)^(1/3) at phi = 10/9 and 10.
argv: [1] build bin dir (unused), [2] scratch dir (unused), [3] source dir."""
import math
import os
import sys

source = sys.argv[3]
sys.path.insert(0, os.path.join(source, "workflows"))
sys.path.insert(0, os.path.join(source, "tests", "support"))
from anisodyn_run import spheroid_theory as st  # noqa: E402
from script_checks import check, finish  # noqa: E402

# spec 70 §7.3: phi, A, B, t_ax, t_perp, r_ax, r_perp, R_eff,t (as printed).
TABLE = """1/10 0.1478 0.0022 0.8525 0.6133 0.4789 0.4305 6.195
1/5 0.2795 0.0169 0.8615 0.6596 0.5344 0.4480 5.200
1/4 0.3403 0.0319 0.8673 0.6823 0.5624 0.4608 4.956
1/3 0.4352 0.0708 0.8787 0.7197 0.6095 0.4882 4.695
1/2 0.6046 0.2064 0.9053 0.7927 0.7050 0.5658 4.428
2/3 0.7523 0.4156 0.9352 0.8636 0.8021 0.6754 4.311
4/5 0.8580 0.6271 0.9606 0.9189 0.8807 0.7877 4.269
9/10 0.9313 0.8064 0.9801 0.9597 0.9402 0.8870 4.254
10/9 1.0717 1.2292 1.0223 1.0441 1.0669 1.1423 4.254
5/4 1.1552 1.5330 1.0505 1.0985 1.1510 1.3460 4.269
3/2 1.2912 2.1197 1.1017 1.1942 1.3037 1.7902 4.313
2 1.5207 3.4248 1.2039 1.3789 1.6134 3.0099 4.436
3 1.8697 6.5741 1.4045 1.7276 2.2439 7.0223 4.728
4 2.1311 10.538 1.5979 2.0565 2.8842 13.583 5.025
5 2.3397 15.394 1.7848 2.3710 3.5304 23.203 5.311
10 3.0083 53.973 2.6471 3.8115 6.8047 133.68 6.557"""


def half_unit(printed):
    """Half a unit of the last printed digit."""
    digits = len(printed.split(".")[1]) if "." in printed else 0
    return 0.5 * 10.0 ** -digits


TABLE_FACTORS = ("A", "B", "t_ax", "t_perp", "r_ax", "r_perp")  # the table's columns (the ratios are derived)
worst = 0.0
for line in TABLE.splitlines():
    words = line.split()
    num, _, den = words[0].partition("/")
    phi = float(num) / float(den or 1)
    a = 4.25 * phi ** (2.0 / 3.0)
    values = [st.factor(name, phi) for name in TABLE_FACTORS] + [a / st.lab_factors(phi)[0]]
    for name, value, printed in zip(list(TABLE_FACTORS) + ["R_eff,t"], values, words[1:]):
        off = abs(value - float(printed)) / half_unit(printed)
        worst = max(worst, off)
        check(off <= 1.0, f"phi = {words[0]}: {name} = {value:.6g} (printed {printed})")
print(f"largest difference from the table: {worst:.2f} half-units of the last digit")

for phi in (0.1, 0.25, 0.5, 0.9, 10 / 9, 2.0, 5.0, 10.0):
    check(st.factor("t_ratio", phi) == st.factor("t_perp", phi) / st.factor("t_ax", phi)
          and st.factor("r_ratio", phi) == st.factor("r_perp", phi) / st.factor("r_ax", phi), f"phi = {phi:.4g}: the anisotropy ratios")
    t_ax, t_perp = st.translation_factors(phi)
    r_ax_int, r_perp_int = st.axis_translation_radii(phi)
    check(abs(t_ax - r_ax_int) < 1e-8 * t_ax and abs(t_perp - r_perp_int) < 1e-8 * t_perp,
          f"phi = {phi:.4g}: closed forms E-H = the ellipsoid integrals ({t_ax:.10f} {r_ax_int:.10f}; {t_perp:.10f} {r_perp_int:.10f})")
    A, B = st.lab_factors(phi)
    a, c = phi, 1.0
    check(abs(3.0 / (1.0 / (c * t_ax) + 2.0 / (c * t_perp)) - a / A) < 1e-8 * a / A, f"phi = {phi:.4g}: harmonic mean of the axis radii = a/A")
    r_ax, r_perp = st.rotation_factors(phi)
    check(abs(a ** 3 / (3.0 / (1.0 / r_ax + 2.0 / r_perp)) - B) < 1e-8 * B, f"phi = {phi:.4g}: rotational mean = B")

near = [st.factor(name, 1.0 + 1e-4) for name in st.FACTORS] + [st.factor(name, 1.0 - 1e-4) for name in st.FACTORS]
check(all(abs(v - 1.0) < 1e-3 for v in near), "every factor tends to 1 as phi -> 1 from both sides")
check(all(st.factor(name, 1.0) == 1.0 for name in ("A", "B", "t_ax", "t_perp")) and all(abs(st.factor(n, 1.0) - 1.0) < 1e-10 for n in ("r_ax", "r_perp")),
      "a sphere's factors are 1")
G, H = st.translation_factors(1e-6)
check(abs(G - 8.0 / (3.0 * math.pi)) < 1e-5 and abs(H - 16.0 / (9.0 * math.pi)) < 1e-5,
      f"disk limits: G = {G:.6f} (8/(3 pi) = {8 / (3 * math.pi):.6f}), H = {H:.6f} (16/(9 pi) = {16 / (9 * math.pi):.6f})")
ratio = [(st.rotation_factors(p)[0] / st.rotation_factors(p)[1]) ** (1 / 3) for p in (10 / 9, 10.0)]
check(abs(ratio[0] - 0.977) < 1e-3 and abs(ratio[1] - 0.370) < 1e-3, f"(I/J)^(1/3) = {ratio[0]:.4f} at 10/9, {ratio[1]:.4f} at 10 (printed 0.977, 0.370: within a unit of the last digit)")
# The report's `spheroid` line (report.py) draws the same function, and the manifest check refuses a
# factor it does not know, naming the JSON path.
import matplotlib  # noqa: E402
matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
from anisodyn_run.manifest import ManifestError, validate_report  # noqa: E402
from anisodyn_run.report import Report  # noqa: E402

fig, ax = plt.subplots()
Report.theory(None, ax, {"kind": "spheroid", "factor": "t_perp", "scale": 2.0}, None, np.array([0.25, 4.0]), "report.plots[0]")
x, y = ax.lines[0].get_data()
check(abs(x[0] - 0.25) < 1e-12 and abs(x[-1] - 4.0) < 1e-12 and all(abs(yi - 2.0 * st.factor("t_perp", xi)) < 1e-12 for xi, yi in zip(x, y)),
      "the report's spheroid line is scale x factor over the plotted phi range")
manifest = {"study": "s", "grid": {"phi": [0.5, 2.0]}, "stages": [{"name": "msd", "tool": "msd", "params": {}}],
            "report": {"plots": [{"name": "p", "stage": "msd", "scalar": "D", "x": "phi", "theory": [{"kind": "spheroid", "factor": "E"}]}]}}
try:
    validate_report(manifest)
    check(False, "an unknown spheroid factor is refused")
except ManifestError as e:
    check("report.plots[0].theory[0].factor" in str(e), f"an unknown spheroid factor is refused at its path: {e}")
except TypeError as e:
    check(False, f"validate_report's signature: {e}")
assert not finish()
