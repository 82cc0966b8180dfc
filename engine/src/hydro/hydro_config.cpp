#include "anisodyn/hydro/hydro_config.hpp"

#include <set>

#include "anisodyn/core/error.hpp"
#include "anisodyn/hydro/diffusion_tensor.hpp"

namespace anisodyn::hydro {

namespace {

using ShapeParser = HydroShape (*)(tool::ConfigNode&);

HydroShape parse_sphere(tool::ConfigNode& n) { return HydroShape::sphere(n.positive("diameter")); }
HydroShape parse_cube(tool::ConfigNode& n) { return HydroShape::cuboid(Vec3::Constant(n.positive("edge"))); }
HydroShape parse_cuboid(tool::ConfigNode& n) { return HydroShape::cuboid(n.positive_vec3("edges")); }
HydroShape parse_ellipsoid(tool::ConfigNode& n) { return HydroShape::ellipsoid(n.positive_vec3("semi_axes")); }
HydroShape parse_cylinder(tool::ConfigNode& n) { return HydroShape::cylinder(n.positive("length"), n.positive("diameter")); }
HydroShape parse_spherocylinder(tool::ConfigNode& n) {
  return HydroShape::spherocylinder(n.non_negative("length"), n.positive("diameter"));
}
HydroShape parse_sphere_union(tool::ConfigNode& n) {
  const auto& centres = n.value("centres");
  if (!centres.is_array() || centres.empty()) n.fail("centres", "expected an array of [x, y, z] sphere centres");
  std::vector<Vec3> c;
  for (std::size_t k = 0; k < centres.size(); ++k) {
    const auto& p = centres[k];
    if (!p.is_array() || p.size() != 3 || !p[0].is_number() || !p[1].is_number() || !p[2].is_number())
      n.fail("centres[" + std::to_string(k) + "]", "expected [x, y, z]");
    c.emplace_back(p[0].get<double>(), p[1].get<double>(), p[2].get<double>());
  }
  const std::vector<double> d = n.numbers("diameters");
  if (d.size() != c.size()) n.fail("diameters", "expected one diameter per centre (" + std::to_string(c.size()) + ")");
  std::vector<double> radii;
  for (std::size_t k = 0; k < d.size(); ++k) {
    if (!(d[k] > 0.0)) n.fail("diameters[" + std::to_string(k) + "]", "expected a positive diameter");
    radii.push_back(0.5 * d[k]);
  }
  return HydroShape::sphere_union(std::move(c), std::move(radii));
}

struct ShapeRegistration {
  const char* type;
  ShapeParser parse;
};
// One line per shape type.
const ShapeRegistration kShapeRegistry[] = {
    {"sphere", &parse_sphere},         {"cube", &parse_cube},
    {"cuboid", &parse_cuboid},         {"spherocylinder", &parse_spherocylinder},
    {"ellipsoid", &parse_ellipsoid},   {"cylinder", &parse_cylinder},
    {"sphere_union", &parse_sphere_union},
};

struct ConstructionRegistration {
  const char* name;
  ShellConstruction beads;
};
// One line per shell construction; the first is the default.
const ConstructionRegistration kConstructionRegistry[] = {
    {"surface_grid", &shell_beads},
    {"cell_centres", &cell_centre_beads},
};

const ConstructionRegistration& parse_construction(tool::ConfigNode& n, const std::string& fallback) {
  std::vector<std::string> names;
  for (const auto& r : kConstructionRegistry) names.emplace_back(r.name);
  const std::string name = n.choice("construction", names, fallback);
  for (const auto& r : kConstructionRegistry)
    if (name == r.name) return r;
  n.fail("construction", "expected a known shell construction");
}

ExtrapolationRule parse_extrapolation(tool::ConfigNode& n, ExtrapolationRule fallback) {
  const ExtrapolationRule orders[] = {ExtrapolationRule::Linear, ExtrapolationRule::Quadratic, ExtrapolationRule::Auto};
  std::vector<std::string> names;
  for (auto o : orders) names.push_back(extrapolation_name(o));
  const std::string name = n.choice("extrapolation", names, extrapolation_name(fallback));
  for (auto o : orders)
    if (name == extrapolation_name(o)) return o;
  n.fail("extrapolation", "expected linear, quadratic or auto");
}

/// Builds the coarsest allowed shell once, so that a construction that does not cover the shape
/// fails while parsing.
void check_construction_covers(tool::ConfigNode& n, const HydroSpeciesJob& job) {
  try {
    job.construction(job.shape, 0.25 * thinnest_dimension(job.shape));
  } catch (const InputError& e) {
    n.fail("construction", std::string("a construction that covers this shape: ") + e.what());
  }
}

ShellSeries parse_shell_series(tool::ConfigNode& n, const ShellSeries& fallback) {
  ShellSeries s = fallback;
  s.count = static_cast<int>(n.positive_integer("count", s.count));
  if (s.count < 3) n.fail("count", "expected at least 3 shell resolutions for an extrapolation to zero bead size");
  s.max_beads = static_cast<std::size_t>(n.positive_integer("max_beads", static_cast<std::int64_t>(s.max_beads)));
  s.size_ratio = n.positive("size_ratio", s.size_ratio);
  if (!(s.size_ratio > 1.0)) n.fail("size_ratio", "expected a ratio > 1 between the coarsest and the finest bead radius");
  return s;
}

std::vector<double> parse_bead_radii(tool::ConfigNode& n) {
  std::vector<double> r = n.numbers("bead_radii");
  for (std::size_t k = 0; k < r.size(); ++k)
    if (!(r[k] > 0.0)) n.fail("bead_radii[" + std::to_string(k) + "]", "expected a positive bead radius");
  if (std::set<double>(r.begin(), r.end()).size() < 3)
    n.fail("bead_radii", "expected at least 3 distinct bead radii for an extrapolation to zero bead size");
  std::sort(r.rbegin(), r.rend());
  return r;
}

}  // namespace

HydroShape parse_hydro_shape(tool::ConfigNode node) { return tool::parse_registered(node, "type", kShapeRegistry); }

HydroConfig parse_hydro_config(tool::ConfigNode& cfg) {
  HydroConfig out;
  out.use_symmetry = cfg.boolean("symmetry", true);
  const std::string default_construction = parse_construction(cfg, kConstructionRegistry[0].name).name;
  const ExtrapolationRule default_extrapolation = parse_extrapolation(cfg, kDefaultExtrapolation);
  ShellSeries defaults;
  if (auto s = cfg.optional_object("shells")) defaults = parse_shell_series(*s, defaults);
  std::optional<std::vector<double>> default_radii;
  if (cfg.has("bead_radii")) {
    if (cfg.has("shells")) cfg.fail("bead_radii", "expected either shells or bead_radii, not both");
    default_radii = parse_bead_radii(cfg);
  }

  // Top-level keys are defaults: each must reach at least one species, or it has no effect.
  bool default_construction_used = false, default_series_used = false, default_extrapolation_used = false;
  std::set<std::string> seen;
  auto nodes = cfg.objects("species");
  if (nodes.empty()) cfg.fail("species", "expected at least one species");
  for (auto& n : nodes) {
    HydroSpeciesJob job;
    job.name = n.string("name");
    if (job.name.empty() || !seen.insert(job.name).second) n.fail("name", "expected a unique, non-empty species name");
    job.shape_json = n.raw().at("shape");
    job.shape = parse_hydro_shape(n.object("shape"));
    default_construction_used |= !n.has("construction");
    const ConstructionRegistration& construction = parse_construction(n, default_construction);
    job.construction_name = construction.name;
    job.construction = construction.beads;
    check_construction_covers(n, job);
    if (n.has("bead_radii") && n.has("shells")) n.reject_unless(false, "shells", "with bead_radii (the radii are given: either shells or bead_radii, not both)");
    default_series_used |= !n.has("bead_radii") && !n.has("shells");
    default_extrapolation_used |= !n.has("extrapolation");
    job.extrapolation = parse_extrapolation(n, default_extrapolation);
    if (n.has("bead_radii")) {
      job.bead_radii = parse_bead_radii(n);
    } else if (default_radii && !n.has("shells")) {
      job.bead_radii = *default_radii;
    } else {
      ShellSeries series = defaults;
      std::string where = cfg.has("shells") ? cfg.child_path("shells") : cfg.child_path("shells") + " (defaults)";
      if (auto s = n.optional_object("shells")) {
        series = parse_shell_series(*s, defaults);
        where = s->path();
      }
      try {
        job.bead_radii = choose_bead_radii(job.shape, series, job.construction);
      } catch (const InputError& e) {
        throw InputError(cfg.file(), where, "species '" + job.name + "': " + e.what());
      }
    }
    out.species.push_back(std::move(job));
  }
  const std::string own = "with every species setting its own ";
  cfg.reject_unless(default_construction_used, "construction", "(a default) " + own + "construction");
  cfg.reject_unless(default_series_used, "shells", "(a default) " + own + "bead_radii or shells");
  cfg.reject_unless(default_series_used, "bead_radii", "(a default) " + own + "bead_radii or shells");
  cfg.reject_unless(default_extrapolation_used, "extrapolation", "(a default) " + own + "extrapolation");
  return out;
}

}  // namespace anisodyn::hydro
