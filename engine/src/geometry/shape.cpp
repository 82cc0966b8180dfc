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

const char* shape_kind_name(ShapeKind kind) {
  switch (kind) {
    case ShapeKind::Sphere: return "sphere";
    case ShapeKind::Cuboid: return "cuboid";
    case ShapeKind::Spherocylinder: return "spherocylinder";
  }
  return "unknown";
}

}  // namespace anisodyn
