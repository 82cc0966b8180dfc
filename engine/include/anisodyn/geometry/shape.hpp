#pragma once
// Particle shapes. Body frame conventions:
//   sphere          — diameter d;
//   cuboid          — edges (T, W, L) along body x, y, z (T ≤ W ≤ L for board-like particles), so
//                     the rotation-matrix columns are ê_T, ê_W, ê_L; a cube has T = W = L = σ;
//   spherocylinder  — cylinder of length `length` and diameter d, axis along body z, capped by
//                     hemispheres (total length length + d).
#include <string>

#include "anisodyn/core/types.hpp"

namespace anisodyn {

enum class ShapeKind { Sphere = 0, Cuboid = 1, Spherocylinder = 2 };
inline constexpr int kShapeKindCount = 3;

struct Shape {
  ShapeKind kind = ShapeKind::Sphere;
  Vec3 edges = Vec3::Zero();  // cuboid: full edge lengths (T, W, L)
  double diameter = 0.0;      // sphere, spherocylinder
  double length = 0.0;        // spherocylinder: cylinder length (cap centres are ±length/2 · ê_z)

  static Shape sphere(double d) { Shape s; s.kind = ShapeKind::Sphere; s.diameter = d; return s; }
  static Shape cuboid(double T, double W, double L) {
    Shape s; s.kind = ShapeKind::Cuboid; s.edges = Vec3(T, W, L); return s;
  }
  static Shape spherocylinder(double length, double d) {
    Shape s; s.kind = ShapeKind::Spherocylinder; s.length = length; s.diameter = d; return s;
  }

  Vec3 half_extents() const { return 0.5 * edges; }
  /// Radius of the smallest centred sphere containing the body (bounding radius).
  double circumradius() const;
  /// Radius of the largest centred sphere inside the body.
  double inscribed_radius() const;
  double volume() const;
  /// Whether the body has an orientation at all (spheres don't rotate).
  bool is_anisotropic() const { return kind != ShapeKind::Sphere; }
  /// A body of the same kind containing every point within distance t of this one (t ≥ 0):
  /// exactly that set for spheres and spherocylinders, its bounding box for cuboids.
  Shape grown(double t) const;
};

/// An upper bound on how far any point of the body moves from placement (0, from) to (dr, to)
/// (rotation matrices, columns = body axes): every point of the moved body lies within this
/// distance of the body in its first placement.
double motion_bound(const Shape& shape, const Vec3& dr, const Mat3& from, const Mat3& to);

const char* shape_kind_name(ShapeKind kind);

}  // namespace anisodyn
