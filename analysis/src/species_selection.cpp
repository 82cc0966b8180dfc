#include "anisodyn/analysis/species_selection.hpp"

#include "anisodyn/core/error.hpp"
#include "anisodyn/io/h5md.hpp"

namespace anisodyn::analysis {

namespace {

/// Whether each species of the table has particles in the file's first frame: a file's table may
/// name species its frames leave out (anisodyn-dpd's frame_species shows a colloid without its liquid).
std::vector<char> present_species(const io::H5mdReader& reader, std::size_t species) {
  std::vector<char> present(species, 0);
  for (const std::int64_t s : reader.read_integer_element_frames("species", io::FrameSlice{0, 1, 1}))
    if (s >= 0 && static_cast<std::size_t>(s) < species) present[static_cast<std::size_t>(s)] = 1;
  return present;
}

}  // namespace

std::vector<SelectedSpecies> select_species(const std::string& first_input, const std::string& requested,
                                            const std::string& config_file, const std::string& key) {
  const io::H5mdReader reader(first_input);
  const SpeciesTable table = reader.species();
  const std::vector<char> present = present_species(reader, table.size());
  std::vector<SelectedSpecies> out;
  std::string known;
  for (std::size_t s = 0; s < table.size(); ++s) {
    known += (known.empty() ? "" : ", ") + table[s].name;
    // Every species means every species the frames hold; a named one is taken as named.
    if ((requested.empty() && present[s]) || table[s].name == requested) out.push_back({table[s].name, static_cast<int>(s), table[s]});
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
  const std::vector<char> present = present_species(io::H5mdReader(first_input), table.size());
  std::vector<SelectedSpecies> out;
  for (std::size_t s = 0; s < table.size(); ++s)
    if (table[s].shape.is_anisotropic() && present[s]) out.push_back({table[s].name, static_cast<int>(s), table[s]});
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
