#include "anisodyn/system/species_config.hpp"

#include <set>

namespace anisodyn {

namespace {
using ShapeParser = Shape (*)(io::ConfigNode&);

Shape parse_sphere(io::ConfigNode& n) { return Shape::sphere(n.positive("diameter")); }
Shape parse_cuboid(io::ConfigNode& n) {
  const Vec3 e = n.positive_vec3("edges");
  return Shape::cuboid(e.x(), e.y(), e.z());
}
Shape parse_cube(io::ConfigNode& n) {
  const double a = n.positive("edge");
  return Shape::cuboid(a, a, a);
}
Shape parse_spherocylinder(io::ConfigNode& n) {
  return Shape::spherocylinder(n.non_negative("length"), n.positive("diameter"));
}

struct ShapeRegistration {
  const char* type;
  ShapeParser parse;
};
// One line per shape type.
const ShapeRegistration kShapeRegistry[] = {
    {"sphere", &parse_sphere},
    {"cuboid", &parse_cuboid},
    {"cube", &parse_cube},
    {"spherocylinder", &parse_spherocylinder},
};
}  // namespace

Shape parse_shape(io::ConfigNode node) {
  std::vector<std::string> names;
  for (const auto& r : kShapeRegistry) names.emplace_back(r.type);
  const std::string type = node.choice("type", names);
  for (const auto& r : kShapeRegistry)
    if (type == r.type) return r.parse(node);
  node.fail("type", "expected a known shape type");
}

Species parse_species(io::ConfigNode node) {
  Species s;
  s.name = node.string("name");
  if (s.name.empty()) node.fail("name", "expected a non-empty species name");
  s.shape = parse_shape(node.object("shape"));
  s.mass = node.positive("mass", 1.0);
  auto non_negative_vec3 = [&](const std::string& key) {
    const Vec3 v = node.vec3(key, Vec3::Zero());
    if (v.minCoeff() < 0.0) node.fail(key, "expected three non-negative diffusion coefficients (body axes T, W, L)");
    return v;
  };
  s.D_trans = non_negative_vec3("D_trans");
  s.D_rot = non_negative_vec3("D_rot");
  return s;
}

SpeciesTable parse_species_table(io::ConfigNode& parent, const std::string& key) {
  SpeciesTable table;
  std::set<std::string> seen;
  auto nodes = parent.objects(key);
  if (nodes.empty()) parent.fail(key, "expected at least one species");
  for (auto& n : nodes) {
    table.push_back(parse_species(n));
    if (!seen.insert(table.back().name).second) n.fail("name", "expected a unique species name ('" + table.back().name + "' is repeated)");
  }
  return table;
}

nlohmann::json species_to_json(const Species& s) {
  nlohmann::json shape;
  switch (s.shape.kind) {
    case ShapeKind::Sphere: shape = {{"type", "sphere"}, {"diameter", s.shape.diameter}}; break;
    case ShapeKind::Cuboid: shape = {{"type", "cuboid"}, {"edges", {s.shape.edges.x(), s.shape.edges.y(), s.shape.edges.z()}}}; break;
    case ShapeKind::Spherocylinder: shape = {{"type", "spherocylinder"}, {"length", s.shape.length}, {"diameter", s.shape.diameter}}; break;
  }
  return {{"name", s.name}, {"shape", shape}, {"mass", s.mass},
          {"D_trans", {s.D_trans.x(), s.D_trans.y(), s.D_trans.z()}}, {"D_rot", {s.D_rot.x(), s.D_rot.y(), s.D_rot.z()}}};
}

}  // namespace anisodyn
