#pragma once
// How far bodies reach along the box axes, on average: what neighbour searches and domain layouts
// size themselves by.
#include <vector>

#include "anisodyn/core/types.hpp"
#include "anisodyn/system/state.hpp"

namespace anisodyn {

/// Per species: the mean lab-box half-extents of its particles in their current orientations (its
/// circumradius along every axis where it has no particles yet).
std::vector<Vec3> mean_lab_half_extents(const State& state);
/// The same from the particles' rotation matrices, where a caller keeps them (one per particle).
std::vector<Vec3> mean_lab_half_extents(const State& state, const std::vector<Mat3>& rotations);

}  // namespace anisodyn
