#pragma once
// Sphere of diameter d: {"type": "sphere", "diameter": d}. No orientation.
#include <array>
#include <cmath>

#include "anisodyn/geometry/shape.hpp"
#include "anisodyn/geometry/sphere_sphere.hpp"
#include "anisodyn/tool/json_config.hpp"

namespace anisodyn {

template <>
struct ShapeTraits<ShapeKind::Sphere> {
  static constexpr const char* name = "sphere";
  static constexpr std::array<const char*, 0> aliases{};
  static constexpr bool anisotropic = false;

  static Shape parse(tool::ConfigNode& n, const std::string&) { return Shape::sphere(n.positive("diameter")); }
  static nlohmann::json spec(const Shape& s) { return {{"type", name}, {"diameter", s.diameter}}; }
  static double circumradius(const Shape& s) { return 0.5 * s.diameter; }
  static double inscribed_radius(const Shape& s) { return 0.5 * s.diameter; }
  static double volume(const Shape& s) { return M_PI * s.diameter * s.diameter * s.diameter / 6.0; }
  static Shape grown(const Shape& s, double t) { return Shape::sphere(s.diameter + 2.0 * t); }  // exact
  static double swing(const Shape&, const Mat3&, const Mat3&) { return 0.0; }  // a sphere only translates
  static Vec3 lab_half_extents(const Shape& s, const Mat3&) { return Vec3::Constant(0.5 * s.diameter); }
  static int alignment_axis(const Shape&) { return 2; }  // no orientation: any axis

  static bool sphere_sphere(const Shape& a, const Mat3&, const Shape& b, const Mat3&, const Vec3& t) {
    return overlap_sphere_sphere(0.5 * a.diameter, 0.5 * b.diameter, t);
  }
  static constexpr std::array<PairRegistration, 1> overlaps{{{ShapeKind::Sphere, ShapeKind::Sphere, &sphere_sphere}}};
};

}  // namespace anisodyn
