#pragma once
// External orientational field on one body axis (spec 10 §5, Mirzad Rafael et al. 2021):
//   βU_i = −(ε_f*/2) [3 (ê_axis,i · ê)² − 1],
// minimum −ε_f* with the axis along ê, maximum +ε_f*/2 perpendicular to it. One-body, so only the
// moved particle contributes to ΔU.
#include "anisodyn/core/types.hpp"

namespace anisodyn {

struct OrientationalField {
  double strength = 0.0;            // ε_f* = βε_f
  int body_axis = 1;                // 0 = T, 1 = W, 2 = L (body x, y, z)
  Vec3 direction = Vec3::UnitX();   // unit vector ê

  bool active() const { return strength != 0.0; }
  /// Reduced energy βU of one particle whose rotation matrix (body axes as columns) is r.
  double energy(const Mat3& r) const {
    const double c = r.col(body_axis).dot(direction);
    return -0.5 * strength * (3.0 * c * c - 1.0);
  }
};

}  // namespace anisodyn
