#include "anisodyn/dpd/colloid_coupling.hpp"

#include <algorithm>
#include <cmath>

#include "anisodyn/core/error.hpp"

namespace anisodyn {

namespace {

/// Noise key of site k of the colloid with this id (ids below 2³², at most 2⁸ sites per body).
constexpr int kSiteBits = 8;

std::string number(double x) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.6g", x);
  return buf;
}

}  // namespace

ColloidCoupling::ColloidCoupling(const State& state, const std::vector<char>& is_liquid, const DpdProtocol& protocol,
                                 std::uint64_t seed, const std::string& config_file)
    : forces_(protocol.colloids.value().shell, protocol.time_step, seed), fixed_(protocol.colloids->fixed) {
  classify(state, is_liquid, protocol, config_file);
  check_geometry(state, protocol, config_file);
}

void ColloidCoupling::classify(const State& state, const std::vector<char>& is_liquid, const DpdProtocol& protocol,
                               const std::string& config_file) {
  const auto& col = *protocol.colloids;
  std::vector<char> is_colloid(state.species.size(), 0);
  for (std::size_t k = 0; k < col.species.size(); ++k) {
    const std::string key = "colloids.species[" + std::to_string(k) + "]";
    const int s = species_index(state.species, col.species[k]);  // known: the runner checked the names
    if (is_liquid[static_cast<std::size_t>(s)])
      throw InputError(config_file, key, "'" + col.species[k] + "' is a liquid species too: expected each species to be one or the other");
    is_colloid[static_cast<std::size_t>(s)] = 1;
  }
  bodies_.resize(state.species.size());
  for (std::size_t s = 0; s < state.species.size(); ++s) {
    if (!is_colloid[s] && !is_liquid[s])
      throw InputError(config_file, "colloids.species", "species '" + state.species[s].name +
                                                            "' is neither liquid nor colloid: expected it in liquid.species or colloids.species");
    if (!is_colloid[s]) continue;
    try {
      bodies_[s] = colloid_body(state.species[s].shape, col.mass_density, col.site_spacing, col.shell.surface_velocity);
    } catch (const InputError& e) {
      throw InputError(config_file, "colloids.species", "species '" + state.species[s].name + "': " + e.what());
    }
    if (bodies_[s].sites.size() > (1u << kSiteBits))
      throw InputError(config_file, "colloids.site_spacing", "species '" + state.species[s].name + "' would have more than " +
                                                                 std::to_string(1u << kSiteBits) + " sites");
  }
  const Particles& p = state.particles;
  for (std::size_t i = 0; i < p.size(); ++i)
    (is_colloid[static_cast<std::size_t>(p.species[i])] ? colloids_ : liquid_).push_back(static_cast<std::int32_t>(i));
}

void ColloidCoupling::check_geometry(const State& state, const DpdProtocol& protocol, const std::string& config_file) const {
  const auto& shell = protocol.colloids->shell;
  const Particles& p = state.particles;
  for (const std::int32_t c : colloids_) {
    const auto s = static_cast<std::size_t>(p.species[static_cast<std::size_t>(c)]);
    const ColloidBody& b = bodies_[s];
    const double d = b.sites.radii.front();
    const double reach = std::max(0.5 * d + (shell.gamma_surface > 0.0 ? shell.shell : 0.0), forces_.core().cutoff(d));
    if (b.extent(reach) > state.box.shortest_edge())
      throw InputError(config_file, "colloids.species", "species '" + state.species[s].name + "' reaches " + number(b.extent(reach)) +
                                                            " across with its interaction range, more than the shortest box edge " +
                                                            number(state.box.shortest_edge()) +
                                                            ": expected a box in which each liquid particle sees one image of it");
  }
  // Cores may not overlap: there are no colloid–colloid forces to push them apart (spec 30 §3.3).
  std::vector<std::vector<Vec3>> sites(colloids_.size());
  for (std::size_t a = 0; a < colloids_.size(); ++a) {
    const auto i = static_cast<std::size_t>(colloids_[a]);
    const ColloidBody& b = bodies_[static_cast<std::size_t>(p.species[i])];
    sites[a].resize(b.sites.size());
    site_positions(b.sites, p.position(i), p.orientation(i), sites[a]);
  }
  for (std::size_t a = 0; a < colloids_.size(); ++a)
    for (std::size_t b = a + 1; b < colloids_.size(); ++b) {
      const auto ia = static_cast<std::size_t>(colloids_[a]), ib = static_cast<std::size_t>(colloids_[b]);
      const double contact = 0.5 * (bodies_[static_cast<std::size_t>(p.species[ia])].sites.radii.front() +
                                    bodies_[static_cast<std::size_t>(p.species[ib])].sites.radii.front());
      for (const Vec3& ra : sites[a])
        for (const Vec3& rb : sites[b])
          if (state.box.min_image(ra - rb).norm() < contact)
            throw InputError("", "", "colloids " + std::to_string(p.id[ia]) + " and " + std::to_string(p.id[ib]) +
                                         " overlap: expected colloid cores apart (there are no colloid-colloid forces)");
    }
}

