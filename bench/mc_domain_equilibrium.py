#!/usr/bin/env python3
"""Domain sweeps against sequential sweeps: the same equilibrium (issue 18).

Runs anisodyn-mc twice from one cached benchmark state (bench_mc_throughput prepares them in
$ANISODYN_BENCH_CACHE): NPT at the given βP with "sweeps": "sequential" on one thread, then with
"sweeps": "domains" on two threads. Each run tunes its moves for `--tune` cycles, then samples
`--cycles` cycles. Prints the mean packing fraction and order parameters U_T, U_W, U_L of the
sampling phase with their block-averaged standard errors, the difference in combined standard
errors, and each run's wall time.

    bench/mc_domain_equilibrium.py STATE_NAME --pressure BETA_P [--cycles 20000] [--tune 2000] [--seeds 5,6,7]

With several seeds it also prints the mean over seeds with the seed-to-seed standard error: under
NPT the volume decorrelates slowly (thousands of cycles for thousands of particles), and one run's
block errors can be far too small.
"""
import argparse
import json
import os
import statistics
import subprocess
import sys
import tempfile
import time


def run(mc, state, pressure, sweeps, threads, cycles, tune, seed, workdir):
    config = {
        "seed": seed,
        "sweeps": sweeps,
        "observe_every": 10,
        "phases": [
            {"type": "npt", "label": "tune", "pressure": pressure, "cycles": tune, "tune": True},
            {"type": "npt", "label": "sample", "pressure": pressure, "cycles": cycles},
        ],
    }
    cfg = os.path.join(workdir, f"{sweeps}.json")
    with open(cfg, "w") as f:
        json.dump(config, f)
    t0 = time.perf_counter()
    out = subprocess.run([mc, "--threads", str(threads), "--config", cfg, "--input", state,
                          "--output", os.path.join(workdir, f"{sweeps}.h5")],
                         check=True, capture_output=True, text=True).stdout
    wall = time.perf_counter() - t0
    return json.loads(out)["phases"][-1], wall


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("state", help="cached state name, e.g. cuboids_12x1x1_N2000_eta0.34")
    ap.add_argument("--pressure", type=float, required=True, help="βP in the particles' length unit")
    ap.add_argument("--cycles", type=int, default=20000)
    ap.add_argument("--tune", type=int, default=2000)
    ap.add_argument("--seeds", default="5", help="comma-separated seeds: one pair of runs per seed")
    ap.add_argument("--build", default=os.environ.get("ANISODYN_BUILD_DIR", "build"))
    args = ap.parse_args()
    cache = os.environ.get("ANISODYN_BENCH_CACHE", "bench-cache")
    state = os.path.join(cache, args.state + ".h5")
    if not os.path.exists(state):
        sys.exit(f"mc_domain_equilibrium: no {state}: run build/bin/bench_mc_throughput first")
    mc = os.path.join(args.build, "bin", "anisodyn-mc")
    seeds = [int(x) for x in args.seeds.split(",")]
    print(f"{args.state}: NPT betaP = {args.pressure}, {args.tune} tuning + {args.cycles} sampled cycles, seeds {seeds}")
    per_seed = {"sequential": [], "domains": []}
    for seed in seeds:
        with tempfile.TemporaryDirectory() as workdir:
            seq, seq_wall = run(mc, state, args.pressure, "sequential", 1, args.cycles, args.tune, seed, workdir)
            dom, dom_wall = run(mc, state, args.pressure, "domains", 2, args.cycles, args.tune, seed, workdir)
        per_seed["sequential"].append(seq)
        per_seed["domains"].append(dom)
        print(f" seed {seed}: wall time sequential (1 thread) {seq_wall:.1f} s, domains (2 threads) {dom_wall:.1f} s")
        compare("eta", seq["packing_fraction"], dom["packing_fraction"])
        for species, order in seq.get("order", {}).items():
            if isinstance(order, dict) and "T" in order:
                for axis in ("T", "W", "L"):
                    compare(f"U_{axis}", order[axis], dom["order"][species][axis])
        for name, phase in (("sequential", seq), ("domains", dom)):
            print(f"   {name} acceptance {json.dumps(phase['acceptance'])}")
    if len(seeds) > 1:
        # The block errors of one run can miss slow volume or order fluctuations: the spread
        # over seeds is the check on them.
        print(" over seeds (mean ± standard error of the per-seed means):")
        for name, runs in per_seed.items():
            eta = [r["packing_fraction"]["mean"] for r in runs]
            print(f"   {name:>10}: eta {statistics.mean(eta):.5f} ± {statistics.stdev(eta) / len(eta) ** 0.5:.5f}")


def compare(name, a, b):
    se = (a["error"] ** 2 + b["error"] ** 2) ** 0.5
    z = (b["mean"] - a["mean"]) / se if se > 0 else float("nan")
    print(f"   {name:>4}: sequential {a['mean']:.5f} ± {a['error']:.5f}   domains {b['mean']:.5f} ± {b['error']:.5f}"
          f"   difference {z:+.2f} SE (block errors)")


if __name__ == "__main__":
    main()
