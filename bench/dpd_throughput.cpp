// DPD throughput: particle-steps per second of the Groot–Warren liquid (spec 30 §2: ρ = 3, a = 25,
// γ = 4.5, k_BT = 1, Δt = 0.005, r_c = 1, skin 0.3), as anisodyn-dpd steps it: the DPD pair forces
// (interactions/dpd_pairs.hpp: once per pair, keyed noise), velocity Verlet (RigidBodyNve with
// point bodies) and the per-step kinetic tensor of the observables (core/ordered_sum.hpp, as the runner). N particles in a cubic box at
// ρ = 3 (N = 24000: box 20, the benchmark; 1536: box 8); one and two threads (the results
// are the same bits). The liquid starts from uniform random positions and Maxwell–Boltzmann
// velocities and is relaxed for 200 steps before timing. Arguments: particles, threads.
// bench/peers/lammps.sh builds LAMMPS with DPD-BASIC for the side-by-side run (docs/performance.md).
#include <benchmark/benchmark.h>

#include <cmath>
#include <cstdlib>

#ifdef _OPENMP
#include <omp.h>
#endif

#include "anisodyn/core/ordered_sum.hpp"
#include "anisodyn/core/rng.hpp"
#include "anisodyn/integrate/rigid_body_nve.hpp"
#include "anisodyn/interactions/dpd_pairs.hpp"
#include "support/timing.hpp"

using namespace anisodyn;

namespace {

State liquid(std::size_t n) {
  State s;
  s.species = {Species{"liquid", Shape::sphere(1.0), 1.0, {}, {}}};
  const double edge = std::cbrt(static_cast<double>(n) / 3.0);
  s.box = Box(Vec3::Constant(edge));
  Rng rng(7, 0);
  for (std::size_t i = 0; i < n; ++i)
    s.particles.add(0, Vec3(rng.uniform(0, edge), rng.uniform(0, edge), rng.uniform(0, edge)), Quat::Identity(),
                    static_cast<std::int64_t>(i));
  s.particles.carry_velocities();
  for (std::size_t i = 0; i < n; ++i) s.particles.set_velocity(i, Vec3(rng.normal(), rng.normal(), rng.normal()));
  return s;
}

void BM_DpdLiquid(benchmark::State& bs) {
  const auto n = static_cast<std::size_t>(bs.range(0));
#ifdef _OPENMP
  omp_set_num_threads(static_cast<int>(bs.range(1)));
#endif
  State s = liquid(n);
  const char* skin = std::getenv("ANISODYN_BENCH_DPD_SKIN");  // default 0.3, anisodyn-dpd's and LAMMPS's
  DpdForceField field({25.0, 4.5, 1.0, 1.0}, 0.005, 11, skin ? std::atof(skin) : 0.3);
  RigidBodyNve nve(0.005, {{1.0, Vec3::Zero()}}, [&field](const State& st, BodyForces& out) { field(st, out); });
  Mat3 kinetic = Mat3::Zero();
  auto step = [&] {
    field.set_noise_step(static_cast<std::uint64_t>(s.step) + 1);
    nve.step(s);
    ++s.step;
    kinetic += ordered_sum(n, Mat3::Zero().eval(), [&](std::size_t i) -> Mat3 {  // the runner's kinetic tensor
      const Vec3 v = s.particles.velocity(i);
      return v * v.transpose();
    });
  };
  for (int k = 0; k < 200; ++k) step();
  const auto builds0 = field.list().builds();
  const std::int64_t steps0 = s.step;
  for (auto _ : bs) step();
  benchmark::DoNotOptimize(kinetic);
  const double steps = static_cast<double>(s.step - steps0);
  bs.counters["particle_steps_per_s"] = benchmark::Counter(static_cast<double>(n) * steps, benchmark::Counter::kIsRate);
  bs.counters["builds_per_step"] = static_cast<double>(field.list().builds() - builds0) / steps;
  bs.counters["pairs_per_particle"] = static_cast<double>(field.list().pairs()) / static_cast<double>(n);
  bs.counters["threads"] = static_cast<double>(bs.range(1));
}

}  // namespace

BENCHMARK(BM_DpdLiquid)->Args({24000, 1})->Args({24000, 2})->Args({1536, 1})->UseRealTime()->MinTime(3.0)->Unit(benchmark::kMillisecond);
BENCHMARK_MAIN();
