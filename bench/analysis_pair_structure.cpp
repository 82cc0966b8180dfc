// Pair search of the analysis stages: g(r), g_∥, g_⊥ of anisodyn-structure (PairStructureAnalysis)
// and the cluster pair search (close_pairs) on uniform random configurations, one frame per
// iteration. Counter: frames/s.
//   - BM_PairStructure/N/r_max: N particles in a cubic box at the number density of the
//     er_switching study (1500 cubes in l = 42.17 σ, ρ ≈ 0.02 σ⁻³), field reference (g_∥ and g_⊥
//     too, as the study's structure stages). r_max = 0 is the stage's default, half the box edge,
//     where every pair within L/2 must be counted whatever the search; r_max = 5 is a first-shells
//     histogram, where a cell list prunes.
//   - BM_PairStructureTracerLC: the dmc_tracer_LC study's isotropic W* = 1 frame, 2000 boards and
//     200 spheres in l = 54.29 T, pairs board–board, hs–hs and board–hs, default r_max.
//   - BM_ClosePairs/N: every pair within the dipolar bond cut-off σ(γ/|βu_max|)^{1/3} = 1.59 σ
//     (γ = 13, βu_max = −3.2) at the same density, as anisodyn-clusters (dipolar mode) needs it.
#include <benchmark/benchmark.h>

#include <cmath>
#include <random>
#include <vector>

#include "anisodyn/analysis/pair_search.hpp"
#include "anisodyn/analysis/pair_structure.hpp"

using namespace anisodyn;
using namespace anisodyn::analysis;

namespace {

constexpr double kStudyDensity = 1500.0 / (42.17 * 42.17 * 42.17);

double edge_for(std::size_t n, double density) { return std::cbrt(static_cast<double>(n) / density); }

std::vector<Vec3> uniform_positions(std::size_t n, double edge, unsigned seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(0.0, edge);
  std::vector<Vec3> r(n);
  for (auto& p : r) p = Vec3(u(rng), u(rng), u(rng));
  return r;
}

/// One frame of uniformly placed particles; species[i] indexes `table`.
Trajectory one_frame(const std::vector<Vec3>& r, double edge, const std::vector<int>& species, const SpeciesTable& table) {
  Trajectory t;
  t.path = "memory";
  t.frames = 1;
  t.particles = r.size();
  t.time = {0.0};
  t.step = {0};
  t.box = {edge, edge, edge};
  for (const Vec3& p : r) t.position.insert(t.position.end(), {p.x(), p.y(), p.z()});
  t.orientation.assign(4 * r.size(), 0.0);
  for (std::size_t i = 0; i < r.size(); ++i) t.orientation[4 * i] = 1.0;
  t.species = species;
  for (std::size_t i = 0; i < r.size(); ++i) t.id.push_back(static_cast<std::int64_t>(i));
  t.species_table = table;
  return t;
}

void run_structure(benchmark::State& state, const Trajectory& t, const PairStructureSettings& s) {
  for (auto _ : state) {
    PairStructureAnalysis a(s, 2);  // two replicas: no frame blocks
    a.accumulate(t);
    benchmark::DoNotOptimize(a.compute());
  }
  state.counters["frames/s"] = benchmark::Counter(static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
}

void BM_PairStructure(benchmark::State& state) {
  const std::size_t n = static_cast<std::size_t>(state.range(0));
  const double edge = edge_for(n, kStudyDensity);
  const SpeciesTable table{Species{"cube", Shape::cuboid(1, 1, 1), 1.0, Vec3::Ones(), Vec3::Ones()}};
  const Trajectory t = one_frame(uniform_positions(n, edge, 7), edge, std::vector<int>(n, 0), table);
  PairStructureSettings s;
  s.reference = PairReference::Field;
  s.r_max = static_cast<double>(state.range(1));
  run_structure(state, t, s);
  state.counters["box_edge"] = edge;
}
BENCHMARK(BM_PairStructure)
    ->Args({1500, 0})->Args({1500, 5})->Args({10000, 0})->Args({10000, 5})
    ->Unit(benchmark::kMillisecond)->MinTime(2.0);

void BM_PairStructureTracerLC(benchmark::State& state) {
  const std::size_t boards = 2000, spheres = 200;
  const double edge = 54.29;
  const SpeciesTable table{Species{"board", Shape::cuboid(1, 1, 12), 1.0, Vec3::Ones(), Vec3::Ones()},
                           Species{"hs", Shape::sphere(0.1), 1.0, Vec3::Ones(), Vec3::Ones()}};
  std::vector<int> species(boards + spheres, 0);
  for (std::size_t i = boards; i < species.size(); ++i) species[i] = 1;
  const Trajectory t = one_frame(uniform_positions(boards + spheres, edge, 11), edge, species, table);
  PairStructureSettings s;
  s.reference = PairReference::Field;
  s.dr = 0.1;
  s.pairs = {{"board", "board"}, {"hs", "hs"}, {"board", "hs"}};
  run_structure(state, t, s);
}
BENCHMARK(BM_PairStructureTracerLC)->Unit(benchmark::kMillisecond)->MinTime(2.0);

void BM_ClosePairs(benchmark::State& state) {
  const std::size_t n = static_cast<std::size_t>(state.range(0));
  const double edge = edge_for(n, kStudyDensity);
  const std::vector<Vec3> r = uniform_positions(n, edge, 5);
  const Box box(Vec3::Constant(edge));
  const double cutoff = std::cbrt(13.0 / 3.2);
  for (auto _ : state) benchmark::DoNotOptimize(close_pairs(r, box, cutoff));
  state.counters["frames/s"] = benchmark::Counter(static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_ClosePairs)->Arg(1500)->Arg(10000)->Unit(benchmark::kMicrosecond)->MinTime(2.0);

}  // namespace

BENCHMARK_MAIN();
