#pragma once
// Rotational statistics per body axis (spec 50 §2.1 and §2.3): MSAD ⟨φ_λ²(t)⟩ of the unbounded
// rotation vector and the Legendre correlations C_n(t) = ⟨P_n(û(t0+t)·û(t0))⟩, n = 1, 2, with
// rotational diffusion coefficients from both: D_r = slope/4 of the MSAD (a linear rod; for body
// axis λ it is (D_α + D_β)/2 of the other two axes) and D_r = −slope/(n(n+1)) of ln C_n.
#include <optional>
#include <string>
#include <vector>

#include "anisodyn/analysis/lag_grid.hpp"
#include "anisodyn/analysis/replica_statistics.hpp"
#include "anisodyn/analysis/trajectory.hpp"
#include "anisodyn/tool/json_config.hpp"

namespace anisodyn::analysis {

struct RotationSettings {
  std::string species;
  std::vector<int> axes{0, 1, 2};  // body axes analysed (T, W, L)
  double lags_per_decade = 10.0;
  std::size_t max_origins = 0;
  std::optional<std::pair<double, double>> fit_window;  // MSAD fit; absent → every lag up to t_run/20
  // C_n fits use the lags where floor ≤ C_n < ceiling. Spec 20 §6.1 asks for 0.05 … 0.5 (the
  // late-time plateau of the decay rate); the ceiling defaults to 1 so that earlier outputs stay the same.
  double correlation_floor = 0.05;
  double correlation_ceiling = 1.0;
};

RotationSettings parse_rotation_settings(tool::ConfigNode& cfg);

/// The lags a C_n fit used: [t_min, t_max] of the lags with floor ≤ C_n < ceiling (NaN if none).
struct CorrelationFitWindow {
  double t_min = 0, t_max = 0;
  std::size_t lags = 0;
};

struct AxisRotation {
  int axis = 0;
  std::vector<double> msad, msad_error, c1, c1_error, c2, c2_error;
  Estimate D_msad, D_c1, D_c2;
  CorrelationFitWindow window_c1, window_c2;
  bool exact_rotation_vectors = false;
  std::size_t violations = 0, intervals = 0;
};

struct RotationResult {
  std::vector<double> lag;
  std::vector<AxisRotation> axes;
  double fit_t_min = 0, fit_t_max = 0;
  std::size_t samples = 0;
};

class RotationAnalysis {
 public:
  RotationAnalysis(RotationSettings settings, std::size_t replicas);
  void accumulate(const Trajectory& t, int species_index);
  RotationResult compute() const;

 private:
  RotationSettings s_;
  std::size_t replicas_;
  LagGrid grid_;
  ReplicaMeanLags lags_;
  std::size_t seen_ = 0;
  CurveSamples samples_;  // per sample: [axis][msad, c1, c2][lag]
  std::vector<std::size_t> violations_, intervals_;
  std::vector<bool> exact_;
};

}  // namespace anisodyn::analysis
