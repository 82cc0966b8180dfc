#pragma once
// What every time-stepping engine without an external field (BD, DPD) reads and does alike: the
// seed, Δt, the run length (steps or time), the frame rules and the observation cadence, with
// `schedule` and `field` refused; a production client with no field to switch.
#include <cstdint>
#include <string>
#include <vector>

#include "anisodyn/run/frame_rules.hpp"
#include "anisodyn/run/production_runner.hpp"
#include "anisodyn/run/schedule.hpp"
#include "anisodyn/tool/json_config.hpp"

namespace anisodyn::run {

/// The part of an engine's protocol that time stepping needs (the engine's protocol derives from it).
struct TimeStepRun {
  std::uint64_t seed = 1;
  std::uint64_t replica = 0;
  double time_step = 0.0;
  std::vector<FieldSegment> segments;  // the run length: one field-off segment
  FrameRules frames;
  std::int64_t observe_every = 100;
};

/// Reads seed (1), time_step (required), steps or time, frames and observe_every (100) of cfg;
/// `schedule` and `field` are refused, naming `engine` ("BD", "DPD").
TimeStepRun parse_time_step_run(tool::ConfigNode& cfg, const std::string& engine);

/// The number of steps of the run (its segments' end; parse_time_step_run gave every length in steps).
std::int64_t run_steps(const TimeStepRun& run);

/// The production runner's settings for such a run; `label` names the progress line.
ProductionSettings production_settings(const TimeStepRun& run, const std::string& label);

/// A production client of an engine that has no field: switching is never asked of it.
class FieldlessClient : public ProductionClient {
 public:
  Vec3 switch_field(bool, std::int64_t) override { return Vec3::Zero(); }
  bool field_on() const override { return false; }
};

}  // namespace anisodyn::run
