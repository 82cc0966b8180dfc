// Whole-run DMC throughput: single-thread trial moves per second on the three reference systems
// of issue 3 (time steps fixed; balancing and output are not part of the timed loop):
//   (a) 1000 boards 12×3.46×1 at φ = 0.20 plus one pulled tracer (d = 1, Pe = 1, δt_s = 10⁻²);
//   (b) 2000 boards 12×8×1 at η = 0.34 (aligned start, N_U⁻), δt = 10⁻²;
//   (c) 1500 dipolar cubes at η = 0.02, field on (γ = 13, Ewald at relative accuracy 10⁻⁵), δt = 10⁻³.
// The board D tensors of (a) are the bead-model values of manifests/data/boards_L12_bead_model.species.json
// (anisodyn-hydro); (b) and (c) use the published values (spec 10 §8).
#include <benchmark/benchmark.h>

#include "anisodyn/dmc/dmc_engine.hpp"
#include "support/prepared_state.hpp"

using namespace anisodyn;

namespace {

void run_cycles(benchmark::State& bs, State state, const std::vector<double>& dt, const std::function<void(DmcEngine&)>& setup) {
  DmcEngine e(state, RngState{17, 0, 0, 4}, DmcMoveOptions{});
  e.set_time_steps(dt);
  setup(e);
  std::int64_t trials = 0, accepted = 0;
  for (auto _ : bs) {
    e.cycle();
    for (const auto& c : e.last_cycle()) {
      trials += c.tried;
      accepted += c.accepted;
    }
  }
  bs.counters["trials_per_s"] = benchmark::Counter(static_cast<double>(trials), benchmark::Counter::kIsRate);
  bs.counters["acceptance"] = static_cast<double>(accepted) / static_cast<double>(trials);
  bs.counters["eta"] = state.packing_fraction();
}

void BM_DmcBoards1000WithTracer(benchmark::State& bs) {
  static const State prepared = [] {
    State s = bench::cached_melted_lattice("cuboids_12x3.46x1_N1000_eta0.20",
                                           Species{"board", Shape::cuboid(1.0, 3.4641, 12.0), 1.0, Vec3(0.01447, 0.01676, 0.020117), Vec3(6.1655e-4, 5.5102e-4, 2.7965e-3)},
                                           1000, 0.20, 20000);
    s.species.push_back(Species{"tracer", Shape::sphere(1.0), 1.0, Vec3::Constant(1.0 / (3.0 * M_PI)), Vec3::Zero()});
    PlacementRequest req;
    req.counts = {0, 1};
    req.rules = {OrientationRule{}, OrientationRule{}};
    Rng rng(3, 3);
    insert_randomly(s, req, rng);
    return s;
  }();
  run_cycles(bs, prepared, {1e-2, 1e-2}, [&](DmcEngine& e) {
    PulledTracer t;
    t.particle = static_cast<std::int32_t>(prepared.particles.size() - 1);
    t.beta_force = 2.0;  // Pe = 1, a = 0.5
    e.set_tracer(t);
  });
}

void BM_DmcBoards2000Nematic(benchmark::State& bs) {
  static const State prepared = bench::cached_melted_lattice(
      "cuboids_12x8x1_N2000_eta0.34", Species{"board", Shape::cuboid(1.0, 8.0, 12.0), 1.0, Vec3(9.4e-3, 1.4e-2, 1.5e-2), Vec3(3.5e-4, 3.6e-4, 6.3e-4)},
      2000, 0.34, 5000);
  run_cycles(bs, prepared, {1e-2}, [](DmcEngine&) {});
}

void BM_DmcDipolarCubes1500(benchmark::State& bs) {
  static const State prepared = bench::cached_melted_lattice(
      "cubes_N1500_eta0.02", Species{"cube", Shape::cuboid(1.0, 1.0, 1.0), 1.0, Vec3::Constant(8.35e-2), Vec3::Constant(0.148)}, 1500, 0.02, 2000);
  run_cycles(bs, prepared, {1e-3}, [&](DmcEngine& e) {
    DipoleSettings d;
    d.gamma = 13.0;
    d.species_carries = {1};
    d.ewald = choose_ewald_parameters(prepared.box.edges(), prepared.particles.size(), 1e-5);
    e.set_dipoles(d, Vec3::UnitZ());
    e.set_field_on(true);
  });
}

}  // namespace

BENCHMARK(BM_DmcBoards1000WithTracer)->Unit(benchmark::kMillisecond)->MinTime(3.0);
BENCHMARK(BM_DmcBoards2000Nematic)->Unit(benchmark::kMillisecond)->MinTime(3.0);
BENCHMARK(BM_DmcDipolarCubes1500)->Unit(benchmark::kMillisecond)->MinTime(3.0);
BENCHMARK_MAIN();
