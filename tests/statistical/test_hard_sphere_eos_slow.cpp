// Hard spheres, N = 512, NPT at βPσ³ = 2, 5, 8: the mean packing fraction (block-averaged
// standard error) must lie within 1% of the Carnahan–Starling equation of state.
// The volume of a 512-sphere NPT run decorrelates slowly (integrated autocorrelation time ≈ 3000
// cycles at βP = 2), so production is 2×10⁵ cycles: blocks then reach ~12 000 cycles, past the
// plateau of the blocking analysis.
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
  std::vector<double> eta;
  for (int c = 0; c < 200000; ++c) {
    mc.cycle();
    if (c % 10 == 0) eta.push_back(s.packing_fraction());
  }
  const MeanError m = block_average(eta);
  for (int q = 0; q < 4; ++q) {
    const auto first = eta.begin() + static_cast<std::ptrdiff_t>(q * eta.size() / 4);
    std::printf("  quarter %d: %.5f\n", q, block_average(std::vector<double>(first, first + static_cast<std::ptrdiff_t>(eta.size() / 4))).mean);
  }
  const double rel = (m.mean - expected) / expected;
  std::printf("betaP = %.1f: eta = %.5f +- %.5f (CS %.5f), deviation %+.3f%% (%.1f standard errors)\n", beta_p, m.mean, m.error,
              expected, 100 * rel, (m.mean - expected) / m.error);
  EXPECT_LT(std::abs(rel), 0.01);
  EXPECT_LT(m.error / expected, 0.0025);  // precise enough for the 1% criterion to mean something
  EXPECT_FALSE(mc.overlap().first_overlap().has_value());
}

}  // namespace

TEST(HardSphereEos, CarnahanStarlingAtBetaP2) { check_pressure(2.0, 21); }
TEST(HardSphereEos, CarnahanStarlingAtBetaP5) { check_pressure(5.0, 51); }
TEST(HardSphereEos, CarnahanStarlingAtBetaP8) { check_pressure(8.0, 81); }
