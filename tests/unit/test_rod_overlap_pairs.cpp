// RodOverlapPairs through PairForceField (the BD rod forces): per-rod forces, torques and the
// energy equal an O(N²) sum of the kernel over minimum-image pairs; spheres in the same state get
// nothing; 1 and 2 threads give the same bits.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "anisodyn/core/quaternion.hpp"
#include "anisodyn/core/rng.hpp"
#include "anisodyn/interactions/pair_force_field.hpp"
#include "anisodyn/interactions/rod_overlap_pairs.hpp"
#include "field_forces.hpp"
#include "thread_count.hpp"

using namespace anisodyn;

namespace {
/// 300 rods L = 5, D = 0.5 and 20 spheres in a box of 12: dense enough for many overlapping pairs.
State rods_and_spheres() {
  State s;
  s.species = {Species{"rod", Shape::spherocylinder(5.0, 0.5), 1.0, {}, {}}, Species{"ball", Shape::sphere(0.5), 1.0, {}, {}}};
  s.box = Box(Vec3::Constant(12.0));
  Rng rng(21, 0);
  for (int i = 0; i < 320; ++i)
    s.particles.add(i < 300 ? 0 : 1, Vec3(rng.uniform(0, 12), rng.uniform(0, 12), rng.uniform(0, 12)),
                    uniform_quaternion(rng.uniform(), rng.uniform(), rng.uniform()), i);
  return s;
}

RodOverlapPairs evaluator() {
  OverlapVolumeSettings ov;
  ov.length = 5.0;
  ov.diameter = 0.5;
  ov.hardness = OverlapVolume::hardness_for(0.5, 1.0);
  return RodOverlapPairs{OverlapVolume(ov), 0, {}, {}};
}

BodyForces field_forces(const State& s) {
  const RodOverlapPairs e = evaluator();
  PairForceField<RodOverlapPairs> field(e, e.segment_cutoffs(2), 2, 0.25, e.half_lengths(2));
  return testing_support::forces_of(field, s);
}
}  // namespace

TEST(RodOverlapPairs, ForceFieldEqualsTheAllPairsSumOfTheKernel) {
  const State s = rods_and_spheres();
  const BodyForces got = field_forces(s);
  const OverlapVolume& pot = evaluator().potential;
  std::vector<Vec3> force(s.particles.size(), Vec3::Zero()), torque(s.particles.size(), Vec3::Zero());
  double energy = 0.0;
  int interacting = 0;
  for (std::size_t i = 0; i < 300; ++i)
    for (std::size_t j = 0; j < 300; ++j) {
      if (i == j) continue;
      const Vec3 d = s.box.min_image(s.particles.position(j) - s.particles.position(i));
      const RodPairTerm t = pot(d, s.particles.orientation(i) * Vec3::UnitZ(), s.particles.orientation(j) * Vec3::UnitZ());
      if (!t.interacts) continue;
      force[i] += t.force;
      torque[i] += t.torque;
      energy += 0.5 * t.energy;
      interacting += i < j;
    }
  EXPECT_GT(interacting, 200);
  double scale = 0.0;
  for (const Vec3& f : force) scale = std::max(scale, f.norm());
  for (std::size_t i = 0; i < s.particles.size(); ++i) {
    EXPECT_LT((got.force[i] - force[i]).norm(), 1e-12 * scale) << i;
    EXPECT_LT((got.torque[i] - torque[i]).norm(), 1e-12 * scale * 5.0) << i;
  }
  for (std::size_t i = 300; i < 320; ++i) EXPECT_EQ(got.force[i], Vec3::Zero()) << "sphere " << i;
  EXPECT_NEAR(got.energy, energy, 1e-12 * energy);
}

TEST(RodOverlapPairs, SameBitsWithOneAndTwoThreads) {
  const State s = rods_and_spheres();
  const auto forces = [&] { return field_forces(s); };
  const BodyForces one = testing_support::with_threads(1, forces);
  const BodyForces two = testing_support::with_threads(2, forces);
  EXPECT_EQ(one.force, two.force);
  EXPECT_EQ(one.torque, two.torque);
  EXPECT_EQ(one.energy, two.energy);
}
