// BD throughput: particle-steps per second of BdIntegrator (spec 20 §3), free rods and rods with the
// overlap-volume potential (spec 20 §4, through PairForceField<RodOverlapPairs>): 1760 rods at the
// largest density of study B ((L/D)φ = 1.76, box 2.08 µm), and N = 440 … 7040 at the same number
// density for the cost against N (free rods; with the potential from 1320, the smallest box that
// keeps the minimum image, edge/2 > L + D); one and two threads (the noise is keyed by step and particle and
// the pair loop is owner-computes, so the trajectory is the same for both).
#include <benchmark/benchmark.h>

#ifdef _OPENMP
#include <omp.h>
#endif

#include "anisodyn/bd/bd_integrator.hpp"
#include "anisodyn/core/quaternion.hpp"
#include "anisodyn/core/rng.hpp"
#include "anisodyn/interactions/pair_force_field.hpp"
#include "anisodyn/interactions/rod_overlap_pairs.hpp"
#include "support/timing.hpp"

using namespace anisodyn;

namespace {

/// n rods of spec 20 (µm) with random centres and axes at the number density of 1760 rods in 2.08³ µm³.
State free_rods(std::size_t n) {
  State s;
  s.species = {Species{"rod", Shape::spherocylinder(0.88, 0.0148), 1.0, {}, {}}};
  const double edge = 2.08 * std::cbrt(static_cast<double>(n) / 1760.0);
  s.box = Box(Vec3::Constant(edge));
  Rng rng(5, 0);
  for (std::size_t i = 0; i < n; ++i)
    s.particles.add(0, Vec3(rng.uniform(0, edge), rng.uniform(0, edge), rng.uniform(0, edge)),
                    uniform_quaternion(rng.uniform(), rng.uniform(), rng.uniform()), static_cast<std::int64_t>(i));
  return s;
}

void run_steps(benchmark::State& bs, bool with_potential) {
  const auto n = static_cast<std::size_t>(bs.range(0));
#ifdef _OPENMP
  omp_set_num_threads(static_cast<int>(bs.range(1)));
#endif
  State s = free_rods(n);
  BdSettings b;
  b.time_step = 5e-8;  // spec 20 §1, SI: µm and s
  b.kT = 1.0;          // energies in kT
  b.diffusion = {BdDiffusion{3.0603, 1.5302, 23.711}};  // D_∥, D_⊥ in µm²/s, D_r in 1/s (70-theory §5.1)
  OverlapVolumeSettings ov{0.88, 0.0148, OverlapVolume::hardness_for(0.0148, 1.0), FiniteLengthRule::SegmentDistance};
  const RodOverlapPairs pairs{OverlapVolume(ov), 0, {}, {}};
  PairForceField<RodOverlapPairs> field(pairs, pairs.cutoffs(1), 1, 0.88 / 20.0);
  ForceField forces;
  if (with_potential) forces = [&field](const State& st, BodyForces& out) { field(st, out); };
  BdIntegrator bd(b, forces);
  for (auto _ : bs) {
    s.time += bd.step(s);
    ++s.step;
  }
  bs.counters["particle_steps_per_s"] = benchmark::Counter(static_cast<double>(n) * static_cast<double>(bs.iterations()),
                                                           benchmark::Counter::kIsRate);
  bs.counters["threads"] = static_cast<double>(bs.range(1));
}

void BM_BdFreeRods(benchmark::State& bs) { run_steps(bs, false); }
void BM_BdRodsOverlapVolume(benchmark::State& bs) { run_steps(bs, true); }

}  // namespace

BENCHMARK(BM_BdFreeRods)
    ->Args({1760, 1})
    ->Args({1760, 2})
    ->Args({440, 1})
    ->Args({7040, 1})
    ->UseRealTime()
    ->Apply([](benchmark::internal::Benchmark* b) { bench::min_time_or_fixed_iterations(b, 1.0); });

BENCHMARK(BM_BdRodsOverlapVolume)
    ->Args({1760, 1})
    ->Args({1760, 2})
    ->Args({1320, 1})
    ->Args({3520, 1})
    ->Args({7040, 1})
    ->UseRealTime()
    ->Unit(benchmark::kMillisecond)
    ->Apply([](benchmark::internal::Benchmark* b) { bench::min_time_or_fixed_iterations(b, 2.0); });

BENCHMARK_MAIN();
