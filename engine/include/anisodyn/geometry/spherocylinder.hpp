#pragma once
// Spherocylinder overlaps. A spherocylinder is the set of points within `radius` of its axis
// segment {r + s û : |s| ≤ h} (h = cylinder length / 2, û = body z axis), so two bodies overlap iff
// the distance between their segments (or segment and sphere centre) is ≤ the sum of the radii.
// Contact counts as overlap.
//
// Segment–segment distance. With t = r_B − r_A, a = û_A·û_B, b_A = t·û_A, b_B = t·û_B, the squared
// distance f(s, τ) = |t + τ û_B − s û_A|² is a convex quadratic on the rectangle |s| ≤ h_A,
// |τ| ≤ h_B. Its exact minimum is found in three clamped steps:
//   1. s = clamp(s_line), the minimiser of g(s) = min_τ f(s, τ) over the strip |s| ≤ h_A, where
//      s_line = (b_A − a b_B) / |û_A × û_B|² (for exactly parallel axes g is constant: s = 0);
//   2. τ = clamp(a s − b_B), the best τ for that s;
//   3. s = clamp(b_A + a τ), the best s for that τ.
// If step 2 did not clamp, (s, τ) is the strip minimiser and lies inside the rectangle; if it did,
// convexity puts a minimiser on the edge τ = ±h_B, which step 3 finds (step 3 leaves s unchanged
// in the first case). The denominator is |û_A × û_B|² rather than 1 − a², which keeps full relative
// accuracy for nearly parallel axes; a poorly conditioned s_line there only moves s along a
// direction in which g is nearly flat, so the distance stays accurate.
#include <algorithm>

#include "anisodyn/core/types.hpp"

namespace anisodyn {

/// Squared distance between segment A {s û_A : |s| ≤ hA} and segment B {t + τ û_B : |τ| ≤ hB}.
[[nodiscard]] inline double segment_segment_dist2(const Vec3& uA, double hA, const Vec3& uB, double hB,
                                                  const Vec3& t) noexcept {
  const double a = uA.dot(uB), bA = t.dot(uA), bB = t.dot(uB);
  const double den = uA.cross(uB).squaredNorm();
  const double s_line = den > 0.0 ? (bA - a * bB) / den : 0.0;
  double s = std::clamp(s_line, -hA, hA);
  const double tau = std::clamp(a * s - bB, -hB, hB);
  s = std::clamp(bA + a * tau, -hA, hA);
  return (t + tau * uB - s * uA).squaredNorm();
}

/// Squared distance from the point t to the segment {s û : |s| ≤ h}.
[[nodiscard]] inline double point_segment_dist2(const Vec3& u, double h, const Vec3& t) noexcept {
  const double s = std::clamp(t.dot(u), -h, h);
  return (t - s * u).squaredNorm();
}

/// Spherocylinder–spherocylinder overlap. hA, hB: half cylinder lengths; radA, radB: radii;
/// uA, uB: unit axes (lab frame); t = r_B − r_A (minimum-imaged).
[[nodiscard]] inline bool overlap_spherocylinder_spherocylinder(double hA, double radA, const Vec3& uA, double hB,
                                                                double radB, const Vec3& uB,
                                                                const Vec3& t) noexcept {
  const double s = radA + radB;
  return segment_segment_dist2(uA, hA, uB, hB, t) <= s * s;
}

/// Spherocylinder–sphere overlap. h, rad, u: half cylinder length, radius and axis of the
/// spherocylinder; rad_s: sphere radius; t = r_sphere − r_spherocylinder.
[[nodiscard]] inline bool overlap_spherocylinder_sphere(double h, double rad, const Vec3& u, double rad_s,
                                                        const Vec3& t) noexcept {
  const double s = rad + rad_s;
  return point_segment_dist2(u, h, t) <= s * s;
}

}  // namespace anisodyn
