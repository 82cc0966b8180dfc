#pragma once
// Particle state in structure-of-arrays form. Positions are wrapped into the box; image counters
// recover the unwrapped positions. Orientation quaternions map body to lab.
//
// Velocities and angular momenta are optional, for engines with inertia (MD-type: DPD, LB): a
// state carries them when an engine asks for them (carry_velocities / carry_angular_momenta), and
// then every particle has them. Hard-particle MC and DMC states carry none. Both are lab-frame
// vectors; the angular momentum is about the particle's centre.
#include <cstdint>
#include <vector>

#include "anisodyn/core/types.hpp"

namespace anisodyn {

struct Particles {
  std::vector<double> x, y, z;
  std::vector<std::int32_t> ix, iy, iz;
  std::vector<double> qw, qx, qy, qz;
  std::vector<std::int32_t> species;
  std::vector<std::int64_t> id;
  std::vector<double> vx, vy, vz;  // only when has_velocities()
  std::vector<double> lx, ly, lz;  // only when has_angular_momenta()

  std::size_t size() const { return x.size(); }
  bool has_velocities() const { return velocities_; }
  bool has_angular_momenta() const { return angular_momenta_; }
  /// From now on every particle has a velocity (zero for those already present).
  void carry_velocities() {
    velocities_ = true;
    for (auto* v : {&vx, &vy, &vz}) v->resize(size(), 0.0);
  }
  /// From now on every particle has an angular momentum (zero for those already present).
  void carry_angular_momenta() {
    angular_momenta_ = true;
    for (auto* v : {&lx, &ly, &lz}) v->resize(size(), 0.0);
  }

  /// Appends a particle (at rest, if the state carries velocities or angular momenta).
  void add(int species_index, const Vec3& r, const Quat& q, std::int64_t particle_id) {
    x.push_back(r.x()); y.push_back(r.y()); z.push_back(r.z());
    ix.push_back(0); iy.push_back(0); iz.push_back(0);
    qw.push_back(q.w()); qx.push_back(q.x()); qy.push_back(q.y()); qz.push_back(q.z());
    species.push_back(species_index);
    id.push_back(particle_id);
    if (velocities_)
      for (auto* v : {&vx, &vy, &vz}) v->push_back(0.0);
    if (angular_momenta_)
      for (auto* v : {&lx, &ly, &lz}) v->push_back(0.0);
  }

  /// Makes these the particles `indices` of `from`, in that order: positions, images,
  /// orientations, species and ids (at rest, if this state carries velocities or angular
  /// momenta). Keeps the arrays' memory: domain sweeps copy their slabs every cycle.
  void assign_subset(const Particles& from, const std::vector<std::int32_t>& indices) {
    const std::size_t n = indices.size();
    auto pick = [&](auto& to, const auto& source) {
      to.resize(n);
      for (std::size_t k = 0; k < n; ++k) to[k] = source[static_cast<std::size_t>(indices[k])];
    };
    pick(x, from.x); pick(y, from.y); pick(z, from.z);
    pick(ix, from.ix); pick(iy, from.iy); pick(iz, from.iz);
    pick(qw, from.qw); pick(qx, from.qx); pick(qy, from.qy); pick(qz, from.qz);
    pick(species, from.species);
    pick(id, from.id);
    if (velocities_)
      for (auto* v : {&vx, &vy, &vz}) v->assign(n, 0.0);
    if (angular_momenta_)
      for (auto* v : {&lx, &ly, &lz}) v->assign(n, 0.0);
  }

  void pop_back() {
    for (auto* v : {&x, &y, &z, &qw, &qx, &qy, &qz}) v->pop_back();
    for (auto* v : {&ix, &iy, &iz, &species}) v->pop_back();
    id.pop_back();
    if (velocities_)
      for (auto* v : {&vx, &vy, &vz}) v->pop_back();
    if (angular_momenta_)
      for (auto* v : {&lx, &ly, &lz}) v->pop_back();
  }

  Vec3 position(std::size_t i) const { return Vec3(x[i], y[i], z[i]); }
  void set_position(std::size_t i, const Vec3& r) { x[i] = r.x(); y[i] = r.y(); z[i] = r.z(); }
  Int3 image(std::size_t i) const { return Int3(ix[i], iy[i], iz[i]); }
  void set_image(std::size_t i, const Int3& n) { ix[i] = n.x(); iy[i] = n.y(); iz[i] = n.z(); }
  Quat orientation(std::size_t i) const { return Quat(qw[i], qx[i], qy[i], qz[i]); }
  void set_orientation(std::size_t i, const Quat& q) { qw[i] = q.w(); qx[i] = q.x(); qy[i] = q.y(); qz[i] = q.z(); }
  Vec3 velocity(std::size_t i) const { return Vec3(vx[i], vy[i], vz[i]); }
  void set_velocity(std::size_t i, const Vec3& v) { vx[i] = v.x(); vy[i] = v.y(); vz[i] = v.z(); }
  Vec3 angular_momentum(std::size_t i) const { return Vec3(lx[i], ly[i], lz[i]); }
  void set_angular_momentum(std::size_t i, const Vec3& l) { lx[i] = l.x(); ly[i] = l.y(); lz[i] = l.z(); }

 private:
  bool velocities_ = false, angular_momenta_ = false;
};

}  // namespace anisodyn
