#pragma once
// Mirror symmetry of a bead model about the body-frame coordinate planes.
//
// A shell model of a cuboid, spheroid or cylinder is unchanged by the reflections x → −x, y → −y,
// z → −z (and their products). These eight sign flips form the group Z₂³; the subgroup that maps
// the bead set onto itself lets the 3N×3N mobility problem split into independent blocks, one per
// symmetry class of rigid motion, each of size ≈ 3N/|group| (rigid_body_resistance.hpp).
#include <array>
#include <vector>

#include "anisodyn/core/types.hpp"

namespace anisodyn::hydro {

/// A reflection through some of the coordinate planes: diag(sign).
struct MirrorOperation {
  Vec3 sign;                        // each ±1
  std::vector<std::size_t> image;   // image[i] = index of the bead at diag(sign)·r_i
};

/// Beads grouped into orbits under the symmetry group.
struct BeadOrbit {
  std::size_t representative;
  std::vector<int> stabilizer;  // indices into MirrorSymmetry::operations that fix the representative
};

struct MirrorSymmetry {
  std::vector<MirrorOperation> operations;  // the group; operations[0] is the identity
  std::vector<BeadOrbit> orbits;
};

/// The subgroup of the eight coordinate-plane reflections that maps `beads` onto itself (positions
/// matched to `tolerance`), with the bead orbits. Pass use_symmetry = false for the trivial group.
MirrorSymmetry find_mirror_symmetry(const std::vector<Vec3>& beads, double tolerance, bool use_symmetry = true);

}  // namespace anisodyn::hydro
