#pragma once
// Cuboid with edges (T, W, L) along body x, y, z: {"type": "cuboid", "edges": [T, W, L]}, or a cube
// {"type": "cube", "edge": σ}. Overlaps: OCSI for cuboid–sphere (cuboid_sphere.hpp), the separating
// axis test for cuboid–cuboid (cuboid_cuboid.hpp).
#include <array>
#include <cmath>

#include "anisodyn/geometry/cuboid_cuboid.hpp"
#include "anisodyn/geometry/cuboid_sphere.hpp"
#include "anisodyn/geometry/shape.hpp"
#include "anisodyn/tool/json_config.hpp"

namespace anisodyn {

template <>
struct ShapeTraits<ShapeKind::Cuboid> {
  static constexpr const char* name = "cuboid";
  static constexpr std::array<const char*, 1> aliases{"cube"};
  static constexpr bool anisotropic = true;

  static Shape parse(tool::ConfigNode& n, const std::string& type) {
    if (type == "cube") {
      const double a = n.positive("edge");
      return Shape::cuboid(a, a, a);
    }
    const Vec3 e = n.positive_vec3("edges");
    return Shape::cuboid(e.x(), e.y(), e.z());
  }
  static nlohmann::json spec(const Shape& s) { return {{"type", name}, {"edges", {s.edges.x(), s.edges.y(), s.edges.z()}}}; }
  static double circumradius(const Shape& s) { return 0.5 * s.edges.norm(); }
  static double inscribed_radius(const Shape& s) { return 0.5 * s.edges.minCoeff(); }
  static double volume(const Shape& s) { return s.edges.prod(); }
  /// The bounding box of the grown body (rounded edges and corners filled in).
  static Shape grown(const Shape& s, double t) {
    Shape g = s;
    g.edges.array() += 2.0 * t;
    return g;
  }
  static double swing(const Shape& s, const Mat3& from, const Mat3& to) { return extent_swing(s.half_extents(), from, to); }
  static Vec3 lab_half_extents(const Shape& s, const Mat3& R) { return R.cwiseAbs() * s.half_extents(); }

  static int alignment_axis(const Shape& s) { return extent_alignment_axis(s.edges); }

  static bool cuboid_sphere(const Shape& a, const Mat3& Ra, const Shape& b, const Mat3&, const Vec3& t) {
    return overlap_cuboid_sphere(Ra, a.half_extents(), t, 0.5 * b.diameter);
  }
  static bool cuboid_cuboid(const Shape& a, const Mat3& Ra, const Shape& b, const Mat3& Rb, const Vec3& t) {
    return overlap_cuboid_cuboid(a.half_extents(), Ra, b.half_extents(), Rb, t);
  }
  static constexpr std::array<PairRegistration, 2> overlaps{{{ShapeKind::Cuboid, ShapeKind::Sphere, &cuboid_sphere},
                                                             {ShapeKind::Cuboid, ShapeKind::Cuboid, &cuboid_cuboid}}};
};

}  // namespace anisodyn
