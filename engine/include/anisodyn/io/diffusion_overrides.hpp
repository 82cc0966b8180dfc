#pragma once
// An engine's "species" block (docs/run.md): diffusion coefficients replacing those of the input's
// species table,
//   "species": {"board": {"D_trans": [..], "D_rot": [..]} | {"diffusion_from": {"file", "species"}}}
// One parser and one check against the input for every engine (DMC, BD, …); the entries themselves
// are read by parse_diffusion (io/species_config.hpp). Keys of the block starting with '_' are comments.
#include <map>
#include <string>

#include <nlohmann/json.hpp>

#include "anisodyn/io/species_config.hpp"
#include "anisodyn/system/state.hpp"
#include "anisodyn/tool/json_config.hpp"

namespace anisodyn::io {

struct DiffusionOverrides {
  std::map<std::string, DiffusionSpec> entries;          // species name → its override
  std::map<std::string, std::string> rotational_keys;    // species name → JSON path of an explicit D_rot
  nlohmann::json origins = nlohmann::json::object();     // species name → where its values came from

  /// Reads the optional block `key` of cfg.
  static DiffusionOverrides parse(tool::ConfigNode& cfg, const std::string& key = "species");
  /// Against the input: every name is one of its species, an entry from a species file has the
  /// species' shape, and an explicit D_rot is not given for spheres (it would have no effect).
  /// Problems → InputError(file, "<key>.<name>…").
  void check(const State& state, const std::string& file, const std::string& key = "species") const;
  /// Replaces the given coefficients in the species table (names checked before).
  void apply(SpeciesTable& species) const;
};

}  // namespace anisodyn::io
