// The flat walls of spec 30 §6 (interactions/flat_walls.hpp): the core is the colloids' shifted
// Mie(50,49) with Δ = −1 (U = 1 at the plane, zero from 0.0204 on), pushing into the channel from
// either wall, its force minus the gradient of its energy (central differences of the height); the
// friction −ξ(r) v with ξ = γ_ls,0 (δ − r)/δ inside the shell of the wall that has it; the force on
// each wall the opposite of the liquid's; the noise's variance 2 kT ξ/Δt per component.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "anisodyn/interactions/flat_walls.hpp"

using namespace anisodyn;

namespace {

State channel(const std::vector<Vec3>& r, const std::vector<Vec3>& v) {
  State s;
  s.box = Box(Vec3(8, 8, 9.5));
  s.particles.carry_velocities();
  for (std::size_t i = 0; i < r.size(); ++i) {
    s.particles.add(0, r[i], Quat::Identity(), static_cast<std::int64_t>(i));
    s.particles.set_velocity(i, v[i]);
  }
  return s;
}

BodyForces forces_of(FlatWalls& walls, const State& s) {
  BodyForces f;
  f.reset(s.particles.size());
  std::vector<std::int32_t> all(s.particles.size());
  for (std::size_t i = 0; i < all.size(); ++i) all[i] = static_cast<std::int32_t>(i);
  walls.add(s, all, f);
  return f;
}

}  // namespace

TEST(FlatWalls, CoreIsTheShiftedMieOfTheDistanceFromEitherWall) {
  FlatWallParameters p;
  p.kT = 0.0;  // no noise
  FlatWalls walls(p, 0.005, 1);
  EXPECT_NEAR(walls.core().energy(0.0, 0.0), 1.0, 1e-12);  // U = ε at the plane
  EXPECT_EQ(walls.core().energy(0.021, 0.0), 0.0);
  for (const double r : {-0.015, -0.005, 0.0, 0.004, 0.012, 0.019}) {
    // The bottom wall pushes up (+z), the top one down, with −dU/dr.
    const State s = channel({Vec3(1, 1, r), Vec3(2, 2, 8.0 - r)}, {Vec3::Zero(), Vec3::Zero()});
    const BodyForces f = forces_of(walls, s);
    const double h = 1e-7;
    const double gradient = (walls.core().energy(r + h, 0.0) - walls.core().energy(r - h, 0.0)) / (2 * h);
    EXPECT_NEAR(f.force[0].z(), -gradient, 1e-5 * std::abs(gradient) + 1e-9) << r;
    EXPECT_NEAR(f.force[1].z(), gradient, 1e-5 * std::abs(gradient) + 1e-9) << r;
    EXPECT_EQ(f.force[0].x(), 0.0);
    EXPECT_NEAR(f.energy, 2 * walls.core().energy(r, 0.0), 1e-12);
    EXPECT_NEAR((walls.last_sums().force_on_wall[0] + f.force[0]).norm(), 0.0, 1e-12);  // the wall takes the opposite
  }
}

TEST(FlatWalls, FrictionShellOfTheBottomWallOnly) {
  FlatWallParameters p;
  p.kT = 0.0;
  p.gamma_surface = {10.0 / 3.0, 0.0};
  FlatWalls walls(p, 0.005, 1);
  const Vec3 v(0.7, -0.2, 0.1);
  for (const double r : {0.05, 0.25, 0.45, 0.55}) {
    const State s = channel({Vec3(1, 1, r), Vec3(2, 2, 8.0 - r)}, {v, v});
    const BodyForces f = forces_of(walls, s);
    const double xi = r < 0.5 ? 10.0 / 3.0 * (0.5 - r) / 0.5 : 0.0;
    EXPECT_NEAR((f.force[0] - (-xi * v)).norm(), 0.0, 1e-12) << r;  // beyond the core's reach: friction only
    EXPECT_EQ(f.force[1], Vec3::Zero()) << r;                        // the top wall is perfectly slip
  }
}

TEST(FlatWalls, ShellNoiseHasTheFluctuationDissipationVariance) {
  FlatWallParameters p;
  p.gamma_surface = {5.0, 0.0};
  FlatWalls walls(p, 0.005, 3);
  const State s = channel({Vec3(1, 1, 0.2)}, {Vec3::Zero()});  // at rest: the force is the noise alone
  const double target = 2.0 * walls.friction(0, 0.2) / 0.005;
  const int n = 40000;
  Vec3 sum = Vec3::Zero(), sum2 = Vec3::Zero();
  for (int step = 0; step < n; ++step) {
    walls.set_noise_step(static_cast<std::uint64_t>(step));
    const Vec3 f = forces_of(walls, s).force[0];
    sum += f;
    sum2 += f.cwiseProduct(f);
  }
  const Vec3 var = sum2 / n - (sum / n).cwiseProduct(sum / n);
  for (int k = 0; k < 3; ++k) EXPECT_NEAR(var[k], target, 4 * target * std::sqrt(2.0 / n)) << k;
}
