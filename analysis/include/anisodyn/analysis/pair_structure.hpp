#pragma once
// Pair structure (spec 50 §4.1, §4.2) and slab density profiles (§1.7):
//   g_AB(r)  = ⟨Σ_{i∈A} Σ_{j∈B, j≠i} 1[r ≤ r_ij < r + Δr]⟩ / (N_A ρ_B v(r)),  v(r) = 4π[(r+Δr)³ − r³]/3;
//   g_∥(r)   = same count with r ≤ |r_ij·ê| < r + Δr and r_⊥ < R_∥, over v_∥ = 2πR_∥²Δr;
//   g_⊥(r)   = same count with r ≤ r_⊥ < r + Δr and |r_ij·ê| < h_⊥, over v_⊥ = π[(r+Δr)² − r²]·2h_⊥;
//     (Decision of §4.2: the factor 2 counts both sides of the reference plane, so g_∥, g_⊥ → 1);
//   ρ_r(s)   = ⟨N_s in [s, s+Δs)⟩ / (A Δs) / (N/V) along x, y, z, with A = V/L_s the slab area
//     (V^{2/3} of §1.7 for a cubic box), Δs = L/50 by default.
// Pairs use the minimum image and come from the cell lists of pair_search.hpp (the pairs within
// reach of a histogram, each once). A bin whose shell or cylinder does not fit inside the
// minimum-image cell is NaN. Curves are averaged over
// the selected frames, then over replicas with the standard error over replicas; a single
// replica is split into blocks of frames for the error.
#include <array>
#include <cstddef>
#include <string>
#include <utility>
#include <vector>

#include "anisodyn/analysis/trajectory.hpp"
#include "anisodyn/core/types.hpp"
#include "anisodyn/tool/json_config.hpp"

namespace anisodyn::analysis {

enum class PairReference { None, Field, Director };

struct PairStructureSettings {
  std::vector<std::pair<std::string, std::string>> pairs;  // empty = each species with itself
  double dr = 0.05;
  double r_max = 0.0;                    // 0 = half the smallest box edge
  PairReference reference = PairReference::Field;
  Vec3 direction = Vec3::UnitZ();        // Ê for PairReference::Field
  int axis = -1;                         // body axis of the director (0 T, 1 W, 2 L; −1 largest mean U)
  std::string director_species;          // "" = the first anisotropic species of the pair, else of the file
  double cylinder_radius = 0.5;          // R_∥ (spec 50 §4.2 Decision for cubes: 0.5σ)
  double slab_half_height = 0.5;         // h_⊥
  std::size_t slab_bins = 50;            // Δs = L / slab_bins
  std::size_t single_replica_blocks = 10;
  double director_threshold = 0.40;      // a director needs mean U above this (spec 50 §3.1)
};

/// Reads the keys of anisodyn-structure (pairs, dr, r_max, reference, direction, axis,
/// director_species, cylinder_radius, slab_half_height, slab_bins). Frames are chosen by the
/// stage's time window (frame_window.hpp); the former `frames` key is refused with that advice.
PairStructureSettings parse_structure_settings(tool::ConfigNode& cfg);

struct PairCurves {
  std::string a, b;
  std::size_t count_a = 0, count_b = 0;
  std::vector<double> g, g_se, coordination, g_par, g_par_se, g_perp, g_perp_se;
};

struct SlabProfile {
  std::string species;
  std::array<std::vector<double>, 3> s, rho, rho_se;  // per axis x, y, z: bin centres, ρ_r, SE
};

struct PairStructureResult {
  std::vector<double> r;                    // bin centres: bin [r − Δr/2, r + Δr/2)
  std::vector<PairCurves> pairs;
  std::vector<SlabProfile> profiles;
  std::string reference;                    // description of ê
  std::vector<int> director_axis;           // per replica (director reference)
  std::vector<double> director_order;       // per replica: mean U of that axis over the frames
  std::size_t samples = 0, frames_per_replica = 0;
  bool blocks = false;                      // errors from frame blocks of a single replica
};

class PairStructureAnalysis {
 public:
  PairStructureAnalysis(PairStructureSettings settings, std::size_t replicas, std::string config_file = "");
  /// Adds one replica (positions needed; orientations for the director reference).
  void accumulate(const Trajectory& t);
  PairStructureResult compute() const;

 private:
  void resolve_species(const Trajectory& t);
  std::vector<Vec3> frame_reference(const Trajectory& t, const std::vector<std::size_t>& frames);
  PairStructureSettings s_;
  std::size_t replicas_;
  std::string config_file_;
  std::size_t bins_ = 0;
  std::vector<std::pair<int, int>> pair_index_;
  std::vector<int> profile_species_;
  std::vector<std::string> pair_names_a_, pair_names_b_, profile_names_;
  std::vector<std::size_t> count_a_, count_b_;
  std::vector<std::vector<double>> samples_;  // per sample: all curves concatenated
  std::array<double, 3> edge_sum_{0, 0, 0};
  std::vector<double> rho_b_sum_;        // per pair: Σ over frames of N_B/V
  std::size_t frame_count_ = 0, frames_per_replica_ = 0;
  PairStructureResult meta_;
};

}  // namespace anisodyn::analysis
