#include "anisodyn/interactions/flat_walls.hpp"

#include <cmath>

namespace anisodyn {

FlatWalls::FlatWalls(FlatWallParameters params, double time_step, std::uint64_t seed)
    : p_(params), time_step_(time_step), noise_(seed, kWallNoise) {}

double FlatWalls::friction(int w, double r) const {
  return r < p_.shell ? p_.gamma_surface[static_cast<std::size_t>(w)] * (p_.shell - r) / p_.shell : 0.0;
}

void FlatWalls::add(const State& s, std::span<const std::int32_t> liquid, BodyForces& out) {
  const Particles& p = s.particles;
  const double lz = s.box.edges().z();
  const double noise_scale = std::sqrt(2.0 * p_.kT / time_step_);
  constexpr double kWallDiameter = 0.0;  // a flat wall is the core of a sphere of diameter 0 (Δ = −1)
  sums_ = WallSums{};
  for (const std::int32_t index : liquid) {
    const auto i = static_cast<std::size_t>(index);
    const double z = p.z[i] + lz * p.iz[i];
    for (int w = 0; w < 2; ++w) {
      const double r = distance(w, z);
      const double reach = std::max(core_.cutoff(kWallDiameter), p_.gamma_surface[static_cast<std::size_t>(w)] > 0.0 ? p_.shell : 0.0);
      if (r >= reach) continue;
      const Vec3 normal(0.0, 0.0, w == 0 ? 1.0 : -1.0);
      Vec3 f = core_.force(r, kWallDiameter) * normal;
      sums_.energy += core_.energy(r, kWallDiameter);
      if (const double xi = friction(w, r); xi > 0.0) {
        const Vec3 v = p.velocity(i);
        f -= xi * v;
        if (p_.kT > 0.0) {
          double theta[4];
          noise_.normals(noise_step_, static_cast<std::uint64_t>(w), static_cast<std::uint64_t>(p.id[i]), theta, 3);
          const double amplitude = noise_scale * std::sqrt(xi);
          if (p_.noise == SiteLiquidParameters::ShellNoise::Vector3d)
            f += amplitude * Vec3(theta[0], theta[1], theta[2]);
          else if (v.norm() >= 1e-12)
            f += amplitude * theta[0] * v.normalized();
        }
      }
      out.force[i] += f;
      sums_.force_on_wall[static_cast<std::size_t>(w)] -= f;
    }
  }
  out.energy += sums_.energy;
}

}  // namespace anisodyn
