#pragma once
// The species table: shape, mass and infinite-dilution diffusion coefficients in the body frame.
#include <string>
#include <vector>

#include "anisodyn/core/types.hpp"
#include "anisodyn/geometry/shape.hpp"

namespace anisodyn {

struct Species {
  std::string name;
  Shape shape;
  double mass = 1.0;
  Vec3 D_trans = Vec3::Zero();  // translational diffusion along body axes (T, W, L) [length²/τ]
  Vec3 D_rot = Vec3::Zero();    // rotational diffusion about body axes (T, W, L) [rad²/τ]
};

using SpeciesTable = std::vector<Species>;

/// Index of the species called `name`, or −1.
inline int species_index(const SpeciesTable& species, const std::string& name) {
  for (std::size_t s = 0; s < species.size(); ++s)
    if (species[s].name == name) return static_cast<int>(s);
  return -1;
}

}  // namespace anisodyn
