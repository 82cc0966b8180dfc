#pragma once
// O(N²) overlap search over a whole configuration with the generic dispatcher: the reference
// that the neighbour searches (cell grids, skin lists) must agree with.
#include <cstddef>

#include "anisodyn/geometry/overlap.hpp"
#include "anisodyn/system/state.hpp"

namespace anisodyn::testing_support {

/// Whether particle i placed at r (wrapped) with rotation rot overlaps any other particle of s.
inline bool brute_force_overlaps(const State& s, std::size_t i, const Vec3& r, const Mat3& rot) {
  const Shape& a = s.species[static_cast<std::size_t>(s.particles.species[i])].shape;
  for (std::size_t j = 0; j < s.particles.size(); ++j) {
    if (j == i) continue;
    const Shape& b = s.species[static_cast<std::size_t>(s.particles.species[j])].shape;
    const Vec3 t = s.box.min_image(s.particles.position(j) - r);
    if (overlap(a, rot, b, s.particles.orientation(j).toRotationMatrix(), t)) return true;
  }
  return false;
}

}  // namespace anisodyn::testing_support
