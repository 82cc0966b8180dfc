// Core-to-core round trip: two threads, pinned to the first two CPUs this process may use, hand
// one cache line back and forth. On a virtual machine the host may place the two virtual CPUs
// on cores that share a cache or on cores that do not, and moves them now and then; the round
// trip tells which. Every parallel phase that reads data another thread wrote pays it, so the
// two-thread throughput of the engines follows it (docs/performance.md, DPD). The side-by-side
// scripts run it beside each two-thread run to label the run.
#include <benchmark/benchmark.h>

#include <atomic>
#include <thread>
#include <vector>

#include <pthread.h>
#include <sched.h>

namespace {

std::vector<int> allowed_cpus() {
  cpu_set_t set;
  CPU_ZERO(&set);
  std::vector<int> cpus;
  if (sched_getaffinity(0, sizeof set, &set) != 0) return cpus;
  for (int c = 0; c < CPU_SETSIZE; ++c)
    if (CPU_ISSET(c, &set)) cpus.push_back(c);
  return cpus;
}

void pin_to(int cpu) {
  cpu_set_t set;
  CPU_ZERO(&set);
  CPU_SET(cpu, &set);
  pthread_setaffinity_np(pthread_self(), sizeof set, &set);
}

void BM_CoreRoundTrip(benchmark::State& bs) {
  static const std::vector<int> cpus = allowed_cpus();  // before the first pinning
  if (cpus.size() < 2) {
    bs.SkipWithError("fewer than two CPUs");
    return;
  }
  alignas(64) std::atomic<std::int64_t> ball{0};  // odd: the partner's to return; even: back
  alignas(64) std::atomic<bool> stop{false};  // a line of its own
  std::thread partner([&] {
    pin_to(cpus[1]);
    for (std::int64_t b = 1;; b += 2) {
      while (ball.load(std::memory_order_acquire) != b)
        if (stop.load(std::memory_order_relaxed)) return;
      ball.store(b + 1, std::memory_order_release);
    }
  });
  pin_to(cpus[0]);
  std::int64_t b = 0;
  for (auto _ : bs) {
    ball.store(b + 1, std::memory_order_release);
    while (ball.load(std::memory_order_acquire) != b + 2) {
    }
    b += 2;
  }
  stop.store(true);
  partner.join();
}

}  // namespace

// The time per iteration is one round trip.
BENCHMARK(BM_CoreRoundTrip)->UseRealTime()->MinTime(0.5)->Unit(benchmark::kNanosecond);
BENCHMARK_MAIN();
