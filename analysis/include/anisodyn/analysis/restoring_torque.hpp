#pragma once
// Method III of spec 20 §6.3: the self-rotational diffusion D_r(φ) of rods from the restoring
// torque. For the Itô update û ← û + β D_r T×û Δt + noise (renormalised), the generator gives
//   d/dt ⟨û(t)·û(0)⟩ = −2 D_r ⟨û(t)·û(0)⟩ + β D_r ⟨(T(t)×û(t))·û(0)⟩
//                    = −2 D_r C₁(t) + β D_r ⟨(û(t)×û(0))·T(t)⟩,
// so with βT_r(t) = β⟨(û(t)×û(0))·T̄(t)⟩ / C₁(t) (T̄ the systematic torque at the later time):
//   D_r(φ, t) = −½ d ln C₁/dt = D_r [1 − ½ βT_r(t)],
// and for n = 2 (R̂ P₂(û·û₀) = P₂′ û×û₀, P₂′(x) = 3x):
//   D_r⁽²⁾(φ, t) = −⅙ d ln C₂/dt = D_r [1 − β⟨P₂′(x)(û(t)×û(0))·T̄⟩ / (6 C₂(t))].
// The reconstruction check is C₁^rec(t) = exp[−2 ∫₀ᵗ D_r(φ, τ) dτ] (trapezoid from D_r(φ, 0) = D_r).
// Averages over the rods of a species, every time origin of the lag grid, and replicas.
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "anisodyn/analysis/lag_grid.hpp"
#include "anisodyn/analysis/replica_statistics.hpp"
#include "anisodyn/analysis/trajectory.hpp"
#include "anisodyn/tool/json_config.hpp"

namespace anisodyn::analysis {

/// The per-particle element holding T̄ (anisodyn-bd writes it with the rod potential).
inline constexpr const char* kSystematicTorque = "systematic_torque";

struct RestoringTorqueSettings {
  std::string species;
  double lags_per_decade = 10.0;
  std::size_t max_origins = 0;
  /// The plateau: the given lag window {t_min, t_max}, else the lags with floor ≤ C₁ ≤ ceiling
  /// (the late-time range Method I fits in, spec 20 §6.1).
  std::optional<std::pair<double, double>> plateau_window;
  double plateau_floor = 0.05, plateau_ceiling = 0.5;
};

RestoringTorqueSettings parse_restoring_torque_settings(tool::ConfigNode& cfg);

struct RestoringTorqueResult {
  std::vector<double> lag;
  std::vector<double> c1, c1_error, c2, c2_error;           // direct Legendre correlations
  std::vector<double> beta_torque, beta_torque_error;       // βT_r(t)
  std::vector<double> dr1, dr1_error, dr2, dr2_error;       // D_r(φ, t) from n = 1 and n = 2
  std::vector<double> c1_reconstructed, c1_reconstructed_error;
  double free_dr = 0;                                       // D_r of the free rod
  double plateau_t_min = 0, plateau_t_max = 0;              // NaN if no lag qualifies
  std::size_t plateau_lags = 0;
  Estimate dr1_plateau, dr2_plateau, beta_torque_plateau;   // D_r(φ), D_r⁽²⁾(φ), βT_r
  std::size_t samples = 0;
  double capped_torques = 0;  // particle-steps with a capped torque (the `capped` observable), summed
  bool capped_known = false;
};

class RestoringTorqueAnalysis {
 public:
  RestoringTorqueAnalysis(RestoringTorqueSettings settings, std::size_t replicas);
  void accumulate(const Trajectory& t, int species_index);
  /// free_dr: the species' free-rod D_r (free_rotation.hpp), the D_r of the equations above.
  RestoringTorqueResult compute(double free_dr) const;

 private:
  /// The curves of D_r(φ, t) etc. from one mean sample [c1 | s1 | c2 | s2] × lags.
  static std::vector<double> derived_curves(const std::vector<double>& m, const std::vector<double>& lag, double free_dr);
  std::vector<std::size_t> plateau_lags(const std::vector<double>& lag, const std::vector<double>& c1) const;

  RestoringTorqueSettings s_;
  std::size_t replicas_;
  LagGrid grid_;
  ReplicaMeanLags lags_;
  std::size_t seen_ = 0;
  CurveSamples samples_;  // per sample: [C₁ | β⟨(û(t)×û(0))·T̄⟩ | C₂ | β⟨3x (û(t)×û(0))·T̄⟩] × lags
  double capped_torques_ = 0;
  bool capped_known_ = false;
};

}  // namespace anisodyn::analysis
