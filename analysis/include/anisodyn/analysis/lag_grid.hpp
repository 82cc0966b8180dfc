#pragma once
// Lags and time origins for correlation functions over frames that are spaced linearly or
// logarithmically (spec 50 §0). Each lag class is a set of frame pairs (origin, origin + lag):
//   - uniform frames: lag classes are whole frame lags k on a log-thinned grid (every lag below
//     `per_decade`, then `per_decade` lags per decade), with every available origin;
//   - other spacings (DMC log frames, mixed schedules): every pair (i < j) is put in a log bin of
//     its lag t_j − t_i, `per_decade` bins per decade; the class's lag is the mean over its pairs.
// The origins of a class can be thinned to at most `max_origins` (evenly spread).
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "anisodyn/tool/json_config.hpp"

namespace anisodyn::analysis {

struct LagClass {
  double lag = 0.0;  // mean lag time of the pairs
  std::vector<std::pair<std::uint32_t, std::uint32_t>> pairs;  // (origin frame, later frame)
};

struct LagGrid {
  bool uniform = false;
  double frame_spacing = 0.0;  // for uniform frames
  std::vector<LagClass> classes;  // ascending lag
};

/// Error samples per replica: with one replica, `blocks` contiguous blocks of time origins stand in
/// for replicas (spec 50 §0: block averaging for a single run); otherwise the replica itself.
inline std::size_t error_blocks(std::size_t replicas, std::size_t blocks = 10) { return replicas == 1 ? blocks : 1; }
/// The block of an origin frame.
inline std::size_t origin_block(std::size_t origin, std::size_t frames, std::size_t blocks) {
  const std::size_t b = origin * blocks / frames;
  return b < blocks ? b : blocks - 1;
}

/// The lag time of each class averaged over replicas (spec 50 §0: the reported time of a lag is
/// the mean over replicas): each replica adds the mean lag of each class's pairs on its own times.
class ReplicaMeanLags {
 public:
  void add(const LagGrid& grid, const std::vector<double>& time);
  std::vector<double> mean() const;

 private:
  std::vector<double> sum_;
  std::size_t replicas_ = 0;
};

/// A lag window {t_min, t_max} (t_min > 0, t_max > t_min) under `key`, absent when not given.
std::optional<std::pair<double, double>> parse_lag_window(tool::ConfigNode& cfg, const std::string& key);

/// Index of the lag class whose lag is nearest to t (in log distance).
std::size_t nearest_lag_class(const LagGrid& grid, double t);

/// True if consecutive time differences agree within rel_tol.
bool uniformly_spaced(const std::vector<double>& time, double rel_tol = 1e-6);

/// Whole lags 1 … max_lag on a log grid: every lag up to per_decade, then ~per_decade per decade,
/// always including max_lag. per_decade ≤ 0 → every lag.
std::vector<std::size_t> log_spaced_lags(std::size_t max_lag, double per_decade);

/// Lag classes for frame times `time`. max_origins = 0 keeps every origin.
LagGrid make_lag_grid(const std::vector<double>& time, double per_decade, std::size_t max_origins = 0);

}  // namespace anisodyn::analysis
