#include "anisodyn/geometry/shape.hpp"

#include <cmath>

namespace anisodyn {

double Shape::circumradius() const {
  switch (kind) {
    case ShapeKind::Sphere: return 0.5 * diameter;
    case ShapeKind::Cuboid: return 0.5 * edges.norm();
    case ShapeKind::Spherocylinder: return 0.5 * (length + diameter);
  }
  return 0.0;
}

double Shape::inscribed_radius() const {
  switch (kind) {
    case ShapeKind::Sphere: return 0.5 * diameter;
    case ShapeKind::Cuboid: return 0.5 * edges.minCoeff();
    case ShapeKind::Spherocylinder: return 0.5 * diameter;
  }
  return 0.0;
}

double Shape::volume() const {
  switch (kind) {
    case ShapeKind::Sphere: return M_PI * diameter * diameter * diameter / 6.0;
    case ShapeKind::Cuboid: return edges.prod();
    case ShapeKind::Spherocylinder:
      return M_PI * diameter * diameter * length / 4.0 + M_PI * diameter * diameter * diameter / 6.0;
  }
  return 0.0;
}

Shape Shape::grown(double t) const {
  Shape s = *this;
  if (kind == ShapeKind::Cuboid) s.edges.array() += 2.0 * t;
  else s.diameter += 2.0 * t;
  return s;
}

double motion_bound(const Shape& shape, const Vec3& dr, const Mat3& from, const Mat3& to) {
  // A body point at c (body frame) moves by dr + (to − from)c, and |(to − from)c| is at most
  // Σ_k |c_k| |to_k − from_k| over the body axes k: the translation plus each axis's swing
  // times the body's half-extent along it. A spherocylinder is its axis segment grown by its
  // radius, so only the segment's end points count; a sphere only translates.
  double bound = dr.norm();
  switch (shape.kind) {
    case ShapeKind::Sphere: break;
    case ShapeKind::Cuboid:
      for (int k = 0; k < 3; ++k) bound += 0.5 * shape.edges[k] * (to.col(k) - from.col(k)).norm();
      break;
    case ShapeKind::Spherocylinder: bound += 0.5 * shape.length * (to.col(2) - from.col(2)).norm(); break;
  }
  return bound;
}

const char* shape_kind_name(ShapeKind kind) {
  switch (kind) {
    case ShapeKind::Sphere: return "sphere";
    case ShapeKind::Cuboid: return "cuboid";
    case ShapeKind::Spherocylinder: return "spherocylinder";
  }
  return "unknown";
}

}  // namespace anisodyn
