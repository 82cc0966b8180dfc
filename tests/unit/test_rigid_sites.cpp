// Rigid bodies of sites (system/rigid_sites.hpp): lab site positions for rotations worked out by
// hand, the reduction of site forces to the body's force and torque against central finite
// differences of the total potential energy (forces by shifting the centre, torques by small lab
// rotations about it), and the point-mass moments of inertia against the DPD rod table of spec 30
// §3.2 and a box of eight masses.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include "anisodyn/core/error.hpp"
#include "anisodyn/core/quaternion.hpp"
#include "anisodyn/core/rng.hpp"
#include "anisodyn/system/rigid_sites.hpp"

using namespace anisodyn;

namespace {

/// An irregular body: seven sites scattered around the centre.
SiteBody scattered_body(Rng& rng) {
  SiteBody body;
  for (int s = 0; s < 7; ++s) body.offsets.emplace_back(rng.uniform(-1, 1), rng.uniform(-1, 1), rng.uniform(-1, 1));
  return body;
}

/// A nonlinear site field: a Gaussian well per site, U = −Σ_s w_s exp(−|r_s − a_s|² / 2).
struct GaussianWells {
  std::vector<Vec3> anchor;
  std::vector<double> depth;

  double energy(const std::vector<Vec3>& sites) const {
    double u = 0;
    for (std::size_t s = 0; s < sites.size(); ++s) u -= depth[s] * std::exp(-0.5 * (sites[s] - anchor[s]).squaredNorm());
    return u;
  }
  /// f_s = −∇_s U = −w_s (r_s − a_s) exp(−|r_s − a_s|² / 2).
  std::vector<Vec3> forces(const std::vector<Vec3>& sites) const {
    std::vector<Vec3> f(sites.size());
    for (std::size_t s = 0; s < sites.size(); ++s) {
      const Vec3 d = sites[s] - anchor[s];
      f[s] = -depth[s] * std::exp(-0.5 * d.squaredNorm()) * d;
    }
    return f;
  }
};

std::vector<Vec3> sites_of(const SiteBody& body, const Vec3& centre, const Quat& q) {
  std::vector<Vec3> out(body.size());
  site_positions(body, centre, q, out);
  return out;
}

}  // namespace

TEST(RigidSites, SitePositionsFollowTheBodyRotation) {
  SiteBody body;
  body.offsets = {Vec3(1, 0, 0), Vec3(0, 2, 0), Vec3(0, 0, 3)};
  const Vec3 centre(10, 20, 30);
  // A quarter turn about z: x → y, y → −x, z fixed.
  const Quat about_z(std::cos(M_PI / 4), 0, 0, std::sin(M_PI / 4));
  auto r = sites_of(body, centre, about_z);
  EXPECT_NEAR((r[0] - Vec3(10, 21, 30)).norm(), 0, 1e-14);
  EXPECT_NEAR((r[1] - Vec3(8, 20, 30)).norm(), 0, 1e-14);
  EXPECT_NEAR((r[2] - Vec3(10, 20, 33)).norm(), 0, 1e-14);
  // A third of a turn about (1, 1, 1): x → y → z → x.
  const double h = std::sin(M_PI / 3) / std::sqrt(3.0);
  r = sites_of(body, centre, Quat(std::cos(M_PI / 3), h, h, h));
  EXPECT_NEAR((r[0] - Vec3(10, 21, 30)).norm(), 0, 1e-14);
  EXPECT_NEAR((r[1] - Vec3(10, 20, 32)).norm(), 0, 1e-14);
  EXPECT_NEAR((r[2] - Vec3(13, 20, 30)).norm(), 0, 1e-14);
  // The output must have one slot per site.
  std::vector<Vec3> short_out(2);
  EXPECT_THROW(site_positions(body, centre, about_z, short_out), InputError);
}

