#pragma once
// Ellipsoid with semi-axes (a, b, c) along body x, y, z: {"type": "ellipsoid", "semi_axes": [a, b, c]}
// (the form anisodyn-hydro reads too). Stored as Shape::edges = 2 (a, b, c). Overlaps: the
// Perram–Wertheim contact function for ellipsoid–ellipsoid and ellipsoid–sphere
// (ellipsoid_overlap.hpp).
#include <array>
#include <cmath>

#include "anisodyn/geometry/ellipsoid_overlap.hpp"
#include "anisodyn/geometry/shape.hpp"
#include "anisodyn/tool/json_config.hpp"

namespace anisodyn {

template <>
struct ShapeTraits<ShapeKind::Ellipsoid> {
  static constexpr const char* name = "ellipsoid";
  static constexpr std::array<const char*, 0> aliases{};
  static constexpr bool anisotropic = true;

  static Shape parse(tool::ConfigNode& n, const std::string&) { return Shape::ellipsoid(n.positive_vec3("semi_axes")); }
  static nlohmann::json spec(const Shape& s) {
    const Vec3 a = s.half_extents();
    return {{"type", name}, {"semi_axes", {a.x(), a.y(), a.z()}}};
  }
  static double circumradius(const Shape& s) { return 0.5 * s.edges.maxCoeff(); }
  static double inscribed_radius(const Shape& s) { return 0.5 * s.edges.minCoeff(); }
  static double volume(const Shape& s) { return M_PI * s.edges.prod() / 6.0; }  // (4/3)π abc
  /// The body scaled by 1 + t/a_min about its centre. Its support function is (1 + t/a_min) h(u)
  /// ≥ h(u) + t because h(u) ≥ a_min, so it contains every point within t of the body. (Adding t
  /// to each semi-axis does not: its support function is at most h(u) + t.)
  static Shape grown(const Shape& s, double t) {
    return Shape::ellipsoid(s.half_extents() * (1.0 + t / (0.5 * s.edges.minCoeff())));
  }
  static double swing(const Shape& s, const Mat3& from, const Mat3& to) { return extent_swing(s.half_extents(), from, to); }
  /// Exact: the support of the ellipsoid along lab axis i is sqrt(Σ_k (R_ik a_k)²).
  static Vec3 lab_half_extents(const Shape& s, const Mat3& R) {
    return (R * s.half_extents().asDiagonal()).rowwise().norm();
  }

  static int alignment_axis(const Shape& s) { return extent_alignment_axis(s.edges); }

  static bool ellipsoid_sphere(const Shape& a, const Mat3& Ra, const Shape& b, const Mat3&, const Vec3& t) {
    return overlap_ellipsoid_sphere(a.half_extents(), Ra, 0.5 * b.diameter, t);
  }
  static bool ellipsoid_ellipsoid(const Shape& a, const Mat3& Ra, const Shape& b, const Mat3& Rb, const Vec3& t) {
    return overlap_ellipsoid_ellipsoid(a.half_extents(), Ra, b.half_extents(), Rb, t);
  }
  static constexpr std::array<PairRegistration, 2> overlaps{{{ShapeKind::Ellipsoid, ShapeKind::Sphere, &ellipsoid_sphere},
                                                             {ShapeKind::Ellipsoid, ShapeKind::Ellipsoid, &ellipsoid_ellipsoid}}};
};

}  // namespace anisodyn
