#!/usr/bin/env python3
"""Hard-particle MC throughput, anisodyn against HOOMD-blue HPMC, in one run.

Both codes start from the same H5MD state: the benchmark states that bench_mc_throughput
prepares and caches in $ANISODYN_BENCH_CACHE. Each code tunes its own translation and rotation
moves to 35% acceptance (half translations, half rotations in both), then timed rounds
alternate between the codes: one HOOMD round in this process (CPU time of sim.run), then one
anisodyn round (bench_mc_throughput filtered to the system; Google Benchmark's CPU-time rate).
Trial moves are counted by each code's own counters. With --dmc, anisodyn runs DMC on the same
states (bench_dmc_throughput BM_DmcMcSystems: fixed small moves from D tensors) and HOOMD's moves
are tuned to the acceptance that anisodyn's DMC reaches. HOOMD runs with its default nselect = 4
(four trial moves per particle per step between tree builds), one CPU thread.

    PYTHONPATH=$(bench/peers/hoomd.sh) bench/peers/hpmc_side_by_side.py [--systems a,b,c,d] [--rounds 3]

Systems: a, b, c, d, e (issue 18's bench set) and c8000, c32000 ((c) at N = 8000 and 32000).

HOOMD's convex polyhedron cannot hold a sphere, so the board + sphere mixture (e) runs for
anisodyn only (bench_mc_throughput); the driver says so. Exit 77 when HOOMD is not importable.
"""
import argparse
import json
import os
import subprocess
import sys
import time

import numpy as np

SYSTEMS = {
    # key: (anisodyn MC benchmark, anisodyn DMC benchmark, cached state, description)
    "a": ("BM_McCuboids2000", "BM_DmcMcSystems/0", "cuboids_12x3.46x1_N2000_eta0.20", "2000 boards 12x3.46x1, eta 0.20"),
    "b": ("BM_McSpheres4000", "BM_DmcMcSystems/1", "spheres_N4000_eta0.40", "4000 spheres, eta 0.40"),
    "c": ("BM_McRods2000Nematic", "BM_DmcMcSystems/2", "cuboids_12x1x1_N2000_eta0.34", "2000 boards 12x1x1, eta 0.34, nematic"),
    "d": ("BM_McWideBoards2000Nematic", "BM_DmcMcSystems/3", "cuboids_12x8x1_N2000_eta0.34_compressed",
          "2000 boards 12x8x1, eta 0.34 (quick-compressed)"),
    # (c) at larger N, for the cost per trial against N (MC only)
    "c8000": ("BM_McRodsNematicN/8000/0", None, "cuboids_12x1x1_N8000_eta0.34", "8000 boards 12x1x1, eta 0.34, nematic"),
    "c32000": ("BM_McRodsNematicN/32000/0", None, "cuboids_12x1x1_N32000_eta0.34", "32000 boards 12x1x1, eta 0.34, nematic"),
}
TARGET_ACCEPTANCE = 0.35


def read_h5md_state(path):
    import h5py

    with h5py.File(path, "r") as f:
        part = f["particles/all"]
        edges = np.diag(part["box/edges/value"][-1])
        pos = part["position/value"][-1]
        quat = part["orientation/value"][-1]
        species = part["species/value"][-1]
        spec = f["parameters/species"]
        shapes = [s.decode() if isinstance(s, bytes) else s for s in spec["shape"][...]]
        return {
            "box": edges,
            "position": pos,
            "orientation": quat,
            "species": species,
            "shapes": shapes,
            "edges": spec["edges"][...],
            "diameter": spec["diameter"][...],
        }


def hoomd_simulation(state, seed):
    import hoomd

    if len(state["shapes"]) != 1:
        raise SystemExit("hpmc_side_by_side: one species per state (HOOMD's integrators hold one shape class)")
    L = state["box"]
    # H5MD positions are in [0, L); HOOMD's box is centred on the origin.
    pos = state["position"] - L * np.round(state["position"] / L)
    pos = np.where(pos >= L / 2, pos - L, pos)
    snap = hoomd.Snapshot()
    snap.configuration.box = [L[0], L[1], L[2], 0, 0, 0]
    snap.particles.N = len(pos)
    snap.particles.types = ["A"]
    snap.particles.typeid[:] = 0
    snap.particles.position[:] = pos
    snap.particles.orientation[:] = state["orientation"]  # (w, x, y, z), body -> lab in both codes
    sim = hoomd.Simulation(device=hoomd.device.CPU(), seed=seed)  # built without TBB: one thread
    sim.create_state_from_snapshot(snap)
    shape = state["shapes"][0]
    if shape == "sphere":
        mc = hoomd.hpmc.integrate.Sphere(default_d=0.1, default_a=0.0)
        mc.shape["A"] = dict(diameter=float(state["diameter"][0]))
    elif shape == "cuboid":
        h = state["edges"][0] / 2
        corners = [[sx * h[0], sy * h[1], sz * h[2]] for sx in (-1, 1) for sy in (-1, 1) for sz in (-1, 1)]
        mc = hoomd.hpmc.integrate.ConvexPolyhedron(default_d=0.1, default_a=0.1)
        mc.shape["A"] = dict(vertices=corners)
    else:
        raise SystemExit(f"hpmc_side_by_side: no HOOMD shape for {shape}")
    sim.operations.integrator = mc
    sim.run(0)  # attaches the integrator (its counters and overlap count exist from here)
    return sim, mc


