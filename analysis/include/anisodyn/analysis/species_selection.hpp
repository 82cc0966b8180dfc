#pragma once
// Which species a stage analyses: the one named by the config key (checked against the first
// input's species table), or every species in the file.
#include <string>
#include <vector>

#include "anisodyn/system/species.hpp"

namespace anisodyn::analysis {

struct SelectedSpecies {
  std::string name;
  int index = -1;
  Species properties;  // its entry of the first input's species table (shape, D_trans, D_rot)
};

/// `requested` empty → all species of the first input; otherwise that one (unknown → InputError
/// naming config_file and key).
std::vector<SelectedSpecies> select_species(const std::string& first_input, const std::string& requested,
                                            const std::string& config_file, const std::string& key);

}  // namespace anisodyn::analysis
