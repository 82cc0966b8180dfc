#pragma once
// Orientational order of a set of particles in one frame (spec 50 §3.1–3.4):
//   - per-axis Q tensors Q^{kk} = (1/2N) Σ_i (3 ê_k,i ⊗ ê_k,i − I), k = T, W, L, their eigenvalues
//     S_2,k, the largest U_k and its eigenvector d_k; the nematic director is d_k of the largest U_k;
//   - the biaxial order B_2,K about a main axis K (§3.2);
//   - the rod order tensor S = (1/N) Σ û û (trace 1, §3.3) of one body axis;
//   - the cube order parameter S_i (§3.4) averaged over all cubes, and over cubes in dipolar chains
//     and free cubes when a chain mask is given (dipolar_chain_mask of dipolar_bonds.hpp, the bond
//     rule of §5.2).
//
// The kernels take the particles' rotation matrices (columns = body axes T, W, L in the lab), so
// they can be tested without files; frame_rotations() extracts them from a Trajectory.
// The order time-series stage (anisodyn-order) is OrderAnalysis at the end of this file.
#include <array>
#include <cmath>
#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "anisodyn/analysis/dipolar_bonds.hpp"
#include "anisodyn/analysis/replica_statistics.hpp"
#include "anisodyn/analysis/trajectory.hpp"
#include "anisodyn/core/types.hpp"
#include "anisodyn/tool/json_config.hpp"

