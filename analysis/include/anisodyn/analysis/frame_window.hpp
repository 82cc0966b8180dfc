#pragma once
// The time window every analysis stage takes (docs/analysis.md, "Time windows"):
//
//   "window": {"from": t0, "to": t1, "stride": k}
//
// from and to are trajectory times (mapped Brownian time for DMC, integration time otherwise),
// inclusive, each optional; stride k ≥ 1 keeps every k-th frame of the window, starting with its
// first. The frames are chosen on the common time grid of the replicas (the mean time stamp of
// each frame over the replicas, spec 50 §0), so that every replica contributes the same frames
// even though DMC replicas map their cycles to slightly different times. The selection is one
// regular hyperslab (first, count, stride), which the H5MD reader reads without the other frames.
#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "anisodyn/io/h5md.hpp"
#include "anisodyn/tool/json_config.hpp"

namespace anisodyn::analysis {

struct FrameWindow {
  bool given = false;              // the configuration has a `window` key
  std::optional<double> from, to;  // trajectory time, inclusive
  std::size_t stride = 1;
  std::string config_file;         // names the configuration in errors

  /// from ≤ t ≤ to, each bound widened by 1e-9 of its size so that a bound written in decimal
  /// catches the frame stored at that time (e.g. 0.3 vs 3 × 0.1).
  bool contains(double t) const;
  /// The frames of the window on the time grid `time` (all frames, stride 1, when not given).
  io::FrameSlice select(const std::vector<double>& time) const;
  /// "window {from: 5, to: 10, stride: 2}", for messages.
  std::string text() const;
  /// The message for a window that selects fewer frames than a stage needs, naming the trajectory
  /// and the span of its frames.
  std::string too_few_frames(const io::FrameSlice& frames, const std::vector<double>& time, const std::string& path,
                             std::size_t needed) const;
  /// What an output records about the window: the request and the frames it selected.
  nlohmann::json record(const io::FrameSlice& frames, const std::vector<double>& time) const;
};

/// Reads the optional `window` object (keys from, to, stride). from ≥ to or stride < 1 → InputError
/// naming window.to / window.stride; unknown keys inside are reported by the configuration's finish().
FrameWindow parse_frame_window(tool::ConfigNode& cfg);

/// A key that chose frames before every stage took a time window (structure's `frames`, the
/// clusters' `t_min`) → InputError pointing to `window` instead.
void refuse_frame_key(tool::ConfigNode& cfg, const std::string& key);

}  // namespace anisodyn::analysis
