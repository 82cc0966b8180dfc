// Overlap kernels against the independent long-double references on random pairs, about half of
// them within 1e-9..1e-2 (relative) of contact. Acceptance run (label slow): 10^7 random pairs per shape pair.
// Sampling: tests/support/overlap_sampling.hpp; references: tests/support/reference_overlap.hpp.
#include <gtest/gtest.h>

#include <cstdint>

#include "overlap_sampling.hpp"

using namespace anisodyn::testing_support;

namespace {

constexpr std::int64_t kPairs = 10'000'000;
constexpr std::uint64_t kSeed = 2;

void check_family(PairFamily family) {
  const RandomPairStats st = run_random_pairs(family, kPairs, kSeed);
  EXPECT_EQ(st.pairs, kPairs);
  EXPECT_EQ(st.disagreements, 0) << family_name(family);
  EXPECT_EQ(st.dispatcher_mismatches, 0) << family_name(family);
  // Indeterminate pairs (within the reference band of contact) are counted, never dropped silently.
  EXPECT_LT(double(st.indeterminate), 1e-4 * double(kPairs)) << family_name(family);
  // The sample must really probe both verdicts and the contact region.
  const double f_overlap = double(st.overlapping) / double(st.pairs);
  const double f_near = double(st.near_contact) / double(st.pairs);
  EXPECT_GT(f_overlap, 0.2);
  EXPECT_LT(f_overlap, 0.8);
  EXPECT_NEAR(f_near, 0.5, 0.01);
  if (family == PairFamily::CuboidSphere) {
    EXPECT_LT(st.max_dmin2_error, 1e-13);
  }
}

}  // namespace

TEST(OverlapRandomPairs, SphereSphere) { check_family(PairFamily::SphereSphere); }
TEST(OverlapRandomPairs, CuboidSphere) { check_family(PairFamily::CuboidSphere); }
TEST(OverlapRandomPairs, CuboidCuboid) { check_family(PairFamily::CuboidCuboid); }
TEST(OverlapRandomPairs, SpherocylinderSpherocylinder) { check_family(PairFamily::SpherocylinderSpherocylinder); }
TEST(OverlapRandomPairs, SpherocylinderSphere) { check_family(PairFamily::SpherocylinderSphere); }
