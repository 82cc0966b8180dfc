#include "anisodyn/core/progress.hpp"

#include <unistd.h>

#include <algorithm>
#include <cstdio>

namespace anisodyn {

std::string format_duration(double seconds) {
  char buf[64];
  if (seconds < 0 || seconds != seconds) return "?";
  const long s = static_cast<long>(seconds + 0.5);
  if (s < 60) std::snprintf(buf, sizeof buf, "%lds", s);
  else if (s < 3600) std::snprintf(buf, sizeof buf, "%ldm%02lds", s / 60, s % 60);
  else std::snprintf(buf, sizeof buf, "%ldh%02ldm", s / 3600, (s % 3600) / 60);
  return buf;
}

Progress::Progress(std::string label, std::int64_t total, bool quiet, double log_interval_s)
    : label_(std::move(label)), total_(total), quiet_(quiet), tty_(isatty(STDERR_FILENO) != 0),
      log_interval_(log_interval_s), start_(Clock::now()), last_(start_) {}

void Progress::update(std::int64_t done, const std::string& detail) {
  done_ = done;
  if (quiet_) return;
  const auto now = Clock::now();
  const double since_last = std::chrono::duration<double>(now - last_).count();
  if (since_last < (tty_ ? 0.5 : log_interval_)) return;
  last_ = now;
  const double elapsed = std::chrono::duration<double>(now - start_).count();
  const double rate = done / std::max(elapsed, 1e-9);
  const double eta = rate > 0 ? (total_ - done) / rate : -1.0;
  std::fprintf(stderr, "%s%s: %lld/%lld (%.0f%%), %.3g/s, ETA %s%s%s%s", tty_ ? "\r\033[K" : "", label_.c_str(),
               static_cast<long long>(done), static_cast<long long>(total_), 100.0 * done / std::max<std::int64_t>(total_, 1),
               rate, format_duration(eta).c_str(), detail.empty() ? "" : "  ", detail.c_str(), tty_ ? "" : "\n");
  std::fflush(stderr);
}

void Progress::finish(const std::string& detail) {
  if (quiet_) return;
  const double elapsed = std::chrono::duration<double>(Clock::now() - start_).count();
  std::fprintf(stderr, "%s%s: done %lld in %s%s%s\n", tty_ ? "\r\033[K" : "", label_.c_str(),
               static_cast<long long>(done_ > 0 ? done_ : total_), format_duration(elapsed).c_str(), detail.empty() ? "" : "  ", detail.c_str());
}

}  // namespace anisodyn
