// Point coupling of beads to the LB fluid (lb/point_coupling.hpp) against exact references: the
// trilinear stencil reproduces a linear velocity field and its weights sum to one, bead and fluid
// momentum together are conserved to round-off (noise on), no bead's force depends on the order
// of the beads, and a bead's noise does not depend on which beads couple with it; a bead pulled
// through the deterministic fluid has the mobility 1/ξ plus the fluid's, as Ahlrichs and Dünweg's
// effective friction has it.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include "anisodyn/core/error.hpp"
#include "anisodyn/lb/fluid_checks.hpp"
#include "anisodyn/lb/point_coupling.hpp"

using namespace anisodyn;
using namespace anisodyn::lb;

TEST(PointCoupling, TrilinearInterpolationIsExactForALinearField) {
  LbFluid fluid({8, 9, 10}, LbParameters{});
  const Vec3 u0(0.01, -0.02, 0.005);
  const Mat3 grad = (Mat3() << 1e-3, 2e-4, -5e-4, 3e-4, -1e-3, 7e-4, -2e-4, 6e-4, 4e-4).finished();
  for (int z = 0; z < 10; ++z)
    for (int y = 0; y < 9; ++y)
      for (int x = 0; x < 8; ++x) fluid.set_equilibrium(fluid.node(x, y, z), 1.0, u0 + grad * Vec3(x + 0.5, y + 0.5, z + 0.5));
  for (const Vec3& r : {Vec3(0.5, 0.5, 0.5), Vec3(3.2, 4.7, 5.05), Vec3(7.49, 1.0, 9.4), Vec3(2.0, 8.4999, 0.5001)}) {
    const Vec3 u = interpolated_velocity(fluid, r);
    EXPECT_LT((u - (u0 + grad * r)).norm(), 1e-15) << r.transpose();
    const Stencil st = trilinear_stencil(fluid, r);
    double sum = 0.0;
    for (double w : st.weight) sum += w;
    EXPECT_NEAR(sum, 1.0, 1e-15);
  }
  // Periodic images give the same stencil.
  const Stencil a = trilinear_stencil(fluid, Vec3(0.2, 3.3, 9.9)), b = trilinear_stencil(fluid, Vec3(8.2, -5.7, -0.1));
  for (std::size_t c = 0; c < 8; ++c) {
    EXPECT_EQ(a.node[c], b.node[c]);
    EXPECT_NEAR(a.weight[c], b.weight[c], 1e-14);
  }
}

namespace {

struct Beads {
  std::vector<Vec3> r, v;
  std::vector<std::uint32_t> id;
};

Beads some_beads() {
  Beads b;
  for (std::uint32_t k = 0; k < 20; ++k) {
    b.r.emplace_back(0.37 * k, 1.1 + 0.53 * k, 5.9 - 0.29 * k);
    b.v.emplace_back(0.01 * std::sin(k), -0.02 * std::cos(3.0 * k), 0.005 * k);
    b.id.push_back(100 + 7 * k);
  }
  return b;
}

}  // namespace

TEST(PointCoupling, BeadAndFluidMomentumTogetherAreConserved) {
  LbFluid fluid({6, 7, 8}, LbParameters{6.004, 0.016, 0.0, 0.0, 4e-4, 3});
  for (int s = 0; s < 20; ++s) fluid.step();
  const PointCoupling coupling(2.5, 0.5, 4e-4, 9);
  Beads beads = some_beads();
  std::vector<Vec3> force;
  const Vec3 fluid_before = fluid.total_momentum();
  Vec3 bead_impulse = Vec3::Zero();
  for (std::uint64_t md = 0; md < 2; ++md) {  // two MD steps per LB step
    coupling.couple(fluid, beads.r, beads.v, beads.id, md, force);
    for (const Vec3& f : force) bead_impulse += 0.5 * f;
  }
  fluid.step();
  EXPECT_GT(bead_impulse.norm(), 1e-4);  // the test has something to conserve
  EXPECT_LT((fluid.total_momentum() - fluid_before + bead_impulse).norm(), 1e-13);
}

TEST(PointCoupling, NoBeadsForceDependsOnTheOrderOrCompanyOfTheBeads) {
  LbFluid fluid({6, 7, 8}, LbParameters{6.004, 0.016, 0.0, 0.0, 4e-4, 3});
  for (int s = 0; s < 5; ++s) fluid.step();
  const PointCoupling coupling(2.5, 0.5, 4e-4, 9);
  const Beads beads = some_beads();
  std::vector<Vec3> all, reversed, one;
  LbFluid copy = fluid;
  coupling.couple(copy, beads.r, beads.v, beads.id, 4, all);
  Beads back = beads;
  std::reverse(back.r.begin(), back.r.end());
  std::reverse(back.v.begin(), back.v.end());
  std::reverse(back.id.begin(), back.id.end());
  copy = fluid;
  coupling.couple(copy, back.r, back.v, back.id, 4, reversed);
  for (std::size_t b = 0; b < all.size(); ++b) {
    EXPECT_EQ(all[b], reversed[all.size() - 1 - b]) << b;
    copy = fluid;
    coupling.couple(copy, {beads.r[b]}, {beads.v[b]}, {beads.id[b]}, 4, one);
    EXPECT_EQ(all[b], one[0]) << b;
  }
}

TEST(PointCoupling, BadParametersAreRefused) {
  EXPECT_THROW(PointCoupling(0.0, 0.5, 0.0, 1), InputError);
  EXPECT_THROW(PointCoupling(-1.0, 0.5, 0.0, 1), InputError);
  EXPECT_THROW(PointCoupling(1.0, 0.0, 0.0, 1), InputError);
  EXPECT_THROW(PointCoupling(1.0, 1.5, 0.0, 1), InputError);
  EXPECT_THROW(PointCoupling(1.0, 0.5, -1.0, 1), InputError);
}


TEST(PointCoupling, APulledBeadsFrictionActsInSeriesWithTheFluids) {
  // Ahlrichs and Dünweg's form μ = 1/ξ + 1/(g η a) − 2.837297/(6π η L): the fluid's part does not
  // depend on ξ, so μ(ξ₁) − μ(ξ₂) = 1/ξ₁ − 1/ξ₂ at every position of the bead in its cell. The
  // fluid's part (as g) depends on the position: printed, and in docs/lb.md.
  const double eta = 0.5;
  const int L = 12;
  for (const auto convention : {CouplingVelocity::kWithHalfForce, CouplingVelocity::kMomentumOnly})
    for (const Vec3& start : {Vec3(3.5, 3.5, 3.5), Vec3(4.0, 4.0, 4.0), Vec3(3.8, 4.3, 3.6)}) {
      const double weak = checks::pulled_bead_mobility(L, 0.5, 0.5, start, convention), strong = checks::pulled_bead_mobility(L, 0.5, 1.0, start, convention);
      const double g = checks::ahlrichs_dunweg_g(strong, 1.0, eta, L);
      std::printf("%s, bead at (%.1f, %.1f, %.1f), L = %g: mobility %.5f (xi = 0.5), %.5f (xi = 1); difference %.5f (1/xi: 1); g = %.2f\n",
                  convention == CouplingVelocity::kWithHalfForce ? "u = (j + f/2)/rho" : "u = j/rho", start.x(), start.y(), start.z(), double(L), weak, strong,
                  weak - strong, g);
      // Off the nodes within 0.4%. On a node (3.5, …) the form holds less well: 1.1% short with the
      // half force, 2.5% over without it.
      const bool on_node = start.x() == 3.5;
      EXPECT_NEAR(weak - strong, 1.0, on_node ? 0.03 : 0.01);
    }
}