std::vector<BodyInertia> ColloidCoupling::inertia(const SpeciesTable& species) const {
  std::vector<BodyInertia> out;
  for (std::size_t s = 0; s < species.size(); ++s)
    out.push_back(bodies_[s].sites.size() ? BodyInertia{bodies_[s].mass, bodies_[s].moments, fixed_}
                                          : BodyInertia{species[s].mass, Vec3::Zero()});
  return out;
}

int ColloidCoupling::rotational_degrees(const State& state) const {
  int n = 0;
  for (const std::int32_t c : colloids_)
    n += bodies_[static_cast<std::size_t>(state.particles.species[static_cast<std::size_t>(c)])].rotational_degrees;
  return n;
}

Vec3 ColloidCoupling::angular_velocity(const State& s, std::size_t i) const {
  const Particles& p = s.particles;
  if (!p.has_angular_momenta()) return Vec3::Zero();
  return anisodyn::angular_velocity(p.orientation(i), p.angular_momentum(i), bodies_[static_cast<std::size_t>(p.species[i])].moments);
}

void ColloidCoupling::gather_liquid(const Particles& p) {
  const std::size_t n = liquid_.size();
  for (auto* v : {&lx_, &ly_, &lz_, &lvx_, &lvy_, &lvz_}) v->resize(n);
  lid_.resize(n);
  for (std::size_t u = 0; u < n; ++u) {
    const auto i = static_cast<std::size_t>(liquid_[u]);
    lx_[u] = p.x[i], ly_[u] = p.y[i], lz_[u] = p.z[i];
    lvx_[u] = p.vx[i], lvy_[u] = p.vy[i], lvz_[u] = p.vz[i];
    lid_[u] = p.id[i];
  }
  f_liquid_.assign(3 * n, 0.0);
}

void ColloidCoupling::place_sites(const State& s) {
  const Particles& p = s.particles;
  sites_.clear();
  for (const std::int32_t c : colloids_) {
    const auto i = static_cast<std::size_t>(c);
    const ColloidBody& b = bodies_[static_cast<std::size_t>(p.species[i])];
    const Mat3 rot = p.orientation(i).toRotationMatrix();
    const Vec3 v = p.velocity(i), omega = angular_velocity(s, i);
    for (std::size_t k = 0; k < b.sites.size(); ++k) {
      const Vec3 arm = rot * b.sites.offsets[k];
      sites_.push_back({p.position(i) + arm, v + omega.cross(arm), b.sites.radii[k],
                        (static_cast<std::uint64_t>(p.id[i]) << kSiteBits) | k, omega});
    }
  }
}

void ColloidCoupling::operator()(const State& s, BodyForces& out) {
  const Particles& p = s.particles;
  gather_liquid(p);
  place_sites(s);
  f_sites_.assign(sites_.size(), Vec3::Zero());
  t_sites_.assign(sites_.size(), Vec3::Zero());
  const LiquidView view{lx_.data(), ly_.data(), lz_.data(), lvx_.data(), lvy_.data(), lvz_.data(), lid_.data(), liquid_.size()};
  forces_.add(s.box, sites_, view, f_liquid_.data(), f_sites_, t_sites_);
  for (std::size_t u = 0; u < liquid_.size(); ++u)
    out.force[static_cast<std::size_t>(liquid_[u])] += Vec3(f_liquid_[3 * u], f_liquid_[3 * u + 1], f_liquid_[3 * u + 2]);
  std::size_t first = 0;
  for (const std::int32_t c : colloids_) {
    const auto i = static_cast<std::size_t>(c);
    const ColloidBody& b = bodies_[static_cast<std::size_t>(p.species[i])];
    const Wrench w = reduce_site_forces(b.sites, p.orientation(i), std::span<const Vec3>(f_sites_).subspan(first, b.sites.size()),
                                        std::span<const Vec3>(t_sites_).subspan(first, b.sites.size()));
    out.force[i] += w.force;
    out.torque[i] += w.torque;
    first += b.sites.size();
  }
  const SiteLiquidSums& sums = forces_.last_sums();
  out.energy += sums.energy;
  for (const Mat3& w : sums.virial) out.virial += w;
}

ColloidKinetics ColloidCoupling::kinetics(const State& s) const {
  ColloidKinetics k;
  const Particles& p = s.particles;
  for (const std::int32_t c : colloids_) {
    const auto i = static_cast<std::size_t>(c);
    const ColloidBody& b = bodies_[static_cast<std::size_t>(p.species[i])];
    k.translational += b.mass * p.velocity(i).squaredNorm();
    if (p.has_angular_momenta()) k.rotational += p.angular_momentum(i).dot(angular_velocity(s, i));
  }
  return k;
}

}  // namespace anisodyn
