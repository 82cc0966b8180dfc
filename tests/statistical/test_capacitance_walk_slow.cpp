// The walk-on-spheres capacitance solver on the cube to 10⁻⁴: C = 0.6606782 edge (Hwang & Mascagni,
// J. Appl. Phys. 95, 3798 (2004)). Asserted: |C − 0.6606782| ≤ 4 SE with SE ≤ 2.5·10⁻⁵ C, so that
// the test holds C to 10⁻⁴ relative, and the ε-shell bias bound (10⁻⁶ C) below the SE. Slow: half a
// minute on two cores (3 million walks; control variates at depth 0.2 cut the SE fifteenfold
// against plain walk on spheres, which would need about 500 million walks).
#include <gtest/gtest.h>

#include <cstdio>

#include "capacitance_bodies.hpp"

using namespace anisodyn;
using namespace anisodyn::testing_support;

TEST(CapacitanceWalkSlow, CubeMatchesHwangMascagniToOnePartInTenThousand) {
  constexpr double kCube = 0.6606782, kSigmas = 4.0, kMaxRelativeSE = 2.5e-5;
  const CuboidBody cube(Vec3::Ones());
  WalkOptions o;
  o.walks = 3'000'000;
  o.pilot_walks = 100'000;
  o.seed = 2004;
  const auto c = walk_on_spheres_capacitance(cube, launch_for(cube), cuboid_charges(cube, 0.2), o);
  std::printf("cube: C = %.7f ± %.7f (%+.2f SE from %.7f; relative SE %.2e); plain %.6f ± %.6f; bias ≤ %.1e C; %llu walks\n",
              c.value, c.standard_error, (c.value - kCube) / c.standard_error, kCube, c.standard_error / kCube, c.plain_value,
              c.plain_standard_error, c.bias_bound, static_cast<unsigned long long>(c.walks));
  EXPECT_LE(std::abs(c.value - kCube), kSigmas * c.standard_error);
  EXPECT_LE(c.standard_error, kMaxRelativeSE * kCube);
  EXPECT_LE(c.bias_bound * kCube, c.standard_error);
  EXPECT_LE(std::abs(c.plain_value - kCube), kSigmas * c.plain_standard_error);
}
