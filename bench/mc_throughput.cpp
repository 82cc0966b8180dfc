// Whole-run MC throughput: single-thread trial moves per second, with move sizes tuned to 35%
// acceptance (tuning is then frozen while timing), on the reference systems of issue 2 and the
// dense elongated ones of issue 18:
//   cuboids — N = 2000 boards 12×3.46×1 at η = 0.20 (isotropic);
//   spheres — N = 4000 hard spheres at η = 0.40;
//   rods nematic — N = 2000 boards 12×1×1 at η = 0.34 (from an aligned lattice: nematic);
//   rods nematic at N = 8000 and 32000 — the same density and preparation (cost per trial flat in N);
//   rods nematic tiled — the N = 2000 state repeated 2×2×2 and 3×3×3 times (16000 and 54000): the
//     same neighbourhoods at every N, so any growth of the cost per trial is the algorithm's;
//   rods + spheres — the 2000 rods with 200 spheres d = 0.1 (study A3's mixture);
//   wide boards nematic — N = 2000 boards 12×8×1 at η = 0.34, quick-compressed from a dilute lattice;
//   domain sweeps (two-thread preparation) on the first three, with one and two threads.
// The states (lattice at the target density melted by NVT) are prepared once and cached in $ANISODYN_BENCH_CACHE
// (default: ./bench-cache) so repeated runs time only the production loop.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <map>
#include <optional>

#include "anisodyn/system/order.hpp"
#include "support/prepared_state.hpp"
#include "thread_count.hpp"

using namespace anisodyn;
using anisodyn::testing_support::ScopedThreadCount;

