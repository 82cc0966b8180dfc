// Bead-model solve time (docs/performance.md): one shell model → 6×6 resistance.
//   Dense/<beads>       the plain solve: assemble the 3N×3N RPY mobility (lower triangle),
//                       Cholesky-factorise it and solve the six rigid motions; no symmetry used.
//                       The acceptance figure is Dense/2000 on one thread.
//   Mirror/<beads>      the same shell with the mirror-symmetry block split (group of order 8).
//   Series/<W>          a whole anisodyn-hydro species: 5 shells up to 16000 beads and the
//                       extrapolation, for the board 1 × W × 12 (the manifest's setting).
// The shell is a 1 × 3.4641 × 12 board whose bead radius gives about the requested count.
// Run single-threaded (OMP_NUM_THREADS=1) for the one-core figures.
#include <benchmark/benchmark.h>

#include "anisodyn/hydro/diffusion_tensor.hpp"
#include "anisodyn/hydro/rigid_body_resistance.hpp"
#include "anisodyn/hydro/shell_surface.hpp"

using namespace anisodyn;
using namespace anisodyn::hydro;

namespace {

BeadModel board_shell(std::size_t beads) {
  const HydroShape board = HydroShape::cuboid(Vec3(1.0, 3.4641, 12.0));
  double lo = 0.01, hi = 0.5;  // bisection on the bead radius for the requested count
  for (int it = 0; it < 50; ++it) {
    const double mid = 0.5 * (lo + hi);
    if (shell_beads(board, mid).size() >= beads) lo = mid; else hi = mid;
  }
  return {shell_beads(board, lo), lo};
}

void solve(benchmark::State& state, bool use_symmetry) {
  const BeadModel model = board_shell(static_cast<std::size_t>(state.range(0)));
  ResistanceOptions options;
  options.use_symmetry = use_symmetry;
  for (auto _ : state) benchmark::DoNotOptimize(rigid_body_resistance(model, options).resistance(0, 0));
  state.counters["beads"] = static_cast<double>(model.centres.size());
}

void Dense(benchmark::State& state) { solve(state, false); }
void Mirror(benchmark::State& state) { solve(state, true); }

void Series(benchmark::State& state) {
  const HydroShape board = HydroShape::cuboid(Vec3(1.0, static_cast<double>(state.range(0)), 12.0));
  const auto radii = choose_bead_radii(board, {5, 16000, 2.0});
  for (auto _ : state) benchmark::DoNotOptimize(compute_diffusion_tensor(board, radii).diffusion(0, 0));
}

}  // namespace

BENCHMARK(Dense)->Arg(500)->Arg(1000)->Arg(2000)->Unit(benchmark::kSecond)->Iterations(1);
BENCHMARK(Mirror)->Arg(2000)->Arg(8000)->Arg(16000)->Unit(benchmark::kSecond)->Iterations(1);
BENCHMARK(Series)->Arg(1)->Arg(8)->Unit(benchmark::kSecond)->Iterations(1);

BENCHMARK_MAIN();
