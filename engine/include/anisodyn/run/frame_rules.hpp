#pragma once
// When a production run writes a frame: at the start and the end of production, and at the end of
// any step where one of the rules fires (docs/run.md):
//   "frames": {"every_cycles", "every_time", "log_first_time", "log_per_decade",
//              "after_switch": {"every_cycles", "for_cycles"},
//              "log_cycles": {"per_decade", "restart_every"}}
// (the step unit's name replaces "cycles" for time-stepping engines).
#include <cstdint>

#include <nlohmann/json.hpp>

#include "anisodyn/run/step_unit.hpp"
#include "anisodyn/tool/json_config.hpp"

namespace anisodyn::run {

struct FrameRules {
  std::int64_t every_steps = 0;         // linear in steps
  double every_time = 0.0;              // linear in time
  double log_first_time = 0.0;          // logarithmic in time: t_k = first · 10^(k/per_decade)
  double log_per_decade = 0.0;
  std::int64_t after_switch_every = 0;  // denser frames for a while after each field switch
  std::int64_t after_switch_for = 0;
  double log_steps_per_decade = 0.0;    // logarithmic in steps after each switch (and the start) …
  std::int64_t log_steps_restart = 0;   // … restarted every this many steps (0: once per switch)

  /// Whether the logarithmic step rule writes a frame `since_switch` steps after the last switch:
  /// m = since_switch (mod restart) is 0 or one of round(10^(k/per_decade)), k = 0, 1, … (1, 2, 3,
  /// 4, 6, 7, 10, … steps at 5 per decade), so that every restart block holds lags from one step
  /// up, wherever a time window later cuts the run.
  bool log_step_due(std::int64_t since_switch) const;
};

/// What a tool's frames can follow. A production run has a time and field switches; an MC
/// preparation run counts cycles only (its time is the cycle count, its field never switches).
enum class FrameUse { Production, Preparation };

/// Parses the optional "frames" block (absent: the end frame only, and the start in production).
/// For Preparation the rules in time and after switches are input errors naming the key.
FrameRules parse_frame_rules(tool::ConfigNode& cfg, const StepUnit& unit, FrameUse use = FrameUse::Production);

/// The rules with the run's position in them (part of the checkpointed cursor).
class FrameClock {
 public:
  explicit FrameClock(FrameRules rules) : rules_(rules) {}
  /// Whether a frame is due at the end of the step that reached (step, time), `since_switch` steps
  /// after the last field switch. Advances the time-based rules past `time`.
  bool due(std::int64_t step, double time, std::int64_t since_switch);
  void written_at(std::int64_t step) { last_frame_step_ = step; }
  std::int64_t last_frame_step() const { return last_frame_step_; }

  nlohmann::json to_json() const;
  void restore(const nlohmann::json& j);

 private:
  FrameRules rules_;
  std::int64_t next_log_frame_ = 0;   // index k of the next logarithmic frame time
  std::int64_t next_time_frame_ = 1;  // index k of the next linear-in-time frame
  std::int64_t last_frame_step_ = -1;
};

}  // namespace anisodyn::run
