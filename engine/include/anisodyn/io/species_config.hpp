#pragma once
// Species from JSON:
//   {"name": "board", "shape": {"type": "cuboid", "edges": [1, 3.46, 12]},
//    "mass": 1, "D_trans": [Dt_T, Dt_W, Dt_L], "D_rot": [Dr_T, Dr_W, Dr_L]}
// or, with the diffusion coefficients from a species file written by anisodyn-hydro:
//   {"name": "board", "diffusion_from": {"file": "manifests/data/boards_L12_bead_model.species.json",
//                                        "species": "board_W1"}}
// (the shape comes from the file; if "shape" is given too it must match). "file" may also be a list
// of species files searched in order, the first that holds the species giving its values (e.g. the
// published tensors where they exist, else a bead-model table). A relative file path is taken from
// the working directory, else from the directory of the configuration file.
// Shape types: sphere {diameter}, cuboid {edges: [T, W, L]}, cube {edge},
// spherocylinder {length, diameter}. Diffusion coefficients default to zero (MC does not need
// them; the dynamics engines check that they are set).
#include "anisodyn/tool/json_config.hpp"
#include "anisodyn/geometry/shapes.hpp"
#include "anisodyn/system/species.hpp"

#include <optional>

namespace anisodyn {

struct DiffusionFromFile {
  Shape shape;
  Vec3 D_trans = Vec3::Zero();
  Vec3 D_rot = Vec3::Zero();
  /// Where the values came from, for provenance: {"file", "species", and the entry's "source" if any}.
  nlohmann::json origin;
};

/// Same kind and dimensions (to 1e-9 relative).
bool same_shape(const Shape& a, const Shape& b);

/// Reads {"file" (a path or a list of paths), "species"}; checks the entry's shape against
/// expected_shape when given.
DiffusionFromFile read_diffusion_from(tool::ConfigNode node, const std::optional<Shape>& expected_shape);

/// The diffusion coefficients of a species entry or of an engine's per-species override: explicit
/// `D_trans` / `D_rot` (three non-negative values each, body axes T, W, L) or `diffusion_from` (a
/// species file entry, whose shape comes with it), never both. One parser for every place that
/// takes diffusion coefficients.
struct DiffusionSpec {
  std::optional<Vec3> D_trans, D_rot;  // absent: not given
  std::optional<Shape> shape;          // from diffusion_from
  nlohmann::json origin;               // the file entry, "configuration" for explicit values, null for none
};
/// `expected_shape`: checked against a diffusion_from entry's shape when given.
DiffusionSpec parse_diffusion(tool::ConfigNode& node, const std::optional<Shape>& expected_shape = std::nullopt);

/// With diffusion_origin given, it receives where the diffusion coefficients came from (the origin
/// of diffusion_from, or "configuration" for explicit values, null for none).
Species parse_species(tool::ConfigNode node, nlohmann::json* diffusion_origin = nullptr);
/// The array at `key`; names must be unique.
SpeciesTable parse_species_table(tool::ConfigNode& parent, const std::string& key);
/// JSON form accepted by parse_species (for writing parameters back out).
nlohmann::json species_to_json(const Species& s);

}  // namespace anisodyn
