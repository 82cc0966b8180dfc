#pragma once
// A given time window for the analysis tests (what a stage's `window` key produces).
#include <optional>

#include "anisodyn/analysis/frame_window.hpp"

namespace anisodyn::testing_support {

inline analysis::FrameWindow time_window(std::optional<double> from, std::optional<double> to, std::size_t stride = 1) {
  analysis::FrameWindow w;
  w.given = true;
  w.from = from;
  w.to = to;
  w.stride = stride;
  w.config_file = "stage.json";
  return w;
}

}  // namespace anisodyn::testing_support
