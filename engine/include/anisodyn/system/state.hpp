#pragma once
// A complete configuration: box, species table and particles, with the step and time it belongs to.
#include <cstdint>

#include "anisodyn/core/box.hpp"
#include "anisodyn/system/particles.hpp"
#include "anisodyn/system/species.hpp"

namespace anisodyn {

struct State {
  Box box;
  SpeciesTable species;
  Particles particles;
  std::int64_t step = 0;
  double time = 0.0;

  /// Packing fraction Σ v_i / V.
  double packing_fraction() const {
    double v = 0.0;
    for (auto s : particles.species) v += species[static_cast<std::size_t>(s)].shape.volume();
    return v / box.volume();
  }
};

}  // namespace anisodyn
