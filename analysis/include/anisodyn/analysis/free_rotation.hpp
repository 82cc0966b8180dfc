#pragma once
// The free-particle rotational diffusion coefficient that the D_r(φ) of spec 20 §6 is normalised
// by, from a trajectory's species table (the D_rot the engine ran with, infinite dilution).
#include <optional>
#include <string>

#include "anisodyn/system/species.hpp"

namespace anisodyn::analysis {

/// The decay rate of body axis k's Legendre correlations per n(n+1): the D_rot about the two other
/// body axes when they are equal and positive (a top symmetric about k, whose spin about k does not
/// move the axis); none otherwise (then C_n of the axis is no single exponential) or when unset.
std::optional<double> free_axis_rotational_diffusion(const Species& species, int axis);

/// A rod's free D_r (rod axis = body axis L): free_axis_rotational_diffusion(species, 2), or an
/// InputError naming `file` and /parameters/species/D_rot when the species table has none.
double free_rod_rotational_diffusion(const Species& species, const std::string& file);

}  // namespace anisodyn::analysis
