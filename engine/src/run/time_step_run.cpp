#include "anisodyn/run/time_step_run.hpp"

#include <algorithm>
#include <cmath>

#include "anisodyn/run/step_unit.hpp"

namespace anisodyn::run {

TimeStepRun parse_time_step_run(tool::ConfigNode& cfg, const std::string& engine) {
  TimeStepRun r;
  r.seed = static_cast<std::uint64_t>(cfg.non_negative_integer("seed", 1));
  r.time_step = cfg.positive("time_step");
  cfg.reject_unless(false, "schedule", "in a " + engine + " run: there is no field to switch (give the run length as steps or time)");
  cfg.reject_unless(false, "field", "in a " + engine + " run (no external field)");
  const StepUnit unit = StepUnit::steps();
  r.segments = parse_schedule(cfg, unit, false);
  // A fixed step makes a run length in time a number of steps: the nearest whole number when the
  // time is one to round-off (200 τ at Δt = 0.005 is 40000 steps, not the 40001 that summing
  // 0.005 forty thousand times would take), else the next one up.
  for (FieldSegment& s : r.segments) {
    if (s.unit != FieldSegment::Unit::Time) continue;
    const double steps = s.length / r.time_step, nearest = std::round(steps);
    s.length = std::abs(steps - nearest) <= 1e-9 * std::max(1.0, steps) ? nearest : std::ceil(steps);
    s.unit = FieldSegment::Unit::Steps;
  }
  r.frames = parse_frame_rules(cfg, unit);
  r.observe_every = cfg.positive_integer("observe_every", 100);
  return r;
}

ProductionSettings production_settings(const TimeStepRun& run, const std::string& label) {
  return {run.segments, run.frames, run.observe_every, StepUnit::steps(), label};
}

std::int64_t run_steps(const TimeStepRun& run) {
  double end = 0.0;  // in steps (parse_time_step_run made every segment's length steps)
  for (const FieldSegment& s : run.segments) end = s.absolute ? s.length : end + s.length;
  return static_cast<std::int64_t>(std::llround(end));
}

}  // namespace anisodyn::run
