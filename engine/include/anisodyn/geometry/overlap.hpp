#pragma once
// Generic hard-body overlap test dispatching on the pair of shape kinds.
//
// Conventions (docs/geometry.md):
//   - Ra, Rb are rotation matrices whose columns are the body axes in the lab frame (ignored for
//     spheres);
//   - t = r_b − r_a, already minimum-imaged;
//   - contact counts as overlap.
//
// Every supported pair is one line of a shape header's `overlaps` (geometry/shapes/): (first kind,
// second kind, kernel taking its arguments in that order). kPairRegistry gathers them over the
// shape list at compile time; the dispatch table built from it also serves the swapped order
// (b, a) by exchanging the bodies and flipping t. Pairs without a line (e.g. cuboid–spherocylinder)
// are unsupported: overlap_supported() reports them and overlap() throws std::invalid_argument.
#include <array>

#include "anisodyn/core/types.hpp"
#include "anisodyn/geometry/shapes.hpp"

namespace anisodyn {

namespace overlap_detail {

// `supported` is kept separately from fn because comparing a function pointer with nullptr is not a
// constant expression under -fsanitize (ANISODYN_SANITIZE), which would break the constexpr table.
struct DispatchEntry {
  PairOverlapFn fn = nullptr;
  bool supported = false;
  bool swap = false;  // registered as (b, a): call fn(b, Rb, a, Ra, −t)
};
using DispatchTable = std::array<std::array<DispatchEntry, kShapeKindCount>, kShapeKindCount>;

// Every shape's overlap tests, in the order of the shape list.
#define ANISODYN_SHAPE_PAIR_COUNT(Name) +ShapeTraits<ShapeKind::Name>::overlaps.size()
inline constexpr std::size_t kPairCount = 0 ANISODYN_SHAPES(ANISODYN_SHAPE_PAIR_COUNT);
#undef ANISODYN_SHAPE_PAIR_COUNT

constexpr std::array<PairRegistration, kPairCount> collect_pair_registrations() {
  std::array<PairRegistration, kPairCount> all{};
  std::size_t n = 0;
#define ANISODYN_SHAPE_PAIRS(Name) \
  for (const PairRegistration& r : ShapeTraits<ShapeKind::Name>::overlaps) all[n++] = r;
  ANISODYN_SHAPES(ANISODYN_SHAPE_PAIRS)
#undef ANISODYN_SHAPE_PAIRS
  return all;
}
inline constexpr std::array<PairRegistration, kPairCount> kPairRegistry = collect_pair_registrations();

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
