#!/usr/bin/env python3
"""Writes OUT.cmake: `set_tests_properties(integration_study_<manifest> PROPERTIES COST <seconds>)`
for each manifest path given, the CPU time of its engine jobs from the tools' cost models (their
--describe, what `anisodyn-run --dry-run` reports). The build runs it once the tools exist
(tests/integration/manifest_costs/), and ctest reads the file, so that a fresh build directory
starts the longest manifests first. A manifest the runner cannot read gets no line (its test keeps
the default order).
argv: [1] the build's bin directory, [2] OUT.cmake, [3...] manifests."""
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "workflows"))
from anisodyn_run import cost, expand  # noqa: E402
from anisodyn_run.describe import DescriptionError, Tools  # noqa: E402
from anisodyn_run.jobdb import atomic_write_text  # noqa: E402
from anisodyn_run.manifest import ManifestError, load, validate  # noqa: E402

bin_dir, out = sys.argv[1], sys.argv[2]
tools = Tools(bin_dir)
lines = ["# Written by tests/support/manifest_costs.py: estimated CPU seconds of each study manifest's engine jobs."]
for path in sys.argv[3:]:
    try:
        m = load(path)
        jobs, _, _ = expand.expand(m, validate(m, tools), tools)
    except (ManifestError, DescriptionError):
        continue
    seconds = sum(s for _, _, s in cost.estimate(jobs).values())
    name = os.path.splitext(os.path.basename(path))[0]
    lines.append(f"set_tests_properties(integration_study_{name} PROPERTIES COST {round(seconds)})")
atomic_write_text(out, "\n".join(lines) + "\n")
