#pragma once
// Extrapolation of shell-model results to zero bead size (the shell-model procedure of HYDRO++:
// each property is computed at several bead radii σ_b and extrapolated linearly to σ_b → 0).
#include <vector>

namespace anisodyn::hydro {

struct ZeroSizeExtrapolation {
  double linear = 0.0;     // intercept of the least-squares line through (σ_b, y)
  double slope = 0.0;
  double quadratic = 0.0;  // intercept of the least-squares parabola: a check on the curvature
};

/// Needs at least three distinct σ_b (InputError otherwise).
ZeroSizeExtrapolation extrapolate_to_zero_size(const std::vector<double>& sigma_b, const std::vector<double>& y);

}  // namespace anisodyn::hydro
