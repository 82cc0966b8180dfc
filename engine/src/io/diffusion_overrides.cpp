#include "anisodyn/io/diffusion_overrides.hpp"

#include "anisodyn/core/error.hpp"

namespace anisodyn::io {

DiffusionOverrides DiffusionOverrides::parse(tool::ConfigNode& cfg, const std::string& key) {
  DiffusionOverrides o;
  auto block = cfg.optional_object(key);
  if (!block) return o;
  for (const auto& [name, value] : block->raw().items()) {
    if (!name.empty() && name[0] == '_') continue;
    auto node = block->object(name);
    DiffusionSpec d = parse_diffusion(node);
    if (!d.origin.is_null()) o.origins[name] = d.origin;
    if (node.has("D_rot") && !node.has("diffusion_from")) o.rotational_keys[name] = node.child_path("D_rot");
    o.entries.emplace(name, std::move(d));
  }
  return o;
}

void DiffusionOverrides::check(const State& state, const std::string& file, const std::string& key) const {
  std::string known;
  for (const auto& s : state.species) known += (known.empty() ? "" : ", ") + s.name;
  for (const auto& [name, d] : entries) {
    const int s = species_index(state.species, name);
    if (s < 0)
      throw InputError(file, key + "." + name, "unknown species '" + name + "': expected one of the input's species (" + known + ")");
    const Species& sp = state.species[static_cast<std::size_t>(s)];
    if (d.shape && !same_shape(*d.shape, sp.shape))
      throw InputError(file, key + "." + name + ".diffusion_from",
                       "expected a species file entry with the same shape as the input's species '" + name + "'");
    const auto rot = rotational_keys.find(name);
    if (rot != rotational_keys.end() && !sp.shape.is_anisotropic())
      throw InputError(file, rot->second,
                       "no '" + rot->second.substr(rot->second.rfind('.') + 1) + "': it has no effect on the spheres of species '" +
                           name + "' (they do not rotate)");
  }
}

void DiffusionOverrides::apply(SpeciesTable& species) const {
  for (const auto& [name, d] : entries) {
    Species& sp = species[static_cast<std::size_t>(species_index(species, name))];
    if (d.D_trans) sp.D_trans = *d.D_trans;
    if (d.D_rot) sp.D_rot = *d.D_rot;
  }
}

}  // namespace anisodyn::io
