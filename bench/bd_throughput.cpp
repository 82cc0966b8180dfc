// BD throughput: particle-steps per second of BdIntegrator (spec 20 §3), free rods and rods with the
// overlap-volume potential (spec 20 §4, through PairForceField<RodOverlapPairs>, with the step-bound
// caps of §4.5 as in anisodyn-bd): 1760 rods at the largest density of study B ((L/D)φ = 1.76, box
// 2.08 µm), and N = 440 … 7040 at the same number density for the cost against N (free rods; with the
// potential from 1320, the smallest box that keeps the minimum image, edge/2 > L + D), plus 440 rods
// with the potential in the 2.08 µm box ((L/D)φ = 0.44, the D_eff pilot of spec 20 §5); one and two
// threads (the noise is keyed by step and particle and each rod sums its pair terms in a fixed
// order, so the trajectory is the same for both). Arguments: rods, threads, rods of the 2.08 µm box at that density.
// The rods' Verlet list is one of axis segments with skin L/20 (ANISODYN_BENCH_ROD_SKIN, in µm,
// overrides it); the counters give its builds per step, those of its centre-distance candidates, and
// the listed partners per rod at the end.
#include <benchmark/benchmark.h>

#include <cstdlib>

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

/// n rods of spec 20 (µm) with random centres and axes at the number density of n_box rods in 2.08³ µm³.
State free_rods(std::size_t n, std::size_t n_box) {
  State s;
  s.species = {Species{"rod", Shape::spherocylinder(0.88, 0.0148), 1.0, {}, {}}};
  const double edge = 2.08 * std::cbrt(static_cast<double>(n) / static_cast<double>(n_box));
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
  State s = free_rods(n, bs.range(2) > 0 ? static_cast<std::size_t>(bs.range(2)) : 1760);
  BdSettings b;
  b.time_step = 5e-8;  // spec 20 §1, SI: µm and s
  b.kT = 1.0;          // energies in kT
  b.diffusion = {BdDiffusion{3.0603, 1.5302, 23.711}};  // D_∥, D_⊥ in µm²/s, D_r in 1/s (70-theory §5.1)
  // Step-bound caps (spec 20 §4.5): deterministic steps of at most D/10 and 2D/(10L) rad.
  b.force_cap = 0.1 * 0.0148 * b.kT / (3.0603 * b.time_step);
  b.torque_cap = 0.2 * 0.0148 * b.kT / (0.88 * 23.711 * b.time_step);
  OverlapVolumeSettings ov{0.88, 0.0148, OverlapVolume::hardness_for(0.0148, 1.0), FiniteLengthRule::SegmentDistance};
  const RodOverlapPairs pairs{OverlapVolume(ov), 0, {}, {}};
  const char* skin = std::getenv("ANISODYN_BENCH_ROD_SKIN");
  PairForceField<RodOverlapPairs> field(pairs, pairs.segment_cutoffs(1), 1, skin ? std::atof(skin) : 0.88 / 20.0, pairs.half_lengths(1));
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
  if (with_potential) {
    // List rebuilds per step and listed partners per rod at the end of the run.
    bs.counters["builds_per_step"] = static_cast<double>(field.list().builds()) / static_cast<double>(bs.iterations());
    if (const VerletList* c = field.list().candidates())
      bs.counters["candidate_builds_per_step"] = static_cast<double>(c->builds()) / static_cast<double>(bs.iterations());
    std::size_t listed = 0;
    for (std::size_t i = 0; i < n; ++i) listed += field.list().partners(i).size();
    bs.counters["partners_per_rod"] = static_cast<double>(listed) / static_cast<double>(n);
  }
}

void BM_BdFreeRods(benchmark::State& bs) { run_steps(bs, false); }
void BM_BdRodsOverlapVolume(benchmark::State& bs) { run_steps(bs, true); }

}  // namespace

BENCHMARK(BM_BdFreeRods)
    ->Args({1760, 1, 0})
    ->Args({1760, 2, 0})
    ->Args({440, 1, 0})
    ->Args({7040, 1, 0})
    ->UseRealTime()
    ->Apply([](benchmark::internal::Benchmark* b) { bench::min_time_or_fixed_iterations(b, 1.0); });

BENCHMARK(BM_BdRodsOverlapVolume)
    ->Args({1760, 1, 0})
    ->Args({1760, 2, 0})
    ->Args({440, 1, 440})
    ->Args({1320, 1, 0})
    ->Args({3520, 1, 0})
    ->Args({7040, 1, 0})
    ->UseRealTime()
    ->Unit(benchmark::kMillisecond)
    ->Apply([](benchmark::internal::Benchmark* b) { bench::min_time_or_fixed_iterations(b, 2.0); });

BENCHMARK_MAIN();
