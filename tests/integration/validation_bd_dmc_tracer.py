#!/usr/bin/env python3
"""Slow validation: the pulled tracer in two engines. A sphere tracer of the bath's size pulled at
Pe = 0.5 and 1 through hard spheres at eta = 0.20 and 0.30 must feel the same effective friction
in Dynamic Monte Carlo (hard spheres; the tracer's balanced time step and the acceptance-based
time mapping of a mixture with a biased move, spec 10 §4.4-4.5) and in Brownian dynamics
(pseudo-hard Mie(50, 49) spheres at their Barker-Henderson diameter; a force in the equation of
motion): the independent check of the DMC time mapping for mixtures and pulled tracers (issue 15).

Runs manifests/validation/bd_dmc_tracer.json with anisodyn-run on one worker and reads
gamma_eff/gamma_0 = D0 beta F/<v_z> with its jackknife error over the 8 replicas from each engine's
anisodyn-microrheology output (mode active). Checks at every (eta, Pe): |BD - DMC| < 4 SE of the
difference, and that SE below 15% of gamma_eff/gamma_0 (the velocity of one tracer is noisy: its
error falls only as the square root of the run length; docs/validation.md states the budget).
The raw values, the relative differences and the steady velocities are printed.
"""
import sys

sys.path[:0] = [sys.argv[3] + "/tests/support", sys.argv[3] + "/workflows"]
from anisodyn_run.report import read_scalars  # noqa: E402
from validation_runs import Run  # noqa: E402

K = 4.0
MAX_RELATIVE_SE = 0.15
run = Run(sys.argv, "manifests/validation/bd_dmc_tracer.json")
grid = run.spec["grid"]
print("| eta | Pe | DMC gamma_eff/gamma_0 | BD gamma_eff/gamma_0 | BD - DMC |")
print("|---|---|---|---|---|")
rows = []
for eta, placement in zip(grid["eta"], grid["placement"]):
    for pe, t_run in zip(grid["Pe"], grid["t_run"]):
        value = {}
        for engine in ("dmc", "bd"):
            (path,) = run.outputs(f"mr_{engine}", eta=eta, placement=placement, Pe=pe, t_run=t_run)
            value[engine] = read_scalars(path)["gamma_eff_over_gamma0"][:2]
        (d, d_se), (b, b_se) = value["dmc"], value["bd"]
        diff_se = (d_se ** 2 + b_se ** 2) ** 0.5
        print(f"| {eta} | {pe} | {d:.4f} ± {d_se:.4f} | {b:.4f} ± {b_se:.4f} | {(b - d) / d:+.1%} ± {diff_se / d:.1%} |")
        rows.append((eta, pe, b - d, diff_se, d))
for eta, pe, diff, diff_se, d in rows:
    run.check(f"eta={eta} Pe={pe}: gamma_eff/gamma_0 BD - DMC", diff, 0.0, diff_se, K, MAX_RELATIVE_SE * d)
assert not run.failed_checks(), "validation checks failed (listed above)"
