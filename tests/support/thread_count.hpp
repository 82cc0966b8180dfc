#pragma once
// OpenMP thread counts for the tests, mostly those that check that a result has the same bits on
// any thread count. Each sets the count for a scope and afterwards restores the count that was in
// force before (omp_get_max_threads()), also when the scope is left by an exception or by a failed
// ASSERT_*. Built without OpenMP they just run the code on the one thread there is.
//   ScopedThreadCount  sets the count until the end of the enclosing block;
//   with_threads       runs a callable on a given count and returns its result;
//   on_thread_counts   runs a callable once per count and returns the results in that order.
#ifdef _OPENMP
#include <omp.h>
#endif

#include <initializer_list>
#include <type_traits>
#include <utility>
#include <vector>

namespace anisodyn::testing_support {

/// Sets the OpenMP thread count to `threads` for its lifetime and then restores the previous
/// omp_get_max_threads(). Without OpenMP it does nothing.
class ScopedThreadCount {
 public:
  explicit ScopedThreadCount(int threads) {
#ifdef _OPENMP
    previous_ = omp_get_max_threads();
    omp_set_num_threads(threads);
#else
    (void)threads;
#endif
  }
  ~ScopedThreadCount() {
#ifdef _OPENMP
    omp_set_num_threads(previous_);
#endif
  }
  ScopedThreadCount(const ScopedThreadCount&) = delete;
  ScopedThreadCount& operator=(const ScopedThreadCount&) = delete;

 private:
  int previous_ = 1;
};

/// f() run with `threads` OpenMP threads; the previous thread count is restored afterwards.
template <class F>
decltype(auto) with_threads(int threads, F&& f) {
  const ScopedThreadCount count(threads);
  return std::forward<F>(f)();
}

/// f() run once per thread count of `counts`, in that order: the results, for comparison.
template <class F>
std::vector<std::remove_cvref_t<std::invoke_result_t<F&>>> on_thread_counts(std::initializer_list<int> counts, F&& f) {
  std::vector<std::remove_cvref_t<std::invoke_result_t<F&>>> results;
  results.reserve(counts.size());
  for (const int threads : counts) results.push_back(with_threads(threads, f));
  return results;
}

}  // namespace anisodyn::testing_support
