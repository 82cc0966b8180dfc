#pragma once
// Effective diameter of soft rods from the distribution of scaled axis distances of interacting
// pairs (spec 20 §5, spec 50 §9.5 (I5)). anisodyn-bd writes the histogram as the observable
// `pair_distance_histogram`: one row at the end of the run, the counts of pairs with V_ov > 0 in
// equal bins of x = d/D on [0, 1] (d of the branch in use, D the bare diameter), summed over every
// observation row. Per replica, from the bin centres x_b:
//   P_d(x_b) = c_b / (n Δx) (so ∫P_d dx = 1), ⟨x⟩ = Σ c_b x_b / n, σ_x = √(⟨x²⟩ − ⟨x⟩²),
//   D_eff = D⟨x⟩,
// then mean ± standard error over replicas (spec 50 §0). The box of the density series of study B,
// V = 250 π L² D_eff (spec 20 §1), is reported as its cubic edge (jackknife error over replicas).
#include <cstddef>
#include <string>
#include <vector>

#include "anisodyn/analysis/replica_statistics.hpp"
#include "anisodyn/analysis/trajectory.hpp"
#include "anisodyn/tool/json_config.hpp"

namespace anisodyn::analysis {

inline const std::string kPairDistanceObservable = "pair_distance_histogram";

/// Moments of one histogram of x on [0, 1] with equal bins, from the bin centres.
struct HistogramMoments {
  double pairs = 0.0;              // n = Σ c_b
  double mean_x = 0.0, sigma_x = 0.0;
  std::vector<double> density;     // P_d(x_b) = c_b / (n Δx)
};

/// The moments of `counts` (bins of width 1/size on [0, 1]); n = 0 gives NaN moments.
HistogramMoments histogram_moments(const std::vector<double>& counts);

/// The bin centres (b + 1/2)/bins.
std::vector<double> bin_centres(std::size_t bins);

/// Edge of the cube of volume 250 π L² D_eff (spec 20 §1: the box of every density of study B).
double study_box_edge(double rod_length, double effective_diameter);

struct PairDistanceResult {
  std::vector<double> x, density, density_error, counts;  // counts summed over replicas
  Estimate mean_x, sigma_x, effective_diameter, box_edge;
  std::vector<double> replica_pairs;
  double diameter = 0.0, length = 0.0;  // bare D and L of the rod species
};

class PairDistanceAnalysis {
 public:
  /// D and L: the bare diameter and cylinder length of the rod species (its species-table shape).
  PairDistanceAnalysis(double diameter, double length);
  /// Adds one replica's histogram; a missing or malformed observable → InputError naming the file
  /// and the HDF5 path.
  void accumulate(const Trajectory& t);
  PairDistanceResult compute() const;

 private:
  double diameter_, length_;
  std::size_t bins_ = 0;
  std::vector<double> pairs_, total_counts_;
  CurveSamples samples_;  // per replica: [⟨x⟩, σ_x, P_d(x_0) … P_d(x_{bins−1})]
};

}  // namespace anisodyn::analysis
