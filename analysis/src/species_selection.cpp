#include "anisodyn/analysis/species_selection.hpp"

#include "anisodyn/core/error.hpp"
#include "anisodyn/io/h5md.hpp"

namespace anisodyn::analysis {

std::vector<SelectedSpecies> select_species(const std::string& first_input, const std::string& requested,
                                            const std::string& config_file, const std::string& key) {
  const SpeciesTable table = io::H5mdReader(first_input).species();
  std::vector<SelectedSpecies> out;
  std::string known;
  for (std::size_t s = 0; s < table.size(); ++s) {
    known += (known.empty() ? "" : ", ") + table[s].name;
    if (requested.empty() || table[s].name == requested) out.push_back({table[s].name, static_cast<int>(s), table[s]});
  }
  if (out.empty()) throw InputError(config_file, key, "unknown species '" + requested + "' (" + first_input + " has: " + known + ")");
  return out;
}

std::vector<SelectedSpecies> select_oriented_species(const std::string& first_input, const std::string& requested,
                                                     const std::string& config_file, const std::string& key) {
  const SpeciesTable table = io::H5mdReader(first_input).species();
  if (!requested.empty()) {
    auto out = select_species(first_input, requested, config_file, key);
    if (!table[static_cast<std::size_t>(out.front().index)].shape.is_anisotropic())
      throw InputError(config_file, key, "species '" + requested + "' is a sphere: it carries no orientational order");
    return out;
  }
  std::vector<SelectedSpecies> out;
  for (std::size_t s = 0; s < table.size(); ++s)
    if (table[s].shape.is_anisotropic()) out.push_back({table[s].name, static_cast<int>(s), table[s]});
  if (out.empty())
    throw InputError(config_file, key, first_input + " has no anisotropic species (spheres carry no orientational order); name one with \"" + key + "\"");
  return out;
}

namespace {

/// The named species, or the only one in the file (several and none named → InputError).
std::vector<SelectedSpecies> select_single_species(const std::string& first_input, const std::string& requested,
                                                   const std::string& config_file, const std::string& key) {
  auto all = select_species(first_input, requested, config_file, key);
  if (all.size() > 1) {
    std::string names;
    for (const auto& s : all) names += (names.empty() ? "" : ", ") + s.name;
    throw InputError(config_file, key, first_input + " has several species (" + names + "): name the one to analyse with \"" + key + "\"");
  }
  return all;
}

}  // namespace

std::vector<SelectedSpecies> select_species(const std::string& first_input, const SpeciesRequest& request,
                                            const std::string& config_file, const std::string& key) {
  switch (request.scope) {
    case SpeciesScope::Oriented: return select_oriented_species(first_input, request.name, config_file, key);
    case SpeciesScope::Single: return select_single_species(first_input, request.name, config_file, key);
    case SpeciesScope::Every: break;
  }
  return select_species(first_input, request.name, config_file, key);
}

}  // namespace anisodyn::analysis
