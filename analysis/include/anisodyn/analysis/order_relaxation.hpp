#pragma once
// Collective rotational diffusion of rods from the order tensor S = (1/N) Σ û û that anisodyn-bd
// records every observe_every steps as the observable `order_tensor_<species>` (xx, yy, zz, xy, xz,
// yz), spec 20 §7 and spec 50 §9.3 (I3):
//   - Method A (`decay`): each replica is one decay from the aligned start û = ẑ. The replicas are
//     put on the common time grid (spec 50 §0) and δS_zz(t) = S_zz(t) − 1/3 of their mean is fitted
//     by ln δS_zz = a − 6 D_r^coll t in the window where band_low < δS_zz < band_high and
//     δS_zz > noise_factor × the equilibrium noise level (the rms of the mean δS_zz over the late
//     rows t ≥ noise_from);
//   - Method B (`regression`): δS = S − ⟨S⟩ with ⟨S⟩ each replica's mean over its rows, and
//     C(t) = ⟨δS(t0 + t) : δS(t0)⟩ (the full contraction, off-diagonal components counted twice)
//     over every time origin; ln C is fitted over the lags where band_low ≤ C/C(0) ≤ band_high,
//     D_r^coll = −slope/6.
// The fit window runs from the first row (lag) below the band's upper edge to the last one before
// the curve first falls to its lower edge: noise at the upper edge does not cut the window short,
// and a later noisy point that re-enters the band is not fitted. Errors: jackknife over replicas (Method B with one replica:
// 10 blocks of time origins).
#include <cstddef>
#include <functional>
#include <string>
#include <vector>

#include "anisodyn/analysis/fitting.hpp"
#include "anisodyn/analysis/lag_grid.hpp"
#include "anisodyn/analysis/replica_statistics.hpp"
#include "anisodyn/analysis/trajectory.hpp"
#include "anisodyn/tool/json_config.hpp"

namespace anisodyn::analysis {

enum class RelaxationMethod { Decay, Regression };

struct OrderRelaxationSettings {
  std::string species;  // "" = every anisotropic species
  RelaxationMethod method = RelaxationMethod::Decay;
  double band_low = 0.02, band_high = 0.1;  // δS_zz (decay) or C/C(0) (regression; 0.05, 0.5)
  // decay
  double noise_from = -INFINITY;            // −∞: the last quarter of the rows' time span
  double noise_factor = 3.0;
  // regression
  double lags_per_decade = 10.0;
  std::size_t max_origins = 0;
};

/// Reads method, species, fit_band, and the keys of the chosen method (noise_from, noise_factor for
/// decay; lags_per_decade, max_origins for regression); the other method's keys are refused.
OrderRelaxationSettings parse_order_relaxation_settings(tool::ConfigNode& cfg);

/// The name of a species' order-tensor observable.
std::string order_tensor_observable(const std::string& species);

/// S_ab of a row (xx, yy, zz, xy, xz, yz) contracted with another: Σ_ab δS_ab δS'_ab, the
/// off-diagonal components counted twice.
double full_contraction(const double* a, const double* b);

/// Rows [first, last) of a fit window.
struct IndexWindow {
  std::size_t first = 0, last = 0;
  std::size_t size() const { return last - first; }
};
/// The window of a decaying curve over indices start … n − 1: first = the first index with
/// below_top(k), last = the first index from there without above_bottom(k) (n if none); empty
/// (first = last = n) if the curve never falls below the top.
IndexWindow decay_window(std::size_t start, std::size_t n, const std::function<bool(std::size_t)>& below_top,
                         const std::function<bool(std::size_t)>& above_bottom);

/// D_r^coll = −slope/6 of ln y over x[window] (ordinary least squares).
double collective_rate(const std::vector<double>& x, const std::vector<double>& y, const IndexWindow& window);

struct RelaxationFit {
  Estimate rate;             // D_r^coll
  IndexWindow window;        // rows (decay) or lags (regression) fitted
  double t_min = 0, t_max = 0;
  std::string error_method;
};

struct OrderDecayResult {
  std::vector<double> time;  // common grid
  std::vector<double> s_xx, s_xx_error, s_yy, s_yy_error, s_zz, s_zz_error, ds_zz;
  double noise = 0.0, noise_from = 0.0, threshold = 0.0;  // rms of δS_zz at t ≥ noise_from; the band's lower edge in force
  std::size_t noise_rows = 0, replicas = 0;
  RelaxationFit fit;
};

struct OrderRegressionResult {
  std::vector<double> lag, correlation, correlation_error, normalised, normalised_error, origins;
  std::size_t samples = 0, replicas = 0, rows = 0;
  RelaxationFit fit;
};

/// One replica's order tensor rows: times and [rows × 6]; a missing or malformed observable →
/// InputError naming the file and its HDF5 path.
const ObservableSeries& order_tensor_rows(const Trajectory& t, const std::string& species);

class OrderRelaxationAnalysis {
 public:
  OrderRelaxationAnalysis(OrderRelaxationSettings settings, std::size_t replicas, std::string config_file);
  /// Adds one replica: the rows of the observable order_tensor_<species>.
  void accumulate(const Trajectory& t, int species_index);
  OrderDecayResult decay() const;            // Method A
  OrderRegressionResult regression() const;  // Method B

 private:
  void add_correlation_samples(const ObservableSeries& s);
  OrderRelaxationSettings s_;
  std::string config_file_, first_path_;
  std::size_t replicas_, rows_ = 0, seen_ = 0;
  std::vector<double> time_sum_;                 // row times summed over replicas
  std::vector<std::vector<double>> times_;       // decay: [replica][row]
  std::vector<std::vector<double>> tensors_;     // decay: [replica][row × 6]
  LagGrid grid_;                                 // regression: lags over the first replica's rows
  std::vector<double> lag_sum_, origin_count_;   // regression: per lag class (lag 0 first)
  CurveSamples correlations_;                    // regression: per sample C at lag 0, then each lag class
};

}  // namespace anisodyn::analysis
