#!/usr/bin/env bash
# The DPD throughput of issue 16, side by side in one run: the pure Groot–Warren liquid, N = 24000
# (box 20), rho = 3, a = 25, gamma = 4.5, dt = 0.005, on one and two threads, anisodyn
# (build/bin/bench_dpd_throughput) and LAMMPS (pair_style dpd/omp, built by lammps.sh) alternately,
# ROUNDS rounds (default 3). Without LAMMPS (no network for its build, CI) it times anisodyn alone
# and says so. Usage: bench/peers/dpd_side_by_side.sh [BIN_DIR]
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
bin=${1:-$here/../../build/bin}
rounds=${ROUNDS:-3}
if ! lmp=$("$here/lammps.sh"); then
  echo "LAMMPS is not available (see above): timing anisodyn alone"
  lmp=""
fi
echo "machine: $(nproc) cores; $(uptime)"
for r in $(seq "$rounds"); do
  for t in 1 2; do
    "$bin/bench_dpd_throughput" --benchmark_filter="BM_DpdLiquid/24000/$t/" 2>/dev/null | grep BM_ |
      sed -E "s/.*particle_steps_per_s=([0-9.]+[kM]?)\/s.*/anisodyn round $r, $t thread(s): \1 particle-steps\/s/"
    if [ -n "$lmp" ]; then
      # "Loop time of T on P procs for S steps with N atoms": the last one is the production run's.
      (cd "$here" && OMP_NUM_THREADS=$t "$lmp" -sf omp -pk omp "$t" -in dpd_liquid.lmp -var L 20 -var steps 3000 -log none) |
        grep "Loop time" | tail -1 |
        awk -v r="$r" -v t="$t" '{printf "LAMMPS   round %d, %d thread(s): %.3fM particle-steps/s\n", r, t, $9 * $12 / $4 / 1e6}'
    fi
  done
done
echo "after: $(uptime)"
