#pragma once
// A sum over many particles, in parallel, with the same bits for any number of threads: the
// indices go in chunks of fixed size, each chunk is summed in index order (by whichever thread),
// and the chunk sums are added in chunk order. Per-step observables (the kinetic tensor of a DPD
// run) use it: a serial loop there left the other thread idle between two parallel regions, and on
// a virtual machine an idle thread can lose its core for longer than the loop took
// (docs/performance.md).
#include <cstddef>
#include <vector>

namespace anisodyn {

/// Σ_{i<n} term(i), starting from zero (T: anything with +=, such as double or an Eigen matrix).
template <class T, class Term>
T ordered_sum(std::size_t n, const T& zero, Term term) {
  constexpr std::size_t kChunk = 2048;
  const std::size_t chunks = (n + kChunk - 1) / kChunk;
  std::vector<T> partial(chunks, zero);
#pragma omp parallel for schedule(static) if (chunks > 1)
  for (std::size_t c = 0; c < chunks; ++c) {
    T acc = zero;
    const std::size_t end = c + 1 == chunks ? n : (c + 1) * kChunk;
    for (std::size_t i = c * kChunk; i < end; ++i) acc += term(i);
    partial[c] = acc;
  }
  T total = zero;
  for (const T& s : partial) total += s;
  return total;
}

}  // namespace anisodyn
