#pragma once
// Dipolar-energy clusters (chains) of cubes and their statistics (spec 50 §5.2, 5.4–5.6):
//   - clusters of the bond rule βu_ij < βu_max of dipolar_bonds.hpp (E2), free cubes of size l = 1;
//   - chain statistics X(l,t) = N(l,t)/N_cube, X_c = Σ_{l≥2} l X(l), ⟨l⟩_n, ⟨l⟩_w as time series on
//     the common time grid (mean time stamp of each frame over replicas, each replica linearly
//     interpolated onto it; spec 50 §0), and the response time t_r (E4);
//   - the per-cube cluster-size transition matrix P(l → l′) over a lag δt (E5);
//   - the Wertheim fit X_eq(l) = (1 − p_b)² p_b^{l−1} of the stationary X(l) (E6).
//
// Use: DipolarChainAnalysis a(settings); a.accumulate(trajectory, species) per replica;
// optionally a second pass a.accumulate_transitions(trajectory, species, a.time_of_x2_maximum());
// DipolarChainResult r = a.compute().
#include <array>
#include <cstddef>
#include <functional>
#include <map>
#include <string>
#include <vector>

#include "anisodyn/analysis/dipolar_bonds.hpp"
#include "anisodyn/analysis/replica_statistics.hpp"
#include "anisodyn/analysis/trajectory.hpp"
#include "anisodyn/tool/json_config.hpp"

namespace anisodyn::analysis {

// ---- E4: chain statistics of one configuration ------------------------------------------------

struct ChainStatistics {
  double chain_fraction = 0.0;  // X_c = Σ_{l≥2} l N(l) / N_cube
  double mean_length = 0.0;     // ⟨l⟩_n = Σ_{l≥2} l N(l) / Σ_{l≥2} N(l) (NaN without chains)
  double weight_mean_length = 0.0;  // ⟨l⟩_w = Σ_{l≥2} l² N(l) / Σ_{l≥2} l N(l) (NaN without chains)
};
/// From counts[l − 1] = N(l), l = 1 … counts.size(), and the number of cubes.
ChainStatistics chain_statistics(const std::vector<double>& counts, double cubes);

// ---- E6: Wertheim fit -------------------------------------------------------------------------

struct WertheimFit {
  double p_b = 0.0;
  double error = 0.0;            // jackknife over samples when available, else error_curvature
  double error_curvature = 0.0;  // weighted least squares: 1/√(Σ w (∂X_eq/∂p)²)
  double chi2 = 0.0;             // Σ w (X − X_eq)²
  std::string method;            // how weights / error were obtained
  std::vector<double> length, value, variance, weight, model, residual, normalised_residual;
};
/// X_eq(l) = (1 − p)² p^{l−1}.
double wertheim_fraction(double p, double l);
/// Fit of x[k] = X(l = k + 1) with variances var[k], over l = 1 … the last l with x > 0; weights
/// 1/var, zero or NaN variances floored at the smallest positive one (all unweighted if none).
/// Minimisation of Σ w (x − X_eq)² over p ∈ (0, 1): a scan of 400 points, then golden section.
WertheimFit fit_wertheim(const std::vector<double>& x, const std::vector<double>& var);
/// Fit of the mean of the samples (variance = squared standard error of the mean), error by the
/// jackknife over samples with the weights held fixed (spec 50 §0).
WertheimFit fit_wertheim(const CurveSamples& samples);

// ---- E5: transition matrix --------------------------------------------------------------------

struct TransitionMatrix {
  double t1 = 0.0;                 // requested t_1
  std::string source;              // "given" or "maximum of X(2,t)"
  double window_min = 0.0, window_max = 0.0;  // times of the pooled t_1 frames (over replicas)
  std::size_t frame_pairs = 0;     // pooled (t_1, t_1 + δt) frame pairs
  std::size_t sizes = 0;           // l, l′ = 1 … sizes
  std::vector<double> probability, error;  // [l − 1][l′ − 1] row-major, NaN below 1e-6 or empty rows
  std::vector<double> row_count;   // cubes counted in row l (pooled)
};

// ---- the stage --------------------------------------------------------------------------------

struct DipolarClusterSettings {
  std::string species;
  DipolarBondRule rule;
  std::vector<double> transition_times;  // t_1 values
  bool transition_at_x2_maximum = false; // add t_1 = argmax of the mean X(2,t) (second pass)
  double transition_lag = 0.3;           // δt (τ)
  double transition_window = 0.05;       // pool frames with |t − t_1| ≤ window·t_1 (Decision)
  double lag_tolerance = 0.1;            // accept t(f2) − t(f1) within δt(1 ± tolerance)
  double plateau_fraction = 0.25;        // last fraction of the run: plateau of X_c, stationary X(l)
  std::size_t max_chain_length = 0;      // 0 = largest observed; else larger sizes are lumped in it
};

/// Reads the dipolar keys (gamma, sigma, bu_max, field_direction, transition_*, plateau_fraction,
/// max_chain_length).
DipolarClusterSettings parse_dipolar_cluster_settings(tool::ConfigNode& cfg);

struct DipolarChainResult {
  std::vector<double> time;                // common grid
  std::size_t sizes = 0;                   // l = 1 … sizes
  std::vector<double> x, x_error;          // X(l,t) [frame][l − 1]
  std::vector<double> chain_fraction, chain_fraction_error;
  std::vector<double> mean_length, mean_length_error;
  std::vector<double> weight_mean_length, weight_mean_length_error;
  Estimate plateau, response_time;         // X_c plateau and t_r (jackknife over replicas)
  double plateau_t_min = 0.0;              // start of the plateau window
  std::vector<TransitionMatrix> transitions;
  WertheimFit wertheim;
  std::size_t replicas = 0, cubes = 0;
};

class DipolarChainAnalysis {
 public:
  explicit DipolarChainAnalysis(DipolarClusterSettings settings, std::string config_file = "");
  /// Clusters every frame of one replica: time series and transitions at the given t_1 values.
  void accumulate(const Trajectory& t, int species_index);
  /// t_1 = the time of the maximum of the replica-mean X(2,t) on the common grid.
  double time_of_x2_maximum() const;
  /// Transition counts at one more t_1 (a second pass over the same replicas, in the same order).
  void accumulate_transitions(const Trajectory& t, int species_index, double t1, const std::string& source);
  DipolarChainResult compute() const;

