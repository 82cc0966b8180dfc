// The pore frame of spec 40 §9 (analysis/pore_frame.hpp): radial, azimuthal and axial steps land on
// x^p, y^p and z^p; and free Brownian motion in the plane (spec 60 D0's synthetic check), binned by
// its distance from the axis, shows the same D along x^p, y^p and z^p in every bin away from β ≈ 0
// (S = 1), within 4 standard errors.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "anisodyn/analysis/pore_frame.hpp"

using namespace anisodyn;
using namespace anisodyn::analysis;

TEST(PoreFrame, StepsLandOnTheirPoreAxes) {
  const Vec3 axis(10, 10, 0);
  const double angle = 0.8, r = 3.0, d = 1e-3;
  const Vec3 start = axis + Vec3(r * std::cos(angle), r * std::sin(angle), 5.0);
  const Vec3 radial(std::cos(angle), std::sin(angle), 0), azimuthal(-std::sin(angle), std::cos(angle), 0);
  const auto step = [&](const Vec3& move) { return pore_frame_displacements(std::vector<Vec3>{start, start + move}, axis)[0]; };
  EXPECT_LT((step(d * radial) - Vec3(d, 0, 0)).norm(), 1e-15);
  EXPECT_LT((step(d * azimuthal) - Vec3(0, d, 0)).norm(), 1e-15);
  EXPECT_LT((step(Vec3(0, 0, d)) - Vec3(0, 0, d)).norm(), 1e-15);
}

TEST(PoreFrame, FreeBrownianMotionHasTheSameDOnEveryPoreAxis) {
  const double D = 0.01, gap = 5.0;
  std::mt19937_64 rng(23);
  std::normal_distribution<double> normal;
  std::uniform_real_distribution<double> uniform(-4.0, 4.0);
  PoreFrameBins bins;
  bins.bin_width = 0.2;
  bins.lags = 1;
  const Vec3 axis(0, 0, 0);
  for (int run = 0; run < 400; ++run) {
    std::vector<Vec3> x{Vec3(uniform(rng), uniform(rng), 0)};
    for (int n = 0; n < 500; ++n) x.push_back(x.back() + std::sqrt(2 * D) * Vec3(normal(rng), normal(rng), normal(rng)));
    accumulate_pore_bins(x, axis, gap, bins);
  }
  int checked = 0;
  for (std::size_t b = 1; b < bins.count.size(); ++b) {  // from beta = 0.2
    const double n = static_cast<double>(bins.count[b]);
    if (n < 2000) continue;
    for (int i = 0; i < 3; ++i) {
      const double mean = bins.sum[b][0][i] / n, var = bins.sum2[b][0][i] / n - mean * mean;
      const double se = std::sqrt(var / n);  // one lag: the sub-trajectories are independent steps
      EXPECT_LT(std::abs(mean - 2 * D), 4 * se) << "bin " << b << " axis " << i;
    }
    ++checked;
  }
  EXPECT_GE(checked, 5);
}
