#!/usr/bin/env python3
"""Prints "<manifest name> <seconds>" for each manifest path given: the CPU time of its MC/DMC jobs
from the study runner's cost model (workflows/anisodyn_run/cost.py, what `anisodyn-run --dry-run`
reports). study_manifests.cmake runs it at configure time and uses the seconds as the ctest COST of
each manifest's test, so that a fresh build directory starts the longest manifests first. A
manifest the runner cannot read gets no line (its test keeps the default order)."""
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "workflows"))
from anisodyn_run import cost, expand  # noqa: E402
from anisodyn_run.manifest import ManifestError, load, validate  # noqa: E402

for path in sys.argv[1:]:
    try:
        m = load(path)
        jobs, _, _ = expand.expand(m, validate(m, lambda tool: True))
    except ManifestError:
        continue
    seconds = sum(s for _, _, s in cost.estimate(jobs).values())
    print(os.path.splitext(os.path.basename(path))[0], round(seconds))
