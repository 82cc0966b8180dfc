#!/usr/bin/env bash
# Issue 18's two-thread bar, measured in pairs: MC preparation on two threads (domain sweeps)
# against the sequential sweep on one, for (a) boards 12×3.46×1 and (c) rods 12×1×1, NVT and NPT.
# Each one-thread run of bench_mc_throughput is followed at once by its two-thread counterpart,
# so that both see the same phase of a noisy host (one whose speed changes by 25% within minutes);
# the script prints each pair's ratio and, at the end, the median and range of the ratios per
# system. Each line also gives the core-to-core round trip measured just before its pair
# (bench_core_latency): the host places the two virtual CPUs near or far from each other.
# Benchmark states come from $ANISODYN_BENCH_CACHE (prepared on first use).
# Usage: bench/mc_two_threads.sh [ROUNDS (default 8)] [BIN_DIR (default build/bin)]
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
rounds=${1:-8}
bin=${2:-$here/../build/bin}
pairs=(
  "NVT_(a) BM_McCuboids2000/min BM_McDomainSweeps/0/2"
  "NVT_(c) BM_McRods2000Nematic/min BM_McDomainSweeps/2/2"
  "NPT_(a) BM_McNpt/0/1/0 BM_McNpt/0/2/1"
  "NPT_(c) BM_McNpt/2/1/0 BM_McNpt/2/2/1"
)
rate() {
  "$bin/bench_mc_throughput" --benchmark_filter="$1" --benchmark_min_time=1 2>/dev/null |
    awk 'match($0, /trials_per_s=[0-9.]+[kM]?/) {
           v = substr($0, RSTART + 13, RLENGTH - 13); f = 1
           if (v ~ /k$/) f = 1e3; if (v ~ /M$/) f = 1e6
           sub(/[kM]$/, "", v); printf "%.0f\n", v * f; exit }'
}
round_trip() {
  "$bin/bench_core_latency" 2>/dev/null | awk '/BM_CoreRoundTrip/ {printf "%.0f", $2}'
}
for tool in bench_mc_throughput bench_core_latency; do
  [ -x "$bin/$tool" ] || { echo "mc_two_threads.sh: $bin/$tool not found (build the benchmarks first: scripts/build)" >&2; exit 2; }
done
echo "machine: $(nproc) cores; $(uptime)"
results=$(mktemp)
trap 'rm -f "$results"' EXIT
for round in $(seq "$rounds"); do
  for pair in "${pairs[@]}"; do
    read -r name one two <<<"$pair"
    trip=$(round_trip)
    a=$(rate "$one")
    b=$(rate "$two")
    if [ -z "$a" ] || [ -z "$b" ]; then
      echo "mc_two_threads.sh: no rate from $one or $two" >&2
      exit 1
    fi
    ratio=$(awk -v a="$a" -v b="$b" 'BEGIN { printf "%.3f", b / a }')
    printf '%s round %d %s  1 thread %s  2 threads %s  ratio %s  [core round trip %s ns]\n' "$(date -u +%T)" "$round" "$name" "$a" "$b" "$ratio" "$trip"
    echo "$name $ratio" >>"$results"
  done
done
echo "two threads ÷ one, per system: median (range) over $rounds pairs"
sort -k1,1 -k2,2n "$results" | awk '
  { r[$1, ++n[$1]] = $2 }
  END { for (s in n) { k = n[s]; m = (k % 2) ? r[s, (k + 1) / 2] : (r[s, k / 2] + r[s, k / 2 + 1]) / 2
                       printf "%s %.2f× (%.2f–%.2f)\n", s, m, r[s, 1], r[s, k] } }' | sort
