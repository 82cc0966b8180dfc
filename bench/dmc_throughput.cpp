// Whole-run DMC throughput: single-thread trial moves per second (time steps fixed; balancing and
// output are not part of the timed loop). The three reference systems of issue 3:
//   (a) 1000 boards 12×3.46×1 at φ = 0.20 plus one pulled tracer (d = 1, Pe = 1, δt_s = 10⁻²);
//   (b) 2000 boards 12×8×1 at η = 0.34 (aligned start, N_U⁻), δt = 10⁻²;
//   (c) 1500 dipolar cubes at η = 0.02, field on (γ = 13, Ewald at relative accuracy 10⁻⁵), δt = 10⁻³;
// the hard-sphere validation system (manifests/validation/dmc_hs_eta0.30.json):
//   (d) 1000 hard spheres d = 1 at η = 0.30, δt = 10⁻⁴ (and 10⁻²);
// and the board + small-sphere mixture of study A3 (spec 60 §A3), spheres as reference:
//   (e) 2000 boards 12×1×1 + 200 spheres d = 0.1 in the pure-board box of η = 0.15 (isotropic,
//       54.29 T) and of η = 0.34 (aligned start, N_U⁺, 41.33 T), δt = 10⁻² for both species
//       (the balanced board step is 1.04×10⁻² at η = 0.15: docs/validation.md).
// and issue 18's MC systems (a)–(d) run as DMC (BM_DmcMcSystems).
// The board D tensors of (a) and (e) are the bead-model values of manifests/data/boards_L12_bead_model.species.json
// (anisodyn-hydro); (b) and (c) use the published values (spec 10 §8); spheres use Stokes–Einstein.
#include <benchmark/benchmark.h>

#include <map>

#include "anisodyn/dmc/dmc_engine.hpp"
#include "anisodyn/system/order.hpp"
#include "support/prepared_state.hpp"
#include "support/timing.hpp"

using namespace anisodyn;

