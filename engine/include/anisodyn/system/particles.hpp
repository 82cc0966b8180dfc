#pragma once
// Particle state in structure-of-arrays form. Positions are wrapped into the box; image counters
// recover the unwrapped positions. Orientation quaternions map body to lab.
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

  std::size_t size() const { return x.size(); }

  void add(int species_index, const Vec3& r, const Quat& q, std::int64_t particle_id) {
    x.push_back(r.x()); y.push_back(r.y()); z.push_back(r.z());
    ix.push_back(0); iy.push_back(0); iz.push_back(0);
    qw.push_back(q.w()); qx.push_back(q.x()); qy.push_back(q.y()); qz.push_back(q.z());
    species.push_back(species_index);
    id.push_back(particle_id);
  }

  void pop_back() {
    for (auto* v : {&x, &y, &z, &qw, &qx, &qy, &qz}) v->pop_back();
    for (auto* v : {&ix, &iy, &iz, &species}) v->pop_back();
    id.pop_back();
  }

  Vec3 position(std::size_t i) const { return Vec3(x[i], y[i], z[i]); }
  void set_position(std::size_t i, const Vec3& r) { x[i] = r.x(); y[i] = r.y(); z[i] = r.z(); }
  Int3 image(std::size_t i) const { return Int3(ix[i], iy[i], iz[i]); }
  void set_image(std::size_t i, const Int3& n) { ix[i] = n.x(); iy[i] = n.y(); iz[i] = n.z(); }
  Quat orientation(std::size_t i) const { return Quat(qw[i], qx[i], qy[i], qz[i]); }
  void set_orientation(std::size_t i, const Quat& q) { qw[i] = q.w(); qx[i] = q.x(); qy[i] = q.y(); qz[i] = q.z(); }
};

}  // namespace anisodyn
