#include "anisodyn/system/rigid_sites.hpp"

#include <cmath>
#include <string>

#include "anisodyn/core/error.hpp"

namespace anisodyn {

namespace {

void require_one_per_site(const SiteBody& body, std::size_t n, const char* what) {
  if (n != body.size())
    throw InputError(std::string(what) + ": " + std::to_string(n) + " values for a body of " + std::to_string(body.size()) +
                     " sites");
}

}  // namespace

void site_positions(const SiteBody& body, const Vec3& centre, const Quat& q, std::span<Vec3> out) {
  require_one_per_site(body, out.size(), "site_positions");
  const Mat3 rot = q.toRotationMatrix();
  for (std::size_t s = 0; s < body.size(); ++s) out[s] = centre + rot * body.offsets[s];
}

Wrench reduce_site_forces(const SiteBody& body, const Quat& q, std::span<const Vec3> site_forces, std::span<const Vec3> site_torques) {
  require_one_per_site(body, site_forces.size(), "reduce_site_forces");
  if (!site_torques.empty()) require_one_per_site(body, site_torques.size(), "reduce_site_forces (site torques)");
  const Mat3 rot = q.toRotationMatrix();
  Wrench w;
  for (std::size_t s = 0; s < body.size(); ++s) {
    w.force += site_forces[s];
    w.torque += (rot * body.offsets[s]).cross(site_forces[s]);
    if (!site_torques.empty()) w.torque += site_torques[s];
  }
  return w;
}

Vec3 angular_velocity(const Quat& q, const Vec3& angular_momentum, const Vec3& moments) {
  if (moments.maxCoeff() == 0.0) return Vec3::Zero();
  const Mat3 rot = q.toRotationMatrix();
  Vec3 body = rot.transpose() * angular_momentum;
  for (int k = 0; k < 3; ++k) body[k] = moments[k] > 0.0 ? body[k] / moments[k] : 0.0;
  return rot * body;
}

Vec3 point_mass_moments(std::span<const Vec3> offsets, double site_mass) {
  if (!(site_mass > 0.0)) throw InputError("point_mass_moments: the site mass must be positive");
  Vec3 sum = Vec3::Zero();
  double scale = 0.0;  // Σ |d_s|²
  Mat3 inertia = Mat3::Zero();
  for (const Vec3& d : offsets) {
    sum += d;
    scale += d.squaredNorm();
    inertia += d.squaredNorm() * Mat3::Identity() - d * d.transpose();
  }
  const double tol = 1e-10;
  if (sum.norm() > tol * std::sqrt(scale * static_cast<double>(offsets.size())))
    throw InputError("point_mass_moments: the sites' centroid is not the body centre");
  for (int a = 0; a < 3; ++a)
    for (int b = a + 1; b < 3; ++b)
      if (std::abs(inertia(a, b)) > tol * scale)
        throw InputError("point_mass_moments: the body axes are not principal axes of the sites");
  return site_mass * inertia.diagonal();
}

}  // namespace anisodyn
