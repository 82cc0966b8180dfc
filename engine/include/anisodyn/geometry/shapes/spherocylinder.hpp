#pragma once
// Spherocylinder: a cylinder of length `length` and diameter d along body z, capped by hemispheres
// (total length length + d): {"type": "spherocylinder", "length": L, "diameter": d}. It is the set
// of points within d/2 of its axis segment, so its tests are segment distances (spherocylinder.hpp).
#include <array>
#include <cmath>

#include "anisodyn/geometry/shape.hpp"
#include "anisodyn/geometry/spherocylinder.hpp"
#include "anisodyn/tool/json_config.hpp"

namespace anisodyn {

template <>
struct ShapeTraits<ShapeKind::Spherocylinder> {
  static constexpr const char* name = "spherocylinder";
  static constexpr std::array<const char*, 0> aliases{};
  static constexpr bool anisotropic = true;

  static Shape parse(tool::ConfigNode& n, const std::string&) {
    return Shape::spherocylinder(n.non_negative("length"), n.positive("diameter"));
  }
  static nlohmann::json spec(const Shape& s) { return {{"type", name}, {"length", s.length}, {"diameter", s.diameter}}; }
  static double circumradius(const Shape& s) { return 0.5 * (s.length + s.diameter); }
  static double inscribed_radius(const Shape& s) { return 0.5 * s.diameter; }
  static double volume(const Shape& s) {
    return M_PI * s.diameter * s.diameter * s.length / 4.0 + M_PI * s.diameter * s.diameter * s.diameter / 6.0;
  }
  static Shape grown(const Shape& s, double t) { return Shape::spherocylinder(s.length, s.diameter + 2.0 * t); }  // exact
  /// Only the axis segment's end points count: the body is the segment grown by its radius.
  static double swing(const Shape& s, const Mat3& from, const Mat3& to) {
    return 0.5 * s.length * (to.col(2) - from.col(2)).norm();
  }
  static Vec3 lab_half_extents(const Shape& s, const Mat3& R) {
    return 0.5 * s.length * R.col(2).cwiseAbs() + Vec3::Constant(0.5 * s.diameter);
  }

  static int alignment_axis(const Shape&) { return 2; }  // the rod axis
  static bool spherocylinder_spherocylinder(const Shape& a, const Mat3& Ra, const Shape& b, const Mat3& Rb, const Vec3& t) {
    return overlap_spherocylinder_spherocylinder(0.5 * a.length, 0.5 * a.diameter, Ra.col(2), 0.5 * b.length,
                                                 0.5 * b.diameter, Rb.col(2), t);
  }
  static bool spherocylinder_sphere(const Shape& a, const Mat3& Ra, const Shape& b, const Mat3&, const Vec3& t) {
    return overlap_spherocylinder_sphere(0.5 * a.length, 0.5 * a.diameter, Ra.col(2), 0.5 * b.diameter, t);
  }
  static constexpr std::array<PairRegistration, 2> overlaps{
      {{ShapeKind::Spherocylinder, ShapeKind::Sphere, &spherocylinder_sphere},
       {ShapeKind::Spherocylinder, ShapeKind::Spherocylinder, &spherocylinder_spherocylinder}}};
};

}  // namespace anisodyn
