#pragma once
// Starting states for the hard-particle tests: one species on a lattice at a packing fraction
// (aligned along the shape's default axis), and an ideal gas of points.
#include "anisodyn/config/builder.hpp"
#include "anisodyn/core/rng.hpp"
#include "anisodyn/system/state.hpp"

namespace anisodyn::testing_support {

/// n particles of one species on a lattice at packing fraction eta in a cubic box, aligned.
inline State lattice_of(const Species& species, std::size_t n, double eta, Rng& rng) {
  State s;
  s.species.push_back(species);
  s.box = Box(box_edges_for_packing_fraction(s.species, {n}, eta, Vec3::Ones()));
  place_on_lattice(s, PlacementRequest{{n}, {OrientationRule{}}, 10000}, rng);
  return s;
}

/// n points (spheres too small ever to meet) uniform in a cube of the given edge: an ideal gas.
inline State gas_of_points(std::size_t n, double edge) {
  State s;
  s.box = Box(Vec3::Constant(edge));
  s.species.push_back(Species{"point", Shape::sphere(1e-9), 1.0, Vec3::Zero(), Vec3::Zero()});
  Rng rng(99, 0);
  for (std::size_t i = 0; i < n; ++i)
    s.particles.add(0, Vec3(rng.uniform() * edge, rng.uniform() * edge, rng.uniform() * edge), Quat::Identity(), static_cast<std::int64_t>(i));
  return s;
}

}  // namespace anisodyn::testing_support
