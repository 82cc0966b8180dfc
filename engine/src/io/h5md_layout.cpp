// Layout details shared by the H5MD writer and reader (h5md_layout.hpp).
#include "h5md_layout.hpp"

#include <algorithm>

#include "anisodyn/geometry/shapes.hpp"
#include "anisodyn/tool/json_config.hpp"

namespace anisodyn::io::h5md_layout {

using detail::Handle;
using detail::dims_text;
using detail::read_string_array;

ShapeKind shape_kind_from_name(const std::string& name, bool& ok) {
  ok = true;
  for (int k = 0; k < kShapeKindCount; ++k) {
    if (name == shape_kind_name(static_cast<ShapeKind>(k))) return static_cast<ShapeKind>(k);
  }
  ok = false;
  return ShapeKind::Sphere;
}

hsize_t frames_per_chunk(std::size_t n, std::size_t width, std::size_t elem_size, std::size_t hint) {
  if (hint > 0) return static_cast<hsize_t>(hint);
  const std::size_t bytes = std::max<std::size_t>(n, 1) * std::max<std::size_t>(width, 1) * elem_size;
  return static_cast<hsize_t>(std::clamp<std::size_t>((std::size_t{1} << 17) / bytes, 1, 64));
}

bool valid_name(const std::string& name) {
  return !name.empty() && name != "." && name != ".." && name.find('/') == std::string::npos;
}

/// The species' shapes from their JSON specs (one string per species).
std::vector<Shape> read_shape_specs(const FileReader& m, const std::string& path, std::size_t ns) {
  Handle ds = m.dataset(path);
  const std::vector<std::string> specs = read_string_array(ds.get(), m.path, path);
  if (specs.size() != ns) m.bad(path, "expected " + std::to_string(ns) + " entries, got " + std::to_string(specs.size()));
  std::vector<Shape> shapes;
  for (std::size_t i = 0; i < ns; ++i) {
    const std::string where = path + "[" + std::to_string(i) + "]";
    const nlohmann::json j = nlohmann::json::parse(specs[i], nullptr, false);
    if (j.is_discarded() || !j.is_object()) m.bad(where, "expected a shape as a JSON object, got '" + specs[i] + "'");
    tool::ConfigNode node(j, m.path, where);
    shapes.push_back(parse_shape(node));
    node.finish();
  }
  return shapes;
}

SpeciesTable read_species_table(const FileReader& m) {
  const std::string base = "/parameters/species";
  m.group(base);
  std::vector<std::string> names, shapes;
  {
    Handle ds = m.dataset(base + "/name");
    names = read_string_array(ds.get(), m.path, base + "/name");
  }
  {
    Handle ds = m.dataset(base + "/shape");
    shapes = read_string_array(ds.get(), m.path, base + "/shape");
  }
  const std::size_t ns = names.size();
  auto column = [&](const std::string& name, std::size_t width) {
    std::vector<hsize_t> d;
    auto v = m.read_vector<double>(base + "/" + name, H5T_NATIVE_DOUBLE, &d);
    const bool ok = width == 1 ? (d.size() == 1 && d[0] == ns) : (d.size() == 2 && d[0] == ns && d[1] == width);
    if (!ok)
      m.bad(base + "/" + name, "expected shape [" + std::to_string(ns) + (width > 1 ? ", " + std::to_string(width) : "") +
                                   "] (one row per species), got " + dims_text(d));
    return v;
  };
  if (shapes.size() != ns)
    m.bad(base + "/shape", "expected " + std::to_string(ns) + " entries, got " + std::to_string(shapes.size()));
  // The shapes: from their JSON specs, or, in files written before shape_spec, from the kind
  // name and the fixed columns (which the writer still adds for other readers).
  std::vector<Shape> from_specs;
  if (m.exists(base + "/shape_spec")) {
    from_specs = read_shape_specs(m, base + "/shape_spec", ns);
  } else {
    const auto edges = column("edges", 3), diameter = column("diameter", 1), length = column("length", 1);
    for (std::size_t i = 0; i < ns; ++i) {
      Shape& shape = from_specs.emplace_back();
      bool ok = false;
      shape.kind = shape_kind_from_name(shapes[i], ok);
      if (!ok) m.bad(base + "/shape", "unknown shape '" + shapes[i] + "' for species " + std::to_string(i));
      shape.edges = Vec3(edges[3 * i], edges[3 * i + 1], edges[3 * i + 2]);
      shape.diameter = diameter[i];
      shape.length = length[i];
    }
  }
  const auto mass = column("mass", 1), dt = column("D_trans", 3), dr = column("D_rot", 3);
  SpeciesTable table(ns);
  for (std::size_t i = 0; i < ns; ++i) {
    Species& s = table[i];
    s.name = names[i];
    s.shape = from_specs[i];
    s.mass = mass[i];
    s.D_trans = Vec3(dt[3 * i], dt[3 * i + 1], dt[3 * i + 2]);
    s.D_rot = Vec3(dr[3 * i], dr[3 * i + 1], dr[3 * i + 2]);
  }
  return table;
}

/// Number of leading entries of a non-decreasing step series that are ≤ last_step.
hsize_t rows_up_to(const std::vector<std::int64_t>& steps, std::int64_t last_step) {
  return static_cast<hsize_t>(std::upper_bound(steps.begin(), steps.end(), last_step) - steps.begin());
}

/// Adds the names of the links in an HDF5 group to `names`.
void insert_link_names(hid_t group, std::set<std::string>& names) {
  H5Literate(
      group, H5_INDEX_NAME, H5_ITER_INC, nullptr,
      [](hid_t, const char* name, const H5L_info_t*, void* data) -> herr_t {
        static_cast<std::set<std::string>*>(data)->insert(name);
        return 0;
      },
      &names);
}

/// Groups of /particles/all other than the standard H5MD elements that hold a `value` dataset.
std::vector<std::string> extra_element_names(const FileReader& r) {
  const std::string all = std::string("/particles/") + kParticleGroup;
  Handle g = r.group(all);
  std::set<std::string> names;
  insert_link_names(g.get(), names);
  std::vector<std::string> out;
  for (const auto& name : names) {
    if (name == "box" || name == "position" || name == "image" || name == "orientation" || name == "species" ||
        name == "id" || name == "force")
      continue;
    if (r.exists(all + "/" + name + "/value")) out.push_back(name);
  }
  return out;
}

std::string observable_path(const FileReader& r, const std::string& name) {
  if (!valid_name(name)) return "";
  for (const std::string base : {"/observables/", "/anisodyn/observables/"}) {
    if (r.exists(base + name)) return base + name;
  }
  return "";
}

}  // namespace anisodyn::io::h5md_layout
