// The pore's excluded-volume wall (lb/pore_walls.hpp, spec 40 §6): its bead grid, the energy
// against a brute-force sum over every wall bead and its periodic images, forces and torques
// against finite differences of that energy, and nothing for a body away from the wall.
#include <gtest/gtest.h>

#include <cmath>

#include "anisodyn/lb/pore_walls.hpp"

using namespace anisodyn;
using namespace anisodyn::lb;

namespace {

const PoreParameters kPore{8.5, 6.25, 5.0, 0.5, 1.0};

State body_at(const Vec3& r, const Quat& q) {
  State s;
  s.box = Box(Vec3(32, 32, 24));
  s.species = {Species{"raspberry", Shape::sphere(8.5), 1.0, {}, {}}};
  s.particles.add(0, r, q, 0);
  return s;
}

SiteTable sites() { return {SiteBody{{Vec3(3.75, 0, 0), Vec3(0, 3.75, 0), Vec3(-2.0, -1.0, 3.0), Vec3(0.5, -3.0, -2.0)}, {}, {}}}; }

/// Σ over every wall bead, over three periodic images along z, of the WCA of each inner bead.
double brute_force_energy(const State& s, const PoreWalls& walls) {
  const double R = kPore.radius + kPore.wall_bead_radius, sigma = 6.75, cut = std::pow(2.0, 1.0 / 6.0) * sigma;
  const Mat3 rot = s.particles.orientation(0).toRotationMatrix();
  double e = 0.0;
  const SiteTable table = sites();
  for (const Vec3& d : table[0].offsets) {
    const Vec3 r = s.particles.position(0) + rot * d;
    for (std::size_t k = 0; k < walls.rings(); ++k)
      for (std::size_t j = 0; j < walls.beads_per_ring(); ++j)
        for (int image = -1; image <= 1; ++image) {
          const double phi = 2 * M_PI * j / walls.beads_per_ring();
          const Vec3 w(16 + R * std::cos(phi), 16 + R * std::sin(phi), (k + 0.5) * walls.ring_spacing() + image * 24.0);
          const double dist = (r - w).norm();
          if (dist < cut) e += 4 * (std::pow(sigma / dist, 12) - std::pow(sigma / dist, 6)) + 1;
        }
  }
  return e;
}

double energy(PoreWalls& walls, const State& s) {
  BodyForces f;
  f.reset(1);
  return walls.add(s, f);
}

}  // namespace

TEST(PoreWalls, BeadGrid) {
  const PoreWalls walls(kPore, Box(Vec3(32, 32, 24)), sites());
  EXPECT_EQ(walls.rings(), 5u);  // round(24 / 5), 4.8 apart
  EXPECT_DOUBLE_EQ(walls.ring_spacing(), 4.8);
  EXPECT_EQ(walls.beads_per_ring(), 19u);  // round(2 pi 14.75 / 5)
  EXPECT_DOUBLE_EQ(walls.sigma(), 6.75);
  EXPECT_DOUBLE_EQ(walls.radial_distance(Vec3(19, 20, 3)), 5.0);
}

TEST(PoreWalls, EnergyForceAndTorqueAgainstReferences) {
  PoreWalls walls(kPore, Box(Vec3(32, 32, 24)), sites());
  const Quat q = Quat(Eigen::AngleAxisd(0.7, Vec3(1, -2, 0.5).normalized()));
  // The centre 4.6 from the axis: beads up to 8.35 out, inside the WCA range of the wall beads.
  for (const Vec3& centre : {Vec3(20.6, 16.0, 23.5), Vec3(16.0, 11.2, 0.3), Vec3(13.0, 19.0, 11.0)}) {
    const State s = body_at(centre, q);
    BodyForces f;
    f.reset(1);
    const double e = walls.add(s, f);
    const double reference = brute_force_energy(s, walls);
    EXPECT_GT(reference, 0.01) << centre.transpose();  // the case is a real contact
    EXPECT_NEAR(e, reference, 1e-10 * reference);
    const double h = 1e-6;
    for (int k = 0; k < 3; ++k) {
      Vec3 dr = Vec3::Zero();
      dr[k] = h;
      const double de = energy(walls, body_at(centre + dr, q)) - energy(walls, body_at(centre - dr, q));
      EXPECT_NEAR(f.force[0][k], -de / (2 * h), 1e-5 * (1 + f.force[0].norm())) << k;
      Vec3 axis = Vec3::Zero();
      axis[k] = 1;
      const Quat plus = Quat(Eigen::AngleAxisd(h, axis)) * q, minus = Quat(Eigen::AngleAxisd(-h, axis)) * q;
      const double dt = energy(walls, body_at(centre, plus)) - energy(walls, body_at(centre, minus));
      EXPECT_NEAR(f.torque[0][k], -dt / (2 * h), 1e-5 * (1 + f.torque[0].norm())) << k;
    }
  }
}

TEST(PoreWalls, ABodyAwayFromTheWallFeelsNothing) {
  PoreWalls walls(kPore, Box(Vec3(32, 32, 24)), sites());
  BodyForces f;
  f.reset(1);
  EXPECT_EQ(walls.add(body_at(Vec3(16.5, 15.5, 7), Quat::Identity()), f), 0.0);
  EXPECT_EQ(f.force[0], Vec3::Zero());
  EXPECT_EQ(f.torque[0], Vec3::Zero());
}
