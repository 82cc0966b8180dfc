// The pore frame of spec 40 §9 (analysis/pore_frame.hpp): radial, azimuthal and axial steps land on
// x^p, y^p and z^p; and free Brownian motion in the plane (spec 60 D0's synthetic check), binned by
// its distance from the axis, shows the same D along x^p, y^p and z^p in every bin away from β ≈ 0
// (S = 1), within 4 standard errors.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "anisodyn/analysis/lb_analytic_checks.hpp"
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
  // 400 runs of 500 steps started uniformly in a disk of radius 5 about the axis: every bin from β = 0.2
  // with 2000 samples or more has 2D on every pore axis within 4 SE (one lag: independent steps).
  const checks::PoreFrameFree f = checks::pore_frame_free_motion(0.01, 5.0, 400, 500, 23);
  std::printf("%d bins checked, largest pull %.2f\n", f.bins_checked, f.worst_pull);
  EXPECT_LT(f.worst_pull, 4.0);
  EXPECT_GE(f.bins_checked, 5);
}
