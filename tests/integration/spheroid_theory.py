#!/usr/bin/env python3
"""The spheroid factors of spec 40 §8.6 (workflows/anisodyn_run/spheroid_theory.py) against spec 70
§7.3's table (every printed digit: within half a unit of the last) and its verified identities:
E-H equal the radii from the general ellipsoid's integrals; the harmonic mean of the axis radii is
Perrin's a/A and the rotational mean gives B; every factor is 1 for a sphere and tends to it as
phi -> 1; the disk limits G -> 8/(3 pi), H -> 16/(9 pi); (I/J)^(1/3) at phi = 10/9 and 10.
argv: [1] build bin dir (unused), [2] scratch dir (unused), [3] source dir."""
import os
import sys

source = sys.argv[3]
sys.path.insert(0, os.path.join(source, "workflows"))
sys.path.insert(0, os.path.join(source, "tests", "support"))
from anisodyn_run import spheroid_theory as st  # noqa: E402
from script_checks import check, finish  # noqa: E402

rows = st.table_comparison()
worst = 0.0
for phi_text, name, value, printed, diff, half in rows:
    worst = max(worst, diff / half)
    check(diff <= half, f"phi = {phi_text}: {name} = {value:.6g} (printed {printed})")
check(len(rows) == 16 * 7, f"{len(rows)} entries compared (16 aspect ratios x 7 columns)")
print(f"largest difference from the table: {worst:.2f} half-units of the last digit")

for phi in (0.1, 0.25, 0.5, 0.9, 10 / 9, 2.0, 5.0, 10.0):
    check(st.factor("t_ratio", phi) == st.factor("t_perp", phi) / st.factor("t_ax", phi)
          and st.factor("r_ratio", phi) == st.factor("r_perp", phi) / st.factor("r_ax", phi), f"phi = {phi:.4g}: the anisotropy ratios")
# spec 70 §7.3's identities: to 1e-8 (the integrals' quadrature), the disk limits at phi = 1e-6 to 1e-5, the
# sphere to 1e-10 (r_ax, r_perp by quadrature), (I/J)^(1/3) within a unit of the printed third digit.
for what, value, reference in st.identity_checks():
    limit = 1e-3 if what.startswith("(I/J)") else (1e-5 if what.startswith("disk") else 1e-10 if what.startswith("sphere") else 1e-8) * abs(reference)
    check(abs(value - reference) <= limit, f"{what}: {value:.10g} against {reference:.10g}")
near = [st.factor(name, 1.0 + 1e-4) for name in st.FACTORS] + [st.factor(name, 1.0 - 1e-4) for name in st.FACTORS]
check(all(abs(v - 1.0) < 1e-3 for v in near), "every factor tends to 1 as phi -> 1 from both sides")
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
