#!/usr/bin/env bash
# The DPD throughput of issue 16, side by side in one run: the pure Groot–Warren liquid, N = 24000
# (box 20), rho = 3, a = 25, gamma = 4.5, dt = 0.005, on one and two threads, anisodyn
# (build/bin/bench_dpd_throughput) and LAMMPS (pair_style dpd/omp, built by lammps.sh) alternately,
# ROUNDS rounds (default 3). Without LAMMPS (no network for its build, CI) it times anisodyn alone
# and says so. Each two-thread run is labelled with the core-to-core round trip measured just
# before and just after it (bench_core_latency): the host places the two virtual CPUs on cores
# near or far from each other, and moves them now and then (docs/performance.md); a run whose
# two labels differ straddled a move.
# Usage: bench/peers/dpd_side_by_side.sh [BIN_DIR]
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
bin=${1:-$here/../../build/bin}
rounds=${ROUNDS:-3}
if ! lmp=$("$here/lammps.sh"); then
  echo "LAMMPS is not available (see above): timing anisodyn alone"
  lmp=""
fi
echo "machine: $(nproc) cores; $(uptime)"
round_trip() {
  "$bin/bench_core_latency" 2>/dev/null | awk '/BM_CoreRoundTrip/ {printf "%.0f", $2}'
}
# A two-thread run's line ends with the round trips just before and just after it.
label() {
  if [ "$1" = 2 ]; then
    local before after line
    before=$(round_trip)
    line=$("${@:2}")
    after=$(round_trip)
    echo "$line [core round trip $before ns before, $after ns after]"
  else
    "${@:2}"
  fi
}
anisodyn_run() {
  "$bin/bench_dpd_throughput" --benchmark_filter="BM_DpdLiquid/24000/$1/" 2>/dev/null | grep BM_ |
    sed -E "s/.*particle_steps_per_s=([0-9.]+[kM]?)\/s.*/anisodyn round $2, $1 thread(s): \1 particle-steps\/s/"
}
lammps_run() {
  # "Loop time of T on P procs for S steps with N atoms": the last one is the production run's.
  (cd "$here" && OMP_NUM_THREADS=$1 "$lmp" -sf omp -pk omp "$1" -in dpd_liquid.lmp -var L 20 -var steps 3000 -log none) |
    grep "Loop time" | tail -1 |
    awk -v r="$2" -v t="$1" '{printf "LAMMPS   round %d, %d thread(s): %.3fM particle-steps/s\n", r, t, $9 * $12 / $4 / 1e6}'
}
for r in $(seq "$rounds"); do
  for t in 1 2; do
    label "$t" anisodyn_run "$t" "$r"
    if [ -n "$lmp" ]; then label "$t" lammps_run "$t" "$r"; fi
  done
done
echo "after: $(uptime)"
