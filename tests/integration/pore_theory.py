#!/usr/bin/env python3
"""Spec 70 §7.4's centreline drag K(lambda) (workflows/anisodyn_run/pore_theory.py) against the table
printed there (Haberman-Sayre and Bohlin at lambda = 0.1 ... 0.5, three decimals: within half a unit),
and the report's pore_centreline overlay: refused where it has no effect or lacks its radius.
argv: [1] build bin dir (unused), [2] scratch dir (unused), [3] source dir."""
import os
import sys

source = sys.argv[3]
sys.path.insert(0, os.path.join(source, "workflows"))
sys.path.insert(0, os.path.join(source, "tests", "support"))
from anisodyn_run.manifest import ManifestError, validate_report  # noqa: E402
from anisodyn_run.pore_theory import bohlin, haberman_sayre  # noqa: E402
from script_checks import check, finish  # noqa: E402

PRINTED = {0.1: (1.263, 1.263), 0.2: (1.680, 1.679), 0.3: (2.370, 2.370), 0.4: (3.582, 3.588), 0.5: (5.870, 5.923)}
for lam, (hs, bo) in PRINTED.items():
    check(abs(haberman_sayre(lam) - hs) <= 5e-4, f"lambda = {lam}: Haberman-Sayre K = {haberman_sayre(lam):.5f} (printed {hs})")
    check(abs(bohlin(lam) - bo) <= 5e-4, f"lambda = {lam}: Bohlin K = {bohlin(lam):.5f} (printed {bo})")
check(abs(haberman_sayre(1e-9) - 1) < 1e-8 and abs(bohlin(1e-9) - 1) < 1e-8, "K -> 1 for a vanishing sphere")

base = {"study": "s", "grid": {"R_pore": [8.5, 10.625]}, "stages": [{"name": "pore", "tool": "lb-pore", "params": {}}]}
good = {"name": "p", "stage": "pore", "table": "pore_bins", "x": "beta", "y": ["S_z"],
        "theory": [{"kind": "pore_centreline", "formula": "bohlin", "radius": 4.25}]}
validate_report({**base, "report": {"plots": [good]}})
check(True, "a pore_centreline overlay on a curve plot is accepted")
for theory, path in (({"kind": "pore_centreline", "formula": "faxen", "radius": 4.25}, "report.plots[0].theory[0].formula"),
                     ({"kind": "pore_centreline"}, "report.plots[0].theory[0].radius"),
                     ({"kind": "pore_centreline", "radius": 4.25, "pore_radius": "R"}, "report.plots[0].theory[0].pore_radius"),
                     ({"kind": "pore_centreline", "radius": 4.25, "band": 0.1}, "report.plots[0].theory[0].band")):
    try:
        validate_report({**base, "report": {"plots": [{**good, "theory": [theory]}]}})
        check(False, f"{theory} refused")
    except ManifestError as e:
        check(f"at {path}:" in str(e), f"{theory} refused at {path}: {e}")
assert not finish()
