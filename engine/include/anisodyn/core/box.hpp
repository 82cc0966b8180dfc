#pragma once
// Periodic orthorhombic simulation box: minimum image and wrapping with image counters.
#include <cmath>

#include "anisodyn/core/types.hpp"

namespace anisodyn {

class Box {
 public:
  Box() : Box(Vec3(1, 1, 1)) {}
  explicit Box(const Vec3& edges) { set_edges(edges); }

  const Vec3& edges() const { return L_; }
  const Vec3& inverse_edges() const { return inv_L_; }
  double volume() const { return L_.prod(); }
  double shortest_edge() const { return L_.minCoeff(); }

  void set_edges(const Vec3& edges) {
    L_ = edges;
    inv_L_ = edges.cwiseInverse();
  }

  /// Minimum-image separation vector; exact whenever |d| < L/2 per axis.
  Vec3 min_image(Vec3 d) const {
    for (int k = 0; k < 3; ++k) d[k] -= L_[k] * std::nearbyint(d[k] * inv_L_[k]);
    return d;
  }

  /// Wraps r into [0, L) and counts the box crossings in image, so r + image∘L is unchanged.
  void wrap(Vec3& r, Int3& image) const {
    for (int k = 0; k < 3; ++k) {
      const double shift = std::floor(r[k] * inv_L_[k]);
      r[k] -= shift * L_[k];
      image[k] += static_cast<int>(shift);
      // floor() can leave r == L for tiny negative inputs; keep the half-open interval.
      if (r[k] >= L_[k]) { r[k] -= L_[k]; image[k] += 1; }
    }
  }

  Vec3 unwrap(const Vec3& r, const Int3& image) const {
    return r + image.cast<double>().cwiseProduct(L_);
  }

 private:
  Vec3 L_, inv_L_;
};

}  // namespace anisodyn