TEST(RigidSites, ReducedForceAndTorqueAreMinusTheEnergyGradient) {
  Rng rng(41, 2);
  double worst = 0;
  for (int trial = 0; trial < 20; ++trial) {
    const SiteBody body = scattered_body(rng);
    GaussianWells field;
    for (std::size_t s = 0; s < body.size(); ++s) {
      field.anchor.emplace_back(rng.uniform(-1.5, 1.5), rng.uniform(-1.5, 1.5), rng.uniform(-1.5, 1.5));
      field.depth.push_back(rng.uniform(0.5, 2.0));
    }
    const Vec3 centre(rng.uniform(-0.3, 0.3), rng.uniform(-0.3, 0.3), rng.uniform(-0.3, 0.3));
    const Quat q = uniform_quaternion(rng.uniform(), rng.uniform(), rng.uniform());
    const Wrench w = reduce_site_forces(body, q, field.forces(sites_of(body, centre, q)));

    const double h = 1e-5;
    Vec3 force_fd, torque_fd;
    for (int a = 0; a < 3; ++a) {
      const Vec3 e = h * Vec3::Unit(a);
      force_fd[a] = -(field.energy(sites_of(body, centre + e, q)) - field.energy(sites_of(body, centre - e, q))) / (2 * h);
      // τ·ê_a = −dU/dθ for a rotation of the body about the lab axis ê_a through its centre.
      torque_fd[a] = -(field.energy(sites_of(body, centre, rotate_in_lab_frame(q, e))) -
                       field.energy(sites_of(body, centre, rotate_in_lab_frame(q, -e)))) / (2 * h);
    }
    const double scale = w.force.norm() + w.torque.norm() + 1.0;
    EXPECT_LT((w.force - force_fd).norm(), 1e-8 * scale) << "trial " << trial;
    EXPECT_LT((w.torque - torque_fd).norm(), 1e-8 * scale) << "trial " << trial;
    EXPECT_GT(w.torque.norm(), 1e-3) << "the test needs a real torque";
    worst = std::max(worst, ((w.force - force_fd).norm() + (w.torque - torque_fd).norm()) / scale);
  }
  std::printf("reduced force and torque vs finite differences: max relative difference %.1e\n", worst);
}

TEST(RigidSites, APairOfOppositeSiteForcesIsAPureTorque) {
  SiteBody body;
  body.offsets = {Vec3(0, 0, -1), Vec3(0, 0, 1)};
  const Quat q = Quat::Identity();
  const std::vector<Vec3> f = {Vec3(-2, 0, 0), Vec3(2, 0, 0)};
  const Wrench w = reduce_site_forces(body, q, f);
  EXPECT_EQ(w.force, Vec3::Zero());
  // (0, 0, −1) × (−2, 0, 0) + (0, 0, 1) × (2, 0, 0) = (0, 2, 0) + (0, 2, 0).
  EXPECT_NEAR((w.torque - Vec3(0, 4, 0)).norm(), 0, 1e-15);
  EXPECT_THROW(reduce_site_forces(body, q, std::vector<Vec3>(3)), InputError);
  // Torques on the sites about their own centres add to the body's; one per site or none.
  const std::vector<Vec3> t = {Vec3(0.5, 0, 0), Vec3(0, 0, -1)};
  const Wrench wt = reduce_site_forces(body, q, f, t);
  EXPECT_EQ(wt.force, Vec3::Zero());
  EXPECT_NEAR((wt.torque - Vec3(0.5, 4, -1)).norm(), 0, 1e-15);
  EXPECT_THROW(reduce_site_forces(body, q, f, std::vector<Vec3>(1)), InputError);
}

