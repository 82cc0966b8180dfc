#pragma once
// Self van Hove functions at requested lag times (spec 50 §1.6 A6 and §2.2 B2):
//   translational, per component λ of dimension d: v_d G_s,λ(r, t) with ∫ v_d G dr = 1,
//     v_1 = 2 (two-sided, Decision), v_2 = 2πr, v_3 = 4πr²; Gaussian reference
//     (4π D_λ,t t)^{−d/2} exp(−r²/(4 D_λ,t t)), D_λ,t = ⟨Δr_λ²⟩/(2dt) at the same t;
//   angular, per body axis: G(φ, t) with ∫ 4πφ² G dφ = 1 over |Δφ⃗| of the unbounded rotation vector;
//     reference: the d-dimensional Gaussian with the same ⟨φ²⟩ (d = 2: φ⃗ ⟂ the axis), expressed in
//     the same normalisation.
// Bins: width 0.02 ⟨Δr²⟩^{1/2} (Decision) fixed from the first replica, 500 bins; angular 0.02 rad.
#include <optional>
#include <string>
#include <vector>

#include "anisodyn/analysis/lag_grid.hpp"
#include "anisodyn/analysis/replica_statistics.hpp"
#include "anisodyn/analysis/trajectory.hpp"
#include "anisodyn/tool/json_config.hpp"

namespace anisodyn::analysis {

struct VanHoveSettings {
  std::string species;
  std::vector<double> times;             // requested lags (nearest lag class is used)
  std::vector<std::string> components{"tot", "x", "y", "z"};  // tot x y z par perp
  Vec3 direction = Vec3::UnitZ();        // for par / perp
  std::optional<double> bin_width;       // translational; default 0.02 ⟨Δr²⟩^{1/2}
  std::size_t bins = 500;
  std::vector<int> angular_axes;         // body axes for the angular function (empty: none)
  double angular_bin_width = 0.02;
  int angular_dimension = 2;
  double lags_per_decade = 10.0;
  std::size_t max_origins = 0;
};

VanHoveSettings parse_van_hove_settings(tool::ConfigNode& cfg);

struct VanHoveCurve {
  std::string component;  // tot, x, …, or phi_T / phi_W / phi_L
  int dimension = 3;
  double time = 0;        // lag used
  double mean_square = 0; // ⟨Δr_λ²⟩ (or ⟨φ²⟩) at that lag
  double overflow = 0;    // fraction beyond the last bin
  std::vector<double> r, g, g_error, gaussian;
};

class VanHoveAnalysis {
 public:
  VanHoveAnalysis(VanHoveSettings settings, std::size_t replicas);
  void accumulate(const Trajectory& t, int species_index);
  std::vector<VanHoveCurve> compute() const;

 private:
  struct Channel {
    std::string component;
    int dimension = 3, axis = -1;  // axis ≥ 0: angular
    std::size_t lag_class = 0;
    double width = 0;
  };
  void add_channel_counts(const Trajectory& t, const std::vector<std::size_t>& members, const Channel& ch,
                          const std::vector<double>* phi, std::vector<std::vector<double>>& hist, std::vector<double>& m2,
                          std::vector<double>& count) const;
  VanHoveSettings s_;
  std::size_t replicas_, seen_ = 0;
  LagGrid grid_;
  std::vector<Channel> channels_;
  std::vector<CurveSamples> samples_;   // per channel: [bins…, mean square, overflow]
  std::vector<double> lag_sum_;
};

}  // namespace anisodyn::analysis
