#include "anisodyn/lb/body_fluid_coupling.hpp"

#include <string>
#include <utility>

#include "anisodyn/core/error.hpp"

namespace anisodyn::lb {

BodyFluidCoupling::BodyFluidCoupling(LbFluid& fluid, SiteTable bodies, std::vector<Vec3> moments, double friction, double kT, std::uint64_t seed,
                                     LbUnits units, CouplingVelocity velocity)
    : fluid_(fluid),
      bodies_(std::move(bodies)),
      moments_(std::move(moments)),
      units_(units),
      coupling_(friction * units.friction_to_lattice(), 1.0 / units.lb_steps, kT * units.energy_to_lattice(), seed, velocity) {
  if (moments_.size() != bodies_.size()) throw InputError("BodyFluidCoupling: one set of moments per species needed");
  for (const SiteBody& b : bodies_)
    if (b.size() >= (std::size_t{1} << kBeadBits))
      throw InputError("BodyFluidCoupling: at most " + std::to_string((1 << kBeadBits) - 1) + " beads per body, got " + std::to_string(b.size()));
  if (units.lb_steps < 1 || !(units.md_time_step > 0.0) || !(units.agrid > 0.0)) throw InputError("BodyFluidCoupling: bad units");
}

Vec3 BodyFluidCoupling::angular_velocity(const State& s, std::size_t i) const {
  const Particles& p = s.particles;
  if (!p.has_angular_momenta()) return Vec3::Zero();
  return anisodyn::angular_velocity(p.orientation(i), p.angular_momentum(i), moments_[static_cast<std::size_t>(p.species[i])]);
}

void BodyFluidCoupling::operator()(const State& s, BodyForces& out) {
  const Particles& p = s.particles;
  r_.clear(), v_.clear(), id_.clear();
  const double to_lattice_v = units_.velocity_to_lattice();
  // Every coupled body's beads, in body order, then one coupling call: the beads of all bodies see
  // the same fluid.
  for (std::size_t i = 0; i < p.size(); ++i) {
    const SiteBody& body = bodies_[static_cast<std::size_t>(p.species[i])];
    if (body.size() == 0) continue;
    if (p.id[i] < 0 || p.id[i] >= (std::int64_t{1} << (32 - kBeadBits)))
      throw InputError("BodyFluidCoupling: body ids must lie in [0, 2^20), got " + std::to_string(p.id[i]));
    const Mat3 rot = p.orientation(i).toRotationMatrix();
    const Vec3 centre = p.position(i), velocity = p.has_velocities() ? p.velocity(i) : Vec3::Zero(), omega = angular_velocity(s, i);
    for (std::size_t k = 0; k < body.size(); ++k) {
      const Vec3 arm = rot * body.offsets[k];
      r_.push_back((centre + arm) / units_.agrid);
      v_.push_back(to_lattice_v * (velocity + omega.cross(arm)));
      id_.push_back(static_cast<std::uint32_t>((static_cast<std::uint64_t>(p.id[i]) << kBeadBits) | k));
    }
  }
  coupling_.couple(fluid_, r_, v_, id_, noise_step_, f_);
  const double to_md = units_.force_from_lattice();
  std::size_t first = 0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    const SiteBody& body = bodies_[static_cast<std::size_t>(p.species[i])];
    if (body.size() == 0) continue;
    for (std::size_t k = first; k < first + body.size(); ++k) f_[k] *= to_md;
    const Wrench w = reduce_site_forces(body, p.orientation(i), std::span<const Vec3>(f_.data() + first, body.size()));
    out.force[i] += w.force;
    out.torque[i] += w.torque;
    first += body.size();
  }
}

void BodyFluidCoupling::after_step(State& s, double) {
  if ((s.step + 1) % units_.lb_steps == 0) fluid_.step();
}

Vec3 BodyFluidCoupling::fluid_momentum() const { return fluid_.total_momentum() * (units_.agrid / units_.lb_time_step()); }

}  // namespace anisodyn::lb