 private:
  struct Replica {
    std::vector<double> time;
    std::vector<std::vector<double>> counts;    // [frame][l − 1] = N(l), sizes above the cap lumped
    std::vector<std::array<double, 3>> stats;   // [frame] X_c, ⟨l⟩_n, ⟨l⟩_w (exact, never lumped)
  };
  struct TransitionCounts {
    double t1 = 0.0;
    std::string source;
    double window_min = 0.0, window_max = 0.0;
    std::size_t frame_pairs = 0;
    std::vector<std::map<std::pair<std::size_t, std::size_t>, double>> per_replica;  // (l, l′) → cubes
  };
  std::size_t size_class(std::size_t l) const;
  /// Cluster size of every member at each of `frames`.
  std::vector<std::vector<std::size_t>> cluster_sizes(const Trajectory& t, const std::vector<std::size_t>& members,
                                                      const std::vector<std::size_t>& frames) const;
  /// Frame pairs (f1, f2): f1 within ±window·t_1 of t_1 (always the frame nearest t_1), f2 the frame
  /// nearest t(f1) + δt when within the lag tolerance. None → InputError naming `key`.
  std::vector<std::pair<std::size_t, std::size_t>> transition_frames(const Trajectory& t, double t1, const std::string& key) const;
  void count_transitions(const Trajectory& t, const std::vector<std::size_t>& members, TransitionCounts& tc,
                         const std::function<const std::vector<std::size_t>&(std::size_t)>& sizes_at) const;
  std::vector<double> common_grid() const;

  DipolarClusterSettings s_;
  std::string config_file_;
  std::vector<Replica> replicas_;
  std::vector<TransitionCounts> transitions_;
  std::size_t cubes_ = 0, largest_ = 1;
};

}  // namespace anisodyn::analysis
