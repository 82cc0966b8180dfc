#pragma once
// The field schedule of a production run: stretches with the field on or off, each ending after a
// number of steps or a span of time, or at an absolute instant (from a `switches` list). One schema
// for every engine (docs/run.md):
//   "cycles" | "time"                                  run length, field constant ("field.initially")
//   "schedule": {"segments": [{"field", "cycles" | "time"}, …], "repeat"}
//   "schedule": {"switches": [{"cycle" | "time", "field"}, …]}  with "cycles" | "time" as the end
// (the step unit's name replaces "cycles"/"cycle" for time-stepping engines).
#include <cstdint>
#include <vector>

#include <nlohmann/json.hpp>

#include "anisodyn/run/step_unit.hpp"
#include "anisodyn/tool/json_config.hpp"

namespace anisodyn::run {

/// One stretch of the run with the field on or off. Its end is given as a duration from the
/// segment's start (steps or time) or as an absolute instant (from a `switches` list).
struct FieldSegment {
  bool field_on = false;
  enum class Unit { Steps, Time } unit = Unit::Steps;
  bool absolute = false;
  double length = 0.0;  // duration (or end instant when absolute) in steps or time units
};

/// Parses the run length and the schedule from the top level of a configuration. `initially_on`
/// is the field state before the first switch (field.initially); with `segments` the first segment
/// says it, and `initially_given` must then be false (the caller rejects field.initially).
/// Returns the whole run, in order.
std::vector<FieldSegment> parse_schedule(tool::ConfigNode& cfg, const StepUnit& unit, bool initially_on);

/// Whether the configuration gives the schedule as segments (which then decide the initial state).
bool schedule_has_segments(const tool::ConfigNode& cfg);

/// Where a run stands in its schedule (part of the checkpointed cursor).
struct SchedulePosition {
  std::size_t segment = 0;
  bool segment_started = false;
  double segment_start = 0.0, segment_end = 0.0;  // current segment, in its unit (steps or time)

  nlohmann::json to_json() const;
  static SchedulePosition from_json(const nlohmann::json& j);
};

/// The schedule with its position: starts segments, says when the current one is done and how much
/// of the whole run is done.
class ScheduleClock {
 public:
  explicit ScheduleClock(std::vector<FieldSegment> segments) : segments_(std::move(segments)) {}

  const FieldSegment& current() const { return segments_[pos_.segment]; }
  bool started() const { return pos_.segment_started; }
  bool first_segment() const { return pos_.segment == 0; }
  /// Starts the current segment at (step, time).
  void start(std::int64_t step, double time);
  bool segment_done(std::int64_t step, double time) const;
  /// Moves to the next segment; false at the end of the run.
  bool next();
  /// Fraction of the run done, for progress reports (segments count equally).
  double fraction(std::int64_t step, double time) const;

  const SchedulePosition& position() const { return pos_; }
  void restore(const SchedulePosition& p) { pos_ = p; }

 private:
  double now(std::int64_t step, double time) const {
    return current().unit == FieldSegment::Unit::Steps ? static_cast<double>(step) : time;
  }
  std::vector<FieldSegment> segments_;
  SchedulePosition pos_;
};

}  // namespace anisodyn::run
