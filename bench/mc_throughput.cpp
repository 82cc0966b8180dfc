// Whole-run MC throughput: single-thread trial moves per second, with move sizes tuned to 35%
// acceptance (tuning is then frozen while timing), on the reference systems of issue 2 and the
// dense elongated ones of issue 18:
//   cuboids — N = 2000 boards 12×3.46×1 at η = 0.20 (isotropic);
//   spheres — N = 4000 hard spheres at η = 0.40;
//   rods nematic — N = 2000 boards 12×1×1 at η = 0.34 (from an aligned lattice: nematic);
//   wide boards nematic — N = 2000 boards 12×8×1 at η = 0.34.
// The states (lattice at the target density melted by NVT) are prepared once and cached in $ANISODYN_BENCH_CACHE
// (default: ./bench-cache) so repeated runs time only the production loop.
#include <benchmark/benchmark.h>

#include "anisodyn/system/order.hpp"
#include "support/prepared_state.hpp"

using namespace anisodyn;

namespace {

struct Prepared {
  State state;
  MoveSizes moves;
};

Prepared prepare(const std::string& name, const Species& sp, std::size_t n, double eta, std::int64_t melt_cycles) {
  Prepared p;
  p.state = bench::cached_melted_lattice(name, sp, n, eta, melt_cycles);
  // Tune to 35% on the cached state (not timed).
  McEngine mc(p.state, RngState{7, 0, 0, 4});
  for (int round = 0; round < 30; ++round) {
    const MoveCounters mark = mc.counters();
    for (int c = 0; c < 20; ++c) mc.cycle();
    mc.tune(0.35, mc.counters().since(mark));
  }
  p.moves = mc.move_sizes();
  return p;
}

void run_cycles(benchmark::State& bs, const Prepared& prepared) {
  State state = prepared.state;
  McEngine mc(state, RngState{11, 0, 0, 4});
  mc.move_sizes() = prepared.moves;
  const MoveCounters start = mc.counters();
  std::int64_t trials = 0;
  for (auto _ : bs) {
    mc.cycle();
    trials += static_cast<std::int64_t>(state.particles.size());
  }
  const MoveCounters w = mc.counters().since(start);
  const double acc = static_cast<double>(w.translate_accepted[0] + w.rotate_accepted[0]) /
                     static_cast<double>(w.translate_tried[0] + w.rotate_tried[0]);
  bs.counters["trials_per_s"] = benchmark::Counter(static_cast<double>(trials), benchmark::Counter::kIsRate);
  bs.counters["acceptance"] = acc;
  bs.counters["eta"] = state.packing_fraction();
}

void BM_McCuboids2000(benchmark::State& bs) {
  static const Prepared p = prepare("cuboids_12x3.46x1_N2000_eta0.20", Species{"board", Shape::cuboid(1.0, 3.4641, 12.0), 1.0, {}, {}}, 2000, 0.20, 20000);
  run_cycles(bs, p);
}
void BM_McSpheres4000(benchmark::State& bs) {
  static const Prepared p = prepare("spheres_N4000_eta0.40", Species{"hs", Shape::sphere(1.0), 1.0, {}, {}}, 4000, 0.40, 3000);
  run_cycles(bs, p);
}

void BM_McRods2000Nematic(benchmark::State& bs) {
  static const Prepared p = prepare("cuboids_12x1x1_N2000_eta0.34", Species{"board", Shape::cuboid(1.0, 1.0, 12.0), 1.0, {}, {}}, 2000, 0.34, 5000);
  run_cycles(bs, p);
  bs.counters["U_L"] = body_axis_order(p.state, 0)[2].order;
}
void BM_McWideBoards2000Nematic(benchmark::State& bs) {
  static const Prepared p = prepare("cuboids_12x8x1_N2000_eta0.34", Species{"board", Shape::cuboid(1.0, 8.0, 12.0), 1.0, {}, {}}, 2000, 0.34, 5000);
  run_cycles(bs, p);
  bs.counters["U_L"] = body_axis_order(p.state, 0)[2].order;
}

}  // namespace

BENCHMARK(BM_McRods2000Nematic)->Unit(benchmark::kMillisecond)->MinTime(2.0);
BENCHMARK(BM_McWideBoards2000Nematic)->Unit(benchmark::kMillisecond)->MinTime(2.0);
BENCHMARK(BM_McCuboids2000)->Unit(benchmark::kMillisecond)->MinTime(2.0);
BENCHMARK(BM_McSpheres4000)->Unit(benchmark::kMillisecond)->MinTime(2.0);
BENCHMARK_MAIN();