namespace anisodyn::analysis {

/// Isotropic constants of the cube order parameter (spec 50 §3.4):
/// ⟨max_k (n̂·ê_k)²⟩_iso = (π + 2√3)/(3π) and ⟨P_2(max_k |n̂·ê_k|)⟩_iso = √3/π.
inline const double kCubeIsotropicMaxCos2 = (M_PI + 2.0 * std::sqrt(3.0)) / (3.0 * M_PI);
inline const double kCubeIsotropicP2 = std::sqrt(3.0) / M_PI;
/// Biaxiality thresholds of spec 50 §3.2.
inline constexpr double kBiaxialThreshold = 0.35;
inline constexpr double kWeaklyBiaxialThreshold = 0.20;

struct AxisOrder {
  Mat3 q = Mat3::Zero();
  Vec3 eigenvalues = Vec3::Zero();  // S_2,k, ascending
  double order = 0.0;               // U_k, the largest eigenvalue
  Vec3 director = Vec3::UnitZ();    // d_k
};

struct CubeOrder {
  double total = std::nan("");   // S^(tot): mean S_i over all particles
  double chain = std::nan("");   // S^(c): over particles in clusters of size ≥ 2 (NaN without a mask or none)
  double free = std::nan("");    // S^(free): over free particles
  double max_cos2 = std::nan(""); // ⟨max_k (Ê·ê_k)²⟩ over all particles
  double chain_fraction = std::nan("");  // fraction of particles in chains
};

struct FrameOrder {
  std::array<AxisOrder, 3> axis;  // T, W, L
  int nematic_axis = 2;           // k of the largest U_k
  double nematic_order = 0.0;     // max_k U_k
  Vec3 director = Vec3::UnitZ();  // nematic director d_k of that axis
  int main_axis = 2;              // K of B_2,K
  double biaxial = 0.0;           // B_2,K
  Mat3 rod_tensor = Mat3::Zero(); // S of the rod axis
  double rod_order = 0.0;         // largest eigenvalue of S
  CubeOrder cube;
};

struct OrderSettings {
  int main_axis = -1;             // K of B_2,K: 0 T, 1 W, 2 L; −1 = the axis of largest U (resolved by the caller)
  int rod_axis = 2;               // body axis of the rod order tensor
  Vec3 field_direction = Vec3::UnitZ();  // Ê for S_i and the chain rule
  std::optional<DipolarBondRule> chains;  // its field is field_direction
};

/// Body axis from a config value: "T"/"x" → 0, "W"/"y" → 1, "L"/"z" → 2, "auto" → −1 (if allowed).
int parse_body_axis(tool::ConfigNode& cfg, const std::string& key, const std::string& fallback, bool allow_auto);
/// "T", "W" or "L".
const char* axis_letter(int k);

/// Eigen-decomposition of a Q tensor.
AxisOrder axis_order(const Mat3& q);
/// The three per-axis Q tensors of a set of particles (rotation columns = body axes).
std::array<Mat3, 3> axis_q_tensors(const std::vector<Mat3>& rotations);
/// Index of the largest U among the three tensors.
int largest_order_axis(const std::array<Mat3, 3>& q);
/// B_2,K of spec 50 §3.2 with n̂ the director of Q^{KK}, P = (K + 2) mod 3, R = (K + 1) mod 3 (for K = L:
/// P = W, R = T as in the spec's example); p̂ from Q^{PP} projected ⊥ n̂, r̂ = n̂ × p̂.
double biaxial_order(const std::array<Mat3, 3>& q, int main_axis);
/// S = (1/N) Σ û û for the body axis `axis`.
Mat3 rod_order_tensor(const std::vector<Mat3>& rotations, int axis);
/// max_k (Ê·ê_k)² of one particle.
double max_squared_projection(const Mat3& rotation, const Vec3& field);
/// S_i = [π (3 max_k (Ê·ê_k)² − 1) − 2√3] / (2π − 2√3).
double cube_order(const Mat3& rotation, const Vec3& field);
/// Cube order averages; in_chain (one flag per particle, may be empty) splits S^(c) and S^(free).
CubeOrder cube_order_average(const std::vector<Mat3>& rotations, const Vec3& field, const std::vector<char>& in_chain);
/// Every order parameter of one frame; main_axis K of B_2 (0–2, or −1 for this frame's nematic axis); in_chain as above.
FrameOrder frame_order(const std::vector<Mat3>& rotations, const OrderSettings& s, int main_axis,
                       const std::vector<char>& in_chain = {});
/// Rotation matrices of the `members` at frame f.
std::vector<Mat3> frame_rotations(const Trajectory& t, std::size_t f, const std::vector<std::size_t>& members);
/// Positions of the `members` at frame f (unwrapped; the chain rule applies the minimum image).
std::vector<Vec3> frame_positions(const Trajectory& t, std::size_t f, const std::vector<std::size_t>& members);
/// Frame order of the members at frame f of a trajectory, with the chain split when s.chains is set.
FrameOrder trajectory_frame_order(const Trajectory& t, std::size_t f, const std::vector<std::size_t>& members,
                                  const OrderSettings& s, int main_axis);
/// Axis of the largest U of the Q tensors averaged over the frames [first, last) (spec 50 §3.2
/// Decision: "the axis whose U was largest"); `order` receives the three averaged U_k.
int run_averaged_main_axis(const Trajectory& t, const std::vector<std::size_t>& members, std::size_t first, std::size_t last,
                           Vec3* order = nullptr);

/// Linear interpolation of (time, value) onto a grid (constant beyond the ends): puts replicas on
/// the common time grid of the non-equilibrium convention (spec 50 §0).
std::vector<double> interpolate_onto(const std::vector<double>& time, const std::vector<double>& value,
                                     const std::vector<double>& grid);

// ---- anisodyn-order: time series of the order parameters over replicas ----------------------------

struct OrderStageSettings {
  std::string species;                                     // "" = every anisotropic species
  OrderSettings order;
  std::vector<std::string> observables{"U", "B2", "S_rod", "S_cube"};
  double average_from = -INFINITY;                         // run averages over frames with t ≥ this
};

/// Reads the keys of anisodyn-order (species, observables, main_axis, rod_axis, field_direction,
/// chain_threshold {gamma, sigma, bu_max}, average_from).
OrderStageSettings parse_order_settings(tool::ConfigNode& cfg);

struct OrderSeries {
  std::string name, units, definition;
  std::vector<double> mean, error;        // on the common grid, SE over replicas (NaN for one replica)
  Estimate run_average;                   // mean of the replicas' run averages; SE over replicas, or block error for one
  std::vector<double> replica_average, replica_block_error;
};

struct OrderResult {
  std::vector<double> time;               // common grid: mean time stamp of each frame
  std::vector<OrderSeries> series;
  int main_axis = 2;
  Vec3 main_axis_order = Vec3::Zero();    // run-averaged U_k of the first replica (the main-axis choice)
  std::size_t particles = 0, replicas = 0, averaged_frames = 0;
  double isotropic_baseline = 0.0;        // finite-N mean largest eigenvalue for random orientations
  double largest_eigenvalue = 0.0;        // largest run-averaged U_k
  bool nematic = false;
  const OrderSeries& get(const std::string& name) const;
};

class OrderAnalysis {
 public:
  OrderAnalysis(OrderStageSettings settings, std::string config_file = "");
  /// Adds one replica: the order of the particles of `species_index` at every frame.
  void accumulate(const Trajectory& t, int species_index);
  /// Means over replicas on the common grid (for_each_replica's return value).
  OrderResult compute(const std::vector<double>& common_time) const;

 private:
  std::vector<std::string> names() const;
  OrderStageSettings s_;
  std::string config_file_;
  int main_axis_ = -1;
  Vec3 main_axis_order_ = Vec3::Zero();
  std::size_t particles_ = 0;
  std::vector<std::vector<double>> times_;                 // [replica][frame]
  std::vector<std::vector<std::vector<double>>> values_;   // [replica][series][frame]
};

}  // namespace anisodyn::analysis
