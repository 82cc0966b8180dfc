#pragma once
// When a run writes a checkpoint: every `every` steps (0 = never) and, after an interrupt request
// (SIGINT/SIGTERM), at once, after which the run stops with Interrupted. Polled at step boundaries,
// where the state is consistent.
#include <cstdint>
#include <functional>
#include <string>

namespace anisodyn::run {

class CheckpointClock {
 public:
  CheckpointClock(std::int64_t every, std::function<void()> write) : every_(every), write_(std::move(write)) {}
  /// Called after each step; `done` counts the run's steps so far (its checkpoint cadence), `where`
  /// says where the run stands, for the message of an interrupt ("production cycle 1200").
  void tick(std::int64_t done, const std::string& where) { tick_if(every_ > 0 && done % every_ == 0, where); }
  /// The same where the caller decides whether a checkpoint is due (runs that may checkpoint only
  /// at some steps, such as quick compression between shrinks).
  void tick_if(bool due, const std::string& where);
  void write() const { if (write_) write_(); }
  std::int64_t every() const { return every_; }

 private:
  std::int64_t every_;
  std::function<void()> write_;
};

}  // namespace anisodyn::run
