#pragma once
// Passive microrheology from the 3-D tracer MSD (spec 50 §6.1–6.2):
//   - Mason GSER (F1): α(ω) = d ln MSD / d ln t at t = 1/ω from a local quadratic fit of ln MSD
//     against ln t over ±0.25 decade (Decision), |G*| = k_BT / (π a MSD(1/ω) Γ(1 + α)),
//     G′ = |G*| cos(πα/2), G″ = |G*| sin(πα/2);
//   - the GSER to second order (Decision, docs/analysis.md): the same local quadratic also gives the log
//     curvature β = d² ln MSD / d(ln t)², and G* = k_BT / (π a MSD(1/ω) Γ(1 + α) e^{−iπα/2}
//     [1 + (β/2)((ψ(1 + α) − iπ/2)² + ψ₁(1 + α))]) — the Laplace transform of the local
//     log-quadratic MSD to first order in β. F1 assumes a pure power law and is ~20 % low where α
//     changes quickly (a Maxwell fluid at ωλ ≈ 1); the curvature term brings it within ~3 %;
//   - Evans compliance method (F2): J(t) = (π a / k_BT) MSD(t), J(0) = 0, η_∞⁻¹ = (π a / k_BT)·6 D_long,
//     iω/G*(ω) = (1 − e^{−iωt_1}) J_1/t_1 + η_∞⁻¹ e^{−iωt_N} + Σ_{k≥2} (ΔJ_k/Δt_k)(e^{−iωt_{k−1}} − e^{−iωt_k}).
// Both are evaluated at ω = 1/t_k on the MSD's lag grid. The Evans sum runs over the lags up to the end
// of the D_long fit window (t_N; the last lag with ≥ 20 independent origins by default), and J
// continues beyond with the slope η_∞⁻¹. The MSD, D_long and its fit window come
// from MsdAnalysis (msd.hpp) over the tracer species and the replicas; the moduli errors are a
// jackknife over its per-replica MSD curves (over 10 blocks of time origins for a single replica),
// with D_long refitted in every leave-one-out sample.
//
// Use: PassiveMicrorheology p(settings, replicas); p.accumulate(trajectory) per replica;
// PassiveResult r = p.compute(). The closed-form functions mason_moduli / evans_moduli work on
// any (t, MSD) curve.
#include <cstddef>
#include <limits>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "anisodyn/analysis/msd.hpp"
#include "anisodyn/analysis/replica_statistics.hpp"
#include "anisodyn/analysis/trajectory.hpp"
#include "anisodyn/tool/json_config.hpp"

namespace anisodyn::analysis {

/// Half width of the local fit that gives α(t) (spec 50 §6.1 Decision).
inline constexpr double kMasonHalfWidthDecades = 0.25;

/// Storage and loss moduli on an ω grid.
struct Moduli {
  std::vector<double> omega, storage, loss;
  std::vector<double> alpha;      // Mason only: the local log slope used at t = 1/ω
  std::vector<double> curvature;  // Mason only: the local log curvature β at t = 1/ω
};

/// F1 as printed (local power law) or with the log-curvature term (second order).
enum class GserOrder { First, Second };

/// Mason GSER at ω_k = 1/t_k for every lag t_k (ascending t). NaN where fewer than 4 points lie within
/// the fit window (the shortest lags of a grid with whole frame lags) or MSD ≤ 0.
Moduli mason_moduli(const std::vector<double>& t, const std::vector<double>& msd, double radius, double kT,
                    double half_width_decades = kMasonHalfWidthDecades, GserOrder order = GserOrder::First);

/// Evans compliance method on the grid `omega`, from (t_k, MSD_k) (ascending t, t_1 > 0) with J(0) = 0
/// and the long-time slope η_∞⁻¹ = (π a / k_BT)·6 d_long.
Moduli evans_moduli(const std::vector<double>& t, const std::vector<double>& msd, double radius, double kT, double d_long,
                    const std::vector<double>& omega);

struct PassiveMicrorheologySettings {
  std::string species;        // the tracer species (required)
  double radius = std::numeric_limits<double>::quiet_NaN();  // a; NaN = from the species' sphere diameter
  double kT = 1.0;
  double half_width_decades = kMasonHalfWidthDecades;
  std::optional<double> evans_t_max;  // last lag t_N of the Evans sum; absent = end of the D_long window
  MsdSettings msd;            // lags_per_decade, max_origins, fit window of D_long
};

/// Reads the keys of the passive mode: species, radius | tracer_diameter, kT, alpha_fit_decades,
/// lags_per_decade, max_origins, fit {t_min, t_max}, evans_t_max.
PassiveMicrorheologySettings parse_passive_microrheology_settings(tool::ConfigNode& cfg);

struct PassiveResult {
  std::vector<double> time;                 // MSD lags t_k (ascending)
  std::vector<double> msd, msd_error;       // 3-D tracer MSD and its standard error
  Moduli mason, mason2, evans;              // F1, second-order GSER, F2 on ω_k = 1/t_k, same order as `time`
  Moduli mason_error, mason2_error, evans_error;  // jackknife standard errors (α and β errors in mason2_error)
  Estimate d_long;                          // from MsdAnalysis (component tot)
  double fit_t_min = 0, fit_t_max = 0, fit_mean_beta = 0;
  double evans_t_max = 0;                   // t_N: the last lag in the Evans sum
  bool fit_window_automatic = true;
  double radius = 0, kT = 1;
  std::size_t samples = 0;                  // replicas, or origin blocks for a single replica
  std::size_t tracers = 0;                  // tracer particles per replica
};

class PassiveMicrorheology {
 public:
  /// `settings.radius` must be resolved (> 0) by now (resolve_tracer_radius); kT > 0.
  PassiveMicrorheology(PassiveMicrorheologySettings settings, std::size_t replicas, std::string config_file = "");
  /// Adds one replica; the tracer species must exist and have particles (InputError otherwise).
  void accumulate(const Trajectory& t);
  PassiveResult compute() const;

 private:
  PassiveMicrorheologySettings s_;
  std::string config_file_;
  MsdAnalysis msd_;        // the tracer MSD; its per-replica (per-block) curves feed the jackknife
  std::size_t tracers_ = 0;
};

/// The tracer radius: `settings.radius` if given, else half the diameter of the species' sphere
/// shape in `table`; InputError (naming config_file and the key) if neither applies.
double resolve_tracer_radius(const PassiveMicrorheologySettings& settings, const SpeciesTable& table,
                             const std::string& config_file);

}  // namespace anisodyn::analysis
