#pragma once
// Species from JSON:
//   {"name": "board", "shape": {"type": "cuboid", "edges": [1, 3.46, 12]},
//    "mass": 1, "D_trans": [Dt_T, Dt_W, Dt_L], "D_rot": [Dr_T, Dr_W, Dr_L]}
// Shape types: sphere {diameter}, cuboid {edges: [T, W, L]}, cube {edge},
// spherocylinder {length, diameter}. Diffusion coefficients default to zero (MC does not need
// them; the dynamics engines check that they are set).
#include "anisodyn/io/json_config.hpp"
#include "anisodyn/system/species.hpp"

namespace anisodyn {

Shape parse_shape(io::ConfigNode node);
Species parse_species(io::ConfigNode node);
/// The array at `key`; names must be unique.
SpeciesTable parse_species_table(io::ConfigNode& parent, const std::string& key);
/// JSON form accepted by parse_species (for writing parameters back out).
nlohmann::json species_to_json(const Species& s);

}  // namespace anisodyn
