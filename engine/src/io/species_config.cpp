#include "anisodyn/io/species_config.hpp"

#include <filesystem>
#include <set>

#include "anisodyn/core/error.hpp"
#include "anisodyn/geometry/shapes.hpp"
#include "anisodyn/io/species_file.hpp"

namespace anisodyn {

std::string resolve_data_path(const std::string& path, const std::string& relative_to_file) {
  if (std::filesystem::path(path).is_absolute() || std::filesystem::exists(path)) return path;
  const auto beside = std::filesystem::path(relative_to_file).parent_path() / path;
  return std::filesystem::exists(beside) ? beside.string() : path;
}

bool same_shape(const Shape& a, const Shape& b) {
  auto close = [](double x, double y) { return std::abs(x - y) <= 1e-9 * std::max({1.0, std::abs(x), std::abs(y)}); };
  return a.kind == b.kind && close(a.diameter, b.diameter) && close(a.length, b.length) &&
         close(a.edges.x(), b.edges.x()) && close(a.edges.y(), b.edges.y()) && close(a.edges.z(), b.edges.z());
}

namespace {

/// The diffusion_from files, in the order they are searched.
std::vector<std::string> diffusion_files(tool::ConfigNode& node) {
  if (node.has("file") && node.raw().at("file").is_array()) {
    std::vector<std::string> files = node.strings("file");
    if (files.empty()) node.fail("file", "expected a species file or a non-empty list of them");
    return files;
  }
  return {node.string("file")};
}

}  // namespace

DiffusionFromFile read_diffusion_from(tool::ConfigNode node, const std::optional<Shape>& expected_shape) {
  const std::vector<std::string> files = diffusion_files(node);
  const std::string name = node.string("species");
  const nlohmann::json* found = nullptr;
  nlohmann::json doc;
  std::string file, searched;
  for (std::size_t k = 0; k < files.size() && !found; ++k) {
    file = resolve_data_path(files[k], node.file());
    const std::string key = files.size() > 1 ? "file[" + std::to_string(k) + "]" : "file";
    try {
      doc = io::read_species_file(file);
    } catch (const InputError& e) {
      // A missing file is an error even where a later one would do: a typo must not fall through.
      throw InputError(node.file(), node.child_path(key),
                       std::string("expected a readable species file written by anisodyn-hydro (") + e.what() + ")");
    }
    try {
      found = &io::species_file_entry(doc, file, name);
    } catch (const InputError& e) {
      searched += std::string(searched.empty() ? "" : "; ") + e.what();
    }
  }
  if (!found) node.fail("species", "expected a species of " + (files.size() > 1 ? "one of the files" : file) + " (" + searched + ")");
  const nlohmann::json entry = *found;
  tool::ConfigNode e(entry, file, "species[" + name + "]");
  e.mark_used("source");
  DiffusionFromFile d;
  d.shape = parse_shape(e.object("shape"));
  d.D_trans = e.positive_vec3("D_trans");
  d.D_rot = e.vec3("D_rot");
  d.origin = {{"file", file}, {"species", name}};
  if (entry.contains("source")) d.origin["source"] = entry.at("source");
  if (expected_shape && !same_shape(*expected_shape, d.shape))
    node.fail("species", "expected the same shape as this species; '" + name + "' in " + file + " is " +
                             entry.at("shape").dump());
  return d;
}

DiffusionSpec parse_diffusion(tool::ConfigNode& node, const std::optional<Shape>& expected_shape) {
  DiffusionSpec d;
  if (auto from = node.optional_object("diffusion_from")) {
    for (const char* key : {"D_trans", "D_rot"})
      if (node.has(key)) node.fail(key, "expected either diffusion_from or explicit D_trans/D_rot, not both");
    const DiffusionFromFile f = read_diffusion_from(*from, expected_shape);
    d.D_trans = f.D_trans;
    d.D_rot = f.D_rot;
    d.shape = f.shape;
    d.origin = f.origin;
    return d;
  }
  for (const char* key : {"D_trans", "D_rot"}) {
    if (!node.has(key)) continue;
    const Vec3 v = node.vec3(key);
    if (v.minCoeff() < 0.0) node.fail(key, "expected three non-negative diffusion coefficients (body axes T, W, L)");
    (std::string(key) == "D_trans" ? d.D_trans : d.D_rot) = v;
    d.origin = "configuration";
  }
  return d;
}

Species parse_species(tool::ConfigNode node, nlohmann::json* diffusion_origin) {
  Species s;
  s.name = node.string("name");
  if (s.name.empty()) node.fail("name", "expected a non-empty species name");
  s.mass = node.positive("mass", 1.0);
  const std::optional<Shape> given = node.has("shape") ? std::optional(parse_shape(node.object("shape"))) : std::nullopt;
  const DiffusionSpec d = parse_diffusion(node, given);
  // A species file entry brings its shape; otherwise "shape" is required (node.object reports it).
  s.shape = d.shape ? *d.shape : given ? *given : parse_shape(node.object("shape"));
  s.D_trans = d.D_trans.value_or(Vec3::Zero());
  s.D_rot = d.D_rot.value_or(Vec3::Zero());
  if (diffusion_origin) *diffusion_origin = d.origin;
  return s;
}

SpeciesTable parse_species_table(tool::ConfigNode& parent, const std::string& key) {
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
  return {{"name", s.name}, {"shape", s.shape.spec()}, {"mass", s.mass},
          {"D_trans", {s.D_trans.x(), s.D_trans.y(), s.D_trans.z()}}, {"D_rot", {s.D_rot.x(), s.D_rot.y(), s.D_rot.z()}}};
}

}  // namespace anisodyn
