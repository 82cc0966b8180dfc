#pragma once
// The dipolar bond rule of spec 50 §5.2 (E2): cubes i and j are bonded if βu_ij < βu_max, with
// βu_ij = (γ/2)(σ/r_ij)³(1 − 3cos²θ_ij) the bare point-dipole pair energy (no Ewald) at the
// minimum-image r_ij and θ_ij its angle to the field Ê; clusters are the connected components of the
// bonds, free cubes clusters of size 1.
//
// One rule for every stage that needs it: the dipolar chains (dipolar_clusters.hpp), the DBSCAN
// calibration of βu_max (dbscan.hpp) and the chain/free split of the cube order (order_parameters.hpp).
// The energy is the engine's own function (interactions/dipolar_pair.hpp), the pairs come from the
// analyses' pair search (pair_search.hpp).
#include <vector>

#include "anisodyn/analysis/union_find.hpp"
#include "anisodyn/core/box.hpp"
#include "anisodyn/core/types.hpp"
#include "anisodyn/tool/json_config.hpp"

namespace anisodyn::analysis {

struct DipolarBondRule {
  double gamma = 0.0;          // dipolar coupling γ (kT)
  double sigma = 1.0;          // cube edge σ
  double bu_max = -3.20;       // bond threshold (kT), must be negative (spec 50 §5.2)
  Vec3 field = Vec3::UnitZ();  // unit field direction Ê
};

/// Reads the rule's coupling from a stage configuration: gamma (required), sigma (default 1) and
/// field_direction (default z, normalised); bu_max when `with_threshold` (default −3.20, negative).
DipolarBondRule parse_dipolar_bond_rule(tool::ConfigNode& cfg, bool with_threshold);

/// Largest separation at which βu < βu_max is possible: σ (γ/|βu_max|)^{1/3} (θ = 0).
double dipolar_bond_cutoff(const DipolarBondRule& rule);
/// Bonds βu_ij < βu_max among `positions` (indices into it), ordered by i, then j. A threshold that
/// is not negative or a coupling that is not positive → InputError naming the key.
std::vector<Bond> dipolar_bonds(const std::vector<Vec3>& positions, const Box& box, const DipolarBondRule& rule);
/// The clusters of one configuration.
Components dipolar_clusters(const std::vector<Vec3>& positions, const Box& box, const DipolarBondRule& rule);
/// Flags the particles of clusters of size ≥ 2 (the cubes in chains).
std::vector<char> dipolar_chain_mask(const std::vector<Vec3>& positions, const Box& box, const DipolarBondRule& rule);

}  // namespace anisodyn::analysis
