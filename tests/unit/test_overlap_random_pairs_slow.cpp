// Overlap kernels against the independent long-double references on random pairs, about half of
// them within 1e-9..1e-2 (relative) of contact. Acceptance run (label slow): 10^7 random pairs per shape pair.
// Sampling and checks: tests/support/overlap_sampling.hpp; references: tests/support/reference_overlap.hpp.
#include <gtest/gtest.h>

#include <cstdint>

#include "overlap_sampling.hpp"

using namespace anisodyn::testing_support;

namespace {
constexpr std::int64_t kPairs = 10'000'000;
constexpr std::uint64_t kSeed = 2;
}  // namespace

TEST(OverlapRandomPairs, SphereSphere) { EXPECT_TRUE(random_pairs_agree(PairFamily::SphereSphere, kPairs, kSeed)); }
TEST(OverlapRandomPairs, CuboidSphere) { EXPECT_TRUE(random_pairs_agree(PairFamily::CuboidSphere, kPairs, kSeed)); }
TEST(OverlapRandomPairs, CuboidCuboid) { EXPECT_TRUE(random_pairs_agree(PairFamily::CuboidCuboid, kPairs, kSeed)); }
TEST(OverlapRandomPairs, SpherocylinderSpherocylinder) { EXPECT_TRUE(random_pairs_agree(PairFamily::SpherocylinderSpherocylinder, kPairs, kSeed)); }
TEST(OverlapRandomPairs, SpherocylinderSphere) { EXPECT_TRUE(random_pairs_agree(PairFamily::SpherocylinderSphere, kPairs, kSeed)); }
