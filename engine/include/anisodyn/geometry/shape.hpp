#pragma once
// Particle shapes (body frame conventions in each shape's header, geometry/shapes/):
//   sphere          — diameter d;
//   cuboid          — edges (T, W, L) along body x, y, z (T ≤ W ≤ L for board-like particles), so
//                     the rotation-matrix columns are ê_T, ê_W, ê_L; a cube has T = W = L = σ;
//   spherocylinder  — cylinder of length `length` and diameter d, axis along body z, capped by
//                     hemispheres (total length length + d);
//   ellipsoid       — semi-axes (a, b, c) along body x, y, z.
//
// A Shape is a small value: its kind and a few parameters whose meaning the kind's header gives
// (`edges` holds the full extents along the body axes of cuboids and ellipsoids). What a shape can
// do — parse and print its JSON, radii, volume, motion bounds, overlap tests — is written once per
// shape in its header (ShapeTraits) and reached through the members below, which dispatch on the
// kind over the list of geometry/shape_list.hpp.
#include <cmath>
#include <string>

#include <nlohmann/json.hpp>

#include "anisodyn/core/types.hpp"
#include "anisodyn/geometry/shape_list.hpp"

namespace anisodyn {

#define ANISODYN_SHAPE_ENUM(Name) Name,
enum class ShapeKind { ANISODYN_SHAPES(ANISODYN_SHAPE_ENUM) };
#undef ANISODYN_SHAPE_ENUM
#define ANISODYN_SHAPE_COUNT(Name) +1
inline constexpr int kShapeKindCount = 0 ANISODYN_SHAPES(ANISODYN_SHAPE_COUNT);
#undef ANISODYN_SHAPE_COUNT

/// Whether each kind has an orientation (ShapeTraits::anisotropic, shape.cpp): a table, so that the
/// per-trial-move question costs a load, not a call.
extern const bool kShapeAnisotropic[kShapeKindCount];

struct Shape {
  ShapeKind kind = ShapeKind::Sphere;
  Vec3 edges = Vec3::Zero();  // full extents along the body axes: cuboid edges (T, W, L), ellipsoid 2 × semi-axes
  double diameter = 0.0;      // sphere, spherocylinder
  double length = 0.0;        // spherocylinder: cylinder length (cap centres are ±length/2 · ê_z)

  static Shape sphere(double d) { Shape s; s.kind = ShapeKind::Sphere; s.diameter = d; return s; }
  static Shape cuboid(double T, double W, double L) {
    Shape s; s.kind = ShapeKind::Cuboid; s.edges = Vec3(T, W, L); return s;
  }
  static Shape spherocylinder(double length, double d) {
    Shape s; s.kind = ShapeKind::Spherocylinder; s.length = length; s.diameter = d; return s;
  }
  static Shape ellipsoid(const Vec3& semi_axes) {
    Shape s; s.kind = ShapeKind::Ellipsoid; s.edges = 2.0 * semi_axes; return s;
  }

  /// Half the extents along the body axes (cuboid half-edges, ellipsoid semi-axes).
  Vec3 half_extents() const { return 0.5 * edges; }
  /// Radius of the smallest centred sphere containing the body (bounding radius).
  double circumradius() const;
  /// Radius of the largest centred sphere inside the body.
  double inscribed_radius() const;
  double volume() const;
  /// Whether the body has an orientation at all (spheres don't rotate).
  bool is_anisotropic() const { return kShapeAnisotropic[static_cast<int>(kind)]; }
  /// A body of the same kind containing every point within distance t of this one (t ≥ 0).
  Shape grown(double t) const;
  /// Half-extents along the lab axes of the body with rotation matrix R (columns = body axes): the
  /// body lies within ±these of its centre (placement on lattices and in slabs).
  Vec3 lab_half_extents(const Mat3& R) const;
  /// The body axis (0, 1, 2 = body x, y, z) that aligns with a director by default.
  int alignment_axis() const;
  /// The shape as JSON, {"type": name, parameters…}, which parse_shape reads back.
  nlohmann::json spec() const;
};

/// For bodies described by their extents along the body axes (cuboids, ellipsoids): a body point c
/// has |c_k| ≤ half_k, so under a rotation from → to it moves by |(to − from)c| ≤ Σ_k half_k
/// |to_k − from_k|, each axis's swing times the half-extent along it.
inline double extent_swing(const Vec3& half, const Mat3& from, const Mat3& to) {
  double bound = 0.0;
  for (int k = 0; k < 3; ++k) bound += half[k] * (to.col(k) - from.col(k)).norm();
  return bound;
}

/// For the same bodies, the body axis that follows a nematic director: L (body z) for rod-like
/// bodies, T (body x, the short axis) for plate-like ones, split at the geometric mean: W ≤ √(T·L)
/// is rod-like (spec 10 §3.2).
inline int extent_alignment_axis(const Vec3& edges) { return edges.y() <= std::sqrt(edges.x() * edges.z()) ? 2 : 0; }

/// An upper bound on how far any point of the body moves from placement (0, from) to (dr, to)
/// (rotation matrices, columns = body axes): every point of the moved body lies within this
/// distance of the body in its first placement.
double motion_bound(const Shape& shape, const Vec3& dr, const Mat3& from, const Mat3& to);

const char* shape_kind_name(ShapeKind kind);

/// Pairwise hard-body overlap test: takes (a, R_a, b, R_b, r_b − r_a); contact counts as overlap.
using PairOverlapFn = bool (*)(const Shape& a, const Mat3& Ra, const Shape& b, const Mat3& Rb, const Vec3& t);

/// One overlap test of a shape header: the pair of kinds and the kernel, which takes its bodies in
/// that order.
struct PairRegistration {
  ShapeKind first, second;
  PairOverlapFn fn;
};

/// What a shape is and can do; each shape's header specialises it (geometry/shapes/).
template <ShapeKind K>
struct ShapeTraits;

}  // namespace anisodyn
