// BD throughput: particle-steps per second of BdIntegrator (spec 20 §3). Free rods for now (the
// overlap-volume forces come with issue 15's potential): 1760 rods, the largest density of study B
// ((L/D)φ = 1.76), and N = 440 … 7040 for the cost against N; one and two threads (the noise is
// keyed by step and particle, so the trajectory is the same for both).
#include <benchmark/benchmark.h>

#ifdef _OPENMP
#include <omp.h>
#endif

#include "anisodyn/bd/bd_integrator.hpp"
#include "anisodyn/core/quaternion.hpp"
#include "anisodyn/core/rng.hpp"
#include "support/timing.hpp"

using namespace anisodyn;

namespace {

State free_rods(std::size_t n) {
  State s;
  s.species = {Species{"rod", Shape::spherocylinder(0.88, 0.0148), 1.0, {}, {}}};
  s.box = Box(Vec3::Constant(2.08));
  Rng rng(5, 0);
  for (std::size_t i = 0; i < n; ++i)
    s.particles.add(0, Vec3(rng.uniform(0, 2.08), rng.uniform(0, 2.08), rng.uniform(0, 2.08)),
                    uniform_quaternion(rng.uniform(), rng.uniform(), rng.uniform()), static_cast<std::int64_t>(i));
  return s;
}

void BM_BdFreeRods(benchmark::State& bs) {
  const auto n = static_cast<std::size_t>(bs.range(0));
#ifdef _OPENMP
  omp_set_num_threads(static_cast<int>(bs.range(1)));
#endif
  State s = free_rods(n);
  BdSettings b;
  b.time_step = 5e-8;  // spec 20 §1, SI: µm and s
  b.kT = 1.0;
  b.diffusion = {BdDiffusion{3.0603, 1.5302, 23.711}};  // D_∥, D_⊥ in µm²/s, D_r in 1/s (70-theory §5.1)
  BdIntegrator bd(b, nullptr);
  for (auto _ : bs) {
    s.time += bd.step(s);
    ++s.step;
  }
  bs.counters["particle_steps_per_s"] = benchmark::Counter(static_cast<double>(n) * static_cast<double>(bs.iterations()),
                                                           benchmark::Counter::kIsRate);
  bs.counters["threads"] = static_cast<double>(bs.range(1));
}

}  // namespace

BENCHMARK(BM_BdFreeRods)
    ->Args({1760, 1})
    ->Args({1760, 2})
    ->Args({440, 1})
    ->Args({7040, 1})
    ->UseRealTime()
    ->Apply([](benchmark::internal::Benchmark* b) { bench::min_time_or_fixed_iterations(b, 1.0); });

BENCHMARK_MAIN();
