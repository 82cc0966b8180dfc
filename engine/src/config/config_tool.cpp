#include "anisodyn/config/config_tool.hpp"
#include "anisodyn/io/body_axis_choice.hpp"

#include <map>

#include "anisodyn/config/builder.hpp"
#include "anisodyn/interactions/hard_overlap.hpp"
#include "anisodyn/io/species_config.hpp"

namespace anisodyn {

namespace {

OrientationRule parse_orientation(std::optional<tool::ConfigNode> node, const Shape& shape, OrientationRule::Mode fallback) {
  OrientationRule rule;
  rule.mode = fallback;
  rule.body_axis = default_alignment_axis(shape);
  if (!node) return rule;
  if (!shape.is_anisotropic()) node->fail("", "no orientation for a sphere (it has none: the block has no effect)");
  const std::string fallback_name = fallback == OrientationRule::Mode::Aligned ? "aligned" : "random";
  rule.mode = node->choice("mode", {"aligned", "random"}, fallback_name) == "aligned" ? OrientationRule::Mode::Aligned
                                                                                      : OrientationRule::Mode::Random;
  for (const char* key : {"axis", "director", "random_azimuth"})
    node->reject_unless(rule.mode == OrientationRule::Mode::Aligned, key, "with random orientations (it shapes an aligned start)");
  const int axis = io::choose_body_axis(*node, "axis", "auto", false, {"auto"});
  if (axis >= 0) rule.body_axis = axis;
  rule.director = node->vec3("director", Vec3::UnitZ());
  if (rule.director.norm() == 0.0) node->fail("director", "a non-zero direction");
  rule.random_azimuth = node->boolean("random_azimuth", false);
  return rule;
}

/// Merges the configuration's species into `table`: a name already present must describe the same
/// species. Returns the index of each configured species in the table.
std::map<std::string, int> merge_species(SpeciesTable& table, tool::ConfigNode& cfg, nlohmann::json& origins) {
  std::map<std::string, int> index;
  for (std::size_t s = 0; s < table.size(); ++s) index[table[s].name] = static_cast<int>(s);
  if (!cfg.has("species")) return index;
  auto nodes = cfg.objects("species");
  for (auto& n : nodes) {
    nlohmann::json origin;
    Species sp = parse_species(n, &origin);
    if (!origin.is_null()) origins[sp.name] = origin;
    auto it = index.find(sp.name);
    if (it == index.end()) {
      index[sp.name] = static_cast<int>(table.size());
      table.push_back(sp);
    } else if (species_to_json(table[static_cast<std::size_t>(it->second)]) != species_to_json(sp)) {
      n.fail("name", "expected a new species name or the same definition as in the input ('" + sp.name + "' differs)");
    }
  }
  return index;
}

/// The liquid of placement "colloids_in_liquid" (spec 30 §5).
struct LiquidFill {
  int species = -1;
  double density = 3.0;
  bool subtract_colloid_volume = true;
  double z_min = 0.0, z_max = -1.0;  // the slab the liquid fills (z_max < 0: the whole box)
};

LiquidFill parse_liquid_fill(tool::ConfigNode& cfg, const std::map<std::string, int>& index, const PlacementRequest& req) {
  auto node = cfg.object("liquid");
  LiquidFill fill;
  const std::string name = node.string("species");
  auto it = index.find(name);
  if (it == index.end()) node.fail("species", "expected the name of a species in the table");
  fill.species = it->second;
  if (req.counts[static_cast<std::size_t>(fill.species)] > 0)
    node.fail("species", "expected a species that is not in the composition (the composition places the colloids)");
  fill.density = node.positive("density", fill.density);
  fill.subtract_colloid_volume = node.boolean("subtract_colloid_volume", fill.subtract_colloid_volume);
  if (node.has("z_range")) {  // a channel between walls (spec 30 §6)
    const auto range = node.numbers("z_range");
    if (range.size() != 2 || !(range[0] >= 0.0) || !(range[1] > range[0]))
      node.fail("z_range", "expected [z_min, z_max] with 0 <= z_min < z_max: the slab of the box the liquid fills");
    fill.z_min = range[0];
    fill.z_max = range[1];
  }
  return fill;
}

/// N = round(ρ (V_box − Σ V_colloid)) liquid particles (or ρ V_box without the subtraction) outside
/// the colloids; the counts go to `record`.
void add_liquid(State& state, const LiquidFill& fill, Rng& rng, tool::ConfigNode& cfg, nlohmann::json* record) {
  double excluded = 0.0;
  for (std::size_t i = 0; i < state.particles.size(); ++i) {
    const Shape& shape = state.species[static_cast<std::size_t>(state.particles.species[i])].shape;
    if (shape.kind != ShapeKind::Sphere && shape.kind != ShapeKind::Spherocylinder)
      cfg.fail("composition", std::string("expected sphere or spherocylinder colloids around which to place a liquid, not a ") +
                                  shape_kind_name(shape.kind));
    excluded += shape.volume();
  }
  const Vec3 L = state.box.edges();
  if (fill.z_max > L.z()) cfg.fail("liquid.z_range", "expected a slab inside the box (0 ... " + std::to_string(L.z()) + " along z)");
  const double z_min = fill.z_max > 0.0 ? fill.z_min : 0.0, z_max = fill.z_max > 0.0 ? fill.z_max : L.z();
  const double volume = L.x() * L.y() * (z_max - z_min) - (fill.subtract_colloid_volume ? excluded : 0.0);
  if (!(volume > 0.0)) cfg.fail("box", "expected a box larger than the colloids");
  const auto count = static_cast<std::size_t>(std::llround(fill.density * volume));
  const std::size_t colloids = state.particles.size();
  try {
    fill_liquid(state, fill.species, count, rng, z_min, z_max);
  } catch (const PlacementFailure& e) {
    cfg.fail("liquid", std::string("the liquid does not fit: ") + e.what());
  }
  if (record)
    *record = {{"liquid_particles", count}, {"colloids", colloids}, {"density", fill.density},
               {"colloid_volume", excluded}, {"subtract_colloid_volume", fill.subtract_colloid_volume},
               {"rule", "N = round(density (V_box - colloid volume)); positions uniform outside the colloid bodies"}};
}

/// The colloids: a single one at the box centre, several by random insertion without overlaps.
void place_colloids(State& state, const PlacementRequest& req, Rng& rng) {
  std::size_t total = 0;
  for (const std::size_t n : req.counts) total += n;
  if (total == 0) return;  // a liquid alone
  if (total != 1) {
    insert_randomly(state, req, rng);
    return;
  }
  for (std::size_t s = 0; s < req.counts.size(); ++s)
    if (req.counts[s] == 1) {
      PlacementRequest one = req;
      place_uniformly(state, one, rng);  // draws the orientation by the species' rule …
      state.particles.set_position(state.particles.size() - 1, 0.5 * state.box.edges());  // … and the centre replaces the position
    }
}

}  // namespace

State build_configuration(tool::ConfigNode& cfg, const std::optional<State>& existing, std::uint64_t seed, std::uint64_t replica,
                          nlohmann::json* diffusion_origins, nlohmann::json* liquid_record) {
  State state;
  if (existing) state = *existing;
  if (!existing && !cfg.has("species")) cfg.fail("species", "expected the species table (an array of species)");
  nlohmann::json origins = nlohmann::json::object();
  const auto index = merge_species(state.species, cfg, origins);
  if (diffusion_origins) *diffusion_origins = origins;

  PlacementRequest req;
  req.counts.assign(state.species.size(), 0);
  req.rules.resize(state.species.size());
  // A liquid alone (a channel between walls) needs no composition.
  const bool liquid_alone = cfg.has("liquid") && !cfg.has("composition");
  auto entries = liquid_alone ? std::vector<tool::ConfigNode>{} : cfg.objects("composition");
  if (entries.empty() && !liquid_alone) cfg.fail("composition", "expected at least one {\"species\": name, \"count\": n} entry");
  std::vector<std::pair<std::size_t, std::optional<tool::ConfigNode>>> orientation_nodes;
  for (auto& e : entries) {
    const std::string name = e.string("species");
    auto it = index.find(name);
    if (it == index.end()) e.fail("species", "expected the name of a species in the table");
    const std::size_t s = static_cast<std::size_t>(it->second);
    req.counts[s] += static_cast<std::size_t>(e.positive_integer("count"));
    orientation_nodes.emplace_back(s, e.optional_object("orientation"));
  }
  const std::string placement =
      cfg.choice("placement", {"lattice", "random", "uniform", "colloids_in_liquid", "centre"}, existing ? "random" : "lattice");
  const bool liquid_fill = placement == "colloids_in_liquid";
  // Colloids in a liquid start with random orientations (spec 30 §5); other placements, aligned.
  for (auto& [s, node] : orientation_nodes)
    req.rules[s] = parse_orientation(node, state.species[s].shape, liquid_fill ? OrientationRule::Mode::Random : OrientationRule::Mode::Aligned);
  cfg.reject_unless(liquid_fill, "liquid", "without placement \"colloids_in_liquid\" (it is the liquid placed around the colloids)");
  std::optional<LiquidFill> fill;
  if (liquid_fill) fill = parse_liquid_fill(cfg, index, req);
  cfg.reject_unless(placement == "random", "max_attempts_per_particle", "with " + placement + " placement (it bounds random insertion)");
  req.max_attempts_per_particle = static_cast<std::size_t>(cfg.positive_integer("max_attempts_per_particle", 10000));
  if (existing) {
    if (placement != "random") cfg.fail("placement", "expected \"random\" when inserting into an existing configuration");
    if (cfg.has("box")) cfg.fail("box", "expected no box when inserting into an existing configuration (its box is kept)");
  } else {
    auto box = cfg.object("box");
    if (box.has("edges") == box.has("packing_fraction")) box.fail("", "expected either \"edges\" or \"packing_fraction\" (with optional \"aspect\")");
    box.reject_unless(!box.has("edges"), "aspect", "with explicit edges (it shapes the box built from a packing fraction)");
    if (box.has("edges")) {
      state.box = Box(box.positive_vec3("edges"));
    } else {
      const double eta = box.positive("packing_fraction");
      if (eta >= 1.0) box.fail("packing_fraction", "expected a packing fraction below 1");
      state.box = Box(box_edges_for_packing_fraction(state.species, req.counts, eta, box.positive_vec3("aspect", Vec3::Ones())));
    }
  }
  cfg.finish();

  // Minimum image needs every edge to be at least twice the largest interaction range (of hard
  // bodies: a liquid fill's colloids and liquid do not interact as such, and the DPD engine checks
  // its own ranges). A lone body has no pair: it needs only to fit in the box without touching its
  // images (an LB raspberry at infinite dilution, spec 40 §7.1; its engine checks its own margins).
  std::size_t placed = state.particles.size();
  for (const std::size_t n : req.counts) placed += n;
  const double largest = liquid_fill ? 0.0 : largest_pair_cutoff(state.species);
  const double needed = placed == 1 ? largest : 2.0 * largest;
  if (state.box.shortest_edge() < needed)
    cfg.fail(existing ? "" : "box", "expected box edges of at least " + std::to_string(needed) +
                                        (placed == 1 ? " (the body's largest extent)" : " (twice the largest cut-off, for the minimum image)") +
                                        "; the box is " + std::to_string(state.box.shortest_edge()) + " across");

  // Replica K draws from its own stream; replica 0 keeps the stream of a run without --replica.
  Rng rng(seed, 0x00C0F16ULL + (replica << 32));
  try {
    if (placement == "lattice") place_on_lattice(state, req, rng);
    else if (placement == "uniform") place_uniformly(state, req, rng);
    else if (placement == "centre") place_at_centre(state, req, rng);
    else if (liquid_fill) place_colloids(state, req, rng);
    else insert_randomly(state, req, rng);
  } catch (const PlacementFailure& e) {
    if (placement == "centre") cfg.fail("composition", std::string("expected one particle for placement \"centre\": ") + e.what());
    cfg.fail(existing ? "composition" : "box.packing_fraction", std::string("packing fraction cannot be reached: ") + e.what());
  }
  if (fill) add_liquid(state, *fill, rng, cfg, liquid_record);
  if (placement == "lattice") {  // defensive: the lattice spacing rules out overlaps by construction
    if (HardOverlap(state).first_overlap()) throw RuntimeFailure("internal error: the lattice placement overlaps");
  }
  return state;
}

}  // namespace anisodyn
