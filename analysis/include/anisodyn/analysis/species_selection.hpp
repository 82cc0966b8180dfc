#pragma once
// Which species a stage analyses: the one named by the config key (checked against the first
// input's species table), or, when none is named, the species the stage's scope takes from the file.
#include <string>
#include <vector>

#include "anisodyn/system/species.hpp"

namespace anisodyn::analysis {

struct SelectedSpecies {
  std::string name;
  int index = -1;
  Species properties;  // its entry of the first input's species table (shape, D_trans, D_rot)
};

/// What a stage takes when the config names no species.
enum class SpeciesScope {
  Every,     // every species the file's frames hold (its table may name more)
  Oriented,  // every anisotropic species: spheres carry no orientation, and naming one is an error
  Single,    // the only species of the file: several and none named is an error
};

struct SpeciesRequest {
  std::string name;  // the config's `species`; empty = as the scope says
  SpeciesScope scope = SpeciesScope::Every;
};

/// `requested` empty → all species of the first input; otherwise that one (unknown → InputError
/// naming config_file and key).
std::vector<SelectedSpecies> select_species(const std::string& first_input, const std::string& requested,
                                            const std::string& config_file, const std::string& key);

/// Species of the orientational stages: the named one, or every anisotropic species of the first
/// input. Spheres carry no orientation: naming one, or having none other → InputError (config_file, key).
std::vector<SelectedSpecies> select_oriented_species(const std::string& first_input, const std::string& requested,
                                                     const std::string& config_file, const std::string& key);

/// The species of `request` under its scope (errors as above).
std::vector<SelectedSpecies> select_species(const std::string& first_input, const SpeciesRequest& request,
                                            const std::string& config_file, const std::string& key);

}  // namespace anisodyn::analysis