def tune_hoomd(sim, mc, anisotropic, target):
    import hoomd

    moves = ["d", "a"] if anisotropic else ["d"]
    tuner = hoomd.hpmc.tune.MoveSize.scale_solver(
        trigger=hoomd.trigger.Periodic(5), moves=moves, target=target, types=["A"],
        max_translation_move=0.25 * float(min(sim.state.box.L)), max_rotation_move=np.pi)
    sim.operations.tuners.append(tuner)
    sim.run(150)  # 600 sweeps at nselect = 4, tuned every 20 sweeps: as anisodyn tunes (30 rounds of 20 cycles)
    sim.operations.tuners.remove(tuner)


def moves_of_last_run(mc):
    """Trial and accepted moves of the last sim.run (HOOMD's counters restart at every run)."""
    t, r = mc.translate_moves, mc.rotate_moves
    return sum(t) + sum(r), t[0] + r[0]


def hoomd_round(sim, mc, seconds):
    """Trial moves per CPU second and acceptance over runs of about `seconds` CPU seconds."""
    steps, spent, tried, accepted = 10, 0.0, 0, 0
    while spent < seconds:
        t0 = time.process_time()
        sim.run(steps)
        spent += time.process_time() - t0
        n, a = moves_of_last_run(mc)
        tried, accepted = tried + n, accepted + a
        steps = min(steps * 2, 2000)
    return tried / spent, accepted / tried, spent


def anisodyn_round(bench_binary, benchmark):
    out = subprocess.run([bench_binary, f"--benchmark_filter=^{benchmark}(/min_time.*|/iterations.*)?$",
                          "--benchmark_format=json"], check=True, capture_output=True, text=True).stdout
    row = json.loads(out)["benchmarks"][0]
    return row["trials_per_s"], row["acceptance"]


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--systems", default="a,b,c,d")
    ap.add_argument("--rounds", type=int, default=3)
    ap.add_argument("--seconds", type=float, default=5.0, help="CPU seconds per HOOMD round")
    ap.add_argument("--build", default=os.environ.get("ANISODYN_BUILD_DIR", "build"))
    ap.add_argument("--dmc", action="store_true",
                    help="issue 18's (f): anisodyn's DMC on the same states (fixed small moves); HOOMD's move sizes "
                         "tuned to the acceptance anisodyn's DMC reaches")
    args = ap.parse_args()

    try:
        import hoomd
        import hoomd.hpmc  # noqa: F401
    except ImportError as e:
        print(f"hpmc_side_by_side: SKIP: HOOMD-blue is not importable ({e}); "
              "run with PYTHONPATH=$(bench/peers/hoomd.sh)", file=sys.stderr)
        return 77
    bench_binary = os.path.join(args.build, "bin", "bench_dmc_throughput" if args.dmc else "bench_mc_throughput")
    cache = os.environ.get("ANISODYN_BENCH_CACHE", "bench-cache")
    print(f"HOOMD-blue {hoomd.version.version}; anisodyn {bench_binary}; states in {cache}")
    print(f"cpu: {open('/proc/cpuinfo').read().split('model name')[1].split(':')[1].splitlines()[0].strip()}")

    for key in args.systems.split(","):
        if key == "e":
            print("(e) boards + spheres: HOOMD's ConvexPolyhedron cannot hold spheres; anisodyn only "
                  "(bench_mc_throughput BM_McRodsSpheres2200Nematic)")
            continue
        mc_benchmark, dmc_benchmark, state_name, label = SYSTEMS[key]
        benchmark = dmc_benchmark if args.dmc else mc_benchmark
        if benchmark is None:
            print(f"({key}) {label}: no DMC benchmark for this state; skipped")
            continue
        path = os.path.join(cache, state_name + ".h5")
        target = TARGET_ACCEPTANCE
        if args.dmc or not os.path.exists(path):  # the anisodyn benchmark prepares and caches the state
            _, target = anisodyn_round(bench_binary, benchmark)
            target = target if args.dmc else TARGET_ACCEPTANCE
        state = read_h5md_state(path)
        sim, mc = hoomd_simulation(state, seed=7)
        overlaps = mc.overlaps
        anisotropic = state["shapes"][0] != "sphere"
        tune_hoomd(sim, mc, anisotropic, target)
        print(f"\n({key}) {label}: {path}, {len(state['position'])} particles, box {state['box']}, "
              f"HOOMD overlaps at start {overlaps}, HOOMD moves d = {mc.d['A']:.4g}, a = {mc.a['A']:.4g}")
        ratios = []
        for r in range(args.rounds):
            h_rate, h_acc, h_cpu = hoomd_round(sim, mc, args.seconds)
            a_rate, a_acc = anisodyn_round(bench_binary, benchmark)
            ratios.append(a_rate / h_rate)
            print(f"  round {r + 1}: HOOMD {h_rate:.4g} trials/CPU-s (acceptance {h_acc:.3f}, {h_cpu:.1f} s)  "
                  f"anisodyn {a_rate:.4g} (acceptance {a_acc:.3f})  ratio {ratios[-1]:.2f}")
        print(f"  ratio anisodyn/HOOMD: {np.mean(ratios):.2f} (rounds {min(ratios):.2f}-{max(ratios):.2f}); "
              f"HOOMD overlaps at end {mc.overlaps}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
