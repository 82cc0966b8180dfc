#pragma once
// Neighbour lists of hard bodies with a skin: Verlet lists that know the bodies' shapes.
//
// Why: for long particles the centre-distance cut-off (the sum of circumradii) admits about 90
// boards 12×1×1 at η = 0.15, of which a handful can touch; scanning them all is what a trial
// move costs. Here each listed body keeps a reference placement, and the list of the bodies
// whose reference placements, each grown by its species' half-skin t (Shape::grown), overlap.
// While every body lies within t of its reference placement (motion_bound), two bodies that
// overlap are on each other's lists. A body that leaves its skin is re-referenced alone: the
// owner (HardOverlap) drops it from every list and searches its new partners; the others keep
// theirs. This pays when moves are small next to the skin (DMC), not for large MC moves.
//
// This class only stores: references, lists and the skin test. Searching needs the cell lists
// and the overlap kernels, which belong to the owner.
#include <cstdint>
#include <vector>

#include "anisodyn/core/box.hpp"
#include "anisodyn/core/types.hpp"
#include "anisodyn/geometry/shape.hpp"

namespace anisodyn {

class SkinList {
 public:
  /// half_skin[s] > 0 gives species s reference placements; listed[a·ns + b] says whether pairs
  /// of species a and b are listed (both must have a half-skin). Forgets every reference and list.
  void configure(std::vector<double> half_skin, std::vector<char> listed);
  /// Forgets every reference and list, keeping the configuration.
  void clear();

  bool lists(int species) const {
    return species < static_cast<int>(half_skin_.size()) && half_skin_[static_cast<std::size_t>(species)] > 0.0;
  }
  bool pair_listed(int a, int b) const {
    return listed_[static_cast<std::size_t>(a) * half_skin_.size() + static_cast<std::size_t>(b)] != 0;
  }
  bool any() const { return any_; }
  double half_skin(int species) const { return half_skin_[static_cast<std::size_t>(species)]; }
  const std::vector<double>& half_skins() const { return half_skin_; }

  bool has_reference(std::int32_t i) const {
    return static_cast<std::size_t>(i) < reference_r_.size() && referenced_[static_cast<std::size_t>(i)];
  }
  /// Whether body i placed at r (wrapped) with rotation R lies within its species' half-skin of
  /// its reference placement. Requires has_reference(i).
  bool within_skin(std::int32_t i, const Shape& shape, int species, const Box& box, const Vec3& r, const Mat3& R) const {
    const auto ui = static_cast<std::size_t>(i);
    return motion_bound(shape, box.min_image(r - reference_r_[ui]), reference_R_[ui], R) <= half_skin(species);
  }

  /// Makes (r, R) body i's reference placement, removes i from every list and empties its own.
  void reset_reference(std::int32_t i, const Vec3& r, const Mat3& R);
  /// Puts i and j on each other's lists.
  void link(std::int32_t i, std::int32_t j);

  const std::vector<std::int32_t>& neighbors(std::int32_t i) const { return neighbors_[static_cast<std::size_t>(i)]; }
  const Vec3& reference_position(std::int32_t i) const { return reference_r_[static_cast<std::size_t>(i)]; }
  const Mat3& reference_rotation(std::int32_t i) const { return reference_R_[static_cast<std::size_t>(i)]; }

  /// Re-references (for statistics and tests).
  std::int64_t references_reset() const { return resets_; }

 private:
  void grow_to(std::size_t n);

  std::vector<double> half_skin_;
  std::vector<char> listed_;
  bool any_ = false;
  std::vector<Vec3> reference_r_;
  std::vector<Mat3> reference_R_;
  std::vector<char> referenced_;
  std::vector<std::vector<std::int32_t>> neighbors_;
  std::int64_t resets_ = 0;
};

}  // namespace anisodyn
