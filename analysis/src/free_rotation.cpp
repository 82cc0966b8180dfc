#include "anisodyn/analysis/free_rotation.hpp"

#include <cmath>

#include "anisodyn/core/error.hpp"

namespace anisodyn::analysis {

std::optional<double> free_axis_rotational_diffusion(const Species& species, int axis) {
  const double a = species.D_rot[(axis + 1) % 3], b = species.D_rot[(axis + 2) % 3];
  if (!(a > 0.0) || std::abs(a - b) > 1e-12 * a) return std::nullopt;
  return a;
}

double free_rod_rotational_diffusion(const Species& species, const std::string& file) {
  const auto d = free_axis_rotational_diffusion(species, 2);
  if (!d)
    throw InputError(file, "/parameters/species/D_rot",
                     "expected the free-rod D_r of species '" + species.name +
                         "': equal positive D_rot about the body axes T and W (the rod axis is L)");
  return *d;
}

}  // namespace anisodyn::analysis
