#pragma once
// Nematic-like clusters of HBPs in isotropic phases (spec 50 §5.1, E1; Cuetos & Dijkstra 2007).
// Particles i and j are in one cluster if |ê_i·ê_j| > K1, the cluster's local uniaxial order
// U_local > K2, and |r_ij^∥| < K_∥, |r_ij^⊥| < K_⊥ along/across the cluster director (minimum
// image). The thesis gives no procedure; the Decision algorithm (kNematicClusterRule) is:
//   1. candidate bonds from criteria 1 and 3 with the pair director n̂_ij = normalise(ê_i + s ê_j),
//      s = sign(ê_i·ê_j);
//   2. connected components (union-find);
//   3. for each component of size ≥ 2, n̂_local and U_local from the Q tensor of its ê;
//   4. drop its bonds that fail criterion 3 with n̂_local and recompute the components;
//   5. while U_local ≤ K2, remove the member with the smallest |ê·n̂_local| (a singleton from then
//      on, all its bonds dropped) and recompute U_local of the remaining members;
//   6. repeat 2–5 until a pass changes nothing (at most max_passes = 20 passes).
//
// Use: NematicClusterAnalysis a(settings, replicas); a.accumulate(trajectory, species) per
// replica; NematicClusterResult r = a.compute(). Every loaded frame (the stage's time window) is a configuration.
#include <array>
#include <cstddef>
#include <limits>
#include <string>
#include <vector>

#include "anisodyn/analysis/replica_statistics.hpp"
#include "anisodyn/analysis/trajectory.hpp"
#include "anisodyn/core/box.hpp"
#include "anisodyn/tool/json_config.hpp"

namespace anisodyn::analysis {

/// Recorded in the output metadata: which procedure made the clusters.
inline constexpr const char* kNematicClusterRule =
    "E1-decision-v1: candidate bonds |e_i.e_j| > K1 and |r_par| < K_par, |r_perp| < K_perp along "
    "normalise(e_i + sign(e_i.e_j) e_j); union-find components; per component of size >= 2 drop the bonds "
    "failing K_par/K_perp along the Q-tensor director, then peel the member with the smallest |e.n| while "
    "U_local <= K2; repeat until unchanged (at most 20 passes)";

struct NematicClusterSettings {
  std::string species;
  int axis = 2;               // relevant body axis: 0 T (oblate), 1 W, 2 L (prolate)
  double k1 = 0.85;           // |ê_i·ê_j| > K1, K1 ∈ (0, 1]
  double k2 = 0.90;           // U_local > K2, K2 ∈ (−1/2, 1]
  double k_par = 0.0;         // |r^∥| < K_∥ (length)
  double k_perp = 0.0;        // |r^⊥| < K_⊥ (length)
  int max_passes = 20;
  std::size_t cos_bins = 20;  // histogram of |cos θ| between cluster directors and box axes
};

/// Reads species, axis (T | W | L, required), K1, K2, K_par, K_perp (required), cos_bins.
NematicClusterSettings parse_nematic_cluster_settings(tool::ConfigNode& cfg);
/// K1 outside (0, 1], K2 outside (−1/2, 1], K_∥ or K_⊥ not positive, … → InputError naming the key.
void check_nematic_cluster_settings(const NematicClusterSettings& s, const std::string& config_file = "");

/// The clusters of one configuration.
struct NematicClustering {
  std::vector<std::size_t> label;  // cluster of each particle
  std::vector<std::size_t> size;   // members of each cluster
  std::vector<Vec3> director;      // n̂_local (a singleton's own axis)
  std::vector<double> order;       // U_local (1 for singletons)
  int passes = 0;
  bool converged = true;
};

/// Clusters of particles at `positions` (any image) with relevant unit axes `axes` in `box`.
NematicClustering nematic_clusters(const std::vector<Vec3>& positions, const std::vector<Vec3>& axes, const Box& box,
                                   const NematicClusterSettings& s);

/// Per-configuration summary kept for the output tables.
struct NematicConfiguration {
  std::size_t replica = 0, frame = 0;
  double time = 0.0;
  std::size_t clusters = 0, largest = 0, particles = 0;
  int passes = 0;
  bool converged = true;
  std::vector<std::size_t> multi_size;  // clusters with ≥ 2 members: size, director, U_local
  std::vector<Vec3> multi_director;
  std::vector<double> multi_order;
};

struct NematicClusterResult {
  std::vector<double> size;                    // n = 1 … largest
  std::vector<double> mean_count, mean_count_error;  // ⟨N_n⟩ per configuration
  Estimate total;                              // ⟨N_tot⟩
  Estimate largest_fraction;                   // ⟨n_max / N⟩
  std::vector<double> cos_center;              // bin centres of |cos θ|
  std::array<std::vector<double>, 3> cos_density, cos_density_error;  // per box axis x, y, z
  std::size_t configurations = 0, samples = 0, unconverged = 0, directors = 0;
  std::vector<NematicConfiguration> per_configuration;
};

class NematicClusterAnalysis {
 public:
  /// `replicas`: with one replica the errors come from ≤ 10 blocks of its configurations.
  NematicClusterAnalysis(NematicClusterSettings settings, std::size_t replicas, std::string config_file = "");
  void accumulate(const Trajectory& t, int species_index);
  NematicClusterResult compute() const;

 private:
  /// Sums over a sample (a replica, or a block of one replica's configurations).
  struct Sample {
    double configurations = 0, total = 0, largest_fraction = 0, directors = 0;
    std::vector<double> counts;       // Σ N_n
    std::vector<double> cos_counts;   // [axis × bins]
  };
  void add_configuration(Sample& s, const NematicClustering& c) const;

  NematicClusterSettings s_;
  std::size_t replicas_;
  std::string config_file_;
  std::vector<Sample> samples_;
  std::vector<NematicConfiguration> configs_;
  std::size_t replicas_seen_ = 0;
};

}  // namespace anisodyn::analysis
