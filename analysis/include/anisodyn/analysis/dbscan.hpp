#pragma once
// DBSCAN calibration of the dipolar bond threshold βu_max (spec 50 §5.3, E3):
//   1. for each cube, the separations to its first and second nearest neighbours (minimum image),
//      duplicate pairs discarded;
//   2. each mapped to (r_∥, r_⊥) = (|r·Ê|, |r − (r·Ê)Ê|), kept when both are ≤ r_max (2σ);
//   3. DBSCAN (Ester et al. 1996, as R `dbscan`: a point with N_Eps ≥ MinPts, itself included, is
//      a core point; border points join the first cluster that reaches them) on a 2-D grid index;
//   4. the cluster whose centroid is nearest the stacked-cube minimum (σ, 0) is kept;
//   5. βu_max = max of βu(r_∥, r_⊥) over its points; averaged over configurations.
// Decision: MinPts = 10; Eps from the knee of the sorted k-NN distance curve (k = MinPts, the point
// itself excluded), the knee being the point farthest below the chord joining the curve's ends
// after both axes are scaled to [0, 1]; βu_max reported for Eps × {0.7, 1, 1.4}.
#include <cstddef>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "anisodyn/analysis/dipolar_bonds.hpp"
#include "anisodyn/analysis/pair_search.hpp"
#include "anisodyn/analysis/replica_statistics.hpp"
#include "anisodyn/analysis/trajectory.hpp"
#include "anisodyn/tool/json_config.hpp"

namespace anisodyn::analysis {

inline constexpr int kDbscanNoise = -1;

struct DbscanLabels {
  std::vector<int> label;  // cluster 0 … clusters − 1, or kDbscanNoise
  int clusters = 0;
  std::size_t noise = 0;
};

/// DBSCAN with a square grid index of cell Eps (neighbours within |p − q| ≤ eps).
DbscanLabels dbscan(const std::vector<Point2>& points, double eps, std::size_t min_pts);

/// The distance of each point to its k-th nearest other point, sorted ascending (empty if ≤ k points).
std::vector<double> sorted_knn_distances(const std::vector<Point2>& points, std::size_t k);
/// Index of the knee of an ascending curve: the largest (x − y) with x = index/(n − 1) and
/// y = (d − d_0)/(d_{n−1} − d_0), i.e. the point farthest below the chord (n − 1 for fewer than 3
/// points or a flat curve).
std::size_t knee_index(const std::vector<double>& sorted);

struct DbscanCalibrationSettings {
  std::string species;
  DipolarBondRule rule;             // γ, σ, Ê (bu_max unused)
  std::size_t min_pts = 10;
  std::optional<double> eps;        // absent: the knee of each configuration's k-NN curve
  double r_max = 2.0;               // keep r_∥, r_⊥ ≤ r_max (2σ)
  std::vector<double> eps_factors{0.7, 1.0, 1.4};
};

/// Reads gamma (required), sigma, field_direction, min_pts, eps, r_max (default 2 sigma),
/// eps_factors.
DbscanCalibrationSettings parse_dbscan_settings(tool::ConfigNode& cfg);

/// Steps 1–2: the (r_∥, r_⊥) points of one configuration.
std::vector<Point2> neighbour_separation_points(const std::vector<Vec3>& positions, const Box& box,
                                                const DbscanCalibrationSettings& s);

/// Steps 3–5 at one Eps: the kept cluster and its βu_max (NaN, cluster −1 when DBSCAN finds none).
struct BondCalibration {
  double eps = 0.0, bu_max = 0.0;
  int cluster = -1;
  std::size_t cluster_points = 0, noise = 0;
  int clusters = 0;
};
BondCalibration calibrate_bond_threshold(const std::vector<Point2>& points, double eps, const DbscanCalibrationSettings& s);

struct CalibrationConfiguration {
  std::size_t replica = 0, frame = 0, points = 0;
  double time = 0.0, base_eps = 0.0;
  std::vector<BondCalibration> per_factor;  // one per eps factor
};

struct DbscanCalibrationResult {
  std::vector<double> eps_factors;
  std::vector<Estimate> bu_max;         // per factor: mean ± SE over configurations with a cluster
  std::vector<std::size_t> used;        // configurations with a cluster, per factor
  Estimate base_eps;                    // mean Eps (factor 1) over configurations
  std::vector<CalibrationConfiguration> configurations;
};

class DbscanCalibration {
 public:
  explicit DbscanCalibration(DbscanCalibrationSettings settings, std::string config_file = "");
  void accumulate(const Trajectory& t, int species_index);
  DbscanCalibrationResult compute() const;

 private:
  DbscanCalibrationSettings s_;
  std::string config_file_;
  std::vector<CalibrationConfiguration> configs_;
  std::size_t replicas_seen_ = 0;
};

}  // namespace anisodyn::analysis
