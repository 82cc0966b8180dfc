// Hard spheres, N = 512, NPT at βPσ³ = 2, 5, 8: the mean packing fraction must agree with the
// Carnahan–Starling equation of state within k = 4 standard errors. The standard error is the
// larger of the blocking and autocorrelation-time estimates (block_average), and it must be below
// 0.25% of η, so that 4 SE stay within the 1% the comparison is meant to resolve (Carnahan–Starling
// itself is good to ~0.1% in η here).
// The run is sized for that: the volume of a 512-sphere NPT run decorrelates slowly (integrated
// autocorrelation time ≈ 3000–4000 cycles), and σ_η/η = 1/√(N ∂βP/∂ρ) = 1.5%, 0.9%, 0.7% from the
// Carnahan–Starling compressibility, so 2×10⁵ production cycles give SE ≈ σ_η √(2τ/n) ≈ 0.15–0.25%
// of η; the blocks then reach ~12 000 cycles, past the plateau of the blocking analysis.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "anisodyn/core/statistics.hpp"
#include "anisodyn/mc/mc_engine.hpp"

using namespace anisodyn;

namespace {

double carnahan_starling_pressure(double eta) {
  return 6.0 * eta / M_PI * (1 + eta + eta * eta - eta * eta * eta) / std::pow(1 - eta, 3);
}

double carnahan_starling_eta(double beta_p) {
  double lo = 0.0, hi = 0.7;
  for (int k = 0; k < 200; ++k) {
    const double mid = 0.5 * (lo + hi);
    (carnahan_starling_pressure(mid) < beta_p ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

State simple_cubic(int side, double eta) {
  State s;
  s.species.push_back(Species{"hs", Shape::sphere(1.0), 1.0, Vec3::Zero(), Vec3::Zero()});
  const double a = std::cbrt(M_PI / 6.0 / eta);
  s.box = Box(Vec3::Constant(side * a));
  std::int64_t id = 0;
  for (int i = 0; i < side; ++i)
    for (int j = 0; j < side; ++j)
      for (int k = 0; k < side; ++k) s.particles.add(0, a * Vec3(i + 0.5, j + 0.5, k + 0.5), Quat::Identity(), id++);
  return s;
}

void check_pressure(double beta_p, std::uint64_t seed) {
  const double expected = carnahan_starling_eta(beta_p);
  State s = simple_cubic(8, std::min(0.9 * expected, 0.45));
  McEngine mc(s, RngState{seed, 0, 0, 4});
  mc.set_pressure(beta_p);
  for (int round = 0; round < 200; ++round) {  // equilibrate, tuning to 35% acceptance
    const MoveCounters mark = mc.counters();
    for (int c = 0; c < 50; ++c) mc.cycle();
    mc.tune(0.35, mc.counters().since(mark));
  }
  for (int c = 0; c < 10000; ++c) mc.cycle();  // equilibrate with the final move sizes
  const int sample_every = 10;
  std::vector<double> eta;
  for (int c = 0; c < 200000; ++c) {
    mc.cycle();
    if (c % sample_every == 0) eta.push_back(s.packing_fraction());
  }
  const MeanError m = block_average(eta);
  for (int q = 0; q < 4; ++q) {
    const auto first = eta.begin() + static_cast<std::ptrdiff_t>(q * eta.size() / 4);
    std::printf("  quarter %d: %.5f\n", q, block_average(std::vector<double>(first, first + static_cast<std::ptrdiff_t>(eta.size() / 4))).mean);
  }
  const double k = 4.0, se_bound = 0.0025 * expected;
  std::printf("betaP = %.1f: eta = %.5f +- %.5f (CS %.5f), deviation %+.3f%% (%+.1f standard errors; k = %.0f, SE bound %.5f); "
              "tau_int = %.0f cycles\n",
              beta_p, m.mean, m.error, expected, 100 * (m.mean - expected) / expected, (m.mean - expected) / m.error, k, se_bound,
              sample_every * m.tau_int);
  EXPECT_LT(std::abs(m.mean - expected), k * m.error);
  EXPECT_LT(m.error, se_bound);  // precise enough for the comparison to mean something
  EXPECT_FALSE(mc.overlap().first_overlap().has_value());
}

}  // namespace

TEST(HardSphereEos, CarnahanStarlingAtBetaP2) { check_pressure(2.0, 21); }
TEST(HardSphereEos, CarnahanStarlingAtBetaP5) { check_pressure(5.0, 51); }
TEST(HardSphereEos, CarnahanStarlingAtBetaP8) { check_pressure(8.0, 81); }
