#pragma once
// Configuration of anisodyn-hydro (docs/hydro.md):
//   {"species": [{"name": "board_W1", "shape": {"type": "cuboid", "edges": [1, 1, 12]}}, …],
//    "shells": {"count": 5, "max_beads": 6000, "size_ratio": 2.0},   // defaults; per species too
//    "symmetry": true, "construction": "surface_grid",   // default; per species too
//    "extrapolation": "auto"}                            // default (or "linear", "quadratic"); per species too
// or explicit "bead_radii": [σ_1, σ_2, …] (≥ 3) instead of "shells". Constructions: surface_grid
// (shell_beads), cell_centres (cell_centre_beads). Shape types: sphere {diameter},
// cube {edge}, cuboid {edges}, spherocylinder {length, diameter} (as for the engines), plus
// ellipsoid {semi_axes}, cylinder {length, diameter}, sphere_union {centres, diameters}.
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "anisodyn/hydro/extrapolation.hpp"
#include "anisodyn/hydro/shell_surface.hpp"
#include "anisodyn/tool/json_config.hpp"

namespace anisodyn::hydro {

struct HydroSpeciesJob {
  std::string name;
  nlohmann::json shape_json;  // as given, copied to the species file
  HydroShape shape;
  std::vector<double> bead_radii;  // coarsest first
  std::string construction_name = "surface_grid";
  ShellConstruction construction = &shell_beads;
  ExtrapolationRule extrapolation = kDefaultExtrapolation;
};

struct HydroConfig {
  std::vector<HydroSpeciesJob> species;
  bool use_symmetry = true;
};

HydroShape parse_hydro_shape(tool::ConfigNode node);

/// Parses and checks everything, including that each shell series can be built (bead radii are
/// chosen here), so that bad input fails before any computation.
HydroConfig parse_hydro_config(tool::ConfigNode& cfg);

}  // namespace anisodyn::hydro
