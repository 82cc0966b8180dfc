#!/usr/bin/env python3
"""Recomputes the per-phase statistics of anisodyn-mc outputs from their H5MD observables, with
numpy, independently of the C++ estimators: mean, block-averaging error, and the error from the
integrated autocorrelation time (FFT, Sokal window). Prints a Markdown table row per phase.

usage: summarise_mc.py RESULT.h5 [RESULT.h5 ...]   (run with /usr/bin/python3: needs h5py)
The slow validation tests import phases().
"""
import json
import sys

import h5py
import numpy as np


def blocking_error(x, min_blocks=16):
    best = 0.0
    while len(x) >= min_blocks:
        best = max(best, np.sqrt(x.var() / (len(x) - 1)))
        x = 0.5 * (x[: len(x) // 2 * 2 : 2] + x[1 : len(x) // 2 * 2 : 2])
    return best


def autocorrelation_error(x):
    n = len(x)
    y = x - x.mean()
    f = np.fft.rfft(y, 2 * n)
    acf = np.fft.irfft(f * np.conj(f))[:n]
    acf /= acf[0] if acf[0] > 0 else 1.0
    tau = 0.5
    for w in range(1, n // 2):
        tau += acf[w] * n / (n - w)
        if w >= 5 * tau:
            break
    return np.sqrt(x.var(ddof=1) * 2 * tau / n), tau


def series(f, name):
    for root in ("observables", "anisodyn/observables"):
        if f"{root}/{name}" in f:
            g = f[f"{root}/{name}"]
            v = g["value"][...]
            return g["step"][...], v.reshape(len(g["step"]), -1)
    return None, None


def describe(x):
    """Mean, error (the larger of the two estimates), blocking error, autocorrelation error, tau_int in samples."""
    eb = blocking_error(x.copy())
    ea, tau = autocorrelation_error(x)
    return x.mean(), max(eb, ea), eb, ea, tau


def phases(path):
    """Per phase of an anisodyn-mc output: label, cycles, and describe() of eta and of each species' U_T, U_W, U_L."""
    out = []
    with h5py.File(path) as f:
        summary = json.loads(f["anisodyn/checkpoint/engine_state"][()])["runner"]["summary"]
        species = [s.decode() if isinstance(s, bytes) else s for s in f["parameters/species/name"][...]]
        steps, eta = series(f, "packing_fraction")
        for ph in summary["phases"]:
            sel = (steps > ph["first_cycle"]) & (steps <= ph["last_cycle"])
            row = {"label": ph["label"], "first_cycle": ph["first_cycle"], "last_cycle": ph["last_cycle"],
                   "phase": ph.get("phase", ""), "observe_every": int(steps[1] - steps[0]),
                   "eta": describe(eta[sel, 0]), "order": {}}
            for sp in species:
                s_steps, order = series(f, f"order_{sp}")
                if s_steps is not None:
                    sel_o = (s_steps > ph["first_cycle"]) & (s_steps <= ph["last_cycle"])
                    row["order"][sp] = [describe(order[sel_o, k]) for k in range(3)]
            out.append(row)
    return out


def main():
    for path in sys.argv[1:]:
        for ph in phases(path):
            m, e, eb, ea, tau = ph["eta"]
            row = f"| {path} | {ph['label']} | {ph['first_cycle']}–{ph['last_cycle']} | {m:.5f} ± {e:.5f} ({100 * e / m:.2f}%; blocking {eb:.5f}, autocorr. {ea:.5f}, τ_int {tau * ph['observe_every']:.0f} cycles)"
            for sp, stats in ph["order"].items():
                parts = [f"U_{axis} = {mo:.4f} ± {eo:.4f}" for axis, (mo, eo, *_) in zip("TWL", stats)]
                row += f" | {sp}: " + ", ".join(parts) + f" | {ph['phase']}"
            print(row + " |")


if __name__ == "__main__":
    main()
