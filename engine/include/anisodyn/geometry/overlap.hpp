#pragma once
// Generic hard-body overlap test dispatching on the pair of shape kinds.
//
// Conventions (docs/geometry.md):
//   - Ra, Rb are rotation matrices whose columns are the body axes in the lab frame (ignored for
//     spheres);
//   - t = r_b − r_a, already minimum-imaged;
//   - contact counts as overlap.
//
// Every supported pair is ONE line of kPairRegistry below: (first kind, second kind, kernel taking
// its arguments in that order). The dispatch table is built from it at compile time and also
// serves the swapped order (b, a) by exchanging the bodies and flipping t. Pairs without a line
// (e.g. cuboid–spherocylinder) are unsupported: overlap_supported() reports them and overlap()
// throws std::invalid_argument for them.
#include <array>

#include "anisodyn/core/types.hpp"
#include "anisodyn/geometry/cuboid_cuboid.hpp"
#include "anisodyn/geometry/cuboid_sphere.hpp"
#include "anisodyn/geometry/shape.hpp"
#include "anisodyn/geometry/sphere_sphere.hpp"
#include "anisodyn/geometry/spherocylinder.hpp"

namespace anisodyn {

using PairOverlapFn = bool (*)(const Shape& a, const Mat3& Ra, const Shape& b, const Mat3& Rb, const Vec3& t);

namespace overlap_detail {

inline bool sphere_sphere(const Shape& a, const Mat3&, const Shape& b, const Mat3&, const Vec3& t) {
  return overlap_sphere_sphere(0.5 * a.diameter, 0.5 * b.diameter, t);
}
inline bool cuboid_sphere(const Shape& a, const Mat3& Ra, const Shape& b, const Mat3&, const Vec3& t) {
  return overlap_cuboid_sphere(Ra, a.half_extents(), t, 0.5 * b.diameter);
}
inline bool cuboid_cuboid(const Shape& a, const Mat3& Ra, const Shape& b, const Mat3& Rb, const Vec3& t) {
  return overlap_cuboid_cuboid(a.half_extents(), Ra, b.half_extents(), Rb, t);
}
inline bool spherocylinder_spherocylinder(const Shape& a, const Mat3& Ra, const Shape& b, const Mat3& Rb,
                                          const Vec3& t) {
  return overlap_spherocylinder_spherocylinder(0.5 * a.length, 0.5 * a.diameter, Ra.col(2), 0.5 * b.length,
                                               0.5 * b.diameter, Rb.col(2), t);
}
inline bool spherocylinder_sphere(const Shape& a, const Mat3& Ra, const Shape& b, const Mat3&, const Vec3& t) {
  return overlap_spherocylinder_sphere(0.5 * a.length, 0.5 * a.diameter, Ra.col(2), 0.5 * b.diameter, t);
}

struct PairRegistration {
  ShapeKind first, second;
  PairOverlapFn fn;  // takes (first, R_first, second, R_second, r_second − r_first)
};

// clang-format off
inline constexpr PairRegistration kPairRegistry[] = {
    {ShapeKind::Sphere,         ShapeKind::Sphere,         &sphere_sphere},
    {ShapeKind::Cuboid,         ShapeKind::Sphere,         &cuboid_sphere},
    {ShapeKind::Cuboid,         ShapeKind::Cuboid,         &cuboid_cuboid},
    {ShapeKind::Spherocylinder, ShapeKind::Spherocylinder, &spherocylinder_spherocylinder},
    {ShapeKind::Spherocylinder, ShapeKind::Sphere,         &spherocylinder_sphere},
};
// clang-format on

// `supported` is kept separately from fn because comparing a function pointer with nullptr is not a
// constant expression under -fsanitize (ANISODYN_SANITIZE), which would break the constexpr table.
struct DispatchEntry {
  PairOverlapFn fn = nullptr;
  bool supported = false;
  bool swap = false;  // registered as (b, a): call fn(b, Rb, a, Ra, −t)
};
using DispatchTable = std::array<std::array<DispatchEntry, kShapeKindCount>, kShapeKindCount>;

constexpr DispatchTable make_dispatch_table() {
  DispatchTable table{};
  for (const PairRegistration& r : kPairRegistry) {
    table[static_cast<int>(r.first)][static_cast<int>(r.second)] = {r.fn, true, false};
    if (r.first != r.second) table[static_cast<int>(r.second)][static_cast<int>(r.first)] = {r.fn, true, true};
  }
  return table;
}

constexpr bool registry_is_unambiguous() {
  for (const PairRegistration& r : kPairRegistry) {
    int n = 0;
    for (const PairRegistration& s : kPairRegistry)
      n += (s.first == r.first && s.second == r.second) || (s.first == r.second && s.second == r.first);
    if (n != 1) return false;
  }
  return true;
}
static_assert(registry_is_unambiguous(), "each unordered shape pair must be registered exactly once");

inline constexpr DispatchTable kDispatchTable = make_dispatch_table();

[[noreturn]] void throw_unsupported_pair(ShapeKind a, ShapeKind b);

}  // namespace overlap_detail

/// Whether overlap() has a kernel for this pair of kinds (in either order).
[[nodiscard]] constexpr bool overlap_supported(ShapeKind a, ShapeKind b) noexcept {
  return overlap_detail::kDispatchTable[static_cast<int>(a)][static_cast<int>(b)].supported;
}

/// Hard-body overlap of body a (shape a, orientation Ra) and body b at relative position
/// t = r_b − r_a (minimum-imaged). Contact counts as overlap. Throws std::invalid_argument for a
/// pair without a kernel (check overlap_supported() when validating input).
[[nodiscard]] inline bool overlap(const Shape& a, const Mat3& Ra, const Shape& b, const Mat3& Rb, const Vec3& t) {
  const overlap_detail::DispatchEntry& e =
      overlap_detail::kDispatchTable[static_cast<int>(a.kind)][static_cast<int>(b.kind)];
  if (!e.supported) [[unlikely]]
    overlap_detail::throw_unsupported_pair(a.kind, b.kind);
  if (e.swap) return e.fn(b, Rb, a, Ra, Vec3(-t));
  return e.fn(a, Ra, b, Rb, t);
}

}  // namespace anisodyn
