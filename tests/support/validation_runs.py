"""Shared by the slow validation scripts in tests/integration (validation_*.py): run a validation
manifest with anisodyn-run on one worker, replica statistics, and checks that print what they
compare before asserting.

Each script is called as `script BIN_DIR SCRATCH_DIR SOURCE_DIR [ARGS...]` (tests/integration/CMakeLists.txt)
and puts SOURCE_DIR/tests/support and SOURCE_DIR/workflows on its path.
"""
import json
import os
import resource
import shutil
import subprocess
import sys
import time

import numpy as np


class Run:
    """A validation manifest run from scratch by anisodyn-run with one worker (one core)."""

    def __init__(self, argv, manifest):
        self.bin_dir, self.tmp, self.src = argv[1], argv[2], argv[3]
        self.manifest = os.path.join(self.src, manifest)
        self.spec = json.load(open(self.manifest))
        self.failures = []
        results = os.path.join(self.tmp, "results")
        self.campaign = os.path.join(results, self.spec["study"])
        if not os.environ.get("ANISODYN_VALIDATION_KEEP"):  # set it to re-analyse the last run (anisodyn-run skips its jobs)
            shutil.rmtree(self.campaign, ignore_errors=True)
        os.makedirs(results, exist_ok=True)
        t0, cpu0 = time.time(), self._cpu()
        r = subprocess.run([os.path.join(self.bin_dir, "anisodyn-run"), self.manifest, "--jobs", "1", "--no-report", "--quiet",
                            "--bin", self.bin_dir, "--results", results], capture_output=True, text=True)
        if r.returncode != 0:
            sys.exit(f"anisodyn-run {manifest} failed (exit {r.returncode}):\n{r.stdout}\n{r.stderr}")
        self.wall, self.cpu = time.time() - t0, self._cpu() - cpu0
        print(f"{manifest}: {self.wall:.0f} s wall, {self.cpu:.0f} s CPU (engines, one worker)")

    @staticmethod
    def _cpu():
        u = resource.getrusage(resource.RUSAGE_CHILDREN)
        return u.ru_utime + u.ru_stime

    def outputs(self, stage, **grid):
        """Output files of a stage, sorted by replica, for the grid point given as keyword arguments."""
        d = os.path.join(self.campaign, stage, *[f"{k}={v}" for k, v in grid.items()])
        files = sorted((f for f in os.listdir(d) if f.endswith(".h5")), key=lambda f: int(f.rsplit("-r", 1)[1][:-3]) if "-r" in f else 0)
        assert files, f"no outputs in {d}"
        return [os.path.join(d, f) for f in files]

    @staticmethod
    def summary(output):
        """The tool's JSON summary (its stdout, kept by anisodyn-run beside the output)."""
        return json.load(open(output[:-3] + ".log"))

    def check(self, label, value, reference, se, k, se_bound):
        """|value - reference| < k se, and se < se_bound (the run must be precise enough for the first to mean something)."""
        z = self.report(label, value, reference, se)
        if not abs(z) < k:
            print("    <-- FAIL")
            self.failures.append(f"{label}: |deviation| = {abs(z):.2f} SE >= k = {k}")
        self.check_se(label, se, se_bound, shown="  precision")

    @staticmethod
    def report(label, value, reference, se):
        """Prints value against reference in standard errors (and returns that number); asserts nothing."""
        z = (value - reference) / se if se > 0 else float("inf")
        print(f"  {label}: {value:.6g} vs {reference:.6g}: {z:+.2f} SE (SE {se:.3g})")
        return z

    def check_se(self, label, se, se_bound, shown=None):
        """se < se_bound: the run reached the precision it was designed for. Printed as `shown` (default: label)."""
        print(f"  {shown or label}: SE {se:.3g}, bound {se_bound:.3g}" + ("" if se < se_bound else "  <-- FAIL"))
        if not se < se_bound:
            self.failures.append(f"{label}: SE {se:.3g} >= bound {se_bound:.3g}")

    def failed_checks(self):
        """Prints the failed checks (or that all passed) and returns them; the test asserts there are none."""
        print("FAILED:\n  " + "\n  ".join(self.failures) if self.failures else "all checks passed")
        return self.failures


def mean_se(x):
    """Mean and standard error over independent replicas."""
    x = np.asarray(x, dtype=float)
    return x.mean(), x.std(ddof=1) / np.sqrt(len(x))
