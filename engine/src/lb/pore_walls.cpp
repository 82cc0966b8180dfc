#include "anisodyn/lb/pore_walls.hpp"

#include <cmath>
#include <span>
#include <utility>

#include "anisodyn/core/error.hpp"

namespace anisodyn::lb {

PoreWalls::PoreWalls(const PoreParameters& params, const Box& box, SiteTable inner_sites)
    : params_(params), inner_(std::move(inner_sites)) {
  const Vec3 edges = box.edges();
  axis_ = Vec3(0.5 * edges.x(), 0.5 * edges.y(), 0.0);
  length_ = edges.z();
  wall_radius_ = params.radius + params.wall_bead_radius;
  rings_ = static_cast<std::size_t>(std::max(1.0, std::round(length_ / params.bead_spacing)));
  dz_ = length_ / static_cast<double>(rings_);
  per_ring_ = static_cast<std::size_t>(std::max(3.0, std::round(2.0 * M_PI * wall_radius_ / params.bead_spacing)));
  for (std::size_t j = 0; j < per_ring_; ++j) {
    const double phi = 2.0 * M_PI * static_cast<double>(j) / static_cast<double>(per_ring_);
    cos_.push_back(std::cos(phi));
    sin_.push_back(std::sin(phi));
  }
  for (const SiteBody& body : inner_) {
    double reach = 0.0;
    for (const Vec3& d : body.offsets) reach = std::max(reach, d.norm());
    reach_.push_back(reach);
  }
  sigma_ = params.inner_bead_radius + params.wall_bead_radius;
  cutoff_ = std::pow(2.0, 1.0 / 6.0) * sigma_;
}

double PoreWalls::radial_distance(const Vec3& r) const { return std::hypot(r.x() - axis_.x(), r.y() - axis_.y()); }

Vec3 PoreWalls::bead_force(const Vec3& r, double& energy) const {
  const double x = r.x() - axis_.x(), y = r.y() - axis_.y();
  // Only beads within the cut-off of the wall's cylinder can feel it.
  if (wall_radius_ - std::hypot(x, y) >= cutoff_) return Vec3::Zero();
  const double z = r.z() - length_ * std::floor(r.z() / length_);
  const auto reach = static_cast<long>(std::ceil(cutoff_ / dz_));
  const auto nearest = static_cast<long>(std::floor(z / dz_));
  Vec3 force = Vec3::Zero();
  const double cut2 = cutoff_ * cutoff_, s2 = sigma_ * sigma_;
  for (long k = nearest - reach; k <= nearest + reach + 1; ++k) {
    const double dz = z - (static_cast<double>(k) + 0.5) * dz_;  // rings at (k + ½) Δz, k taken periodically
    if (dz * dz >= cut2) continue;
    for (std::size_t j = 0; j < per_ring_; ++j) {
      const Vec3 d(x - wall_radius_ * cos_[j], y - wall_radius_ * sin_[j], dz);
      const double r2 = d.squaredNorm();
      if (r2 >= cut2) continue;
      const double sr6 = (s2 / r2) * (s2 / r2) * (s2 / r2);
      energy += 4.0 * params_.epsilon * (sr6 * sr6 - sr6) + params_.epsilon;
      force += 24.0 * params_.epsilon * (2.0 * sr6 * sr6 - sr6) / r2 * d;
    }
  }
  return force;
}

double PoreWalls::add(const State& state, BodyForces& out) {
  const Particles& p = state.particles;
  double energy = 0.0;
  std::vector<Vec3>& forces = bead_forces_;
  for (std::size_t i = 0; i < p.size(); ++i) {
    const SiteBody& body = inner_[static_cast<std::size_t>(p.species[i])];
    if (body.size() == 0) continue;
    const Mat3 rot = p.orientation(i).toRotationMatrix();
    const Vec3 centre = p.position(i);
    // A body far from the wall feels nothing: skip its beads.
    if (radial_distance(centre) + reach_[static_cast<std::size_t>(p.species[i])] <= wall_radius_ - cutoff_) continue;
    forces.assign(body.size(), Vec3::Zero());
    for (std::size_t k = 0; k < body.size(); ++k) forces[k] = bead_force(centre + rot * body.offsets[k], energy);
    const Wrench w = reduce_site_forces(body, p.orientation(i), std::span<const Vec3>(forces));
    out.force[i] += w.force;
    out.torque[i] += w.torque;
  }
  out.energy += energy;
  return energy;
}

}  // namespace anisodyn::lb
