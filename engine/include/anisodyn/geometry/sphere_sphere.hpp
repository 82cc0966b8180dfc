#pragma once
// Sphere–sphere overlap (spec 10 §2.1). Contact counts as overlap.
#include "anisodyn/core/types.hpp"

namespace anisodyn {

/// Overlap of spheres of radii ra and rb whose centres are separated by t (= r_b − r_a,
/// minimum-imaged): |t|² ≤ (ra + rb)².
template <typename Real>
[[nodiscard]] inline bool overlap_sphere_sphere(Real ra, Real rb, Real tx, Real ty, Real tz) noexcept {
  const Real s = ra + rb;
  return tx * tx + ty * ty + tz * tz <= s * s;
}

[[nodiscard]] inline bool overlap_sphere_sphere(double ra, double rb, const Vec3& t) noexcept {
  return overlap_sphere_sphere<double>(ra, rb, t.x(), t.y(), t.z());
}

}  // namespace anisodyn
