// MSD analysis throughput: R replicas × 500 frames × 2000 particles of Gaussian walks, analysed by
// MsdAnalysis exactly as anisodyn-msd does (bulk read, unwrap, every origin on a 10-per-decade lag
// grid, NGP and jackknife errors). The acceptance case is R = 100 (set
// ANISODYN_BENCH_MSD_REPLICAS=100; the files take 100 × 80 MB); the default is 10 replicas.
// Counter: particle-frames analysed per second. The replica files are written once to
// $ANISODYN_BENCH_TMP (default /tmp/anisodyn-bench-msd) and reused.
#include <benchmark/benchmark.h>

#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

#include "anisodyn/analysis/msd.hpp"
#include "synthetic_trajectory.hpp"

using namespace anisodyn;
using namespace anisodyn::analysis;

namespace {

constexpr std::size_t kParticles = 2000, kFrames = 500;

std::size_t replica_count() {
  const char* r = std::getenv("ANISODYN_BENCH_MSD_REPLICAS");
  return r ? static_cast<std::size_t>(std::atol(r)) : 10;
}

std::vector<std::string> replica_files(std::size_t replicas) {
  const char* base = std::getenv("ANISODYN_BENCH_TMP");
  const std::string dir = std::string(base && *base ? base : "/tmp") + "/anisodyn-bench-msd";
  std::filesystem::create_directories(dir);
  std::vector<std::string> paths;
  for (std::size_t r = 0; r < replicas; ++r) {
    paths.push_back(dir + "/walk" + std::to_string(r) + ".h5");
    if (!std::filesystem::exists(paths.back()))
      anisodyn::testing_support::gaussian_walks(kParticles, anisodyn::testing_support::linear_times(kFrames, 0.01), Vec3(1, 1, 1),
                                                static_cast<unsigned>(r))
          .write(paths.back());
  }
  return paths;
}

void BM_MsdReplicaSet(benchmark::State& state) {
  const auto paths = replica_files(replica_count());
  for (auto _ : state) {
    MsdAnalysis msd(MsdSettings{}, paths.size());
    TrajectoryNeeds needs;
    needs.positions = true;
    for_each_replica(paths, needs, [&](const Trajectory& t, std::size_t) { msd.accumulate(t, -1); });
    benchmark::DoNotOptimize(msd.compute());
  }
  state.counters["replicas"] = static_cast<double>(paths.size());
  state.counters["particle_frames/s"] = benchmark::Counter(static_cast<double>(paths.size() * kParticles * kFrames) * state.iterations(),
                                                           benchmark::Counter::kIsRate);
}
BENCHMARK(BM_MsdReplicaSet)->Unit(benchmark::kSecond)->Iterations(1);

}  // namespace

BENCHMARK_MAIN();
