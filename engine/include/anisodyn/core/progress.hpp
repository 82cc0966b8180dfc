#pragma once
// Progress of long runs: a self-updating line with rate and ETA on a terminal, a plain log line
// every `log_interval` seconds otherwise (so batch logs stay readable).
#include <chrono>
#include <cstdint>
#include <string>

namespace anisodyn {

class Progress {
 public:
  Progress(std::string label, std::int64_t total, bool quiet, double log_interval_s = 30.0);
  /// Reports `done` of `total` units; `detail` is appended (e.g. current packing fraction).
  void update(std::int64_t done, const std::string& detail = "");
  void finish(const std::string& detail = "");

 private:
  using Clock = std::chrono::steady_clock;
  std::string label_;
  std::int64_t total_, done_ = 0;
  bool quiet_, tty_;
  double log_interval_;
  Clock::time_point start_, last_;
};

std::string format_duration(double seconds);

}  // namespace anisodyn
