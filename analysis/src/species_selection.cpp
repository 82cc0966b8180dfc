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

}  // namespace anisodyn::analysis