namespace {

struct Prepared {
  State state;
  MoveSizes moves;
};

/// Move sizes tuned to 35% acceptance on the prepared state, which the tuning cycles advance (not
/// timed). Given a pressure, the tuning runs NPT from the moves already tuned, so that the volume
/// move is tuned too.
Prepared tuned(Prepared p, std::optional<double> beta_pressure = std::nullopt) {
  McEngine mc(p.state, RngState{7, 0, 0, 4});
  if (beta_pressure) mc.move_sizes() = p.moves;
  mc.set_pressure(beta_pressure);
  for (int round = 0; round < 30; ++round) {
    const MoveCounters mark = mc.counters();
    for (int c = 0; c < 20; ++c) mc.cycle();
    mc.tune(0.35, mc.counters().since(mark));
  }
  p.moves = mc.move_sizes();
  return p;
}

Prepared prepare(const std::string& name, const Species& sp, std::size_t n, double eta, std::int64_t melt_cycles) {
  Prepared p;
  p.state = bench::cached_melted_lattice(name, sp, n, eta, melt_cycles);
  return tuned(std::move(p));
}

std::int64_t particle_trials(const MoveCounters& w) {
  std::int64_t n = 0;
  for (std::size_t s = 0; s < w.translate_tried.size(); ++s) n += w.translate_tried[s] + w.rotate_tried[s];
  return n;
}

/// Trial moves per second of MC cycles on a copy of the prepared state, sequential or by domain
/// sweeps (mc/domain_sweep.hpp).
void run_cycles(benchmark::State& bs, const Prepared& prepared, bool domains = false,
                std::optional<double> beta_pressure = std::nullopt) {
  State state = prepared.state;
  McEngine mc(state, RngState{11, 0, 0, 4});
  mc.move_sizes() = prepared.moves;
  mc.set_domain_sweeps(domains);
  mc.set_pressure(beta_pressure);
  const MoveCounters start = mc.counters();
  // As MC preparation runs them: NVT domain sweeps run a cut's cycles as one batch (McEngine::cycles).
  for (auto _ : bs) mc.cycles(DomainSweep::kCyclesPerCut);
  const MoveCounters w = mc.counters().since(start);
  const double acc = static_cast<double>(w.translate_accepted[0] + w.rotate_accepted[0]) /
                     static_cast<double>(w.translate_tried[0] + w.rotate_tried[0]);
  bs.counters["trials_per_s"] = benchmark::Counter(static_cast<double>(particle_trials(w)), benchmark::Counter::kIsRate);
  bs.counters["acceptance"] = acc;
  bs.counters["eta"] = state.packing_fraction();
  if (beta_pressure) bs.counters["volume_acceptance"] = MoveCounters::ratio(w.volume_accepted, w.volume_tried);
  if (const DomainSweep* d = mc.domain_sweep(); d && d->layout()) {
    const DomainSweep::Layout& g = *d->layout();
    bs.counters["domains"] = g[0] * g[1] * g[2];
  }
}

const Prepared& cuboids_a() {
  static const Prepared p = prepare("cuboids_12x3.46x1_N2000_eta0.20", Species{"board", Shape::cuboid(1.0, 3.4641, 12.0), 1.0, {}, {}}, 2000, 0.20, 20000);
  return p;
}
void BM_McCuboids2000(benchmark::State& bs) { run_cycles(bs, cuboids_a()); }
const Prepared& spheres_b() {
  static const Prepared p = prepare("spheres_N4000_eta0.40", Species{"hs", Shape::sphere(1.0), 1.0, {}, {}}, 4000, 0.40, 3000);
  return p;
}
void BM_McSpheres4000(benchmark::State& bs) { run_cycles(bs, spheres_b()); }

const Species kRod{"board", Shape::cuboid(1.0, 1.0, 12.0), 1.0, {}, {}};

std::string rods_state_name(std::size_t n) { return "cuboids_12x1x1_N" + std::to_string(n) + "_eta0.34"; }

const Prepared& rods_c() {
  static const Prepared p = prepare(rods_state_name(2000), kRod, 2000, 0.34, 5000);
  return p;
}
void BM_McRods2000Nematic(benchmark::State& bs) {
  run_cycles(bs, rods_c());
  bs.counters["U_L"] = body_axis_order(rods_c().state, 0)[2].order;
}

// Domain sweeps (MC preparation on two threads) on (a), (b) and (c): range(0) = 0 for (a), 1 for
// (b) (4000 spheres: a grid of 4 domains), 2 for (c); range(1) = OpenMP threads. Wall-clock rates.
void BM_McDomainSweeps(benchmark::State& bs) {
  const Prepared& p = bs.range(0) == 0 ? cuboids_a() : bs.range(0) == 1 ? spheres_b() : rods_c();
  const ScopedThreadCount threads(static_cast<int>(bs.range(1)));
  run_cycles(bs, p, true);
}

// NPT cycles, as MC preparation runs them (one volume move per cycle on average, ln V moves of
// ±0.01): (a) at βP = 0.015 and (c) at βP = 0.3, near their states' equilibrium (docs/
// performance.md). range(0) = 0 for (a), 2 for (c); range(1) = OpenMP threads; range(2) = 1 for
// domain sweeps. Wall-clock rates of particle trials (volume moves not counted).
void BM_McNpt(benchmark::State& bs) {
  const bool a = bs.range(0) == 0;
  const double beta_pressure = a ? 0.015 : 0.3;
  // All eight variants start from the same move sizes, tuned once (sequentially) under NPT.
  static std::map<bool, Prepared> prepared;
  if (!prepared.count(a)) prepared.emplace(a, tuned(a ? cuboids_a() : rods_c(), beta_pressure));
  const ScopedThreadCount threads(static_cast<int>(bs.range(1)));
  run_cycles(bs, prepared.at(a), bs.range(2) != 0, beta_pressure);
}

// The same rods at N = 8000 and 32000 (boxes 66 and 104 T): the cost per trial should not grow with N.
// range(1) = 0: the sequential sweep; k > 0: domain sweeps on k OpenMP threads (wall-clock rate
// then), whose slabs each hold about half the configuration.
void BM_McRodsNematicN(benchmark::State& bs) {
  static std::map<std::int64_t, Prepared> prepared;
  const std::int64_t n = bs.range(0);
  if (!prepared.count(n)) prepared.emplace(n, prepare(rods_state_name(static_cast<std::size_t>(n)), kRod, static_cast<std::size_t>(n), 0.34, 5000));
  const Prepared& p = prepared.at(n);
  const auto domain_threads = static_cast<int>(bs.range(1));
  const ScopedThreadCount threads(std::max(domain_threads, 1));
  run_cycles(bs, p, domain_threads > 0);
  bs.counters["U_L"] = body_axis_order(p.state, 0)[2].order;
}

/// `tiles`³ copies of a periodic state side by side: a box `tiles` times as wide with the same
/// neighbourhoods everywhere.
State tiled(const State& one, int tiles) {
  State s;
  s.species = one.species;
  s.box = Box(one.box.edges() * tiles);
  const Particles& p = one.particles;
  std::int64_t id = 0;
  for (int a = 0; a < tiles; ++a)
    for (int b = 0; b < tiles; ++b)
      for (int c = 0; c < tiles; ++c)
        for (std::size_t i = 0; i < p.size(); ++i) {
          const Vec3 shift = one.box.edges().cwiseProduct(Vec3(a, b, c));
          s.particles.add(p.species[i], p.position(i) + shift, p.orientation(i), id++);
        }
  return s;
}

// The rods of (c) tiled: range(0) = tiles per axis (N = 2000 tiles³); range(1) as above (0:
// sequential, k > 0: domain sweeps on k threads, wall-clock rate). The 2000 rods' tuned moves.
void BM_McRodsTiled(benchmark::State& bs) {
  const auto tiles = static_cast<int>(bs.range(0));
  static std::map<int, Prepared> prepared;
  if (!prepared.count(tiles)) prepared.emplace(tiles, Prepared{tiled(rods_c().state, tiles), rods_c().moves});
  const auto domain_threads = static_cast<int>(bs.range(1));
  const ScopedThreadCount threads(std::max(domain_threads, 1));
  run_cycles(bs, prepared.at(tiles), domain_threads > 0);
}

// Study A3's mixture at η = 0.34: the rods of (c) with 200 spheres d = 0.1 inserted (the DMC
// benchmark's state; spheres take their own tuned translation).
void BM_McRodsSpheres2200Nematic(benchmark::State& bs) {
  static const Prepared p = [] {
    Prepared q;
    q.state = bench::cached_mixture("boards_12x1x1_N2000_spheres_d0.1_N200_eta0.34", rods_state_name(2000), kRod, 2000, 0.34, 5000,
                                    Species{"hs", Shape::sphere(0.1), 1.0, {}, {}}, 200, 2000);
    return tuned(std::move(q));
  }();
  run_cycles(bs, p);
  bs.counters["U_L"] = body_axis_order(p.state, 0)[2].order;
}

// Wide boards: placed on a dilute lattice (η = 0.05) and quick-compressed, since their lattice at
// η = 0.34 stacks them face to face and stays jammed under NVT.
void BM_McWideBoards2000Nematic(benchmark::State& bs) {
  static const Prepared p = [] {
    Prepared q;
    const Species sp{"board", Shape::cuboid(1.0, 8.0, 12.0), 1.0, {}, {}};
    q.state = bench::cached_compressed_lattice("cuboids_12x8x1_N2000_eta0.34_compressed", sp, 2000, 0.05, 0.34, 5000);
    return tuned(std::move(q));
  }();
  run_cycles(bs, p);
  bs.counters["U_L"] = body_axis_order(p.state, 0)[2].order;
}

}  // namespace

