#include "anisodyn/config/config_tool.hpp"
#include "anisodyn/io/body_axis_choice.hpp"

#include <map>

#include "anisodyn/config/builder.hpp"
#include "anisodyn/interactions/hard_overlap.hpp"
#include "anisodyn/io/species_config.hpp"

namespace anisodyn {

namespace {

OrientationRule parse_orientation(std::optional<tool::ConfigNode> node, const Shape& shape) {
  OrientationRule rule;
  rule.body_axis = default_alignment_axis(shape);
  if (!node) return rule;
  if (!shape.is_anisotropic()) node->fail("", "no orientation for a sphere (it has none: the block has no effect)");
  rule.mode = node->choice("mode", {"aligned", "random"}, "aligned") == "aligned" ? OrientationRule::Mode::Aligned
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

}  // namespace

State build_configuration(tool::ConfigNode& cfg, const std::optional<State>& existing, std::uint64_t seed, std::uint64_t replica,
                          nlohmann::json* diffusion_origins) {
  State state;
  if (existing) state = *existing;
  if (!existing && !cfg.has("species")) cfg.fail("species", "expected the species table (an array of species)");
  nlohmann::json origins = nlohmann::json::object();
  const auto index = merge_species(state.species, cfg, origins);
  if (diffusion_origins) *diffusion_origins = origins;

  PlacementRequest req;
  req.counts.assign(state.species.size(), 0);
  req.rules.resize(state.species.size());
  auto entries = cfg.objects("composition");
  if (entries.empty()) cfg.fail("composition", "expected at least one {\"species\": name, \"count\": n} entry");
  for (auto& e : entries) {
    const std::string name = e.string("species");
    auto it = index.find(name);
    if (it == index.end()) e.fail("species", "expected the name of a species in the table");
    const std::size_t s = static_cast<std::size_t>(it->second);
    req.counts[s] += static_cast<std::size_t>(e.positive_integer("count"));
    req.rules[s] = parse_orientation(e.optional_object("orientation"), state.species[s].shape);
  }
  const std::string placement = cfg.choice("placement", {"lattice", "random", "uniform"}, existing ? "random" : "lattice");
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

  // Minimum image needs every edge to be at least twice the largest interaction range.
  const double largest = largest_pair_cutoff(state.species);
  if (state.box.shortest_edge() < 2.0 * largest)
    cfg.fail(existing ? "" : "box", "expected box edges of at least " + std::to_string(2.0 * largest) +
                                        " (twice the largest cut-off, for the minimum image); the box is " +
                                        std::to_string(state.box.shortest_edge()) + " across");

  // Replica K draws from its own stream; replica 0 keeps the stream of a run without --replica.
  Rng rng(seed, 0x00C0F16ULL + (replica << 32));
  try {
    if (placement == "lattice") place_on_lattice(state, req, rng);
    else if (placement == "uniform") place_uniformly(state, req, rng);
    else insert_randomly(state, req, rng);
  } catch (const PlacementFailure& e) {
    cfg.fail(existing ? "composition" : "box.packing_fraction", std::string("packing fraction cannot be reached: ") + e.what());
  }
  if (placement == "lattice") {  // defensive: the lattice spacing rules out overlaps by construction
    if (HardOverlap(state).first_overlap()) throw RuntimeFailure("internal error: the lattice placement overlaps");
  }
  return state;
}

}  // namespace anisodyn
