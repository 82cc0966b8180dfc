#!/usr/bin/env python3
"""Long-time self-diffusion from anisodyn-dmc trajectories, independently of the engine (numpy).

usage: summarise_dmc_msd.py [--fit T1 T2] [--groups G] [--species NAME] TRAJECTORY.h5...

For each trajectory: unwrapped positions (position + image * box) of the chosen species, the MSD
averaged over particles and over all time origins for each lag (frames must be close to evenly
spaced in Brownian time, e.g. `frames.every_time`), and D = slope / 6 of a least-squares line
through the MSD for lag times in [T1, T2]. The error is the standard error over G groups of
particles (each group fitted separately). Prints a table and a JSON line per file.
"""
import argparse
import json
import sys

import h5py
import numpy as np


def unwrapped(f, species_name):
    names = [n.decode() if isinstance(n, bytes) else n for n in f["parameters/species/name"][...]]
    pos = f["particles/all/position/value"][...]
    img = f["particles/all/image/value"][...]
    edges = f["particles/all/box/edges/value"][...]
    box = edges if edges.ndim == 2 else np.einsum("fii->fi", edges)
    r = pos + img * box[:, None, :]
    sp = f["particles/all/species/value"][0]
    if species_name is not None:
        r = r[:, sp == names.index(species_name), :]
    return f["particles/all/position/time"][...], r


def msd_by_lag(t, r):
    """MSD per particle for every lag (frames treated as evenly spaced), and the mean lag time."""
    nf = len(t)
    lags = np.arange(1, nf)
    msd = np.empty((len(lags), r.shape[1]))
    tl = np.empty(len(lags))
    for k, lag in enumerate(lags):
        d = r[lag:] - r[:-lag]
        msd[k] = np.mean(np.sum(d * d, axis=2), axis=0)
        tl[k] = np.mean(t[lag:] - t[:-lag])
    return tl, msd


def fit_d(tl, msd, t1, t2):
    sel = (tl >= t1) & (tl <= t2)
    if sel.sum() < 2:
        raise SystemExit(f"fewer than two lags in the fit window [{t1}, {t2}] (lags up to {tl[-1]:.3g})")
    slope = np.polyfit(tl[sel], msd[sel], 1)[0]
    return slope / 6.0


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("files", nargs="+")
    ap.add_argument("--fit", nargs=2, type=float, default=None, metavar=("T1", "T2"),
                    help="lag-time window of the linear fit (default: 20%%-50%% of the run)")
    ap.add_argument("--groups", type=int, default=10)
    ap.add_argument("--species", default=None)
    a = ap.parse_args()
    print(f"{'file':50s} {'frames':>6s} {'t_end':>8s} {'D_L':>10s} {'error':>9s}")
    for path in a.files:
        with h5py.File(path, "r") as f:
            t, r = unwrapped(f, a.species)
        tl, msd = msd_by_lag(t, r)
        t1, t2 = a.fit if a.fit else (0.2 * t[-1], 0.5 * t[-1])
        groups = np.array_split(np.arange(r.shape[1]), a.groups)
        ds = np.array([fit_d(tl, msd[:, g].mean(axis=1), t1, t2) for g in groups])
        d, err = ds.mean(), ds.std(ddof=1) / np.sqrt(len(ds))
        print(f"{path:50s} {len(t):6d} {t[-1]:8.3f} {d:10.5f} {err:9.5f}")
        print(json.dumps({"file": path, "D_long": d, "error": err, "fit_window": [t1, t2], "particles": r.shape[1],
                          "frames": len(t)}))


if __name__ == "__main__":
    sys.exit(main())