namespace {

void run_cycles(benchmark::State& bs, State state, const std::vector<double>& dt, const std::function<void(DmcEngine&)>& setup) {
  DmcEngine e(state, RngState{17, 0, 0, 4}, DmcMoveOptions{});
  e.set_time_steps(dt);
  setup(e);
  std::int64_t trials = 0, accepted = 0;
  const SkinList& lists = e.overlap().skin_lists();
  const std::int64_t resets_before = lists.references_reset();
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
  // How the skin lists serve (HardOverlap::use_skin_lists): re-references per trial and partners per list.
  if (lists.any()) {
    bs.counters["skin_resets_per_trial"] = static_cast<double>(lists.references_reset() - resets_before) / static_cast<double>(trials);
    double partners = 0.0, bodies = 0.0;
    for (std::size_t i = 0; i < state.particles.size(); ++i)
      if (lists.has_reference(static_cast<std::int32_t>(i))) {
        partners += static_cast<double>(lists.neighbors(static_cast<std::int32_t>(i)).size());
        bodies += 1.0;
      }
    bs.counters["listed_partners"] = partners / bodies;
  }
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

// 1000 hard spheres at η = 0.30: the system and time steps of the DMC hard-sphere validation.
void BM_DmcHardSpheres1000(benchmark::State& bs) {
  static const State prepared = bench::cached_melted_lattice(
      "spheres_N1000_eta0.30", Species{"hs", Shape::sphere(1.0), 1.0, Vec3::Constant(1.0 / (3.0 * M_PI)), Vec3::Zero()}, 1000, 0.30, 8000);
  run_cycles(bs, prepared, {static_cast<double>(bs.range(0)) * 1e-6}, [](DmcEngine&) {});
}

// Study A3's mixture. W* = 1 board D from boards_L12_bead_model.species.json (entry board_W1).
const Species kBoardW1{"board", Shape::cuboid(1.0, 1.0, 12.0), 1.0, Vec3(0.0203767, 0.0203767, 0.0285088),
                       Vec3(9.44021e-4, 9.44021e-4, 1.62628e-2)};
const Species kSphere01{"hs", Shape::sphere(0.1), 1.0, Vec3::Constant(1.0 / (3.0 * M_PI * 0.1)), Vec3::Zero()};

State a3_mixture(double eta, std::int64_t melt_cycles) {
  const std::string tag = eta < 0.2 ? "0.15" : "0.34";
  State s = bench::cached_mixture("boards_12x1x1_N2000_spheres_d0.1_N200_eta" + tag, "cuboids_12x1x1_N2000_eta" + tag,
                                  kBoardW1, 2000, eta, melt_cycles, kSphere01, 200, 2000);
  s.species[0].D_trans = kBoardW1.D_trans;  // whatever the cache holds, time with these tensors
  s.species[0].D_rot = kBoardW1.D_rot;
  s.species[1].D_trans = kSphere01.D_trans;
  return s;
}

void report_board_order(benchmark::State& bs, const State& s) {
  bs.counters["U_L"] = body_axis_order(s, 0)[2].order;
}

// The same boards without the spheres: what the mixture costs on top of its boards.
void BM_DmcBoardsA3Isotropic(benchmark::State& bs) {
  static const State prepared = [] {
    State s = a3_mixture(0.15, 30000);
    while (s.particles.size() > 2000) s.particles.pop_back();  // the spheres were appended last
    s.species.pop_back();
    return s;
  }();
  run_cycles(bs, prepared, {1e-2}, [](DmcEngine&) {});
  report_board_order(bs, prepared);
}

void BM_DmcMixtureA3Isotropic(benchmark::State& bs) {
  static const State prepared = a3_mixture(0.15, 30000);
  run_cycles(bs, prepared, {1e-2, 1e-2}, [](DmcEngine&) {});
  report_board_order(bs, prepared);
}

void BM_DmcMixtureA3Nematic(benchmark::State& bs) {
  static const State prepared = a3_mixture(0.34, 5000);
  run_cycles(bs, prepared, {1e-2, 1e-2}, [](DmcEngine&) {});
  report_board_order(bs, prepared);
}

// Issue 18's MC systems (bench/mc_throughput.cpp, same cached states) as DMC: fixed small moves
// from the species' D tensors at δt = 10⁻² (boards) or 10⁻³ (spheres), acceptance > 0.9.
//   0: (a) 2000 boards 12×3.46×1, η = 0.20;  1: (b) 4000 spheres, η = 0.40;
//   2: (c) 2000 boards 12×1×1, η = 0.34;     3: (d) 2000 boards 12×8×1, η = 0.34 (quick-compressed).
void BM_DmcMcSystems(benchmark::State& bs) {
  static std::map<std::int64_t, State> prepared;
  const std::int64_t k = bs.range(0);
  if (!prepared.count(k)) {
    const Species board_a{"board", Shape::cuboid(1.0, 3.4641, 12.0), 1.0, Vec3(0.01447, 0.01676, 0.020117), Vec3(6.1655e-4, 5.5102e-4, 2.7965e-3)};
    const Species spheres{"hs", Shape::sphere(1.0), 1.0, Vec3::Constant(1.0 / (3.0 * M_PI)), Vec3::Zero()};
    const Species wide{"board", Shape::cuboid(1.0, 8.0, 12.0), 1.0, Vec3(9.4e-3, 1.4e-2, 1.5e-2), Vec3(3.5e-4, 3.6e-4, 6.3e-4)};
    const Species& sp = k == 0 ? board_a : k == 1 ? spheres : k == 2 ? kBoardW1 : wide;
    State s = k == 0   ? bench::cached_melted_lattice("cuboids_12x3.46x1_N2000_eta0.20", sp, 2000, 0.20, 20000)
              : k == 1 ? bench::cached_melted_lattice("spheres_N4000_eta0.40", sp, 4000, 0.40, 3000)
              : k == 2 ? bench::cached_melted_lattice("cuboids_12x1x1_N2000_eta0.34", sp, 2000, 0.34, 5000)
                       : bench::cached_compressed_lattice("cuboids_12x8x1_N2000_eta0.34_compressed", sp, 2000, 0.05, 0.34, 5000);
    // Whatever the cache holds (the MC benchmark may have written it), time with these tensors.
    s.species[0].D_trans = sp.D_trans;
    s.species[0].D_rot = sp.D_rot;
    prepared.emplace(k, std::move(s));
  }
  run_cycles(bs, prepared.at(k), {k == 1 ? 1e-3 : 1e-2}, [](DmcEngine&) {});
}

void three_seconds(benchmark::internal::Benchmark* b) { bench::min_time_or_fixed_iterations(b, 3.0); }

}  // namespace

BENCHMARK(BM_DmcBoards1000WithTracer)->Unit(benchmark::kMillisecond)->Apply(three_seconds);
BENCHMARK(BM_DmcBoards2000Nematic)->Unit(benchmark::kMillisecond)->Apply(three_seconds);
BENCHMARK(BM_DmcDipolarCubes1500)->Unit(benchmark::kMillisecond)->Apply(three_seconds);
BENCHMARK(BM_DmcHardSpheres1000)->Arg(100)->Arg(10000)->Unit(benchmark::kMillisecond)->Apply(three_seconds);  // δt in 10⁻⁶ τ
BENCHMARK(BM_DmcBoardsA3Isotropic)->Unit(benchmark::kMillisecond)->Apply(three_seconds);
BENCHMARK(BM_DmcMixtureA3Isotropic)->Unit(benchmark::kMillisecond)->Apply(three_seconds);
BENCHMARK(BM_DmcMixtureA3Nematic)->Unit(benchmark::kMillisecond)->Apply(three_seconds);
BENCHMARK(BM_DmcMcSystems)->DenseRange(0, 3)->Unit(benchmark::kMillisecond)->Apply(three_seconds);
BENCHMARK_MAIN();
