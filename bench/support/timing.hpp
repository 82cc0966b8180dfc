#pragma once
// Run length of the throughput benchmarks. Normally a minimum time; with ANISODYN_BENCH_ITERATIONS=n
// every benchmark runs exactly n iterations, once, so that an instruction count
// (valgrind --tool=callgrind --toggle-collect=…) divides by a known number of trials.
#include <benchmark/benchmark.h>

#include <cstdlib>

namespace anisodyn::bench {

inline void min_time_or_fixed_iterations(benchmark::internal::Benchmark* b, double seconds) {
  if (const char* n = std::getenv("ANISODYN_BENCH_ITERATIONS")) b->Iterations(std::atoll(n));
  else b->MinTime(seconds);
}

}  // namespace anisodyn::bench