BENCHMARK(BM_McRods2000Nematic)->Unit(benchmark::kMillisecond)->MinTime(2.0);
BENCHMARK(BM_McDomainSweeps)->ArgsProduct({{0, 1, 2}, {1, 2}})->Unit(benchmark::kMillisecond)->MinTime(2.0)->UseRealTime();
BENCHMARK(BM_McNpt)->ArgsProduct({{0, 2}, {1, 2}, {0, 1}})->Unit(benchmark::kMillisecond)->MinTime(2.0)->UseRealTime();
BENCHMARK(BM_McRodsNematicN)->Args({8000, 0})->Args({32000, 0})->Unit(benchmark::kMillisecond)->MinTime(2.0);
BENCHMARK(BM_McRodsNematicN)->ArgsProduct({{2000, 8000, 32000}, {1, 2}})->Unit(benchmark::kMillisecond)->MinTime(2.0)->UseRealTime();
BENCHMARK(BM_McRodsTiled)->ArgsProduct({{1, 2, 3}, {0, 1, 2}})->Unit(benchmark::kMillisecond)->MinTime(2.0)->UseRealTime();
BENCHMARK(BM_McRodsSpheres2200Nematic)->Unit(benchmark::kMillisecond)->MinTime(2.0);
BENCHMARK(BM_McWideBoards2000Nematic)->Unit(benchmark::kMillisecond)->MinTime(2.0);
BENCHMARK(BM_McCuboids2000)->Unit(benchmark::kMillisecond)->MinTime(2.0);
BENCHMARK(BM_McSpheres4000)->Unit(benchmark::kMillisecond)->MinTime(2.0);
BENCHMARK_MAIN();
