#include "anisodyn/interactions/site_liquid.hpp"

#include <algorithm>
#include <cmath>

namespace anisodyn {

namespace {

constexpr std::size_t kChunk = 512;  // liquid particles per chunk (fixed: the sums' order)
constexpr int kPerChunk = 1 + 27;    // energy, 3 virial tensors

}  // namespace

SiteLiquidForces::SiteLiquidForces(SiteLiquidParameters params, double time_step, std::uint64_t seed)
    : p_(params), time_step_(time_step), noise_(seed, kShellNoise) {
  core_.core.epsilon = params.epsilon;
}

double SiteLiquidForces::friction(double r, double d) const {
  const double outer = 0.5 * d + p_.shell;
  return r < outer ? p_.gamma_surface * (outer - r) / p_.shell : 0.0;
}

void SiteLiquidForces::add(const Box& box, std::span<const SiteView> sites, const LiquidView& liquid, double* f_liquid,
                           std::span<Vec3> f_sites, std::span<Vec3> t_sites) {
  const std::size_t n = liquid.n, ns = sites.size();
  const std::size_t chunks = (n + kChunk - 1) / kChunk;
  // Per chunk: the force and the torque on each site, then the sums.
  std::vector<double>& partial = partial_;  // kept between steps: no allocation per step
  partial.assign(chunks * (6 * ns + kPerChunk), 0.0);
  const double noise_scale = std::sqrt(2.0 * p_.kT / time_step_);
  const bool noisy = p_.kT > 0.0 && p_.gamma_surface > 0.0;
#pragma omp parallel for schedule(dynamic, 1)
  for (std::size_t c = 0; c < chunks; ++c) {
    double* mine = partial.data() + c * (6 * ns + kPerChunk);
    double* sums = mine + 6 * ns;
    const std::size_t begin = c * kChunk, end = std::min(n, begin + kChunk);
    for (std::size_t s = 0; s < ns; ++s) {
      const SiteView& site = sites[s];
      const double d = site.diameter;
      const double reach = std::max(core_.cutoff(d), 0.5 * d + (p_.gamma_surface > 0.0 ? p_.shell : 0.0));
      for (std::size_t i = begin; i < end; ++i) {
        const Vec3 rij = box.min_image(Vec3(liquid.x[i], liquid.y[i], liquid.z[i]) - site.position);
        const double r2 = rij.squaredNorm();
        if (r2 >= reach * reach) continue;
        const double r = std::sqrt(r2);
        const Vec3 e = rij / r;
        const Vec3 arm = 0.5 * d * e;  // to the surface point nearest the particle
        const Vec3 surface_motion = p_.surface_velocity ? Vec3(site.angular_velocity.cross(arm)) : Vec3::Zero();
        const Vec3 v = Vec3(liquid.vx[i], liquid.vy[i], liquid.vz[i]) - site.velocity - surface_motion;
        // Parts: core (along r̂), friction (along −v), noise.
        Vec3 parts[3] = {core_.force(r, d) * e, Vec3::Zero(), Vec3::Zero()};
        sums[0] += core_.energy(r, d);
        const double xi = friction(r, d);
        if (xi > 0.0) {
          parts[1] = -xi * v;
          if (noisy) {
            double theta[4];
            noise_.normals(noise_step_, site.id, static_cast<std::uint64_t>(liquid.id[i]), theta, 3);
            const double amplitude = noise_scale * std::sqrt(xi);
            if (p_.noise == SiteLiquidParameters::ShellNoise::Vector3d) {
              parts[2] = amplitude * Vec3(theta[0], theta[1], theta[2]);
            } else if (v.norm() >= 1e-12) {
              parts[2] = amplitude * theta[0] * v.normalized();
            }
          }
        }
        const Vec3 total = parts[0] + parts[1] + parts[2];
        const Vec3 torque = p_.surface_velocity ? Vec3(arm.cross(-(parts[1] + parts[2]))) : Vec3::Zero();
        for (int k = 0; k < 3; ++k) {
          f_liquid[3 * i + static_cast<std::size_t>(k)] += total[k];
          mine[6 * s + static_cast<std::size_t>(k)] -= total[k];
          mine[6 * s + 3 + static_cast<std::size_t>(k)] += torque[k];
        }
        for (int part = 0; part < 3; ++part) {
          const Mat3 w = rij * parts[part].transpose();
          for (int k = 0; k < 9; ++k) sums[1 + 9 * part + k] += w(k);
        }
      }
    }
  }
  sums_ = SiteLiquidSums{};
  for (std::size_t c = 0; c < chunks; ++c) {
    const double* mine = partial.data() + c * (6 * ns + kPerChunk);
    for (std::size_t s = 0; s < ns; ++s) {
      f_sites[s] += Vec3(mine[6 * s], mine[6 * s + 1], mine[6 * s + 2]);
      t_sites[s] += Vec3(mine[6 * s + 3], mine[6 * s + 4], mine[6 * s + 5]);
    }
    const double* sums = mine + 6 * ns;
    sums_.energy += sums[0];
    for (int part = 0; part < 3; ++part)
      for (int k = 0; k < 9; ++k) sums_.virial[static_cast<std::size_t>(part)](k) += sums[1 + 9 * part + k];
  }
}

}  // namespace anisodyn
