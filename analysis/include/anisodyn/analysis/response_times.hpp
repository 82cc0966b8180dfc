#pragma once
// Response times of field switching (spec 50 §8):
//   - per trajectory, the signal (B_2 by default) is smoothed by a centred moving average over 1% of
//     each segment's frames (Decision), then
//     t_ON     = first time after switch-on with B(t) ≥ 0.95 B_on, B_on = mean of the last 25% of the
//                on-segment;
//     t_OFF    = first time after switch-off with B(t) ≤ 1.05 B_eq,off (the literal "105%"),
//                B_eq,off = mean of the field-off segment before the switch-on;
//     t_OFF,95 = first time after switch-off with B(t) ≤ B_eq,off + 0.05 (B_on − B_eq,off);
//     times are measured from the switching instant and located by linear interpolation between
//     the two frames that bracket the threshold;
//   - over trajectories, the modified Z-score M_j = 0.6745 (t_j − t̃)/MAD rejects |M_j| > 3.5
//     (Iglewicz & Hoaglin 1993) and flags the one-sided M_j > 3.5; mean ± SE of the retained values.
#include <cstddef>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "anisodyn/analysis/order_parameters.hpp"
#include "anisodyn/analysis/replica_statistics.hpp"
#include "anisodyn/analysis/trajectory.hpp"
#include "anisodyn/tool/json_config.hpp"

namespace anisodyn::analysis {

struct ResponseParameters {
  double smoothing_fraction = 0.01;  // moving-average window / segment length (Decision)
  double on_tail_fraction = 0.25;    // B_on from the last 25% of the on-segment
  double on_fraction = 0.95;         // t_ON threshold: B ≥ 0.95 B_on
  double off_factor = 1.05;          // t_OFF threshold: B ≤ 1.05 B_eq,off
  double off_margin = 0.05;          // t_OFF,95 threshold: B ≤ B_eq,off + 0.05 (B_on − B_eq,off)
};

/// One switching cycle: field-off reference segment [reference_start, on), on-segment [on, off),
/// off-segment [off, end). off = NaN when the field is never switched off.
struct SwitchCycle {
  double reference_start = -std::numeric_limits<double>::infinity();
  double on = std::numeric_limits<double>::quiet_NaN();
  double off = std::numeric_limits<double>::quiet_NaN();
  double end = std::numeric_limits<double>::infinity();
  std::optional<Vec3> field;  // field direction recorded at switch-on, if any
};

/// Cycle `cycle` (0 = first) of a field_switches observable: rows (time, [on, ex, ey, ez]), the first
/// row being the initial state. No such switch-on → InputError naming `path`.
SwitchCycle switch_cycle_from_observable(const ObservableSeries& switches, std::size_t cycle, const std::string& path);

/// Centred moving average with `window` frames (an even window is widened by one to stay centred);
/// truncated at the ends.
std::vector<double> moving_average(const std::vector<double>& x, std::size_t window);

struct ReplicaResponse {
  double switch_on = std::numeric_limits<double>::quiet_NaN(), switch_off = std::numeric_limits<double>::quiet_NaN();
  double t_on = std::numeric_limits<double>::quiet_NaN();
  double t_off = std::numeric_limits<double>::quiet_NaN();
  double t_off95 = std::numeric_limits<double>::quiet_NaN();
  double b_on = std::numeric_limits<double>::quiet_NaN();
  double b_eq_off = std::numeric_limits<double>::quiet_NaN();
  std::size_t window_on = 0, window_off = 0;              // smoothing windows (frames, odd)
  std::size_t reference_frames = 0, on_frames = 0, off_frames = 0;
};

/// §8.1 on one trajectory's signal.
ReplicaResponse response_times(const std::vector<double>& time, const std::vector<double>& signal, const SwitchCycle& cycle,
                               const ResponseParameters& p = {});

struct OutlierRejection {
  std::vector<double> score;              // M_j (NaN for missing values)
  std::vector<char> rejected, one_sided;  // |M_j| > threshold; M_j > threshold
  Estimate retained;                      // mean ± SE of the retained values
  std::size_t used = 0, rejected_count = 0, one_sided_count = 0, missing = 0;
  bool mean_absolute_deviation = false;   // MAD was 0: M_j = (t_j − t̃)/(1.253314 · mean |t − t̃|)
};

/// §8.2 over the finite values of t (NaN = threshold never reached: left out and counted as missing).
OutlierRejection reject_outliers(const std::vector<double>& t, double threshold = 3.5);

// ---- anisodyn-response --------------------------------------------------------------------------

struct ResponseSettings {
  std::string species;                 // "" = every anisotropic species
  std::string signal = "B2";           // B2 | U_L | U_W | U_T | S_cube
  OrderSettings order;                 // main axis K of B_2 (−1 = largest U before the switch-on), field direction
  bool field_given = false;            // field_direction from the config (else from field_switches, else z)
  std::optional<double> switch_on, switch_off;  // from the config; absent → the field_switches observable
  std::size_t cycle = 0;
  ResponseParameters parameters;
  double z_threshold = 3.5;
};

/// Reads the keys of anisodyn-response (species, signal, main_axis, field_direction, switch_on,
/// switch_off, cycle, smoothing_fraction, outlier_threshold).
ResponseSettings parse_response_settings(tool::ConfigNode& cfg);

struct ResponseResult {
  std::string signal;
  int main_axis = 2;
  Vec3 main_axis_order = Vec3::Zero();   // U_k before the switch-on in the first replica
  std::vector<ReplicaResponse> replicas;
  std::vector<std::string> paths;
  OutlierRejection on, off, off95;
  std::vector<double> curve_time, curve, curve_se;  // signal against time since switch-on (common grid)
};

class ResponseAnalysis {
 public:
  ResponseAnalysis(ResponseSettings settings, std::string config_file = "");
  /// Adds one replica: the signal of the particles of `species_index` at every frame and the switch
  /// instants (config, or the replica's field_switches observable).
  void accumulate(const Trajectory& t, int species_index);
  ResponseResult compute() const;

 private:
  SwitchCycle cycle_of(const Trajectory& t) const;
  double signal_of(const FrameOrder& o) const;
  ResponseSettings s_;
  std::string config_file_;
  int main_axis_ = -1;
  Vec3 main_axis_order_ = Vec3::Zero();
  std::vector<std::string> paths_;
  std::vector<std::vector<double>> times_, signals_;
  std::vector<SwitchCycle> cycles_;
};

}  // namespace anisodyn::analysis