TEST(RigidSites, RodMomentsMatchTheDpdTable) {
  // Spec 30 §3.2: spheres of diameter d at spacing 0.5 on a segment of length L − d, each of mass
  // ρ_l V / N_s with V the spherocylinder volume and ρ_l = 3; the table gives I⊥ = Σ m_r z_k².
  // The table is rounded: each row carries the unit of its last printed digit.
  struct Row { double d, L, I_perp, last_digit; };
  for (const Row row : {Row{1, 2, 0.654, 1e-3}, Row{1, 3, 3.142, 1e-3}, Row{1, 6, 33.379, 1e-3}, Row{2, 6, 83.776, 1e-3},
                        Row{3, 6, 106.03, 1e-2}}) {
    const int n = static_cast<int>(std::lround((row.L - row.d) / 0.5)) + 1;
    const double volume = M_PI * row.d * row.d * (row.d + 1.5 * (row.L - row.d)) / 6.0;
    const double m = 3.0 * volume / n;
    std::vector<Vec3> offsets;
    for (int k = 0; k < n; ++k) offsets.emplace_back(0, 0, -0.5 * (row.L - row.d) + 0.5 * k);
    const Vec3 moments = point_mass_moments(offsets, m);
    EXPECT_NEAR(moments.x(), row.I_perp, 0.5 * row.last_digit) << "d = " << row.d << ", L = " << row.L;
    EXPECT_EQ(moments.x(), moments.y());
    EXPECT_EQ(moments.z(), 0.0);
  }
}

TEST(RigidSites, MomentsOfABoxOfEightMasses) {
  const double a = 0.5, b = 1.0, c = 2.0, m = 0.25;
  std::vector<Vec3> offsets;
  for (int sx : {-1, 1})
    for (int sy : {-1, 1})
      for (int sz : {-1, 1}) offsets.emplace_back(sx * a, sy * b, sz * c);
  const Vec3 moments = point_mass_moments(offsets, m);
  EXPECT_NEAR(moments.x(), 8 * m * (b * b + c * c), 1e-14);
  EXPECT_NEAR(moments.y(), 8 * m * (a * a + c * c), 1e-14);
  EXPECT_NEAR(moments.z(), 8 * m * (a * a + b * b), 1e-14);
}

TEST(RigidSites, MomentsNeedCentredSitesOnPrincipalAxes) {
  EXPECT_THROW(point_mass_moments(std::vector<Vec3>{Vec3(0, 0, 1), Vec3(0, 0, 2)}, 1.0), InputError);  // off centre
  EXPECT_THROW(point_mass_moments(std::vector<Vec3>{Vec3(1, 1, 0), Vec3(-1, -1, 0)}, 1.0), InputError);  // tilted axes
  EXPECT_THROW(point_mass_moments(std::vector<Vec3>{Vec3(1, 0, 0), Vec3(-1, 0, 0)}, 0.0), InputError);  // no mass
  EXPECT_NO_THROW(point_mass_moments(std::vector<Vec3>{Vec3(1, 0, 0), Vec3(-1, 0, 0)}, 1.0));
}

TEST(RigidSites, AngularVelocityInvertsTheInertiaInTheBodyFrame) {
  // L = R I Rᵀ ω for a rotated asymmetric body: back to ω; a linear rotor's zero-moment axis does
  // not turn, and a body of no moments does not turn at all.
  const Quat q = Quat(Eigen::AngleAxisd(0.7, Vec3(1, 2, -1).normalized()));
  const Mat3 rot = q.toRotationMatrix();
  const Vec3 moments(1.0, 2.5, 4.0), omega(0.3, -1.2, 0.8);
  const Vec3 L = rot * moments.asDiagonal() * rot.transpose() * omega;
  EXPECT_LT((angular_velocity(q, L, moments) - omega).norm(), 1e-14);
  const Vec3 rotor(2.0, 2.0, 0.0);
  const Vec3 spin = angular_velocity(q, rot * Vec3(1.0, -3.0, 5.0), rotor);
  EXPECT_NEAR(spin.dot(rot.col(2)), 0.0, 1e-14);
  EXPECT_LT((spin - rot * Vec3(0.5, -1.5, 0.0)).norm(), 1e-14);
  EXPECT_EQ(angular_velocity(q, L, Vec3::Zero()), Vec3::Zero());
}
