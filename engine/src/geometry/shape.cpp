// The shape queries, dispatched on the kind over the shape list (geometry/shape_list.hpp).
#include <vector>

#include "anisodyn/geometry/shapes.hpp"

namespace anisodyn {

namespace {
template <class F>
decltype(auto) with_traits(ShapeKind kind, F&& f) {
  switch (kind) {
#define ANISODYN_SHAPE_CASE(Name) \
  case ShapeKind::Name: return f(ShapeTraits<ShapeKind::Name>{});
    ANISODYN_SHAPES(ANISODYN_SHAPE_CASE)
#undef ANISODYN_SHAPE_CASE
  }
  __builtin_unreachable();
}
}  // namespace

double Shape::circumradius() const { return with_traits(kind, [&](auto t) { return decltype(t)::circumradius(*this); }); }
double Shape::inscribed_radius() const { return with_traits(kind, [&](auto t) { return decltype(t)::inscribed_radius(*this); }); }
double Shape::volume() const { return with_traits(kind, [&](auto t) { return decltype(t)::volume(*this); }); }
#define ANISODYN_SHAPE_ANISOTROPIC(Name) ShapeTraits<ShapeKind::Name>::anisotropic,
const bool kShapeAnisotropic[kShapeKindCount] = {ANISODYN_SHAPES(ANISODYN_SHAPE_ANISOTROPIC)};
#undef ANISODYN_SHAPE_ANISOTROPIC
Shape Shape::grown(double t) const { return with_traits(kind, [&](auto tr) { return decltype(tr)::grown(*this, t); }); }
Vec3 Shape::lab_half_extents(const Mat3& R) const {
  return with_traits(kind, [&](auto t) -> Vec3 { return decltype(t)::lab_half_extents(*this, R); });
}
int Shape::alignment_axis() const { return with_traits(kind, [&](auto t) { return decltype(t)::alignment_axis(*this); }); }
nlohmann::json Shape::spec() const { return with_traits(kind, [&](auto t) { return decltype(t)::spec(*this); }); }

double motion_bound(const Shape& shape, const Vec3& dr, const Mat3& from, const Mat3& to) {
  // A body point at c (body frame) moves by dr + (to − from)c: the translation plus the shape's
  // bound on |(to − from)c| over its points.
  return dr.norm() + with_traits(shape.kind, [&](auto t) { return decltype(t)::swing(shape, from, to); });
}

const char* shape_kind_name(ShapeKind kind) { return with_traits(kind, [](auto t) { return decltype(t)::name; }); }

Shape parse_shape(tool::ConfigNode node) {
  std::vector<std::string> names;
#define ANISODYN_SHAPE_NAMES(Name)                                          \
  names.emplace_back(ShapeTraits<ShapeKind::Name>::name);                  \
  for (const char* alias : ShapeTraits<ShapeKind::Name>::aliases) names.emplace_back(alias);
  ANISODYN_SHAPES(ANISODYN_SHAPE_NAMES)
#undef ANISODYN_SHAPE_NAMES
  const std::string type = node.choice("type", names);
#define ANISODYN_SHAPE_PARSE(Name)                                                           \
  {                                                                                          \
    using T = ShapeTraits<ShapeKind::Name>;                                                  \
    bool match = type == T::name;                                                            \
    for (const char* alias : T::aliases) match = match || type == alias;                     \
    if (match) return T::parse(node, type);                                                  \
  }
  ANISODYN_SHAPES(ANISODYN_SHAPE_PARSE)
#undef ANISODYN_SHAPE_PARSE
  node.fail("type", "expected a known shape type");
}

}  // namespace anisodyn
