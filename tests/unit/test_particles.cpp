// Particles::assign_subset, the copy a domain sweep makes of each slab every cycle: every array
// the subset carries is the source's at the chosen indices, in their order; a target that carries
// velocities gets the new particles at rest; a shorter subset after a longer one leaves no tail.
#include <gtest/gtest.h>

#include "anisodyn/system/particles.hpp"

using namespace anisodyn;

namespace {

Particles numbered(std::size_t n) {
  Particles p;
  for (std::size_t i = 0; i < n; ++i) {
    const double a = static_cast<double>(i);
    p.add(static_cast<int>(i % 3), Vec3(a, 10 + a, 20 + a), Quat(1 + a, 2 + a, 3 + a, 4 + a).normalized(), 100 + static_cast<std::int64_t>(i));
    p.set_image(i, Int3(static_cast<int>(i), -static_cast<int>(i), 2 * static_cast<int>(i)));
  }
  return p;
}

}  // namespace

TEST(Particles, AssignSubsetCopiesEveryArrayAtTheChosenIndicesInOrder) {
  const Particles from = numbered(7);
  Particles to = numbered(2);  // stale content that must not survive
  const std::vector<std::int32_t> pick{5, 0, 3, 6};
  to.assign_subset(from, pick);
  ASSERT_EQ(to.size(), pick.size());
  for (std::size_t k = 0; k < pick.size(); ++k) {
    const auto i = static_cast<std::size_t>(pick[k]);
    EXPECT_EQ(to.position(k), from.position(i)) << k;
    EXPECT_EQ(to.image(k), from.image(i)) << k;
    EXPECT_EQ(to.orientation(k).coeffs(), from.orientation(i).coeffs()) << k;
    EXPECT_EQ(to.species[k], from.species[i]) << k;
    EXPECT_EQ(to.id[k], from.id[i]) << k;
  }
  to.assign_subset(from, {2});
  ASSERT_EQ(to.size(), 1u);
  for (const auto* v : {&to.x, &to.y, &to.z, &to.qw, &to.qx, &to.qy, &to.qz}) EXPECT_EQ(v->size(), 1u);
  for (const auto* v : {&to.ix, &to.iy, &to.iz, &to.species}) EXPECT_EQ(v->size(), 1u);
  EXPECT_EQ(to.id.size(), 1u);
  EXPECT_EQ(to.id[0], 102);
}

TEST(Particles, AssignSubsetLeavesCarriedVelocitiesAtRest) {
  const Particles from = numbered(4);
  Particles to;
  to.carry_velocities();
  to.carry_angular_momenta();
  to.add(0, Vec3::Zero(), Quat::Identity(), 0);
  to.set_velocity(0, Vec3(1, 2, 3));
  to.set_angular_momentum(0, Vec3(4, 5, 6));
  to.assign_subset(from, {1, 2});
  ASSERT_EQ(to.vx.size(), 2u);
  ASSERT_EQ(to.lx.size(), 2u);
  for (std::size_t k = 0; k < 2; ++k) {
    EXPECT_EQ(to.velocity(k), Vec3::Zero());
    EXPECT_EQ(to.angular_momentum(k), Vec3::Zero());
  }
}
