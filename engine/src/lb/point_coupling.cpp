#include "anisodyn/lb/point_coupling.hpp"

#include <cmath>
#include <string>

#include "anisodyn/core/error.hpp"

namespace anisodyn::lb {

namespace {
inline constexpr std::uint64_t kLbBeadNoise = 0x4C424245414400ULL;  // "LBBEAD"
}  // namespace

Stencil trilinear_stencil(const LbFluid& fluid, const Vec3& r) {
  const auto& dims = fluid.dims();
  std::array<std::size_t, 3> lo{}, hi{};
  std::array<double, 3> t{};
  for (int d = 0; d < 3; ++d) {
    // Node centres at i + ½: the point lies between nodes floor(r − ½) and the next, periodically.
    const double s = r[d] - 0.5;
    const double cell = std::floor(s);
    t[static_cast<std::size_t>(d)] = s - cell;
    const long n = dims[static_cast<std::size_t>(d)];
    const long i = (static_cast<long>(cell) % n + n) % n;
    lo[static_cast<std::size_t>(d)] = static_cast<std::size_t>(i);
    hi[static_cast<std::size_t>(d)] = static_cast<std::size_t>((i + 1) % n);
  }
  Stencil st;
  for (int c = 0; c < 8; ++c) {
    const bool ux = c & 1, uy = c & 2, uz = c & 4;
    st.node[static_cast<std::size_t>(c)] = fluid.node(static_cast<int>(ux ? hi[0] : lo[0]), static_cast<int>(uy ? hi[1] : lo[1]), static_cast<int>(uz ? hi[2] : lo[2]));
    st.weight[static_cast<std::size_t>(c)] = (ux ? t[0] : 1.0 - t[0]) * (uy ? t[1] : 1.0 - t[1]) * (uz ? t[2] : 1.0 - t[2]);
  }
  return st;
}

Vec3 interpolated_velocity(const LbFluid& fluid, const Stencil& stencil, CouplingVelocity velocity) {
  Vec3 u = Vec3::Zero();
  for (std::size_t c = 0; c < 8; ++c) u += stencil.weight[c] * fluid.velocity(stencil.node[c], velocity == CouplingVelocity::kWithHalfForce);
  return u;
}

Vec3 interpolated_velocity(const LbFluid& fluid, const Vec3& r) { return interpolated_velocity(fluid, trilinear_stencil(fluid, r)); }

PointCoupling::PointCoupling(double friction, double md_step_fraction, double kT, std::uint64_t seed, CouplingVelocity velocity)
    : friction_(friction), h_(md_step_fraction), noise_amplitude_(0.0), noise_(seed, kLbBeadNoise), velocity_(velocity) {
  if (!(friction > 0.0) || !std::isfinite(friction)) throw InputError("PointCoupling: the bead friction must be positive, got " + std::to_string(friction));
  if (!(md_step_fraction > 0.0 && md_step_fraction <= 1.0))
    throw InputError("PointCoupling: the MD step must be a fraction (0, 1] of the LB step, got " + std::to_string(md_step_fraction));
  if (!(kT >= 0.0) || !std::isfinite(kT)) throw InputError("PointCoupling: k_BT must be zero or positive");
  noise_amplitude_ = std::sqrt(2.0 * kT * friction / md_step_fraction);
}

void PointCoupling::couple(LbFluid& fluid, const std::vector<Vec3>& position, const std::vector<Vec3>& velocity, const std::vector<std::uint32_t>& id,
                           std::uint64_t md_step, std::vector<Vec3>& force) const {
  const std::size_t beads = position.size();
  if (velocity.size() != beads || id.size() != beads) throw InputError("PointCoupling::couple: as many positions, velocities and ids needed");
  force.resize(beads);
  // Every bead sees the fluid as it was at the start of the MD step: the impulses go in after all
  // forces are known, so that no bead's force depends on the order of the beads.
  std::vector<Stencil> stencils(beads);
  for (std::size_t b = 0; b < beads; ++b) {
    stencils[b] = trilinear_stencil(fluid, position[b]);
    force[b] = -friction_ * (velocity[b] - interpolated_velocity(fluid, stencils[b], velocity_));
    if (noise_amplitude_ > 0.0) {
      double z[3];
      noise_.normals(md_step, id[b], 0, z, 3);
      force[b] += noise_amplitude_ * Vec3(z[0], z[1], z[2]);
    }
  }
  for (std::size_t b = 0; b < beads; ++b)
    for (std::size_t c = 0; c < 8; ++c) fluid.add_force(stencils[b].node[c], (-h_ * stencils[b].weight[c]) * force[b]);
}

}  // namespace anisodyn::lb
