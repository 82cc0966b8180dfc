#!/usr/bin/env python3
"""Slow validation: self rotational diffusion of long thin rods (issue 15, spec 20 §6).

Two manifests, both run with anisodyn-run on one worker, rods L = 0.88 um in the box 2.0802 um at
N = 90 and 440 (rho L^3 = 6.8 and 33.3, (L/D)phi = 0.09 and 0.44), slender-body D tensor:

- manifests/validation/bd_methods_I_III.json: BD with the overlap-volume potential, 4 replicas of
  0.2 s. Methods I (anisodyn-rotation: C_1 and C_2 of the axis) and III (anisodyn-restoring-torque)
  read the same frames.
- manifests/validation/dmc_hard_rods_rotation.json: DMC of hard spherocylinders of BD's effective
  diameter, 4 replicas of 6.3e4 cycles (about 0.1 s): an engine that shares no code with BD's
  forces, noise or integrator, for rods that cannot cross (BD's cross over barriers of ~12 kT).

Checks at each N, on D_r(phi)/D_r:
- Method I against Method III, n = 1 (C_1) and n = 2 (C_2): |I - III| < 4 SE, SE of the difference
  below 0.1 (the errors are added in quadrature although the two read the same frames: their
  correlation would only shrink the true SE, so the check is conservative);
- BD against DMC: Method I with C_2, and D(t) = MSAD/4t at t = 5 and 15 ms (linear in log t between
  the tables' lags): |BD - DMC| < 4 SE, SE below 0.1; Method I with C_1 within 4 SE, its precision
  printed but not bound (its window runs to C_1 = 0.05, at lags of 0.07-0.14 s, close to the runs'
  lengths, so its errors are large in both engines).
Everything compared is printed, with the Dhont-Briels line 1 - (L/D)phi/5 beside it (not asserted:
the line is a mean-field theory without the entanglement that rods at rho L^3 >> 1 feel).
"""
import sys

import h5py
import numpy as np

sys.path[:0] = [sys.argv[3] + "/tests/support", sys.argv[3] + "/workflows"]
from anisodyn_run.report import read_scalars  # noqa: E402
from validation_runs import Run  # noqa: E402

K = 4.0
MAX_SE = 0.1
L_OVER_D_PHI = {90: 0.09, 440: 0.44}

bd = Run(sys.argv, "manifests/validation/bd_methods_I_III.json")
dmc = Run(sys.argv, "manifests/validation/dmc_hard_rods_rotation.json")


def scalar(run, stage, n, name):
    (path,) = run.outputs(stage, N=n)
    value, se = read_scalars(path)[name][:2]
    return value, se


DR_FREE = 23.71107784886779  # 1/s: the slender-body D_r of both manifests
LAGS = (0.005, 0.015)  # s


def compare(label, a, b, bound=MAX_SE):
    (va, sa), (vb, sb) = a, b
    se = (sa ** 2 + sb ** 2) ** 0.5
    if bound is None:
        if not abs(va - vb) < K * se:
            bd.failures.append(f"{label}: |deviation| >= {K} SE")
        bd.report(label, va - vb, 0.0, se)
    else:
        bd.check(label, va - vb, 0.0, se, K, bound)


def msad_rate(run, n, t):
    """D(t)/D_r = MSAD/(4 t D_r) of the axis at lag t (interpolated in log t) with its error."""
    (path,) = run.outputs("rotation", N=n)
    with h5py.File(path) as f:
        g = f["rotation_rod"]
        lag, msad, se = g["time"][...], g["msad_L"][...], g["msad_L_se"][...]
    x = np.log(lag[lag > 0])
    value = np.interp(np.log(t), x, msad[lag > 0]) / (4 * t * DR_FREE)
    error = np.interp(np.log(t), x, se[lag > 0]) / (4 * t * DR_FREE)
    return value, error


print("| N | (L/D)phi | Dhont-Briels | BD I, C_1 | BD I, C_2 | BD III, n = 1 | BD III, n = 2 | DMC I, C_1 | DMC I, C_2 |")
print("|---|---|---|---|---|---|---|---|---|")
values = {}
for n in bd.spec["grid"]["N"]:
    v = values[n] = {
        "bd_c1": scalar(bd, "rotation", n, "Dr_C1_over_Dr_L_rod"),
        "bd_c2": scalar(bd, "rotation", n, "Dr_C2_over_Dr_L_rod"),
        "bd_iii1": scalar(bd, "restoring", n, "Dr_phi_over_Dr_rod"),
        "bd_iii2": scalar(bd, "restoring", n, "Dr2_phi_over_Dr_rod"),
        "dmc_c1": scalar(dmc, "rotation", n, "Dr_C1_over_Dr_L_rod"),
        "dmc_c2": scalar(dmc, "rotation", n, "Dr_C2_over_Dr_L_rod"),
    }
    for t in LAGS:
        v[f"bd_d{t}"], v[f"dmc_d{t}"] = msad_rate(bd, n, t), msad_rate(dmc, n, t)
    cells = " | ".join(f"{v[k][0]:.4f} ± {v[k][1]:.4f}" for k in ("bd_c1", "bd_c2", "bd_iii1", "bd_iii2", "dmc_c1", "dmc_c2"))
    print(f"| {n} | {L_OVER_D_PHI[n]} | {1 - L_OVER_D_PHI[n] / 5:.3f} | {cells} |")
print("\n| N | engine | " + " | ".join(f"D({t * 1e3:g} ms)/D_r" for t in LAGS) + " |")
print("|---|---|" + "---|" * len(LAGS))
for n, v in values.items():
    for engine in ("bd", "dmc"):
        print(f"| {n} | {engine.upper()} | " + " | ".join(f"{v[f'{engine}_d{t}'][0]:.4f} ± {v[f'{engine}_d{t}'][1]:.4f}" for t in LAGS) + " |")
for n, v in values.items():
    compare(f"N={n}: Method I - III, n = 1", v["bd_c1"], v["bd_iii1"])
    compare(f"N={n}: Method I - III, n = 2", v["bd_c2"], v["bd_iii2"])
    compare(f"N={n}: BD - DMC, C_1", v["bd_c1"], v["dmc_c1"], bound=None)
    compare(f"N={n}: BD - DMC, C_2", v["bd_c2"], v["dmc_c2"])
    for t in LAGS:
        compare(f"N={n}: BD - DMC, D({t * 1e3:g} ms)", v[f"bd_d{t}"], v[f"dmc_d{t}"])
assert not bd.failed_checks(), "validation checks failed (listed above)"
