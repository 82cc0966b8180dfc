#include "anisodyn/run/time_step_run.hpp"

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
  r.frames = parse_frame_rules(cfg, unit);
  r.observe_every = cfg.positive_integer("observe_every", 100);
  return r;
}

ProductionSettings production_settings(const TimeStepRun& run, const std::string& label) {
  return {run.segments, run.frames, run.observe_every, StepUnit::steps(), label};
}

std::int64_t run_steps(const TimeStepRun& run) {
  double end = 0.0;  // in steps
  for (const FieldSegment& s : run.segments) {
    const double length = s.unit == FieldSegment::Unit::Steps ? s.length : s.length / run.time_step;
    end = s.absolute ? length : end + length;
  }
  return static_cast<std::int64_t>(std::ceil(end - 1e-9));
}

}  // namespace anisodyn::run
