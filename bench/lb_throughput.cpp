// LB throughput (issue 17): million lattice-node updates per second (MLUPS) of the D3Q19 fluid
// (lb/lb_fluid.hpp) on 64³ nodes, deterministic and fluctuating (spec 40's ρ = 6.004, ν = 0.016,
// k_BT = 4×10⁻⁴ in lattice units), on one and two threads; and, in the same binary, the machine's
// copy bandwidth (b[i] = a[i] over two arrays of 80 MB each, counted as 16 bytes per element, as
// STREAM counts it), with ordinary and with streaming stores. A step reads and writes 19 populations per node and reads the three force
// components and the solid flag: 2 × 152 + 24 + 1 = 329 bytes per node update, so the bandwidth
// limit is copy bandwidth / 329 B (docs/performance.md). Arguments: edge, threads, thermal, streaming
// stores (1; the default above 32 MB) or ordinary ones (0). And
// the cost of coupling 1000 beads for one LB step (two MD steps).
#include <benchmark/benchmark.h>

#include <cmath>
#if defined(__AVX__)
#include <immintrin.h>
#endif
#include <vector>

#ifdef _OPENMP
#include <omp.h>
#endif

#include "anisodyn/lb/lb_fluid.hpp"
#include "anisodyn/lb/point_coupling.hpp"
#include "support/timing.hpp"

using namespace anisodyn;

namespace {

constexpr double kBytesPerNodeUpdate = 2 * 19 * 8 + 3 * 8 + 1;

void set_threads(benchmark::State& bs, int threads) {
#ifdef _OPENMP
  omp_set_num_threads(threads);
#endif
  bs.counters["threads"] = threads;
}

void BM_LbStep(benchmark::State& bs) {
  const int edge = static_cast<int>(bs.range(0));
  set_threads(bs, static_cast<int>(bs.range(1)));
  const bool thermal = bs.range(2) != 0;
  lb::LbFluid fluid({edge, edge, edge}, lb::LbParameters{6.004, 0.016, 0.0, 0.0, thermal ? 4e-4 : 0.0, 1});
  fluid.use_streaming_stores(bs.range(3) != 0);
  for (int s = 0; s < 3; ++s) fluid.step();
  for (auto _ : bs) fluid.step();
  bs.counters["MLUPS"] = benchmark::Counter(static_cast<double>(fluid.nodes()) * static_cast<double>(bs.iterations()) / 1e6, benchmark::Counter::kIsRate);
  bs.counters["thermal"] = thermal;
  bs.counters["streaming_stores"] = fluid.streaming_stores();
}

// The coupling of 1000 beads (lb/point_coupling.hpp), two MD steps per LB step, on its own: the
// per-step cost to add to the fluid's (issue 17 asks for it). Beads spread through the 64³ box.
void BM_LbCoupling1000Beads(benchmark::State& bs) {
  set_threads(bs, 1);
  lb::LbFluid fluid({64, 64, 64}, lb::LbParameters{6.004, 0.016, 0.0, 0.0, 4e-4, 1});
  const lb::PointCoupling coupling(0.56, 0.5, 4e-4, 2);
  std::vector<Vec3> r, v, force;
  std::vector<std::uint32_t> id;
  for (std::uint32_t b = 0; b < 1000; ++b) {
    r.emplace_back(std::fmod(7.3 * b, 64.0), std::fmod(3.1 * b + 0.4, 64.0), std::fmod(11.9 * b + 0.8, 64.0));
    v.emplace_back(0.01, 0.0, -0.01);
    id.push_back(b);
  }
  std::uint64_t md = 0;
  for (auto _ : bs) {
    coupling.couple(fluid, r, v, id, md++, force);
    coupling.couple(fluid, r, v, id, md++, force);
  }
  bs.counters["beads"] = 1000;
}

void copy_line_streaming(const double* from, double* to) {
#if defined(__AVX512F__)
  _mm512_stream_pd(to, _mm512_load_pd(from));
#elif defined(__AVX__)
  _mm256_stream_pd(to, _mm256_load_pd(from));
  _mm256_stream_pd(to + 4, _mm256_load_pd(from + 4));
#else
  for (int k = 0; k < 8; ++k) to[k] = from[k];
#endif
}
void fence() {
#if defined(__AVX__)
  _mm_sfence();
#endif
}

// b[i] = a[i] with ordinary stores (range(1) = 0: the line of b is read before it is written, as
// STREAM's copy does) or non-temporal ones (1: no read for ownership, as the LB step writes its
// rows where n_x is a multiple of 8). Both count 16 bytes per element.
void BM_CopyBandwidth(benchmark::State& bs) {
  set_threads(bs, static_cast<int>(bs.range(0)));
  const bool streaming = bs.range(1) != 0;
  const std::size_t n = std::size_t{10} << 20;  // 80 MB per array, far beyond the caches
  std::vector<double, lb::CacheLineAllocator<double>> a(n, 1.0), b(n, 0.0);
#pragma omp parallel for schedule(static)
  for (std::size_t i = 0; i < n; ++i) a[i] = 1.0, b[i] = 0.0;  // first touch by the copying thread
  for (auto _ : bs) {
    if (streaming) {
#pragma omp parallel for schedule(static)
      for (std::size_t i = 0; i < n; i += 8) copy_line_streaming(a.data() + i, b.data() + i);
      fence();
    } else {
#pragma omp parallel for schedule(static)
      for (std::size_t i = 0; i < n; ++i) b[i] = a[i];
    }
    benchmark::DoNotOptimize(b.data());
    benchmark::ClobberMemory();
  }
  const double bytes = 16.0 * static_cast<double>(n) * static_cast<double>(bs.iterations());
  bs.counters["GB_per_s"] = benchmark::Counter(bytes / 1e9, benchmark::Counter::kIsRate);
  bs.counters["limit_MLUPS"] = benchmark::Counter(bytes / kBytesPerNodeUpdate / 1e6, benchmark::Counter::kIsRate);
  bs.counters["streaming"] = streaming;
}

}  // namespace

BENCHMARK(BM_LbStep)->ArgsProduct({{64}, {1, 2}, {0, 1}, {1}})->UseRealTime()->Unit(benchmark::kMillisecond)->Apply([](auto* b) { bench::min_time_or_fixed_iterations(b, 2.0); });
BENCHMARK(BM_LbStep)->ArgsProduct({{24, 32, 48, 96}, {1}, {0}, {0, 1}})->Args({64, 1, 0, 0})->Args({64, 2, 0, 0})->UseRealTime()->Unit(benchmark::kMillisecond)->Apply([](auto* b) { bench::min_time_or_fixed_iterations(b, 2.0); });
BENCHMARK(BM_LbCoupling1000Beads)->UseRealTime()->Unit(benchmark::kMillisecond)->Apply([](auto* b) { bench::min_time_or_fixed_iterations(b, 1.0); });
BENCHMARK(BM_CopyBandwidth)->ArgsProduct({{1, 2}, {0, 1}})->UseRealTime()->Unit(benchmark::kMillisecond)->Apply([](auto* b) { bench::min_time_or_fixed_iterations(b, 1.0); });
BENCHMARK_MAIN();
